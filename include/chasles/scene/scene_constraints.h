#pragma once
/// @file
/// The constraint part of a scene (docs/scene-format.md, "Joints, rolling and drivers"):
/// joints, rolling contacts and prescribed-motion drivers as the file gives them, in SI and in
/// world coordinates at the initial configuration. BuildStudy turns them into the Model's
/// Joint, RollingContact, PrescribedMotion, GearMesh (include/chasles/model/constraints.h) and
/// StringConstraint (include/chasles/model/string_constraint.h).

#include <limits>
#include <string>
#include <vector>

#include "chasles/math/types.h"
#include "chasles/model/body.h"
#include "chasles/model/constraints.h"
#include "chasles/model/surface_rolling.h"

namespace chasles {

/// Where an entry stands in the scene file, for errors found only when the constraints are
/// assembled or solved (line and column 1-based, 0 unknown; key path "joints[1]").
struct SceneSpot {
  int line = 0;
  int column = 0;
  std::string key;
};

/// One entry of `joints`.
struct SceneJoint {
  /// Unique name (reports, CSV columns "<name>_Fx" ...).
  std::string name;
  SceneSpot where;
  JointKind kind = JointKind::kWeld;
  /// Parent body (scene index) or kWorld; child body (scene index).
  int parent = kWorld;
  int child = -1;
  /// The joint point in W at the initial configuration [m].
  Vec3 p_WJ = Vec3::Zero();
  /// Unit joint axis in W at the initial configuration (plane normal, line direction); for a
  /// kPrismaticInPlane or kPointOnLineInPlane joint the direction of the slide or
  /// line in the x-y plane.
  Vec3 axis_W = Vec3::UnitZ();
};

/// One entry of `rolling`: a round body rolling without slipping on a plane of the world or of
/// another body (key `on`).
struct SceneRolling {
  std::string name;
  SceneSpot where;
  RollingShape shape = RollingShape::kSphere;
  /// The rolling body (scene index).
  int body = -1;
  /// The body the plane belongs to (scene index), or kWorld (key `on`, default world).
  int on = kWorld;
  /// Centre of the sphere / cylinder / disk from Bo in B [m] (the centre of mass by default).
  Vec3 p_BoC_B = Vec3::Zero();
  /// Symmetry axis in B (cylinder, disk).
  Vec3 axis_B = Vec3::UnitZ();
  /// Radius [m].
  double radius = 0.0;
  /// A point of the plane [m] and its upward unit normal, in W at the initial configuration.
  Vec3 plane_point_W = Vec3::Zero();
  Vec3 plane_normal_W = Vec3::UnitZ();
  /// Coefficient of static friction (key `mu_s`), for `chasles solve` to compare the friction
  /// rolling needs with; NaN when not given (the simulation does not use it).
  double mu_s = std::numeric_limits<double>::quiet_NaN();
  /// Key `surface` instead of `plane`: rolling on a fixed sphere or circular cylinder of the
  /// world (model/surface_rolling.h): its shape, centre (a point of a cylinder's axis) and
  /// axis in W, radius [m], and whether the body is inside it.
  bool on_surface = false;
  SurfaceShape surface_shape = SurfaceShape::kSphere;
  Vec3 surface_center_W = Vec3::Zero();
  Vec3 surface_axis_W = Vec3::UnitZ();
  double surface_radius = 0.0;
  bool inside = true;
};

/// One entry of `drivers`: a prescribed translation or rotation f(t) = f0 + f1 t + ½ f2 t².
struct SceneDriver {
  std::string name;
  SceneSpot where;
  DriverKind kind = DriverKind::kTranslation;
  int parent = kWorld;
  int child = -1;
  /// Driver point and unit axis in W at the initial configuration [m].
  Vec3 p_WJ = Vec3::Zero();
  Vec3 axis_W = Vec3::UnitZ();
  /// f0 [m or rad], f1 [m/s or rad/s], f2 [m/s² or rad/s²].
  double f0 = 0.0, f1 = 0.0, f2 = 0.0;
};

/// A pitch circle of one entry of `gears`, in W at the initial configuration.
struct ScenePitchCircle {
  /// Centre [m] and unit axis, in W.
  Vec3 center_W = Vec3::Zero();
  Vec3 axis_W = Vec3::UnitZ();
  /// Pitch radius [m] (NaN for the parent of a face gear: its pitch surface is a plane).
  double radius = std::numeric_limits<double>::quiet_NaN();
};

/// One entry of `gears`: two gears in mesh, their pitch circles rolling on each other.
struct SceneGear {
  std::string name;
  SceneSpot where;
  GearKind kind = GearKind::kExternal;
  /// Parent body (scene index) or kWorld; child body (scene index).
  int parent = kWorld;
  int child = -1;
  ScenePitchCircle parent_circle, child_circle;
  /// Also hold the pitch surfaces together (the normal-force row; key `keep_contact`).
  bool keep_contact = false;
};

/// One end of an entry of `strings`: a point of a body (or of the world), or a drum of the
/// body the string is wound on; in W at the initial configuration.
struct SceneStringEnd {
  /// Scene body index, or kWorld.
  int body = kWorld;
  /// The point or the drum's centre in W [m]; not finite: the body's centre of mass.
  Vec3 p_W = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  /// Drum radius [m]; 0 for a point end.
  double radius = 0.0;
  /// +1 when the string, followed from `from` to `to`, goes round the drum counterclockwise
  /// about the string's normal, -1 clockwise.
  int sense = 1;
};

/// A frictionless, massless pulley (an entry of a string's `over`), fixed in the world or
/// carried by a body; its centre in W at the initial configuration.
struct SceneStringPulley {
  Vec3 center_W = Vec3::Zero();
  double radius = 0.0;
  int sense = 1;
  /// Scene body index carrying it, or kWorld (fixed).
  int body = kWorld;
};

/// One entry of `strings`: an inextensible string held taut from `from` over the pulleys
/// `over` to `to` (model/string_constraint.h).
struct SceneString {
  std::string name;
  SceneSpot where;
  SceneStringEnd from, to;
  std::vector<SceneStringPulley> over;
  /// Unit normal of the string's plane, in W (z in a planar scene).
  Vec3 normal_W = Vec3::UnitZ();
  /// Free length L0 [m] (key `length`); NaN: the path's length at the start. Longer than the
  /// path: the string starts slack.
  double length = std::numeric_limits<double>::quiet_NaN();
  /// Newton's restitution when it snaps taut (key `restitution`; 0: plastic).
  double restitution = 0.0;
};

/// Keys `joints`, `rolling`, `drivers`, `gears`, `strings`.
struct SceneConstraints {
  std::vector<SceneJoint> joints;
  std::vector<SceneRolling> rolling;
  std::vector<SceneDriver> drivers;
  std::vector<SceneGear> gears;
  std::vector<SceneString> strings;
  /// True when the scene has none.
  bool empty() const {
    return joints.empty() && rolling.empty() && drivers.empty() && gears.empty() && strings.empty();
  }
  /// Names in Model order (joints, rolling, drivers, gears, then strings).
  std::vector<std::string> names() const;
  /// Where the entry at `i` in Model order (that of names()) stands in the file; null past the
  /// last.
  const SceneSpot* At(int i) const;
};

}  // namespace chasles
