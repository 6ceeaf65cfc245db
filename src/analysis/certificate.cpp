// The certificate of a run: checks of each sampled state against the physics it must obey
// (see include/chasles/analysis/certificate.h and docs/contact.md, "Certificate").

#include "chasles/analysis/certificate.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "chasles/dynamics/contact_solve.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/model/string_constraint.h"

namespace chasles {

namespace {

// The checks, in report order.
enum Check {
  kFrictionCone,
  kSlidingFriction,
  kRollingResistance,
  kNormalForce,
  kGap,
  kConstraintPosition,
  kConstraintVelocity,
  kLedger,
  kLinearBalance,
  kAngularBalance,
  kLinearImpulseBalance,
  kAngularImpulseBalance,
  kNumChecks
};

struct CheckInfo {
  const char* name;
  const char* description;
  const char* unit;
};

constexpr CheckInfo kChecks[kNumChecks] = {
    {"friction cone", "sticking points: |f| - mu_s N <= 0", "N"},
    {"sliding friction", "sliding points: |f + mu_k N s| = 0 (s the unit slip)", "N"},
    {"rolling resistance",
     "held rolling: |M| - mu_r N R <= 0; rolling: |M + mu_r N R w_r/|w_r|| = 0", "N*m"},
    {"normal force", "points in contact: -N <= 0", "N"},
    {"gap", "every contact point: -gap <= 0", "m"},
    {"constraint position", "holonomic rows of joints, rolling, gears, drivers: |g| = 0",
     "m or rad"},
    {"constraint velocity", "every row: |J u - b| = 0", "m/s or rad/s"},
    {"ledger", "work-energy balance: |E - E0 - W_nc - jumps| = 0", "J"},
    {"linear momentum balance", "per body: |m a_cm - sum F| = 0 (all forces)", "N"},
    {"angular momentum balance", "per body: |dH_cm/dt - sum M_cm| = 0 (all forces)", "N*m"},
    {"linear impulse balance",
     "per body at each impulse or impact: |m dv_cm - sum J| = 0 (all impulses)", "N*s"},
    {"angular impulse balance",
     "per body at each impulse or impact: |dH_cm - sum (r x J + M)| = 0 (all impulses)", "N*m*s"},
};

}  // namespace

const char* CheckPhaseName(CheckPhase phase) {
  switch (phase) {
    case CheckPhase::kSample:
      return "sample";
    case CheckPhase::kEvent:
      return "event";
    case CheckPhase::kBeforeTransition:
      return "before a contact transition";
    case CheckPhase::kAfterTransition:
      return "after a contact transition";
    case CheckPhase::kSolve:
      return "solved state";
    case CheckPhase::kJump:
      return "impulse or impact";
  }
  return "";
}

bool Certificate::passed() const {
  return std::all_of(checks.begin(), checks.end(), [](const CheckResult& c) { return c.passed(); });
}

std::vector<std::string> Certificate::FailureMessages() const {
  std::vector<std::string> out;
  for (const CheckResult& c : checks) {
    if (c.passed()) continue;
    out.push_back(fmt::format(
        "check '{}' failed: {:.3e} {} against a tolerance of {:.3e} {} at {}, t = {:.9g} s ({})",
        c.name, c.worst, c.unit, c.tolerance, c.unit, c.where, c.t, CheckPhaseName(c.phase)));
  }
  return out;
}

CertificateBuilder::CertificateBuilder(const CertificateTolerances& tolerances)
    : tol_(tolerances), gap_time_(tolerances.gap_time), counts_(kNumChecks, 0) {
  // Room for a run of a few hundred samples at once: grown by doubling instead, the entries
  // were copied and their fresh pages faulted in again at each doubling (a tenth of a short
  // run's cost in the CLI). Pages not written are not touched.
  entries_.reserve(size_t{1} << 11);
}

void CertificateBuilder::Add(int check, double value, Scale scale, double a, double b,
                             double local_scale, std::string where, double t, CheckPhase phase) {
  ++counts_[static_cast<size_t>(check)];
  entries_.push_back(
      {check, value, scale, a, b, local_scale, std::move(where), t, phase, gap_time_});
  if (entries_.size() >= compact_at_) Compact();
}

void CertificateBuilder::CheckLedger(double t, double residual, double energy_scale,
                                     CheckPhase phase, const std::string& where) {
  energy_ = std::max(energy_, std::abs(energy_scale));
  Add(kLedger, std::abs(residual), Scale::kEnergy, 1.0, 0.0, 0.0, where, t, phase);
}

void CertificateBuilder::AddPart(const Certificate& part) {
  if (parts_.empty()) {
    parts_.resize(kNumChecks);
    part_ratio_.assign(kNumChecks, -1.0);
  }
  for (size_t c = 0; c < parts_.size() && c < part.checks.size(); ++c) {
    const CheckResult& x = part.checks[c];
    if (x.count == 0) continue;
    const long long count = parts_[c].count + x.count;
    // As Ratio: a zero tolerance passes a zero value only.
    const double ratio =
        x.tolerance > 0.0 ? x.worst / x.tolerance : (x.worst > 0.0 ? HUGE_VAL : 0.0);
    if (ratio > part_ratio_[c]) {
      part_ratio_[c] = ratio;
      parts_[c] = x;
    }
    parts_[c].count = count;
  }
}

void CertificateBuilder::CheckImpulseBalance(double t,
                                             const std::vector<BodyImpulseBalance>& bodies) {
  // Impulse-momentum per body over the instant (eqs. 8.118, 8.119): m Δv_cm = ΣJ and
  // ΔH_cm = Σ (r × J + M), r from the centre of mass to the impulse's point. Round-off is
  // relative to what was summed: the impulses, and the momenta before and after whose
  // difference is the jump.
  for (const BodyImpulseBalance& b : bodies) {
    Vec3 J = Vec3::Zero(), H = Vec3::Zero();
    double J_size = 0.0, H_size = 0.0;
    for (const BodyImpulse& i : b.impulses) {
      const Vec3 r = i.p_WP - b.p_WBcm;
      J += i.J_W;
      H += r.cross(i.J_W) + i.M_W;
      J_size += i.J_W.norm();
      H_size += r.norm() * i.J_W.norm() + i.M_W.norm();
      impulse_ = std::max(impulse_, i.J_W.norm());
      angular_impulse_ = std::max({angular_impulse_, r.norm() * i.J_W.norm(), i.M_W.norm()});
      length_ = std::max(length_, i.p_WP.norm());
    }
    const Vec3 dP = b.mass * b.dv_WBcm_W;
    const double P_size = b.mass * (b.v_WBcm_W.norm() + (b.v_WBcm_W - b.dv_WBcm_W).norm()) + J_size;
    const double L_size = b.H_Bcm_W.norm() + (b.H_Bcm_W - b.dH_Bcm_W).norm() + H_size;
    impulse_ = std::max(impulse_, dP.norm());
    angular_impulse_ = std::max(angular_impulse_, b.dH_Bcm_W.norm());
    const std::string where = fmt::format("body '{}'", b.body);
    Add(kLinearImpulseBalance, (dP - J).norm(), Scale::kImpulse, 1.0, 0.0, P_size, where, t,
        CheckPhase::kJump);
    Add(kAngularImpulseBalance, (b.dH_Bcm_W - H).norm(), Scale::kAngularImpulse, 1.0, 0.0, L_size,
        where, t, CheckPhase::kJump);
  }
}

void CertificateBuilder::CheckState(const Model& model, const State& state, CheckPhase phase) {
  Data data = MakeData(model);
  CalcAccelerations(model, state, data);
  CheckState(model, state, data, phase);
}

void CertificateBuilder::CheckState(const Model& model, const State& state, const Data& data,
                                    CheckPhase phase) {
  CheckDataFor(model, data);
  double total_mass = 0.0;
  for (int b = 0; b < model.num_bodies(); ++b) total_mass += model.body(b).mass();
  mass_ = std::max(mass_, total_mass);
  BodyResultants resultants = CollectForces(model, state, data);
  CheckContacts(model, state, data, phase, resultants);
  CheckBalances(model, state, data, phase, resultants);
  CheckConstraintRows(model, state, data, phase);
}

void CertificateBuilder::AddForce(const State& state, BodyResultants& r, int b, const Vec3& f,
                                  const Vec3& p_W) {
  if (b == kWorld) return;
  const auto i = static_cast<size_t>(b);
  const Vec3 arm = p_W - state.bodies[i].p_WBcm;
  r.F[i] += f;
  r.M[i] += arm.cross(f);
  r.F_size[i] += f.norm();
  r.M_size[i] += arm.norm() * f.norm();
  force_ = std::max(force_, f.norm());
  moment_ = std::max(moment_, arm.norm() * f.norm());
  length_ = std::max(length_, p_W.norm());
}

void CertificateBuilder::AddMoment(BodyResultants& r, int b, const Vec3& m) {
  if (b == kWorld) return;
  const auto i = static_cast<size_t>(b);
  r.M[i] += m;
  r.M_size[i] += m.norm();
  moment_ = std::max(moment_, m.norm());
}

CertificateBuilder::BodyResultants CertificateBuilder::CollectForces(const Model& model,
                                                                     const State& state,
                                                                     const Data& data) {
  const auto nb = static_cast<size_t>(model.num_bodies());
  BodyResultants r{std::vector<Vec3>(nb), std::vector<Vec3>(nb), std::vector<double>(nb, 0.0),
                   std::vector<double>(nb, 0.0)};
  // Applied forces, gravity, springs, drag: the force stage's resultants about each Bcm.
  for (size_t i = 0; i < nb; ++i) {
    r.F[i] = data.F_Bcm_W[i];
    r.M[i] = data.M_Bcm_W[i];
    r.F_size[i] = data.F_Bcm_W[i].norm();
    r.M_size[i] = data.M_Bcm_W[i].norm();
    force_ = std::max(force_, r.F_size[i]);
    moment_ = std::max(moment_, r.M_size[i]);
  }
  for (const ForceElementOutput& e : data.elements) force_ = std::max(force_, e.force_W.norm());
  // Reactions: the force and moment about J on the child, the opposite on the parent (the
  // constraint forces are internal: Newton's third law at the common point J).
  for (int c = 0; c < model.num_constraints(); ++c) {
    const Constraint& con = model.constraint(c);
    const ConstraintOutput& o = data.constraints[static_cast<size_t>(c)];
    AddForce(state, r, con.child(), o.F_Jc_W, o.p_WJ);
    AddMoment(r, con.child(), o.M_Jc_W);
    if (dynamic_cast<const StringConstraint*>(&con) != nullptr) {
      // A string over pulleys pulls its parent along its own end segment, not opposite to
      // the child (the pulleys take the difference): the parent's share of Jᵀλ, T e_A at
      // its leaving point, which the row's angular part r_A × e_A already moves to Pcm; a
      // pulley carried by a further body pulls it with that body's share, T (e_out - e_in).
      const ConstraintEval& e = data.constraint_rows[static_cast<size_t>(c)];
      const auto share = [&](BodyIndex b, const ConstraintEval::Rows& J) {
        const Vec3 F = J.row(0).head<3>().transpose() * o.lambda[0];
        const Vec3 M = J.row(0).tail<3>().transpose() * o.lambda[0];
        AddForce(state, r, b, F, state.bodies[static_cast<size_t>(b)].p_WBcm);
        AddMoment(r, b, M);
      };
      if (con.parent() != kWorld) share(con.parent(), e.J_parent);
      for (int k = 0; k < e.num_extra; ++k) {
        share(e.extra_body[static_cast<size_t>(k)], e.J_extra[static_cast<size_t>(k)]);
      }
      continue;
    }
    AddForce(state, r, con.parent(), -o.F_Jc_W, o.p_WJ);
    AddMoment(r, con.parent(), -o.M_Jc_W);
  }
  return r;
}

void CertificateBuilder::CheckContacts(const Model& model, const State& state, const Data& data,
                                       CheckPhase phase, BodyResultants& r) {
  const double t = state.t;
  // Contact forces at the contact point: normal N n and friction on the body, the opposite
  // on the other body; rolling-resistance moments likewise.
  for (int p = 0; p < model.num_contact_points(); ++p) {
    const ContactPointOutput& o = data.contact_points[static_cast<size_t>(p)];
    const Contact& con = model.contact(model.contact_of_point(p));
    const std::string where = fmt::format("contact point '{}'", model.contact_point_name(p));
    length_ = std::max(length_, o.p_WC.norm());
    // Gap, every point (a separated point may be far away: only penetration counts).
    Add(kGap, std::max(0.0, -o.gap), Scale::kLength, 1.0, 0.0, 0.0, where, t, phase);
    if (o.mode == ContactMode::kSeparated) continue;
    const Vec3 f = o.normal_force * o.n_W + o.friction_force_W;
    AddForce(state, r, con.body(), f, o.p_WC);
    AddForce(state, r, con.other_body(), -f, o.p_WC);
    AddMoment(r, con.body(), o.rolling_moment_W);
    AddMoment(r, con.other_body(), -o.rolling_moment_W);
    force_ = std::max({force_, std::abs(o.normal_force), o.friction_force_W.norm()});
    const double N = o.normal_force;
    const double local = std::abs(N) + o.friction_force_W.norm();
    Add(kNormalForce, std::max(0.0, -N), Scale::kForce, 1.0, 0.0, local, where, t, phase);
    if (o.mode == ContactMode::kSticking) {
      // Coulomb: a sticking point holds while the friction it needs is inside the cone.
      Add(kFrictionCone, std::max(0.0, o.friction_force_W.norm() - con.mu_s() * N), Scale::kForce,
          1.0, 0.0, local, where, t, phase);
    } else {
      // Coulomb: sliding friction is mu_k N against the slip. While the slip speed is below
      // the velocity scale's round-off its direction is noise (the engine then keeps the
      // mode's reference direction, as when the slip stops or starts from rest; below
      // kSlipSpeedRoundOff too, as the engine decides): the size alone is checked.
      const double vs = o.slip_velocity_W.norm();
      const Vec3 s = vs > std::max(tol_.state * velocity_, kSlipSpeedRoundOff)
                         ? Vec3(o.slip_velocity_W / vs)
                         : Vec3::Zero();
      double value = 0.0;
      if (s.squaredNorm() > 0.0) {
        value = (o.friction_force_W + con.mu_k() * N * s).norm();
      } else {
        value = std::abs(o.friction_force_W.norm() - con.mu_k() * std::abs(N));
      }
      Add(kSlidingFriction, value, Scale::kForce, 1.0, 0.0, local, where, t, phase);
    }
    if (o.mode == ContactMode::kSticking && o.rolling_moment_capacity > 0.0) {
      CheckRollingResistance(o, where, t, phase);
    }
  }
}

void CertificateBuilder::CheckRollingResistance(const ContactPointOutput& o,
                                                const std::string& where, double t,
                                                CheckPhase phase) {
  // Rolling resistance, a complementarity like Coulomb's: a held rolling needs at most
  // mu_r N R; a rolling point gets mu_r N R against its rolling. A rolling speed at the
  // velocity scale's round-off has no direction of its own (the engine keeps the mode's
  // reference, as it does when the rolling starts from rest): its size alone is checked.
  const double cap = o.rolling_moment_capacity;
  const double M = o.rolling_moment_W.norm();
  moment_ = std::max(moment_, M);
  double value = 0.0;
  if (o.rolling_held) {
    value = std::max(0.0, M - cap);
  } else {
    const double wr = o.rolling_velocity_W.norm();
    if (wr > std::max(tol_.state * rate_, kSlipSpeedRoundOff)) {
      value = (o.rolling_moment_W + cap * o.rolling_velocity_W / wr).norm();
    } else {
      value = std::abs(M - cap);
    }
  }
  Add(kRollingResistance, value, Scale::kMoment, 1.0, 0.0, M + cap, where, t, phase);
}

void CertificateBuilder::CheckBalances(const Model& model, const State& state, const Data& data,
                                       CheckPhase phase, const BodyResultants& r) {
  const double t = state.t;
  // Newton–Euler per body (eqs. 8.76-8.78 and Euler's equations, eqs. 8.75-8.81): m a_cm = ΣF;
  // dH_cm/dt = R (I ω̇ + ω × I ω) with ω in B = ΣM_cm.
  for (int b = 0; b < model.num_bodies(); ++b) {
    const auto i = static_cast<size_t>(b);
    const Body& body = model.body(b);
    const BodyState& bs = state.bodies[i];
    const Vec3 ma = body.mass() * data.a_WBcm_W[i];
    const Vec3 w = bs.w_WB_B;
    const Vec3 Iwdot = body.I_BBcm_B() * data.wdot_WB_B[i];
    const Vec3 gyro = w.cross(Vec3(body.I_BBcm_B() * w));
    const Vec3 Hdot_W = data.R_WB[i] * (Iwdot + gyro);
    const double radius = std::sqrt(body.I_BBcm_B().diagonal().maxCoeff() / body.mass());
    force_ = std::max(force_, ma.norm());
    moment_ = std::max({moment_, Iwdot.norm(), gyro.norm()});
    length_ = std::max({length_, bs.p_WBcm.norm(), radius});
    velocity_ = std::max({velocity_, bs.v_WBcm_W.norm(), radius * w.norm()});
    rate_ = std::max(rate_, w.norm());
    radius_ = std::max(radius_, radius);
    const std::string where = fmt::format("body '{}'", body.name());
    Add(kLinearBalance, (ma - r.F[i]).norm(), Scale::kForce, 1.0, 0.0, ma.norm() + r.F_size[i],
        where, t, phase);
    Add(kAngularBalance, (Hdot_W - r.M[i]).norm(), Scale::kMoment, 1.0, 0.0,
        Iwdot.norm() + gyro.norm() + r.M_size[i], where, t, phase);
  }
}

void CertificateBuilder::CheckConstraintRows(const Model& model, const State& state,
                                             const Data& data, CheckPhase phase) {
  const double t = state.t;
  // Constraint residuals, row by row. A row's position error is a length (its translational
  // Jacobian part is a unit direction) or an angle (only a rotational part): its scale is
  // |J_trans| L + |J_rot| (1 rad); its velocity residual's is |J_trans| V + |J_rot| Ω.
  for (int c = 0; c < model.num_constraints(); ++c) {
    const Constraint& con = model.constraint(c);
    if (con.can_release() && IsReleased(state, c)) continue;  // a slack string holds nothing
    const ConstraintEval& e = data.constraint_rows[static_cast<size_t>(c)];
    auto u_of = [&](int b) {
      Eigen::Matrix<double, 6, 1> u = Eigen::Matrix<double, 6, 1>::Zero();
      if (b == kWorld) return u;
      const auto i = static_cast<size_t>(b);
      u.head<3>() = state.bodies[i].v_WBcm_W;
      u.tail<3>() = data.R_WB[i] * state.bodies[i].w_WB_B;
      return u;
    };
    const Eigen::Matrix<double, 6, 1> up = u_of(con.parent()), uc = u_of(con.child());
    for (int k = 0; k < con.num_rows(); ++k) {
      const bool has_parent = con.parent() != kWorld;
      double jt = e.J_child.row(k).head<3>().norm() +
                  (has_parent ? e.J_parent.row(k).head<3>().norm() : 0.0);
      double jr = e.J_child.row(k).tail<3>().norm() +
                  (has_parent ? e.J_parent.row(k).tail<3>().norm() : 0.0);
      double jt_extra = 0.0, jr_extra = 0.0, Ju_extra = 0.0, terms_extra = 0.0;
      for (int x = 0; x < e.num_extra; ++x) {
        const auto j = static_cast<size_t>(x);
        const Eigen::Matrix<double, 6, 1> ux = u_of(e.extra_body[j]);
        jt_extra += e.J_extra[j].row(k).head<3>().norm();
        jr_extra += e.J_extra[j].row(k).tail<3>().norm();
        Ju_extra += e.J_extra[j].row(k).dot(ux);
        terms_extra += e.J_extra[j].row(k).cwiseAbs().dot(ux.cwiseAbs());
      }
      jt += jt_extra;
      jr += jr_extra;
      const double Ju =
          e.J_child.row(k).dot(uc) + (has_parent ? e.J_parent.row(k).dot(up) : 0.0) + Ju_extra;
      const double terms = e.J_child.row(k).cwiseAbs().dot(uc.cwiseAbs()) +
                           (has_parent ? e.J_parent.row(k).cwiseAbs().dot(up.cwiseAbs()) : 0.0) +
                           terms_extra + std::abs(e.velocity_rhs[k]);
      const std::string where = fmt::format("constraint '{}' row {}", con.name(), k);
      Add(kConstraintVelocity, std::abs(Ju - e.velocity_rhs[k]), Scale::kVelocity, jt, jr, terms,
          where, t, phase);
      if (e.holonomic[static_cast<size_t>(k)]) {
        Add(kConstraintPosition, std::abs(e.position_error[k]), Scale::kLength, jt, jr, 0.0, where,
            t, phase);
      }
    }
  }
}

CertificateBuilder::Scales CertificateBuilder::CurrentScales() const {
  Scales k;
  // A moment scale at least the force scale times the largest radius of gyration, so that a
  // run whose moments happen to vanish still compares them with its forces' lever arms.
  k.moment = std::max(moment_, force_ * radius_);
  // A velocity scale at least the speed the run's forces give its mass over its length,
  // v² = F L / m (e.g. √(g L) under gravity), and a rate scale that speed over the largest
  // radius of gyration: a run that starts and stays at rest still has a velocity scale.
  const double v_floor = mass_ > 0.0 ? std::sqrt(force_ * length_ / mass_) : 0.0;
  k.velocity = std::max(velocity_, v_floor);
  k.rate = std::max(rate_, radius_ > 0.0 ? v_floor / radius_ : 0.0);
  // As for moments: at least the impulse scale times the largest radius of gyration.
  k.angular_impulse = std::max(angular_impulse_, impulse_ * radius_);
  return k;
}

double CertificateBuilder::Tolerance(const Entry& e, const Scales& k) const {
  double rel = tol_.force, run = 0.0;
  switch (e.scale) {
    case Scale::kForce:
      run = force_;
      break;
    case Scale::kMoment:
      run = k.moment;
      break;
    case Scale::kLength:
      rel = tol_.state;
      run = e.a * length_ + e.b;  // b: the rotational part, per radian
      if (e.check == kGap && e.gap_time > 0.0) {
        return std::max(rel * std::max(run, e.local_scale), e.gap_time * k.velocity);
      }
      break;
    case Scale::kVelocity:
      rel = tol_.state;
      run = e.a * k.velocity + e.b * k.rate;
      break;
    case Scale::kEnergy:
      rel = tol_.ledger;
      run = energy_;
      break;
    case Scale::kImpulse:
      rel = tol_.impulse;
      run = impulse_;
      break;
    case Scale::kAngularImpulse:
      rel = tol_.impulse;
      run = k.angular_impulse;
      break;
  }
  return rel * std::max(run, e.local_scale);
}

// value / tolerance (a zero tolerance with a zero value is a pass; with a positive value an
// infinite ratio).
double CertificateBuilder::Ratio(const Entry& e, const Scales& k) const {
  const double tolerance = Tolerance(e, k);
  return tolerance > 0.0 ? e.value / tolerance : (e.value > 0.0 ? HUGE_VAL : 0.0);
}

void CertificateBuilder::Compact() {
  // The scales only grow, so every ratio only shrinks from here on: an entry below
  // kKeep times its check's largest ratio now stays far below any tolerance the check's worst
  // value could fail (it passes whenever the worst does, by a factor 1/kKeep), and is dropped.
  // This bounds the memory of long runs.
  constexpr double kKeep = 1e-3;
  const Scales k = CurrentScales();
  std::vector<double> worst(kNumChecks, 0.0);
  for (const Entry& e : entries_) {
    worst[static_cast<size_t>(e.check)] =
        std::max(worst[static_cast<size_t>(e.check)], Ratio(e, k));
  }
  std::vector<bool> kept_one(kNumChecks, false);
  std::vector<Entry> kept;
  for (Entry& e : entries_) {
    const auto c = static_cast<size_t>(e.check);
    const double r = Ratio(e, k);
    if (r >= kKeep * worst[c] && (r > 0.0 || !kept_one[c])) {
      kept_one[c] = true;
      kept.push_back(std::move(e));
    }
  }
  entries_ = std::move(kept);
  compact_at_ = std::max(compact_at_, 2 * entries_.size());
}

Certificate CertificateBuilder::Finish() const {
  Certificate cert;
  const Scales k = CurrentScales();
  cert.force_scale = force_;
  cert.moment_scale = k.moment;
  cert.length_scale = length_;
  cert.velocity_scale = k.velocity;
  cert.energy_scale = energy_;
  cert.impulse_scale = impulse_;
  cert.angular_impulse_scale = k.angular_impulse;
  for (int c = 0; c < kNumChecks; ++c) {
    CheckResult r;
    r.name = kChecks[c].name;
    r.description = kChecks[c].description;
    r.unit = kChecks[c].unit;
    r.count = counts_[static_cast<size_t>(c)];
    cert.checks.push_back(r);
  }
  std::vector<double> worst_ratio(kNumChecks, -1.0);
  for (const Entry& e : entries_) {
    // The worst value is the one with the largest value/tolerance.
    const double ratio = Ratio(e, k);
    const double tolerance = Tolerance(e, k);
    const auto c = static_cast<size_t>(e.check);
    if (ratio > worst_ratio[c]) {
      worst_ratio[c] = ratio;
      CheckResult& r = cert.checks[c];
      r.worst = e.value;
      r.tolerance = tolerance;
      r.where = e.where;
      r.t = e.t;
      r.phase = e.phase;
    }
  }
  for (size_t c = 0; c < parts_.size(); ++c) {
    CheckResult& r = cert.checks[c];
    r.count += parts_[c].count;
    if (part_ratio_[c] > worst_ratio[c]) {
      r.worst = parts_[c].worst;
      r.tolerance = parts_[c].tolerance;
      r.where = parts_[c].where;
      r.t = parts_[c].t;
      r.phase = parts_[c].phase;
    }
  }
  return cert;
}

}  // namespace chasles
