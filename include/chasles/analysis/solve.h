#pragma once
/// @file
/// The instantaneous problem of a Model at a state, as `chasles solve` reports it (chapter
/// 8.2-8.3): every body's acceleration, every constraint's reaction, the friction rolling needs
/// against mu_s, each contact point's mode and forces, the kinetic energy and momenta, and the
/// solve's checks of its own answer. A SolveDefinition says what to solve and how to name it;
/// the scene layer makes one from a scene (MakeSolveDefinition), a program in code.

#include <memory>
#include <string>
#include <vector>

#include "chasles/analysis/solve_report.h"
#include "chasles/math/types.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {

/// A named point fixed in a body (its velocity and acceleration are reported).
struct NamedBodyPoint {
  std::string name;
  /// From the body origin, in B [m].
  Vec3 p_BoP_B = Vec3::Zero();
};

struct SolveDefinition {
  std::shared_ptr<const Model> model;
  /// The state to solve at (on the constraints up to round-off: the solve projects it).
  State initial;
  /// A planar problem: reports in x, y and about z.
  bool planar = false;
  /// Warnings to list first (e.g. the scene's, then initial values changed by a projection).
  std::vector<std::string> warnings;
  /// Named points of each body (Model order; shorter: the rest have none).
  std::vector<std::vector<NamedBodyPoint>> points;
  /// mu_s of each reported constraint (NaN when it has none); its size is the number of the
  /// Model's constraints (the first ones) reported.
  std::vector<double> mu_s;
  /// Contact point labels in Model order (empty: Model::contact_point_name).
  std::vector<std::string> contact_point_labels;
};

/// Solves the instantaneous problem at the definition's state, projected onto the constraints,
/// in the contact modes chosen as a simulation starts (impacts not applied). Throws InputError
/// for a state or Model it cannot solve.
SolveReport SolveAtState(const SolveDefinition& definition);

}  // namespace chasles
