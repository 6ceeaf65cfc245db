// Reading the constraint keys of a scene (docs/scene-format.md, "Joints, rolling and
// drivers"): `joints`, `rolling` and `drivers`. Joint points and axes are world coordinates at
// the initial configuration; BuildStudy turns them into each body's attachment frame.

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "chasles/scene/scene.h"
#include "chasles/scene/scene_constraints.h"
#include "chasles/suggest.h"
#include "internal/scene_reader.h"

namespace chasles {

std::vector<std::string> SceneConstraints::names() const {
  std::vector<std::string> n;
  for (const auto& j : joints) n.push_back(j.name);
  for (const auto& r : rolling) n.push_back(r.name);
  for (const auto& d : drivers) n.push_back(d.name);
  return n;
}

namespace scene_internal {

namespace {

constexpr Dimension kVelocity{1, 0, -1};
constexpr Dimension kAcceleration{1, 0, -2};
constexpr Dimension kAngularVelocity{0, 0, -1};
constexpr Dimension kAngularAcceleration{0, 0, -2};

struct JointType {
  const char* name;
  JointKind kind;
  /// True when the joint needs `axis` (the others are symmetric about their point).
  bool needs_axis;
};

constexpr JointType kJointTypes[] = {
    {"weld", JointKind::kWeld, false},
    {"revolute", JointKind::kRevolute, true},
    {"prismatic", JointKind::kPrismatic, true},
    {"spherical", JointKind::kSpherical, false},
    {"cylindrical", JointKind::kCylindrical, true},
    {"planar", JointKind::kPlanar, true},
    {"point_on_plane", JointKind::kPointOnPlane, true},
    {"point_on_line", JointKind::kPointOnLine, true},
};

}  // namespace

int SceneReader::ParentIndexAt(const At& at, const Scene& scene) {
  const std::string name = report_.Text(at, "a body name or 'world'");
  if (name == "world") return kWorld;
  std::vector<std::string> names;
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].name == name) return static_cast<int>(i);
    names.push_back(scene.bodies[i].name);
  }
  names.emplace_back("world");
  report_.Fail(at, fmt::format("the scene has no body '{}'{}; name one of its bodies or 'world' "
                               "({})",
                               name, DidYouMean(name, names), fmt::join(names, ", ")));
}

Vec3 SceneReader::AxisAt(const At& at, std::string_view what) {
  const Vec3 a = WorldVector(at, kDimensionless, what);
  // Only the direction matters; a zero (or non-finite) vector has none.
  if (!(a.norm() > 0) || !a.allFinite()) {
    report_.Fail(at, fmt::format("{} has zero length; give a direction such as {}", what,
                                 planar_ ? "[1, 0]" : "[0, 0, 1]"));
  }
  return a.normalized();
}

std::string SceneReader::ConstraintName(const At& at, const char* kind, size_t index,
                                        std::vector<std::string>& taken) {
  const std::string name = at.Has("name") ? report_.Text(at.Child("name"), "a name")
                                          : fmt::format("{}{}", kind, index + 1);
  if (std::find(taken.begin(), taken.end(), name) != taken.end()) {
    report_.Fail(at.Has("name") ? at.Child("name") : at,
                 fmt::format("two joints, rolling contacts or drivers are named '{}'; names must "
                             "be unique",
                             name));
  }
  taken.push_back(name);
  return name;
}

void SceneReader::ReadConstraints(const At& root, Scene& scene) {
  SceneConstraints& c = scene.dynamics.constraints;
  std::vector<std::string> taken;

  if (root.Has("joints")) {
    const At list = root.Child("joints");
    report_.CheckSequence(list, "a list of joints");
    for (size_t i = 0; i < list.node.size(); ++i) {
      const At at = list.Item(i);
      report_.CheckMap(at, {"name", "type", "parent", "child", "at", "axis"}, "a joint");
      SceneJoint j;
      j.name = ConstraintName(at, "joint", i, taken);
      const std::string what = fmt::format("joint '{}'", j.name);
      const At type_at = report_.Require(at, "type", what);
      const std::string type = report_.Text(type_at, "a joint type");
      const JointType* jt = nullptr;
      std::vector<std::string> types;
      for (const JointType& t : kJointTypes) {
        types.emplace_back(t.name);
        if (type == t.name) jt = &t;
      }
      if (!jt) {
        report_.Fail(type_at, fmt::format("unknown joint type '{}'{}; types: {}", type,
                                          DidYouMean(type, types), fmt::join(types, ", ")));
      }
      j.kind = jt->kind;
      if (planar_) ReadPlanarJointType(at, what, j);
      j.parent = ParentIndexAt(report_.Require(at, "parent", what), scene);
      j.child = BodyIndexAt(report_.Require(at, "child", what), scene);
      if (j.parent == j.child) {
        report_.Fail(at.Child("child"), "a joint's parent and child must differ");
      }
      j.p_WJ = WorldVector(report_.Require(at, "at", what), kLength, "the joint point (world)");
      if (planar_) {
        // ReadPlanarJointType read the axis.
      } else if (jt->needs_axis) {
        j.axis_W = AxisAt(report_.Require(at, "axis", what), "the joint axis");
      } else if (at.Has("axis")) {
        j.axis_W = AxisAt(at.Child("axis"), "the joint axis");
      }
      c.joints.push_back(j);
    }
  }

  if (root.Has("rolling")) {
    const At list = root.Child("rolling");
    report_.CheckSequence(list, "a list of rolling contacts");
    for (size_t i = 0; i < list.node.size(); ++i) {
      const At at = list.Item(i);
      report_.CheckMap(at, {"name", "body", "shape", "radius", "axis", "center", "plane", "mu_s"},
                       "a rolling contact");
      SceneRolling r;
      r.name = ConstraintName(at, "rolling", i, taken);
      const std::string what = fmt::format("rolling contact '{}'", r.name);
      r.body = BodyIndexAt(report_.Require(at, "body", what), scene);
      const SceneBody& body = scene.bodies[static_cast<size_t>(r.body)];
      if (planar_) {
        ReadPlanarRolling(at, body, what, r);
        c.rolling.push_back(r);
        continue;
      }
      const At shape_at = report_.Require(at, "shape", what);
      const std::string shape = report_.Text(shape_at, "sphere, cylinder or disk");
      if (shape == "sphere") {
        r.shape = RollingShape::kSphere;
      } else if (shape == "cylinder") {
        r.shape = RollingShape::kCylinder;
      } else if (shape == "disk") {
        r.shape = RollingShape::kDisk;
      } else {
        report_.Fail(shape_at,
                     fmt::format("unknown rolling shape '{}'{}; shapes: sphere, cylinder, disk",
                                 shape, DidYouMean(shape, {"sphere", "cylinder", "disk"})));
      }
      r.radius = PositiveValue(report_.Require(at, "radius", what), kLength, "the radius");
      if (r.shape != RollingShape::kSphere) {
        r.axis_B = AxisAt(report_.Require(at, "axis", what), "the symmetry axis (body frame)");
      } else if (at.Has("axis")) {
        report_.Fail(at.Child("axis"), "a sphere has no axis; remove 'axis'");
      }
      r.p_BoC_B = at.Has("center") ? BodyPointAt(at.Child("center"), body)
                                   : body.mass_properties.p_BoBcm_B();
      const At plane = report_.Require(at, "plane", what);
      report_.CheckMap(plane, {"point", "normal"}, "a plane ({point, normal})");
      if (plane.Has("point")) {
        r.plane_point_W = Vector(plane.Child("point"), kLength, "a point of the plane");
      }
      r.plane_normal_W = AxisAt(report_.Require(plane, "normal", "a plane"), "the plane's normal");
      if (at.Has("mu_s")) {
        r.mu_s = Value(at.Child("mu_s"), kDimensionless, "the coefficient of static friction");
        if (!(r.mu_s >= 0)) report_.Fail(at.Child("mu_s"), "mu_s must be >= 0");
      }
      c.rolling.push_back(r);
    }
  }

  if (root.Has("drivers")) {
    const At list = root.Child("drivers");
    report_.CheckSequence(list, "a list of drivers");
    for (size_t i = 0; i < list.node.size(); ++i) {
      const At at = list.Item(i);
      report_.CheckMap(at, {"name", "type", "parent", "child", "at", "axis", "value"}, "a driver");
      SceneDriver d;
      d.name = ConstraintName(at, "driver", i, taken);
      const std::string what = fmt::format("driver '{}'", d.name);
      const At type_at = report_.Require(at, "type", what);
      const std::string type = report_.Text(type_at, "translation or rotation");
      if (type == "translation") {
        d.kind = DriverKind::kTranslation;
      } else if (type == "rotation") {
        d.kind = DriverKind::kRotation;
      } else {
        report_.Fail(type_at,
                     fmt::format("unknown driver type '{}'{}; types: translation, rotation", type,
                                 DidYouMean(type, {"translation", "rotation"})));
      }
      const bool rot = d.kind == DriverKind::kRotation;
      d.parent = ParentIndexAt(report_.Require(at, "parent", what), scene);
      d.child = BodyIndexAt(report_.Require(at, "child", what), scene);
      if (d.parent == d.child) {
        report_.Fail(at.Child("child"), "a driver's parent and child must differ");
      }
      d.p_WJ = WorldVector(report_.Require(at, "at", what), kLength, "the driver point (world)");
      if (planar_ && rot) {
        // A rotation in the plane is about z.
        if (at.Has("axis")) {
          report_.Fail(at.Child("axis"),
                       "in a planar scene a rotation driver turns about z; remove 'axis'");
        }
        d.axis_W = Vec3::UnitZ();
      } else {
        d.axis_W = AxisAt(report_.Require(at, "axis", what), "the driver axis");
      }
      const At value = report_.Require(at, "value", what);
      report_.CheckMap(value, {"position", "velocity", "acceleration"},
                       "a driver's value ({position, velocity, acceleration})");
      if (value.Has("position")) {
        d.f0 = Value(value.Child("position"), rot ? kDimensionless : kLength,
                     rot ? "the angle at t = 0" : "the position at t = 0");
      }
      if (value.Has("velocity")) {
        d.f1 = Value(value.Child("velocity"), rot ? kAngularVelocity : kVelocity,
                     rot ? "the rate at t = 0" : "the velocity at t = 0");
      }
      if (value.Has("acceleration")) {
        d.f2 = Value(value.Child("acceleration"), rot ? kAngularAcceleration : kAcceleration,
                     "the (constant) acceleration");
      }
      c.drivers.push_back(d);
    }
  }
}

}  // namespace scene_internal
}  // namespace chasles
