// A scene's dynamics as a StudyDefinition: the Model builder (bodies, the scene's force
// elements with their expressions, joints, rolling contacts, drivers, gears and contacts, all
// placed through the body map), the events, the initial state, the options and the limits
// (see include/chasles/scene/study.h). The run itself is the library's RunStudy
// (include/chasles/analysis/study.h).

#include "chasles/scene/study.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <span>

#include <fmt/format.h>

#include "chasles/analysis/ledger.h"
#include "chasles/analysis/momentum.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/error.h"
#include "chasles/integrate/ball_pairs.h"
#include "chasles/integrate/run_path.h"
#include "chasles/model/bearing.h"
#include "chasles/model/constraints.h"
#include "chasles/model/data.h"
#include "chasles/model/forces.h"
#include "chasles/model/string_constraint.h"
#include "chasles/model/surface_rolling.h"
#include "chasles/scene/column_units.h"
#include "chasles/scene/scene_error.h"
#include "internal/study_columns.h"

namespace chasles {

namespace {

using scene_internal::ColumnInfo;

/// Euler ZYX angles (yaw, pitch, roll) of R = Rz(yaw) Ry(pitch) Rx(roll) [rad].
Vec3 CalcYawPitchRoll(const Mat3& R) {
  const double pitch = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  return {std::atan2(R(1, 0), R(0, 0)), pitch, std::atan2(R(2, 1), R(2, 2))};
}

/// The scene's body map and how many of the Model's constraints are the scene's own (a planar
/// Model adds its plane constraints after them; those have no state variables).
struct SceneMap {
  BodyMap map;
  int num_scene_constraints = 0;
  /// Planar scenes: each body's initial θ [rad] (the `theta` variable's branch); empty in 3-D.
  std::vector<double> initial_theta;
  /// True for the events' map: only an event may read α (a force that did would call the
  /// acceleration solve it is part of).
  bool events = false;
};

/// θ of a planar body from its quaternion q = (cos θ/2, 0, 0, sin θ/2) (a rotation about z):
/// q covers θ twice over 4π and the integrator carries it continuously, so the branch of
/// 2 atan2(q_z, q_w) nearest the initial θ is θ itself while |θ - θ0| < 2π (one turn either
/// way; the output column, which tracks the motion, continues over any number of turns).
double PlanarTheta(const Quat& q_WB, double theta0) {
  const double half = std::atan2(q_WB.z(), q_WB.w());
  return theta0 + 2.0 * std::remainder(half - 0.5 * theta0, 2.0 * std::numbers::pi);
}

std::vector<double> PlanarInitialTheta(const Scene& scene) {
  std::vector<double> theta;
  if (scene.planar) {
    for (const SceneInitialState& in : scene.dynamics.initial) theta.push_back(in.theta);
  }
  return theta;
}

/// The values of one evaluation's state variables (StateVariableLayout, at least one slot: t)
/// on the caller's stack, on the heap only past kInline slots: forces and event functions run
/// at every evaluation of every step, and keep nothing mutable of their own.
class VariableBuffer {
 public:
  explicit VariableBuffer(int count) : size_(static_cast<size_t>(std::max(count, 1))) {
    if (size_ > kInline) heap_.resize(size_);
  }
  std::span<double> span() {
    return size_ > kInline ? std::span<double>(heap_) : std::span<double>(inline_.data(), size_);
  }

 private:
  static constexpr size_t kInline = 64;
  std::array<double, kInline> inline_;
  std::vector<double> heap_;
  size_t size_;
};

/// Body `b`'s block of state variables (StateVariableLayout), as many as `block` holds: the
/// angles (tilt, yaw, pitch, roll, θ) only when a slot that holds one is read.
void FillBodyBlock(const Model& model, const State& state, const SceneMap& scene_map, int b,
                   double alpha_z, std::span<double> block) {
  const MappedBodyMotion m = CalcMappedBodyMotion(model, state, scene_map.map, b);
  const int used = static_cast<int>(block.size());
  const Vec3 w_B = m.R_WB.transpose() * m.w_WB_W;
  const Vec3 ypr = used > StateVariableLayout::kYaw ? CalcYawPitchRoll(m.R_WB) : Vec3::Zero();
  const double tilt =
      used > StateVariableLayout::kTilt ? std::acos(std::clamp(m.R_WB(2, 2), -1.0, 1.0)) : 0.0;
  double theta = 0.0;
  if (!scene_map.initial_theta.empty() && used > StateVariableLayout::kTheta) {
    const BodyPlacement& pl = scene_map.map.place[static_cast<size_t>(b)];
    theta = PlanarTheta(state.bodies[static_cast<size_t>(pl.model_body)].q_WB * Quat(pl.R_MB),
                        scene_map.initial_theta[static_cast<size_t>(b)]);
  }
  const double values[StateVariableLayout::kPerBody] = {
      m.p_WBcm.x(), m.p_WBcm.y(), m.p_WBcm.z(), m.v_WBcm_W.x(), m.v_WBcm_W.y(),    m.v_WBcm_W.z(),
      m.w_WB_W.x(), m.w_WB_W.y(), m.w_WB_W.z(), w_B.x(),        w_B.y(),           w_B.z(),
      tilt,         ypr.x(),      ypr.y(),      ypr.z(),        m.v_WBcm_W.norm(), m.w_WB_W.norm(),
      theta,        alpha_z};
  std::copy_n(values, block.size(), block.begin());
}

/// Fills the state variables (StateVariableLayout), as many as `v` holds (v[0] = t).
void FillVariables(const Model& model, const State& state, const SceneMap& scene_map,
                   std::span<double> v) {
  const BodyMap& map = scene_map.map;
  const int count = static_cast<int>(v.size());
  std::fill(v.begin(), v.end(), 0.0);
  v[0] = state.t;
  const int per = StateVariableLayout::kPerBody;
  const int num_scene_bodies = static_cast<int>(map.place.size());
  // α (planar events only: a force cannot read it) needs the accelerations of this state.
  const bool planar = !scene_map.initial_theta.empty();
  bool alpha = false;
  for (int b = 0; planar && scene_map.events && b < num_scene_bodies; ++b) {
    alpha = alpha || StateVariableLayout::Slot(b, StateVariableLayout::kAlpha) < count;
  }
  const int first = StateVariableLayout::Slot(num_scene_bodies, 0);
  const int num_constraints = std::min(scene_map.num_scene_constraints, model.num_constraints());
  const int first_contact =
      first + StateVariableLayout::kPerConstraint * scene_map.num_scene_constraints;
  const bool reactions = count > first && num_constraints > 0;
  const bool contacts = count > first_contact && model.num_contact_points() > 0;
  // The workspace only when a value needs the accelerations: event functions run at every
  // evaluation of a step and most read the state alone.
  std::optional<Data> data;
  if (alpha || reactions || contacts) {
    data.emplace(MakeData(model));
    CalcAccelerations(model, state, *data);
  }
  for (int b = 0; b < num_scene_bodies && b * per + 1 < count; ++b) {
    const int used = std::min(per, count - StateVariableLayout::Slot(b, 0));
    const auto mb = static_cast<size_t>(map.place[static_cast<size_t>(b)].model_body);
    const double alpha_z = alpha ? (data->R_WB[mb] * data->wdot_WB_B[mb]).z() : 0.0;
    FillBodyBlock(
        model, state, scene_map, b, alpha_z,
        v.subspan(static_cast<size_t>(StateVariableLayout::Slot(b, 0)), static_cast<size_t>(used)));
  }
  // Reactions (events only): six slots per scene constraint after the scene bodies' blocks,
  // then the contact points' values (StateVariableLayout).
  if (!reactions && !contacts) return;
  for (int i = 0; i < num_constraints; ++i) {
    const ConstraintOutput& o = data->constraints[static_cast<size_t>(i)];
    for (int k = 0; k < 6; ++k) {
      const int slot = first + 6 * i + k;
      if (slot < count) v[static_cast<size_t>(slot)] = k < 3 ? o.F_Jc_W[k] : o.M_Jc_W[k - 3];
    }
  }
  if (!contacts) return;
  // Contact points in the modes `state` carries (the values of the output columns).
  for (int p = 0; p < model.num_contact_points(); ++p) {
    const ContactPointOutput& o = data->contact_points[static_cast<size_t>(p)];
    const double values[StateVariableLayout::kPerContactPoint] = {
        static_cast<double>(o.mode), o.normal_force, o.friction_force_W.norm(),
        o.slip_velocity_W.norm(), o.gap};
    for (int k = 0; k < StateVariableLayout::kPerContactPoint; ++k) {
      const int slot = first_contact + StateVariableLayout::kPerContactPoint * p + k;
      if (slot < count) v[static_cast<size_t>(slot)] = values[k];
    }
  }
}

/// A VectorFunction evaluating a scene vector expression; `R_MB` turns a body-frame value into
/// the model body's frame. Its variables are filled on the caller's stack at each call: the
/// function keeps nothing mutable, so one Model runs in several threads at once.
VectorFunction MakeVectorFunction(std::shared_ptr<const SceneMap> map,
                                  const SceneVectorExpression& value, const Mat3& R_MB) {
  const int count = value.variable_count();
  return [map, value, R_MB, count](const Model& model, const State& state) -> Vec3 {
    VariableBuffer variables(count);
    FillVariables(model, state, *map, variables.span());
    return R_MB * value.Evaluate(variables.span());
  };
}

ScalarFunction MakeScalarFunction(std::shared_ptr<const SceneMap> map, const Expression& value) {
  const int count = value.variable_count();
  return [map, value, count](const Model& model, const State& state) -> double {
    VariableBuffer variables(count);
    FillVariables(model, state, *map, variables.span());
    return value.Evaluate(variables.span());
  };
}

State InitialState(const Scene& scene, const Model& model);

/// Runs `add`, which adds the next element of `kind` (a force element or a constraint) to
/// `model`. An element's own checks (its constructor's, the scene's while placing it) know it
/// by its name only: their InputError is rethrown naming the element by its index to be.
template <class Add>
void AddElement(Model& model, ErrorElement::Kind kind, const Add& add) {
  const int next = kind == ErrorElement::Kind::kForceElement ? model.num_force_elements()
                                                             : model.num_constraints();
  try {
    add();
  } catch (const InputError& e) {
    RethrowForElement(e, {kind, next});
  }
}

/// Name of the constraint that holds scene body `b` of a planar scene in its plane (after the
/// scene's own constraints in Model order; reports of planar scenes leave these out).
std::string PlaneConstraintName(const Scene& scene, int b) {
  return fmt::format("{} (in plane)", scene.bodies[static_cast<size_t>(b)].name);
}

/// A scene string as the model's StringConstraint: each end's point (the body's centre of mass
/// by default; in a planar scene its projection on the plane of motion, z = 0, since a part's
/// offset along z plays no part there) in its body's frame, and its `length` (default: the free
/// length it has at the initial configuration), which it keeps. The model's second end must be
/// a body, so a string given from a body to the world is turned round: the world end first, the
/// pulleys in reverse order, every sense flipped (followed the other way, the string goes round
/// each circle the other way); the reports say so (StringTurnRoundWarnings).
void AddSceneString(const SceneString& st, bool planar, const BodyMap& map, const State& s0,
                    Model& model) {
  auto model_body = [&](int b) {
    return b == kWorld ? kWorld : map.place[static_cast<size_t>(b)].model_body;
  };
  SceneStringEnd from = st.from, to = st.to;
  std::vector<SceneStringPulley> over = st.over;
  if (to.body == kWorld) {
    std::swap(from, to);
    std::reverse(over.begin(), over.end());
    from.sense = -from.sense;
    to.sense = -to.sense;
    for (SceneStringPulley& p : over) p.sense = -p.sense;
  }
  // In W, for the plane check, with what each is in the file.
  std::vector<std::pair<Vec3, std::string>> points;
  const auto end = [&](const SceneStringEnd& e, const char* key) {
    const int b = model_body(e.body);
    Vec3 p_W = e.p_W;
    std::string what =
        fmt::format("the '{}' end's {}", key, e.radius > 0 ? "drum centre" : "point");
    if (!p_W.allFinite()) {
      p_W = s0.bodies[static_cast<size_t>(b)].p_WBcm;
      if (planar) p_W.z() = 0.0;
      what += " (no 'at': its body's centre of mass)";
    }
    points.emplace_back(p_W, what);
    const AttachmentFrame X = AttachmentFrameAtWorldPose(model, s0, b, p_W, Mat3::Identity());
    return StringEnd{b, X.p_BoJ_B, e.radius, e.sense};
  };
  const bool turned = st.to.body == kWorld;  // from and to were swapped above
  const StringEnd a = end(from, turned ? "to" : "from"), b = end(to, turned ? "from" : "to");
  std::vector<StringPulley> pulleys;
  for (size_t k = 0; k < over.size(); ++k) {
    const SceneStringPulley& p = over[k];
    // A pulley on a body: its centre in the body's frame (the world pose at the start).
    const int pb = model_body(p.body);
    const Vec3 c = AttachmentFrameAtWorldPose(model, s0, pb, p.center_W, Mat3::Identity()).p_BoJ_B;
    pulleys.push_back({c, p.radius, p.sense, pb});
    points.emplace_back(p.center_W,
                        fmt::format("the centre of pulley {}", turned ? over.size() - k : k + 1));
  }
  // With a pulley or a drum the path is planar (model/string_constraint.h): every point and
  // centre in one plane normal to the string's normal.
  if (a.radius > 0.0 || b.radius > 0.0 || !pulleys.empty()) {
    double scale = 1e-3;
    for (const auto& [p, what] : points) scale = std::max(scale, p.norm());
    const auto& [first, first_what] = points.front();
    for (const auto& [p, what] : points) {
      const double off = st.normal_W.dot(p - first);
      if (std::abs(off) > 1e-9 * scale) {
        // In a planar scene every point is in the plane z = 0 (world points are [x, y], an
        // end's default is projected), so only a 3-D scene gets here.
        throw InputError(fmt::format(
            "string '{}': its ends, drums and pulleys must lie in one plane normal to its "
            "normal [{:.6g}, {:.6g}, {:.6g}], but {} at [{:.6g}, {:.6g}, {:.6g}] is {:.6g} m off "
            "the plane through {}; give the points in one plane ('at' of an end, 'center' of a "
            "pulley), or set 'normal' to the normal of the plane the string runs in",
            st.name, st.normal_W.x(), st.normal_W.y(), st.normal_W.z(), what, p.x(), p.y(), p.z(),
            off, first_what));
      }
    }
  }
  const StringConstraint probe(st.name, a, pulleys, b, st.normal_W, 1.0);
  Data data = MakeData(model);
  CalcKinematics(model, s0, data);
  const double length =
      std::isfinite(st.length) ? st.length : probe.CalcPath(model, s0, data).length;
  auto string = std::make_shared<StringConstraint>(st.name, a, pulleys, b, st.normal_W, length);
  string->set_restitution(st.restitution);
  model.AddConstraint(string);
}

/// A rolling contact on a curved surface. The contact point lies on the line from the surface's
/// centre (or its axis) through the body's centre: with the body's centre there at the initial
/// configuration it is undefined, an input error rather than a NaN.
std::shared_ptr<SurfaceRolling> MakeSurfaceRolling(const SceneRolling& r, BodyIndex body,
                                                   const Model& model, const State& s0) {
  const BodyState& bs = s0.bodies[static_cast<size_t>(body)];
  const Vec3 c = bs.p_WBcm + bs.q_WB.normalized().toRotationMatrix() *
                                 model.body(body).PointFromCenterOfMass(r.p_BoC_B);
  Vec3 d = c - r.surface_center_W;
  if (r.surface_shape == SurfaceShape::kCylinder) {
    const Vec3 a = r.surface_axis_W.normalized();
    d -= a * a.dot(d);
  }
  const double reach = r.inside ? r.surface_radius - r.radius : r.surface_radius + r.radius;
  if (!(d.norm() > 1e-9 * reach)) {
    throw InputError(fmt::format(
        "rolling contact '{}': the body's centre is on the surface's {} at the start, where the "
        "contact point is undefined; place it {:.6g} m from it",
        r.name, r.surface_shape == SurfaceShape::kSphere ? "centre" : "axis", reach));
  }
  const SurfaceShape body_shape =
      r.shape == RollingShape::kSphere ? SurfaceShape::kSphere : SurfaceShape::kCylinder;
  return std::make_shared<SurfaceRolling>(r.name, body, body_shape, r.p_BoC_B, r.axis_B, r.radius,
                                          r.surface_shape, r.surface_center_W, r.surface_axis_W,
                                          r.surface_radius, r.inside);
}

/// Adds the scene's joints, rolling contacts, drivers and gear meshes to `model` (bodies already
/// added, one per scene body). A scene gives joint points and axes in W at the initial
/// configuration; each side's attachment frame is the one that coincides with that world pose
/// there.
void AddSceneConstraints(const Scene& scene, const BodyMap& map, Model& model) {
  const SceneConstraints& c = scene.dynamics.constraints;
  if (c.empty() && !scene.planar) return;
  if (model.num_bodies() != static_cast<int>(scene.bodies.size())) {
    throw InputError(
        scene.planar
            ? "an impact that embeds a projectile cannot be used in a planar scene (its bodies "
              "are held in the plane by constraints, which would change); use exit_fraction > 0"
            : "an impact that embeds a projectile cannot be combined with joints, rolling "
              "contacts or drivers (the constrained bodies would change); use exit_fraction > 0 "
              "or remove the constraints");
  }
  const State s0 = InitialState(scene, model);
  auto model_body = [&](int b) {
    return b == kWorld ? kWorld : map.place[static_cast<size_t>(b)].model_body;
  };
  auto frame = [&](int b, const Vec3& p_WJ, const Mat3& R_WJ) {
    return AttachmentFrameAtWorldPose(model, s0, model_body(b), p_WJ, R_WJ);
  };
  constexpr ErrorElement::Kind kConstraint = ErrorElement::Kind::kConstraint;
  for (const SceneJoint& j : c.joints) {
    Mat3 R_WJ = FrameWithZAxis(j.axis_W);
    if (j.kind == JointKind::kPrismaticInPlane || j.kind == JointKind::kPointOnLineInPlane) {
      // J's z is the plane's normal and x the sliding direction (the line).
      R_WJ << j.axis_W, Vec3::UnitZ().cross(j.axis_W), Vec3::UnitZ();
    }
    AddElement(model, kConstraint, [&] {
      model.AddConstraint(std::make_shared<Joint>(
          j.name, j.kind, model_body(j.parent), frame(j.parent, j.p_WJ, R_WJ), model_body(j.child),
          frame(j.child, j.p_WJ, R_WJ)));
    });
  }
  for (const SceneRolling& r : c.rolling) {
    AddElement(model, kConstraint, [&] {
      if (r.on_surface) {
        model.AddConstraint(MakeSurfaceRolling(r, model_body(r.body), model, s0));
        return;
      }
      // The plane is given in W at the initial configuration; on a body it is fixed in that
      // body's frame from there on.
      const AttachmentFrame X = frame(r.on, r.plane_point_W, FrameWithZAxis(r.plane_normal_W));
      model.AddConstraint(std::make_shared<RollingContact>(
          r.name, r.shape, model_body(r.on), X.p_BoJ_B, Vec3(X.R_BJ.col(2)), model_body(r.body),
          r.p_BoC_B, r.axis_B, r.radius));
    });
  }
  for (const SceneDriver& d : c.drivers) {
    const Mat3 R_WJ = FrameWithZAxis(d.axis_W);
    AddElement(model, kConstraint, [&] {
      model.AddConstraint(std::make_shared<PrescribedMotion>(
          d.name, d.kind, model_body(d.parent), frame(d.parent, d.p_WJ, R_WJ), model_body(d.child),
          frame(d.child, d.p_WJ, R_WJ), TimeFunction::Quadratic(d.f0, d.f1, d.f2)));
    });
  }
  for (const SceneGear& g : c.gears) {
    const auto circle = [&](int b, const ScenePitchCircle& pc) {
      const AttachmentFrame X = frame(b, pc.center_W, FrameWithZAxis(pc.axis_W));
      return PitchCircle{X.p_BoJ_B, Vec3(X.R_BJ.col(2)), pc.radius};
    };
    AddElement(model, kConstraint, [&] {
      model.AddConstraint(std::make_shared<GearMesh>(
          g.name, g.kind, model_body(g.parent), circle(g.parent, g.parent_circle),
          model_body(g.child), circle(g.child, g.child_circle), g.keep_contact));
    });
  }
  for (const SceneString& st : c.strings) {
    AddElement(model, kConstraint, [&] { AddSceneString(st, scene.planar, map, s0, model); });
  }
  if (scene.planar) {
    // Every body of a planar scene is held in its plane z = const by one kPlanar joint with
    // the world at its centre of mass (3 rows: v_z, w_x, w_y). The scene's joints contribute
    // only their in-plane rows (kRevoluteInPlane, ...), so no row repeats another and the
    // solve never meets a redundant set (docs/constraints.md, "Planar mechanisms").
    for (size_t b = 0; b < scene.bodies.size(); ++b) {
      const int mb = model_body(static_cast<int>(b));
      const Vec3 p_WBcm = s0.bodies[static_cast<size_t>(mb)].p_WBcm;
      AddElement(model, kConstraint, [&] {
        model.AddConstraint(std::make_shared<Joint>(
            PlaneConstraintName(scene, static_cast<int>(b)), JointKind::kPlanar, kWorld,
            AttachmentFrame{p_WBcm, Mat3::Identity()}, mb,
            frame(static_cast<int>(b), p_WBcm, Mat3::Identity())));
      });
    }
  }
}

/// The engine's shape for a scene contact shape.
ContactShape ModelContactShape(const SceneContact& c) {
  if (!c.with_plane) return ContactShape::kSphereSphere;
  switch (c.shape) {
    case SceneContactShape::kSphere:
      return ContactShape::kSphere;
    case SceneContactShape::kDisk:
      return ContactShape::kDiskRim;
    case SceneContactShape::kDiskFace:
      return ContactShape::kDiskFace;
    case SceneContactShape::kCylinder:
      return ContactShape::kCylinder;
    case SceneContactShape::kBox:
      return ContactShape::kBox;
    case SceneContactShape::kPoints:
      return ContactShape::kPointSet;
    case SceneContactShape::kCapsule:
      return ContactShape::kCapsule;
  }
  return ContactShape::kSphere;
}

/// Adds the scene's contacts to `model`, in scene order (so contact points follow
/// SceneContacts::point_labels()). Geometry is in each body's own frame.
void AddSceneContacts(const Scene& scene, const BodyMap& map, Model& model) {
  const SceneContacts& sc = scene.dynamics.contacts;
  if (sc.empty()) return;
  if (model.num_bodies() != static_cast<int>(scene.bodies.size())) {
    throw InputError(
        "an impact that embeds a projectile cannot be combined with contacts (the touching "
        "bodies would change); use exit_fraction > 0 or remove the contacts");
  }
  for (const SceneContact& c : sc.contacts) {
    ContactSpec spec;
    spec.name = c.name;
    spec.shape = ModelContactShape(c);
    spec.body = map.place[static_cast<size_t>(c.body)].model_body;
    spec.p_BoC_B = c.p_BoC_B;
    spec.axis_B = c.axis_B;
    spec.radius = c.radius;
    spec.length = c.length;
    spec.half_extents = c.size / 2;
    spec.points_B = c.points_B;
    spec.face_points = kDiskFacePoints;
    spec.point_labels = ContactPointLabels(c);
    if (!c.with_plane) {
      spec.other_body = map.place[static_cast<size_t>(c.other_body)].model_body;
      spec.p_OoC_O = c.p_OoD_O;
      spec.other_radius = c.other_radius;
    }
    spec.plane_point_W = c.plane_point_W;
    spec.plane_normal_W = c.plane_normal_W;
    spec.mu_s = c.mu_s;
    spec.mu_k = c.mu_k;
    spec.mu_r = c.mu_r;
    spec.restitution = c.restitution;
    spec.restitution_law = c.restitution_law;
    model.AddContact(spec);
  }
}

/// The Model of one segment: bodies (name, mass properties) and the scene's force elements
/// placed through `body_map` (the StudyDefinition's ModelBuilder).
Model BuildModel(const Scene& scene, const std::vector<NamedBody>& bodies,
                 const BodyMap& body_map) {
  Model model;
  for (const NamedBody& b : bodies) model.AddBody(b.name, b.mass_properties);
  const auto map = std::make_shared<const SceneMap>(
      SceneMap{body_map, static_cast<int>(scene.dynamics.constraints.names().size()),
               PlanarInitialTheta(scene)});
  const SceneDynamics& d = scene.dynamics;
  if (d.has_gravity) model.AddForceElement(std::make_shared<UniformGravity>("gravity", d.g_W));
  auto point = [&](int b, const Vec3& p_BoP_B) { return map->map.PointInModelBody(b, p_BoP_B); };
  for (const SceneForce& f : d.forces) {
    const BodyPlacement* pl = f.body >= 0 ? &map->map.place[static_cast<size_t>(f.body)] : nullptr;
    AddElement(model, ErrorElement::Kind::kForceElement, [&] {
      switch (f.type) {
        case SceneForce::Type::kForce: {
          const Vec3 p =
              f.point_frame == VectorFrame::kWorld ? f.p_BoP_B : point(f.body, f.p_BoP_B);
          const Mat3 R = f.frame == VectorFrame::kBody ? pl->R_MB : Mat3::Identity();
          VectorFunction value;
          if (f.value.is_constant()) {
            const Vec3 v = R * f.value.Evaluate(std::array{0.0});
            value = [v](const Model&, const State&) { return v; };
          } else {
            value = MakeVectorFunction(map, f.value, R);
          }
          model.AddForceElement(std::make_shared<AppliedForce>(f.name, pl->model_body, p,
                                                               f.point_frame, value, f.frame));
          break;
        }
        case SceneForce::Type::kCable:
          model.AddForceElement(std::make_shared<CableForce>(f.name, pl->model_body,
                                                             point(f.body, f.p_BoP_B), f.p_WQ,
                                                             MakeScalarFunction(map, f.scalar)));
          break;
        case SceneForce::Type::kStringPull:
          // The drum's axis turns from the scene body's frame into the model body's.
          model.AddForceElement(std::make_shared<StringPull>(
              f.name, pl->model_body, point(f.body, f.p_BoP_B), pl->R_MB * f.drum_axis_B,
              f.drum_radius, f.drum_sense, f.direction_W, MakeScalarFunction(map, f.scalar)));
          break;
        case SceneForce::Type::kJointTorque: {
          // The joint's axis is given in W at the initial configuration; the torque turns it
          // with the parent: a_P = R_WP(0)ᵀ a_W.
          const SceneJoint& j = d.constraints.joints[static_cast<size_t>(f.joint)];
          const int parent = j.parent == kWorld
                                 ? kWorld
                                 : map->map.place[static_cast<size_t>(j.parent)].model_body;
          Vec3 axis_P = j.axis_W;
          if (parent != kWorld) {
            const State s0 = InitialState(scene, model);
            axis_P = s0.bodies[static_cast<size_t>(parent)]
                         .q_WB.normalized()
                         .toRotationMatrix()
                         .transpose() *
                     j.axis_W;
          }
          model.AddForceElement(std::make_shared<JointTorque>(
              f.name, parent, pl->model_body, axis_P, MakeScalarFunction(map, f.scalar)));
          break;
        }
        case SceneForce::Type::kMoment:
          if (f.value.is_constant()) {
            const Vec3 v = f.value.Evaluate(std::array{0.0});
            model.AddForceElement(AppliedMoment::Constant(
                f.name, pl->model_body, f.frame == VectorFrame::kBody ? Vec3(pl->R_MB * v) : v,
                f.frame));
          } else {
            model.AddForceElement(std::make_shared<AppliedMoment>(
                f.name, pl->model_body,
                MakeVectorFunction(map, f.value,
                                   f.frame == VectorFrame::kBody ? pl->R_MB : Mat3::Identity()),
                f.frame));
          }
          break;
        case SceneForce::Type::kSpring: {
          const int mb = f.body_b == kWorld
                             ? kWorld
                             : map->map.place[static_cast<size_t>(f.body_b)].model_body;
          const Vec3 q = f.body_b == kWorld ? f.p_BoQ_B : point(f.body_b, f.p_BoQ_B);
          model.AddForceElement(
              std::make_shared<SpringDamper>(f.name, pl->model_body, point(f.body, f.p_BoP_B), mb,
                                             q, f.rest_length, f.stiffness, f.damping));
          break;
        }
        case SceneForce::Type::kDrag:
          model.AddForceElement(
              std::make_shared<LinearDrag>(f.name, pl->model_body, f.linear, f.angular));
          break;
        case SceneForce::Type::kCentralGravity:
          model.AddForceElement(std::make_shared<CentralGravity>(f.name, f.mu, f.centre_W));
          break;
        case SceneForce::Type::kBearing: {
          // The journal is the body's material point at `at` at the initial configuration.
          const State s0 = InitialState(scene, model);
          const BodyState& bs = s0.bodies[static_cast<size_t>(pl->model_body)];
          const Vec3 p_Bo = CalcBodyOriginPosition(model, s0, pl->model_body);
          const Vec3 p_BoP_B = bs.q_WB.normalized().conjugate() * (f.bearing_at_W - p_Bo);
          model.AddForceElement(std::make_shared<Bearing>(f.name, pl->model_body, p_BoP_B,
                                                          f.bearing_at_W, f.bearing_axis_W,
                                                          f.bearing_K, f.bearing_C));
          break;
        }
      }
    });
  }
  AddSceneConstraints(scene, body_map, model);
  AddSceneContacts(scene, body_map, model);
  return model;
}

/// The certificate's tolerances for a scene's run. Force-level checks are round-off (the
/// default); the state-level ones and the ledger carry the integration error, which the
/// adaptive integrator's relative tolerance bounds per step: the defaults hold down to
/// rtol = 1e-12 (every shipped example is at or below 1e-3 of them there) and grow in
/// proportion above it. Fixed-step runs keep the defaults: their error is not controlled, so
/// a step too coarse for the motion fails the ledger, as it should.
CertificateTolerances CertificateTolerancesFor(const Scene& scene) {
  CertificateTolerances t;
  const SceneSimulation& sim = scene.dynamics.simulation;
  if (sim.integrator == IntegratorKind::kDormandPrince5) {
    const double loosening = std::max(1.0, sim.rtol / 1e-12);
    t.state *= loosening;
    t.ledger *= loosening;
  }
  // Moreau–Jean: an approaching point is seen at the step's midpoint (time_stepping.h).
  if (sim.time_stepping) t.gap_time = 0.5 * sim.step;
  return t;
}

/// Whether a contact point's mode change `c` is the `change` a contact-mode event watches.
bool IsModeChange(SceneModeChange change, const ContactEvent& c) {
  const bool touching_before = c.from != ContactMode::kSeparated;
  const bool touching_after = c.to != ContactMode::kSeparated;
  // A bounce is a touch-down whose impact sends the point off again (separated to separated).
  const bool bounce = c.reason == ContactEventReason::kTouchDown;
  switch (change) {
    case SceneModeChange::kNone:
      return false;
    case SceneModeChange::kStartsSliding:
      return c.to == ContactMode::kSliding && c.from != ContactMode::kSliding;
    case SceneModeChange::kStopsSliding:
      return c.from == ContactMode::kSliding && c.to == ContactMode::kSticking;
    case SceneModeChange::kSeparates:
      return touching_before && !touching_after;
    case SceneModeChange::kTouches:
      return (!touching_before && touching_after) || bounce;
    case SceneModeChange::kAny:
      return c.from != c.to || bounce;
  }
  return false;
}

std::vector<EventSpec> BuildEvents(const Scene& scene, const BodyMap& body_map) {
  std::vector<EventSpec> events;
  const auto map = std::make_shared<const SceneMap>(
      SceneMap{body_map, static_cast<int>(scene.dynamics.constraints.names().size()),
               PlanarInitialTheta(scene), true});
  for (const SceneEvent& e : scene.dynamics.events) {
    if (e.change != SceneModeChange::kNone) {
      // Contact points are added to the Model in the scene's label order (AddSceneContacts).
      EventSpec spec;
      spec.name = e.name;
      spec.action = e.action;
      spec.on_mode_change = [points = e.points, change = e.change](const ContactEvent& c) {
        return std::find(points.begin(), points.end(), c.point) != points.end() &&
               IsModeChange(change, c);
      };
      events.push_back(std::move(spec));
      continue;
    }
    const Expression when = e.when;
    const double level = e.crosses;
    const int count = when.variable_count();
    events.push_back(EventSpec{e.name,
                               [map, when, level, count](const Model& model, const State& state) {
                                 VariableBuffer variables(count);
                                 FillVariables(model, state, *map, variables.span());
                                 return when.Evaluate(variables.span()) - level;
                               },
                               e.direction, e.action});
  }
  return events;
}

double EndTime(const Scene& scene, double until) {
  const double t = std::isfinite(until) ? until : scene.dynamics.simulation.until;
  if (!std::isfinite(t)) {
    throw InputError(
        "the scene gives no end time: add 'until' under 'simulation:' (e.g. 'until: 10 s') or "
        "pass --until");
  }
  if (!(t > 0)) throw InputError(fmt::format("the end time must be positive, got {:.6g} s", t));
  return t;
}

/// The limits on a run's work (docs/reliability-limits.md): the command line's, else the
/// scene's, else the defaults.
struct RunLimits {
  std::int64_t max_steps = kDefaultMaxSteps;
  std::int64_t max_rows = kDefaultMaxRows;
  /// Wall time [s]; 0: none.
  double timeout = 0.0;
  /// Smallest step [s].
  double min_step = 0.0;
};

RunLimits ResolveLimits(const Scene& scene, const StudyOptions& o, double span) {
  const SceneSimulation& sim = scene.dynamics.simulation;
  RunLimits l;
  l.max_steps = o.max_steps > 0 ? o.max_steps : sim.max_steps;
  l.max_rows = o.max_rows > 0 ? o.max_rows : sim.max_rows;
  l.timeout = std::isfinite(o.timeout) ? o.timeout : sim.timeout;
  l.min_step = std::isfinite(o.min_step)     ? o.min_step
               : std::isfinite(sim.min_step) ? sim.min_step
                                             : kDefaultMinStepFraction * span;
  return l;
}

/// A limit reached, or certain to be: a SceneError at `spot` (a key of `simulation`, the
/// block, or the entry to blame) saying what happened, then `alternative` (another way out,
/// ending in "or "), and how to change the limit: scene key `key`, command-line flag `flag`.
[[noreturn]] void ThrowLimit(const Scene& scene, const SceneSpot& spot, std::string_view key,
                             std::string_view flag, const std::string& what,
                             std::string_view alternative = "", std::string_view verb = "raise") {
  throw SceneError(scene.file, spot.line, spot.column, spot.key,
                   fmt::format("{}; {}{} the limit with {} or '{}:' under 'simulation:'", what,
                               alternative, verb, flag, key));
}

/// A limit the run reached (RunStudy's LimitError), at the `simulation` key that sets it.
[[noreturn]] void ThrowLimitReached(const Scene& scene, const LimitError& e) {
  const SceneSimulation& sim = scene.dynamics.simulation;
  switch (e.limit()) {
    case LimitError::Limit::kSteps:
      ThrowLimit(
          scene, sim.Spot("max_steps"), "max_steps", "--max-steps", e.what(),
          sim.event_driven ? "shorten the run, or " : "loosen 'tolerance', shorten the run, or ");
    case LimitError::Limit::kRows:
      ThrowLimit(scene, sim.Spot("max_rows"), "max_rows", "--max-rows", e.what(),
                 "choose a longer 'output_interval' or ");
    case LimitError::Limit::kTime:
      ThrowLimit(scene, sim.Spot("timeout"), "timeout", "--timeout", e.what());
    case LimitError::Limit::kMinStep:
      break;
  }
  // The adaptive step fell below the smallest step.
  ThrowLimit(scene, sim.Spot("min_step"), "min_step", "--min-step", e.what(),
             "check the forces and masses for a singularity, or ", "lower");
}

/// The accepted range of a body's mass [kg] and of the trace of its inertia [kg·m²]: with
/// forces and lengths of any physical size the accelerations F/m and I⁻¹M stay far inside
/// double precision (1e-300 kg would turn 1 N into 1e300 m/s²).
constexpr double kMinBodyScale = 1e-100, kMaxBodyScale = 1e100;

/// Inputs no run can integrate, refused before it starts at their entries: a body's mass or
/// inertia outside [1e-100, 1e100] SI, a driver whose motion over the span [0, t_end] exceeds
/// kMotionScale (f = f0 + f1 t + ½ f2 t², f' = f1 + f2 t).
void CheckPhysicalInputs(const Scene& scene, double t_end) {
  for (const SceneBody& b : scene.bodies) {
    // A part 1e200 m out puts the body's centre of mass there: refused at the part's position,
    // not later as a motion that "diverged".
    for (const ScenePart& part : b.parts) {
      const double d = part.mass_properties.p_BoBcm_B().stableNorm();
      if (d <= kMotionScale) continue;
      throw SceneError(
          scene.file, part.where.line, part.where.column, part.where.key,
          fmt::format("body '{}', part '{}': its centre of mass is {:.6g} m from the body's "
                      "origin; a run accepts positions up to {:g} m (beyond, energies and "
                      "moments leave double precision): check the position and its unit",
                      b.name, part.name, d, kMotionScale));
    }
    const double m = b.mass_properties.mass();
    const double tr = b.mass_properties.I_BBcm_B().Trace();
    const bool m_ok = m >= kMinBodyScale && m <= kMaxBodyScale;
    // A particle (all its mass at one point) has no inertia at all: tr = 0 is exact.
    if (!m_ok || !(tr == 0.0 || (tr >= kMinBodyScale && tr <= kMaxBodyScale))) {
      throw SceneError(
          scene.file, b.where.line, b.where.column, b.where.key,
          fmt::format(
              "body '{}': its {} is {:.6g} {}; a body in motion needs a "
              "mass and an inertia (trace, or 0 for a point mass) between {:g} and {:g} in SI, so "
              "that forces divided by them stay finite",
              b.name, m_ok ? "moment of inertia (trace)" : "mass", m_ok ? tr : m,
              m_ok ? "kg*m^2" : "kg", kMinBodyScale, kMaxBodyScale));
    }
  }
  for (const SceneDriver& d : scene.dynamics.constraints.drivers) {
    const double f = std::abs(d.f0) + std::abs(d.f1) * t_end + 0.5 * std::abs(d.f2) * t_end * t_end;
    const double v = std::abs(d.f1) + std::abs(d.f2) * t_end;
    const double a = std::abs(d.f2);
    if (f <= kMotionScale && v <= kMotionScale && a <= kMotionScale) continue;
    throw SceneError(
        scene.file, d.where.line, d.where.column, d.where.key,
        fmt::format("driver '{}': its motion reaches {:.3g} (position), {:.3g} (rate), {:.3g} "
                    "(acceleration) in SI by t = {:.6g} s; a run accepts motions up to {:g} in "
                    "SI (beyond, energies and reactions leave double precision): check f0, f1, "
                    "f2 and their units",
                    d.name, f, v, a, t_end, kMotionScale));
  }
}

/// Bodies held by a constraint or touching through a contact: a spring's stiffness estimate
/// below is a lower bound only for bodies free of them.
std::vector<bool> HeldBodies(const Scene& scene) {
  std::vector<bool> held(scene.bodies.size(), false);
  const auto hold = [&](int b) {
    if (b >= 0 && b < static_cast<int>(held.size())) held[static_cast<size_t>(b)] = true;
  };
  const SceneConstraints& c = scene.dynamics.constraints;
  for (const auto& j : c.joints) hold(j.parent), hold(j.child);
  for (const auto& r : c.rolling) hold(r.on), hold(r.body);
  for (const auto& d : c.drivers) hold(d.parent), hold(d.child);
  for (const auto& g : c.gears) hold(g.parent), hold(g.child);
  for (const auto& st : c.strings) hold(st.from.body), hold(st.to.body);
  for (const auto& k : scene.dynamics.contacts.contacts) hold(k.body), hold(k.other_body);
  return held;
}

/// Refuses, before the run, a spring so stiff that the adaptive integrator cannot cross the
/// span within the step limit. Along the spring's line the two free bodies oscillate at
/// ω² = k (1/m_a + 1/m_b) at least (the Rayleigh quotient of the stiffness k (u_a - u_b)² over
/// the kinetic m_a u_a² + m_b u_b²: rotations and other springs only raise the highest
/// frequency). The stability region of Dormand-Prince 5(4), |R(hλ)| <= 1 with
/// R(z) = Σ_{k<=5} z^k/k! + z^6/600, lies inside |hλ| <= 3.4 (it reaches -3.3 on the real axis
/// and only ±i on the imaginary one; Hairer & Wanner, Solving ODE II, IV.2), so the step must
/// keep h ω below 4: at least span ω / 4 steps. A damper adds the rate c (1/m_a + 1/m_b) on
/// the real axis, with the same bound.
void CheckSpringStiffness(const Scene& scene, const RunLimits& limits, double span) {
  if (scene.dynamics.simulation.integrator != IntegratorKind::kDormandPrince5) return;
  const std::vector<bool> held = HeldBodies(scene);
  for (const SceneForce& f : scene.dynamics.forces) {
    if (f.type != SceneForce::Type::kSpring) continue;
    const auto inv_mass = [&](int b) {
      return b == kWorld ? 0.0 : 1.0 / scene.bodies[static_cast<size_t>(b)].mass_properties.mass();
    };
    if (held[static_cast<size_t>(f.body)] ||
        (f.body_b != kWorld && held[static_cast<size_t>(f.body_b)])) {
      continue;
    }
    const double s = inv_mass(f.body) + inv_mass(f.body_b);
    const double rate = std::max(std::sqrt(f.stiffness * s), f.damping * s);
    const double steps = span * rate / 4.0;
    if (!(steps > static_cast<double>(limits.max_steps))) continue;
    ThrowLimit(scene, f.where, "max_steps", "--max-steps",
               fmt::format("spring '{}' is too stiff for the step limit: its bodies oscillate "
                           "at {:.3g} rad/s or faster, an explicit step must be shorter than "
                           "about 4 / ({:.3g} rad/s) = {:.3g} s to stay stable, so the span of "
                           "{:.6g} s needs at least {:.3g} steps, more than the limit of {} "
                           "steps",
                           f.name, rate, rate, 4.0 / rate, span, steps, limits.max_steps),
               "soften the spring, shorten the run, or ");
  }
}

/// Limits the run would exceed for sure, refused before it starts: the rows the output grid
/// needs (span / output_interval + the first and last + one per impulse or impact), a fixed
/// step below the smallest step or needing more steps than allowed, a spring too stiff.
void CheckLimitsUpFront(const Scene& scene, const RunLimits& limits, double span,
                        double output_interval) {
  const SceneSimulation& sim = scene.dynamics.simulation;
  const double jumps =
      static_cast<double>(scene.dynamics.impulses.size() + scene.dynamics.impacts.size());
  const double rows = std::floor(span / output_interval + 1e-9) + 2.0 + jumps;
  if (rows > static_cast<double>(limits.max_rows)) {
    ThrowLimit(scene, sim.Spot(sim.keys.count("output_interval") ? "output_interval" : "max_rows"),
               "max_rows", "--max-rows",
               fmt::format("the run would write {:.4g} output rows (a span of {:.6g} s every "
                           "{:.6g} s), more than the limit of {} rows",
                           rows, span, output_interval, limits.max_rows),
               "choose a longer 'output_interval' or ");
  }
  if (!(limits.min_step > 0) || !std::isfinite(limits.min_step)) {
    ThrowLimit(
        scene, sim.Spot("min_step"), "min_step", "--min-step",
        fmt::format("the smallest step must be a positive time, got {:.6g} s", limits.min_step), "",
        "set");
  }
  // A smallest step longer than the whole run bounds nothing: any rejected step would stop
  // the run, and an accepted one never meets it (--min-step 1e300 would be taken silently).
  if (limits.min_step > span) {
    ThrowLimit(scene, sim.Spot("min_step"), "min_step", "--min-step",
               fmt::format("the smallest step {:.6g} s is longer than the run's span of {:.6g} s",
                           limits.min_step, span),
               "", "lower");
  }
  if (sim.integrator != IntegratorKind::kDormandPrince5 && std::isfinite(sim.step)) {
    if (sim.step < limits.min_step) {
      ThrowLimit(scene, sim.Spot("step"), "min_step", "--min-step",
                 fmt::format("the step {:.6g} s is below the smallest step allowed, {:.6g} s "
                             "({:g} of the span {:.6g} s unless 'min_step' says otherwise)",
                             sim.step, limits.min_step, kDefaultMinStepFraction, span),
                 "choose a longer 'step' or ", "lower");
    }
    const double steps = std::ceil(span / sim.step);
    if (steps > static_cast<double>(limits.max_steps)) {
      ThrowLimit(scene, sim.Spot("step"), "max_steps", "--max-steps",
                 fmt::format("the run would take {:.4g} steps of {:.6g} s over {:.6g} s, more "
                             "than the limit of {} steps",
                             steps, sim.step, span, limits.max_steps),
                 "choose a longer 'step' or ");
    }
  }
  CheckSpringStiffness(scene, limits, span);
}

/// The scene's bodies as the study's bodies. In plane motion (w = w_z e_z, held by the plane
/// constraint) only I_zz about Bcm acts: eq. 8.36-8.38, H_z = I_zz w_z. The other entries only
/// change the out-of-plane reactions, which a planar scene does not report, so the Model takes
/// a lamina's, I_xx = I_yy = I_zz / 2 and no products: valid, and invertible for any body with
/// I_zz > 0 (a slender rod in the plane has I_xx = 0 about its own axis).
std::vector<NamedBody> StudyBodies(const Scene& scene) {
  std::vector<NamedBody> bodies;
  bodies.reserve(scene.bodies.size());
  for (const SceneBody& b : scene.bodies) {
    const MassProperties& mp = b.mass_properties;
    if (scene.planar) {
      const double Izz = mp.I_BBcm_B().Izz();
      bodies.push_back({b.name, MassProperties(mp.mass(), mp.p_BoBcm_B(),
                                               RotationalInertia(0.5 * Izz, 0.5 * Izz, Izz))});
    } else {
      bodies.push_back({b.name, mp});
    }
  }
  return bodies;
}

/// The identity map of the scene's bodies (before any embedding).
BodyMap IdentityMap(const Scene& scene) {
  BodyMap map;
  const size_t n = scene.bodies.size();
  map.place.reserve(n);
  map.p_BoBcm_B.reserve(n);
  map.mass.reserve(n);
  map.I_BBcm_B.reserve(n);
  for (size_t b = 0; b < n; ++b) {
    map.place.push_back({static_cast<int>(b), Mat3::Identity(), Vec3::Zero()});
    map.p_BoBcm_B.push_back(scene.bodies[b].mass_properties.p_BoBcm_B());
    map.mass.push_back(scene.bodies[b].mass_properties.mass());
    map.I_BBcm_B.push_back(scene.bodies[b].mass_properties.I_BBcm_B().matrix());
  }
  return map;
}

State InitialState(const Scene& scene, const Model& model) {
  State s = MakeRestState(model);
  for (size_t b = 0; b < scene.bodies.size(); ++b) {
    const SceneInitialState& in = scene.dynamics.initial[b];
    const int i = static_cast<int>(b);
    SetBodyPose(model, i, in.p_WBo, in.q_WB, s);
    // v_Bo = v_P - w × (R p_BoP).
    const Vec3 v_WBo = in.v_WP_W - in.w_WB_W.cross(in.q_WB * in.p_BoP_B);
    // The spin about a zero-moment axis is not a degree of freedom (docs/design.md, "Particles
    // and slender bodies"): the body keeps it at its initial value, which must be 0.
    const Body& body = model.body(i);
    if (body.num_zero_moments() > 0) {
      const Vec3 w_B = in.q_WB.conjugate() * in.w_WB_W;
      const Vec3 w_frozen = w_B - body.free_rotation_B() * w_B;
      if (w_frozen.norm() > 1e-12 * w_B.norm()) {
        const SceneBody& sb = scene.bodies[b];
        throw SceneError(
            scene.file, sb.where.line, sb.where.column, sb.where.key,
            fmt::format("body '{}': {}; its initial angular velocity has {:.6g} rad/s about "
                        "the zero-inertia {}: give an angular velocity {}",
                        sb.name,
                        body.is_particle() ? "a point mass has no rotational inertia"
                                           : "all its mass lies on a line (a zero principal "
                                             "moment)",
                        w_frozen.norm(), body.is_particle() ? "directions" : "axis",
                        body.is_particle() ? "of 0" : "perpendicular to that line"));
      }
    }
    SetBodyVelocity(model, i, v_WBo, in.w_WB_W, s);
  }
  return s;
}

/// How the run settles the scene's initial state (SettleInitialState): projected when the scene
/// says `project_initial: true`, its values named as the scene gives them.
InitialSettling Settling(const Scene& scene) {
  InitialSettling s;
  s.project = scene.dynamics.project_initial;
  s.planar = scene.planar;
  for (const SceneInitialState& in : scene.dynamics.initial) {
    s.theta.push_back(in.theta);
    s.p_BoP_B.push_back(in.p_BoP_B);
  }
  return s;
}

/// Nothing silent: a string given from a body to the world is modelled the other way round.
std::vector<std::string> StringWarnings(const Scene& scene) {
  std::vector<std::string> warnings;
  for (const SceneString& st : scene.dynamics.constraints.strings) {
    if (st.to.body != kWorld) continue;
    const std::string& body = scene.bodies[static_cast<size_t>(st.from.body)].name;
    warnings.push_back(fmt::format(
        "string '{}' is given from body '{}' to the world; it is modelled from its world end to "
        "'{}' (the same string followed the other way, every sense flipped), so its reaction is "
        "reported on '{}'",
        st.name, body, body, body));
  }
  return warnings;
}

SimulationOptions BaseOptions(const Scene& scene, double t_end) {
  const SceneSimulation& sim = scene.dynamics.simulation;
  SimulationOptions o;
  o.integrator = sim.integrator;
  o.t_end = t_end;
  o.output_interval = std::isfinite(sim.output_interval) ? sim.output_interval : t_end / 200;
  if (std::isfinite(sim.step)) o.fixed_step = sim.step;
  o.adaptive.rtol = sim.rtol;
  o.adaptive.atol = sim.atol;
  return o;
}

}  // namespace

namespace {

/// Where the Model element `e` stands in the file: BuildModel adds the force elements after
/// the uniform gravity (when the scene has gravity: no entry of its own), the constraints in
/// SceneConstraints order and then a planar scene's plane constraints (one per body, at the
/// body's entry), the contacts and their points in scene order (AddSceneContacts); the events
/// are BuildEvents' in scene order, the bodies the scene's (a run names its user bodies), an
/// initial state the body's `initial` entry. Null when the element has no entry.
const SceneSpot* SceneEntryOf(const Scene& scene, const ErrorElement& e) {
  const SceneDynamics& d = scene.dynamics;
  const auto at = [](const auto& entries, int i) -> const SceneSpot* {
    return i >= 0 && static_cast<size_t>(i) < entries.size()
               ? &entries[static_cast<size_t>(i)].where
               : nullptr;
  };
  switch (e.kind) {
    case ErrorElement::Kind::kBody:
      return at(scene.bodies, e.index);
    case ErrorElement::Kind::kForceElement:
      return at(d.forces, e.index - (d.has_gravity ? 1 : 0));
    case ErrorElement::Kind::kConstraint: {
      const int n = static_cast<int>(d.constraints.names().size());
      return e.index < n ? d.constraints.At(e.index) : at(scene.bodies, e.index - n);
    }
    case ErrorElement::Kind::kContact:
      return at(d.contacts.contacts, e.index);
    case ErrorElement::Kind::kContactPoint: {
      int first = 0;
      for (const SceneContact& c : d.contacts.contacts) {
        first += static_cast<int>(ContactPointLabels(c).size());
        if (e.index < first) return &c.where;
      }
      return nullptr;
    }
    case ErrorElement::Kind::kEvent:
      return at(d.events, e.index);
    case ErrorElement::Kind::kInitialState:
      return at(d.initial, e.index);
  }
  return nullptr;
}

}  // namespace

void ThrowAtSceneEntry(const Scene& scene, const InputError& error) {
  if (const auto* located = dynamic_cast<const SceneError*>(&error)) throw *located;
  const std::string what = error.what();
  const SceneSpot* spot = error.element() ? SceneEntryOf(scene, *error.element()) : nullptr;
  // A force, moment or torque that is its expression and evaluated to NaN or an infinity (the
  // state is finite: that is checked first): the expression did, at its own value.
  if (spot && error.element()->kind == ErrorElement::Kind::kForceElement &&
      error.element()->non_finite_output) {
    const SceneForce& f = scene.dynamics.forces[static_cast<size_t>(
        error.element()->index - (scene.dynamics.has_gravity ? 1 : 0))];
    const SceneSpot& at = f.expression_where;
    if (at.line != 0) {
      throw SceneError(scene.file, at.line, at.column, at.key,
                       fmt::format("the expression of force element '{}' produced a non-finite "
                                   "value (a division by zero, a logarithm of 0, a root of a "
                                   "negative number or an overflow): {}",
                                   f.name, what));
    }
  }
  // Naming none, it is about the run as the `simulation` block sets it up.
  if (!spot) spot = &scene.dynamics.simulation.where;
  throw SceneError(scene.file, spot->line, spot->column, spot->key, what);
}

Study BuildStudy(const Scene& scene, double until) {
  try {
    const double t_end = EndTime(scene, until);
    CheckPhysicalInputs(scene, t_end);
    Study study;
    const BodyMap identity = IdentityMap(scene);
    study.model = std::make_shared<const Model>(BuildModel(scene, StudyBodies(scene), identity));
    study.options = BaseOptions(scene, t_end);
    study.initial = InitialState(scene, *study.model);
    study.settling = Settling(scene);
    study.warnings = StringWarnings(scene);
    study.options.events = BuildEvents(scene, identity);
    return study;
  } catch (const InputError& e) {
    ThrowAtSceneEntry(scene, e);
  }
}

namespace {

/// A run's error at its scene entry: a limit reached at the `simulation` key that sets it, any
/// other as ThrowAtSceneEntry.
[[noreturn]] void ThrowRunErrorAtSceneEntry(const Scene& scene, const InputError& e) {
  if (const auto* limit = dynamic_cast<const LimitError*>(&e)) ThrowLimitReached(scene, *limit);
  ThrowAtSceneEntry(scene, e);
}

// What a time-stepped run with `ball_collisions` does differently from what the scene may
// expect, said as warnings (none without ball_collisions).
void AddBallCollisionWarnings(const SceneSimulation& sim, const Model& first,
                              std::vector<std::string>& warnings) {
  if (!sim.collide_all_pairs) return;
  if (sim.ball_collisions.restitution > 0 && sim.ball_collisions.law != RestitutionLaw::kNewton) {
    warnings.push_back(fmt::format(
        "ball_collisions: time stepping applies Newton's law at all touching points at once; "
        "its restitution_law '{}' is not used (the laws agree for a frictionless collision "
        "of two bodies)",
        RestitutionLawName(sim.ball_collisions.law)));
  }
  const std::vector<double> radii = BallRadii(first);
  if (std::count_if(radii.begin(), radii.end(), [](double r) { return r > 0.0; }) < 2) {
    warnings.push_back(
        "ball_collisions: fewer than two bodies are balls (a ball is a body with a sphere "
        "contact centred at its centre of mass), so no pair can collide");
  }
  // The rows' contact forces are the smooth engine's at each sample, over the listed
  // contacts (docs/contact.md, "Every pair of balls"): say that they do not see the pairs.
  warnings.push_back(
      "ball_collisions: the contact forces in the rows and in the contacts at the end are "
      "those of the listed contacts alone, found at each sample as if no two balls touched: "
      "a ball pressed by another shows less than it carries (the pairs' impulses are in "
      "every step's certificate)");
}

StudyDefinition MakeUnlocatedStudyDefinition(const Scene& scene, const StudyOptions& options) {
  const SceneDynamics& d = scene.dynamics;
  const double t_end = EndTime(scene, options.until);
  CheckPhysicalInputs(scene, t_end);
  const RunLimits limits = ResolveLimits(scene, options, t_end);
  StudyDefinition def;
  def.options = BaseOptions(scene, t_end);
  CheckLimitsUpFront(scene, limits, t_end, def.options.output_interval);
  def.options.adaptive.min_step = limits.min_step;
  def.limits = {limits.max_steps, limits.max_rows, limits.timeout};
  def.bodies = StudyBodies(scene);
  // The builder and the events outlive the caller's Scene (a definition may be kept and run
  // later, or in another thread): they hold their own copy.
  const auto shared = std::make_shared<const Scene>(scene);
  def.build_model = [shared](const std::vector<NamedBody>& bodies, const BodyMap& map) {
    return BuildModel(*shared, bodies, map);
  };
  def.events = [shared](const BodyMap& map) { return BuildEvents(*shared, map); };
  def.locate_error = [shared](const InputError& e) { ThrowRunErrorAtSceneEntry(*shared, e); };
  def.column_units = [shared](const std::vector<std::string>& columns) {
    return StudyColumnUnits(*shared, columns);
  };
  const scene_internal::ColumnIndex columns(scene);
  for (const std::string& name : d.columns) {
    if (std::optional<scene_internal::ColumnInfo> c = columns.Find(name)) {
      def.columns.push_back(std::move(*c));
    }
  }
  for (const SceneImpulse& i : d.impulses) {
    def.impulses.push_back({i.t, i.body, i.p_BoP_B, i.J, i.frame});
  }
  for (const SceneImpact& i : d.impacts) {
    def.impacts.push_back({i.t, i.target, i.projectile, i.exit_fraction});
  }
  def.contact_point_labels = d.contacts.point_labels();
  for (const SceneForce& f : d.forces) def.reported_forces.push_back(f.name);
  def.num_reported_constraints = static_cast<int>(d.constraints.names().size());
  if (scene.planar) {
    for (const SceneInitialState& in : d.initial) def.initial_theta.push_back(in.theta);
  }
  for (size_t i = 0; i < d.constraints.rolling.size(); ++i) {
    const SceneRolling& r = d.constraints.rolling[i];
    if (std::isnan(r.mu_s)) continue;
    def.rolling_watch.push_back(
        {r.name, static_cast<int>(d.constraints.joints.size() + i), r.mu_s});
  }
  def.certificate = CertificateTolerancesFor(scene);
  def.progress = options.progress;
  def.record_row_snapshots = options.record_row_snapshots;
  def.record_row_poses = options.record_row_poses;
  // The first segment's Model, built once: the checks below read it and the run starts on it.
  def.model = std::make_shared<const Model>(BuildModel(scene, def.bodies, IdentityMap(scene)));
  const Model& first = *def.model;
  const SceneSimulation& sim = d.simulation;
  if (sim.event_driven) {
    // Balls on a table only (the message names the body, contact or force that is not).
    ChooseRunPath(first, def.options, EngineRequest::kEvents);
    SphereEventOptions events;
    events.collide_all_pairs = sim.collide_all_pairs;
    events.pair_law = sim.ball_collisions;
    events.hybrid = def.options.adaptive;  // the pressing groups' runs
    def.sphere_events = events;
  }
  if (sim.time_stepping) {
    ChooseRunPath(first, def.options, EngineRequest::kStepping);
    // Moreau's law at every point at once (docs/contact.md, "Time stepping"): a contact that
    // asks for another law is told which one it gets.
    for (std::string& w : TimeSteppingLawWarnings(first)) def.warnings.push_back(std::move(w));
    TimeSteppingOptions stepping;
    stepping.step = sim.step;
    stepping.collide_all_pairs = sim.collide_all_pairs;
    stepping.pair_law = sim.ball_collisions;
    AddBallCollisionWarnings(sim, first, def.warnings);
    def.time_stepping = stepping;
  }
  if (sim.auto_engine) {
    // Time stepping's step: the scene's, else one derived from the bodies' sizes and gravity.
    StudyDefinition::AutoEngine engines;
    engines.rule = MakeEngineChoiceRule(
        std::isfinite(sim.step) ? sim.step : DefaultEngineStep(first, def.options.output_interval));
    engines.by_default = sim.auto_by_default;
    // Every pair of balls may collide: only time stepping finds the pairs, so the run is time
    // stepped throughout (StudyRun::Start).
    engines.stepping.collide_all_pairs = sim.collide_all_pairs;
    engines.stepping.pair_law = sim.ball_collisions;
    AddBallCollisionWarnings(sim, first, def.warnings);
    def.auto_engine = engines;
  }
  // The run settles it: on the constraints, or an error, or projected with each change a
  // warning.
  def.initial = InitialState(scene, first);
  def.settle_initial = Settling(scene);
  for (std::string& w : StringWarnings(scene)) def.warnings.push_back(std::move(w));
  return def;
}

}  // namespace

StudyDefinition MakeStudyDefinition(const Scene& scene, const StudyOptions& options) {
  try {
    return MakeUnlocatedStudyDefinition(scene, options);
  } catch (const InputError& e) {
    ThrowAtSceneEntry(scene, e);
  }
}

}  // namespace chasles
