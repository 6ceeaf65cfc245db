#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "certificate_report.h"
#include "chasles/error.h"
#include "chasles/io/output_set.h"
#include "chasles/math/quaternion.h"
#include "chasles/scene/scene.h"
#include "chasles/scene/study.h"
#include "chasles/scene/units.h"
#include "commands.h"
#include "progress.h"
#include "report_guard.h"
#include "run_limits.h"
#include "scene_args.h"

namespace chasles::cli {

namespace {

nlohmann::json VecJson(const Vec3& v) {
  return {v.x(), v.y(), v.z()};
}

std::string CsvName(const std::string& name) {
  if (name.find_first_of(",\"\n") == std::string::npos) return name;
  std::string q = "\"";
  for (char c : name) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string Csv(const StudyResult& r) {
  std::string out;
  for (size_t i = 0; i < r.columns.size(); ++i) {
    out += (i ? "," : "") + CsvName(r.columns[i]);
  }
  out += '\n';
  for (const auto& row : r.rows) {
    for (size_t i = 0; i < row.size(); ++i) {
      // Shortest text that reads back as the same double.
      if (i) out += ',';
      out += fmt::format("{}", row[i]);
    }
    out += '\n';
  }
  return out;
}

/// Bodies, reactions and contact points at one instant (SI, world frame).
nlohmann::json SnapshotJson(const Scene& scene, const StudySnapshot& snap) {
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
    if (scene.planar) {
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
                         {"power", x.power}});
    if (scene.planar) {
      reactions.back()["planar"] = {
          {"Fx", x.F_Jc_W.x()}, {"Fy", x.F_Jc_W.y()}, {"Mz", x.M_Jc_W.z()}};
    }
  }
  nlohmann::json contacts = nlohmann::json::array();
  for (const auto& c : snap.contacts) {
    contacts.push_back({{"point", c.point},
                        {"mode", c.mode},
                        {"normal_force", c.normal_force},
                        {"friction_force", VecJson(c.friction_force_W)},
                        {"slip_velocity", VecJson(c.slip_velocity_W)},
                        {"gap", c.gap},
                        {"friction_work", c.friction_work},
                        {"rolling_work", c.rolling_work},
                        {"impact_work", c.impact_work}});
  }
  nlohmann::json j = {{"bodies", bodies}, {"reactions", reactions}};
  if (!snap.contacts.empty()) j["contacts"] = contacts;
  return j;
}

nlohmann::json Json(const Scene& scene, const StudyResult& r, const std::string& csv_path) {
  nlohmann::json j;
  j["scene"] = scene.file;
  j["title"] = scene.title;
  j["units"] = "SI";
  j["planar"] = scene.planar;
  j["csv"] = csv_path;
  j["columns"] = r.columns;
  j["t_end"] = r.t_end;
  j["stopped_by_event"] = r.stopped_by_event;
  j["events"] = nlohmann::json::array();
  for (const auto& e : r.events) {
    j["events"].push_back({{"name", e.name},
                           {"t", e.t},
                           {"stopped", e.stopped},
                           {"state", SnapshotJson(scene, e.snapshot)}});
  }
  j["jumps"] = nlohmann::json::array();
  for (const auto& x : r.jumps) {
    j["jumps"].push_back({{"kind", x.kind},
                          {"description", x.description},
                          {"t", x.t},
                          {"energy_before", x.energy_before},
                          {"energy_after", x.energy_after},
                          {"energy_change", x.energy_after - x.energy_before},
                          {"velocity_after", VecJson(x.v_after_W)},
                          {"angular_velocity_after", VecJson(x.w_after_W)}});
  }
  j["final"] = SnapshotJson(scene, {r.final_bodies, r.final_reactions, r.final_contacts});
  j["final"]["t"] = r.t_end;
  j["contact_events"] = nlohmann::json::array();
  for (const auto& e : r.contact_events) {
    j["contact_events"].push_back({{"t", e.t},
                                   {"point", e.point},
                                   {"contact", e.contact},
                                   {"from", e.from},
                                   {"to", e.to},
                                   {"reason", e.reason}});
  }
  j["impacts"] = nlohmann::json::array();
  for (const auto& x : r.impacts) {
    j["impacts"].push_back({{"t", x.t},
                            {"point", x.point},
                            {"approach_speed", x.approach_speed},
                            {"normal_impulse", x.normal_impulse},
                            {"energy_lost", x.energy_lost},
                            {"accumulation", x.accumulation},
                            {"jam", x.jam},
                            {"restitution_law", x.restitution_law}});
    if (x.frictionless_fallback) j["impacts"].back()["frictionless_fallback"] = true;
    if (x.accumulation) j["impacts"].back()["rest_time"] = x.rest_time;
  }
  const StudyLedger& L = r.ledger;
  nlohmann::json work = nlohmann::json::object();
  for (const auto& [name, w] : L.work_by_force) work[name] = w;
  nlohmann::json constraint_work = nlohmann::json::object();
  for (const auto& [name, w] : L.work_by_constraint) constraint_work[name] = w;
  j["ledger"] = {{"kinetic_translational", L.kinetic_translational},
                 {"kinetic_rotational", L.kinetic_rotational},
                 {"potential", L.potential},
                 {"energy", L.energy},
                 {"energy_initial", L.energy_initial},
                 {"work_nonconservative", L.work_nonconservative},
                 {"work_by_force", work},
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
  j["integrator"] = {{"name", r.integrator},
                     {"steps", r.stats.steps},
                     {"rejected_steps", r.stats.rejected_steps},
                     {"function_evaluations", r.stats.function_evaluations}};
  j["notes"] = r.notes;
  std::vector<std::string> warnings = scene.warnings;
  warnings.insert(warnings.end(), r.warnings.begin(), r.warnings.end());
  for (const std::string& w : r.certificate.FailureMessages()) warnings.push_back(w);
  j["warnings"] = warnings;
  j["checks"] = CertificateJson(r.certificate);
  return j;
}

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

constexpr Dimension kTimeDim{0, 0, 1};
constexpr Dimension kVelocityDim{1, 0, -1};
constexpr Dimension kRateDim{0, 0, -1};
constexpr Dimension kEnergyDim{2, 1, -2};
constexpr Dimension kMomentumDim{1, 1, -1};
constexpr Dimension kAngularMomentumDim{2, 1, -1};

/// The state at an event, concisely: per body position, velocity and angular velocity (world
/// frame), per reaction force and moment, per contact point mode, N and friction.
std::string SnapshotText(const Scene& scene, const StudySnapshot& snap, const Show& show,
                         const ReportScales& k) {
  constexpr Dimension kForceDim{1, 1, -2};
  constexpr Dimension kMomentDim{2, 1, -2};
  std::string out;
  for (size_t i = 0; i < snap.bodies.size(); ++i) {
    const auto& b = snap.bodies[i];
    const double v_s = i < k.body_speed.size() ? k.body_speed[i] : k.speed;
    const double w_s = i < k.body_rate.size() ? k.body_rate[i] : 0.0;
    if (scene.planar) {
      out += fmt::format("    {}: x, y [{}, {}], theta {}; v [{}, {}], omega {}\n", b.name,
                         show(b.p_WBcm.x(), kLength), show(b.p_WBcm.y(), kLength),
                         show(b.theta, kDimensionless, Angular::kYes),
                         show(b.v_WBcm_W.x(), kVelocityDim), show(b.v_WBcm_W.y(), kVelocityDim),
                         show(b.w_WB_W.z(), kRateDim, Angular::kYes));
      continue;
    }
    out += fmt::format("    {}: position {}, velocity {}, angular velocity {}\n", b.name,
                       show(b.p_WBcm, kLength, Angular::kNo, k.length),
                       show(b.v_WBcm_W, kVelocityDim, Angular::kNo, v_s),
                       show(b.w_WB_W, kRateDim, Angular::kYes, w_s));
  }
  for (const auto& x : snap.reactions) {
    out += fmt::format("    {}: force {}, moment {}\n", x.name,
                       show(x.F_Jc_W, kForceDim, Angular::kNo, k.force),
                       show(x.M_Jc_W, kMomentDim, Angular::kNo, k.moment));
  }
  for (const auto& c : snap.contacts) {
    out += fmt::format("    {}: {}, N = {}, friction {}\n", c.point, c.mode,
                       show(c.normal_force, kForceDim),
                       show(c.friction_force_W, kForceDim, Angular::kNo, k.force));
  }
  return out;
}

std::string Text(const Scene& scene, const StudyResult& r, const UnitSystem& units,
                 const std::string& csv_path, const std::string& json_path) {
  const Show show{units};
  const auto time = [&](double t) { return show(t, kTimeDim); };
  // Energy and torque share a dimension; in SI the energy's own name is the joule.
  const bool joules = units.FormatUnit(kEnergyDim) == "N*m";
  const auto energy = [&](double e) {
    return joules ? fmt::format("{:.9g} J", Finite(e, "an energy of the report"))
                  : show(e, kEnergyDim);
  };
  std::string out;
  out += fmt::format("{}{}\n", scene.title.empty() ? scene.file : scene.title,
                     scene.title.empty() ? "" : fmt::format(" ({})", scene.file));
  out +=
      fmt::format("Simulated to t = {}{} (report in {} units; CSV and JSON in SI)\n", time(r.t_end),
                  r.stopped_by_event ? ", stopped by an event" : "", units.spec());
  if (!r.events.empty()) {
    out += "\nEvents\n";
    // A long run can record thousands: show the first and the last few, the JSON has all.
    constexpr size_t kHead = 10, kTail = 3;
    const size_t n = r.events.size();
    for (size_t i = 0; i < n; ++i) {
      if (n > kHead + kTail + 1 && i == kHead) {
        out +=
            fmt::format("  ... {} more (every event is in the JSON summary)\n", n - kHead - kTail);
        i = n - kTail - 1;
        continue;
      }
      const auto& e = r.events[i];
      out += fmt::format("  {:<24} t = {}{}\n", e.name, show(e.t, kTimeDim),
                         e.stopped ? "  (stop)" : "");
      out += SnapshotText(scene, e.snapshot, show, CalcReportScales(r));
    }
  }
  if (!r.jumps.empty()) {
    out += "\nImpulses and impacts\n";
    for (const auto& x : r.jumps) {
      out += fmt::format("  t = {}: {}; energy {} -> {} (change {})\n", time(x.t), x.description,
                         energy(x.energy_before), energy(x.energy_after),
                         energy(x.energy_after - x.energy_before));
      out += fmt::format("    afterwards: v = {}, w = {}\n", show(x.v_after_W, kVelocityDim),
                         show(x.w_after_W, kRateDim, Angular::kYes));
    }
  }
  if (!r.contact_events.empty()) {
    out += "\nContact modes (time, contact point: from -> to, why)\n";
    constexpr size_t kHead = 20, kTail = 5;
    const size_t n = r.contact_events.size();
    for (size_t i = 0; i < n; ++i) {
      if (n > kHead + kTail + 1 && i == kHead) {
        out +=
            fmt::format("  ... {} more (every change is in the JSON summary)\n", n - kHead - kTail);
        i = n - kTail - 1;
        continue;
      }
      const auto& e = r.contact_events[i];
      if (e.from == e.to) {
        out += fmt::format("  t = {}  {}: {} ({})\n", time(e.t), e.point, e.to, e.reason);
      } else {
        out += fmt::format("  t = {}  {}: {} -> {} ({})\n", time(e.t), e.point, e.from, e.to,
                           e.reason);
      }
    }
  }
  if (!r.impacts.empty()) {
    out += fmt::format("\nImpacts at contacts: {}\n", r.impacts.size());
    constexpr size_t kHead = 10, kTail = 3;
    const size_t n = r.impacts.size();
    for (size_t i = 0; i < n; ++i) {
      if (n > kHead + kTail + 1 && i == kHead) {
        out +=
            fmt::format("  ... {} more (every impact is in the JSON summary)\n", n - kHead - kTail);
        i = n - kTail - 1;
        continue;
      }
      const auto& x = r.impacts[i];
      out += fmt::format("  t = {}  {}: approach speed {}, energy lost {}{}\n", time(x.t), x.point,
                         show(x.approach_speed, kVelocityDim), energy(x.energy_lost),
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
            time(x.rest_time));
      }
    }
  }
  out += scene.planar
             ? "\nFinal state (planar, x-y plane: centre of mass, angle and rates about z)\n"
             : "\nFinal state (centre of mass, velocity and angular velocity in the world "
               "frame)\n";
  const ReportScales k = CalcReportScales(r);
  for (size_t i = 0; i < r.final_bodies.size(); ++i) {
    const auto& b = r.final_bodies[i];
    const double v_s = k.body_speed[i], w_s = k.body_rate[i];
    const auto clean = [](double x, double scale) {
      return std::abs(x) <= 1e-12 * scale ? 0.0 : x;
    };
    if (scene.planar) {
      // Chapter eqs. 8.41-8.43: x, y, θ and their rates.
      out += fmt::format("  {}\n    position [{}, {}], theta {}\n    velocity [{}, {}], omega {}\n",
                         b.name, show(clean(b.p_WBcm.x(), k.length), kLength),
                         show(clean(b.p_WBcm.y(), k.length), kLength),
                         show(b.theta, kDimensionless, Angular::kYes),
                         show(clean(b.v_WBcm_W.x(), v_s), kVelocityDim),
                         show(clean(b.v_WBcm_W.y(), v_s), kVelocityDim),
                         show(clean(b.w_WB_W.z(), w_s), kRateDim, Angular::kYes));
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
        show(b.v_WBcm_W, kVelocityDim, Angular::kNo, v_s),
        show(b.w_WB_W, kRateDim, Angular::kYes, w_s), show(b.w_WB_B, kRateDim, Angular::kYes, w_s));
  }
  if (!r.final_reactions.empty()) {
    out += "\nReactions at the end (on the child at the joint point, world frame)\n";
    constexpr Dimension kForceDim{1, 1, -2};
    constexpr Dimension kMomentDim{2, 1, -2};
    for (const auto& x : r.final_reactions) {
      if (scene.planar) {
        out += fmt::format("  {} ({}) at [{}, {}]\n    force [{}, {}]\n    moment {}\n", x.name,
                           x.kind, show(x.p_WJ.x(), kLength), show(x.p_WJ.y(), kLength),
                           show(x.F_Jc_W.x(), kForceDim), show(x.F_Jc_W.y(), kForceDim),
                           show(x.M_Jc_W.z(), kMomentDim));
        continue;
      }
      out += fmt::format("  {} ({}) at {}\n    force {}\n    moment {}\n", x.name, x.kind,
                         show(x.p_WJ, kLength, Angular::kNo, k.length),
                         show(x.F_Jc_W, kForceDim, Angular::kNo, k.force),
                         show(x.M_Jc_W, kMomentDim, Angular::kNo, k.moment));
    }
  }
  if (!r.final_contacts.empty()) {
    out += "\nContacts at the end (forces on the body, world frame)\n";
    constexpr Dimension kForceDim{1, 1, -2};
    for (const auto& c : r.final_contacts) {
      out += fmt::format("  {}: {}, N = {}, friction {}, slip {}, gap {}\n", c.point, c.mode,
                         show(c.normal_force, kForceDim),
                         show(c.friction_force_W, kForceDim, Angular::kNo, k.force),
                         show(c.slip_velocity_W, kVelocityDim, Angular::kNo, k.speed),
                         show(std::abs(c.gap) <= 1e-12 * k.length ? 0.0 : c.gap, kLength));
    }
  }
  const StudyLedger& L = r.ledger;
  out += "\nLedger (from t = 0)\n";
  out += fmt::format("  kinetic energy      {} (translation {}, rotation {})\n",
                     energy(L.kinetic_translational + L.kinetic_rotational),
                     energy(L.kinetic_translational), energy(L.kinetic_rotational));
  out += fmt::format("  potential energy    {}\n", energy(L.potential));
  out += fmt::format("  mechanical energy   {} (initially {})\n", energy(L.energy),
                     energy(L.energy_initial));
  out += fmt::format("  non-conservative work {}\n", energy(L.work_nonconservative));
  for (const auto& [name, w] : L.work_by_force)
    out += fmt::format("    {:<20} {}\n", name, energy(w));
  for (const auto& [name, w] : L.work_by_constraint)
    out += fmt::format("    {:<20} {} (constraint)\n", name, energy(w));
  if (!r.final_contacts.empty()) {
    out += fmt::format("    {:<20} {}\n", "friction (sliding)", energy(L.friction_work));
    if (L.rolling_work != 0) {
      out += fmt::format("    {:<20} {}\n", "rolling resistance", energy(L.rolling_work));
    }
    out += fmt::format("    {:<20} {}\n", "impacts", energy(L.impact_work));
  }
  out += fmt::format("  dissipated          {}\n", energy(L.dissipated));
  if (!r.jumps.empty()) out += fmt::format("  impulses and impacts {}\n", energy(L.jumps));
  out += fmt::format(
      "  balance residual    {} ({:.2e} of the energy scale {})\n", energy(L.residual),
      L.energy_scale > 0 ? std::abs(L.residual) / L.energy_scale : 0.0, energy(L.energy_scale));
  out += fmt::format("  linear momentum     {}\n", show(L.linear_momentum_W, kMomentumDim));
  out += fmt::format("  angular momentum    {} about the centre of mass, {} about the origin\n",
                     show(L.angular_momentum_Scm_W, kAngularMomentumDim),
                     show(L.angular_momentum_Wo_W, kAngularMomentumDim));
  out += fmt::format("\nIntegrator: {}: {} steps, {} rejected, {} evaluations\n", r.integrator,
                     r.stats.steps, r.stats.rejected_steps, r.stats.function_evaluations);
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
  cmd->add_option("--format", args.format, "Report on standard output: text (default) or json")
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
  AddRunLimitOptions(*cmd, args);
  cmd->footer(
      "Examples:\n"
      "  chasles simulate examples/dzhanibekov.yaml --out results\n"
      "  chasles simulate examples/projectile-drag.yaml --set 'c=0.2 N*s/m' --format json\n"
      "  chasles simulate examples/spring-mass.yaml --until 20\n"
      "Progress goes to standard error: redrawn on a terminal after the first second, one "
      "line every 10 s otherwise (--quiet: none). Scene keys: docs/scene-format.md, section "
      "Dynamics; limits: docs/reliability-limits.md.\n"
      "Exit codes: 0 success, 2 bad input, 3 a check failed with --strict, 1 internal error.");
  return cmd;
}

int RunSimulate(const SimulateArgs& args) {
  if (args.scene.scene.empty()) {
    throw InputError("chasles simulate needs a scene file (chasles simulate --help)");
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
  const double t_end =
      std::isfinite(options.until) ? options.until : scene.dynamics.simulation.until;
  StudyResult r;
  {
    Progress progress("simulating", "s", args.quiet, args.progress_interval);
    options.progress = [&](double t) { progress.Update(t, t_end); };
    r = RunStudy(scene, options);
  }

  const std::filesystem::path dir = args.out_dir.empty() ? "." : args.out_dir;
  CreateOutputFolder(dir.string());
  const std::string stem = std::filesystem::path(args.scene.scene).stem().string();
  const std::string csv_path = (dir / (stem + ".csv")).string();
  const std::string json_path = (dir / (stem + ".json")).string();
  // Every output is made and checked (no non-finite number) before any file appears; then
  // the CSV and the JSON appear together or not at all (output_set.h).
  CheckFiniteTable(r.columns, r.rows, "the CSV time series");
  const std::string json_text = DumpJson(Json(scene, r, csv_path), "the JSON summary");
  const std::string report =
      args.format == "json" ? json_text : Text(scene, r, units, csv_path, json_path);
  OutputSet files;
  files.Add(csv_path, Csv(r));
  files.Add(json_path, json_text);
  files.Commit();
  Emit("", report);
  return args.strict && !r.certificate.passed() ? kExitCheckFailed : 0;
}

}  // namespace chasles::cli
