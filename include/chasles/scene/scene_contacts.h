#pragma once
/// @file
/// The contact part of a scene (docs/scene-format.md, "Contacts"): unilateral contacts with
/// Coulomb friction between a body's shape and a world plane, or between two bodies' spheres,
/// as the file gives them, in SI. Friction and restitution come from the entry itself or from
/// the scene's `material_pairs` table. BuildStudy turns each entry into the Model's contact.

#include <limits>
#include <string>
#include <vector>

#include "chasles/math/types.h"
#include "chasles/model/contact.h"
#include "chasles/scene/scene_constraints.h"

namespace chasles {

/// The shape feature of a contact, in the body frame B.
enum class SceneContactShape {
  kSphere,    ///< a sphere (centre, radius)
  kDisk,      ///< a thin disk's rim circle (centre, axis, radius)
  kDiskFace,  ///< a disk's flat face (centre, axis, radius): it may lie flat on the plane
  kCylinder,  ///< both end rims of a solid cylinder (centre, axis, radius, length)
  kBox,       ///< the eight vertices of a box (centre, full edge lengths along B's axes)
  kPoints,    ///< named body points or positions in B (a car's wheel contacts, a stool)
  kCapsule,   ///< the two end spheres of a capsule (centre, axis, radius, length)
};

/// Keyword of a shape ("sphere", "disk_face", ...).
const char* SceneContactShapeName(SceneContactShape shape);

/// One entry of `material_pairs`: the friction and restitution of two surface materials.
struct SceneMaterialPair {
  /// The two materials (order does not matter).
  std::string a, b;
  /// Static and kinetic friction coefficients, rolling-resistance coefficient (moment
  /// mu_r N R) [-], coefficient of restitution in [0, 1] [-].
  double mu_s = 0.0, mu_k = 0.0, mu_r = 0.0, restitution = 0.0;
  /// How the coefficient of restitution is read (`restitution_law`).
  RestitutionLaw restitution_law = RestitutionLaw::kEnergetic;
};

/// One entry of `contacts`.
struct SceneContact {
  /// Unique name (reports, columns "<name>_N" ...).
  std::string name;
  /// The entry, for errors found when the motion is built or run.
  SceneSpot where;
  /// The body (scene index).
  int body = -1;
  SceneContactShape shape = SceneContactShape::kSphere;
  /// Centre of the shape from Bo in B [m] (the centre of mass by default).
  Vec3 p_BoC_B = Vec3::Zero();
  /// Symmetry axis in B (disk, disk face, cylinder, capsule), unit.
  Vec3 axis_B = Vec3::UnitZ();
  /// Radius [m] (sphere, disk, disk face, cylinder, capsule).
  double radius = std::numeric_limits<double>::quiet_NaN();
  /// Length along the axis [m]: a cylinder's height, a capsule's distance between its end
  /// spheres' centres.
  double length = 0.0;
  /// A box's full edge lengths along B's axes [m].
  Vec3 size = Vec3::Zero();
  /// Points in B [m] (shape points).
  std::vector<Vec3> points_B;
  /// The names of those points, for reports ("rear", "front"; empty when given as positions).
  std::vector<std::string> point_names;
  /// True for a world plane; false for the other body's sphere (`with`).
  bool with_plane = true;
  /// A point of the plane [m] and its unit normal pointing to the body's side, in W.
  Vec3 plane_point_W = Vec3::Zero();
  Vec3 plane_normal_W = Vec3::UnitZ();
  /// The other body (scene index) of a sphere-sphere contact, its sphere's centre from its Bo in
  /// its frame [m] and radius [m].
  int other_body = -1;
  Vec3 p_OoD_O = Vec3::Zero();
  double other_radius = std::numeric_limits<double>::quiet_NaN();
  /// Coefficients as resolved (the entry's own keys override its material pair's).
  double mu_s = 0.0, mu_k = 0.0, mu_r = 0.0, restitution = 0.0;
  RestitutionLaw restitution_law = RestitutionLaw::kEnergetic;
  /// "a/b" when the values came from a material pair, empty otherwise.
  std::string materials;
};

/// Number of ring points the engine puts on a disk face (ContactSpec::face_points).
inline constexpr int kDiskFacePoints = 8;

/// Labels of a contact's points in the engine's order (Contact::num_points()): the contact's
/// name for a one-point shape; otherwise "<name>_<point>" with the point's name for shape
/// points given by name, or its index from 0 ("<name>_0", ...). Column and variable prefixes.
std::vector<std::string> ContactPointLabels(const SceneContact& contact);

/// Keys `contacts` and `material_pairs`.
struct SceneContacts {
  std::vector<SceneMaterialPair> material_pairs;
  std::vector<SceneContact> contacts;
  bool empty() const { return contacts.empty(); }
  /// ContactPointLabels of every contact, concatenated (Model contact-point order).
  std::vector<std::string> point_labels() const;
};

}  // namespace chasles
