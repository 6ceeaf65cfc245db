// chasles solve: the instantaneous problem of chapter 8.2-8.3 at a scene's initial state —
// every body's acceleration and every constraint's reaction ("what force does the support
// exert?"), and for rolling the friction it needs against mu_s. Scenes with contacts get their
// modes chosen first (SelectContactModes: which points press, stick or slide) and a report per
// contact point. With --sweep, the same over a range of one parameter, as a table.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "certificate_report.h"
#include "chasles/analysis/certificate.h"
#include "chasles/analysis/instantaneous.h"
#include "chasles/dynamics/contact_solve.h"
#include "chasles/error.h"
#include "chasles/files/output_set.h"
#include "chasles/model/model.h"
#include "chasles/report/json_report.h"
#include "chasles/report/report_data.h"
#include "chasles/report/solve_json.h"
#include "chasles/scene/scene.h"
#include "chasles/scene/scene_error.h"
#include "chasles/scene/solve.h"
#include "chasles/scene/study.h"
#include "chasles/scene/units.h"
#include "cluster.h"
#include "commands.h"
#include "html_report.h"
#include "progress.h"
#include "scene_args.h"

namespace chasles::cli {

namespace {

/// `x` with round-off against `scale` shown as 0: a component below 1e-12 of the scale is the
/// solve's rounding, not a physical value (the JSON keeps every digit).
double Clean(double x, double scale) {
  return std::abs(Finite(x, "a value of the solve report")) <= 1e-12 * scale ? 0.0 : x;
}

/// The text report's values in the units asked for (--units, else the scene's `units:`); the
/// JSON and CSV stay SI. Each value is converted from SI after its round-off is cleaned.
struct Show {
  const UnitSystem& u;
  /// " unit" (nothing for a pure number).
  std::string Unit(const Dimension& d, Angular a = Angular::kNo) const {
    const std::string unit = u.FormatUnit(d, a);
    return unit.empty() ? "" : " " + unit;
  }
  /// An energy: as a moment (same dimension), but in SI its own name, the joule.
  std::string E(double si) const {
    const std::string unit = u.FormatUnit(kEnergy);
    return Num(si, kEnergy) + (unit == "N*m" ? " J" : " " + unit);
  }
  std::string Num(double si, const Dimension& d, Angular a = Angular::kNo) const {
    return fmt::format("{:.9g}", u.FromSI(Finite(si, "a value of the solve report"), d, a));
  }
  /// "value unit".
  std::string operator()(double si, const Dimension& d, Angular a = Angular::kNo) const {
    return Num(si, d, a) + Unit(d, a);
  }
  /// "[x, y, z] unit"; `scale` is the size of the largest quantity of its kind in the report
  /// (e.g. the largest acceleration of any body), so that 1e-15 m/s² next to 2 m/s² prints as
  /// 0: a student reads [2.83, 0, -1.63], not [2.83, -2.5e-32, -1.63].
  std::string Vec(const Vec3& v, const Dimension& d, double scale = 0.0,
                  Angular a = Angular::kNo) const {
    const double s = std::max(v.stableNorm(), scale);
    return fmt::format("[{}, {}, {}]{}", Num(Clean(v.x(), s), d, a), Num(Clean(v.y(), s), d, a),
                       Num(Clean(v.z(), s), d, a), Unit(d, a));
  }
  /// An in-plane vector of a planar scene's report, "[x, y] unit" (its z is 0); Vec otherwise.
  std::string InPlane(bool planar, const Vec3& v, const Dimension& d, double scale = 0.0) const {
    if (!planar) return Vec(v, d, scale);
    const double s = std::max(v.stableNorm(), scale);
    return fmt::format("[{}, {}]{}", Num(Clean(v.x(), s), d), Num(Clean(v.y(), s), d), Unit(d));
  }
};

/// The scales of the report's quantities: the largest of each kind over bodies and reactions.
struct ReportScales {
  double a = 0.0, alpha = 0.0, force = 0.0, moment = 0.0, p = 0.0, h = 0.0, v = 0.0, w = 0.0,
         hdot = 0.0;
};

ReportScales CalcScales(const SolveReport& s) {
  ReportScales k;
  for (const auto& b : s.solution.bodies) {
    k.a = std::max(k.a, b.a_WBcm_W.stableNorm());
    k.alpha = std::max(k.alpha, b.alpha_WB_W.stableNorm());
  }
  double arm = 0.0;
  for (const ContactPointReport& c : s.contacts) {
    k.force = std::max({k.force, c.out.normal_force, c.out.friction_force_W.stableNorm()});
  }
  for (const auto& r : s.solution.reactions) {
    k.force = std::max(k.force, r.F_Jc_W.stableNorm());
    k.moment = std::max(k.moment, r.M_Jc_W.stableNorm());
    arm = std::max(arm, r.p_WJ.stableNorm());
  }
  // A moment's round-off comes from forces times lever arms as well as from other moments.
  k.moment = std::max(k.moment, k.force * arm);
  for (const BodyMotionReport& m : s.motion) {
    k.p = std::max(k.p, m.P.stableNorm());
    k.h = std::max({k.h, m.H_cm.stableNorm(), m.H_O.stableNorm()});
    k.v = std::max(k.v, m.v_WBcm_W.stableNorm());
    k.w = std::max(k.w, m.w_WB_W.stableNorm());
    k.hdot = std::max({k.hdot, m.Hdot_cm.stableNorm(), m.Hdot_O.stableNorm(), k.moment});
    for (const PointMotionReport& p : m.points) {
      k.v = std::max(k.v, p.v_WP_W.stableNorm());
      k.a = std::max(k.a, p.a_WP_W.stableNorm());
    }
  }
  return k;
}

/// The velocities, the named points' velocities and accelerations and dH/dt of every body.
std::string KinematicsText(const SolveReport& s, const ReportScales& k, const Show& u) {
  std::string out;
  // ΣM = dH/dt (eq. 8.30): the Checks section's angular momentum balance compares the
  // moments on each body with this dH_cm/dt.
  out +=
      "\nVelocities, named points and dH/dt (about each centre of mass; dH_O/dt about the "
      "origin)\n";
  const auto hdot = [&](const Vec3& cm, const Vec3& o) {
    if (s.planar) {
      return fmt::format("    dH_z/dt  {}\n    dH_Oz/dt {}\n", u(Clean(cm.z(), k.hdot), kMoment),
                         u(Clean(o.z(), k.hdot), kMoment));
    }
    return fmt::format("    dH/dt   {}\n    dH_O/dt {}\n", u.Vec(cm, kMoment, k.hdot),
                       u.Vec(o, kMoment, k.hdot));
  };
  for (const BodyMotionReport& m : s.motion) {
    out += fmt::format("  {}\n", m.name);
    if (s.planar) {
      out += fmt::format("    v_x   {}\n    v_y   {}\n    omega {}\n",
                         u(Clean(m.v_WBcm_W.x(), k.v), kVelocity),
                         u(Clean(m.v_WBcm_W.y(), k.v), kVelocity),
                         u(Clean(m.w_WB_W.z(), k.w), kRate, Angular::kYes));
    } else {
      out += fmt::format("    v_cm  {}\n    omega {}\n", u.Vec(m.v_WBcm_W, kVelocity, k.v),
                         u.Vec(m.w_WB_W, kRate, k.w, Angular::kYes));
    }
    for (const PointMotionReport& p : m.points) {
      if (s.planar) {
        out +=
            fmt::format("    point {} at {}: v {}, a {}\n", p.name,
                        u.InPlane(true, p.p_WP, kLength), u.InPlane(true, p.v_WP_W, kVelocity, k.v),
                        u.InPlane(true, p.a_WP_W, kAcceleration, k.a));
      } else {
        out += fmt::format("    point {} at {}\n      v {}\n      a {}\n", p.name,
                           u.Vec(p.p_WP, kLength), u.Vec(p.v_WP_W, kVelocity, k.v),
                           u.Vec(p.a_WP_W, kAcceleration, k.a));
      }
    }
    out += hdot(m.Hdot_cm, m.Hdot_O);
  }
  if (s.motion.size() > 1) {
    out += "  all bodies (dH/dt about the system's centre of mass)\n";
    out += hdot(s.total.Hdot_cm, s.total.Hdot_O);
  }
  return out;
}

/// Each body's acceleration and angular acceleration.
std::string AccelerationsText(const SolveReport& s, const ReportScales& k, const Show& u) {
  std::string out;
  for (const auto& b : s.solution.bodies) {
    if (s.planar) {
      out += fmt::format("  {}\n    a_x   {}\n    a_y   {}\n    alpha {}\n", b.name,
                         u(Clean(b.a_WBcm_W.x(), k.a), kAcceleration),
                         u(Clean(b.a_WBcm_W.y(), k.a), kAcceleration),
                         u(Clean(b.alpha_WB_W.z(), k.alpha), kAngularAcceleration, Angular::kYes));
      continue;
    }
    out += fmt::format("  {}\n    a_cm  {}\n    alpha {}\n", b.name,
                       u.Vec(b.a_WBcm_W, kAcceleration, k.a),
                       u.Vec(b.alpha_WB_W, kAngularAcceleration, k.alpha, Angular::kYes));
  }
  return out;
}

/// Each constraint's reaction; for a string its mode, for rolling the friction it needs.
std::string ReactionsText(const SolveReport& s, const ReportScales& k, const Show& u) {
  if (s.solution.reactions.empty()) return "";
  std::string out = "\nReactions (on the child at the joint point)\n";
  for (size_t i = 0; i < s.solution.reactions.size(); ++i) {
    const ReactionReport& r = s.solution.reactions[i];
    if (s.planar) {
      out += fmt::format("  {} ({}) at {}\n", r.name, r.kind, u.InPlane(true, r.p_WJ, kLength));
      out += fmt::format("    Fx {}, Fy {}, Mz {}\n", u(Clean(r.F_Jc_W.x(), k.force), kForce),
                         u(Clean(r.F_Jc_W.y(), k.force), kForce),
                         u(Clean(r.M_Jc_W.z(), k.moment), kMoment));
    } else {
      out += fmt::format("  {} ({}) at {}\n", r.name, r.kind, u.Vec(r.p_WJ, kLength));
      out += fmt::format("    force  {}\n", u.Vec(r.F_Jc_W, kForce, k.force));
      out += fmt::format("    moment {}\n", u.Vec(r.M_Jc_W, kMoment, k.moment));
      // What a bearing fixed in the child feels, and what its housing (the parent) feels;
      // a joint to the world has the world as its parent frame (the lines above).
      out += fmt::format("    in the child's frame: force {}, moment {}\n",
                         u.Vec(r.F_Jc_B, kForce, k.force), u.Vec(r.M_Jc_B, kMoment, k.moment));
      if (r.parent != kWorld) {
        out += fmt::format("    in the parent's frame: force {}, moment {}\n",
                           u.Vec(r.F_Jc_P, kForce, k.force), u.Vec(r.M_Jc_P, kMoment, k.moment));
      }
    }
    if (!r.mode.empty()) {
      out += fmt::format(
          "    {}: tension {}, slack {} (chosen by T >= 0, slack acceleration >= 0, "
          "T * slack acceleration = 0)\n",
          r.mode, u(Clean(r.lambda[0], k.force), kForce), u(r.gap, kLength));
    }
    if (r.is_rolling) {
      out +=
          fmt::format("    normal force {}, friction {}, f/N = {:.9g}", u(r.normal_force, kForce),
                      u(r.friction_W.norm(), kForce), r.friction_needed);
      if (!std::isnan(s.mu_s[i])) {
        out += fmt::format(" against mu_s = {:.6g}: {}", s.mu_s[i],
                           r.friction_needed <= s.mu_s[i] ? "rolls" : "slips");
      }
      out += "\n";
    }
  }
  return out;
}

/// A sticking round point's rolling resistance: the moment holding its rolling, or resisting it.
std::string RollingResistanceText(const SolveReport& s, const ContactPointReport& c,
                                  const ReportScales& k, const Show& u) {
  const Vec3& M = c.out.rolling_moment_W;
  const double cap = c.out.rolling_moment_capacity;
  const double scale = std::max({k.moment, M.stableNorm(), cap});
  // A planar scene's moments are about z.
  const std::string moment =
      s.planar ? "Mz " + u(Clean(M.z(), scale), kMoment) : u.Vec(M, kMoment, scale);
  if (c.out.rolling_held) {
    return fmt::format(
        "    rolling held: moment {} (|M| {}) within mu_r N R = {} (|M|/(mu_r N R) = {:.9g})\n",
        moment, u(M.norm(), kMoment), u(cap, kMoment), cap > 0.0 ? M.norm() / cap : 0.0);
  }
  return fmt::format("    rolling: moment {} = mu_r N R = {} against the rolling (mu_r = {:.6g})\n",
                     moment, u(cap, kMoment), c.mu_r);
}

/// Each contact point's mode and forces.
std::string ContactsText(const SolveReport& s, const ReportScales& k, const Show& u) {
  if (s.contacts.empty()) return "";
  std::string out = "\nContacts (modes chosen at the initial state; friction on the body)\n";
  for (const ContactPointReport& c : s.contacts) {
    out += fmt::format("  {}: {} ({})\n", c.point, c.Regime(), ContactModeName(c.out.mode));
    if (c.out.mode == ContactMode::kSeparated) {
      out += fmt::format("    gap {}\n", u(c.out.gap, kLength));
      continue;
    }
    out += fmt::format("    normal force {}, friction {} (|f| {})\n", u(c.out.normal_force, kForce),
                       u.InPlane(s.planar, c.out.friction_force_W, kForce, k.force),
                       u(c.out.friction_force_W.norm(), kForce));
    if (c.out.mode == ContactMode::kSticking) {
      out += fmt::format("    f/N = {:.9g} against mu_s = {:.6g}\n", c.FrictionRatio(), c.mu_s);
      if (c.round && c.mu_r > 0.0) out += RollingResistanceText(s, c, k, u);
    } else {
      out += fmt::format("    slip velocity {}, f/N = mu_k = {:.6g}\n",
                         u.InPlane(s.planar, c.out.slip_velocity_W, kVelocity), c.mu_k);
    }
  }
  return out;
}

std::string Text(const Scene& scene, const SolveReport& s, const UnitSystem& units) {
  const Show u{units};
  std::string out = fmt::format("{}{}\n", scene.title.empty() ? scene.file : scene.title,
                                scene.title.empty() ? "" : fmt::format(" ({})", scene.file));
  out += fmt::format(
      "Instantaneous solution at the initial state (report in {} units; JSON and CSV in SI; "
      "{})\n\nAccelerations\n",
      units.spec(), s.planar ? "planar: x-y plane, moments about z" : "world frame");
  const ReportScales k = CalcScales(s);
  out += AccelerationsText(s, k, u);
  out += ReactionsText(s, k, u);
  out += ContactsText(s, k, u);
  out += "\nKinetic energy and momenta (H about each centre of mass, H_O about the origin)\n";
  const auto motion = [&out, &k, &s, &u](const BodyMotionReport& m, const char* cm) {
    out += fmt::format("    T {} (translational {}, rotational {})\n", u.E(m.T_trans + m.T_rot),
                       u.E(m.T_trans), u.E(m.T_rot));
    if (s.planar) {
      // In the plane: p = (p_x, p_y), H about z (eq. 8.38).
      out += fmt::format("    p   {}\n", u.InPlane(true, m.P, kMomentum, k.p));
      out +=
          fmt::format("    H_z {} (about {})\n", u(Clean(m.H_cm.z(), k.h), kAngularMomentum), cm);
      out += fmt::format("    H_Oz {}\n", u(Clean(m.H_O.z(), k.h), kAngularMomentum));
      return;
    }
    out += fmt::format("    p   {}\n", u.Vec(m.P, kMomentum, k.p));
    out += fmt::format("    H   {} (about {})\n", u.Vec(m.H_cm, kAngularMomentum, k.h), cm);
    out += fmt::format("    H_O {}\n", u.Vec(m.H_O, kAngularMomentum, k.h));
  };
  for (const BodyMotionReport& m : s.motion) {
    out += fmt::format("  {}\n", m.name);
    motion(m, "its centre of mass");
  }
  if (s.motion.size() > 1) {
    out += "  all bodies\n";
    motion(s.total, "the system's centre of mass");
  }
  out += KinematicsText(s, k, u);
  for (const auto& w : s.solution.warnings) out += fmt::format("warning: {}\n", w);
  for (const auto& w : s.certificate.FailureMessages()) out += fmt::format("warning: {}\n", w);
  out += CertificateText(s.certificate);
  return out;
}

}  // namespace

CLI::App* AddSolveCommand(CLI::App& app, SolveArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "solve",
      "Solve the instantaneous problem at a scene's initial state: every body's acceleration, "
      "every joint's reaction, the friction rolling needs, each contact point's mode, normal "
      "and friction force (chapter 8.2-8.3)");
  AddSceneArgs(*cmd, args.scene);
  cmd->add_option("--html", args.html,
                  "Also write the browser report here: the configuration with the force arrows "
                  "of the solved instant (one HTML file); with --sweep, every column plotted "
                  "against the swept parameter");
  cmd->add_option("--sweep", args.sweep,
                  "Repeat over a parameter range: NAME=START:STOP:COUNT (START and STOP are "
                  "expressions with units, e.g. 'theta=0 deg:60 deg:7'); prints a table");
  cmd->add_option("--format", args.format,
                  "text (default; with --sweep the CSV table), json, or csv (one row of the "
                  "solved quantities, the columns of a sweep after its parameter)")
      ->check(CLI::IsMember({"text", "json", "csv"}));
  cmd->add_option("--units", args.units,
                  "Units of the text report: SI, US (in, lb, lbf), or a list such as 'ft,slug' "
                  "(default: the scene's own units; JSON and CSV are always SI)");
  cmd->add_option("-o,--out,--output", args.output,
                  "Write the report (or the sweep's table) to this file instead of standard "
                  "output; the file appears complete or not at all");
  cmd->add_option("--precision", args.precision,
                  "Digits of a CSV's numbers: default (12 significant digits) or full (every "
                  "double with %.17g, reads back bitwise)")
      ->check(CLI::IsMember({"default", "full"}));
  cmd->add_flag("--full-precision", args.full_precision, "The same as --precision full");
  cmd->add_flag("--strict", args.strict,
                "Exit with code 3 when a check of the answer fails (the report's Checks section; "
                "otherwise a failed check is only a warning)");
  cmd->add_option("--max-rows", args.max_rows,
                  "Most values of a sweep (its rows; default 1000000); a larger COUNT is refused")
      ->check(WholeNumber(kMaxWholeNumber));
  cmd->add_flag("--quiet", args.quiet,
                "No progress of a sweep on standard error (otherwise: redrawn on a terminal, one "
                "line every 10 s off it)");
  cmd->add_option("--progress-interval", args.progress_interval,
                  "Seconds between progress lines when standard error is not a terminal "
                  "(default 10)");
  cmd->footer(
      "Examples:\n"
      "  chasles solve examples/example-8.3-cylinder-incline.yaml\n"
      "  chasles solve examples/example-8.3-cylinder-incline.yaml --sweep 'theta=10 deg:50 "
      "deg:5'\n"
      "  chasles solve examples/example-8.3-cylinder-incline.yaml --units US -o incline.txt\n"
      "  chasles solve examples/example-8.3-cylinder-incline.yaml --format csv --full-precision\n"
      "Scene keys: docs/scene-format.md, section Joints, rolling and drivers.\n"
      "Exit codes: 0 success, 2 bad input, 3 a check failed with --strict, 1 internal error.");
  return cmd;
}

int RunSolve(const SolveArgs& args) {
  if (args.scene.scene.empty()) {
    throw InputError("chasles solve needs a scene file (chasles solve --help)");
  }
  const CsvPrecision precision =
      args.full_precision ? CsvPrecision::kFull : ParseCsvPrecision(args.precision);
  // Every target is checked before the solve, so a mistyped path does not waste a long sweep.
  OutputSet out;
  out.Expect(ReportTarget(args.output), "-o");
  if (!args.html.empty()) {
    RequireHtmlReport("--html");
    out.Expect(args.html, "--html");
  }
  if (args.sweep.empty()) {
    const Scene scene = LoadScene(args.scene);
    // Checked before the solve: a mistyped unit is bad input (exit 2).
    const UnitSystem units = UnitSystem::Parse(args.units.empty() ? scene.units : args.units);
    const SolveReport s = SolveScene(scene);
    // Every value of any report is in the JSON form: checked there first, by name (and let go
    // before another form is written).
    std::string report;
    {
      const nlohmann::json j = SolveJson(s);
      if (args.format == "json") {
        report = DumpJson(j, "the solve report");
      } else if (args.format == "text") {
        CheckFiniteJson(j, "the solve report");
      }
    }
    if (args.format == "csv") report = SolveCsv(s, precision);
    if (args.format == "text") report = Text(scene, s, units);
    if (!args.html.empty()) out.Add(args.html, HtmlReport(SolveReportData(scene, s)));
    out.Add(ReportTarget(args.output), std::move(report));
    out.Commit();
    SayWroteHtmlReport(args.html);
    return args.strict && !s.certificate.passed() ? kExitCheckFailed : 0;
  }
  if (!args.units.empty()) {
    throw InputError("--units sets the units of the text report; a sweep's table is SI");
  }
  const SweepSpec sweep = ParseSweep(args.sweep, "command line", "--sweep");
  const std::int64_t max_rows = args.max_rows > 0 ? args.max_rows : kDefaultMaxRows;
  if (sweep.count > max_rows) {
    throw SceneError("command line", 0, 0, "--sweep",
                     fmt::format("COUNT {} is more than the limit of {} rows; raise the limit "
                                 "with --max-rows",
                                 sweep.count, max_rows));
  }
  if (!(args.progress_interval > 0) || !std::isfinite(args.progress_interval)) {
    throw InputError(fmt::format("--progress-interval must be a positive time in seconds, got {}",
                                 args.progress_interval));
  }
  // Under mpirun: this rank's values; rank 0 gathers the rows and alone writes (cluster.h).
  Cluster& cluster = Cluster::Get();
  Progress progress("solve --sweep", "", args.quiet || cluster.rank() != 0, args.progress_interval);
  SweepOptions options;
  options.share = cluster.share();
  options.progress = [&progress, &cluster](int k, int count) {
    cluster.set_point(k);  // where this rank stopped, if the solve fails
    progress.Update(k, count);
  };
  // A failed check of one value: a warning on standard error (the table stays a table); under
  // mpirun kept with the value's row and printed by rank 0 in order.
  SweepWarnings warnings;
  options.on_solution = [&](int k, double value, const SolveReport& s) {
    for (const std::string& w : s.certificate.FailureMessages()) {
      if (cluster.distributed()) {
        warnings[k].push_back(fmt::format("{} = {:.12g}: {}", sweep.name, value, w));
      } else {
        std::fprintf(stderr, "warning: %s = %.12g: %s\n", sweep.name.c_str(), value, w.c_str());
      }
    }
  };
  SweepTable table =
      SolveSweep(SceneLoader(args.scene), SceneOptionsFrom(args.scene), sweep, options);
  bool check_failed = false;
  if (!GatherSweep(&table, &warnings, &check_failed)) return 0;
  if (cluster.distributed()) {
    for (const std::string& w : table.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  }
  CheckFiniteTable(table.columns, table.rows, "the sweep table");
  const std::string text = args.format == "json" ? DumpJson(SweepJson(table), "the sweep table")
                                                 : SweepCsv(table, precision);
  out.Add(ReportTarget(args.output), text);
  if (!args.html.empty()) {
    out.Add(args.html, HtmlReport(SweepReportData(LoadScene(args.scene), table, "solve")));
  }
  out.Commit();
  SayWroteHtmlReport(args.html);
  return args.strict && table.failed ? kExitCheckFailed : 0;
}

}  // namespace chasles::cli
