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
#include "chasles/io/atomic_file.h"
#include "chasles/io/json_report.h"
#include "chasles/io/solve_json.h"
#include "chasles/model/model.h"
#include "chasles/scene/report_data.h"
#include "chasles/scene/scene.h"
#include "chasles/scene/scene_error.h"
#include "chasles/scene/solve.h"
#include "chasles/scene/study.h"
#include "commands.h"
#include "html_report.h"
#include "progress.h"
#include "scene_args.h"

namespace chasles::cli {

namespace {

// A vector for the report: components that are round-off against the vector's own size
// (1e-12 of it) show as 0, so a student reads [2.83, 0, -1.63], not [2.83, -2.5e-32, -1.63].
/// `x` with round-off against `scale` shown as 0: a component below 1e-12 of the scale is the
/// solve's rounding, not a physical value (the JSON keeps every digit).
double Clean(double x, double scale) {
  return std::abs(Finite(x, "a value of the solve report")) <= 1e-12 * scale ? 0.0 : x;
}

/// A vector for the text report; `scale` is the size of the largest quantity of its kind in
/// the report (e.g. the largest acceleration of any body), so that 1e-15 m/s² next to 2 m/s²
/// prints as 0.
std::string V(const Vec3& v, double scale = 0.0) {
  const double s = std::max(v.stableNorm(), scale);
  return fmt::format("[{:.9g}, {:.9g}, {:.9g}]", Clean(v.x(), s), Clean(v.y(), s), Clean(v.z(), s));
}

/// An in-plane vector of a planar scene's text report, [x, y] (its z is 0); V otherwise.
std::string VInPlane(bool planar, const Vec3& v, double scale = 0.0) {
  if (!planar) return V(v, scale);
  const double s = std::max(v.stableNorm(), scale);
  return fmt::format("[{:.9g}, {:.9g}]", Clean(v.x(), s), Clean(v.y(), s));
}

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
std::string KinematicsText(const SolveReport& s, const ReportScales& k) {
  std::string out;
  // ΣM = dH/dt (eq. 8.30): the Checks section's angular momentum balance compares the
  // moments on each body with this dH_cm/dt.
  out +=
      "\nVelocities, named points and dH/dt (about each centre of mass; dH_O/dt about the "
      "origin)\n";
  for (const BodyMotionReport& m : s.motion) {
    out += fmt::format("  {}\n", m.name);
    if (s.planar) {
      out += fmt::format("    v_x   {:.9g} m/s\n    v_y   {:.9g} m/s\n    omega {:.9g} rad/s\n",
                         Clean(m.v_WBcm_W.x(), k.v), Clean(m.v_WBcm_W.y(), k.v),
                         Clean(m.w_WB_W.z(), k.w));
    } else {
      out += fmt::format("    v_cm  {} m/s\n    omega {} rad/s\n", V(m.v_WBcm_W, k.v),
                         V(m.w_WB_W, k.w));
    }
    for (const PointMotionReport& p : m.points) {
      if (s.planar) {
        out += fmt::format(
            "    point {} at [{:.9g}, {:.9g}] m: v [{:.9g}, {:.9g}] m/s, a [{:.9g}, {:.9g}] "
            "m/s^2\n",
            p.name, p.p_WP.x(), p.p_WP.y(), Clean(p.v_WP_W.x(), k.v), Clean(p.v_WP_W.y(), k.v),
            Clean(p.a_WP_W.x(), k.a), Clean(p.a_WP_W.y(), k.a));
      } else {
        out += fmt::format("    point {} at {} m\n      v {} m/s\n      a {} m/s^2\n", p.name,
                           V(p.p_WP), V(p.v_WP_W, k.v), V(p.a_WP_W, k.a));
      }
    }
    if (s.planar) {
      out += fmt::format("    dH_z/dt  {:.9g} N*m\n    dH_Oz/dt {:.9g} N*m\n",
                         Clean(m.Hdot_cm.z(), k.hdot), Clean(m.Hdot_O.z(), k.hdot));
    } else {
      out += fmt::format("    dH/dt   {} N*m\n    dH_O/dt {} N*m\n", V(m.Hdot_cm, k.hdot),
                         V(m.Hdot_O, k.hdot));
    }
  }
  if (s.motion.size() > 1) {
    out += "  all bodies (dH/dt about the system's centre of mass)\n";
    if (s.planar) {
      out += fmt::format("    dH_z/dt  {:.9g} N*m\n    dH_Oz/dt {:.9g} N*m\n",
                         Clean(s.total.Hdot_cm.z(), k.hdot), Clean(s.total.Hdot_O.z(), k.hdot));
    } else {
      out += fmt::format("    dH/dt   {} N*m\n    dH_O/dt {} N*m\n", V(s.total.Hdot_cm, k.hdot),
                         V(s.total.Hdot_O, k.hdot));
    }
  }
  return out;
}

std::string Text(const Scene& scene, const SolveReport& s) {
  std::string out = fmt::format("{}{}\n", scene.title.empty() ? scene.file : scene.title,
                                scene.title.empty() ? "" : fmt::format(" ({})", scene.file));
  out += fmt::format("Instantaneous solution at the initial state (SI, {})\n\nAccelerations\n",
                     s.planar ? "planar: x-y plane, moments about z" : "world frame");
  const ReportScales k = CalcScales(s);
  for (const auto& b : s.solution.bodies) {
    if (s.planar) {
      out += fmt::format("  {}\n    a_x   {:.9g} m/s^2\n    a_y   {:.9g} m/s^2\n", b.name,
                         Clean(b.a_WBcm_W.x(), k.a), Clean(b.a_WBcm_W.y(), k.a));
      out += fmt::format("    alpha {:.9g} rad/s^2\n", Clean(b.alpha_WB_W.z(), k.alpha));
      continue;
    }
    out += fmt::format("  {}\n    a_cm  {} m/s^2\n", b.name, V(b.a_WBcm_W, k.a));
    out += fmt::format("    alpha {} rad/s^2\n", V(b.alpha_WB_W, k.alpha));
  }
  if (!s.solution.reactions.empty()) {
    out += "\nReactions (on the child at the joint point)\n";
  }
  for (size_t i = 0; i < s.solution.reactions.size(); ++i) {
    const ReactionReport& r = s.solution.reactions[i];
    if (s.planar) {
      out +=
          fmt::format("  {} ({}) at [{:.9g}, {:.9g}] m\n", r.name, r.kind, r.p_WJ.x(), r.p_WJ.y());
      out +=
          fmt::format("    Fx {:.9g} N, Fy {:.9g} N, Mz {:.9g} N*m\n", Clean(r.F_Jc_W.x(), k.force),
                      Clean(r.F_Jc_W.y(), k.force), Clean(r.M_Jc_W.z(), k.moment));
    } else {
      out += fmt::format("  {} ({}) at {} m\n", r.name, r.kind, V(r.p_WJ));
      out += fmt::format("    force  {} N\n", V(r.F_Jc_W, k.force));
      out += fmt::format("    moment {} N*m\n", V(r.M_Jc_W, k.moment));
    }
    if (!r.mode.empty()) {
      out += fmt::format(
          "    {}: tension {:.9g} N, slack {:.9g} m (chosen by T >= 0, slack acceleration >= 0, "
          "T * slack acceleration = 0)\n",
          r.mode, Clean(r.lambda[0], k.force), r.gap);
    }
    if (r.is_rolling) {
      out += fmt::format("    normal force {:.9g} N, friction {:.9g} N, f/N = {:.9g}",
                         r.normal_force, r.friction_W.norm(), r.friction_needed);
      if (!std::isnan(s.mu_s[i])) {
        out += fmt::format(" against mu_s = {:.6g}: {}", s.mu_s[i],
                           r.friction_needed <= s.mu_s[i] ? "rolls" : "slips");
      }
      out += "\n";
    }
  }
  if (!s.contacts.empty()) {
    out += "\nContacts (modes chosen at the initial state; friction on the body)\n";
  }
  for (const ContactPointReport& c : s.contacts) {
    out += fmt::format("  {}: {} ({})\n", c.point, c.Regime(), ContactModeName(c.out.mode));
    if (c.out.mode == ContactMode::kSeparated) {
      out += fmt::format("    gap {:.9g} m\n", c.out.gap);
      continue;
    }
    out += fmt::format("    normal force {:.9g} N, friction {} N (|f| {:.9g} N)\n",
                       c.out.normal_force, VInPlane(s.planar, c.out.friction_force_W, k.force),
                       c.out.friction_force_W.norm());
    if (c.out.mode == ContactMode::kSticking) {
      out += fmt::format("    f/N = {:.9g} against mu_s = {:.6g}\n", c.FrictionRatio(), c.mu_s);
    } else {
      out += fmt::format("    slip velocity {} m/s, f/N = mu_k = {:.6g}\n",
                         VInPlane(s.planar, c.out.slip_velocity_W), c.mu_k);
    }
  }
  out += "\nKinetic energy and momenta (H about each centre of mass, H_O about the origin)\n";
  const auto motion = [&out, &k, &s](const BodyMotionReport& m, const char* cm) {
    out += fmt::format("    T {:.9g} J (translational {:.9g} J, rotational {:.9g} J)\n",
                       m.T_trans + m.T_rot, m.T_trans, m.T_rot);
    if (s.planar) {
      // In the plane: p = (p_x, p_y), H about z (eq. 8.40).
      out += fmt::format("    p   [{:.9g}, {:.9g}] kg*m/s\n", Clean(m.P.x(), k.p),
                         Clean(m.P.y(), k.p));
      out += fmt::format("    H_z {:.9g} kg*m^2/s (about {})\n", Clean(m.H_cm.z(), k.h), cm);
      out += fmt::format("    H_Oz {:.9g} kg*m^2/s\n", Clean(m.H_O.z(), k.h));
      return;
    }
    out += fmt::format("    p   {} kg*m/s\n", V(m.P, k.p));
    out += fmt::format("    H   {} kg*m^2/s (about {})\n", V(m.H_cm, k.h), cm);
    out += fmt::format("    H_O {} kg*m^2/s\n", V(m.H_O, k.h));
  };
  for (const BodyMotionReport& m : s.motion) {
    out += fmt::format("  {}\n", m.name);
    motion(m, "its centre of mass");
  }
  if (s.motion.size() > 1) {
    out += "  all bodies\n";
    motion(s.total, "the system's centre of mass");
  }
  out += KinematicsText(s, k);
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
                  "of the solved instant (one HTML file; not with --sweep)");
  cmd->add_option("--sweep", args.sweep,
                  "Repeat over a parameter range: NAME=START:STOP:COUNT (START and STOP are "
                  "expressions with units, e.g. 'theta=0 deg:60 deg:7'); prints a table");
  cmd->add_option("--format", args.format, "text (default) or json")
      ->check(CLI::IsMember({"text", "json"}));
  cmd->add_flag("--strict", args.strict,
                "Exit with code 3 when a check of the answer fails (the report's Checks section; "
                "otherwise a failed check is only a warning)");
  cmd->add_option("--max-rows", args.max_rows,
                  "Most values of a sweep (its rows; default 1000000); a larger COUNT is refused")
      ->check(CLI::PositiveNumber);
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
      "Scene keys: docs/scene-format.md, section Joints, rolling and drivers.\n"
      "Exit codes: 0 success, 2 bad input, 3 a check failed with --strict, 1 internal error.");
  return cmd;
}

int RunSolve(const SolveArgs& args) {
  if (args.scene.scene.empty()) {
    throw InputError("chasles solve needs a scene file (chasles solve --help)");
  }
  if (args.sweep.empty()) {
    const Scene scene = LoadScene(args.scene);
    const SolveReport s = SolveScene(scene);
    // Every value of either report is in the JSON form: checked there first, by name.
    const nlohmann::json j = SolveJson(s);
    if (!args.html.empty()) {
      RequireHtmlReport("--html");
      WriteFileAtomically(args.html, HtmlReport(SolveReportData(scene, s)));
    }
    Emit("", args.format == "json" ? DumpJson(j, "the solve report")
                                   : (CheckFiniteJson(j, "the solve report"), Text(scene, s)));
    return args.strict && !s.certificate.passed() ? kExitCheckFailed : 0;
  }
  if (!args.html.empty()) {
    throw InputError("--html draws one solved instant; it does not go with --sweep");
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
  Progress progress("solve --sweep", "", args.quiet, args.progress_interval);
  SweepOptions options;
  options.progress = [&progress](int k, int count) { progress.Update(k, count); };
  // A failed check of one value: a warning on standard error (the table stays a table).
  options.on_solution = [&sweep](double value, const SolveReport& s) {
    for (const std::string& w : s.certificate.FailureMessages()) {
      std::fprintf(stderr, "warning: %s = %.12g: %s\n", sweep.name.c_str(), value, w.c_str());
    }
  };
  const SweepTable table =
      SolveSweep(SceneLoader(args.scene), SceneOptionsFrom(args.scene), sweep, options);
  CheckFiniteTable(table.columns, table.rows, "the sweep table");
  Emit("", args.format == "json" ? DumpJson(SweepJson(table), "the sweep table") : SweepCsv(table));
  return args.strict && table.failed ? kExitCheckFailed : 0;
}

}  // namespace chasles::cli
