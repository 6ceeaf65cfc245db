#pragma once
/// @file
/// The text report of the mass properties of a scene's bodies, as `chasles mass` prints it:
/// per body its parts, mass, centre of mass, volume and surface area, inertia about the centre
/// of mass with its principal moments and axes, radii of gyration, and the inertia about named
/// points and in a rotated frame.

#include <optional>
#include <string>
#include <vector>

#include "chasles/math/types.h"
#include "chasles/report/text_format.h"
#include "chasles/scene/mass_report.h"
#include "chasles/scene/scene.h"

namespace chasles {

/// What the mass report is asked for beyond its units.
struct MassTextOptions {
  TextOptions text;
  /// Points besides each body's own `points` about which the inertia is given (--about).
  std::vector<MassReportPoint> about;
  /// A frame F rotated in the body (R_BF): the central inertia in F as well (--frame).
  std::optional<Mat3> R_BF;
  /// The table of each body's parts (--no-parts: false).
  bool parts = true;
};

/// The report of `scene`'s mass properties. Throws InputError naming a value that is not finite
/// or a bad unit.
std::string MassText(const Scene& scene, const MassTextOptions& options = {});

}  // namespace chasles
