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
  for (const auto& g : gears) n.push_back(g.name);
  for (const auto& st : strings) n.push_back(st.name);
  return n;
}

const SceneSpot* SceneConstraints::At(int i) const {
  if (i < 0) return nullptr;
  size_t k = static_cast<size_t>(i);
  if (k < joints.size()) return &joints[k].where;
  k -= joints.size();
  if (k < rolling.size()) return &rolling[k].where;
  k -= rolling.size();
  if (k < drivers.size()) return &drivers[k].where;
  k -= drivers.size();
  if (k < gears.size()) return &gears[k].where;
  k -= gears.size();
  if (k < strings.size()) return &strings[k].where;
  return nullptr;
}

namespace scene_internal {

namespace {

// The entry's position in the file (marks are 0-based).
SceneSpot Spot(const At& at) {
  const YamlMark mark = at.node.Mark();
  return {mark.line >= 0 ? mark.line + 1 : 0, mark.column >= 0 ? mark.column + 1 : 0, at.path};
}

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
    report_.Fail(
        at.Has("name") ? at.Child("name") : at,
        fmt::format("two joints, rolling contacts, drivers, gears or strings are named '{}'; "
                    "names must be unique",
                    name));
  }
  taken.push_back(name);
  return name;
}

SceneJoint SceneReader::ReadJoint(const At& at, size_t i, const Scene& scene,
                                  std::vector<std::string>& taken) {
  report_.CheckMap(at, {"name", "type", "parent", "child", "at", "axis"}, "a joint");
  SceneJoint j;
  j.name = ConstraintName(at, "joint", i, taken);
  j.where = Spot(at);
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
  return j;
}

SceneRolling SceneReader::ReadRolling(const At& at, size_t i, const Scene& scene,
                                      std::vector<std::string>& taken) {
  report_.CheckMap(
      at, {"name", "body", "on", "shape", "radius", "axis", "center", "plane", "surface", "mu_s"},
      "a rolling contact");
  SceneRolling r;
  r.name = ConstraintName(at, "rolling", i, taken);
  r.where = Spot(at);
  const std::string what = fmt::format("rolling contact '{}'", r.name);
  r.body = BodyIndexAt(report_.Require(at, "body", what), scene);
  if (at.Has("on")) {
    r.on = ParentIndexAt(at.Child("on"), scene);
    if (r.on == r.body) {
      report_.Fail(at.Child("on"), "a body cannot roll on itself; name the body under it");
    }
  }
  const SceneBody& body = scene.bodies[static_cast<size_t>(r.body)];
  if (planar_) {
    ReadPlanarRolling(at, body, what, r);
    return r;
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
                 fmt::format("unknown rolling shape '{}'{}; shapes: sphere, cylinder, disk", shape,
                             DidYouMean(shape, {"sphere", "cylinder", "disk"})));
  }
  r.radius = PositiveValue(report_.Require(at, "radius", what), kLength, "the radius");
  if (r.shape != RollingShape::kSphere) {
    r.axis_B = AxisAt(report_.Require(at, "axis", what), "the symmetry axis (body frame)");
  } else if (at.Has("axis")) {
    report_.Fail(at.Child("axis"), "a sphere has no axis; remove 'axis'");
  }
  r.p_BoC_B =
      at.Has("center") ? BodyPointAt(at.Child("center"), body) : body.mass_properties.p_BoBcm_B();
  if (at.Has("surface")) {
    ReadRollingSurface(at, what, r);
    return r;
  }
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
  return r;
}

SceneDriver SceneReader::ReadDriver(const At& at, size_t i, const Scene& scene,
                                    std::vector<std::string>& taken) {
  report_.CheckMap(at, {"name", "type", "parent", "child", "at", "axis", "value"}, "a driver");
  SceneDriver d;
  d.name = ConstraintName(at, "driver", i, taken);
  d.where = Spot(at);
  const std::string what = fmt::format("driver '{}'", d.name);
  const At type_at = report_.Require(at, "type", what);
  const std::string type = report_.Text(type_at, "translation or rotation");
  if (type == "translation") {
    d.kind = DriverKind::kTranslation;
  } else if (type == "rotation") {
    d.kind = DriverKind::kRotation;
  } else {
    report_.Fail(type_at, fmt::format("unknown driver type '{}'{}; types: translation, rotation",
                                      type, DidYouMean(type, {"translation", "rotation"})));
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
    d.axis_W = PlanarZAxis(at, "axis", "the axis of a rotation driver");
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
  return d;
}

SceneGear SceneReader::ReadGear(const At& at, size_t i, const Scene& scene,
                                std::vector<std::string>& taken) {
  report_.CheckMap(
      at, {"name", "type", "parent", "child", "parent_circle", "child_circle", "keep_contact"},
      "a gear mesh");
  SceneGear g;
  g.where = Spot(at);
  g.name = ConstraintName(at, "gear", i, taken);
  const std::string what = fmt::format("gear mesh '{}'", g.name);
  const At type_at = report_.Require(at, "type", what);
  const std::string type = report_.Text(type_at, "external, internal or face");
  if (type == "external") {
    g.kind = GearKind::kExternal;
  } else if (type == "internal") {
    g.kind = GearKind::kInternal;
  } else if (type == "face") {
    g.kind = GearKind::kFace;
  } else {
    report_.Fail(type_at, fmt::format("unknown gear type '{}'{}; types: external, internal, face",
                                      type, DidYouMean(type, {"external", "internal", "face"})));
  }
  g.parent = ParentIndexAt(report_.Require(at, "parent", what), scene);
  g.child = BodyIndexAt(report_.Require(at, "child", what), scene);
  if (g.parent == g.child) {
    report_.Fail(at.Child("child"), "a gear mesh's parent and child must differ");
  }
  const auto circle = [&](const char* key, bool with_radius) {
    const At c_at = report_.Require(at, key, what);
    report_.CheckMap(c_at, {"center", "axis", "radius"}, "a pitch circle ({center, axis, radius})");
    ScenePitchCircle pc;
    pc.center_W = WorldVector(report_.Require(c_at, "center", "a pitch circle"), kLength,
                              "the centre (world)");
    pc.axis_W = planar_
                    ? PlanarZAxis(c_at, "axis", "the gear's axis")
                    : AxisAt(report_.Require(c_at, "axis", "a pitch circle"), "the gear's axis");
    if (with_radius) {
      pc.radius = PositiveValue(report_.Require(c_at, "radius", "a pitch circle"), kLength,
                                "the pitch radius");
    } else if (c_at.Has("radius")) {
      report_.Fail(c_at.Child("radius"),
                   "a face gear's pitch surface is the plane through its centre normal to "
                   "its axis; remove 'radius'");
    }
    return pc;
  };
  g.parent_circle = circle("parent_circle", g.kind != GearKind::kFace);
  g.child_circle = circle("child_circle", true);
  if (at.Has("keep_contact")) {
    const At k = at.Child("keep_contact");
    if (!k.node.IsScalar() || !DecodeBool(k.node, g.keep_contact)) {
      report_.Fail(k, fmt::format("expected true or false, got {}", KindOf(k.node)));
    }
  }
  CheckPitchCirclesTouch(at, g);
  return g;
}

// The pitch circles must touch at the initial configuration (the mesh row alone does not pull
// them together): the same distance the constraint's contact row holds.
void SceneReader::CheckPitchCirclesTouch(const At& at, const SceneGear& g) {
  const ScenePitchCircle& pc = g.parent_circle;
  const ScenePitchCircle& cc = g.child_circle;
  const double ra = cc.radius;
  const Vec3 d = pc.center_W - cc.center_W;
  double gap = 0.0;
  std::string rule;
  if (g.kind == GearKind::kFace) {
    const double sigma = pc.axis_W.dot(cc.axis_W);
    gap = d.dot(-pc.axis_W) - ra * std::sqrt(std::max(0.0, 1.0 - sigma * sigma));
    rule =
        "the lowest point of the child's pitch circle lies on the parent's pitch plane "
        "(the parent's axis points towards the child)";
  } else {
    const double ell = (d - d.dot(cc.axis_W) * cc.axis_W).norm();
    if (g.kind == GearKind::kInternal && !(ra < pc.radius)) {
      report_.Fail(at.Child("child_circle"),
                   fmt::format("an internal mesh needs the child's pitch radius ({:.6g} m) "
                               "smaller than the ring's ({:.6g} m)",
                               ra, pc.radius));
    }
    gap = g.kind == GearKind::kExternal ? ell - (ra + pc.radius) : (pc.radius - ra) - ell;
    rule = fmt::format("the centre distance in the child's plane is {:.9g} m, {} {:.9g} m", ell,
                       g.kind == GearKind::kExternal ? "the radii's sum" : "their difference",
                       g.kind == GearKind::kExternal ? ra + pc.radius : pc.radius - ra);
  }
  if (std::abs(gap) > 1e-6 * std::max(ra, 1e-3)) {
    report_.Fail(at, fmt::format("the pitch circles of gear mesh '{}' do not touch (gap "
                                 "{:.6g} m): {}; move a centre or change a radius",
                                 g.name, gap, rule));
  }
}

// A string's sense round a drum or pulley, about the string's normal.
int SceneReader::StringSenseAt(const At& at) {
  const std::string sense = report_.Text(at, "counterclockwise or clockwise");
  if (sense == "counterclockwise") return 1;
  if (sense == "clockwise") return -1;
  report_.Fail(at, fmt::format("unknown sense '{}'{}; expected counterclockwise or clockwise "
                               "(about the string's normal, following the string from 'from' "
                               "to 'to')",
                               sense, DidYouMean(sense, {"counterclockwise", "clockwise"})));
}

// An end of a string: {body, at, radius, sense}; `radius` makes it a drum (then `sense` is
// needed); `at` defaults to the body's centre of mass (the world has none).
SceneStringEnd SceneReader::ReadStringEnd(const At& at, const Scene& scene,
                                          const std::string& what) {
  report_.CheckMap(at, {"body", "at", "radius", "sense"},
                   "a string end ({body, at} or a drum {body, at, radius, sense})");
  SceneStringEnd e;
  e.body = ParentIndexAt(report_.Require(at, "body", what), scene);
  if (at.Has("at")) {
    e.p_W = WorldVector(at.Child("at"), kLength, "the end's point (world)");
  } else if (e.body == kWorld) {
    report_.Require(at, "at", what + " (the world has no centre of mass to default to)");
  }
  if (at.Has("radius")) {
    e.radius = PositiveValue(at.Child("radius"), kLength, "the drum's radius");
    e.sense = StringSenseAt(report_.Require(at, "sense", what + " (a drum)"));
  } else if (at.Has("sense")) {
    report_.Fail(at.Child("sense"),
                 "'sense' belongs to a drum; give its 'radius' too, or remove "
                 "'sense' for a string tied to a point");
  }
  return e;
}

SceneString SceneReader::ReadString(const At& at, size_t i, const Scene& scene,
                                    std::vector<std::string>& taken) {
  report_.CheckMap(at, {"name", "from", "to", "over", "normal", "length", "restitution"},
                   "a string");
  SceneString st;
  st.where = Spot(at);
  st.name = ConstraintName(at, "string", i, taken);
  const std::string what = fmt::format("string '{}'", st.name);
  st.from = ReadStringEnd(report_.Require(at, "from", what), scene, what + ": 'from'");
  st.to = ReadStringEnd(report_.Require(at, "to", what), scene, what + ": 'to'");
  if (st.from.body == kWorld && st.to.body == kWorld) {
    report_.Fail(at.Child("to"), "both ends of the string are on the world; tie one to a body");
  }
  if (st.from.body == st.to.body) {
    report_.Fail(at.Child("to"),
                 "both ends of the string are on the same body; tie them to two "
                 "different bodies (or one to the world)");
  }
  if (at.Has("over")) {
    const At list = at.Child("over");
    report_.CheckSequence(list, "a list of pulleys [{center, radius, sense, body}, ...]");
    for (size_t k = 0; k < list.node.size(); ++k) {
      const At p_at = list.Item(k);
      report_.CheckMap(p_at, {"center", "radius", "sense", "body"},
                       "a pulley ({center, radius, sense}, and 'body' when a body carries it)");
      SceneStringPulley p;
      if (p_at.Has("body")) p.body = ParentIndexAt(p_at.Child("body"), scene);
      p.center_W = WorldVector(report_.Require(p_at, "center", "a pulley"), kLength,
                               "the pulley's centre (world)");
      p.radius = PositiveValue(report_.Require(p_at, "radius", "a pulley"), kLength,
                               "the pulley's radius");
      p.sense = StringSenseAt(report_.Require(p_at, "sense", "a pulley"));
      st.over.push_back(p);
    }
  }
  if (planar_) {
    // A planar scene's strings lie in its plane: the normal is z.
    st.normal_W = PlanarZAxis(at, "normal", "the string's normal");
  } else if (at.Has("normal")) {
    st.normal_W = AxisAt(at.Child("normal"), "the string's normal");
  }
  // Slack strings (docs/constraints.md, "Strings that go slack"): the free length (default: the
  // path's length at the start) and Newton's restitution when it snaps taut.
  if (at.Has("length")) {
    st.length = PositiveValue(at.Child("length"), kLength, "the string's length");
  }
  if (at.Has("restitution")) {
    st.restitution =
        Value(at.Child("restitution"), kDimensionless, "the string's coefficient of restitution");
    if (!(st.restitution >= 0 && st.restitution <= 1)) {
      report_.Fail(at.Child("restitution"),
                   fmt::format("restitution must be in [0, 1] (0: the string snaps taut "
                               "plastically, 1: elastic), got {:g}",
                               st.restitution));
    }
  }
  if ((at.Has("length") || at.Has("restitution")) && (st.from.radius > 0.0 || st.to.radius > 0.0)) {
    report_.Fail(at.Child(at.Has("length") ? "length" : "restitution"),
                 "a string wound on a drum is held taut (how far a drum has turned is known "
                 "only modulo a turn, so its slack cannot be tracked); remove this key or tie "
                 "the string to a point of the body");
  }
  return st;
}

void SceneReader::ReadConstraints(const At& root, Scene& scene) {
  SceneConstraints& c = scene.dynamics.constraints;
  std::vector<std::string> taken;

  if (root.Has("joints")) {
    const At list = root.Child("joints");
    report_.CheckSequence(list, "a list of joints");
    for (size_t i = 0; i < list.node.size(); ++i) {
      c.joints.push_back(ReadJoint(list.Item(i), i, scene, taken));
    }
  }

  if (root.Has("rolling")) {
    const At list = root.Child("rolling");
    report_.CheckSequence(list, "a list of rolling contacts");
    for (size_t i = 0; i < list.node.size(); ++i) {
      c.rolling.push_back(ReadRolling(list.Item(i), i, scene, taken));
    }
  }

  if (root.Has("drivers")) {
    const At list = root.Child("drivers");
    report_.CheckSequence(list, "a list of drivers");
    for (size_t i = 0; i < list.node.size(); ++i) {
      c.drivers.push_back(ReadDriver(list.Item(i), i, scene, taken));
    }
  }

  if (root.Has("gears")) {
    const At list = root.Child("gears");
    report_.CheckSequence(list, "a list of gear meshes");
    for (size_t i = 0; i < list.node.size(); ++i) {
      c.gears.push_back(ReadGear(list.Item(i), i, scene, taken));
    }
  }

  if (root.Has("strings")) {
    const At list = root.Child("strings");
    report_.CheckSequence(list, "a list of strings");
    for (size_t i = 0; i < list.node.size(); ++i) {
      c.strings.push_back(ReadString(list.Item(i), i, scene, taken));
    }
  }
}

}  // namespace scene_internal
}  // namespace chasles
