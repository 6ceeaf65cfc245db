#pragma once
/// @file
/// The steps of AuditRobot (chasles/analysis/audit.h), one file each: the geometry's mass
/// properties (audit_geometry.cpp, with the mesh repairs of audit_mesh.cpp), the checks of one
/// link's inertial on its own and against its geometry (audit_checks.cpp, audit_repairs.cpp),
/// and the checks across links (audit_links.cpp).

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "chasles/analysis/audit.h"
#include "chasles/files/robot_model.h"
#include "chasles/mass/triangle_mesh.h"

namespace chasles::internal {

/// Thresholds of the checks (docs/audit.md gives each with its reason).
struct AuditThresholds {
  /// Relative tolerance of validity: eigenvalues and the triangle inequality, times the trace.
  static constexpr double kValidity = 1e-9;
  /// Implied densities outside this range [kg/m³] are implausible for a link (foam to
  /// tungsten).
  static constexpr double kDensityLow = 30.0, kDensityHigh = 30000.0;
  /// The radius of gyration may exceed the geometry's reach by this factor (visual meshes are
  /// slightly smaller or larger than the part).
  static constexpr double kReach = 1.05;
  /// Given and computed tensors disagreeing by more than these factors (their generalised
  /// eigenvalues): a warning, an error.
  static constexpr double kMismatchWarning = 3.0, kMismatchError = 10.0;
  /// A repair is looked for when the tensor is off by more than kMismatchWarning, and accepted
  /// when it brings the tensor within this factor of the geometry's.
  static constexpr double kAgree = 1.5;
  /// Products of at least this fraction of the trace whose sign, turned, brings the tensor
  /// within kSignAgree of the geometry's: a sign slip even below kMismatchWarning.
  static constexpr double kProducts = 0.1, kSignAgree = 1.2;
  /// The centre of mass may lie outside the geometry's box by this fraction of its diagonal.
  static constexpr double kComMargin = 0.05;
};

/// A mesh's solid in its own frame G at unit density: how it was obtained and its vertices.
struct MeshSolidPart {
  MassProperties unit_density;
  GeometryMethod method = GeometryMethod::kExactMesh;
  std::string why_open;
  std::vector<Vec3> vertices;
};

}  // namespace chasles::internal

namespace chasles {

class AuditMeshCache {
 public:
  explicit AuditMeshCache(MeshLoader load) : load_(std::move(load)) {}
  /// The soup of `path`, or null with `problem` set when meshes are not read; throws the
  /// reader's InputError for a malformed mesh.
  const TriangleSoup* Get(const std::string& path, std::string* problem);
  /// Solids already integrated, by path and scale.
  std::map<std::pair<std::string, std::array<double, 3>>, internal::MeshSolidPart> solids;

 private:
  MeshLoader load_;
  std::map<std::string, std::optional<TriangleSoup>> soups_;
  std::map<std::string, std::string> problems_;
};

}  // namespace chasles

namespace chasles::internal {

using MeshCache = AuditMeshCache;

/// What each geometry set of `link` implies (one estimate per set that has geometry). Throws
/// InputError "FILE:LINE: ..." (`file` the robot file, LINE its mesh's) for a malformed mesh.
std::vector<GeometryEstimate> EstimateGeometry(const RobotLink& link, MeshCache& meshes,
                                               const std::string& file);

/// Caps the holes of an open mesh: every boundary loop is closed by a fan from its centroid.
/// False when the boundary is not a set of simple loops (a vertex on two holes, a
/// non-manifold edge).
bool CapHoles(TriangleMesh& mesh);

/// The convex hull of `points`, outward oriented; empty when they are (nearly) coplanar.
TriangleMesh ConvexHull(const std::vector<Vec3>& points);

/// Generalised eigenvalues of `given` against `computed` (both symmetric, `computed`
/// positive definite): the factors by which the given tensor's moments exceed the computed
/// one's along the directions where they differ most. Sorted ascending.
Vec3 TensorRatios(const Mat3& given, const Mat3& computed);

/// The largest factor between two tensors: max over TensorRatios of max(r, 1/r); infinity
/// when `given` has a moment <= 0.
double TensorFactor(const Mat3& given, const Mat3& computed);

/// The link's own checks: validity, mass, placeholders (no geometry needed).
void CheckInertialAlone(const RobotLink& link, LinkAudit& audit);

/// The checks against the link's computed geometry: density, radius of gyration, centre of
/// mass, agreement, and the repairs that explain a disagreement (decimal slips, swapped
/// entries, signs of products, frames).
void CheckAgainstGeometry(const RobotLink& link, LinkAudit& audit);

/// The checks across links: duplicates, left/right twins; and zero-mass fixes from the
/// robot's typical density.
void CheckAcrossLinks(const RobotModel& model, std::vector<LinkAudit>& audits);

/// The fix for a given inertial: the nearest physically valid tensor with the same principal
/// axes and the magnitudes of its moments (a negative moment is most often a sign slip), the
/// moments projected onto the cone of valid moments and the smallest kept above 1e-6 of the
/// largest.
Mat3 NearestValidTensor(const Mat3& I);

/// "acceleration about the link's z axis under 1 N·m: 4.56 → 456 rad/s² (100×)": the axis of
/// the largest change; or why there is no comparison.
std::string DynamicEffect(const Mat3& before, const Mat3& after);

/// Adds a finding to `audit`.
void AddFinding(LinkAudit& audit, Severity severity, FindingCode code, int line,
                std::string message, std::optional<MassProperties> fix = std::nullopt,
                std::string rule = "");

/// A tensor as "[Ixx, Iyy, Izz, Ixy, Ixz, Iyz]" with 4 significant digits.
std::string TensorText(const Mat3& I);

}  // namespace chasles::internal
