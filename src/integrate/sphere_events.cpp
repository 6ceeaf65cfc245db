// Event-driven spheres on a level plane (docs/contact.md, "Event-driven spheres"): the event
// queue and the run. The other parts: see integrate/internal/sphere_runner.h.
#include "chasles/integrate/sphere_events.h"

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/model/forces.h"
#include "integrate/internal/collision_law.h"
#include "integrate/internal/sphere_runner.h"

namespace chasles {

using namespace sphere_events_detail;

ModelObstacle SphereEventObstacle(const Model& model) {
  if (model.num_constraints() > 0) return {"the model has constraints", {}};
  Vec3 g = Vec3::Zero();
  for (int e = 0; e < model.num_force_elements(); ++e) {
    const auto* ug = dynamic_cast<const UniformGravity*>(&model.force_element(e));
    if (ug == nullptr) {
      return {
          fmt::format("force element '{}' is not uniform gravity", model.force_element(e).name()),
          ErrorElement{ErrorElement::Kind::kForceElement, e}};
    }
    g += ug->g_W();
  }
  if (!(g.norm() > 0.0)) return {"there is no gravity to press the balls on the plane", {}};
  std::vector<int> plane_of(static_cast<size_t>(model.num_bodies()), -1);
  Vec3 n = Vec3::Zero(), p0 = Vec3::Zero();
  bool have_plane = false;
  for (int c = 0; c < model.num_contacts(); ++c) {
    const Contact& con = model.contact(c);
    const ContactSpec& s = con.spec();
    const Body& body = model.body(s.body);
    if (s.shape == ContactShape::kSphereSphere) continue;
    if (s.shape != ContactShape::kSphere) {
      return {fmt::format("contact '{}' is a {}, not a sphere on the plane", con.name(),
                          ContactShapeName(s.shape)),
              ErrorElement{ErrorElement::Kind::kContact, c}};
    }
    if ((s.p_BoC_B - body.p_BoBcm_B()).norm() > 1e-12 * s.radius) {
      return {fmt::format("contact '{}': the sphere is not centred at body '{}''s centre of mass",
                          con.name(), body.name()),
              ErrorElement{ErrorElement::Kind::kContact, c}};
    }
    if (plane_of[static_cast<size_t>(s.body)] >= 0) {
      return {fmt::format("body '{}' has two plane contacts", body.name()),
              ErrorElement{ErrorElement::Kind::kBody, s.body}};
    }
    plane_of[static_cast<size_t>(s.body)] = c;
    const Vec3 nc = s.plane_normal_W.normalized();
    if (!have_plane) {
      n = nc;
      p0 = s.plane_point_W;
      have_plane = true;
    } else if ((nc - n).norm() > 1e-12 || std::abs(n.dot(s.plane_point_W - p0)) > 1e-12) {
      return {fmt::format("contact '{}' is on another plane than the first contact's", con.name()),
              ErrorElement{ErrorElement::Kind::kContact, c}};
    }
  }
  if (!have_plane) return {"no body has a sphere contact with a plane", {}};
  if ((g / g.norm() + n).norm() > 1e-12) {
    return {"gravity is not normal to the plane (a tilted table)", {}};
  }
  for (int b = 0; b < model.num_bodies(); ++b) {
    const Body& body = model.body(b);
    if (plane_of[static_cast<size_t>(b)] < 0) {
      return {fmt::format("body '{}' has no sphere contact with the plane", body.name()),
              ErrorElement{ErrorElement::Kind::kBody, b}};
    }
    const Mat3& I = body.I_BBcm_B();
    const double i0 = I.trace() / 3.0;
    if (!(i0 > 0.0) || (I - i0 * Mat3::Identity()).norm() > 1e-12 * i0) {
      return {fmt::format("body '{}' has no isotropic inertia about its centre of mass (a ball)",
                          body.name()),
              ErrorElement{ErrorElement::Kind::kBody, b}};
    }
    const Contact& con = model.contact(plane_of[static_cast<size_t>(b)]);
    const double kappa = body.mass() * con.spec().radius * con.spec().radius / i0;
    if (con.mu_r() / (1.0 + 1.0 / kappa) > con.mu_s()) {
      return {fmt::format("contact '{}': rolling resistance mu_r = {} needs more friction than "
                          "mu_s = {} holds (it would roll and slip)",
                          con.name(), con.mu_r(), con.mu_s()),
              ErrorElement{ErrorElement::Kind::kContact, plane_of[static_cast<size_t>(b)]}};
    }
  }
  for (int c = 0; c < model.num_contacts(); ++c) {
    const ContactSpec& s = model.contact(c).spec();
    if (s.shape != ContactShape::kSphereSphere) continue;
    const auto fits = [&](BodyIndex body, const Vec3& p, double r) {
      const ContactSpec& ps = model.contact(plane_of[static_cast<size_t>(body)]).spec();
      return (p - model.body(body).p_BoBcm_B()).norm() <= 1e-12 * r &&
             std::abs(r - ps.radius) <= 1e-12 * r;
    };
    if (!fits(s.body, s.p_BoC_B, s.radius) || !fits(s.other_body, s.p_OoC_O, s.other_radius)) {
      return {fmt::format("contact '{}': its spheres are not the balls' own (same radius, "
                          "centred at the centres of mass)",
                          model.contact(c).name()),
              ErrorElement{ErrorElement::Kind::kContact, c}};
    }
  }
  return {};
}

namespace sphere_events_detail {

void Runner::ReadModel() {
  const ModelObstacle obstacle = SphereEventObstacle(model_);
  if (!obstacle.empty()) {
    throw InputError(
        fmt::format("the event-driven sphere path cannot run this model: {}", obstacle.why),
        obstacle.element);
  }
  for (int e = 0; e < model_.num_force_elements(); ++e) {
    w_.g_W += static_cast<const UniformGravity&>(model_.force_element(e)).g_W();
    gravity_elements_.push_back(e);
  }
  w_.g = w_.g_W.norm();
  w_.tol = options_.tolerances;
  const int nb = model_.num_bodies();
  balls_.resize(static_cast<size_t>(nb));
  for (int c = 0; c < model_.num_contacts(); ++c) {
    const Contact& con = model_.contact(c);
    const ContactSpec& s = con.spec();
    if (s.shape == ContactShape::kSphereSphere) {
      listed_pairs_[PairKey(s.body, s.other_body)] = c;
      continue;
    }
    Ball& b = balls_[static_cast<size_t>(s.body)];
    const Body& body = model_.body(s.body);
    b.body = s.body;
    b.point = model_.contact_point_offset(c);
    b.m = body.mass();
    b.R = s.radius;
    b.I = body.I_BBcm_B().trace() / 3.0;
    b.kappa = b.m * b.R * b.R / b.I;
    b.mu_s = s.mu_s;
    b.mu_k = s.mu_k;
    b.mu_r = s.mu_r;
    w_.n = s.plane_normal_W.normalized();
    w_.p0 = s.plane_point_W;
    R_max_ = std::max(R_max_, b.R);
  }
  w_.e1 = (std::abs(w_.n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(w_.n).normalized();
  w_.e2 = w_.n.cross(w_.e1);
  cell_ = 4.0 * R_max_;
}

// The segment ball b starts at t from (r, v, ω, q): on the plane when it touches it (gap
// within tol.gap) with a normal velocity within resting_speed (then removed); otherwise in
// flight, which for a ball touching and moving into the plane ends at once in an impact.
Segment Runner::Restart(int b, double t, const Vec3& r, const Vec3& v, const Vec3& om,
                        const Quat& q) const {
  const Ball& ball = balls_[static_cast<size_t>(b)];
  const double gap = w_.n.dot(r - w_.p0) - ball.R;
  const bool on_plane = gap <= w_.tol.gap && std::abs(w_.n.dot(v)) <= w_.tol.resting_speed;
  return StartSegment(ball, w_, t, r, v, om, q, on_plane);
}

void Runner::BeginChain(int i, const Segment& s) {
  chain_[static_cast<size_t>(i)] = MakeChain(balls_[static_cast<size_t>(i)], w_, s);
  ++ver_[static_cast<size_t>(i)];
  const Chain& c = chain_[static_cast<size_t>(i)];
  const std::uint32_t v = ver_[static_cast<size_t>(i)];
  for (int k = 0; k + 1 < c.count; ++k) {
    Schedule({c.seg[static_cast<size_t>(k)].end(), Kind::kPhase, i, -1, v, 0, 0});
  }
  if (std::isfinite(c.known_until)) Schedule({c.known_until, Kind::kLanding, i, -1, v, 0, 0});
  RenewBox(i, s.t0);
}

// Books ball i's ledger from its last booked time to t along its chain (closed forms per
// segment): sliding friction's work -mu_k m g ∫|u| = -mu_k m g (|u0| τ - ½ k τ²) with
// k = mu_k g (1 + m R²/I); rolling resistance's -mu_r m g ∫|v|; gravity's work m g·Δr, impulse
// m g τ and moment of impulse about Wo, ∫ r × m g = (r0 τ + v0 τ²/2 + a τ³/6) × m g.
void Runner::CloseSegment(int i, double t) {
  const auto iu = static_cast<size_t>(i);
  const Ball& b = balls_[iu];
  const Chain& c = chain_[iu];
  double from = booked_until_[iu];
  for (int k = 0; k < c.count && from < t; ++k) {
    const Segment& s = c.seg[static_cast<size_t>(k)];
    if (s.end() <= from && k + 1 < c.count) continue;
    const double ta = from - s.t0, tb = std::min(t, s.end()) - s.t0;
    if (tb <= ta) continue;
    ContactPointState& cp = ledger_.contacts[static_cast<size_t>(b.point)];
    if (s.phase == Phase::kSliding && b.mu_k > 0.0) {
      const double kk = b.mu_k * w_.g * (1.0 + b.kappa);
      const auto I = [&](double x) { return s.slip0 * x - 0.5 * kk * x * x; };
      const double work = -b.mu_k * b.m * w_.g * (I(tb) - I(ta));
      cp.friction_work += work;
      res_.energy.friction += work;
    } else if (s.phase == Phase::kRolling && b.mu_r > 0.0) {
      const double v0 = s.v0.norm(), ar = s.a.norm();
      const auto I = [&](double x) { return v0 * x - 0.5 * ar * x * x; };
      const double work = -b.mu_r * b.m * w_.g * (I(tb) - I(ta));
      cp.rolling_work += work;
      res_.energy.rolling += work;
    }
    const auto integral_r = [&](double x) {
      return Vec3(s.r0 * x + s.v0 * (x * x / 2.0) + s.a * (x * x * x / 6.0));
    };
    const Vec3 dr = s.Pos(s.t0 + tb) - s.Pos(s.t0 + ta);
    const Vec3 int_r = integral_r(tb) - integral_r(ta);
    for (const int e : gravity_elements_) {
      const Vec3 ge = static_cast<const UniformGravity&>(model_.force_element(e)).g_W();
      ForceIntegrals& fi = ledger_.force_integrals[static_cast<size_t>(e)];
      fi.work += b.m * ge.dot(dr);
      fi.linear_impulse_W += b.m * ge * (tb - ta);
      fi.angular_impulse_Wo_W += int_r.cross(b.m * ge);
    }
    from = s.t0 + tb;
  }
  booked_until_[iu] = t;
}

State Runner::StateAt(double t) const {
  State s = ledger_;
  s.t = t;
  for (size_t i = 0; i < balls_.size(); ++i) {
    if (group_of_[i] >= 0) {  // brought to t by the caller
      const Group& g = groups_[static_cast<size_t>(group_of_[i])];
      const auto m = static_cast<size_t>(
          std::find(g.members.begin(), g.members.end(), static_cast<int>(i)) - g.members.begin());
      s.bodies[i] = g.states[m];
      ContactPointState& cp = s.contacts[static_cast<size_t>(balls_[i].point)];
      cp.mode = g.modes[m].mode;
      cp.rolling_held = g.modes[m].rolling_held;
      continue;
    }
    const Segment& seg = chain_[i].At(t);
    BodyState& bs = s.bodies[i];
    bs.p_WBcm = seg.Pos(t);
    bs.v_WBcm_W = seg.Vel(t);
    const Vec3 om = seg.Omega(t);
    bs.q_WB = ChainOrient(chain_[i], t);
    bs.w_WB_B = bs.q_WB.conjugate() * om;
    ContactPointState& cp = s.contacts[static_cast<size_t>(balls_[i].point)];
    cp.mode = ModeOfPhase(seg.phase);
    cp.slip_direction_W = seg.phase == Phase::kSliding ? seg.s_hat : Vec3::Zero();
    // The rolling reference, as the hybrid engine writes it (rolling resistance's moment in the
    // contact outputs): the direction of the rolling angular velocity n × v / R.
    const Vec3 v_plane = bs.v_WBcm_W - w_.n.dot(bs.v_WBcm_W) * w_.n;
    cp.rolling_direction_W =
        seg.phase == Phase::kRolling && balls_[i].mu_r > 0.0 && v_plane.norm() > w_.tol.stick_speed
            ? Vec3(w_.n.cross(v_plane).normalized())
            : Vec3::Zero();
    // At rest on the level table, rolling resistance holds the rolling (a moment of zero).
    cp.rolling_held = seg.phase == Phase::kRest && balls_[i].mu_r > 0.0;
  }
  return s;
}

// One event off the queue (stale ones, whose ball has a new chain, are dropped).
void Runner::Handle(const Event& e) {
  const size_t n = balls_.size();
  const auto iu = static_cast<size_t>(std::max(e.i, 0));
  switch (e.kind) {
    case Kind::kSample: {
      for (size_t g = 0; g < groups_.size(); ++g) {
        if (groups_[g].alive) Advance(static_cast<int>(g), e.t);
      }
      for (size_t i = 0; i < n; ++i) {
        if (group_of_[i] < 0) CloseSegment(static_cast<int>(i), e.t);
      }
      res_.samples.push_back(StateAt(e.t));
      break;
    }
    case Kind::kPhase: {
      if (e.ver_i != ver_[iu]) break;
      const Chain& c = chain_[iu];
      // The segment ending at e.t and the one after it.
      int k = 0;
      while (k + 1 < c.count && c.seg[static_cast<size_t>(k)].end() != e.t) ++k;
      const Segment& s0 = c.seg[static_cast<size_t>(k)];
      const Segment& s1 = c.seg[static_cast<size_t>(std::min(k + 1, c.count - 1))];
      ++res_.stats.phase_events;
      ContactEvent ev;
      ev.t = e.t;
      ev.point = balls_[iu].point;
      ev.from = ModeOfPhase(s0.phase);
      ev.to = ModeOfPhase(s1.phase);
      ev.reason = s0.phase == Phase::kSliding ? ContactEventReason::kSlipStopped
                                              : ContactEventReason::kRollingStopped;
      ev.held_to = s1.phase == Phase::kRest && balls_[iu].mu_r > 0.0;
      res_.contact_events.push_back(ev);
      break;
    }
    case Kind::kHorizon: {
      if (e.ver_i != ver_[iu] || horizon_[iu] != e.t) break;
      RenewBox(e.i, e.t);
      break;
    }
    case Kind::kLanding: {
      if (e.ver_i != ver_[iu]) break;
      const Segment& s = chain_[iu].At(e.t);
      const double vn = w_.n.dot(s.Vel(e.t));
      Impact(e.t, e.i, -1);
      if (-vn <= w_.tol.resting_speed && ver_[iu] == e.ver_i) {
        // Set down without an impact: the ball continues on the plane.
        CloseSegment(e.i, e.t);
        Vec3 v = s.Vel(e.t);
        v -= w_.n.dot(v) * w_.n;
        const Quat q = ChainOrient(chain_[iu], e.t);
        const Segment next =
            StartSegment(balls_[iu], w_, e.t, s.Pos(e.t), v, s.Omega(e.t), q, true);
        res_.contact_events.push_back({e.t, balls_[iu].point, ContactMode::kSeparated,
                                       ModeOfPhase(next.phase), ContactEventReason::kTouchDown});
        BeginChain(e.i, next);
      }
      break;
    }
    case Kind::kGroup: {
      const Group& g = groups_[static_cast<size_t>(e.i)];
      if (g.alive && g.ver == e.ver_i) EndWindow(e.i, e.t);
      break;
    }
    case Kind::kPair: {
      if (e.ver_i != ver_[iu] || e.ver_j != ver_[static_cast<size_t>(e.j)]) break;
      Impact(e.t, e.i, e.j);
      break;
    }
  }
}

// The balls' first segments: a ball below the plane is refused, and what the rules of contact
// adjust in the given state is said (warnings); the initial modes are recorded.
std::vector<Segment> Runner::InitialSegments(const State& initial) {
  const size_t n = balls_.size();
  const double t0 = initial.t;
  std::vector<Segment> first(n);
  for (size_t i = 0; i < n; ++i) {
    const Ball& b = balls_[i];
    const BodyState& bs = initial.bodies[i];
    const std::string& name = model_.body(b.body).name();
    const double gap = w_.n.dot(bs.p_WBcm - w_.p0) - b.R;
    if (gap < -w_.tol.gap) {
      throw InputError(fmt::format("body '{}' starts {} m into the plane", name, -gap),
                       ErrorElement{ErrorElement::Kind::kBody, b.body});
    }
    const Vec3 om = bs.q_WB * bs.w_WB_B;
    first[i] = Restart(static_cast<int>(i), t0, bs.p_WBcm, bs.v_WBcm_W, om, bs.q_WB);
    if (first[i].phase != Phase::kFlight) {
      const double vn = w_.n.dot(bs.v_WBcm_W);
      if (vn != 0.0) {
        res_.warnings.push_back(fmt::format(
            "body '{}': its normal velocity {:.3g} m/s (within resting_speed) was set to 0: it "
            "starts on the plane",
            name, vn));
      }
      const double moved = (first[i].w0 - om).norm() * b.R;
      if (moved > 1e-14 * (bs.v_WBcm_W.norm() + om.norm() * b.R)) {
        res_.warnings.push_back(fmt::format(
            "body '{}': its slip of {:.3g} m/s (within stick_speed) was taken as rolling: its "
            "angular velocity along the plane was set to n × v / R",
            name, moved));
      }
    }
    res_.contact_events.push_back({t0, b.point, ContactMode::kSeparated,
                                   ModeOfPhase(first[i].phase), ContactEventReason::kInitial});
  }
  return first;
}

SphereEventResult Runner::Run(const State& initial) {
  ReadModel();
  ValidateState(model_, initial);
  if (!(options_.t_end >= initial.t)) {
    throw InputError(
        fmt::format("t_end = {} s is before the initial time {} s", options_.t_end, initial.t));
  }
  if (!std::isfinite(options_.t_end)) {
    throw InputError(fmt::format("t_end = {} s must be finite", options_.t_end));
  }
  if (!(options_.output_interval >= 0.0) || !std::isfinite(options_.output_interval)) {
    throw InputError(
        fmt::format("output_interval = {} s must be >= 0 (0: first and last state only)",
                    options_.output_interval));
  }
  if (options_.collide_all_pairs)
    internal::ValidateSphereCollisionLaw(options_.pair_law, model_, R_max_);
  const auto n = balls_.size();
  chain_.resize(n);
  ver_.assign(n, 0);
  box_.assign(n, Box{});
  horizon_.assign(n, 0.0);
  cells_of_.assign(n, {0, -1, 0, -1});
  stamp_.assign(n, 0);
  booked_until_.assign(n, initial.t);
  group_of_.assign(n, -1);
  renew_tick_.assign(n, 0);
  ledger_ = initial;
  ledger_.contacts.assign(static_cast<size_t>(model_.num_contact_points()), ContactPointState{});
  const double t0 = initial.t;
  const std::vector<Segment> first = InitialSegments(initial);
  for (size_t i = 0; i < n; ++i) chain_[i] = MakeChain(balls_[i], w_, first[i]);
  CheckNoOverlap(initial);
  for (size_t i = 0; i < n; ++i) {
    const Chain& c = chain_[i];
    const auto ii = static_cast<int>(i);
    for (int k = 0; k + 1 < c.count; ++k) {
      Schedule({c.seg[static_cast<size_t>(k)].end(), Kind::kPhase, ii, -1, 0, 0, 0});
    }
    if (std::isfinite(c.known_until)) Schedule({c.known_until, Kind::kLanding, ii, -1, 0, 0, 0});
  }
  for (size_t i = 0; i < n; ++i) RenewBox(static_cast<int>(i), t0);
  res_.samples.push_back(StateAt(t0));
  if (options_.output_interval > 0.0) {
    for (long k = 1;; ++k) {
      const double ts = t0 + static_cast<double>(k) * options_.output_interval;
      if (ts >= options_.t_end) break;
      Schedule({ts, Kind::kSample, -1, -1, 0, 0, 0});
    }
  }
  while (!queue_.empty()) {
    const Event e = queue_.top();
    if (e.t > options_.t_end) break;
    queue_.pop();
    Handle(e);
    CheckGroups(e.t);
    if (options_.on_progress) options_.on_progress(e.t);
  }
  for (size_t g = 0; g < groups_.size(); ++g) {
    if (groups_[g].alive) Advance(static_cast<int>(g), options_.t_end);
  }
  for (size_t i = 0; i < n; ++i) {
    if (group_of_[i] < 0) CloseSegment(static_cast<int>(i), options_.t_end);
  }
  res_.final_state = StateAt(options_.t_end);
  if (res_.samples.back().t != options_.t_end) res_.samples.push_back(res_.final_state);
  // The run's own check: the energy balance, each term from its closed form.
  const auto energy = [&](const State& s) {
    double e = 0.0;
    for (size_t i = 0; i < n; ++i) {
      const Ball& b = balls_[i];
      const BodyState& bs = s.bodies[i];
      e += 0.5 * b.m * bs.v_WBcm_W.squaredNorm() + 0.5 * b.I * bs.w_WB_B.squaredNorm() -
           b.m * w_.g_W.dot(bs.p_WBcm);
    }
    return e;
  };
  res_.energy.initial = energy(initial);
  res_.energy.final = energy(res_.final_state);
  res_.energy.residual = res_.energy.final - (res_.energy.initial + res_.energy.friction +
                                              res_.energy.rolling + res_.energy.impacts);
  return res_;
}

}  // namespace sphere_events_detail

SphereEventResult SimulateSphereEvents(const Model& model, const State& initial,
                                       const SphereEventOptions& options) {
  Runner runner(model, options);
  return runner.Run(initial);
}

namespace internal {

void ValidateSphereCollisionLaw(const SphereCollisionLaw& law, const Model& model, double radius) {
  ContactSpec spec;
  spec.name = "pair_law";
  spec.shape = ContactShape::kSphereSphere;
  spec.radius = spec.other_radius = radius;
  spec.body = 0;
  spec.other_body = model.num_bodies() > 1 ? 1 : 0;
  spec.restitution = law.restitution;
  spec.mu_s = law.mu_s;
  spec.mu_k = law.mu_k;
  spec.restitution_law = law.law;
  ValidateContactSpec(spec);
}

}  // namespace internal

}  // namespace chasles
