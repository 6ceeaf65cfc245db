#include "commands.h"

namespace chasles::cli {

// Section 8.3 of the chapter: a thin disk of mass m and radius r on an axle of mass 9/16 m and
// length 2r pivoting at O. Centre of mass at 41/25 r from O; inertia about O
// diag(5, 1/2, 5) m r^2; about the centre of mass diag(319/400, 1/2, 319/400) m r^2.
const char* const kDemoScene = R"(chasles: 3
title: Disk and axle assembly (Section 8.3)
description: >
  A thin disk of mass m and radius r rolls on a circle; its axle OA, of mass 9/16 m and
  length 2r, pivots at O. The report gives the assembly's centre of mass (41/25 r from O) and
  its inertia about O and about the centre of mass.
parameters:
  m: 2 kg
  r: 10 cm
bodies:
  - name: assembly
    points:
      O: [0, 0, 0]
    parts:
      - name: axle
        shape: rod
        mass: 9/16*m
        from: [0, 0, 0]
        to: [0, 2*r, 0]
      - name: disk
        shape: disk
        mass: m
        radius: r
        position: [0, 2*r, 0]
        axis: [0, 1, 0]
)";

}  // namespace chasles::cli
