// Reading the dynamics keys of a scene (docs/scene-format.md, "Dynamics"): gravity, initial
// motion, forces, events, impulses, impacts, simulation and output.

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include <fmt/format.h>

#include "chasles/scene/expression.h"
#include "chasles/scene/scene.h"
#include "chasles/suggest.h"
#include "internal/scene_reader.h"
#include "internal/study_columns.h"

namespace chasles {

namespace {

// Dimension of each state variable suffix, in StateVariableLayout order.
constexpr std::array<Dimension, StateVariableLayout::kPerBody> kSuffixDimensions = {
    kLength,          kLength,          kLength,          kVelocity,        kVelocity,
    kVelocity,        kAngularVelocity, kAngularVelocity, kAngularVelocity, kAngularVelocity,
    kAngularVelocity, kAngularVelocity, kDimensionless,   kDimensionless,   kDimensionless,
    kDimensionless,   kVelocity,        kAngularVelocity, kDimensionless,   kAngularAcceleration};

// Standard gravity (CGPM 1901, exact) [m/s²].
constexpr double kStandardGravity = 9.80665;

// [A-Za-z_][A-Za-z_0-9]*, as the expression reader takes a name.
bool IsIdentifier(std::string_view name) {
  const auto letter = [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
  };
  if (name.empty() || !letter(name[0])) return false;
  return std::all_of(name.begin() + 1, name.end(),
                     [&](char c) { return letter(c) || (c >= '0' && c <= '9'); });
}

// Shortest text that parses back to exactly `v` (fmt's round-trip format).
std::string ExactText(double v) {
  return v < 0 ? fmt::format("(-{})", -v) : fmt::format("{}", v);
}

}  // namespace

bool SceneVectorExpression::is_constant() const {
  return components[0].is_constant() && components[1].is_constant() && components[2].is_constant();
}

int SceneVectorExpression::variable_count() const {
  return std::max({components[0].variable_count(), components[1].variable_count(),
                   components[2].variable_count()});
}

const SceneSpot& SceneSimulation::Spot(std::string_view key) const {
  const auto it = keys.find(key);
  return it != keys.end() ? it->second : where;
}

Vec3 SceneVectorExpression::Evaluate(std::span<const double> v) const {
  return {components[0].Evaluate(v), components[1].Evaluate(v), components[2].Evaluate(v)};
}

namespace scene_internal {

SceneSpot KeySpotAt(const At& map, std::string_view key) {
  const std::string path = map.Child(key).path;
  if (map.node.IsMap()) {
    for (const auto& kv : map.node) {
      if (kv.first.IsScalar() && kv.first.Scalar() == key) {
        const YamlMark mark = kv.first.Mark();
        return {mark.line >= 0 ? mark.line + 1 : 0, mark.column >= 0 ? mark.column + 1 : 0, path};
      }
    }
  }
  SceneSpot spot = SpotAt(map.Child(key));
  spot.key = path;
  return spot;
}

std::optional<Symbol> SceneReader::ResolveStateSymbol(const At& at, std::string_view name) {
  if (const int slot = StateSlot(name); slot >= 0) {
    if (parameters_.count(name)) {
      report_.Fail(at, fmt::format("'{}' is both a parameter and a state variable in this "
                                   "expression; rename the parameter",
                                   name));
    }
    if (slot >= contact_slot_begin_) {
      // A contact point's force, slip or mode: known only after the contact solve in the
      // point's current mode, so (like a reaction) only an event may read it.
      if (!allow_reactions_) {
        report_.Fail(at, fmt::format("'{}' is a contact quantity; contact quantities may appear "
                                     "only in an event's 'when'",
                                     name));
      }
      static constexpr std::array<Dimension, StateVariableLayout::kPerContactPoint> kDims = {
          kDimensionless, kForce, kForce, kVelocity, kLength};
      return Symbol::Variable(slot,
                              kDims[static_cast<size_t>((slot - contact_slot_begin_) %
                                                        StateVariableLayout::kPerContactPoint)]);
    }
    if (slot >= reaction_slot_begin_) {
      // A constraint's reaction: known only after the constraint solve, so only an event may
      // read it (a force that read it would feed back into the solve).
      if (!allow_reactions_) {
        report_.Fail(at, fmt::format("'{}' is a reaction; reactions may appear only in an "
                                     "event's 'when'",
                                     name));
      }
      return Symbol::Variable(slot, (slot - reaction_slot_begin_) % 6 < 3 ? kForce : kMoment);
    }
    const int suffix = slot == 0 ? -1 : (slot - 1) % StateVariableLayout::kPerBody;
    if (suffix == StateVariableLayout::kAlpha && !allow_reactions_) {
      // α comes out of the solve that the forces feed (eq. 8.43), as a reaction does.
      report_.Fail(at, fmt::format("'{}' is an angular acceleration; accelerations may appear "
                                   "only in an event's 'when'",
                                   name));
    }
    return Symbol::Variable(slot,
                            suffix < 0 ? kTime : kSuffixDimensions[static_cast<size_t>(suffix)]);
  }
  std::optional<Symbol> parameter = ResolveParameter(name);
  if (!parameter && planar_) {
    // A version-1 name (scene_versions.cpp), else a 3-D name: say which planar name to use.
    if (std::optional<Symbol> renamed = PlanarOldName(at, name)) return renamed;
    PlanarNameHint(at, name);
  }
  return parameter;
}

void SceneReader::PlanarNameHint(const At& at, std::string_view name) {
  // A 3-D body variable in a planar scene: say which planar name to use instead of a bare
  // "unknown name". Every suffix is one word: the body is what comes before the last '_'.
  const size_t cut = name.rfind('_');
  if (cut == std::string_view::npos || !state_bodies_.contains(name.substr(0, cut))) return;
  const std::string prefix(name.substr(0, cut + 1));  // "<body>_"
  const std::string_view suffix = name.substr(cut + 1);
  bool three_d = false;
  for (const char* s : StateVariableLayout::kSuffixes) three_d = three_d || suffix == s;
  if (!three_d) return;
  std::vector<std::string> names;
  for (const auto& [s, k] : StateVariableLayout::kPlanarNames) names.push_back(prefix + s);
  const bool rotation = suffix[0] == 'w' || suffix == "omega";
  report_.Fail(at, fmt::format("'{}' is a 3-D state variable; a planar scene's body variables "
                               "are {}{}",
                               name, fmt::join(names, ", "),
                               rotation ? fmt::format(" ('{}omega' is the signed angular "
                                                      "velocity about z)",
                                                      prefix)
                                        : ""));
}

Expression SceneReader::StateExpression(const At& at, const Dimension& expected,
                                        std::string_view what) {
  const std::string text = report_.Text(at, fmt::format("{} ({})", what, expected.Describe()));
  Expression e;
  try {
    e = Expression::Parse(
        text, [&](std::string_view n) { return ResolveStateSymbol(at, n); },
        [this] { return StateVariableNames(); });
  } catch (const SceneError&) {
    throw;
  } catch (const ExpressionError& err) {
    report_.Fail(at, err.message(), at.node.Scalar() == text ? err.offset() : 0);
  }
  if (e.is_constant()) {
    // A constant: read as any other value (bare numbers in the scene's units), kept exactly.
    return Expression::Parse(ExactText(Value(at, expected, what)), {});
  }
  if (e.dimension() != expected) {
    report_.Fail(at, fmt::format("expected {} for {}, got {}{}", expected.Describe(), what,
                                 e.dimension().Describe(),
                                 e.unit_note().empty() ? "" : "; " + e.unit_note()));
  }
  return e;
}

SceneVectorExpression SceneReader::StateVector(const At& at, const Dimension& expected,
                                               std::string_view what) {
  if (!at.node.IsSequence() || at.node.size() != 3) {
    report_.Fail(at, fmt::format("expected {} as a list of three values [x, y, z], got {}", what,
                                 KindOf(at.node)));
  }
  SceneVectorExpression v;
  for (size_t i = 0; i < 3; ++i) v.components[i] = StateExpression(at.Item(i), expected, what);
  return v;
}

int SceneReader::BodyIndexAt(const At& at, const Scene& scene) {
  const std::string name = report_.Text(at, "a body name");
  std::vector<std::string> names;
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].name == name) return static_cast<int>(i);
    names.push_back(scene.bodies[i].name);
  }
  report_.Fail(at, fmt::format("the scene has no body '{}'{}; bodies: {}", name,
                               DidYouMean(name, names), fmt::join(names, ", ")));
}

Vec3 SceneReader::BodyPointAt(const At& at, const SceneBody& body) {
  if (at.node.IsSequence()) return BodyVector(at, kLength, "a point in the body frame");
  const std::string name = report_.Text(at, "a point name or a position [x, y, z]");
  std::vector<std::string> names;
  for (const ScenePoint& p : body.points) {
    if (p.name == name) return p.p_BoP_B;
    names.push_back(p.name);
  }
  if (name == "center_of_mass") return body.mass_properties.p_BoBcm_B();
  if (name == "origin") return Vec3::Zero();
  names.emplace_back("center_of_mass");
  names.emplace_back("origin");
  report_.Fail(at, fmt::format("body '{}' has no point '{}'{}; name one of its 'points' ({}), or "
                               "give a position [x, y, z] in the body frame",
                               body.name, name, DidYouMean(name, names), fmt::join(names, ", ")));
}

VectorFrame SceneReader::FrameAt(const At& at) {
  const std::string f = report_.Text(at, "world or body");
  if (f == "world") return VectorFrame::kWorld;
  if (f == "body") return VectorFrame::kBody;
  report_.Fail(at, fmt::format("frame must be 'world' or 'body', got '{}'", f));
}

void SceneReader::ReadInitial(const At& at, const SceneBody& body, SceneInitialState& initial) {
  if (planar_) return ReadPlanarInitial(at, body, initial);
  report_.CheckMap(at,
                   {"position", "rotation", "euler", "quaternion", "velocity", "velocity_point",
                    "angular_velocity", "angular_velocity_frame"},
                   "an initial state");
  if (at.Has("position")) {
    const At p = at.Child("position");
    initial.p_WBo = InitialMotion(p, Vector(p, kLength, "a position"), "position", "m");
  }
  const Mat3 R_WB = ReadOrientation(at);
  initial.q_WB = Quat(R_WB).normalized();
  if (at.Has("velocity")) {
    const At v = at.Child("velocity");
    initial.v_WP_W = InitialMotion(v, Vector(v, kVelocity, "a velocity"), "velocity", "m/s");
  }
  if (at.Has("velocity_point")) {
    const At p = at.Child("velocity_point");
    if (!at.Has("velocity")) report_.Fail(p, "'velocity_point' needs 'velocity'");
    if (!p.node.IsScalar()) report_.Fail(p, "expected the name of one of the body's points");
    initial.p_BoP_B = BodyPointAt(p, body);
  }
  if (at.Has("angular_velocity")) {
    const At w = at.Child("angular_velocity");
    initial.w_WB_W = InitialMotion(w, Vector(w, kAngularVelocity, "an angular velocity"),
                                   "angular velocity", "rad/s");
  }
  if (at.Has("angular_velocity_frame")) {
    if (FrameAt(at.Child("angular_velocity_frame")) == VectorFrame::kBody) {
      initial.w_WB_W = R_WB * initial.w_WB_W;
    }
  }
}

Vec3 SceneReader::InitialMotion(const At& at, const Vec3& v, std::string_view what,
                                std::string_view unit) {
  const double magnitude = v.stableNorm();
  if (magnitude <= kMotionScale) return v;
  report_.Fail(at, fmt::format("the initial {} has a magnitude of {:.6g} {}; a run accepts motions "
                               "up to {:g} in SI (beyond, energies and moments leave double "
                               "precision): check the value and its unit",
                               what, magnitude, unit, kMotionScale));
}

SceneForce SceneReader::ReadForce(const At& at, const Scene& scene, size_t index) {
  if (!at.node.IsMap()) {
    report_.Fail(at, fmt::format("expected a force element (a mapping with 'type:'), got {}",
                                 KindOf(at.node)));
  }
  SceneForce f;
  f.where = SpotAt(at);
  const std::string type =
      report_.Text(report_.Require(at, "type", "a force element"),
                   "force, moment, spring, drag, central_gravity, cable, string_pull, "
                   "joint_torque or bearing");
  const std::vector<std::string> types = {"force",       "moment",          "spring",
                                          "drag",        "central_gravity", "cable",
                                          "string_pull", "joint_torque",    "bearing"};
  f.name = at.Has("name") ? report_.Text(at.Child("name"), "a name")
                          : fmt::format("{} {}", type, index + 1);
  const std::string what = fmt::format("{} '{}'", type, f.name);
  if (type == "force" || type == "moment") {
    const bool force = type == "force";
    std::vector<std::string> keys = {"type", "name", "body", "value", "frame"};
    if (force) keys.emplace_back("point");
    report_.CheckMap(at, keys, fmt::format("a {} element", type));
    f.type = force ? SceneForce::Type::kForce : SceneForce::Type::kMoment;
    f.body = BodyIndexAt(report_.Require(at, "body", what), scene);
    const SceneBody& body = scene.bodies[static_cast<size_t>(f.body)];
    if (force && at.Has("point") && at.Child("point").node.IsMap()) {
      // {world: [x, y, z]}: a point fixed in the world (the material point there now).
      const At p = at.Child("point");
      report_.CheckMap(p, {"world"}, "a world point ({world: [x, y, z]})");
      f.p_BoP_B = WorldVector(report_.Require(p, "world", what), kLength, "a world point");
      f.point_frame = VectorFrame::kWorld;
    } else {
      f.p_BoP_B =
          at.Has("point") ? BodyPointAt(at.Child("point"), body) : body.mass_properties.p_BoBcm_B();
    }
    f.expression_where = SpotAt(report_.Require(at, "value", what));
    f.value = planar_
                  ? PlanarStateVector(report_.Require(at, "value", what), force ? kForce : kMoment,
                                      force ? "a force" : "a moment", !force)
                  : StateVector(report_.Require(at, "value", what), force ? kForce : kMoment,
                                force ? "a force" : "a moment");
    if (at.Has("frame")) f.frame = FrameAt(at.Child("frame"));
  } else if (type == "cable") {
    ReadCable(at, scene, what, f);
  } else if (type == "string_pull") {
    ReadStringPull(at, scene, what, f);
  } else if (type == "joint_torque") {
    ReadJointTorque(at, scene, what, f);
  } else if (type == "bearing") {
    ReadBearing(at, scene, what, f);
  } else if (type == "spring") {
    report_.CheckMap(at, {"type", "name", "from", "to", "rest_length", "stiffness", "damping"},
                     "a spring element");
    f.type = SceneForce::Type::kSpring;
    auto end = [&](const At& e, int& body, Vec3& point) {
      if (e.Has("world")) {
        report_.CheckMap(e, {"world"}, "a world point");
        body = kWorld;
        point = WorldVector(e.Child("world"), kLength, "a world point");
        return;
      }
      report_.CheckMap(e, {"body", "point"}, "a spring end ({body, point} or {world: [x, y, z]})");
      body = BodyIndexAt(report_.Require(e, "body", "a spring end"), scene);
      const SceneBody& b = scene.bodies[static_cast<size_t>(body)];
      point = e.Has("point") ? BodyPointAt(e.Child("point"), b) : b.mass_properties.p_BoBcm_B();
    };
    end(report_.Require(at, "from", what), f.body, f.p_BoP_B);
    if (f.body == kWorld) {
      report_.Fail(at.Child("from"), "'from' must be a body end; put the world point in 'to'");
    }
    end(report_.Require(at, "to", what), f.body_b, f.p_BoQ_B);
    if (f.body_b == f.body) {
      report_.Fail(at.Child("to"),
                   fmt::format("both ends of {} are on body '{}'; a spring inside one rigid body "
                               "exerts no net force or moment on it: put one end on another body "
                               "or on the world ({{world: [x, y, z]}})",
                               what, scene.bodies[static_cast<size_t>(f.body)].name));
    }
    f.rest_length =
        at.Has("rest_length") ? Value(at.Child("rest_length"), kLength, "the rest length") : 0.0;
    f.stiffness =
        at.Has("stiffness") ? Value(at.Child("stiffness"), kStiffness, "the stiffness") : 0.0;
    f.damping = at.Has("damping") ? Value(at.Child("damping"), kLinearDamping, "the damping") : 0.0;
    if (f.rest_length < 0) report_.Fail(at.Child("rest_length"), "the rest length must be >= 0");
    if (f.stiffness < 0) report_.Fail(at.Child("stiffness"), "the stiffness must be >= 0");
    if (f.damping < 0) report_.Fail(at.Child("damping"), "the damping must be >= 0");
  } else if (type == "drag") {
    report_.CheckMap(at, {"type", "name", "body", "linear", "angular"}, "a drag element");
    f.type = SceneForce::Type::kDrag;
    f.body = BodyIndexAt(report_.Require(at, "body", what), scene);
    f.linear = at.Has("linear") ? Value(at.Child("linear"), kLinearDamping, "linear drag") : 0.0;
    f.angular =
        at.Has("angular") ? Value(at.Child("angular"), kAngularDamping, "angular drag") : 0.0;
    if (f.linear < 0) report_.Fail(at.Child("linear"), "the linear drag must be >= 0");
    if (f.angular < 0) report_.Fail(at.Child("angular"), "the angular drag must be >= 0");
  } else if (type == "central_gravity") {
    report_.CheckMap(at, {"type", "name", "mu", "centre"}, "a central_gravity element");
    f.type = SceneForce::Type::kCentralGravity;
    f.mu = PositiveValue(report_.Require(at, "mu", what), kGravitationalParameter, "mu (= G M)");
    if (at.Has("centre")) f.centre_W = WorldVector(at.Child("centre"), kLength, "the centre");
  } else {
    report_.Fail(at.Child("type"), fmt::format("unknown force type '{}'{}; types: {}", type,
                                               DidYouMean(type, types), fmt::join(types, ", ")));
  }
  return f;
}

// A cable from a body point to a fixed world point (the winch), pulling with a tension >= 0.
void SceneReader::ReadCable(const At& at, const Scene& scene, const std::string& what,
                            SceneForce& f) {
  report_.CheckMap(at, {"type", "name", "body", "point", "winch", "tension"}, "a cable element");
  f.type = SceneForce::Type::kCable;
  f.body = BodyIndexAt(report_.Require(at, "body", what), scene);
  const SceneBody& body = scene.bodies[static_cast<size_t>(f.body)];
  f.p_BoP_B =
      at.Has("point") ? BodyPointAt(at.Child("point"), body) : body.mass_properties.p_BoBcm_B();
  f.p_WQ = WorldVector(report_.Require(at, "winch", what), kLength, "the winch's world point");
  f.scalar = StateExpression(report_.Require(at, "tension", what), kForce, "the tension");
  if (f.scalar.is_constant() && f.scalar.Evaluate({}) < 0) {
    report_.Fail(at.Child("tension"), "the tension must be >= 0: a cable can only pull");
  }
}

// A string wound on a drum of a body, pulled by hand with a tension along a fixed world
// direction (model/forces.h, StringPull): {body, drum: {center, radius, sense, axis},
// direction, tension}; the centre (default the centre of mass) and axis (default z) in the
// body's frame.
void SceneReader::ReadStringPull(const At& at, const Scene& scene, const std::string& what,
                                 SceneForce& f) {
  report_.CheckMap(at, {"type", "name", "body", "drum", "direction", "tension"},
                   "a string_pull element");
  f.type = SceneForce::Type::kStringPull;
  f.body = BodyIndexAt(report_.Require(at, "body", what), scene);
  const SceneBody& body = scene.bodies[static_cast<size_t>(f.body)];
  const At drum = report_.Require(at, "drum", what);
  report_.CheckMap(drum, {"center", "radius", "sense", "axis"},
                   "a drum ({radius, sense}, optionally center and axis in the body's frame)");
  f.p_BoP_B = drum.Has("center") ? BodyPointAt(drum.Child("center"), body)
                                 : body.mass_properties.p_BoBcm_B();
  f.drum_radius = PositiveValue(report_.Require(drum, "radius", what + ": 'drum'"), kLength,
                                "the drum's radius");
  f.drum_sense = StringSenseAt(report_.Require(drum, "sense", what + ": 'drum'"));
  if (drum.Has("axis")) {
    if (planar_) {
      report_.Fail(drum.Child("axis"),
                   "a planar scene's drums turn about z, the plane's normal; remove 'axis'");
    }
    const At axis = drum.Child("axis");
    const Vec3 a = BodyVector(axis, kDimensionless, "the drum's axis (body frame)");
    if (!(a.norm() > 0) || !a.allFinite()) {
      report_.Fail(axis, "the drum's axis has zero length; give a direction such as [0, 0, 1]");
    }
    f.drum_axis_B = a.normalized();
  }
  f.direction_W = AxisAt(report_.Require(at, "direction", what), "the pull's direction");
  if (std::abs(f.direction_W.dot(f.drum_axis_B)) > 1.0 - 1e-12 && !planar_) {
    report_.Fail(at.Child("direction"),
                 "the pull's direction is along the drum's axis; the string would leave the "
                 "drum from no side: give a direction in the drum's plane");
  }
  f.scalar = StateExpression(report_.Require(at, "tension", what), kForce, "the tension");
  if (f.scalar.is_constant() && f.scalar.Evaluate({}) < 0) {
    report_.Fail(at.Child("tension"), "the tension must be >= 0: a string can only pull");
  }
}

// A torque across a revolute or cylindrical joint, about its axis (+ on the child).
void SceneReader::ReadJointTorque(const At& at, const Scene& scene, const std::string& what,
                                  SceneForce& f) {
  report_.CheckMap(at, {"type", "name", "joint", "value"}, "a joint_torque element");
  f.type = SceneForce::Type::kJointTorque;
  const At joint_at = report_.Require(at, "joint", what);
  const std::string joint = report_.Text(joint_at, "a joint name");
  const std::vector<SceneJoint>& joints = scene.dynamics.constraints.joints;
  std::vector<std::string> names;
  for (size_t j = 0; j < joints.size(); ++j) {
    const JointKind k = joints[j].kind;
    if (k != JointKind::kRevolute && k != JointKind::kCylindrical &&
        k != JointKind::kRevoluteInPlane) {
      continue;
    }
    if (joints[j].name == joint) f.joint = static_cast<int>(j);
    names.push_back(joints[j].name);
  }
  if (f.joint < 0) {
    report_.Fail(joint_at, fmt::format("the scene has no revolute or cylindrical joint '{}'{}; "
                                       "a joint torque acts about such a joint's axis{}{}",
                                       joint, DidYouMean(joint, names),
                                       names.empty() ? "" : "; joints: ", fmt::join(names, ", ")));
  }
  f.body = joints[static_cast<size_t>(f.joint)].child;
  f.expression_where = SpotAt(report_.Require(at, "value", what));
  f.scalar = StateExpression(report_.Require(at, "value", what), kMoment, "a torque");
}

SceneEvent SceneReader::ReadEvent(const At& at, size_t index, const Scene& scene) {
  report_.CheckMap(at, {"name", "when", "crosses", "direction", "action", "contact", "change"},
                   "an event");
  SceneEvent e;
  e.where = SpotAt(at);
  e.name = at.Has("name") ? report_.Text(at.Child("name"), "a name")
                          : fmt::format("event {}", index + 1);
  if (at.Has("contact") || at.Has("change")) {
    ReadModeEvent(at, scene, e);
    return e;
  }
  const At when = report_.Require(at, "when", fmt::format("event '{}'", e.name));
  // The level crossed fixes the dimension: read `when` for its dimension first.
  const std::string text = report_.Text(when, "an expression of t and the state");
  Expression probe;
  allow_reactions_ = true;
  try {
    probe = Expression::Parse(
        text, [&](std::string_view n) { return ResolveStateSymbol(when, n); },
        [this] { return StateVariableNames(); });
  } catch (const SceneError&) {
    allow_reactions_ = false;
    throw;
  } catch (const ExpressionError& err) {
    allow_reactions_ = false;
    report_.Fail(when, err.message(), when.node.Scalar() == text ? err.offset() : 0);
  }
  allow_reactions_ = false;
  if (probe.is_constant()) {
    report_.Fail(when,
                 "an event's 'when' must depend on t or the state (e.g. 'ball_z' or "
                 "'t - 2 s')");
  }
  e.when = probe;
  if (at.Has("crosses")) e.crosses = Value(at.Child("crosses"), probe.dimension(), "the level");
  if (at.Has("direction")) {
    const std::string d = report_.Text(at.Child("direction"), "rising, falling or both");
    if (d == "rising") {
      e.direction = EventDirection::kRising;
    } else if (d == "falling") {
      e.direction = EventDirection::kFalling;
    } else if (d == "both") {
      e.direction = EventDirection::kEither;
    } else {
      report_.Fail(at.Child("direction"),
                   fmt::format("direction must be rising, falling or both, got '{}'", d));
    }
  }
  ReadEventAction(at, e);
  return e;
}

void SceneReader::ReadSimulation(const At& at, SceneSimulation& sim) {
  report_.CheckMap(
      at,
      {"until", "integrator", "tolerance", "absolute_tolerance", "step", "output_interval",
       "max_steps", "max_rows", "timeout", "min_step", "ball_collisions"},
      "the simulation settings");
  sim.present = true;
  if (at.node.IsMap()) {
    for (const auto& kv : at.node) {
      const std::string key(kv.first.Scalar());
      sim.keys[key] = KeySpotAt(at, key);
    }
  }
  // A whole number >= 1 (a count of steps or rows), read as any value (expressions allowed).
  auto count = [&](const char* key, std::string_view what) {
    const At c = at.Child(key);
    const double v = Value(c, kDimensionless, what);
    if (!(v >= 1) || v != std::floor(v) || v > 9e18) {
      report_.Fail(c, fmt::format("{} must be a whole number >= 1, got {:.6g}", what, v));
    }
    return static_cast<std::int64_t>(v);
  };
  if (at.Has("max_steps")) sim.max_steps = count("max_steps", "the most integration steps");
  if (at.Has("max_rows")) sim.max_rows = count("max_rows", "the most output rows");
  if (at.Has("timeout")) {
    sim.timeout = Value(at.Child("timeout"), kTime, "the wall-time limit");
    if (!(sim.timeout >= 0)) {
      report_.Fail(
          at.Child("timeout"),
          fmt::format("the wall-time limit must be >= 0 s (0: none), got {:.6g} s", sim.timeout));
    }
  }
  if (at.Has("min_step")) sim.min_step = PositiveValue(at.Child("min_step"), kTime, "min_step");
  if (at.Has("until")) sim.until = PositiveValue(at.Child("until"), kTime, "the end time");
  if (at.Has("integrator")) {
    const std::string name =
        report_.Text(at.Child("integrator"),
                     "adaptive, rk4, energy_momentum, splitting, events, stepping or auto");
    if (name == "adaptive") {
      sim.integrator = IntegratorKind::kDormandPrince5;
    } else if (name == "auto") {
      // Event-driven while regime changes come slowly, time stepped while they chatter.
      sim.integrator = IntegratorKind::kDormandPrince5;
      sim.auto_engine = true;
    } else if (name == "events") {
      // Balls on a table between events in closed form; pressing groups on the adaptive one.
      sim.integrator = IntegratorKind::kDormandPrince5;
      sim.event_driven = true;
    } else if (name == "stepping") {
      // Moreau–Jean time stepping through the contacts' regime changes.
      sim.integrator = IntegratorKind::kDormandPrince5;
      sim.time_stepping = true;
    } else if (name == "rk4") {
      sim.integrator = IntegratorKind::kRk4;
    } else if (name == "energy_momentum") {
      sim.integrator = IntegratorKind::kEnergyMomentum;
    } else if (name == "splitting") {
      sim.integrator = IntegratorKind::kSplitting;
    } else {
      report_.Fail(at.Child("integrator"),
                   fmt::format("unknown integrator '{}'{}; integrators: adaptive (default), rk4, "
                               "energy_momentum, splitting, events, stepping, auto",
                               name,
                               DidYouMean(name, {"adaptive", "rk4", "energy_momentum", "splitting",
                                                 "events", "stepping", "auto"})));
    }
  }
  const bool fixed = sim.integrator != IntegratorKind::kDormandPrince5 || sim.time_stepping;
  if (at.Has("tolerance")) {
    if (fixed) {
      report_.Fail(at.Child("tolerance"),
                   "'tolerance' is for the adaptive integrator; a fixed-step integrator's "
                   "accuracy is set by 'step'");
    }
    sim.rtol = PositiveValue(at.Child("tolerance"), kDimensionless, "the tolerance");
    if (!(sim.rtol >= kMinTolerance && sim.rtol <= kMaxTolerance)) {
      report_.Fail(
          at.Child("tolerance"),
          fmt::format("the tolerance {:.3g} is out of range: the accepted range is {:g} "
                      "to {:g} (below {:g} double precision cannot deliver it; above "
                      "{:g} the answer has no digits worth reporting)",
                      sim.rtol, kMinTolerance, kMaxTolerance, kMinTolerance, kMaxTolerance));
    }
    sim.atol = 1e-2 * sim.rtol;
  }
  if (at.Has("absolute_tolerance")) {
    sim.atol = PositiveValue(at.Child("absolute_tolerance"), kDimensionless,
                             "the absolute tolerance (in SI units of each state component)");
  }
  if (at.Has("step")) {
    if (sim.event_driven) {
      report_.Fail(at.Child("step"),
                   "'step' is for the fixed-step integrators; 'events' takes no steps (the balls "
                   "move in closed form between events)");
    }
    if (!fixed && !sim.auto_engine) {
      report_.Fail(at.Child("step"),
                   "'step' is for the fixed-step integrators (rk4, energy_momentum, splitting) "
                   "and time stepping (stepping, auto); the adaptive integrator chooses its own "
                   "steps from 'tolerance'");
    }
    sim.step = PositiveValue(at.Child("step"), kTime, "the step");
  } else if (fixed) {
    report_.Fail(at.Child("integrator"),
                 "a fixed-step integrator or time stepping needs 'step' (e.g. 'step: 1 ms')");
  }
  if (at.Has("output_interval")) {
    sim.output_interval = PositiveValue(at.Child("output_interval"), kTime, "the output interval");
  }
}

// `ball_collisions`: the coefficients of every pair of balls the scene does not list, read as
// a contact's (numbers, or a material pair). The event-driven path and time stepping let every
// pair collide; the adaptive engine does not, so auto time steps such a run throughout.
void SceneReader::ReadBallCollisions(const At& at, Scene& scene) {
  SceneSimulation& sim = scene.dynamics.simulation;
  if (!sim.event_driven && !sim.time_stepping && !sim.auto_engine) {
    report_.Fail(at,
                 "'ball_collisions' lets every pair of balls collide, which only 'integrator: "
                 "events', 'stepping' and 'auto' do (auto time steps such a run throughout), not "
                 "the adaptive engine or a fixed-step integrator; for another integrator list "
                 "each pair as a contact with 'with'");
  }
  report_.CheckMap(at, {"materials", "mu_s", "mu_k", "restitution", "restitution_law"},
                   "the collisions between balls");
  SceneContact c;
  if (at.Has("materials")) {
    ReadContactMaterials(at.Child("materials"), scene.dynamics.contacts.material_pairs, c);
  }
  ReadContactCoefficients(at, c.mu_s, c.mu_k, c.mu_r, c.restitution, c.restitution_law,
                          at.Has("materials"));
  if (c.mu_r != 0.0) {
    report_.Fail(at.Child("materials"),
                 fmt::format("the material pair {} has rolling resistance mu_r = {:.6g}, which "
                             "balls rolling on each other do not have here; use a pair without "
                             "mu_r",
                             c.materials, c.mu_r));
  }
  sim.collide_all_pairs = true;
  sim.ball_collisions = {c.restitution, c.mu_s, c.mu_k, c.restitution_law};
}

void SceneReader::ReadOutput(const At& at, Scene& scene) {
  report_.CheckMap(at, {"columns"}, "the output settings");
  const At cols = report_.Require(at, "columns", "the output settings");
  report_.CheckSequence(cols, "a list of columns");
  const ColumnIndex index(scene);
  std::vector<std::string> columns;
  std::unordered_set<std::string> seen;
  for (size_t i = 0; i < cols.node.size(); ++i) {
    const At c = cols.Item(i);
    const std::string name = report_.Text(c, "a column or a group of columns");
    const std::vector<std::string> expanded = index.Expand(name);
    if (expanded.empty()) report_.Fail(c, index.Unknown(name));
    for (const auto& e : expanded) {
      if (seen.insert(e).second) columns.push_back(e);
    }
  }
  if (columns.empty() || columns.front() != "t") columns.insert(columns.begin(), "t");
  scene.dynamics.columns = columns;
}

void SceneReader::ReadDynamics(const At& root, Scene& scene) {
  SceneDynamics& d = scene.dynamics;
  DeclareStateVariables(scene);
  if (root.Has("gravity")) ReadGravity(root.Child("gravity"), d);
  ReadInitialStates(root, scene);
  if (root.Has("project_initial")) {
    const At at = root.Child("project_initial");
    if (!at.node.IsScalar() || !DecodeBool(at.node, d.project_initial)) {
      report_.Fail(at, fmt::format("expected true or false, got {}", KindOf(at.node)));
    }
  }

  ReadForces(root, scene);

  // The default engine first: the simulation block's checks ('step', 'ball_collisions') depend
  // on it.
  DefaultIntegrator(root, scene);
  if (root.Has("simulation")) {
    d.simulation.where = KeySpotAt(root, "simulation");
    ReadSimulation(root.Child("simulation"), d.simulation);
    if (root.Child("simulation").Has("ball_collisions")) {
      ReadBallCollisions(root.Child("simulation").Child("ball_collisions"), scene);
    }
  }

  if (root.Has("events")) {
    const At events = root.Child("events");
    report_.CheckSequence(events, "a list of events");
    for (size_t i = 0; i < events.node.size(); ++i)
      d.events.push_back(ReadEvent(events.Item(i), i, scene));
    if (!d.events.empty() && d.simulation.integrator != IntegratorKind::kDormandPrince5) {
      report_.Fail(root.Child("simulation").Child("integrator"),
                   "events are located only by the adaptive integrator (on its dense output); "
                   "use 'integrator: adaptive' or remove the events");
    }
  }

  if (root.Has("impulses")) {
    const At list = root.Child("impulses");
    report_.CheckSequence(list, "a list of impulses");
    for (size_t i = 0; i < list.node.size(); ++i)
      d.impulses.push_back(ReadImpulse(list.Item(i), scene));
  }

  if (root.Has("impacts")) {
    const At list = root.Child("impacts");
    report_.CheckSequence(list, "a list of impacts");
    for (size_t i = 0; i < list.node.size(); ++i)
      d.impacts.push_back(ReadImpact(list.Item(i), scene));
  }

  if (d.simulation.time_stepping) {
    // What time stepping has no place for (docs/scene-format.md, `simulation`).
    for (const char* key : {"events", "impulses", "impacts"}) {
      if (root.Has(key)) {
        report_.Fail(root.Child(key),
                     fmt::format("'integrator: stepping' takes no '{}' yet; use 'integrator: "
                                 "adaptive'",
                                 key));
      }
    }
    if (scene.planar) {
      report_.Fail(root.Child("simulation").Child("integrator"),
                   "'integrator: stepping' runs in three dimensions; remove 'planar: true'");
    }
  }
  if (d.simulation.event_driven) {
    // What the event-driven path has no place for (docs/scene-format.md, `simulation`).
    const auto refuse = [&](const char* key, const char* why) {
      if (root.Has(key)) report_.Fail(root.Child(key), why);
    };
    refuse("events",
           "'integrator: events' locates only the balls' own events (collisions, slips that stop, "
           "rolling that stops); a scene event needs 'integrator: adaptive'");
    refuse("impulses",
           "'integrator: events' applies no impulses during the run; give the ball its velocity "
           "in 'initial', or use 'integrator: adaptive'");
    refuse("impacts",
           "'integrator: events' applies no embedding impacts; use 'integrator: adaptive'");
    if (scene.planar) {
      report_.Fail(root.Child("simulation").Child("integrator"),
                   "'integrator: events' runs balls on a table in three dimensions; remove "
                   "'planar: true'");
    }
  }

  if (root.Has("output")) {
    ReadOutput(root.Child("output"), scene);
  } else {
    d.columns = DefaultColumns(scene);
  }
}

// The names expressions may use: t, every body's state variables, then the constraints'
// reactions and the contact points' variables (StateVariableLayout's slots).
void SceneReader::DeclareStateVariables(const Scene& scene) {
  // The owners of the names, not the names: a scene of 100 000 bodies has 1.8 million of them,
  // and a name is resolved from its parts (StateSlot). A name that is not an identifier cannot
  // appear in an expression.
  const SceneDynamics& d = scene.dynamics;
  state_planar_ = scene.planar;
  state_bodies_.clear();
  state_constraints_.clear();
  state_points_.clear();
  for (size_t b = 0; b < scene.bodies.size(); ++b) {
    if (IsIdentifier(scene.bodies[b].name)) state_bodies_.emplace(scene.bodies[b].name, b);
  }
  // Reactions of the constraints, after the bodies' blocks: "<name>_Fx" ... "<name>_Mz" (W).
  reaction_slot_begin_ = StateVariableLayout::Slot(static_cast<int>(scene.bodies.size()), 0);
  const std::vector<std::string> constraint_names = d.constraints.names();
  for (size_t i = 0; i < constraint_names.size(); ++i) {
    if (IsIdentifier(constraint_names[i])) state_constraints_.emplace(constraint_names[i], i);
  }
  // Contact points after the reactions: "<point>_mode", "<point>_N", ... (the columns' names).
  contact_slot_begin_ = reaction_slot_begin_ + StateVariableLayout::kPerConstraint *
                                                   static_cast<int>(constraint_names.size());
  const std::vector<std::string> point_labels = d.contacts.point_labels();
  for (size_t p = 0; p < point_labels.size(); ++p) {
    if (IsIdentifier(point_labels[p])) state_points_.emplace(point_labels[p], p);
  }
}

namespace {

/// Index of `suffix` in `suffixes`, or -1.
int SuffixIndex(std::span<const char* const> suffixes, std::string_view suffix) {
  for (size_t k = 0; k < suffixes.size(); ++k) {
    if (suffix == suffixes[k]) return static_cast<int>(k);
  }
  return -1;
}

constexpr std::array<const char*, StateVariableLayout::kPerConstraint> kReactionSuffixes = {
    "Fx", "Fy", "Fz", "Mx", "My", "Mz"};

}  // namespace

int SceneReader::StateSlot(std::string_view name) const {
  if (name == "t") return 0;
  // Every suffix is one word: the owner is what comes before the last '_'.
  const size_t cut = name.rfind('_');
  if (cut == std::string_view::npos) return -1;
  const std::string_view owner = name.substr(0, cut), suffix = name.substr(cut + 1);
  if (const auto b = state_bodies_.find(owner); b != state_bodies_.end()) {
    const int body = static_cast<int>(b->second);
    if (state_planar_) {
      // One name per quantity, those of the `planar` output columns: θ, signed ω and α about z.
      for (const auto& [s, j] : StateVariableLayout::kPlanarNames) {
        if (suffix == s) return StateVariableLayout::Slot(body, j);
      }
    } else if (const int j = SuffixIndex(
                   std::span(StateVariableLayout::kSuffixes).first(StateVariableLayout::kTheta),
                   suffix);
               j >= 0) {
      return StateVariableLayout::Slot(body, j);
    }
  }
  if (const auto c = state_constraints_.find(owner); c != state_constraints_.end()) {
    if (const int k = SuffixIndex(kReactionSuffixes, suffix); k >= 0) {
      return reaction_slot_begin_ +
             StateVariableLayout::kPerConstraint * static_cast<int>(c->second) + k;
    }
  }
  if (const auto p = state_points_.find(owner); p != state_points_.end()) {
    const auto& suffixes = StateVariableLayout::kContactSuffixes;
    if (const int k = SuffixIndex(suffixes, suffix); k >= 0) {
      return contact_slot_begin_ +
             StateVariableLayout::kPerContactPoint * static_cast<int>(p->second) + k;
    }
  }
  return -1;
}

std::vector<std::string> SceneReader::StateVariableNames() const {
  // In slot order: t, each body's block, the reactions, the contact points.
  const auto by_index = [](const NameIndex& names) {
    std::vector<const std::string*> v(names.size());
    size_t k = 0;
    for (const auto& [name, i] : names) v[k++] = &name;
    std::sort(v.begin(), v.end(), [&names](const std::string* a, const std::string* b) {
      return names.find(*a)->second < names.find(*b)->second;
    });
    return v;
  };
  std::vector<std::string> out{"t"};
  for (const std::string* body : by_index(state_bodies_)) {
    if (state_planar_) {
      for (const auto& [s, j] : StateVariableLayout::kPlanarNames) out.push_back(*body + "_" + s);
    } else {
      for (int j = 0; j < StateVariableLayout::kTheta; ++j) {
        out.push_back(*body + "_" + StateVariableLayout::kSuffixes[static_cast<size_t>(j)]);
      }
    }
  }
  for (const std::string* c : by_index(state_constraints_)) {
    for (const char* s : kReactionSuffixes) out.push_back(*c + "_" + s);
  }
  for (const std::string* p : by_index(state_points_)) {
    for (const char* s : StateVariableLayout::kContactSuffixes) out.push_back(*p + "_" + s);
  }
  return out;
}

void SceneReader::ReadGravity(const At& g, SceneDynamics& d) {
  d.has_gravity = true;
  // "Down" is -z, or -y in a planar scene (its plane is x-y).
  const Vec3 down = planar_ ? Vec3(0, -1, 0) : Vec3(0, 0, -1);
  if (g.node.IsScalar() && g.node.Scalar() == "standard") {
    d.g_W = kStandardGravity * down;
  } else if (g.node.IsScalar()) {
    // A magnitude g > 0 along "down"; the sign is the direction's, so a negative value
    // (gravity pointing up) must be written as a vector.
    d.g_W = PositiveValue(g, kAcceleration,
                          "the magnitude of the gravitational acceleration (a vector such as "
                          "[0, 0, 9.81 m/s^2] points it anywhere)") *
            down;
  } else if (g.node.IsSequence()) {
    d.g_W = WorldVector(g, kAcceleration, "the gravitational acceleration");
  } else {
    report_.Fail(g, fmt::format("expected 'standard' (9.80665 m/s^2 along -z), a magnitude such "
                                "as 9.81 m/s^2 (along -z, -y in a planar scene) or a vector "
                                "such as [0, 0, -9.81 m/s^2], got {}",
                                KindOf(g.node)));
  }
}

// Every body's `initial` (its position and where it is written, for messages).
void SceneReader::ReadInitialStates(const At& root, Scene& scene) {
  SceneDynamics& d = scene.dynamics;
  const At bodies = root.Child("bodies");
  d.initial.assign(scene.bodies.size(), SceneInitialState{});
  for (size_t b = 0; b < scene.bodies.size(); ++b) {
    d.initial[b].p_BoP_B = scene.bodies[b].mass_properties.p_BoBcm_B();
    const At body_at = bodies.Item(b);
    const bool given = body_at.Has("initial");
    const At spot_at = given ? body_at.Child("initial") : body_at;
    const YamlMark mark = spot_at.node.Mark();
    d.initial[b].where = {mark.line >= 0 ? mark.line + 1 : 0,
                          mark.column >= 0 ? mark.column + 1 : 0, spot_at.path};
    if (given) ReadInitial(spot_at, scene.bodies[b], d.initial[b]);
  }
}

void SceneReader::ReadForces(const At& root, Scene& scene) {
  SceneDynamics& d = scene.dynamics;
  const std::vector<std::string> constraint_names = d.constraints.names();
  if (root.Has("forces")) {
    const At forces = root.Child("forces");
    report_.CheckSequence(forces, "a list of force elements");
    for (size_t i = 0; i < forces.node.size(); ++i) {
      SceneForce f = ReadForce(forces.Item(i), scene, i);
      const bool clash = (d.has_gravity && f.name == "gravity") ||
                         std::any_of(d.forces.begin(), d.forces.end(),
                                     [&](const SceneForce& o) { return o.name == f.name; }) ||
                         std::any_of(constraint_names.begin(), constraint_names.end(),
                                     [&](const std::string& o) { return o == f.name; });
      if (clash) {
        report_.Fail(
            forces.Item(i).Has("name") ? forces.Item(i).Child("name") : forces.Item(i),
            fmt::format("two force elements are named '{}'; names must be unique{}", f.name,
                        f.name == "gravity" ? " ('gravity' is the root key's)" : ""));
      }
      d.forces.push_back(std::move(f));
    }
  }
}

SceneImpulse SceneReader::ReadImpulse(const At& at, const Scene& scene) {
  report_.CheckMap(at, {"time", "body", "point", "value", "frame"}, "an impulse");
  SceneImpulse imp;
  imp.t = Value(report_.Require(at, "time", "an impulse"), kTime, "the time");
  if (imp.t < 0) report_.Fail(at.Child("time"), "the time must be >= 0");
  imp.body = BodyIndexAt(report_.Require(at, "body", "an impulse"), scene);
  const SceneBody& body = scene.bodies[static_cast<size_t>(imp.body)];
  imp.p_BoP_B =
      at.Has("point") ? BodyPointAt(at.Child("point"), body) : body.mass_properties.p_BoBcm_B();
  imp.J = WorldVector(report_.Require(at, "value", "an impulse"), kImpulse, "an impulse");
  if (at.Has("frame")) imp.frame = FrameAt(at.Child("frame"));
  return imp;
}

SceneImpact SceneReader::ReadImpact(const At& at, const Scene& scene) {
  report_.CheckMap(at, {"time", "target", "projectile", "exit_fraction"}, "an impact");
  SceneImpact imp;
  imp.t = Value(report_.Require(at, "time", "an impact"), kTime, "the time");
  if (imp.t < 0) report_.Fail(at.Child("time"), "the time must be >= 0");
  imp.target = BodyIndexAt(report_.Require(at, "target", "an impact"), scene);
  imp.projectile = BodyIndexAt(report_.Require(at, "projectile", "an impact"), scene);
  if (imp.target == imp.projectile) {
    report_.Fail(at.Child("projectile"), "the projectile and the target are the same body");
  }
  if (at.Has("exit_fraction")) {
    imp.exit_fraction = Value(at.Child("exit_fraction"), kDimensionless, "the exit fraction");
    if (!(imp.exit_fraction >= 0 && imp.exit_fraction <= 1)) {
      report_.Fail(at.Child("exit_fraction"),
                   fmt::format("the exit fraction must be in [0, 1] (0: the projectile "
                               "embeds; 1: it passes through unslowed), got {:.6g}",
                               imp.exit_fraction));
    }
  }
  return imp;
}

}  // namespace scene_internal
}  // namespace chasles
