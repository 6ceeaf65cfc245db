#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <mutex>
#include <string>
#include <unordered_set>
#include <vector>

#include <fmt/format.h>

#include "certificate_report.h"
#include "chasles/error.h"
#include "chasles/io/json_report.h"
#include "chasles/io/output_set.h"
#include "chasles/io/simulation_report.h"
#include "chasles/math/quaternion.h"
#include "chasles/scene/report_data.h"
#include "chasles/scene/scene.h"
#include "chasles/scene/study.h"
#include "chasles/scene/sweep.h"
#include "chasles/scene/units.h"
#include "cluster.h"
#include "commands.h"
#include "html_report.h"
#include "progress.h"
#include "run_limits.h"
#include "scene_args.h"
#include "sweep_output.h"

namespace chasles::cli {

namespace {

// Values of the text report in the units asked for (the scene's own by default). Adding 0.0
// turns a negative zero (a zero force times -1) into the 0 a reader expects.
struct Show {
  const UnitSystem& u;
  std::string operator()(double v, const Dimension& d, Angular a = Angular::kNo) const {
    const std::string unit = u.FormatUnit(d, a);
    return fmt::format("{:.9g}{}{}", Finite(u.FromSI(v, d, a), "a value of the report") + 0.0,
                       unit.empty() ? "" : " ", unit);
  }
  /// A vector; components below 1e-12 of max(|v|, scale) are round-off and print as 0
  /// (`scale`: the size of that kind of quantity in the run, e.g. a speed from the energy).
  std::string operator()(const Vec3& v, const Dimension& d, Angular a = Angular::kNo,
                         double scale = 0.0) const {
    const std::string unit = u.FormatUnit(d, a);
    // stableNorm: |v| of components near 1e200 overflows norm() to inf, and every component
    // would then print as round-off 0.
    const double floor = 1e-12 * std::max(v.stableNorm(), scale);
    const auto c = [&](double x) {
      return Finite(u.FromSI(std::abs(x) <= floor ? 0.0 : x, d, a), "a value of the report") + 0.0;
    };
    return fmt::format("[{:.9g}, {:.9g}, {:.9g}]{}{}", c(v.x()), c(v.y()), c(v.z()),
                       unit.empty() ? "" : " ", unit);
  }
  /// The in-plane components [x, y] of a vector of a planar scene (round-off as above).
  std::string Xy(const Vec3& v, const Dimension& d, double scale = 0.0) const {
    const std::string unit = u.FormatUnit(d, Angular::kNo);
    const double floor = 1e-12 * std::max(v.head<2>().stableNorm(), scale);
    const auto c = [&](double x) {
      return Finite(u.FromSI(std::abs(x) <= floor ? 0.0 : x, d, Angular::kNo),
                    "a value of the report") +
             0.0;
    };
    return fmt::format("[{:.9g}, {:.9g}]{}{}", c(v.x()), c(v.y()), unit.empty() ? "" : " ", unit);
  }
};

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

/// `x`, or 0 when it is round-off next to `scale` (at most 1e-12 of it).
double Clean(double x, double scale) {
  return std::abs(x) <= 1e-12 * scale ? 0.0 : x;
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
                         show(Clean(b.w_WB_W.z(), w_s), kRate, Angular::kYes));
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
    out += fmt::format("    {}: {}, N = {}, friction {}\n", c.point, c.mode,
                       show(c.normal_force, kForce),
                       scene.planar ? show.Xy(c.friction_force_W, kForce, k.force)
                                    : show(c.friction_force_W, kForce, Angular::kNo, k.force));
  }
  return out;
}

/// How the sections of the text report print times and energies. Energy and torque share a
/// dimension; in SI the energy's own name is the joule.
struct TextUnits {
  Show show;
  bool joules;
  explicit TextUnits(const UnitSystem& units)
      : show{units}, joules(units.FormatUnit(kEnergy) == "N*m") {}
  std::string Time(double t) const { return show(t, kTime); }
  std::string Energy(double e) const {
    return joules ? fmt::format("{:.9g} J", Finite(e, "an energy of the report"))
                  : show(e, kEnergy);
  }
};

/// "1 collision", "2 collisions".
std::string Count(long n, const char* noun) {
  return fmt::format("{} {}{}", n, noun, n == 1 ? "" : "s");
}

/// The certificate of time-stepped steps (docs/contact.md, "Time stepping"): the worst step's
/// values and the ledger's totals, each line after `indent`.
std::string SteppingCertificateText(const TimeSteppingSummary& c, bool tolerance_met,
                                    const TextUnits& u, const char* indent) {
  std::string out = fmt::format(
      "{}contact problems' residual at most {} ({}); momentum balance to {}, angular momentum "
      "to {}\n",
      indent, u.show(c.max_residual_impulse, kMomentum), u.show(c.max_residual_velocity, kVelocity),
      u.show(c.max_momentum_residual, kMomentum),
      u.show(c.max_angular_momentum_residual, kAngularMomentum));
  out += fmt::format(
      "{}penetration at most {}, gap drift at most {}; step-doubling error estimate per step at "
      "most {} ({}), summed over the steps {}{}\n",
      indent, u.show(c.max_penetration, kLength), u.show(c.max_gap_drift, kLength),
      u.show(c.max_velocity_error, kVelocity),
      u.show(c.max_angular_velocity_error, kRate, Angular::kYes),
      u.show(c.accumulated_velocity_error, kVelocity),
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
std::string SteppingText(const StudyResult& r, const TextUnits& u) {
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
  return out + SteppingCertificateText(c, ts.tolerance_met, u, "  ");
}

/// Why an engine took over (integrator: auto).
std::string SwitchText(const StudyEngineSegment& g, const TextUnits& u) {
  switch (g.reason) {
    case EngineSwitch::kStart:
      return g.stays.empty() ? "start" : fmt::format("start; stays event-driven: {}", g.stays);
    case EngineSwitch::kRegimeChanges:
      return fmt::format("{} regime changes within {} (the last at {}): faster than the bound",
                         g.changes, u.Time(g.span), g.where);
    case EngineSwitch::kQuiet:
      return fmt::format(
          "no regime change for {}; the touching points projected onto their planes: {} deep "
          "at most, energy changed by {}",
          u.Time(g.quiet), u.show(g.projection_depth, kLength), u.Energy(g.projection_energy));
  }
  return "";
}

/// integrator: auto: the rule, then each engine's stretch of the run, why it took over and its
/// work (a time-stepped one with the certificate of its steps).
std::string EnginesText(const StudyResult& r, const TextUnits& u) {
  const EngineChoiceRule& rule = *r.engine_rule;
  std::string out = fmt::format(
      "\nIntegrator: auto (event-driven, time stepped with step {} while {} regime changes come "
      "within {}, back after {} without one): {} steps, {} rejected, {} evaluations\n",
      u.Time(rule.step), rule.changes, u.Time(rule.window), u.Time(rule.quiet_span), r.stats.steps,
      r.stats.rejected_steps, r.stats.function_evaluations);
  for (const StudyEngineSegment& g : r.segments) {
    out += fmt::format("  {} to {}: {}, {}\n", u.Time(g.t_begin), u.Time(g.t_end),
                       StudyEngineName(g.engine), SwitchText(g, u));
    if (g.engine == StudyEngine::kAdaptive) {
      out += fmt::format("    {} steps, {} rejected, {} evaluations\n", g.stats.steps,
                         g.stats.rejected_steps, g.stats.function_evaluations);
      continue;
    }
    out +=
        fmt::format("    {} steps, {}, largest contact problem {} points\n", g.stepping.steps,
                    Count(g.stepping.regime_changes, "regime change"), g.stepping.largest_island);
    out += SteppingCertificateText(g.stepping, g.tolerance_met, u, "    ");
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
                                      show(Clean(b.dw_WB_W.z(), dw), kRate, Angular::kYes))
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
                             show(Clean(r.M_Jc_W.z(), M), kAngularMomentum))
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

std::string JumpsText(const Scene& scene, const StudyResult& r, const TextUnits& u,
                      const ReportScales& k) {
  if (r.jumps.empty()) return "";
  std::string out = "\nImpulses and impacts\n";
  for (const auto& x : r.jumps) {
    out += fmt::format("  t = {}: {}; energy {} -> {} (change {})\n", u.Time(x.t), x.description,
                       u.Energy(x.energy_before), u.Energy(x.energy_after),
                       u.Energy(x.energy_after - x.energy_before));
    out +=
        scene.planar
            ? fmt::format("    afterwards: v = {}, omega = {}\n", u.show.Xy(x.v_after_W, kVelocity),
                          u.show(x.w_after_W.z(), kRate, Angular::kYes))
            : fmt::format("    afterwards: v = {}, w = {}\n", u.show(x.v_after_W, kVelocity),
                          u.show(x.w_after_W, kRate, Angular::kYes));
    out += JumpDetailText(scene, x, u.show, k.length);
  }
  return out;
}

std::string ContactEventsText(const StudyResult& r, const TextUnits& u) {
  if (r.contact_events.empty()) return "";
  return "\nContact modes (time, contact point: from -> to, why)\n" +
         Abridged(r.contact_events, 20, 5, "change", [&](const StudyContactEvent& e) {
           if (e.from == e.to && e.reason == "rolling stopped") {  // and rolls on, turned
             return fmt::format("  t = {}  {}: {} (rolling stopped and rolls on the other way)\n",
                                u.Time(e.t), e.point, e.to);
           }
           if (e.from == e.to && e.reason != "initial") {  // a bounce: touch-down, apart at once
             return fmt::format("  t = {}  {}: stays {} ({})\n", u.Time(e.t), e.point, e.to,
                                e.reason);
           }
           if (e.from == e.to) {
             return fmt::format("  t = {}  {}: {} ({})\n", u.Time(e.t), e.point, e.to, e.reason);
           }
           return fmt::format("  t = {}  {}: {} -> {} ({})\n", u.Time(e.t), e.point, e.from, e.to,
                              e.reason);
         });
}

std::string StringEventsText(const StudyResult& r, const TextUnits& u) {
  if (r.string_events.empty()) return "";
  return "\nString modes (time, string: from -> to, why)\n" +
         Abridged(r.string_events, 20, 5, "change", [&](const StudyStringEvent& e) {
           std::string line = e.from == e.to
                                  ? fmt::format("  t = {}  string '{}': {} ({})\n", u.Time(e.t),
                                                e.string, e.to, e.reason)
                                  : fmt::format("  t = {}  string '{}': {} -> {} ({})\n",
                                                u.Time(e.t), e.string, e.from, e.to, e.reason);
           if (e.reason == "snapped taut" && e.to == "slack") {
             line += "    it rebounded (restitution): taut for an instant, slack again at once\n";
           }
           if (e.reason == "snapped taut") {
             line += fmt::format("    approach speed {}, impulse {}, energy lost {}\n",
                                 u.show(e.approach_speed, kVelocity), u.show(e.impulse, kMomentum),
                                 u.Energy(e.energy_lost));
           }
           return line;
         });
}

std::string ImpactText(const StudyImpact& x, const TextUnits& u) {
  std::string out =
      fmt::format("  t = {}  {}: approach speed {}, energy lost {}{}\n", u.Time(x.t), x.point,
                  u.show(x.approach_speed, kVelocity), u.Energy(x.energy_lost),
                  x.jam ? "" : fmt::format(" ({} restitution)", x.restitution_law));
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

std::string ImpactsText(const StudyResult& r, const TextUnits& u) {
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
    const auto clean = Clean;
    if (scene.planar) {
      // Chapter eqs. 8.41-8.43: x, y, θ and their rates.
      out += fmt::format("  {}\n    position {}, theta {}\n    velocity {}, omega {}\n", b.name,
                         show.Xy(b.p_WBcm, kLength, k.length),
                         show(b.theta, kDimensionless, Angular::kYes),
                         show.Xy(b.v_WBcm_W, kVelocity, v_s),
                         show(clean(b.w_WB_W.z(), w_s), kRate, Angular::kYes));
      continue;
    }
    const Eigen::Vector4d q = QuatToWxyz(b.q_WB);
    // A unit quaternion's components are known to round-off against 1.
    out += fmt::format(
        "  {}\n    position {}\n    quaternion [{:.9g}, {:.9g}, {:.9g}, {:.9g}]\n"
        "    velocity {}\n    angular velocity {} (body frame {})\n",
        b.name, show(b.p_WBcm, kLength, Angular::kNo, k.length),
        Finite(clean(q[0], 1.0), "a quaternion of the report") + 0.0,
        Finite(clean(q[1], 1.0), "a quaternion of the report") + 0.0,
        Finite(clean(q[2], 1.0), "a quaternion of the report") + 0.0,
        Finite(clean(q[3], 1.0), "a quaternion of the report") + 0.0,
        show(b.v_WBcm_W, kVelocity, Angular::kNo, v_s), show(b.w_WB_W, kRate, Angular::kYes, w_s),
        show(b.w_WB_B, kRate, Angular::kYes, w_s));
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
                         show(Clean(x.M_Jc_W.z(), k.moment), kMoment));
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
    out += fmt::format("  {}: {}, N = {}, friction {}, slip {}, gap {}\n", c.point, c.mode,
                       show(c.normal_force, kForce),
                       scene.planar ? show.Xy(c.friction_force_W, kForce, k.force)
                                    : show(c.friction_force_W, kForce, Angular::kNo, k.force),
                       scene.planar ? show.Xy(c.slip_velocity_W, kVelocity, k.speed)
                                    : show(c.slip_velocity_W, kVelocity, Angular::kNo, k.speed),
                       show(std::abs(c.gap) <= 1e-12 * k.length ? 0.0 : c.gap, kLength));
    if (c.rolling_moment_W.squaredNorm() > 0.0) {
      // Rolling resistance: the moment holding the rolling, or resisting it (about z in a
      // planar scene).
      out += fmt::format("    rolling-resistance moment {}\n",
                         scene.planar ? show(Clean(c.rolling_moment_W.z(), k.moment), kMoment)
                                      : show(c.rolling_moment_W, kMoment, Angular::kNo,
                                             std::max(k.moment, c.rolling_moment_W.norm())));
    }
  }
  return out;
}

std::string LedgerText(const Scene& scene, const StudyResult& r, const TextUnits& u) {
  const StudyLedger& L = r.ledger;
  // Works and kinetic energies below 1e-12 of the energy scale are round-off (an ideal
  // joint's work, a body brought to rest) and print as 0; the balance residual prints as it
  // is, being the check.
  const auto W = [&](double w) {
    return u.Energy(std::abs(w) <= 1e-12 * L.energy_scale ? 0.0 : w);
  };
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
  if (r.engine_rule) {
    out += fmt::format(
        "    time stepping's own {} (its scheme's energy error, and the projections of its "
        "penetration at the handovers to events)\n",
        u.Energy(L.time_stepping_error));
  }
  if (scene.planar) {
    // Plane motion: momentum in the plane, angular momentum about z (eqs. 8.34-8.38).
    out += fmt::format("  linear momentum     {}\n", u.show.Xy(L.linear_momentum_W, kMomentum));
    out += fmt::format(
        "  angular momentum    {} about the centre of mass, {} about the origin "
        "(about z)\n",
        u.show(L.angular_momentum_Scm_W.z(), kAngularMomentum),
        u.show(L.angular_momentum_Wo_W.z(), kAngularMomentum));
    return out;
  }
  out += fmt::format("  linear momentum     {}\n", u.show(L.linear_momentum_W, kMomentum));
  out += fmt::format("  angular momentum    {} about the centre of mass, {} about the origin\n",
                     u.show(L.angular_momentum_Scm_W, kAngularMomentum),
                     u.show(L.angular_momentum_Wo_W, kAngularMomentum));
  return out;
}

std::string Text(const Scene& scene, const StudyResult& r, const UnitSystem& units,
                 const std::string& csv_path, const std::string& json_path) {
  const TextUnits u(units);
  const ReportScales k = CalcReportScales(r);
  std::string out;
  out += fmt::format("{}{}\n", scene.title.empty() ? scene.file : scene.title,
                     scene.title.empty() ? "" : fmt::format(" ({})", scene.file));
  out +=
      fmt::format("Simulated to t = {}{} (report in {} units; CSV and JSON in SI)\n",
                  u.Time(r.t_end), r.stopped_by_event ? ", stopped by an event" : "", units.spec());
  out += EventsText(scene, r, u.show);
  out += JumpsText(scene, r, u, k);
  out += ContactEventsText(r, u);
  out += StringEventsText(r, u);
  out += ImpactsText(r, u);
  out += FinalStateText(scene, r, u.show, k);
  out += EndReactionsText(scene, r, u.show, k);
  out += EndContactsText(scene, r, u.show, k);
  out += LedgerText(scene, r, u);
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
  } else if (r.time_stepping) {
    out += SteppingText(r, u);
  } else if (r.engine_rule) {
    out += EnginesText(r, u);
  } else {
    out += fmt::format("\nIntegrator: {}: {} steps, {} rejected, {} evaluations\n", r.integrator,
                       r.stats.steps, r.stats.rejected_steps, r.stats.function_evaluations);
  }
  if (r.islands.count > 0) {
    out += r.islands.split
               ? fmt::format("Islands: {}, each run as its own hybrid system\n", r.islands.count)
               : fmt::format("Islands: {}, run as one hybrid system: {}\n", r.islands.count,
                             r.islands.reason);
  }
  out += fmt::format("Run path: {}: {}\n", RunPathName(r.run_path.path), r.run_path.reason);
  for (const auto& n : r.notes) out += fmt::format("note: {}\n", n);
  for (const auto& w : scene.warnings) out += fmt::format("warning: {}\n", w);
  for (const auto& w : r.warnings) out += fmt::format("warning: {}\n", w);
  for (const auto& w : r.certificate.FailureMessages()) out += fmt::format("warning: {}\n", w);
  out += CertificateText(r.certificate);
  out += fmt::format("Wrote {} ({} rows) and {}\n", csv_path, r.rows.size(), json_path);
  return out;
}

}  // namespace

CLI::App* AddSimulateCommand(CLI::App& app, SimulateArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "simulate",
      "Integrate the motion of a scene's bodies; write a CSV time series and a JSON summary "
      "(final state, events, energy/work/momentum ledger, integrator statistics)");
  AddSceneArgs(*cmd, args.scene);
  cmd->add_option("--until", args.until, "End time [s], overriding the scene's simulation.until")
      ->check(PositiveFiniteNumber("--until must be a positive time in seconds"));
  cmd->add_option("--out", args.out_dir,
                  "Directory for <scene>.csv and <scene>.json (default: the current directory)");
  cmd->add_option("--format", args.format,
                  "Report on standard output: text (default) or json; a sweep's table: CSV "
                  "(default) or json")
      ->check(CLI::IsMember({"text", "json"}));
  cmd->add_option("--columns", args.columns,
                  "CSV columns or groups, replacing the scene's output.columns, e.g. "
                  "--columns position,euler,energy (groups: docs/scene-format.md, output)")
      ->delimiter(',');
  cmd->add_flag("--strict", args.strict,
                "Exit with code 3 when a check of the certificate fails (the report's Checks "
                "section; otherwise a failed check is only a warning)");
  cmd->add_option("--units", args.units,
                  "Units of the text report: SI, US (in, lb, lbf), or a list such as 'ft,slug' "
                  "(default: the scene's own units; the CSV and JSON are always SI)");
  cmd->add_option("--html", args.html,
                  "Also write the browser report (a 3-D replay with plots, one HTML file) here; "
                  "the CSV then also holds the columns the report needs (poses, ledger, "
                  "reactions, contacts); with --sweep, the quantities plotted against the swept "
                  "parameters");
  cmd->add_option("--precision", args.precision,
                  "Digits of the CSV's numbers: default (the shortest text that reads back as "
                  "the same double) or full (every double with %.17g)")
      ->check(CLI::IsMember({"default", "full"}));
  cmd->add_flag("--full-precision", args.full_precision, "The same as --precision full");
  AddRunLimitOptions(*cmd, args);
  AddSweepOptions(*cmd, args.sweep, args.quantity, args.jobs, args.max_runs,
                  "final(COLUMN), max(COLUMN), min(COLUMN) (over the samples and the events), "
                  "event(NAME) (time of its first firing; event(NAME, k) the k-th), "
                  "event(NAME2) - event(NAME1), or t_end (repeatable)");
  cmd->add_option("--keep-runs", args.keep_runs,
                  "With --sweep, also write each run's CSV and JSON in this folder, named by the "
                  "scene and the parameter values (<scene>_L=0.5_theta0=0.1.csv)");
  cmd->footer(
      "Examples:\n"
      "  chasles simulate examples/dzhanibekov.yaml --out results\n"
      "  chasles simulate examples/dzhanibekov.yaml --html dzhanibekov.html\n"
      "  chasles simulate examples/projectile-drag.yaml --set 'c=0.2 N*s/m' --format json\n"
      "  chasles simulate examples/spring-mass.yaml --until 20\n"
      "  chasles simulate examples/problem-8.26-spinning-ball.yaml --sweep 'mu_k=0.2:0.5:4' "
      "--quantity 'final(ball_vx)' --quantity 'max(floor_f)'\n"
      "Progress goes to standard error: redrawn on a terminal after the first second, one "
      "line every 10 s otherwise (--quiet: none). Scene keys: docs/scene-format.md, section "
      "Dynamics; limits: docs/reliability-limits.md; sweeps: docs/sweeps.md.\n"
      "Exit codes: 0 success, 2 bad input, 3 a check failed (a sweep: or a point failed) with "
      "--strict, 1 internal error.");
  return cmd;
}

namespace {

/// Whether kept runs are named with every parameter value in full (the shortest text that
/// reads back as the same double) rather than with 12 significant digits, as docs/sweeps.md
/// names them: only when two points of the grid would have one name at 12 digits, so that no
/// run's files replace another's.
bool KeptRunNamesInFull(const Scene& base, const std::vector<SweepSpec>& specs,
                        std::int64_t max_runs) {
  const SweepGrid grid = MakeSweepGrid(base, specs, max_runs);
  std::unordered_set<std::string> names;
  for (std::int64_t k = 0; k < grid.size; ++k) {
    std::string name;
    for (const double v : grid.Values(k)) name += fmt::format("_{:.12g}", v);
    if (!names.insert(name).second) return true;
  }
  return false;
}

/// The run at each point of a grid (simulate --sweep): a table of the quantities on standard
/// output, each run's files in --keep-runs when asked.
int RunSimulateSweep(const SimulateArgs& args) {
  if (args.scene.scene.empty()) {
    throw InputError("chasles simulate --sweep needs a scene file (chasles simulate --help)");
  }
  if (!args.out_dir.empty()) {
    throw InputError(
        "--out writes one run's files; with --sweep use --keep-runs DIR for every run's CSV and "
        "JSON");
  }
  // Every target is checked before the first run: the table (standard output), the page and
  // the folder of kept runs.
  OutputSet out;
  out.Expect("-", "the table");
  if (!args.html.empty()) {
    RequireHtmlReport("--html");
    out.Expect(args.html, "--html");
  }
  if (!args.units.empty()) {
    throw InputError("--units sets the text report's units; a sweep's table is in SI");
  }
  const std::vector<SweepSpec> specs = ParseSweeps(args.sweep);
  std::vector<SweepQuantity> quantities;
  for (const std::string& q : args.quantity) {
    quantities.push_back(ParseSweepQuantity(q, "command line", "--quantity"));
  }
  SimulateSweepOptions options;
  if (!std::isnan(args.until)) options.study.until = args.until;
  ApplyRunLimitOptions(args, options.study);
  options.columns = args.columns;
  options.jobs = args.jobs;
  // Under mpirun: this rank's points; rank 0 gathers the rows and alone writes (cluster.h).
  const Cluster& cluster = Cluster::Get();
  options.share = cluster.share();
  const std::string stem =
      args.scene.scene.empty() ? "demo" : std::filesystem::path(args.scene.scene).stem().string();
  const std::int64_t max_runs = args.max_runs > 0 ? args.max_runs : kDefaultMaxRuns;
  bool names_in_full = false;
  if (!args.keep_runs.empty()) {
    CheckOutputFolder(args.keep_runs, "--keep-runs");
    names_in_full = KeptRunNamesInFull(LoadScene(args.scene), specs, max_runs);
    CreateOutputFolder(args.keep_runs);
  }
  // Warnings of the runs (failed checks), by point, printed in grid order afterwards.
  std::mutex mutex;
  SweepWarnings warnings;
  bool check_failed = false;
  options.on_run = [&](std::int64_t k, const Scene& scene, const StudyResult& r) {
    std::string name = stem;
    for (const SweepSpec& s : specs) {
      for (const auto& [n, q] : scene.parameters) {
        if (n == s.name) {
          name += names_in_full ? fmt::format("_{}={}", n, q.value)
                                : fmt::format("_{}={:.12g}", n, q.value);
        }
      }
    }
    if (!args.keep_runs.empty()) {
      const std::filesystem::path dir = args.keep_runs;
      const std::string csv_path = (dir / (name + ".csv")).string();
      OutputSet files;
      files.Add(csv_path, SimulationCsv(r));
      files.Add((dir / (name + ".json")).string(),
                DumpJson(SimulationJson(
                             r, ReportHeader{scene.file, scene.title, scene.planar, scene.warnings},
                             csv_path),
                         "the JSON summary"));
      files.Commit();
    }
    const std::lock_guard<std::mutex> lock(mutex);
    for (const std::string& w : r.certificate.FailureMessages()) {
      warnings[k].push_back(fmt::format("{}: {}", name, w));
      check_failed = true;
    }
  };
  SweepTable table;
  {
    Progress progress("simulate --sweep", "", args.quiet || cluster.rank() != 0,
                      args.progress_interval);
    options.progress = [&progress](std::int64_t done, std::int64_t total) {
      progress.Update(static_cast<double>(done), static_cast<double>(total));
    };
    table = SimulateSweep(SceneLoader(args.scene), SceneOptionsFrom(args.scene), specs, quantities,
                          options, max_runs);
  }
  if (!GatherSweep(&table, &warnings, &check_failed)) return 0;
  for (const auto& [k, list] : warnings) {
    for (const std::string& w : list) std::fprintf(stderr, "warning: %s\n", w.c_str());
  }
  const int failed = AddSweepTable(
      out, table, args.format,
      args.full_precision ? CsvPrecision::kFull : ParseCsvPrecision(args.precision), "-");
  if (!args.html.empty()) {
    out.Add(args.html, HtmlReport(SweepReportData(LoadScene(args.scene), table, "simulate")));
  }
  out.Commit();
  SayWroteHtmlReport(args.html);
  return args.strict && (failed > 0 || check_failed) ? kExitCheckFailed : 0;
}

}  // namespace

int RunSimulate(const SimulateArgs& args) {
  if (!args.sweep.empty()) return RunSimulateSweep(args);
  if (!args.quantity.empty() || !args.keep_runs.empty() || args.jobs > 0 || args.max_runs > 0) {
    throw InputError(fmt::format("{} goes with --sweep", !args.quantity.empty()    ? "--quantity"
                                                         : !args.keep_runs.empty() ? "--keep-runs"
                                                         : args.jobs > 0           ? "--jobs"
                                                                                   : "--max-runs"));
  }
  if (args.scene.scene.empty()) {
    throw InputError("chasles simulate needs a scene file (chasles simulate --help)");
  }
  // Every target is checked before the run: the folder, the CSV, the JSON, the page.
  const std::filesystem::path dir = args.out_dir.empty() ? "." : args.out_dir;
  const std::string stem = std::filesystem::path(args.scene.scene).stem().string();
  const std::string csv_path = (dir / (stem + ".csv")).string();
  const std::string json_path = (dir / (stem + ".json")).string();
  OutputSet files;
  files.ExpectFolder(dir.string(), "--out");
  files.Expect(csv_path, "--out");
  files.Expect(json_path, "--out");
  files.Expect("-", "the report");
  if (!args.html.empty()) {
    RequireHtmlReport("--html");
    files.Expect(args.html, "--html");
  }
  Scene scene = LoadScene(args.scene);
  if (!args.columns.empty()) scene.dynamics.columns = SelectColumns(scene, args.columns);
  // Checked before the run, so a mistyped unit does not waste a long simulation.
  const UnitSystem units = UnitSystem::Parse(args.units.empty() ? scene.units : args.units);
  StudyOptions options;
  if (!std::isnan(args.until)) {
    if (!(args.until > 0) || !std::isfinite(args.until)) {
      throw InputError(
          fmt::format("--until must be a positive time in seconds, got {}", args.until));
    }
    options.until = args.until;
  }
  ApplyRunLimitOptions(args, options);
  if (!args.html.empty()) {
    // The replay needs every body's pose at every sample, the plots the ledger, reaction and
    // contact columns, and the arrows the forces at every sample.
    scene.dynamics.columns = ReportColumns(scene, scene.dynamics.columns);
    options.record_row_snapshots = true;
  }
  const double t_end =
      std::isfinite(options.until) ? options.until : scene.dynamics.simulation.until;
  StudyResult r;
  {
    Progress progress("simulating", "s", args.quiet, args.progress_interval);
    options.progress = [&](double t) { progress.Update(t, t_end); };
    r = RunStudy(scene, options);
  }

  // Every output is made and checked (no non-finite number) before any file appears; then
  // the CSV and the JSON appear together or not at all (output_set.h).
  const std::string csv_text = SimulationCsv(
      r, args.full_precision ? CsvPrecision::kFull : ParseCsvPrecision(args.precision));
  const std::string json_text = DumpJson(
      SimulationJson(r, ReportHeader{scene.file, scene.title, scene.planar, scene.warnings},
                     csv_path),
      "the JSON summary");
  std::string report =
      args.format == "json" ? json_text : Text(scene, r, units, csv_path, json_path);
  files.Add(csv_path, csv_text);
  files.Add(json_path, json_text);
  if (!args.html.empty()) {
    files.Add(args.html, HtmlReport(SimulationReportData(scene, r)));
    if (args.format != "json") report += fmt::format("Wrote {} (the browser report)\n", args.html);
  }
  files.Add("-", report);
  files.Commit();
  return args.strict && !r.certificate.passed() ? kExitCheckFailed : 0;
}

}  // namespace chasles::cli
