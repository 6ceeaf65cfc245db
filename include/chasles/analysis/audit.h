#pragma once
/// @file
/// The audit of a robot description's mass properties against the links' own geometry
/// (docs/audit.md). For every link, from each of its geometry sets (collision, visual) at the
/// link's given mass and a uniform density, chasles computes exactly (src/mass: the Appendix-A
/// primitives and the divergence-theorem mesh integrals) the centre of mass, the inertia about
/// it in the link frame, the volume and so the implied density; it then checks the given
/// inertial on its own (positive definite, triangle inequality, mass, placeholders), against
/// that geometry (radius of gyration, centre of mass inside, agreement, decimal slips, swapped
/// entries, signs of products, frames) and against the other links (duplicates, left/right
/// twins). Every finding has a severity, a stable code, a message with the numbers and, where
/// one follows from a stated rule, a fix: the values to write instead.

#include <cstddef>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "chasles/files/collada_reader.h"
#include "chasles/files/robot_model.h"
#include "chasles/mass/mass_properties.h"
#include "chasles/math/types.h"

namespace chasles {

/// How bad a finding is: an error is a value that cannot be right (the exit code says so),
/// a warning one that is very likely wrong, a note something to know.
enum class Severity { kNote, kWarning, kError };

/// The checks, each with a stable name (FindingCodeName) documented in docs/audit.md.
enum class FindingCode {
  kNotPositiveDefinite,
  kTriangleInequality,
  kZeroMass,
  kMissingInertial,
  kPlaceholderInertia,
  kImplausibleDensity,
  kRadiusOfGyration,
  kComOutsideGeometry,
  kMismatchGeometry,
  kDecimalSlip,
  kTransposedEntries,
  kMirrorMismatch,
  kDuplicateInertial,
  kFrame,
  kSignOfProducts,
  kMissingGeometry,
};

/// "error", "warning", "note".
const char* SeverityName(Severity severity);
/// "not_positive_definite", "triangle_inequality", ... (docs/audit.md).
const char* FindingCodeName(FindingCode code);
/// Every code, in the order of the enum.
std::vector<FindingCode> AllFindingCodes();

/// One finding on a link.
struct Finding {
  Severity severity = Severity::kNote;
  FindingCode code = FindingCode::kMissingGeometry;
  /// What is wrong, by how much, and what to write instead.
  std::string message;
  /// The line of the element concerned (1-based).
  int line = 0;
  /// The values to write instead (mass, centre of mass in L, inertia about it in L), when a
  /// rule gives them; `fix_rule` says which, `effect` what it changes in the motion.
  std::optional<MassProperties> fix;
  std::string fix_rule, effect;
};

/// How a geometry set's volume and moments were obtained, from the most to the least exact.
enum class GeometryMethod {
  kPrimitive,     ///< closed forms of boxes, cylinders, spheres, capsules, ellipsoids
  kExactMesh,     ///< a closed mesh: exact polyhedral integrals
  kRepairedMesh,  ///< an open mesh whose holes were capped (each boundary loop fanned)
  kConvexHull,    ///< an open mesh that could not be capped: its convex hull
  kBoundingBox,   ///< nothing better: the box of the vertices
};

/// "primitive", "exact closed mesh", "repaired mesh", "convex hull", "bounding box".
const char* GeometryMethodName(GeometryMethod method);

/// What a link's geometry set implies.
struct GeometryEstimate {
  GeometrySet set = GeometrySet::kCollision;
  /// The least exact method among its parts.
  GeometryMethod method = GeometryMethod::kPrimitive;
  /// Volume [m³] (parts summed: overlaps count twice, as they would in a density model).
  double volume = std::numeric_limits<double>::quiet_NaN();
  /// At a density of 1 kg/m³: mass = volume, centre of mass and inertia about it, in L.
  MassProperties unit_density;
  /// The box of the geometry in L [m], and its points (mesh vertices, primitives' box
  /// corners) for bounds about any point.
  Vec3 box_min = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  Vec3 box_max = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  std::vector<Vec3> points;
  /// Lines of its geometries, and what was done to them (repairs, skipped meshes).
  std::vector<int> lines;
  std::vector<std::string> notes;

  /// The geometry's mass properties at `mass` (uniform density).
  MassProperties AtMass(double mass) const;
  /// Largest distance from `p` to the geometry [m].
  double RadiusAbout(const Vec3& p) const;
};

/// The audit of one link.
struct LinkAudit {
  std::string name;
  int line = 0;
  /// The inertial as given: mass, centre of mass in L, inertia about it in L (the file's
  /// tensor turned from its frame I into L). Absent when the link has none.
  bool has_inertial = false;
  MassProperties given;
  /// What the geometry implies, per set present; `computed` is the one compared (visual when
  /// it could be computed, the part's own shape; else collision, often a larger stand-in).
  std::vector<GeometryEstimate> estimates;
  std::optional<std::size_t> computed;
  std::vector<Finding> findings;
};

/// The audit of a robot file.
struct RobotAudit {
  std::string file;
  RobotFormat format = RobotFormat::kUrdf;
  std::string robot_name;
  std::vector<LinkAudit> links;
  /// The whole robot at the configuration given (zero by default): total mass, centre of mass
  /// and inertia about it, in the base (root link) frame, from the given inertials (links
  /// with an unusable inertial left out: `robot_notes` names them).
  MassProperties robot;
  std::vector<std::string> robot_notes;
  /// The reader's warnings.
  std::vector<std::string> warnings;

  /// Number of findings of a severity.
  std::size_t Count(Severity severity) const;
};

/// Reads a mesh file's triangles, in the file's units (the caller's mesh readers: the files
/// layer's, the Collada reader for .dae among them).
using MeshLoader = std::function<TriangleSoup(const std::string& path)>;

/// Meshes read and integrated, by file and scale: kept across the audits that share it (the
/// variants of one robot), each mesh read and integrated once.
class AuditMeshCache;

/// A cache for AuditOptions::cache, reading meshes with `load`.
std::shared_ptr<AuditMeshCache> MakeAuditMeshCache(MeshLoader load);

/// Options of the audit.
struct AuditOptions {
  /// Reads meshes; without one, meshes are not read (a note says so).
  MeshLoader load_mesh;
  /// Meshes kept from earlier audits (then load_mesh is not used); null: read afresh.
  std::shared_ptr<AuditMeshCache> cache;
  /// Joint values [rad or m] by joint name, for the robot's total (zero when not given).
  std::map<std::string, double> joints;
};

/// Audits `model`.
RobotAudit AuditRobot(const RobotModel& model, const AuditOptions& options);

/// The finding whose fix `--fix` writes for a link with at least one error: of the findings
/// with a fix, the most specific explanation first (decimal_slip, transposed_entries,
/// sign_of_products, frame), then the validity rules, then the geometry's values; the first
/// whose values pass the plain checks (a valid tensor; against the geometry a plausible
/// density, the radius of gyration within reach, the centre of mass inside, no disagreement of
/// an error's size), else the first; null when the link has no error or no finding gives a fix.
const Finding* FixToApply(const LinkAudit& link);

}  // namespace chasles
