#include "chasles/report/simulation_text.h"
#include "chasles/report/result_names.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "chasles/math/quaternion.h"
#include "chasles/report/certificate_text.h"
#include "chasles/report/text_format.h"

namespace chasles {

namespace {

/// Sizes of the report's kinds of quantity, so that round-off next to them prints as 0: a
/// speed and an angular speed per body from the run's energy scale (½ m v² = E, ½ I ω² = E),
/// a force and a moment from the largest reaction or contact force and its lever arm.
struct ReportScales {
  double speed = 0.0, length = 0.0, force = 0.0, moment = 0.0;
  std::vector<double> body_speed, body_rate;
};

ReportScales CalcReportScales(const StudyResult& r) {
  ReportScales k;
  const double E = r.ledger.energy_scale;
  for (const auto& b : r.final_bodies) {
    const double v = b.mass > 0.0 ? std::sqrt(2.0 * E / b.mass) : 0.0;
    k.body_speed.push_back(v);
    k.body_rate.push_back(b.inertia_max > 0.0 ? std::sqrt(2.0 * E / b.inertia_max) : 0.0);
    k.speed = std::max(k.speed, v);
    k.length = std::max(k.length, b.p_WBcm.stableNorm());
  }
  for (const auto& x : r.final_reactions) {
    k.force = std::max(k.force, x.F_Jc_W.stableNorm());
    k.moment = std::max(k.moment, x.M_Jc_W.stableNorm());
    k.length = std::max(k.length, x.p_WJ.stableNorm());
  }
  for (const auto& c : r.final_contacts) {
    k.force = std::max({k.force, std::abs(c.normal_force), c.friction_force_W.stableNorm()});
  }
  k.moment = std::max(k.moment, k.force * k.length);
  return k;
}

/// The state at an event, concisely: per body position, velocity and angular velocity (world
/// frame), per reaction force and moment, per contact point mode, N and friction.
std::string SnapshotText(const Scene& scene, const StudySnapshot& snap, const Show& show,
                         const ReportScales& k) {
  std::string out;
  for (size_t i = 0; i < snap.bodies.size(); ++i) {
    const auto& b = snap.bodies[i];
    const double v_s = i < k.body_speed.size() ? k.body_speed[i] : k.speed;
    const double w_s = i < k.body_rate.size() ? k.body_rate[i] : 0.0;
    if (scene.planar) {
      out += fmt::format("    {}: x, y {}, theta {}; v {}, omega {}\n", b.name,
                         show.Xy(b.p_WBcm, kLength, k.length),
                         show(b.theta, kDimensionless, Angular::kYes),
                         show.Xy(b.v_WBcm_W, kVelocity, v_s),
                         show(show.Clean(b.w_WB_W.z(), w_s), kRate, Angular::kYes));
      continue;
    }
    out += fmt::format("    {}: position {}, velocity {}, angular velocity {}\n", b.name,
                       show(b.p_WBcm, kLength, Angular::kNo, k.length),
                       show(b.v_WBcm_W, kVelocity, Angular::kNo, v_s),
                       show(b.w_WB_W, kRate, Angular::kYes, w_s));
  }
  for (const auto& x : snap.reactions) {
    if (scene.planar) {
      out += fmt::format("    {}: force {}, moment {}\n", x.name,
                         show.Xy(x.F_Jc_W, kForce, k.force), show(x.M_Jc_W.z(), kMoment));
      continue;
    }
    out += fmt::format("    {}: force {}, moment {}\n", x.name,
                       show(x.F_Jc_W, kForce, Angular::kNo, k.force),
                       show(x.M_Jc_W, kMoment, Angular::kNo, k.moment));
  }
  for (const auto& c : snap.contacts) {
    out += fmt::format("    {}: {}, N = {}, friction {}\n", c.point, StudyContactModeName(c.mode),
                       show(c.normal_force, kForce),
                       scene.planar ? show.Xy(c.friction_force_W, kForce, k.force)
                                    : show(c.friction_force_W, kForce, Angular::kNo, k.force));
  }
  return out;
}

/// "1 collision", "2 collisions".
std::string Count(long n, const char* noun) {
  return fmt::format("{} {}{}", n, noun, n == 1 ? "" : "s");
}

/// The certificate of time-stepped steps (docs/contact.md, "Time stepping"): the worst step's
/// values and the ledger's totals, each line after `indent`. An accumulated estimate above the
/// run's largest speed (`speed_scale`, the certificate's) says that it bounds nothing there.
std::string SteppingCertificateText(const TimeSteppingSummary& c, bool tolerance_met, const Show& u,
                                    const char* indent, double speed_scale) {
  std::string loose;
  if (speed_scale > 0.0 && c.accumulated_velocity_error > speed_scale) {
    loose = fmt::format(
        ", more than the run's largest speed {} and so no bound here (collisions that share a "
        "body within one step are charged whole: docs/contact.md, \"The accumulated error "
        "estimate\")",
        u(speed_scale, kVelocity));
  }
  std::string out = fmt::format(
      "{}contact problems' residual at most {} ({}); momentum balance to {}, angular momentum "
      "to {}\n",
      indent, u(c.max_residual_impulse, kMomentum), u(c.max_residual_velocity, kVelocity),
      u(c.max_momentum_residual, kMomentum), u(c.max_angular_momentum_residual, kAngularMomentum));
  out += fmt::format(
      "{}penetration at most {}, gap drift at most {}; step-doubling error estimate per step at "
      "most {} ({}), the accumulated velocity error estimated at {}{}{}\n",
      indent, u(c.max_penetration, kLength), u(c.max_gap_drift, kLength),
      u(c.max_velocity_error, kVelocity), u(c.max_angular_velocity_error, kRate, Angular::kYes),
      u(c.accumulated_velocity_error, kVelocity), loose,
      tolerance_met ? "" : " (a tolerance was missed: see the warnings)");
  out += fmt::format(
      "{}energy: {} at the start, {} at the end; non-conservative forces {}, normal impulses {}, "
      "friction {}; the scheme's own error {}\n",
      indent, u.Energy(c.initial_energy), u.Energy(c.final_energy),
      u.Energy(c.work_nonconservative), u.Energy(c.work_normal), u.Energy(c.work_friction),
      u.Energy(c.numerical_energy_error));
  return out;
}

/// Moreau–Jean: the certificate of its steps, the worst step's values and the ledger's totals;
/// the point whose regime changed most.
std::string SteppingText(const StudyResult& r, const Show& u) {
  const StudyResult::TimeStepped& ts = *r.time_stepping;
  const TimeSteppingSummary& c = ts.summary;
  std::string busiest = "none";
  int most = 0;
  for (const auto& [label, changes] : ts.regime_changes) {
    if (changes > most) {
      most = changes;
      busiest = fmt::format("most at {}: {}", label, changes);
    }
  }
  std::string out = fmt::format(
      "\nIntegrator: stepping (Moreau–Jean, step {}): {} steps, {} ({}), largest contact "
      "problem {} points\n",
      u.Time(ts.step), r.stats.steps, Count(c.regime_changes, "regime change"), busiest,
      c.largest_island);
  return out + SteppingCertificateText(c, ts.tolerance_met, u, "  ", r.certificate.velocity_scale);
}

/// Why an engine took over (integrator: auto).
std::string SwitchText(const StudyEngineSegment& g, const Show& u) {
  switch (g.reason) {
    case EngineSwitch::kStart:
      return g.stays.empty()
                 ? "start"
                 : fmt::format("start; stays {}: {}",
                               g.engine == StudyEngine::kStepping ? "time stepped" : "event-driven",
                               g.stays);
    case EngineSwitch::kRegimeChanges:
      return fmt::format("{} regime changes within {} (the last at {}): faster than the bound",
                         g.changes, u.Time(g.span), g.where);
    case EngineSwitch::kQuiet:
      return fmt::format(
          "no regime change for {}; the touching points projected onto their planes: {} deep "
          "at most, energy changed by {}",
          u.Time(g.quiet), u(g.projection_depth, kLength), u.Energy(g.projection_energy));
  }
  return "";
}

/// integrator: auto: the rule, then each engine's stretch of the run, why it took over and its
/// work (a time-stepped one with the certificate of its steps).
std::string EnginesText(const StudyResult& r, const Show& u) {
  const EngineChoiceRule& rule = *r.engine_rule;
  const char* named = r.engine_by_default ? ", the default for a scene with contacts" : "";
  // A run that stays on one engine: the rule has nothing to say, only why (and a time-stepped
  // one its certificate).
  if (r.segments.size() == 1 && !r.segments[0].stays.empty() &&
      r.segments[0].engine == StudyEngine::kStepping) {
    const StudyEngineSegment& g = r.segments[0];
    return fmt::format(
               "\nIntegrator: auto{} (time stepped throughout with step {}: {}): {} steps, {}, "
               "largest contact problem {} points\n",
               named, u.Time(rule.step), g.stays, g.stepping.steps,
               Count(g.stepping.regime_changes, "regime change"), g.stepping.largest_island) +
           SteppingCertificateText(g.stepping, g.tolerance_met, u, "    ",
                                   r.certificate.velocity_scale);
  }
  if (r.segments.size() == 1 && !r.segments[0].stays.empty()) {
    const int islands = r.segments[0].islands;
    return fmt::format(
        "\nIntegrator: auto{} (event-driven throughout: {}): {} steps, {} rejected, {} "
        "evaluations{}\n",
        named, r.segments[0].stays, r.stats.steps, r.stats.rejected_steps,
        r.stats.function_evaluations,
        islands > 1 ? fmt::format("; {} islands, each its own hybrid system (the counts are "
                                  "their sums)",
                                  islands)
                    : std::string());
  }
  std::string out = fmt::format(
      "\nIntegrator: auto{} (event-driven, time stepped with step {} while {} regime changes "
      "come within {}, back after {} without one): {} steps, {} rejected, {} evaluations\n",
      named, u.Time(rule.step), rule.changes, u.Time(rule.window), u.Time(rule.quiet_span),
      r.stats.steps, r.stats.rejected_steps, r.stats.function_evaluations);
  for (const StudyEngineSegment& g : r.segments) {
    out += fmt::format("  {} to {}: {}, {}\n", u.Time(g.t_begin), u.Time(g.t_end),
                       StudyEngineName(g.engine), SwitchText(g, u));
    if (g.engine == StudyEngine::kAdaptive) {
      out += fmt::format(
          "    {} steps, {} rejected, {} evaluations{}\n", g.stats.steps, g.stats.rejected_steps,
          g.stats.function_evaluations,
          g.islands > 1
              ? fmt::format("; {} islands, each its own hybrid system (the counts are their sums)",
                            g.islands)
              : std::string());
      continue;
    }
    out +=
        fmt::format("    {} steps, {}, largest contact problem {} points\n", g.stepping.steps,
                    Count(g.stepping.regime_changes, "regime change"), g.stepping.largest_island);
    out += SteppingCertificateText(g.stepping, g.tolerance_met, u, "    ",
                                   r.certificate.velocity_scale);
  }
  return out;
}

/// Items first to last, or, past head + tail + 1 of them, the first `head`, a line saying how
/// many more the JSON summary has (`what`: "event", "change", "impact"), and the last `tail`:
/// a long run can record thousands.
template <typename T, typename F>
std::string Abridged(const std::vector<T>& items, size_t head, size_t tail, const char* what,
                     F line) {
  std::string out;
  const size_t n = items.size();
  for (size_t i = 0; i < n; ++i) {
    if (n > head + tail + 1 && i == head) {
      out +=
          fmt::format("  ... {} more (every {} is in the JSON summary)\n", n - head - tail, what);
      i = n - tail - 1;
      continue;
    }
    out += line(items[i]);
  }
  return out;
}

std::string EventsText(const Scene& scene, const StudyResult& r, const Show& show) {
  if (r.events.empty()) return "";
  return "\nEvents\n" + Abridged(r.events, 10, 3, "event", [&](const StudyEvent& e) {
           return fmt::format("  {:<24} t = {}{}\n", e.name, show(e.t, kTime),
                              e.stopped ? "  (stop)" : "") +
                  SnapshotText(scene, e.snapshot, show, CalcReportScales(r));
         });
}

/// One jump's velocity jumps per body and the supports' impulsive reactions (on the child at
/// the joint point, world frame; planar: [x, y] and about z). Components below 1e-12 of the
/// jump's largest of their kind are round-off and print as 0.
std::string JumpDetailText(const Scene& scene, const StudyJump& x, const Show& show,
                           double length) {
  double dv = 0.0, dw = 0.0, J = 0.0, M = 0.0;
  for (const BodyImpulseBalance& b : x.bodies) {
    dv = std::max(dv, b.dv_WBcm_W.stableNorm());
    dw = std::max(dw, b.dw_WB_W.stableNorm());
    J = std::max(J, b.mass * b.dv_WBcm_W.stableNorm());
  }
  for (const StudyReaction& r : x.reactions) {
    J = std::max(J, r.F_Jc_W.stableNorm());
    M = std::max(M, r.M_Jc_W.stableNorm());
  }
  M = std::max(M, J * length);
  std::string out = scene.planar ? "    velocity jumps (centre of mass [x, y], angular about z)\n"
                                 : "    velocity jumps (centre of mass, angular; world frame)\n";
  for (const BodyImpulseBalance& b : x.bodies) {
    out += scene.planar ? fmt::format("      {}: dv {}, domega {}\n", b.body,
                                      show.Xy(b.dv_WBcm_W, kVelocity, dv),
                                      show(show.Clean(b.dw_WB_W.z(), dw), kRate, Angular::kYes))
                        : fmt::format("      {}: dv {}, dw {}\n", b.body,
                                      show(b.dv_WBcm_W, kVelocity, Angular::kNo, dv),
                                      show(b.dw_WB_W, kRate, Angular::kYes, dw));
  }
  if (!x.reactions.empty()) {
    out += "    impulsive reactions (on the child at the joint point)\n";
  }
  for (const StudyReaction& r : x.reactions) {
    out += scene.planar
               ? fmt::format("      {} at {}: impulse {}, moment impulse {}\n", r.name,
                             show.Xy(r.p_WJ, kLength, length), show.Xy(r.F_Jc_W, kMomentum, J),
                             show(show.Clean(r.M_Jc_W.z(), M), kAngularMomentum))
               : fmt::format("      {} at {}: impulse {}, moment impulse {}\n", r.name,
                             show(r.p_WJ, kLength, Angular::kNo, length),
                             show(r.F_Jc_W, kMomentum, Angular::kNo, J),
                             show(r.M_Jc_W, kAngularMomentum, Angular::kNo, M));
  }
  if (!x.impacts.empty()) {
    out += fmt::format("    contact impacts at this instant: {} (under \"Impacts at contacts\")\n",
                       x.impacts.size());
  }
  return out;
}

std::string JumpsText(const Scene& scene, const StudyResult& r, const Show& u,
                      const ReportScales& k) {
  if (r.jumps.empty()) return "";
  std::string out = "\nImpulses and impacts\n";
  for (const auto& x : r.jumps) {
    out += fmt::format("  t = {}: {}; energy {} -> {} (change {})\n", u.Time(x.t), x.description,
                       u.Energy(x.energy_before), u.Energy(x.energy_after),
                       u.Energy(x.energy_after - x.energy_before));
    out += scene.planar
               ? fmt::format("    afterwards: v = {}, omega = {}\n", u.Xy(x.v_after_W, kVelocity),
                             u(x.w_after_W.z(), kRate, Angular::kYes))
               : fmt::format("    afterwards: v = {}, w = {}\n", u(x.v_after_W, kVelocity),
                             u(x.w_after_W, kRate, Angular::kYes));
    out += JumpDetailText(scene, x, u, k.length);
  }
  return out;
}

std::string ContactEventsText(const StudyResult& r, const Show& u) {
  if (r.contact_events.empty()) return "";
  return "\nContact modes (time, contact point: from -> to, why)\n" +
         Abridged(r.contact_events, 20, 5, "change", [&](const StudyContactEvent& e) {
           const char* from = StudyContactModeName(e.from);
           const char* to = StudyContactModeName(e.to);
           const char* why = ContactEventReasonName(e.reason);
           if (e.from == e.to && e.reason == ContactEventReason::kRollingStopped) {  // turned
             return fmt::format("  t = {}  {}: {} (rolling stopped and rolls on the other way)\n",
                                u.Time(e.t), e.point, to);
           }
           if (e.from == e.to && e.reason != ContactEventReason::kInitial) {  // a bounce
             return fmt::format("  t = {}  {}: stays {} ({})\n", u.Time(e.t), e.point, to, why);
           }
           if (e.from == e.to) {
             return fmt::format("  t = {}  {}: {} ({})\n", u.Time(e.t), e.point, to, why);
           }
           return fmt::format("  t = {}  {}: {} -> {} ({})\n", u.Time(e.t), e.point, from, to, why);
         });
}

std::string StringEventsText(const StudyResult& r, const Show& u) {
  if (r.string_events.empty()) return "";
  return "\nString modes (time, string: from -> to, why)\n" +
         Abridged(r.string_events, 20, 5, "change", [&](const StudyStringEvent& e) {
           const char* why = ConstraintEventReasonName(e.reason);
           std::string line =
               e.from == e.to
                   ? fmt::format("  t = {}  string '{}': {} ({})\n", u.Time(e.t), e.string,
                                 StringModeName(e.to), why)
                   : fmt::format("  t = {}  string '{}': {} -> {} ({})\n", u.Time(e.t), e.string,
                                 StringModeName(e.from), StringModeName(e.to), why);
           const bool snapped = e.reason == ConstraintEventReason::kSnappedTaut;
           if (snapped && e.to == ConstraintMode::kReleased) {
             line += "    it rebounded (restitution): taut for an instant, slack again at once\n";
           }
           if (snapped) {
             line += fmt::format("    approach speed {}, impulse {}, energy lost {}\n",
                                 u(e.approach_speed, kVelocity), u(e.impulse, kMomentum),
                                 u.Energy(e.energy_lost));
           }
           return line;
         });
}

std::string ImpactText(const StudyImpact& x, const Show& u) {
  std::string out = fmt::format(
      "  t = {}  {}: approach speed {}, energy lost {}{}\n", u.Time(x.t), x.point,
      u(x.approach_speed, kVelocity), u.Energy(x.energy_lost),
      x.jam ? "" : fmt::format(" ({} restitution)", RestitutionLawName(*x.restitution_law)));
  if (x.jam) {
    out +=
        "    a jam: the slip had no consistent contact forces (Painlevé) and was stopped "
        "by this impulse (see the warnings)\n";
  }
  if (x.frictionless_fallback) {
    out +=
        "    warning: the impulse with friction would have raised the kinetic energy (the "
        "restitution law allows it); the frictionless impulse was used\n";
  }
  if (x.accumulation) {
    out += fmt::format(
        "    the bounces shrink by the ratio e: this impact is made plastic; the remaining "
        "bounces (their sum) end at t = {}\n",
        u.Time(x.rest_time));
  }
  return out;
}

std::string ImpactsText(const StudyResult& r, const Show& u) {
  if (r.impacts.empty()) return "";
  return fmt::format("\nImpacts at contacts: {}\n", r.impacts.size()) +
         Abridged(r.impacts, 10, 3, "impact",
                  [&](const StudyImpact& x) { return ImpactText(x, u); });
}

std::string FinalStateText(const Scene& scene, const StudyResult& r, const Show& show,
                           const ReportScales& k) {
  std::string out =
      scene.planar
          ? "\nFinal state (planar, x-y plane: centre of mass, angle and rates about z)\n"
          : "\nFinal state (centre of mass, velocity and angular velocity in the world frame)\n";
  for (size_t i = 0; i < r.final_bodies.size(); ++i) {
    const auto& b = r.final_bodies[i];
    const double v_s = k.body_speed[i], w_s = k.body_rate[i];
    if (scene.planar) {
      // Chapter eqs. 8.41-8.43: x, y, θ and their rates.
      out += fmt::format("  {}\n    position {}, theta {}\n    velocity {}, omega {}\n", b.name,
                         show.Xy(b.p_WBcm, kLength, k.length),
                         show(b.theta, kDimensionless, Angular::kYes),
                         show.Xy(b.v_WBcm_W, kVelocity, v_s),
                         show(show.Clean(b.w_WB_W.z(), w_s), kRate, Angular::kYes));
      continue;
    }
    const Eigen::Vector4d q = QuatToWxyz(b.q_WB);
    // A unit quaternion's components are known to round-off against 1.
    out += fmt::format(
        "  {}\n    position {}\n    quaternion [{}, {}, {}, {}]\n"
        "    velocity {}\n    angular velocity {} (body frame {})\n",
        b.name, show(b.p_WBcm, kLength, Angular::kNo, k.length), show.Number(show.Clean(q[0], 1.0)),
        show.Number(show.Clean(q[1], 1.0)), show.Number(show.Clean(q[2], 1.0)),
        show.Number(show.Clean(q[3], 1.0)), show(b.v_WBcm_W, kVelocity, Angular::kNo, v_s),
        show(b.w_WB_W, kRate, Angular::kYes, w_s), show(b.w_WB_B, kRate, Angular::kYes, w_s));
  }
  return out;
}

std::string EndReactionsText(const Scene& scene, const StudyResult& r, const Show& show,
                             const ReportScales& k) {
  if (r.final_reactions.empty()) return "";
  std::string out = "\nReactions at the end (on the child at the joint point, world frame)\n";
  for (const auto& x : r.final_reactions) {
    if (scene.planar) {
      out += fmt::format("  {} ({}) at {}\n    force {}\n    moment {}\n", x.name, x.kind,
                         show.Xy(x.p_WJ, kLength, k.length), show.Xy(x.F_Jc_W, kForce, k.force),
                         show(show.Clean(x.M_Jc_W.z(), k.moment), kMoment));
      continue;
    }
    out += fmt::format("  {} ({}) at {}\n    force {}\n    moment {}\n", x.name, x.kind,
                       show(x.p_WJ, kLength, Angular::kNo, k.length),
                       show(x.F_Jc_W, kForce, Angular::kNo, k.force),
                       show(x.M_Jc_W, kMoment, Angular::kNo, k.moment));
  }
  return out;
}

std::string EndContactsText(const Scene& scene, const StudyResult& r, const Show& show,
                            const ReportScales& k) {
  if (r.final_contacts.empty()) return "";
  std::string out = "\nContacts at the end (forces on the body, world frame)\n";
  for (const auto& c : r.final_contacts) {
    out += fmt::format("  {}: {}, N = {}, friction {}, slip {}, gap {}\n", c.point,
                       StudyContactModeName(c.mode), show(c.normal_force, kForce),
                       scene.planar ? show.Xy(c.friction_force_W, kForce, k.force)
                                    : show(c.friction_force_W, kForce, Angular::kNo, k.force),
                       scene.planar ? show.Xy(c.slip_velocity_W, kVelocity, k.speed)
                                    : show(c.slip_velocity_W, kVelocity, Angular::kNo, k.speed),
                       show(show.Clean(c.gap, k.length), kLength));
    if (c.rolling_moment_W.squaredNorm() > 0.0) {
      // Rolling resistance: the moment holding the rolling, or resisting it (about z in a
      // planar scene).
      out += fmt::format("    rolling-resistance moment {}\n",
                         scene.planar ? show(show.Clean(c.rolling_moment_W.z(), k.moment), kMoment)
                                      : show(c.rolling_moment_W, kMoment, Angular::kNo,
                                             std::max(k.moment, c.rolling_moment_W.norm())));
    }
  }
  return out;
}

std::string LedgerText(const Scene& scene, const StudyResult& r, const Show& u) {
  const StudyLedger& L = r.ledger;
  // Works and kinetic energies below 1e-12 of the energy scale are round-off (an ideal
  // joint's work, a body brought to rest) and print as 0; the balance residual prints as it
  // is, being the check.
  const auto W = [&](double w) { return u.Energy(u.Clean(w, L.energy_scale)); };
  std::string out = "\nLedger (from t = 0)\n";
  out += fmt::format("  kinetic energy      {} (translation {}, rotation {})\n",
                     W(L.kinetic_translational + L.kinetic_rotational), W(L.kinetic_translational),
                     W(L.kinetic_rotational));
  std::string parts;
  for (const auto& [name, v] : L.potential_by_force) {
    parts += fmt::format("{}{} {}", parts.empty() ? "" : ", ", name, u.Energy(v));
  }
  out += fmt::format("  potential energy    {}{}\n", u.Energy(L.potential),
                     L.potential_by_force.size() > 1 ? " (" + parts + ")" : "");
  out += fmt::format("  mechanical energy   {} (initially {})\n", u.Energy(L.energy),
                     u.Energy(L.energy_initial));
  out += fmt::format("  non-conservative work {}\n", W(L.work_nonconservative));
  // A purely conservative element (gravity) does no non-conservative work: its work is -ΔV,
  // in the energy above, so it is not listed here.
  const auto conservative = [&](const std::string& name, double w) {
    for (const auto& [n, v] : L.potential_by_force) {
      if (n == name && w == 0.0) return true;
    }
    return false;
  };
  for (const auto& [name, w] : L.work_by_force) {
    if (!conservative(name, w)) out += fmt::format("    {:<20} {}\n", name, W(w));
  }
  for (const auto& [name, w] : L.work_by_constraint) {
    out += fmt::format("    {:<20} {} (constraint)\n", name, W(w));
  }
  if (!r.final_contacts.empty()) {
    out += fmt::format("    {:<20} {}\n", "friction (sliding)", W(L.friction_work));
    if (L.rolling_work != 0) {
      out += fmt::format("    {:<20} {}\n", "rolling resistance", W(L.rolling_work));
    }
    out += fmt::format("    {:<20} {}\n", "impacts", W(L.impact_work));
  } else if (!r.string_events.empty()) {
    out += fmt::format("    {:<20} {}\n", "strings snapping", W(L.impact_work));
  }
  out += fmt::format("  dissipated          {}\n", W(L.dissipated));
  if (!r.jumps.empty()) out += fmt::format("  impulses and impacts {}\n", u.Energy(L.jumps));
  out += fmt::format(
      "  balance residual    {} ({:.2e} of the energy scale {})\n", u.Energy(L.residual),
      L.energy_scale > 0 ? std::abs(L.residual) / L.energy_scale : 0.0, u.Energy(L.energy_scale));
  // Time stepping's own term, where a stretch was time stepped (an auto run that stayed
  // event-driven has none).
  if (std::any_of(r.segments.begin(), r.segments.end(),
                  [](const StudyEngineSegment& g) { return g.engine == StudyEngine::kStepping; })) {
    out += fmt::format(
        "    time stepping's own {} (its scheme's energy error, and the projections of its "
        "penetration at the handovers to events)\n",
        u.Energy(L.time_stepping_error));
  }
  if (scene.planar) {
    // Plane motion: momentum in the plane, angular momentum about z (eqs. 8.34-8.38).
    out += fmt::format("  linear momentum     {}\n", u.Xy(L.linear_momentum_W, kMomentum));
    out += fmt::format(
        "  angular momentum    {} about the centre of mass, {} about the origin "
        "(about z)\n",
        u(L.angular_momentum_Scm_W.z(), kAngularMomentum),
        u(L.angular_momentum_Wo_W.z(), kAngularMomentum));
    return out;
  }
  out += fmt::format("  linear momentum     {}\n", u(L.linear_momentum_W, kMomentum));
  out += fmt::format("  angular momentum    {} about the centre of mass, {} about the origin\n",
                     u(L.angular_momentum_Scm_W, kAngularMomentum),
                     u(L.angular_momentum_Wo_W, kAngularMomentum));
  return out;
}

/// The integrator's work: the event-driven balls' counts and closed-form energy balance, the
/// time-stepped run's certificate, integrator: auto's engines, or an integrator's steps.
std::string IntegratorText(const StudyResult& r, const Show& u) {
  std::string out;
  if (r.event_driven) {
    // Closed form between events: counts instead of steps, and the run's own energy balance.
    const StudyEventDriven& e = *r.event_driven;
    out += fmt::format(
        "\nIntegrator: events (the balls in closed form between events): {} between balls, {} "
        "in all, {} slips or rollings that stopped\n",
        Count(e.collisions, "collision"), Count(e.stats.impacts, "impact"), e.stats.phase_events);
    out += fmt::format(
        "  closed-form energy balance: {} at the start, {} at the end, friction {}, rolling {}, "
        "impacts {}; residual {}\n",
        u.Energy(e.energy.initial), u.Energy(e.energy.final), u.Energy(e.energy.friction),
        u.Energy(e.energy.rolling), u.Energy(e.energy.impacts), u.Energy(e.energy.residual));
    if (e.stats.groups > 0) {
      out += fmt::format(
          "  balls pressing on each other: {} groups, run by the adaptive integrator in {} runs "
          "({} steps, {} rejected, {} evaluations)\n",
          e.stats.groups, e.stats.group_windows, r.stats.steps, r.stats.rejected_steps,
          r.stats.function_evaluations);
    }
    return out;
  }
  if (r.time_stepping) return SteppingText(r, u);
  if (r.engine_rule) return EnginesText(r, u);
  return fmt::format("\nIntegrator: {}: {} steps, {} rejected, {} evaluations\n",
                     StudyIntegratorName(r.engine, r.integrator), r.stats.steps,
                     r.stats.rejected_steps, r.stats.function_evaluations);
}

// The run path and why, with the islands where they add to it: a hybrid run of several
// islands as one system says how many (its reason says why one; a run split into islands
// counts them in its own reason).
std::string RunPathText(const StudyResult& r) {
  std::string line =
      fmt::format("Run path: {}: {}", RunPathName(r.run_path.path), r.run_path.reason);
  if (r.islands.count > 1 && !r.islands.split && r.run_path.path != RunPath::kIslands) {
    line += fmt::format(" (the bodies form {} islands)", r.islands.count);
  }
  return line + "\n";
}

}  // namespace

std::string SimulationText(const Scene& scene, const StudyResult& r, const TextOptions& options) {
  const UnitSystem units = TextUnits(scene, options);
  const Show u{units};
  const ReportScales k = CalcReportScales(r);
  std::string out = TitleLine(scene);
  out +=
      fmt::format("Simulated to t = {}{} (report in {} units; CSV and JSON in SI)\n",
                  u.Time(r.t_end), r.stopped_by_event ? ", stopped by an event" : "", units.spec());
  out += EventsText(scene, r, u);
  out += JumpsText(scene, r, u, k);
  out += ContactEventsText(r, u);
  out += StringEventsText(r, u);
  out += ImpactsText(r, u);
  out += FinalStateText(scene, r, u, k);
  out += EndReactionsText(scene, r, u, k);
  out += EndContactsText(scene, r, u, k);
  out += LedgerText(scene, r, u);
  out += IntegratorText(r, u);
  out += RunPathText(r);
  for (const auto& n : r.notes) out += fmt::format("note: {}\n", n);
  for (const auto& w : scene.warnings) out += fmt::format("warning: {}\n", w);
  for (const auto& w : r.warnings) out += fmt::format("warning: {}\n", w);
  for (const auto& w : r.certificate.FailureMessages()) out += fmt::format("warning: {}\n", w);
  out += CertificateText(r.certificate);
  if (!options.csv_path.empty() || !options.json_path.empty()) {
    out += fmt::format("Wrote {} ({} rows) and {}\n", options.csv_path, r.rows.size(),
                       options.json_path);
  }
  return out;
}

SimulationFiles SimulationFilesIn(const std::string& folder, const std::string& scene_file) {
  const std::filesystem::path dir = folder.empty() ? "." : folder;
  const std::string stem = std::filesystem::path(scene_file).stem().string();
  return {(dir / (stem + ".csv")).string(), (dir / (stem + ".json")).string()};
}

}  // namespace chasles
