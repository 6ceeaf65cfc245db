// The instants of a study where the state jumps: impulses, projectiles passing through a body,
// and projectiles that embed (a new Model with the composite body), the impulses of the
// supports and contacts at those instants with every body's velocity jumps, and the ledger at
// the end (include/chasles/analysis/study.h).

#include <algorithm>

#include <fmt/format.h>

#include "chasles/analysis/instantaneous.h"
#include "chasles/analysis/ledger.h"
#include "chasles/analysis/study.h"
#include "chasles/dynamics/constraint_solve.h"
#include "chasles/dynamics/contact_solve.h"
#include "chasles/dynamics/impulse.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/error.h"
#include "chasles/model/data.h"
#include "internal/study_steps.h"

namespace chasles::study_internal {

namespace {

/// The motion of model body m at `state`, with its mass properties.
BodyMotion ModelBodyMotion(const Model& model, const State& state, int m) {
  const BodyState& s = state.bodies[static_cast<size_t>(m)];
  BodyMotion bm;
  bm.mass_properties = model.body(m).mass_properties();
  bm.R_WB = s.q_WB.toRotationMatrix();
  bm.p_WBcm = s.p_WBcm;
  bm.v_WBcm_W = s.v_WBcm_W;
  bm.w_WB_W = bm.R_WB * s.w_WB_B;
  return bm;
}

/// The map after the projectile's model body mp embeds in the target's mt: the projectile's
/// user bodies are re-placed in the target's frame,
///   R_TB = R_WTᵀ R_WP R_PB,  p_ToBo_T = R_WTᵀ (p_WPo + R_WP p_PoBo_P - p_WTo),
/// and the model bodies after mp move down by one.
BodyMap EmbeddedMap(const BodyMap& map, int mt, int mp, const Mat3& R_WT, const Vec3& p_WTo,
                    const Mat3& R_WP, const Vec3& p_WPo) {
  BodyMap out = map;
  for (BodyPlacement& pl : out.place) {
    if (pl.model_body == mp) {
      pl.p_MoBo_M = R_WT.transpose() * (p_WPo + R_WP * pl.p_MoBo_M - p_WTo);
      pl.R_MB = R_WT.transpose() * R_WP * pl.R_MB;
      pl.model_body = mt;
    }
    if (pl.model_body > mp) --pl.model_body;
  }
  return out;
}

}  // namespace

Segment FirstSegment(const StudyDefinition& definition) {
  if (!definition.model && !definition.build_model) {
    throw InputError("a study needs its Model (model) or a ModelBuilder (build_model)");
  }
  Segment seg;
  seg.bodies = definition.bodies;
  for (size_t b = 0; b < definition.bodies.size(); ++b) {
    seg.map.place.push_back({static_cast<int>(b), Mat3::Identity(), Vec3::Zero()});
    seg.map.p_BoBcm_B.push_back(definition.bodies[b].mass_properties.p_BoBcm_B());
    seg.map.mass.push_back(definition.bodies[b].mass_properties.mass());
    seg.map.I_BBcm_B.push_back(definition.bodies[b].mass_properties.I_BBcm_B().matrix());
  }
  // The caller's Model when it has built it (the scene's definition checks its inputs on it):
  // a run builds each Model once.
  seg.model = definition.model
                  ? definition.model
                  : std::make_shared<const Model>(definition.build_model(seg.bodies, seg.map));
  if (seg.model->num_bodies() != static_cast<int>(seg.bodies.size())) {
    throw InputError(fmt::format("the study's Model has {} bodies for {} study bodies",
                                 seg.model->num_bodies(), seg.bodies.size()));
  }
  return seg;
}

int ApplyStudyImpulse(const StudyImpulseSpec& impulse, const Segment& seg, State& state,
                      std::vector<JumpImpulse>* applied) {
  const BodyPlacement& pl = seg.map.place[static_cast<size_t>(impulse.body)];
  const BodyState& bs = state.bodies[static_cast<size_t>(pl.model_body)];
  const Mat3 R_WM = bs.q_WB.toRotationMatrix();
  const Vec3 J_W =
      impulse.frame == VectorFrame::kWorld ? impulse.J : Vec3(R_WM * pl.R_MB * impulse.J);
  const Vec3 p_MoP_M = seg.map.PointInModelBody(impulse.body, impulse.p_BoP_B);
  if (applied != nullptr) {
    // P in W as ApplyImpulse places it.
    const Vec3 p_WP = bs.p_WBcm + bs.q_WB.normalized() *
                                      seg.model->body(pl.model_body).PointFromCenterOfMass(p_MoP_M);
    applied->push_back({pl.model_body, {"applied", p_WP, J_W, Vec3::Zero()}});
  }
  ApplyImpulse(*seg.model, pl.model_body, p_MoP_M, J_W, state);
  return pl.model_body;
}

int ApplyStudyImpact(const StudyImpactSpec& impact, const ModelBuilder& build, Segment& seg,
                     State& state, std::vector<JumpImpulse>* applied) {
  const Model& model = *seg.model;
  const int mt = seg.map.place[static_cast<size_t>(impact.target)].model_body;
  const int mp = seg.map.place[static_cast<size_t>(impact.projectile)].model_body;
  if (mt == mp) {
    throw InputError(
        fmt::format("impact at t = {:.6g} s: '{}' and '{}' are already one body (an earlier impact "
                    "embedded one in the other)",
                    impact.t, seg.bodies[static_cast<size_t>(mp)].name,
                    seg.bodies[static_cast<size_t>(mt)].name),
        ErrorElement{ErrorElement::Kind::kBody, mp});
  }
  const BodyState& sp = state.bodies[static_cast<size_t>(mp)];
  if (impact.exit_fraction > 0) {
    const Vec3 v_p = sp.v_WBcm_W;
    const Vec3 p_WP = sp.p_WBcm;
    const PassThroughResult r =
        ApplyPassThrough(model, mt, p_WP, model.body(mp).mass(), v_p, impact.exit_fraction, state);
    state.bodies[static_cast<size_t>(mp)].v_WBcm_W = r.projectile_exit_velocity_W;
    if (applied != nullptr) {
      // Action and reaction between the two at the projectile's centre of mass.
      applied->push_back({mt, {"applied", p_WP, r.impulse_W, Vec3::Zero()}});
      applied->push_back({mp, {"applied", p_WP, -r.impulse_W, Vec3::Zero()}});
    }
    return mt;
  }
  const BodyMotion target = ModelBodyMotion(model, state, mt);
  const BodyMotion projectile = ModelBodyMotion(model, state, mp);
  const EmbeddingResult e = CalcEmbedding(target, projectile);
  Segment next;
  next.map = EmbeddedMap(seg.map, mt, mp, target.R_WB, CalcBodyOriginPosition(model, state, mt),
                         projectile.R_WB, CalcBodyOriginPosition(model, state, mp));
  for (int m = 0; m < model.num_bodies(); ++m) {
    if (m == mp) continue;
    const NamedBody& body = seg.bodies[static_cast<size_t>(m)];
    if (m == mt) {
      next.bodies.push_back({body.name + "+" + seg.bodies[static_cast<size_t>(mp)].name,
                             e.composite.mass_properties});
    } else {
      next.bodies.push_back(body);
    }
  }
  if (!build) {
    throw InputError(
        fmt::format("impact at t = {:.6g} s: '{}' embeds in '{}', which needs a "
                    "ModelBuilder (build_model) for the composite body's Model",
                    impact.t, seg.bodies[static_cast<size_t>(mp)].name,
                    seg.bodies[static_cast<size_t>(mt)].name));
  }
  next.model = std::make_shared<const Model>(build(next.bodies, next.map));
  State s2 = MakeRestState(*next.model);
  s2.t = state.t;
  int k = 0, shown = 0;
  for (int m = 0; m < model.num_bodies(); ++m) {
    if (m == mp) continue;
    if (m == mt) {
      BodyState& c = s2.bodies[static_cast<size_t>(k)];
      c.p_WBcm = e.composite.p_WBcm;
      c.q_WB = Quat(e.composite.R_WB).normalized();
      c.v_WBcm_W = e.composite.v_WBcm_W;
      c.w_WB_B = e.composite.R_WB.transpose() * e.composite.w_WB_W;
      shown = k;
    } else {
      s2.bodies[static_cast<size_t>(k)] = state.bodies[static_cast<size_t>(m)];
    }
    ++k;
  }
  seg = std::move(next);
  state = std::move(s2);
  return shown;
}

std::vector<JumpImpulse> ContactJumpImpulses(const Model& model, const State& state,
                                             const std::vector<std::pair<int, Vec3>>& impulses,
                                             const std::vector<std::string>& labels) {
  std::vector<JumpImpulse> out;
  if (impulses.empty()) return out;
  const std::vector<ContactPointOutput> points = CalcContactOutputs(model, state);
  for (const auto& [p, J_W] : impulses) {
    const ContactPointOutput& o = points[static_cast<size_t>(p)];
    const Contact& c = model.contact(model.contact_of_point(p));
    const std::string source = fmt::format("contact '{}'", static_cast<size_t>(p) < labels.size()
                                                               ? labels[static_cast<size_t>(p)]
                                                               : model.contact_point_name(p));
    out.push_back({c.body(), {source, o.p_WC, J_W, Vec3::Zero()}});
    // The other sphere's surface point: C_O = c_O + R_O n = C - gap n (contact_solve.cpp).
    if (c.other_body() != kWorld) {
      out.push_back({c.other_body(), {source, o.p_WC - o.gap * o.n_W, -J_W, Vec3::Zero()}});
    }
  }
  return out;
}

Eigen::VectorXd SupportImpulseOf(const Model& model, const State& state,
                                 const std::vector<JumpImpulse>& impulses) {
  Eigen::VectorXd mu = Eigen::VectorXd::Zero(model.num_constraint_rows());
  if (model.num_constraints() == 0 || impulses.empty()) return mu;
  State scratch = state;
  for (const JumpImpulse& i : impulses) {
    ApplyImpulseAtWorldPoint(model, i.body, i.impulse.p_WP, i.impulse.J_W, scratch);
  }
  Data data = MakeData(model);
  ProjectOntoConstraints(model, scratch, data, {}, &mu);
  return mu;
}

namespace {

/// Each constraint's share of Jᵀμ on body `b` ([F; M about Bcm] in W, from the rows on b),
/// as an impulse at the constraint's point J: M_J = M_Bcm - (p_WJ - p_WBcm) × F.
// The constraints acting on each body (as child, parent or extra body), in Model order: one pass
// over the constraints, so that a jump's records cost O(bodies + constraints), not their product.
std::vector<std::vector<int>> ConstraintsOfBodies(const Model& model, const Data& data) {
  std::vector<std::vector<int>> of_body(static_cast<size_t>(model.num_bodies()));
  for (int c = 0; c < model.num_constraints(); ++c) {
    const Constraint& con = model.constraint(c);
    const ConstraintEval& e = data.constraint_rows[static_cast<size_t>(c)];
    std::vector<BodyIndex> bodies = {con.child(), con.parent()};
    for (int k = 0; k < e.num_extra; ++k) bodies.push_back(e.extra_body[static_cast<size_t>(k)]);
    std::sort(bodies.begin(), bodies.end());
    bodies.erase(std::unique(bodies.begin(), bodies.end()), bodies.end());
    for (BodyIndex b : bodies) {
      if (b >= 0 && b < model.num_bodies()) of_body[static_cast<size_t>(b)].push_back(c);
    }
  }
  return of_body;
}

// The supports' impulses on body b: each constraint `constraints` lists for it (by
// ConstraintsOfBodies).
void AddSupportImpulses(const Model& model, const State& state, const Data& data,
                        const Eigen::VectorXd& mu, int b, const std::vector<int>& constraints,
                        std::vector<BodyImpulse>& out) {
  const Vec3& p_WBcm = state.bodies[static_cast<size_t>(b)].p_WBcm;
  for (int c : constraints) {
    const Constraint& con = model.constraint(c);
    const ConstraintEval& e = data.constraint_rows[static_cast<size_t>(c)];
    const int n = con.num_rows();
    const auto mu_c = mu.segment(model.constraint_row_offset(c), n);
    const ConstraintEval::Rows* rows = nullptr;
    if (b == con.child()) rows = &e.J_child;
    if (b == con.parent()) rows = &e.J_parent;
    for (int k = 0; k < e.num_extra; ++k) {
      if (e.extra_body[static_cast<size_t>(k)] == b) rows = &e.J_extra[static_cast<size_t>(k)];
    }
    if (rows == nullptr) continue;
    const Eigen::Matrix<double, 6, 1> share = rows->topRows(n).transpose() * mu_c;
    const Vec3 F = share.head<3>();
    const Vec3 p_WJ = data.constraints[static_cast<size_t>(c)].p_WJ;
    out.push_back({con.name(), p_WJ, F, Vec3(share.tail<3>() - (p_WJ - p_WBcm).cross(F))});
  }
}

}  // namespace

void RecordJumpImpulses(const Model& model, const State& before, const State& after,
                        const Eigen::VectorXd& mu, const std::vector<JumpImpulse>& impulses,
                        int num_reported_constraints, StudyJump& jump) {
  // The reactions of the multipliers μ at the instant's configuration, by the constraint
  // stage's own conversion (CalcConstraintReactions, then MakeReactionReport): impulses now.
  Data data = MakeData(model);
  CalcKinematics(model, after, data);
  if (model.num_constraints() > 0) {
    CalcConstraintRows(model, after, data);
    CalcConstraintReactions(model, after, mu, data);
  }
  const int reported = num_reported_constraints < 0
                           ? model.num_constraints()
                           : std::min(num_reported_constraints, model.num_constraints());
  for (int c = 0; c < reported; ++c) {
    jump.reactions.push_back(MakeReactionReport(model, data, c));
    jump.reactions.back().power = 0.0;
  }
  // Each body's applied impulses, in their order, and its constraints.
  std::vector<std::vector<const JumpImpulse*>> applied(static_cast<size_t>(model.num_bodies()));
  for (const JumpImpulse& j : impulses) {
    if (j.body >= 0 && j.body < model.num_bodies())
      applied[static_cast<size_t>(j.body)].push_back(&j);
  }
  const std::vector<std::vector<int>> constraints = ConstraintsOfBodies(model, data);
  // Each body: ΔH_cm = R I_B (ω_B after - ω_B before) (the instant moves nothing).
  for (int b = 0; b < model.num_bodies(); ++b) {
    const auto i = static_cast<size_t>(b);
    const Body& body = model.body(b);
    const BodyState& s1 = after.bodies[i];
    const BodyState& s0 = before.bodies[i];
    const Mat3& R = data.R_WB[i];
    BodyImpulseBalance r;
    r.body = body.name();
    r.mass = body.mass();
    r.p_WBcm = s1.p_WBcm;
    r.v_WBcm_W = s1.v_WBcm_W;
    r.w_WB_W = R * s1.w_WB_B;
    r.dv_WBcm_W = s1.v_WBcm_W - s0.v_WBcm_W;
    r.dw_WB_W = R * (s1.w_WB_B - s0.w_WB_B);
    r.H_Bcm_W = R * (body.I_BBcm_B() * s1.w_WB_B);
    r.dH_Bcm_W = R * (body.I_BBcm_B() * (s1.w_WB_B - s0.w_WB_B));
    for (const JumpImpulse* j : applied[i]) r.impulses.push_back(j->impulse);
    AddSupportImpulses(model, after, data, mu, b, constraints[i], r.impulses);
    jump.bodies.push_back(std::move(r));
  }
}

StudyLedger FinalLedger(const StudyDefinition& definition, const Model& model, const State& state,
                        const LedgerCarry& carry, double energy_initial) {
  const LedgerSample L = CalcLedgerSample(model, state, carry.segment_initial);
  StudyLedger out;
  out.kinetic_translational = L.kinetic_translational;
  out.kinetic_rotational = L.kinetic_rotational;
  out.potential = L.potential;
  out.energy = L.mechanical_energy;
  out.energy_initial = energy_initial;
  out.work_nonconservative = carry.work_nc + L.work_nonconservative;
  out.dissipated = carry.dissipated + L.dissipated;
  for (const ContactPointState& p : state.contacts) {
    out.friction_work += p.friction_work;
    out.rolling_work += p.rolling_work;
    out.impact_work += p.impact_work;
  }
  out.friction_work += state.unlisted_contact_work.friction_work;
  out.rolling_work += state.unlisted_contact_work.rolling_work;
  out.impact_work += state.unlisted_contact_work.impact_work;
  for (const ConstraintModeState& m : state.constraint_modes) out.impact_work += m.impact_work;
  out.jumps = carry.jumps;
  out.residual = carry.residual + L.energy_residual;
  out.energy_scale = std::max(carry.scale, L.energy_scale);
  const auto carried = [&](const std::string& name) {
    const auto it = carry.work_by_force.find(name);
    return it == carry.work_by_force.end() ? 0.0 : it->second;
  };
  std::vector<std::string> forces = definition.reported_forces;
  if (forces.empty()) {
    for (const ForceLedger& fl : L.forces) forces.push_back(fl.name);
  }
  for (const ForceLedger& fl : L.forces) {
    if (fl.has_potential) out.potential_by_force.emplace_back(fl.name, fl.potential_energy);
  }
  for (const std::string& name : forces) {
    double w = carried(name);
    for (const ForceLedger& fl : L.forces) {
      if (fl.name == name) w += fl.work_nonconservative;
    }
    out.work_by_force.emplace_back(name, w);
  }
  // Only the reported constraints (a planar run's plane constraints come after them).
  const size_t reported = definition.num_reported_constraints < 0
                              ? L.constraints.size()
                              : static_cast<size_t>(definition.num_reported_constraints);
  for (const ConstraintLedger& cl : L.constraints) {
    if (out.work_by_constraint.size() == reported) break;
    out.work_by_constraint.emplace_back(cl.name, carried(cl.name) + cl.work);
  }
  out.linear_momentum_W = L.linear_momentum_W;
  out.angular_momentum_Scm_W = L.angular_momentum_Scm_W;
  out.angular_momentum_Wo_W = L.angular_momentum_Wo_W;
  return out;
}

}  // namespace chasles::study_internal
