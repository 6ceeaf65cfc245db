// The files of `chasles simulate` (chasles/report/simulation_report.h).

#include "chasles/report/simulation_report.h"

#include <string>
#include <vector>

#include <fmt/format.h>

#include "chasles/math/quaternion.h"
#include "chasles/report/certificate_json.h"
#include "chasles/report/json_report.h"
#include "chasles/report/result_names.h"

namespace chasles {

std::string SimulationCsv(const StudyResult& r, CsvPrecision precision) {
  // Default: the shortest text that reads back as the same double (digits 0).
  return CsvText({r.columns, r.units, r.rows, {}}, precision == CsvPrecision::kFull ? 17 : 0,
                 "the CSV time series");
}

nlohmann::json SnapshotJson(const StudySnapshot& snap, bool planar) {
  nlohmann::json bodies = nlohmann::json::array();
  for (const auto& b : snap.bodies) {
    const Eigen::Vector4d q = QuatToWxyz(b.q_WB);
    bodies.push_back({{"name", b.name},
                      {"mass", b.mass},
                      {"center_of_mass", VecJson(b.p_WBcm)},
                      {"origin", VecJson(b.p_WBo)},
                      {"quaternion", {q[0], q[1], q[2], q[3]}},
                      {"velocity", VecJson(b.v_WBcm_W)},
                      {"angular_velocity", VecJson(b.w_WB_W)},
                      {"angular_velocity_body", VecJson(b.w_WB_B)}});
    if (planar) {
      // The planar state (x, y of the centre of mass, θ continuous from the initial one).
      bodies.back()["planar"] = {{"x", b.p_WBcm.x()},    {"y", b.p_WBcm.y()},
                                 {"theta", b.theta},     {"vx", b.v_WBcm_W.x()},
                                 {"vy", b.v_WBcm_W.y()}, {"omega", b.w_WB_W.z()}};
    }
  }
  nlohmann::json reactions = nlohmann::json::array();
  for (const auto& x : snap.reactions) {
    reactions.push_back({{"name", x.name},
                         {"kind", x.kind},
                         {"point", VecJson(x.p_WJ)},
                         {"force", VecJson(x.F_Jc_W)},
                         {"moment", VecJson(x.M_Jc_W)},
                         {"force_body", VecJson(x.F_Jc_B)},
                         {"moment_body", VecJson(x.M_Jc_B)},
                         {"force_parent", VecJson(x.F_Jc_P)},
                         {"moment_parent", VecJson(x.M_Jc_P)},
                         {"power", x.power}});
    if (planar) {
      reactions.back()["planar"] = {
          {"Fx", x.F_Jc_W.x()}, {"Fy", x.F_Jc_W.y()}, {"Mz", x.M_Jc_W.z()}};
    }
  }
  nlohmann::json contacts = nlohmann::json::array();
  for (const auto& c : snap.contacts) {
    contacts.push_back({{"point", c.point},
                        {"mode", StudyContactModeName(c.mode)},
                        {"normal_force", c.normal_force},
                        {"friction_force", VecJson(c.friction_force_W)},
                        {"slip_velocity", VecJson(c.slip_velocity_W)},
                        {"gap", c.gap},
                        {"friction_work", c.friction_work},
                        {"rolling_work", c.rolling_work},
                        {"impact_work", c.impact_work},
                        {"rolling_moment", VecJson(c.rolling_moment_W)}});
  }
  nlohmann::json j = {{"bodies", bodies}, {"reactions", reactions}};
  if (!snap.contacts.empty()) j["contacts"] = contacts;
  return j;
}

namespace {

/// The supports' impulsive reactions of a jump (StudyJump::reactions): impulses on the child
/// at the joint point, in W, in the child's frame and in the parent's [N·s, N·m·s].
nlohmann::json ImpulsiveReactionsJson(const std::vector<StudyReaction>& reactions, bool planar) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& x : reactions) {
    out.push_back({{"name", x.name},
                   {"kind", x.kind},
                   {"point", VecJson(x.p_WJ)},
                   {"impulse", VecJson(x.F_Jc_W)},
                   {"moment_impulse", VecJson(x.M_Jc_W)},
                   {"impulse_body", VecJson(x.F_Jc_B)},
                   {"moment_impulse_body", VecJson(x.M_Jc_B)},
                   {"impulse_parent", VecJson(x.F_Jc_P)},
                   {"moment_impulse_parent", VecJson(x.M_Jc_P)},
                   {"multipliers", x.lambda}});
    if (planar) {
      out.back()["planar"] = {{"Jx", x.F_Jc_W.x()}, {"Jy", x.F_Jc_W.y()}, {"Mz", x.M_Jc_W.z()}};
    }
  }
  return out;
}

/// Every body's velocity jumps and the impulses on it (StudyJump::bodies), so that m Δv = ΣJ
/// and ΔH_cm = Σ (r × J + M) can be checked from the JSON alone.
nlohmann::json JumpBodiesJson(const std::vector<BodyImpulseBalance>& bodies, bool planar) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& b : bodies) {
    nlohmann::json impulses = nlohmann::json::array();
    for (const BodyImpulse& i : b.impulses) {
      impulses.push_back({{"source", i.source},
                          {"point", VecJson(i.p_WP)},
                          {"impulse", VecJson(i.J_W)},
                          {"moment_impulse", VecJson(i.M_W)}});
    }
    out.push_back({{"name", b.body},
                   {"mass", b.mass},
                   {"center_of_mass", VecJson(b.p_WBcm)},
                   {"velocity_after", VecJson(b.v_WBcm_W)},
                   {"angular_velocity_after", VecJson(b.w_WB_W)},
                   {"velocity_change", VecJson(b.dv_WBcm_W)},
                   {"angular_velocity_change", VecJson(b.dw_WB_W)},
                   {"angular_momentum_after", VecJson(b.H_Bcm_W)},
                   {"angular_momentum_change", VecJson(b.dH_Bcm_W)},
                   {"impulses", impulses}});
    if (planar) {
      out.back()["planar"] = {
          {"dvx", b.dv_WBcm_W.x()}, {"dvy", b.dv_WBcm_W.y()}, {"domega", b.dw_WB_W.z()}};
    }
  }
  return out;
}

nlohmann::json JumpsJson(const std::vector<StudyJump>& jumps, bool planar) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& x : jumps) {
    out.push_back({{"kind", StudyJumpKindName(x.kind)},
                   {"description", x.description},
                   {"t", x.t},
                   {"energy_before", x.energy_before},
                   {"energy_after", x.energy_after},
                   {"energy_change", x.energy_after - x.energy_before},
                   {"velocity_after", VecJson(x.v_after_W)},
                   {"angular_velocity_after", VecJson(x.w_after_W)},
                   {"reactions", ImpulsiveReactionsJson(x.reactions, planar)},
                   {"bodies", JumpBodiesJson(x.bodies, planar)},
                   {"impacts", x.impacts}});
  }
  return out;
}

nlohmann::json ContactEventsJson(const std::vector<StudyContactEvent>& events) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& e : events) {
    out.push_back({{"t", e.t},
                   {"point", e.point},
                   {"contact", e.contact},
                   {"from", StudyContactModeName(e.from)},
                   {"to", StudyContactModeName(e.to)},
                   {"reason", ContactEventReasonName(e.reason)}});
  }
  return out;
}

nlohmann::json StringEventsJson(const std::vector<StudyStringEvent>& events) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& e : events) {
    out.push_back({{"t", e.t},
                   {"string", e.string},
                   {"from", StringModeName(e.from)},
                   {"to", StringModeName(e.to)},
                   {"reason", ConstraintEventReasonName(e.reason)}});
    if (e.reason == ConstraintEventReason::kSnappedTaut) {
      out.back()["approach_speed"] = e.approach_speed;
      out.back()["impulse"] = e.impulse;
      out.back()["energy_lost"] = e.energy_lost;
    }
  }
  return out;
}

nlohmann::json ImpactsJson(const std::vector<StudyImpact>& impacts) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& x : impacts) {
    out.push_back(
        {{"t", x.t},
         {"point", x.point},
         {"approach_speed", x.approach_speed},
         {"normal_impulse", x.normal_impulse},
         {"energy_lost", x.energy_lost},
         {"accumulation", x.accumulation},
         {"jam", x.jam},
         {"restitution_law", x.restitution_law ? RestitutionLawName(*x.restitution_law) : ""}});
    if (x.frictionless_fallback) out.back()["frictionless_fallback"] = true;
    if (x.accumulation) out.back()["rest_time"] = x.rest_time;
  }
  return out;
}

/// The energy/work/momentum ledger from t = 0 (chasles/analysis/study.h, StudyLedger).
nlohmann::json LedgerJson(const StudyLedger& L) {
  nlohmann::json work = nlohmann::json::object();
  for (const auto& [name, w] : L.work_by_force) work[name] = w;
  nlohmann::json potential = nlohmann::json::object();
  for (const auto& [name, v] : L.potential_by_force) potential[name] = v;
  nlohmann::json constraint_work = nlohmann::json::object();
  for (const auto& [name, w] : L.work_by_constraint) constraint_work[name] = w;
  return {{"kinetic_translational", L.kinetic_translational},
          {"kinetic_rotational", L.kinetic_rotational},
          {"potential", L.potential},
          {"energy", L.energy},
          {"energy_initial", L.energy_initial},
          {"work_nonconservative", L.work_nonconservative},
          {"work_by_force", work},
          {"potential_by_force", potential},
          {"work_by_constraint", constraint_work},
          {"friction_work", L.friction_work},
          {"rolling_work", L.rolling_work},
          {"impact_work", L.impact_work},
          {"dissipated", L.dissipated},
          {"jumps", L.jumps},
          {"residual", L.residual},
          {"energy_scale", L.energy_scale},
          {"relative_residual", L.energy_scale > 0 ? L.residual / L.energy_scale : 0.0},
          {"linear_momentum", VecJson(L.linear_momentum_W)},
          {"angular_momentum_cm", VecJson(L.angular_momentum_Scm_W)},
          {"angular_momentum_origin", VecJson(L.angular_momentum_Wo_W)}};
}

/// The certificate of time-stepped steps: the worst step and the ledger's totals.
nlohmann::json SteppingSummaryJson(const TimeSteppingSummary& c) {
  return {{"residual_impulse", c.max_residual_impulse},
          {"residual_velocity", c.max_residual_velocity},
          {"momentum_residual", c.max_momentum_residual},
          {"angular_momentum_residual", c.max_angular_momentum_residual},
          {"max_penetration", c.max_penetration},
          {"max_gap_drift", c.max_gap_drift},
          {"velocity_error_estimate", c.max_velocity_error},
          {"angular_velocity_error_estimate", c.max_angular_velocity_error},
          {"accumulated_velocity_error_estimate", c.accumulated_velocity_error},
          {"regime_changes", c.regime_changes},
          {"largest_island", c.largest_island},
          {"newton_iterations", c.newton_iterations},
          {"sweeps", c.sweeps},
          {"energy",
           {{"initial", c.initial_energy},
            {"final", c.final_energy},
            {"nonconservative", c.work_nonconservative},
            {"normal_impulses", c.work_normal},
            {"friction_impulses", c.work_friction},
            {"scheme_error", c.numerical_energy_error}}}};
}

/// integrator: auto: each engine's stretch of the run and why it took over.
nlohmann::json EngineSegmentsJson(const std::vector<StudyEngineSegment>& segments) {
  nlohmann::json out = nlohmann::json::array();
  for (const StudyEngineSegment& g : segments) {
    nlohmann::json x = {{"t_begin", g.t_begin},
                        {"t_end", g.t_end},
                        {"engine", StudyEngineName(g.engine)},
                        {"reason", EngineSwitchName(g.reason)},
                        {"steps", g.stats.steps},
                        {"rejected_steps", g.stats.rejected_steps},
                        {"function_evaluations", g.stats.function_evaluations}};
    if (g.engine == StudyEngine::kAdaptive) x["islands"] = g.islands;
    switch (g.reason) {
      case EngineSwitch::kStart:
        if (!g.stays.empty()) {
          x[g.engine == StudyEngine::kStepping ? "stays_time_stepped" : "stays_event_driven"] =
              g.stays;
        }
        break;
      case EngineSwitch::kRegimeChanges:
        x["changes"] = g.changes;
        x["span"] = g.span;
        x["last_at"] = g.where;
        break;
      case EngineSwitch::kQuiet:
        x["quiet"] = g.quiet;
        x["projection"] = {{"depth", g.projection_depth}, {"energy", g.projection_energy}};
        break;
    }
    if (g.engine == StudyEngine::kStepping) {
      x["time_stepping"] = SteppingSummaryJson(g.stepping);
      x["time_stepping"]["tolerance_met"] = g.tolerance_met;
    }
    out.push_back(std::move(x));
  }
  return out;
}

}  // namespace

nlohmann::json SimulationJson(const StudyResult& r, const ReportHeader& header,
                              const std::string& csv_path) {
  nlohmann::json j;
  j["scene"] = header.scene_file;
  j["title"] = header.title;
  j["units"] = "SI";
  j["planar"] = header.planar;
  j["csv"] = csv_path;
  j["columns"] = r.columns;
  // The unit of each column, as the CSV header gives it after the name ("" for a pure number).
  if (r.units.size() == r.columns.size()) j["column_units"] = r.units;
  j["t_end"] = r.t_end;
  j["stopped_by_event"] = r.stopped_by_event;
  j["events"] = nlohmann::json::array();
  for (const auto& e : r.events) {
    j["events"].push_back({{"name", e.name},
                           {"t", e.t},
                           {"stopped", e.stopped},
                           {"state", SnapshotJson(e.snapshot, header.planar)}});
  }
  j["jumps"] = JumpsJson(r.jumps, header.planar);
  j["final"] =
      SnapshotJson({r.final_bodies, r.final_reactions, r.final_contacts, {}}, header.planar);
  j["final"]["t"] = r.t_end;
  j["contact_events"] = ContactEventsJson(r.contact_events);
  j["impacts"] = ImpactsJson(r.impacts);
  j["string_events"] = StringEventsJson(r.string_events);
  j["ledger"] = LedgerJson(r.ledger);
  j["integrator"] = {{"name", StudyIntegratorName(r.engine, r.integrator)},
                     {"steps", r.stats.steps},
                     {"rejected_steps", r.stats.rejected_steps},
                     {"function_evaluations", r.stats.function_evaluations}};
  if (r.event_driven) {
    const StudyEventDriven& e = *r.event_driven;
    j["integrator"]["event_driven"] = {{"collisions", e.collisions},
                                       {"impacts", e.stats.impacts},
                                       {"phase_events", e.stats.phase_events},
                                       {"box_renewals", e.stats.box_renewals},
                                       {"pair_tests", e.stats.pair_tests},
                                       {"pressing_groups", e.stats.groups},
                                       {"group_runs", e.stats.group_windows},
                                       {"energy",
                                        {{"initial", e.energy.initial},
                                         {"final", e.energy.final},
                                         {"friction", e.energy.friction},
                                         {"rolling", e.energy.rolling},
                                         {"impacts", e.energy.impacts},
                                         {"residual", e.energy.residual}}}};
  }
  if (r.time_stepping) {
    j["integrator"]["time_stepping"] = SteppingSummaryJson(r.time_stepping->summary);
    j["integrator"]["time_stepping"]["step"] = r.time_stepping->step;
    j["integrator"]["time_stepping"]["tolerance_met"] = r.time_stepping->tolerance_met;
    nlohmann::json points = nlohmann::json::array();
    for (const auto& [label, changes] : r.time_stepping->regime_changes) {
      points.push_back({{"point", label}, {"regime_changes", changes}});
    }
    j["integrator"]["time_stepping"]["points"] = std::move(points);
  }
  if (r.engine_rule) {
    const EngineChoiceRule& rule = *r.engine_rule;
    j["integrator"]["auto"] = {{"step", rule.step},
                               {"changes", rule.changes},
                               {"window", rule.window},
                               {"quiet_span", rule.quiet_span},
                               {"default", r.engine_by_default}};
    j["integrator"]["segments"] = EngineSegmentsJson(r.segments);
    j["ledger"]["time_stepping_error"] = r.ledger.time_stepping_error;
  }
  if (r.islands.count > 0) {
    j["integrator"]["islands"] = {
        {"count", r.islands.count}, {"split", r.islands.split}, {"reason", r.islands.reason}};
  }
  j["run_path"] = {{"path", RunPathName(r.run_path.path)}, {"reason", r.run_path.reason}};
  j["notes"] = r.notes;
  std::vector<std::string> warnings = header.warnings;
  warnings.insert(warnings.end(), r.warnings.begin(), r.warnings.end());
  for (const std::string& w : r.certificate.FailureMessages()) warnings.push_back(w);
  j["warnings"] = warnings;
  j["checks"] = CertificateJson(r.certificate);
  return j;
}

}  // namespace chasles
