// Planar scenes (docs/scene-format.md, "Planar scenes"): `planar: true` puts every body's
// motion in W's x-y plane (chapter 8.2, eqs. 8.34-8.43). World-frame inputs are [x, y]; the
// orientation is the angle theta about z and the angular velocity the scalar omega; a body may
// be given by its mass and its moment about z alone (`shape: planar`); joints, rolling contacts
// and drivers take their in-plane forms. The Model stays 3-D (study.cpp holds each body in
// the plane with one kPlanar joint with the world).

#include <cmath>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include "chasles/scene/expression.h"
#include "chasles/scene/scene.h"
#include "internal/scene_reader.h"

namespace chasles::scene_internal {

namespace {}  // namespace

void SceneReader::ReadPlanar(const At& root, Scene& scene) {
  if (!root.Has("planar")) return;
  const At at = root.Child("planar");
  bool planar = false;
  if (!at.node.IsScalar() || !DecodeBool(at.node, planar)) {
    report_.Fail(at, fmt::format("expected true or false, got {}", KindOf(at.node)));
  }
  planar_ = planar;
  scene.planar = planar;
}

Vec3 SceneReader::WorldVector(const At& at, const Dimension& expected, std::string_view what) {
  if (!planar_) return Vector(at, expected, what);
  if (at.node.IsSequence() && at.node.size() == 3) {
    // [x, y, 0]: the version-1 spelling (scene_versions.cpp).
    PlanarThreeValues(at, what, "[x, y]", [&] { return Value(at.Item(2), expected, what) == 0.0; });
  } else if (!at.node.IsSequence() || at.node.size() != 2) {
    report_.Fail(at, fmt::format("expected {} as a list of two values [x, y] (a planar scene), "
                                 "got {}",
                                 what, KindOf(at.node)));
  }
  return {Value(at.Item(0), expected, what), Value(at.Item(1), expected, what), 0.0};
}

Vec3 SceneReader::BodyVector(const At& at, const Dimension& expected, std::string_view what) {
  if (!planar_) return Vector(at, expected, what);
  // Body-frame geometry may keep its z (the body frame's z axis is the plane's normal).
  if (at.node.IsSequence() && at.node.size() == 2) {
    return {Value(at.Item(0), expected, what), Value(at.Item(1), expected, what), 0.0};
  }
  if (!at.node.IsSequence() || at.node.size() != 3) {
    report_.Fail(
        at, fmt::format("expected {} as [x, y] or [x, y, z] (body frame, a planar "
                        "scene), got {}",
                        what,
                        at.node.IsSequence() ? fmt::format("a list of {} values", at.node.size())
                                             : KindOf(at.node)));
  }
  return Vector(at, expected, what);
}

Vec3 SceneReader::BodyAxisAt(const At& at, std::string_view what) {
  const Vec3 a = BodyVector(at, kDimensionless, what);
  if (!(a.norm() > 0) || !a.allFinite()) {
    report_.Fail(at, fmt::format("{} has zero length; give a direction such as [0, 0, 1]", what));
  }
  return a.normalized();
}

Vec3 SceneReader::PlanarZAxis(const At& holder, const char* key, std::string_view what) {
  if (!holder.Has(key)) return Vec3::UnitZ();
  // Every rotation of a planar scene is about z, the plane's normal (eq. 8.43): the only axis
  // a turning element can have is +z. [0, 0, 1] (any length) is accepted so that a 3-D scene's
  // entry reads unchanged; anything else names the rule.
  const At at = holder.Child(key);
  const bool two = at.node.IsSequence() && at.node.size() == 2;
  const Vec3 a = two ? Vec3::Zero() : BodyVector(at, kDimensionless, what);
  const double tol = 1e-12 * a.norm();
  if (two || !(a.z() > 0) || !(std::abs(a.x()) <= tol) || !(std::abs(a.y()) <= tol)) {
    report_.Fail(
        at, fmt::format("{} of a planar scene is z, the plane's normal; leave '{}' out "
                        "(or give [0, 0, 1]){}",
                        what, key, two ? ": [x, y] would be an axis in the plane" : ", not off z"));
  }
  return Vec3::UnitZ();
}

SceneVectorExpression SceneReader::PlanarStateVector(const At& at, const Dimension& expected,
                                                     std::string_view what, bool moment) {
  SceneVectorExpression v;
  const Expression zero = Expression::Parse("0", {});
  v.components = {zero, zero, zero};
  if (moment) {
    // A moment in the plane is about z: eq. 8.43, sum of M = I alpha.
    if (!at.node.IsScalar()) {
      report_.Fail(at, fmt::format("in a planar scene {} is the scalar Mz about z (e.g. 'value: "
                                   "2 N*m'), got {}",
                                   what, KindOf(at.node)));
    }
    v.components[2] = StateExpression(at, expected, what);
    return v;
  }
  if (at.node.IsSequence() && at.node.size() == 3) {
    // [Fx, Fy, 0]: the version-1 spelling (scene_versions.cpp).
    PlanarThreeValues(at, what, "[Fx, Fy]", [&] {
      const Expression z = StateExpression(at.Item(2), expected, what);
      return z.is_constant() && z.Evaluate({}) == 0.0;
    });
  } else if (!at.node.IsSequence() || at.node.size() != 2) {
    report_.Fail(at, fmt::format("expected {} as a list of two values [x, y] (a planar scene), "
                                 "got {}",
                                 what, KindOf(at.node)));
  }
  for (size_t i = 0; i < 2; ++i) v.components[i] = StateExpression(at.Item(i), expected, what);
  return v;
}

void SceneReader::ReadPlanarInitial(const At& at, const SceneBody& body,
                                    SceneInitialState& initial) {
  // The 3-D keys get a pointer to their planar form rather than a bare "unknown key".
  for (const char* key : {"rotation", "euler", "quaternion"}) {
    if (at.Has(key)) {
      report_.Fail(at.Child(key), fmt::format("a planar scene's orientation is the angle 'theta' "
                                              "about z (e.g. 'theta: 30 deg'), not '{}'",
                                              key));
    }
  }
  for (const char* key : {"angular_velocity", "angular_velocity_frame"}) {
    if (at.Has(key)) {
      report_.Fail(at.Child(key), fmt::format("a planar scene's angular velocity is the scalar "
                                              "'omega' about z (e.g. 'omega: 2 rad/s'), not '{}'",
                                              key));
    }
  }
  report_.CheckMap(at, {"position", "theta", "velocity", "velocity_point", "omega"},
                   "an initial state (planar: position [x, y], theta, velocity [vx, vy], omega)");
  if (at.Has("position")) {
    const At p = at.Child("position");
    initial.p_WBo = InitialMotion(p, WorldVector(p, kLength, "a position"), "position", "m");
  }
  if (at.Has("theta")) {
    initial.theta = Value(at.Child("theta"), kDimensionless, "the angle theta about z");
  }
  initial.q_WB = Quat(Eigen::AngleAxisd(initial.theta, Vec3::UnitZ()));
  if (at.Has("velocity")) {
    const At v = at.Child("velocity");
    initial.v_WP_W = InitialMotion(v, WorldVector(v, kVelocity, "a velocity"), "velocity", "m/s");
  }
  if (at.Has("velocity_point")) {
    const At p = at.Child("velocity_point");
    if (!at.Has("velocity")) report_.Fail(p, "'velocity_point' needs 'velocity'");
    if (!p.node.IsScalar()) report_.Fail(p, "expected the name of one of the body's points");
    initial.p_BoP_B = BodyPointAt(p, body);
  }
  if (at.Has("omega")) {
    initial.w_WB_W =
        Vec3(0, 0, Value(at.Child("omega"), kAngularVelocity, "the angular velocity omega"));
  }
}

MassProperties SceneReader::ReadPlanarPart(const At& at, ScenePart& part, Vec3& p_BoPo_B) {
  if (!planar_) {
    report_.Fail(at.Child("shape"),
                 "shape 'planar' (a mass and a moment about z only) is for planar scenes: add "
                 "'planar: true' at the top of the file, or use a 3-D shape or 'custom'");
  }
  report_.CheckMap(at,
                   {"name", "shape", "subtract", "mass", "inertia_z", "radius_of_gyration",
                    "center_of_mass", "position"},
                   "a planar part (mass, inertia_z or radius_of_gyration, center_of_mass)");
  const std::string what = fmt::format("part '{}' (planar)", part.name);
  const double mass = PositiveValue(report_.Require(at, "mass", what), kMass, "the mass");
  part.mass_source = "mass";
  if (at.Has("inertia_z") == at.Has("radius_of_gyration")) {
    report_.Fail(at.Has("inertia_z") ? at.Child("radius_of_gyration") : at,
                 fmt::format("{}: give its moment about z one way: 'inertia_z' (about the centre "
                             "of mass) or 'radius_of_gyration' (I = m k^2)",
                             what));
  }
  // I about the centre of mass (eq. 8.38's I; the parallel-axis theorem 8.39 moves it).
  double I = 0.0;
  if (at.Has("inertia_z")) {
    I = PositiveValue(at.Child("inertia_z"), kInertia, "the moment of inertia about z");
  } else {
    const double k =
        PositiveValue(at.Child("radius_of_gyration"), kLength, "the radius of gyration");
    I = mass * k * k;
  }
  const Vec3 com = at.Has("center_of_mass")
                       ? BodyVector(at.Child("center_of_mass"), kLength, "the centre of mass")
                       : Vec3::Zero();
  if (at.Has("position")) p_BoPo_B = BodyVector(at.Child("position"), kLength, "a position");
  // Only I_zz acts in plane motion (eq. 8.36: the products with z vanish). The out-of-plane
  // moments are chosen as a lamina's in the x-y plane, I_xx = I_yy = I_zz / 2 (perpendicular-
  // axis theorem I_zz = I_xx + I_yy): a valid rigid body (the flat limit of the triangle
  // inequality) whose out-of-plane moments play no part in the motion.
  return MassProperties(mass, com, RotationalInertia(0.5 * I, 0.5 * I, I, 0.0, 0.0, 0.0));
}

void SceneReader::ReadPlanarJointType(const At& at, const std::string& what, SceneJoint& j) {
  const At type_at = at.Child("type");
  const std::string type(type_at.node.Scalar());
  switch (j.kind) {
    case JointKind::kRevolute:
      j.kind = JointKind::kRevoluteInPlane;
      j.axis_W = PlanarZAxis(at, "axis", "the axis of a revolute");
      return;
    case JointKind::kWeld:
      j.kind = JointKind::kWeldInPlane;
      j.axis_W = PlanarZAxis(at, "axis", "the axis of a weld");
      return;
    case JointKind::kPrismatic:
      j.kind = JointKind::kPrismaticInPlane;
      j.axis_W = AxisAt(report_.Require(at, "axis", what), "the sliding direction");
      return;
    case JointKind::kPointOnLine:
      // The child's point stays on a line of the plane: one row along the line's in-plane
      // normal z × u (a frictionless wall or floor seen edge-on).
      j.kind = JointKind::kPointOnLineInPlane;
      j.axis_W = AxisAt(report_.Require(at, "axis", what), "the line's direction");
      return;
    default:
      break;
  }
  const char* hint = "";
  if (j.kind == JointKind::kSpherical) hint = "; in the plane a spherical joint is a revolute";
  if (j.kind == JointKind::kCylindrical) hint = "; use revolute or prismatic";
  if (j.kind == JointKind::kPlanar) {
    hint = "; every body of a planar scene already moves in the plane: remove the joint";
  }
  if (j.kind == JointKind::kPointOnPlane) {
    hint = "; a wall or floor of a planar scene is point_on_line with 'axis' along the line";
  }
  report_.Fail(type_at, fmt::format("joint type '{}' is 3-D; a planar scene's joints are "
                                    "revolute, prismatic, weld and point_on_line{}",
                                    type, hint));
}

void SceneReader::ReadPlanarRolling(const At& at, const SceneBody& body, const std::string& what,
                                    SceneRolling& r) {
  // The same reading as a disk or cylinder contact's axis (scene_contacts.cpp).
  r.axis_B = PlanarZAxis(at, "axis", "the axis of a rolling wheel");
  if (at.Has("shape")) {
    // Any round body rolls the same way in the plane: the circle of radius R on a line.
    const std::string shape = report_.Text(at.Child("shape"), "sphere, cylinder or disk");
    if (shape != "sphere" && shape != "cylinder" && shape != "disk") {
      report_.Fail(at.Child("shape"),
                   fmt::format("unknown rolling shape '{}'; shapes: sphere, cylinder, disk (in a "
                               "planar scene all roll as a circle on a line; 'shape' may be "
                               "left out)",
                               shape));
    }
  }
  r.shape = RollingShape::kWheelInPlane;
  r.radius = PositiveValue(report_.Require(at, "radius", what), kLength, "the radius");
  r.p_BoC_B =
      at.Has("center") ? BodyPointAt(at.Child("center"), body) : body.mass_properties.p_BoBcm_B();
  const At plane = report_.Require(at, "plane", what);
  report_.CheckMap(plane, {"point", "normal"},
                   "a rolling line ({point: [x, y], normal: [x, y]}: where the surface cuts the "
                   "plane of motion)");
  if (plane.Has("point")) {
    r.plane_point_W = WorldVector(plane.Child("point"), kLength, "a point of the line");
  }
  r.plane_normal_W = AxisAt(report_.Require(plane, "normal", "a plane"), "the line's normal");
  if (at.Has("mu_s")) {
    r.mu_s = Value(at.Child("mu_s"), kDimensionless, "the coefficient of static friction");
    if (!(r.mu_s >= 0)) report_.Fail(at.Child("mu_s"), "mu_s must be >= 0");
  }
}

}  // namespace chasles::scene_internal
