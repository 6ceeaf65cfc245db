// Running a scene's dynamics: Model building, segments between impulses and impacts, output
// rows and the ledger carried across segments (see include/chasles/scene/study.h).

#include "chasles/scene/study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <numbers>

#include <fmt/format.h>

#include "chasles/analysis/ledger.h"
#include "chasles/analysis/momentum.h"
#include "chasles/dynamics/constraint_solve.h"
#include "chasles/dynamics/contact_solve.h"
#include "chasles/dynamics/impulse.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/dynamics/redundancy.h"
#include "chasles/error.h"
#include "chasles/model/constraints.h"
#include "chasles/model/data.h"
#include "chasles/model/forces.h"
#include "chasles/scene/scene_error.h"
#include "internal/initial_state.h"
#include "internal/study_columns.h"

namespace chasles {

namespace {

using scene_internal::AllColumns;
using scene_internal::ColumnInfo;

/// Where a scene body sits in a Model body: the same body, or a part of a composite after an
/// embedding. R_MB and p_MoBo_M place the scene body's frame in the model body's frame.
struct Placement {
  int model_body = 0;
  Mat3 R_MB = Mat3::Identity();
  Vec3 p_MoBo_M = Vec3::Zero();
};

/// Scene bodies mapped to the current Model, with each scene body's own centre of mass.
struct BodyMap {
  std::vector<Placement> place;
  std::vector<Vec3> p_BoBcm_B;
  /// Number of the scene's own constraints (a planar Model adds its plane constraints after
  /// them; those have no state variables).
  int num_scene_constraints = 0;
};

/// Kinematics of one scene body at a state (exact for a part of a composite too).
struct SceneBodyMotion {
  Mat3 R_WB;
  Vec3 p_WBo, p_WBcm, v_WBcm_W, w_WB_W;
};

SceneBodyMotion CalcSceneBodyMotion(const Model& model, const State& state, const BodyMap& map,
                                    int b) {
  const Placement& pl = map.place[static_cast<size_t>(b)];
  const BodyState& s = state.bodies[static_cast<size_t>(pl.model_body)];
  const Body& body = model.body(pl.model_body);
  const Mat3 R_WM = s.q_WB.toRotationMatrix();
  SceneBodyMotion m;
  m.R_WB = R_WM * pl.R_MB;
  m.w_WB_W = R_WM * s.w_WB_B;
  const Vec3 p_WMo = s.p_WBcm - R_WM * body.p_BoBcm_B();
  m.p_WBo = p_WMo + R_WM * pl.p_MoBo_M;
  m.p_WBcm = m.p_WBo + m.R_WB * map.p_BoBcm_B[static_cast<size_t>(b)];
  // Rigid-body velocity field: v_P = v_Mcm + w × (p_P - p_Mcm).
  m.v_WBcm_W = s.v_WBcm_W + m.w_WB_W.cross(m.p_WBcm - s.p_WBcm);
  return m;
}

/// Euler ZYX angles (yaw, pitch, roll) of R = Rz(yaw) Ry(pitch) Rx(roll) [rad].
Vec3 CalcYawPitchRoll(const Mat3& R) {
  const double pitch = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  return {std::atan2(R(1, 0), R(0, 0)), pitch, std::atan2(R(2, 1), R(2, 2))};
}

/// Fills the state variables (StateVariableLayout) up to `count` slots.
void FillVariables(const Model& model, const State& state, const BodyMap& map, int count,
                   std::vector<double>& v) {
  v.assign(static_cast<size_t>(std::max(count, 1)), 0.0);
  v[0] = state.t;
  const int per = StateVariableLayout::kPerBody;
  const int num_scene_bodies = static_cast<int>(map.place.size());
  for (int b = 0; b < num_scene_bodies && b * per + 1 < count; ++b) {
    const SceneBodyMotion m = CalcSceneBodyMotion(model, state, map, b);
    const Vec3 w_B = m.R_WB.transpose() * m.w_WB_W;
    const Vec3 ypr = CalcYawPitchRoll(m.R_WB);
    const double block[StateVariableLayout::kPerBody] = {
        m.p_WBcm.x(),
        m.p_WBcm.y(),
        m.p_WBcm.z(),
        m.v_WBcm_W.x(),
        m.v_WBcm_W.y(),
        m.v_WBcm_W.z(),
        m.w_WB_W.x(),
        m.w_WB_W.y(),
        m.w_WB_W.z(),
        w_B.x(),
        w_B.y(),
        w_B.z(),
        std::acos(std::clamp(m.R_WB(2, 2), -1.0, 1.0)),
        ypr.x(),
        ypr.y(),
        ypr.z(),
        m.v_WBcm_W.norm(),
        m.w_WB_W.norm()};
    for (int j = 0; j < per; ++j) {
      const int slot = StateVariableLayout::Slot(b, j);
      if (slot < count) v[static_cast<size_t>(slot)] = block[j];
    }
  }
  // Reactions (events only): six slots per scene constraint after the scene bodies' blocks,
  // then the contact points' values (StateVariableLayout).
  const int first = StateVariableLayout::Slot(num_scene_bodies, 0);
  const int num_constraints = std::min(map.num_scene_constraints, model.num_constraints());
  const int first_contact = first + StateVariableLayout::kPerConstraint * map.num_scene_constraints;
  const bool reactions = count > first && num_constraints > 0;
  const bool contacts = count > first_contact && model.num_contact_points() > 0;
  if (!reactions && !contacts) return;
  Data data = MakeData(model);
  CalcAccelerations(model, state, data);
  for (int i = 0; i < num_constraints; ++i) {
    const ConstraintOutput& o = data.constraints[static_cast<size_t>(i)];
    for (int k = 0; k < 6; ++k) {
      const int slot = first + 6 * i + k;
      if (slot < count) v[static_cast<size_t>(slot)] = k < 3 ? o.F_Jc_W[k] : o.M_Jc_W[k - 3];
    }
  }
  if (!contacts) return;
  // Contact points in the modes `state` carries (the values of the output columns).
  for (int p = 0; p < model.num_contact_points(); ++p) {
    const ContactPointOutput& o = data.contact_points[static_cast<size_t>(p)];
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
/// the model body's frame.
VectorFunction MakeVectorFunction(std::shared_ptr<const Model*> model_ref,
                                  std::shared_ptr<const BodyMap> map,
                                  const SceneVectorExpression& value, const Mat3& R_MB) {
  auto buffer = std::make_shared<std::vector<double>>();
  const int count = value.variable_count();
  return [model_ref, map, value, R_MB, buffer, count](double, const State& state) -> Vec3 {
    FillVariables(**model_ref, state, *map, count, *buffer);
    return R_MB * value.Evaluate(*buffer);
  };
}

State InitialState(const Scene& scene, const Model& model);

/// Name of the constraint that holds scene body `b` of a planar scene in its plane (after the
/// scene's own constraints in Model order; reports of planar scenes leave these out).
std::string PlaneConstraintName(const Scene& scene, int b) {
  return fmt::format("{} (in plane)", scene.bodies[static_cast<size_t>(b)].name);
}

/// The angle θ of B about z in a planar scene, continuous from `reference` (the previous
/// sample's θ advanced by the trapezoidal ω Δt, or the initial θ): the branch of
/// atan2(R(1,0), R(0,0)) + 2πk nearest to it. Output samples closer than half a turn of
/// prediction error apart keep θ continuous however many turns the body makes.
double UnwrapTheta(const Mat3& R_WB, double reference) {
  const double wrapped = std::atan2(R_WB(1, 0), R_WB(0, 0));
  const double two_pi = 2.0 * std::numbers::pi;
  return wrapped + two_pi * std::round((reference - wrapped) / two_pi);
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
  for (const SceneJoint& j : c.joints) {
    Mat3 R_WJ = FrameWithZAxis(j.axis_W);
    if (j.kind == JointKind::kPrismaticInPlane || j.kind == JointKind::kPointOnLineInPlane) {
      // J's z is the plane's normal and x the sliding direction (the line).
      R_WJ << j.axis_W, Vec3::UnitZ().cross(j.axis_W), Vec3::UnitZ();
    }
    model.AddConstraint(std::make_shared<Joint>(j.name, j.kind, model_body(j.parent),
                                                frame(j.parent, j.p_WJ, R_WJ), model_body(j.child),
                                                frame(j.child, j.p_WJ, R_WJ)));
  }
  for (const SceneRolling& r : c.rolling) {
    // The plane is given in W at the initial configuration; on a body it is fixed in that
    // body's frame from there on.
    const AttachmentFrame X = frame(r.on, r.plane_point_W, FrameWithZAxis(r.plane_normal_W));
    model.AddConstraint(std::make_shared<RollingContact>(
        r.name, r.shape, model_body(r.on), X.p_BoJ_B, Vec3(X.R_BJ.col(2)), model_body(r.body),
        r.p_BoC_B, r.axis_B, r.radius));
  }
  for (const SceneDriver& d : c.drivers) {
    const Mat3 R_WJ = FrameWithZAxis(d.axis_W);
    model.AddConstraint(std::make_shared<PrescribedMotion>(
        d.name, d.kind, model_body(d.parent), frame(d.parent, d.p_WJ, R_WJ), model_body(d.child),
        frame(d.child, d.p_WJ, R_WJ), TimeFunction::Quadratic(d.f0, d.f1, d.f2)));
  }
  for (const SceneGear& g : c.gears) {
    const auto circle = [&](int b, const ScenePitchCircle& pc) {
      const AttachmentFrame X = frame(b, pc.center_W, FrameWithZAxis(pc.axis_W));
      return PitchCircle{X.p_BoJ_B, Vec3(X.R_BJ.col(2)), pc.radius};
    };
    model.AddConstraint(std::make_shared<GearMesh>(
        g.name, g.kind, model_body(g.parent), circle(g.parent, g.parent_circle),
        model_body(g.child), circle(g.child, g.child_circle), g.keep_contact));
  }
  if (scene.planar) {
    // Every body of a planar scene is held in its plane z = const by one kPlanar joint with
    // the world at its centre of mass (3 rows: v_z, w_x, w_y). The scene's joints contribute
    // only their in-plane rows (kRevoluteInPlane, ...), so no row repeats another and the
    // solve never meets a redundant set (docs/constraints.md, "Planar mechanisms").
    for (size_t b = 0; b < scene.bodies.size(); ++b) {
      const int mb = model_body(static_cast<int>(b));
      const Vec3 p_WBcm = s0.bodies[static_cast<size_t>(mb)].p_WBcm;
      model.AddConstraint(std::make_shared<Joint>(
          PlaneConstraintName(scene, static_cast<int>(b)), JointKind::kPlanar, kWorld,
          AttachmentFrame{p_WBcm, Mat3::Identity()}, mb,
          frame(static_cast<int>(b), p_WBcm, Mat3::Identity())));
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
/// placed through `map`. `model_ref` is set to the Model's final address by the caller.
Model BuildModel(const Scene& scene,
                 const std::vector<std::pair<std::string, MassProperties>>& bodies,
                 const std::shared_ptr<const BodyMap>& map,
                 const std::shared_ptr<const Model*>& model_ref) {
  Model model;
  for (const auto& [name, mp] : bodies) model.AddBody(name, mp);
  const SceneDynamics& d = scene.dynamics;
  if (d.has_gravity) model.AddForceElement(std::make_shared<UniformGravity>("gravity", d.g_W));
  auto point = [&](int b, const Vec3& p_BoP_B) {
    const Placement& pl = map->place[static_cast<size_t>(b)];
    return Vec3(pl.R_MB * p_BoP_B + pl.p_MoBo_M);
  };
  for (const SceneForce& f : d.forces) {
    const Placement* pl = f.body >= 0 ? &map->place[static_cast<size_t>(f.body)] : nullptr;
    switch (f.type) {
      case SceneForce::Type::kForce:
        if (f.value.is_constant()) {
          const Vec3 v = f.value.Evaluate({0.0});
          model.AddForceElement(AppliedForce::Constant(
              f.name, pl->model_body, point(f.body, f.p_BoP_B),
              f.frame == VectorFrame::kBody ? Vec3(pl->R_MB * v) : v, f.frame));
        } else {
          model.AddForceElement(std::make_shared<AppliedForce>(
              f.name, pl->model_body, point(f.body, f.p_BoP_B),
              MakeVectorFunction(model_ref, map, f.value,
                                 f.frame == VectorFrame::kBody ? pl->R_MB : Mat3::Identity()),
              f.frame));
        }
        break;
      case SceneForce::Type::kMoment:
        if (f.value.is_constant()) {
          const Vec3 v = f.value.Evaluate({0.0});
          model.AddForceElement(AppliedMoment::Constant(
              f.name, pl->model_body, f.frame == VectorFrame::kBody ? Vec3(pl->R_MB * v) : v,
              f.frame));
        } else {
          model.AddForceElement(std::make_shared<AppliedMoment>(
              f.name, pl->model_body,
              MakeVectorFunction(model_ref, map, f.value,
                                 f.frame == VectorFrame::kBody ? pl->R_MB : Mat3::Identity()),
              f.frame));
        }
        break;
      case SceneForce::Type::kSpring: {
        const int mb =
            f.body_b == kWorld ? kWorld : map->place[static_cast<size_t>(f.body_b)].model_body;
        const Vec3 q = f.body_b == kWorld ? f.p_BoQ_B : point(f.body_b, f.p_BoQ_B);
        model.AddForceElement(
            std::make_shared<SpringDamper>(f.name, pl->model_body, point(f.body, f.p_BoP_B), mb, q,
                                           f.rest_length, f.stiffness, f.damping));
        break;
      }
      case SceneForce::Type::kDrag:
        model.AddForceElement(
            std::make_shared<LinearDrag>(f.name, pl->model_body, f.linear, f.angular));
        break;
      case SceneForce::Type::kCentralGravity:
        model.AddForceElement(std::make_shared<CentralGravity>(f.name, f.mu, f.centre_W));
        break;
    }
  }
  AddSceneConstraints(scene, *map, model);
  AddSceneContacts(scene, *map, model);
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

std::vector<EventSpec> BuildEvents(const Scene& scene, std::shared_ptr<const Model*> model_ref,
                                   std::shared_ptr<const BodyMap> map) {
  std::vector<EventSpec> events;
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
    auto buffer = std::make_shared<std::vector<double>>();
    const Expression when = e.when;
    const double level = e.crosses;
    const int count = when.variable_count();
    events.push_back(
        EventSpec{e.name,
                  [model_ref, map, when, level, buffer, count](double, const State& state) {
                    FillVariables(**model_ref, state, *map, count, *buffer);
                    return when.Evaluate(*buffer) - level;
                  },
                  e.direction, e.action});
  }
  return events;
}

double MechanicalEnergy(const Model& model, const State& state) {
  double V = 0.0;
  for (int i = 0; i < model.num_force_elements(); ++i) {
    V += model.force_element(i).CalcPotentialEnergy(model, state);
  }
  return CalcTranslationalKineticEnergy(model, state) + CalcRotationalKineticEnergy(model, state) +
         V;
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

/// Largest magnitude of a motion in SI (position, speed) that a run accepts: beyond it the
/// energies (½ m v²) and moments (r × F) of ordinary bodies leave double precision, so such a
/// motion is a blown-up or mistyped input (CheckFinite stops a run that gets there).
constexpr double kMotionScale = 1e150;
/// The accepted range of a body's mass [kg] and of the trace of its inertia [kg·m²]: with
/// forces and lengths of any physical size the accelerations F/m and I⁻¹M stay far inside
/// double precision (1e-300 kg would turn 1 N into 1e300 m/s²).
constexpr double kMinBodyScale = 1e-100, kMaxBodyScale = 1e100;

/// Inputs no run can integrate, refused before it starts at their entries: a body's mass or
/// inertia outside [1e-100, 1e100] SI, a driver whose motion over the span [0, t_end] exceeds
/// kMotionScale (f = f0 + f1 t + ½ f2 t², f' = f1 + f2 t).
void CheckPhysicalInputs(const Scene& scene, double t_end) {
  for (const SceneBody& b : scene.bodies) {
    const double m = b.mass_properties.mass();
    const double tr = b.mass_properties.I_BBcm_B().Trace();
    const bool m_ok = m >= kMinBodyScale && m <= kMaxBodyScale;
    if (!m_ok || !(tr >= kMinBodyScale && tr <= kMaxBodyScale)) {
      throw SceneError(
          scene.file, b.where.line, b.where.column, b.where.key,
          fmt::format("body '{}': its {} is {:.6g} {}; a body in motion needs a "
                      "mass and an inertia (trace) between {:g} and {:g} in SI, so "
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

/// Throws when a body's motion is not finite (or has run away beyond any physical scale).
void CheckFinite(const Model& model, const State& state) {
  for (int b = 0; b < model.num_bodies(); ++b) {
    const BodyState& s = state.bodies[static_cast<size_t>(b)];
    const double big = 1e150;
    const bool ok = s.p_WBcm.allFinite() && s.v_WBcm_W.allFinite() && s.w_WB_B.allFinite() &&
                    s.q_WB.coeffs().allFinite() && s.p_WBcm.norm() < big &&
                    s.v_WBcm_W.norm() < big && s.w_WB_B.norm() < big;
    if (!ok) {
      throw InputError(fmt::format(
          "the motion of body '{}' diverged (non-finite or beyond 1e150 in SI) near t = {:.9g} s; "
          "the run is stopped. Check the force expressions for a singularity, or use a smaller "
          "'step' or the adaptive integrator",
          model.body(b).name(), state.t));
    }
  }
}

const char* IntegratorName(IntegratorKind k) {
  switch (k) {
    case IntegratorKind::kDormandPrince5:
      return "adaptive Dormand-Prince 5(4)";
    case IntegratorKind::kRk4:
      return "RK4 (fixed step)";
    case IntegratorKind::kEnergyMomentum:
      return "energy-momentum (fixed step)";
  }
  return "";
}

/// Everything that changes at an embedding: the bodies, the map and the Model built on them.
struct Segment {
  std::vector<std::pair<std::string, MassProperties>> bodies;
  std::shared_ptr<BodyMap> map;
  std::shared_ptr<const Model*> model_ref = std::make_shared<const Model*>(nullptr);
  std::unique_ptr<Model> model;

  void Build(const Scene& scene) {
    model_ref = std::make_shared<const Model*>(nullptr);
    model = std::make_unique<Model>(BuildModel(scene, bodies, map, model_ref));
    *model_ref = model.get();
  }
};

Segment FirstSegment(const Scene& scene) {
  Segment seg;
  seg.map = std::make_shared<BodyMap>();
  seg.map->num_scene_constraints = static_cast<int>(scene.dynamics.constraints.names().size());
  for (size_t b = 0; b < scene.bodies.size(); ++b) {
    const MassProperties& mp = scene.bodies[b].mass_properties;
    if (scene.planar) {
      // In plane motion (w = w_z e_z, held by the plane constraint) only I_zz about Bcm acts:
      // eq. 8.36-8.38, H_z = I_zz w_z. The other entries only change the out-of-plane
      // reactions, which a planar scene does not report, so the Model takes a lamina's,
      // I_xx = I_yy = I_zz / 2 and no products: valid, and invertible for any body with
      // I_zz > 0 (a slender rod in the plane has I_xx = 0 about its own axis).
      const double Izz = mp.I_BBcm_B().Izz();
      seg.bodies.emplace_back(
          scene.bodies[b].name,
          MassProperties(mp.mass(), mp.p_BoBcm_B(), RotationalInertia(0.5 * Izz, 0.5 * Izz, Izz)));
    } else {
      seg.bodies.emplace_back(scene.bodies[b].name, mp);
    }
    seg.map->place.push_back(Placement{static_cast<int>(b), Mat3::Identity(), Vec3::Zero()});
    seg.map->p_BoBcm_B.push_back(scene.bodies[b].mass_properties.p_BoBcm_B());
  }
  seg.Build(scene);
  return seg;
}

State InitialState(const Scene& scene, const Model& model) {
  State s = MakeRestState(model);
  for (size_t b = 0; b < scene.bodies.size(); ++b) {
    const SceneInitialState& in = scene.dynamics.initial[b];
    const int i = static_cast<int>(b);
    SetBodyPose(model, i, in.p_WBo, in.q_WB, s);
    // v_Bo = v_P - w × (R p_BoP).
    const Vec3 v_WBo = in.v_WP_W - in.w_WB_W.cross(in.q_WB * in.p_BoP_B);
    SetBodyVelocity(model, i, v_WBo, in.w_WB_W, s);
  }
  return s;
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

/// The ledger across segments: totals of the finished segments plus the running one.
struct LedgerCarry {
  State segment_initial;
  double work_nc = 0.0, dissipated = 0.0, jumps = 0.0, residual = 0.0, scale = 0.0;
  std::map<std::string, double> work_by_force;
};

struct RowMaker {
  const Scene& scene;
  std::vector<ColumnInfo> columns;
  bool needs_accelerations = false;
  /// Planar scenes: each body's last reported θ [rad], ω [rad/s] and time [s], for unwrapping.
  struct ThetaTrack {
    bool started = false;
    double theta = 0.0, omega = 0.0, t = 0.0;
  };
  mutable std::vector<ThetaTrack> theta_track;

  /// θ of scene body `b` at time t, continuous with the previous call (calls in time order).
  double Theta(int b, const Mat3& R_WB, double omega, double t) const {
    theta_track.resize(scene.bodies.size());
    ThetaTrack& k = theta_track[static_cast<size_t>(b)];
    const double reference = k.started ? k.theta + 0.5 * (k.omega + omega) * (t - k.t)
                                       : scene.dynamics.initial[static_cast<size_t>(b)].theta;
    k = {true, UnwrapTheta(R_WB, reference), omega, t};
    return k.theta;
  }

  /// θ of scene body `b` at time t from the last reported one, without advancing the track
  /// (for an event's state, which may lie before the last sample).
  double ThetaAt(int b, const Mat3& R_WB, double omega, double t) const {
    theta_track.resize(scene.bodies.size());
    const ThetaTrack& k = theta_track[static_cast<size_t>(b)];
    const double reference = k.started ? k.theta + 0.5 * (k.omega + omega) * (t - k.t)
                                       : scene.dynamics.initial[static_cast<size_t>(b)].theta;
    return UnwrapTheta(R_WB, reference);
  }

  std::vector<double> Row(const Model& model, const BodyMap& map, const State& s,
                          const LedgerCarry& carry) const {
    const LedgerSample L = CalcLedgerSample(model, s, carry.segment_initial);
    Data data;
    if (needs_accelerations) {
      data = MakeData(model);
      CalcAccelerations(model, s, data);
    }
    std::vector<double> row;
    row.reserve(columns.size());
    if (scene.planar) {
      // θ of every body at every sample, so that it stays continuous whatever is printed.
      for (size_t b = 0; b < map.place.size(); ++b) {
        const SceneBodyMotion m = CalcSceneBodyMotion(model, s, map, static_cast<int>(b));
        Theta(static_cast<int>(b), m.R_WB, m.w_WB_W.z(), s.t);
      }
    }
    for (const ColumnInfo& c : columns) {
      if (c.body >= 0) {
        const SceneBodyMotion m = CalcSceneBodyMotion(model, s, map, c.body);
        const std::string& q = c.quantity;
        const Vec3 w_B = m.R_WB.transpose() * m.w_WB_W;
        Vec3 a_W = Vec3::Zero(), al_W = Vec3::Zero();
        if (q[0] == 'a') {
          const int mb = map.place[static_cast<size_t>(c.body)].model_body;
          const BodyState& bs = s.bodies[static_cast<size_t>(mb)];
          al_W = data.R_WB[static_cast<size_t>(mb)] * data.wdot_WB_B[static_cast<size_t>(mb)];
          const Vec3 r = m.p_WBcm - bs.p_WBcm;
          a_W = data.a_WBcm_W[static_cast<size_t>(mb)] + al_W.cross(r) +
                m.w_WB_W.cross(m.w_WB_W.cross(r));
        }
        const Quat q_WB(m.R_WB);
        const Vec3 ypr = CalcYawPitchRoll(m.R_WB);
        const Vec3 al_B = m.R_WB.transpose() * al_W;
        static const std::map<std::string, int> index = {
            {"x", 0},     {"y", 1},     {"z", 2},     {"ox", 3},     {"oy", 4},     {"oz", 5},
            {"qw", 6},    {"qx", 7},    {"qy", 8},    {"qz", 9},     {"yaw", 10},   {"pitch", 11},
            {"roll", 12}, {"tilt", 13}, {"vx", 14},   {"vy", 15},    {"vz", 16},    {"speed", 17},
            {"wx", 18},   {"wy", 19},   {"wz", 20},   {"wbx", 21},   {"wby", 22},   {"wbz", 23},
            {"ax", 24},   {"ay", 25},   {"az", 26},   {"alx", 27},   {"aly", 28},   {"alz", 29},
            {"albx", 30}, {"alby", 31}, {"albz", 32}, {"theta", 33}, {"omega", 34}, {"alpha", 35}};
        // Quaternion sign: keep w >= 0 so that the printed components are continuous where
        // they can be and the same rotation always prints the same.
        const double sign = q_WB.w() < 0 ? -1.0 : 1.0;
        const double values[] = {
            m.p_WBcm.x(),    m.p_WBcm.y(),
            m.p_WBcm.z(),    m.p_WBo.x(),
            m.p_WBo.y(),     m.p_WBo.z(),
            sign * q_WB.w(), sign * q_WB.x(),
            sign * q_WB.y(), sign * q_WB.z(),
            ypr.x(),         ypr.y(),
            ypr.z(),         std::acos(std::clamp(m.R_WB(2, 2), -1.0, 1.0)),
            m.v_WBcm_W.x(),  m.v_WBcm_W.y(),
            m.v_WBcm_W.z(),  m.v_WBcm_W.norm(),
            m.w_WB_W.x(),    m.w_WB_W.y(),
            m.w_WB_W.z(),    w_B.x(),
            w_B.y(),         w_B.z(),
            a_W.x(),         a_W.y(),
            a_W.z(),         al_W.x(),
            al_W.y(),        al_W.z(),
            al_B.x(),        al_B.y(),
            al_B.z(),        q == "theta" ? theta_track[static_cast<size_t>(c.body)].theta : 0.0,
            m.w_WB_W.z(),    al_W.z()};
        row.push_back(values[index.at(q)]);
        continue;
      }
      const std::string& q = c.quantity;
      if (c.group == "contacts") {
        const ContactPointOutput& o = data.contact_points[static_cast<size_t>(c.point)];
        const double values[] = {static_cast<double>(o.mode), o.normal_force,
                                 o.friction_force_W.norm(), o.slip_velocity_W.norm(), o.gap};
        static const std::map<std::string, int> index = {
            {"mode", 0}, {"N", 1}, {"f", 2}, {"slip", 3}, {"gap", 4}};
        row.push_back(values[index.at(q)]);
        continue;
      }
      if (q == "W_friction" || q == "W_rolling" || q == "W_impacts") {
        // Running integrals the State carries since t = 0 (across every segment).
        double w = 0.0;
        for (const ContactPointState& p : s.contacts) {
          w += q == "W_friction" ? p.friction_work
                                 : (q == "W_rolling" ? p.rolling_work : p.impact_work);
        }
        row.push_back(w);
        continue;
      }
      if (c.group == "reactions") {
        // Force (F) or moment about J (M) the parent exerts on the child, in W ("Fx") or in
        // the child's frame B ("Fx_B").
        const ConstraintOutput& r =
            data.constraints[static_cast<size_t>(model.FindConstraint(c.force))];
        const bool in_B = q.size() > 2;
        const Vec3& v = q[0] == 'F' ? (in_B ? r.F_Jc_B : r.F_Jc_W) : (in_B ? r.M_Jc_B : r.M_Jc_W);
        row.push_back(v[q[1] - 'x']);
        continue;
      }
      double v = 0.0;
      if (q == "t") {
        v = s.t;
      } else if (q == "T_trans") {
        v = L.kinetic_translational;
      } else if (q == "T_rot") {
        v = L.kinetic_rotational;
      } else if (q == "T") {
        v = L.kinetic_translational + L.kinetic_rotational;
      } else if (q == "V") {
        v = L.potential;
      } else if (q == "E") {
        v = L.mechanical_energy;
      } else if (q == "W_nc") {
        v = carry.work_nc + L.work_nonconservative;
      } else if (q == "W") {
        v = carry.work_by_force.count(c.force) ? carry.work_by_force.at(c.force) : 0.0;
        for (const ForceLedger& f : L.forces) {
          if (f.name == c.force) v += f.work_nonconservative;
        }
        for (const ConstraintLedger& f : L.constraints) {
          if (f.name == c.force) v += f.work;
        }
      } else if (q == "dissipated") {
        v = carry.dissipated + L.dissipated;
      } else if (q == "jumps") {
        v = carry.jumps;
      } else if (q == "residual") {
        v = carry.residual + L.energy_residual;
      } else if (q[0] == 'P') {
        v = L.linear_momentum_W[q[1] - 'x'];
      } else if (q[0] == 'H' && q[1] == 'O') {
        v = L.angular_momentum_Wo_W[q[2] - 'x'];
      } else if (q[0] == 'H') {
        v = L.angular_momentum_Scm_W[q[1] - 'x'];
      }
      row.push_back(v);
    }
    return row;
  }
};

/// Watches the friction each rolling contact with a `mu_s` needs over the output samples: the
/// simulation holds the rolling whatever friction it takes, so the report says when more than
/// mu_s N was needed (the body would slip).
struct SlipWatch {
  struct Entry {
    const SceneRolling* rolling;
    int constraint;  // Model index
    double worst = 0.0, t_worst = 0.0;
    bool lifts = false;
    double t_lift = 0.0;
  };
  std::vector<Entry> entries;

  explicit SlipWatch(const Scene& scene) {
    const SceneConstraints& c = scene.dynamics.constraints;
    for (size_t i = 0; i < c.rolling.size(); ++i) {
      if (std::isnan(c.rolling[i].mu_s)) continue;
      entries.push_back({&c.rolling[i], static_cast<int>(c.joints.size() + i)});
    }
  }
  void Sample(const Model& model, const State& s) {
    if (entries.empty() || model.num_constraints() == 0) return;
    Data data = MakeData(model);
    CalcAccelerations(model, s, data);
    for (Entry& e : entries) {
      // The multipliers are N (row 0) and the friction components along the plane's
      // tangents t1, t2 (rows 1, 2); the plane may turn with its body.
      const ConstraintEval::Column& lambda =
          data.constraints[static_cast<size_t>(e.constraint)].lambda;
      const double N = lambda[0];
      if (!(N > 0)) {
        if (!e.lifts) e.lifts = true, e.t_lift = s.t;
        continue;
      }
      const double ratio = std::hypot(lambda[1], lambda[2]) / N;
      if (ratio > e.worst) e.worst = ratio, e.t_worst = s.t;
    }
  }
  void Report(std::vector<std::string>& notes) const {
    for (const Entry& e : entries) {
      if (e.lifts) {
        notes.push_back(
            fmt::format("rolling contact '{}': the plane would have to pull (N <= 0) "
                        "at t = {:.6g} s: the body would lift off",
                        e.rolling->name, e.t_lift));
      }
      if (e.worst > e.rolling->mu_s) {
        notes.push_back(
            fmt::format("rolling contact '{}' needs f/N = {:.6g} at t = {:.6g} s, "
                        "more than mu_s = {:.6g}: the body would slip (the "
                        "simulation holds it rolling)",
                        e.rolling->name, e.worst, e.t_worst, e.rolling->mu_s));
      }
    }
  }
};

/// Bodies, reactions (the scene's own constraints) and contact points of `model` at `state`.
/// Planar scenes: θ continuous with the rows' track, which `advance` moves on to `state`.
StudySnapshot MakeSnapshot(const Scene& scene, const Model& model, const State& state,
                           const RowMaker& rows, bool advance) {
  StudySnapshot out;
  const size_t num_scene_constraints = scene.dynamics.constraints.names().size();
  if (model.num_constraints() > 0) {
    // The reactions at `state` (the constraint stage of CalcAccelerations).
    Data data = MakeData(model);
    CalcAccelerations(model, state, data);
    for (int i = 0; i < static_cast<int>(num_scene_constraints); ++i) {
      const Constraint& con = model.constraint(i);
      const ConstraintOutput& o = data.constraints[static_cast<size_t>(i)];
      StudyReaction r;
      r.name = con.name();
      r.kind = con.kind();
      r.p_WJ = o.p_WJ;
      r.F_Jc_W = o.F_Jc_W;
      r.M_Jc_W = o.M_Jc_W;
      r.F_Jc_B = o.F_Jc_B;
      r.M_Jc_B = o.M_Jc_B;
      r.power = o.power;
      out.reactions.push_back(r);
    }
  }
  if (model.num_contacts() > 0) {
    const std::vector<std::string> point_labels = scene.dynamics.contacts.point_labels();
    const std::vector<ContactPointOutput> outputs = CalcContactOutputs(model, state);
    for (int p = 0; p < model.num_contact_points(); ++p) {
      const ContactPointOutput& o = outputs[static_cast<size_t>(p)];
      const ContactPointState& ps = state.contacts[static_cast<size_t>(p)];
      out.contacts.push_back({point_labels[static_cast<size_t>(p)], ContactModeName(ps.mode),
                              o.normal_force, o.friction_force_W, o.slip_velocity_W, o.gap,
                              ps.friction_work, ps.rolling_work, ps.impact_work});
    }
  }
  for (int b = 0; b < model.num_bodies(); ++b) {
    const BodyState& s = state.bodies[static_cast<size_t>(b)];
    StudyBodyState f;
    f.name = model.body(b).name();
    f.mass = model.body(b).mass();
    f.inertia_max = model.body(b).I_BBcm_B().diagonal().maxCoeff();
    f.p_WBcm = s.p_WBcm;
    f.p_WBo = CalcBodyOriginPosition(model, state, b);
    f.q_WB = s.q_WB.w() < 0 ? Quat(-s.q_WB.coeffs()) : s.q_WB;
    f.v_WBcm_W = s.v_WBcm_W;
    f.w_WB_B = s.w_WB_B;
    f.w_WB_W = s.q_WB * s.w_WB_B;
    if (scene.planar) {
      // Planar bodies map one to one onto Model bodies (no embedding in a planar scene).
      const Mat3 R = s.q_WB.toRotationMatrix();
      f.theta = advance ? rows.Theta(b, R, f.w_WB_W.z(), state.t)
                        : rows.ThetaAt(b, R, f.w_WB_W.z(), state.t);
    }
    out.bodies.push_back(f);
  }
  return out;
}

}  // namespace

namespace {

/// The entry of the scene element called `name`; `before` is the message's text before the
/// quoted name, whose last words say the kind ("force element", "constraint", "contact point",
/// "body", "event"). Any kind matches when that kind has no such name; null when none has.
const SceneSpot* FindSceneEntry(const Scene& scene, const std::string& name,
                                std::string_view before) {
  const SceneDynamics& d = scene.dynamics;
  const auto ends_with = [&](std::string_view w) {
    return before.size() >= w.size() && before.substr(before.size() - w.size()) == w;
  };
  const auto force = [&]() -> const SceneSpot* {
    for (const SceneForce& f : d.forces) {
      if (f.name == name) return &f.where;
    }
    return nullptr;
  };
  const auto constraint = [&]() { return d.constraints.Find(name); };
  const auto contact = [&]() -> const SceneSpot* {
    for (const SceneContact& c : d.contacts.contacts) {
      if (c.name == name || name.rfind(c.name + "[", 0) == 0) return &c.where;
      for (const std::string& label : ContactPointLabels(c)) {
        if (label == name) return &c.where;
      }
    }
    return nullptr;
  };
  const auto body = [&]() -> const SceneSpot* {
    for (const SceneBody& b : scene.bodies) {
      if (b.name == name) return &b.where;
    }
    return nullptr;
  };
  const auto event = [&]() -> const SceneSpot* {
    for (const SceneEvent& e : d.events) {
      if (e.name == name) return &e.where;
    }
    return nullptr;
  };
  const SceneSpot* spot = nullptr;
  if (ends_with("force element ") || ends_with("spring ") || ends_with("force ")) {
    spot = force();
  } else if (ends_with("contact point ") || ends_with("contact ")) {
    spot = contact();
  } else if (ends_with("body ")) {
    spot = body();
  } else if (ends_with("event ")) {
    spot = event();
  }
  if (!spot) spot = constraint();
  if (!spot) spot = force();
  if (!spot) spot = contact();
  if (!spot) spot = body();
  if (!spot) spot = event();
  return spot;
}

}  // namespace

void ThrowAtSceneEntry(const Scene& scene, const InputError& error) {
  if (const auto* located = dynamic_cast<const SceneError*>(&error)) throw *located;
  // The first quoted name in the message that is an element of the scene.
  const std::string what = error.what();
  const SceneSpot* spot = nullptr;
  size_t at = 0;
  while (!spot && (at = what.find('\'', at)) != std::string::npos) {
    const size_t end = what.find('\'', at + 1);
    if (end == std::string::npos) break;
    spot = FindSceneEntry(scene, what.substr(at + 1, end - at - 1),
                          std::string_view(what).substr(0, at));
    at = end + 1;
  }
  // Naming none, it is about the run as the `simulation` block sets it up.
  if (!spot) spot = &scene.dynamics.simulation.where;
  throw SceneError(scene.file, spot->line, spot->column, spot->key, what);
}

Study BuildStudy(const Scene& scene, double until) {
  try {
    const double t_end = EndTime(scene, until);
    CheckPhysicalInputs(scene, t_end);
    Segment seg = FirstSegment(scene);
    Study study;
    study.model = std::shared_ptr<const Model>(std::move(seg.model));  // same address
    study.options = BaseOptions(scene, t_end);
    // On the constraints, or an error, or projected with each change a warning.
    study.initial = scene_internal::SettleInitialState(
        scene, *study.model, InitialState(scene, *study.model), study.warnings);
    study.options.events = BuildEvents(scene, seg.model_ref, seg.map);
    return study;
  } catch (const InputError& e) {
    ThrowAtSceneEntry(scene, e);
  }
}

namespace {
StudyResult RunStudyUnlocated(const Scene& scene, const StudyOptions& options);
}  // namespace

StudyResult RunStudy(const Scene& scene, const StudyOptions& options) {
  try {
    return RunStudyUnlocated(scene, options);
  } catch (const InputError& e) {
    ThrowAtSceneEntry(scene, e);
  }
}

namespace {

StudyResult RunStudyUnlocated(const Scene& scene, const StudyOptions& options) {
  const double t_end = EndTime(scene, options.until);
  CheckPhysicalInputs(scene, t_end);
  const RunLimits limits = ResolveLimits(scene, options, t_end);
  CheckLimitsUpFront(scene, limits, t_end, BaseOptions(scene, t_end).output_interval);
  const auto started = std::chrono::steady_clock::now();
  std::int64_t steps_taken = 0;
  const SceneDynamics& d = scene.dynamics;
  StudyResult result;
  result.integrator = IntegratorName(d.simulation.integrator);

  RowMaker rows{scene, {}, false, {}};
  const std::vector<ColumnInfo> all = AllColumns(scene);
  for (const std::string& name : d.columns) {
    for (const ColumnInfo& c : all) {
      if (c.name == name) {
        rows.columns.push_back(c);
        if ((c.quantity[0] == 'a' && c.body >= 0) || c.group == "reactions" ||
            c.group == "contacts") {
          rows.needs_accelerations = true;
        }
        break;
      }
    }
  }
  for (const ColumnInfo& c : rows.columns) result.columns.push_back(c.name);

  Segment seg = FirstSegment(scene);
  State state = scene_internal::SettleInitialState(
      scene, *seg.model, InitialState(scene, *seg.model), result.warnings);
  CheckFinite(*seg.model, state);
  const std::vector<std::string> point_labels = d.contacts.point_labels();
  auto record_impacts = [&](const ImpactResult& r, double t) {
    for (const ContactImpulse& imp : r.impulses) {
      result.impacts.push_back({t, point_labels[static_cast<size_t>(imp.point)], imp.approach_speed,
                                imp.normal_impulse,
                                r.kinetic_energy_before - r.kinetic_energy_after, false,
                                std::numeric_limits<double>::quiet_NaN(), false,
                                RestitutionLawName(imp.law), r.frictionless_fallback});
    }
  };
  auto record_changes = [&](const std::vector<ContactModeChange>& changes, double t,
                            const char* reason) {
    for (const ContactModeChange& c : changes) {
      const Model& m = *seg.model;
      result.contact_events.push_back({t, point_labels[static_cast<size_t>(c.point)],
                                       m.contact(m.contact_of_point(c.point)).name(),
                                       ContactModeName(c.from), ContactModeName(c.to), reason});
    }
  };
  // Contacts that approach at t = 0 take their impact first; then every contact point gets a
  // consistent initial mode, so that the first output row already shows it.
  auto settle_contacts = [&](const char* reason) {
    if (seg.model->num_contacts() == 0) return;
    const ContactTolerances tol;
    const ImpactResult impacts = ResolveImpacts(*seg.model, state, tol);
    record_impacts(impacts, state.t);
    ModeSelectionNotes notes;
    record_changes(SelectContactModes(*seg.model, state, tol, {}, &notes), state.t, reason);
    for (const JamImpulse& j : notes.jams) {
      result.impacts.push_back({state.t, point_labels[static_cast<size_t>(j.point)], 0.0,
                                j.normal_impulse, j.energy_lost, false,
                                std::numeric_limits<double>::quiet_NaN(), true, "", false});
      result.warnings.push_back(fmt::format(
          "contact point '{}' at t = {:.9g} s: sliding at {:.6g} m/s, the contact forces had "
          "no consistent solution (a Painlevé-type paradox); the slip was stopped by an "
          "impulsive jam (an impact without collision) that took {:.6g} J",
          point_labels[static_cast<size_t>(j.point)], state.t, j.slip_speed, j.energy_lost));
    }
  };
  // The ledger starts from the state as given: an impact or a jam at t = 0 is part of it.
  if (seg.model->num_contacts() > 0) {
    state.contacts.assign(static_cast<size_t>(seg.model->num_contact_points()),
                          ContactPointState{});
  }
  const State as_given = state;
  if (seg.model->num_contacts() > 0) {
    settle_contacts("initial");
    // Every point's initial mode is part of the timeline, changed or not.
    for (int p = 0; p < seg.model->num_contact_points(); ++p) {
      const bool listed = std::any_of(result.contact_events.begin(), result.contact_events.end(),
                                      [&](const StudyContactEvent& e) {
                                        return e.point == point_labels[static_cast<size_t>(p)];
                                      });
      if (!listed) {
        const ContactMode m = state.contacts[static_cast<size_t>(p)].mode;
        result.contact_events.push_back({state.t, point_labels[static_cast<size_t>(p)],
                                         seg.model->contact(seg.model->contact_of_point(p)).name(),
                                         ContactModeName(m), ContactModeName(m), "initial"});
      }
    }
  }
  LedgerCarry carry;
  carry.segment_initial = as_given;
  const double E0 = MechanicalEnergy(*seg.model, as_given);
  result.rows.push_back(rows.Row(*seg.model, *seg.map, state, carry));
  // The certificate: every sample, event and contact transition is checked (the ledger with
  // the residual carried across the segments).
  CertificateBuilder certificate(CertificateTolerancesFor(scene));
  auto certify = [&](const State& s, CheckPhase phase) {
    certificate.CheckState(*seg.model, s, phase);
    const LedgerSample L = CalcLedgerSample(*seg.model, s, carry.segment_initial);
    certificate.CheckLedger(s.t, carry.residual + L.energy_residual,
                            std::max(carry.scale, L.energy_scale), phase);
  };
  certify(state, CheckPhase::kSample);
  SlipWatch slip(scene);
  slip.Sample(*seg.model, state);

  // Impulses and impacts in time order (stable: the file's order at equal times).
  struct Jump {
    double t;
    const SceneImpulse* impulse;
    const SceneImpact* impact;
  };
  std::vector<Jump> jumps;
  for (const auto& i : d.impulses) jumps.push_back({i.t, &i, nullptr});
  for (const auto& i : d.impacts) jumps.push_back({i.t, nullptr, &i});
  std::stable_sort(jumps.begin(), jumps.end(),
                   [](const Jump& a, const Jump& b) { return a.t < b.t; });

  SimulationOptions base = BaseOptions(scene, t_end);
  base.adaptive.min_step = limits.min_step;
  const double dt_out = base.output_interval;
  bool stopped = false;
  const SceneSimulation& sim = d.simulation;
  // Every accepted step of every segment counts against the step limit and the wall time.
  const auto on_step = [&](double t) {
    if (options.progress) options.progress(t);
    if (++steps_taken > limits.max_steps) {
      ThrowLimit(scene, sim.Spot("max_steps"), "max_steps", "--max-steps",
                 fmt::format("the run reached the limit of {} integration steps at t = {:.9g} s "
                             "(of {:.9g} s)",
                             limits.max_steps, t, t_end),
                 "loosen 'tolerance', shorten the run, or ");
    }
    if (limits.timeout > 0) {
      const std::chrono::duration<double> used = std::chrono::steady_clock::now() - started;
      if (used.count() > limits.timeout) {
        ThrowLimit(scene, sim.Spot("timeout"), "timeout", "--timeout",
                   fmt::format("the run reached its wall-time limit of {:g} s at t = {:.9g} s "
                               "(of {:.9g} s) after {} steps (a limit of 0 s turns it off)",
                               limits.timeout, t, t_end, steps_taken));
      }
    }
  };

  // Integrates from state.t to t_b, sampling on the global grid k * dt_out.
  auto run_to = [&](double t_b) {
    while (state.t < t_b && !stopped) {
      const double k = std::ceil(state.t / dt_out - 1e-9);
      const double next_grid = k * dt_out;
      const bool on_grid = std::abs(next_grid - state.t) <= 1e-9 * dt_out;
      SimulationOptions o = base;
      o.t_end = on_grid ? t_b : std::min(next_grid, t_b);
      o.output_interval = on_grid ? dt_out : 0.0;
      o.events = BuildEvents(scene, seg.model_ref, seg.map);
      o.store_samples = false;
      o.on_step = on_step;
      bool first = true;
      o.on_sample = [&](const State& s) {
        if (first) {
          first = false;
          return;
        }
        if (static_cast<std::int64_t>(result.rows.size()) >= limits.max_rows) {
          ThrowLimit(scene, sim.Spot("max_rows"), "max_rows", "--max-rows",
                     fmt::format("the run reached the limit of {} output rows at t = {:.9g} s",
                                 limits.max_rows, s.t),
                     "choose a longer 'output_interval' or ");
        }
        CheckFinite(*seg.model, s);
        result.rows.push_back(rows.Row(*seg.model, *seg.map, s, carry));
        certify(s, CheckPhase::kSample);
        slip.Sample(*seg.model, s);
        if (options.progress) options.progress(s.t);
      };
      o.on_transition = [&](const State& before, const State& after) {
        certify(before, CheckPhase::kBeforeTransition);
        certify(after, CheckPhase::kAfterTransition);
      };
      SimulationResult r;
      const double t_from = state.t;
      // Modes carried into this run: its "initial" records that only restate them are dropped.
      std::vector<ContactMode> carried(state.contacts.size());
      for (size_t p = 0; p < carried.size(); ++p) carried[p] = state.contacts[p].mode;
      try {
        r = Simulate(*seg.model, state, o);
      } catch (const SceneError&) {
        throw;  // a limit, already located
      } catch (const LimitError& e) {
        // The adaptive step fell below the smallest step.
        ThrowLimit(scene, sim.Spot("min_step"), "min_step", "--min-step", e.what(),
                   "check the forces and masses for a singularity, or ", "lower");
      } catch (const InputError& e) {
        const double t_last = result.rows.empty() ? t_from : result.rows.back().front();
        throw InputError(fmt::format("the run stopped after t = {:.9g} s: {}", t_last, e.what()));
      }
      CheckFinite(*seg.model, r.final_state);
      result.stats.steps += r.stats.steps;
      result.stats.rejected_steps += r.stats.rejected_steps;
      result.stats.function_evaluations += r.stats.function_evaluations;
      for (const EventRecord& e : r.events) {
        const bool stop = d.events[static_cast<size_t>(e.event)].action == EventAction::kStop;
        certify(e.state, CheckPhase::kEvent);
        result.events.push_back(
            {e.name, e.t, stop, MakeSnapshot(scene, *seg.model, e.state, rows, false)});
      }
      for (const ContactEvent& e : r.contact_events) {
        // The modes carried into this run are already in the timeline: Simulate lists every
        // point's starting mode (as a change from separated); only a mode it chose
        // differently from the one carried in is news.
        ContactMode from = e.from;
        if (e.reason == ContactEventReason::kInitial) {
          const auto p = static_cast<size_t>(e.point);
          from = p < carried.size() ? carried[p] : ContactMode::kSeparated;
          if (from == e.to) continue;
        }
        const Model& m = *seg.model;
        result.contact_events.push_back({e.t, point_labels[static_cast<size_t>(e.point)],
                                         m.contact(m.contact_of_point(e.point)).name(),
                                         ContactModeName(from), ContactModeName(e.to),
                                         ContactEventReasonName(e.reason)});
      }
      for (const ImpactRecord& imp : r.impacts) {
        result.impacts.push_back({imp.t, point_labels[static_cast<size_t>(imp.point)],
                                  imp.approach_speed, imp.normal_impulse, imp.energy_lost,
                                  imp.accumulation, imp.accumulation_time, imp.jam,
                                  RestitutionLawName(imp.law), imp.frictionless_fallback});
      }
      result.warnings.insert(result.warnings.end(), r.warnings.begin(), r.warnings.end());
      state = r.final_state;
      if (r.stopped_by_event) stopped = true;
    }
  };

  auto close_segment = [&]() {
    const LedgerSample L = CalcLedgerSample(*seg.model, state, carry.segment_initial);
    carry.work_nc += L.work_nonconservative;
    carry.dissipated += L.dissipated;
    carry.residual += L.energy_residual;
    carry.scale = std::max(carry.scale, L.energy_scale);
    for (const ForceLedger& f : L.forces) carry.work_by_force[f.name] += f.work_nonconservative;
    for (const ConstraintLedger& f : L.constraints) carry.work_by_force[f.name] += f.work;
  };

  for (const Jump& j : jumps) {
    if (j.t > t_end) {
      result.notes.push_back(
          fmt::format("an impulse or impact at t = {:.6g} s is after the end "
                      "time {:.6g} s and was not applied",
                      j.t, t_end));
      continue;
    }
    run_to(j.t);
    if (stopped) break;
    close_segment();
    const double E_before = MechanicalEnergy(*seg.model, state);
    StudyJump rec;
    rec.t = state.t;
    int shown_body = 0;
    if (j.impulse) {
      const SceneImpulse& imp = *j.impulse;
      const Placement& pl = seg.map->place[static_cast<size_t>(imp.body)];
      const Mat3 R_WM = state.bodies[static_cast<size_t>(pl.model_body)].q_WB.toRotationMatrix();
      const Vec3 J_W = imp.frame == VectorFrame::kWorld ? imp.J : Vec3(R_WM * pl.R_MB * imp.J);
      ApplyImpulse(*seg.model, pl.model_body, pl.R_MB * imp.p_BoP_B + pl.p_MoBo_M, J_W, state);
      rec.kind = "impulse";
      rec.description =
          fmt::format("impulse on {}", scene.bodies[static_cast<size_t>(imp.body)].name);
      shown_body = pl.model_body;
    } else {
      const SceneImpact& imp = *j.impact;
      const std::string& tname = scene.bodies[static_cast<size_t>(imp.target)].name;
      const std::string& pname = scene.bodies[static_cast<size_t>(imp.projectile)].name;
      const int mt = seg.map->place[static_cast<size_t>(imp.target)].model_body;
      const int mp = seg.map->place[static_cast<size_t>(imp.projectile)].model_body;
      if (mt == mp) {
        throw InputError(
            fmt::format("impact at t = {:.6g} s: '{}' and '{}' are already one body "
                        "(an earlier impact embedded one in the other)",
                        imp.t, pname, tname));
      }
      const BodyState& sp = state.bodies[static_cast<size_t>(mp)];
      if (imp.exit_fraction > 0) {
        const Vec3 v_p = sp.v_WBcm_W;
        ApplyPassThrough(*seg.model, mt, sp.p_WBcm, seg.model->body(mp).mass(), v_p,
                         imp.exit_fraction, state);
        state.bodies[static_cast<size_t>(mp)].v_WBcm_W = imp.exit_fraction * v_p;
        rec.kind = "pass-through";
        rec.description = fmt::format("{} passes through {} keeping {:.4g} of its velocity", pname,
                                      tname, imp.exit_fraction);
        shown_body = mt;
      } else {
        auto motion = [&](int m) {
          const BodyState& s = state.bodies[static_cast<size_t>(m)];
          BodyMotion bm;
          bm.mass_properties = seg.model->body(m).mass_properties();
          bm.R_WB = s.q_WB.toRotationMatrix();
          bm.p_WBcm = s.p_WBcm;
          bm.v_WBcm_W = s.v_WBcm_W;
          bm.w_WB_W = bm.R_WB * s.w_WB_B;
          return bm;
        };
        const BodyMotion target = motion(mt), projectile = motion(mp);
        const EmbeddingResult e = CalcEmbedding(target, projectile);
        // Re-place the projectile's scene bodies in the target's frame:
        // R_TB = R_WTᵀ R_WP R_PB,  p_ToBo_T = R_WTᵀ (p_WPo + R_WP p_PoBo_P - p_WTo).
        const Vec3 p_WTo = CalcBodyOriginPosition(*seg.model, state, mt);
        const Vec3 p_WPo = CalcBodyOriginPosition(*seg.model, state, mp);
        auto map = std::make_shared<BodyMap>(*seg.map);
        for (Placement& pl : map->place) {
          if (pl.model_body == mp) {
            pl.p_MoBo_M = target.R_WB.transpose() * (p_WPo + projectile.R_WB * pl.p_MoBo_M - p_WTo);
            pl.R_MB = target.R_WB.transpose() * projectile.R_WB * pl.R_MB;
            pl.model_body = mt;
          }
          if (pl.model_body > mp) --pl.model_body;
        }
        Segment next;
        next.map = map;
        for (int m = 0; m < seg.model->num_bodies(); ++m) {
          if (m == mp) continue;
          if (m == mt) {
            next.bodies.emplace_back(seg.bodies[static_cast<size_t>(mt)].first + "+" +
                                         seg.bodies[static_cast<size_t>(mp)].first,
                                     e.composite.mass_properties);
          } else {
            next.bodies.push_back(seg.bodies[static_cast<size_t>(m)]);
          }
        }
        next.Build(scene);
        State s2 = MakeRestState(*next.model);
        s2.t = state.t;
        int k = 0;
        for (int m = 0; m < seg.model->num_bodies(); ++m) {
          if (m == mp) continue;
          if (m == mt) {
            BodyState& c = s2.bodies[static_cast<size_t>(k)];
            c.p_WBcm = e.composite.p_WBcm;
            c.q_WB = Quat(e.composite.R_WB).normalized();
            c.v_WBcm_W = e.composite.v_WBcm_W;
            c.w_WB_B = e.composite.R_WB.transpose() * e.composite.w_WB_W;
            shown_body = k;
          } else {
            s2.bodies[static_cast<size_t>(k)] = state.bodies[static_cast<size_t>(m)];
          }
          ++k;
        }
        seg = std::move(next);
        state = std::move(s2);
        rec.kind = "embedding";
        rec.description = fmt::format("{} embeds in {}", pname, tname);
      }
    }
    if (seg.model->num_constraints() > 0) {
      // The supports' impulsive reaction: projecting the velocities onto the constraints with
      // the mass metric, du = -M⁻¹ Jᵀ μ, is exactly the response of ideal constraints to the
      // impulse (impulse-momentum with the constraint impulse Jᵀ μ).
      Data data = MakeData(*seg.model);
      ProjectOntoConstraints(*seg.model, state, data);
    }
    // A contact the jump drives into its plane takes an impact; then the modes are chosen
    // again for the new velocities (a sticking point may now slip).
    settle_contacts("impulse");
    CheckFinite(*seg.model, state);
    rec.energy_before = E_before;
    rec.energy_after = MechanicalEnergy(*seg.model, state);
    const BodyState& shown = state.bodies[static_cast<size_t>(shown_body)];
    rec.v_after_W = shown.v_WBcm_W;
    rec.w_after_W = shown.q_WB * shown.w_WB_B;
    carry.jumps += rec.energy_after - rec.energy_before;
    carry.scale = std::max({carry.scale, std::abs(rec.energy_before), std::abs(rec.energy_after)});
    carry.segment_initial = state;
    result.jumps.push_back(rec);
    result.rows.push_back(rows.Row(*seg.model, *seg.map, state, carry));
    certify(state, CheckPhase::kSample);
  }
  if (!stopped) run_to(t_end);

  // Final ledger.
  const Model& model = *seg.model;
  const LedgerSample L = CalcLedgerSample(model, state, carry.segment_initial);
  StudyLedger& out = result.ledger;
  out.kinetic_translational = L.kinetic_translational;
  out.kinetic_rotational = L.kinetic_rotational;
  out.potential = L.potential;
  out.energy = L.mechanical_energy;
  out.energy_initial = E0;
  out.work_nonconservative = carry.work_nc + L.work_nonconservative;
  out.dissipated = carry.dissipated + L.dissipated;
  for (const ContactPointState& p : state.contacts) {
    out.friction_work += p.friction_work;
    out.rolling_work += p.rolling_work;
    out.impact_work += p.impact_work;
  }
  out.jumps = carry.jumps;
  out.residual = carry.residual + L.energy_residual;
  out.energy_scale = std::max(carry.scale, L.energy_scale);
  for (const SceneForce& f : d.forces) {
    double w = carry.work_by_force.count(f.name) ? carry.work_by_force.at(f.name) : 0.0;
    for (const ForceLedger& fl : L.forces) {
      if (fl.name == f.name) w += fl.work_nonconservative;
    }
    out.work_by_force.emplace_back(f.name, w);
  }
  // The plane constraints of a planar scene come after the scene's own; they are left out of
  // its reports (their reactions are out of plane, not physical for a planar body).
  const size_t num_scene_constraints = d.constraints.names().size();
  for (const ConstraintLedger& cl : L.constraints) {
    if (out.work_by_constraint.size() == num_scene_constraints) break;
    const double w =
        (carry.work_by_force.count(cl.name) ? carry.work_by_force.at(cl.name) : 0.0) + cl.work;
    out.work_by_constraint.emplace_back(cl.name, w);
  }
  if (model.num_constraints() > 0) {
    Data data = MakeData(model);
    CalcAccelerations(model, state, data);
    if (data.constraint_rank < model.num_constraint_rows()) {
      Data scratch = MakeData(model);
      for (std::string& w : DescribeRedundancy(model, AnalyseRedundancy(model, state, scratch))) {
        result.warnings.push_back(std::move(w));
      }
    }
  }
  StudySnapshot final_snapshot = MakeSnapshot(scene, model, state, rows, true);
  result.final_reactions = std::move(final_snapshot.reactions);
  result.final_contacts = std::move(final_snapshot.contacts);
  result.final_bodies = std::move(final_snapshot.bodies);
  out.linear_momentum_W = L.linear_momentum_W;
  out.angular_momentum_Scm_W = L.angular_momentum_Scm_W;
  out.angular_momentum_Wo_W = L.angular_momentum_Wo_W;

  slip.Report(result.notes);
  result.certificate = certificate.Finish();
  result.t_end = state.t;
  result.stopped_by_event = stopped;
  return result;
}

}  // namespace

}  // namespace chasles
