#pragma once
/// @file
/// The JSON report of `chasles mass`: every body's mass, centre of mass, central inertia
/// tensor, principal moments and axes, radii of gyration, inertia about its named points (and
/// any others asked for) and in a rotated frame, and every part's own mass properties, in the
/// units asked for. It reads the Scene's bodies, parts and parameters, and the mass sweep
/// (sweep.h) reads its quantities from it, so it is of this layer, below the report layer; the
/// finite-number check and the dump are the report layer's DumpJson
/// (chasles/report/json_report.h).

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "chasles/math/types.h"
#include "chasles/scene/scene.h"
#include "chasles/scene/units.h"

namespace chasles {

/// The sign convention of every inertia matrix of the report (its "inertia_convention").
extern const char* const kInertiaConvention;

/// A point about which the report gives a body's inertia (parallel-axis theorem, eqs.
/// 8.24-8.29).
struct MassReportPoint {
  /// As the report names it ("pivot", "'[0, 0, 0.5 m]'").
  std::string name;
  /// From the body origin, in body axes [m].
  Vec3 p_BoP_B = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
};

/// A body's volume and surface area, or why one is not given.
struct BodyMeasures {
  /// Σ of the parts' volumes, a cut's subtracted [m³]; NaN when a part has no geometry.
  double volume = std::numeric_limits<double>::quiet_NaN();
  /// The surface area [m²] where it is exact: a body of one part (a shape or a mesh); NaN
  /// otherwise.
  double surface_area = std::numeric_limits<double>::quiet_NaN();
  /// "n/a: ..." for a value not given; empty otherwise.
  std::string volume_note, surface_area_note;
};

/// The body's volume and surface area (BodyMeasures).
BodyMeasures CalcBodyMeasures(const SceneBody& body);

/// The body's own points (its `points:` entries) followed by `extra` (e.g. --about).
std::vector<MassReportPoint> MassReportPoints(const SceneBody& body,
                                              const std::vector<MassReportPoint>& extra);

/// The report: "scene", "title", "units" (length, mass, inertia, density, volume, area),
/// "inertia_convention", "parameters" (SI value and dimension), "bodies" (each with "volume" and
/// "surface_area" (null with "volume_note", "surface_area_note" when not given), "points" from
/// MassReportPoints, "frame" when R_BF is given: the central inertia in frame F, R_BF its
/// orientation in the body, and "parts", each with its "volume" and "surface_area", null when
/// the part has no geometry), "warnings". Values in `units`.
nlohmann::json MassReportJson(const Scene& scene, const UnitSystem& units,
                              const std::vector<MassReportPoint>& extra = {},
                              const std::optional<Mat3>& R_BF = std::nullopt);

}  // namespace chasles
