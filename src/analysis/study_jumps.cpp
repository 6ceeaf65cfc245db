// The instants of a study where the state jumps: impulses, projectiles passing through a body,
// and projectiles that embed (a new Model with the composite body), and the ledger at the end
// (include/chasles/analysis/study.h).

#include <algorithm>

#include <fmt/format.h>

#include "chasles/analysis/ledger.h"
#include "chasles/analysis/study.h"
#include "chasles/dynamics/impulse.h"
#include "chasles/error.h"
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
  if (!definition.build_model) throw InputError("a study needs a ModelBuilder (build_model)");
  Segment seg;
  seg.bodies = definition.bodies;
  for (size_t b = 0; b < definition.bodies.size(); ++b) {
    seg.map.place.push_back({static_cast<int>(b), Mat3::Identity(), Vec3::Zero()});
    seg.map.p_BoBcm_B.push_back(definition.bodies[b].mass_properties.p_BoBcm_B());
    seg.map.mass.push_back(definition.bodies[b].mass_properties.mass());
    seg.map.I_BBcm_B.push_back(definition.bodies[b].mass_properties.I_BBcm_B().matrix());
  }
  seg.model = std::make_shared<const Model>(definition.build_model(seg.bodies, seg.map));
  if (seg.model->num_bodies() != static_cast<int>(seg.bodies.size())) {
    throw InputError(fmt::format("the ModelBuilder made {} bodies for {} study bodies",
                                 seg.model->num_bodies(), seg.bodies.size()));
  }
  return seg;
}

int ApplyStudyImpulse(const StudyImpulseSpec& impulse, const Segment& seg, State& state) {
  const BodyPlacement& pl = seg.map.place[static_cast<size_t>(impulse.body)];
  const Mat3 R_WM = state.bodies[static_cast<size_t>(pl.model_body)].q_WB.toRotationMatrix();
  const Vec3 J_W =
      impulse.frame == VectorFrame::kWorld ? impulse.J : Vec3(R_WM * pl.R_MB * impulse.J);
  ApplyImpulse(*seg.model, pl.model_body, seg.map.PointInModelBody(impulse.body, impulse.p_BoP_B),
               J_W, state);
  return pl.model_body;
}

int ApplyStudyImpact(const StudyImpactSpec& impact, const ModelBuilder& build, Segment& seg,
                     State& state) {
  const Model& model = *seg.model;
  const int mt = seg.map.place[static_cast<size_t>(impact.target)].model_body;
  const int mp = seg.map.place[static_cast<size_t>(impact.projectile)].model_body;
  if (mt == mp) {
    throw InputError(
        fmt::format("impact at t = {:.6g} s: '{}' and '{}' are already one body (an earlier impact "
                    "embedded one in the other)",
                    impact.t, seg.bodies[static_cast<size_t>(mp)].name,
                    seg.bodies[static_cast<size_t>(mt)].name));
  }
  const BodyState& sp = state.bodies[static_cast<size_t>(mp)];
  if (impact.exit_fraction > 0) {
    const Vec3 v_p = sp.v_WBcm_W;
    ApplyPassThrough(model, mt, sp.p_WBcm, model.body(mp).mass(), v_p, impact.exit_fraction, state);
    state.bodies[static_cast<size_t>(mp)].v_WBcm_W = impact.exit_fraction * v_p;
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
