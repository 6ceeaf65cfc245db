// chasles balance: a rotor's static and couple unbalance, the two correction masses in its two
// planes, what is left after them, the bearing forces at speed (the chapter's Euler equations
// about a fixed axis) and the ISO 21940-11 permissible residual unbalance for a balance grade
// (docs/modes.md, "Rotors"; analysis/balance.h has the equations).

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "chasles/analysis/balance.h"
#include "chasles/analysis/initial_state.h"
#include "chasles/analysis/whirl.h"
#include "chasles/error.h"
#include "chasles/files/output_set.h"
#include "chasles/model/bearing.h"
#include "chasles/report/balance_text.h"
#include "chasles/report/json_report.h"
#include "chasles/scene/expression.h"
#include "chasles/scene/scene.h"
#include "chasles/scene/scene_error.h"
#include "chasles/scene/study.h"
#include "chasles/suggest.h"
#include "commands.h"
#include "scene_args.h"
#include "whirl_report.h"

namespace chasles::cli {
namespace {

/// A command-line quantity written as in the scene (its parameters and units known), checked
/// against `dim`; SceneError at the option otherwise.
double ReadQuantity(const Scene& scene, const std::string& text, const std::string& option,
                    const Dimension& dim, const char* what) {
  const SymbolResolver resolver = [&](std::string_view name) -> std::optional<Symbol> {
    for (const auto& [n, q] : scene.parameters) {
      if (n == name) return Symbol::Constant(q);
    }
    return std::nullopt;
  };
  Quantity q;
  try {
    q = EvaluateQuantity(text, resolver);
  } catch (const InputError& e) {
    throw SceneError("command line", 0, 0, option, e.what());
  }
  if (!(q.dim == dim)) {
    throw SceneError("command line", 0, 0, option,
                     fmt::format("'{}' is not {} (e.g. {})", text, what,
                                 dim == kLength ? "'12 cm'" : "'3000 rpm'"));
  }
  return q.value;
}

/// "A, B": the two planes' positions along the axis.
std::pair<double, double> ReadPlanes(const Scene& scene, const std::string& text) {
  const size_t comma = text.find(',');
  if (text.empty() || comma == std::string::npos ||
      text.find(',', comma + 1) != std::string::npos) {
    throw SceneError("command line", 0, 0, "--planes",
                     fmt::format("'{}' is not two positions along the axis 'A, B' "
                                 "(e.g. '-10 cm, 10 cm')",
                                 text));
  }
  return {ReadQuantity(scene, text.substr(0, comma), "--planes", kLength, "a length"),
          ReadQuantity(scene, text.substr(comma + 1), "--planes", kLength, "a length")};
}

/// 'A:B:N': N spins (2 to 1,000) from A to B, 0 <= A < B (angular speeds, e.g. '0 rpm:6000
/// rpm:31').
std::vector<double> ReadWhirlSpeeds(const Scene& scene, const std::string& text) {
  const size_t c1 = text.find(':'), c2 = c1 == std::string::npos ? c1 : text.find(':', c1 + 1);
  const auto bad = [&](const std::string& why) {
    return SceneError("command line", 0, 0, "--whirl",
                      fmt::format("'{}' {}: give 'A:B:N', N spins from A to B (e.g. "
                                  "'0 rpm:6000 rpm:31')",
                                  text, why));
  };
  if (c2 == std::string::npos || text.find(':', c2 + 1) != std::string::npos) {
    throw bad("is not three fields");
  }
  const double a = ReadQuantity(scene, text.substr(0, c1), "--whirl", kRate, "an angular speed");
  const double b =
      ReadQuantity(scene, text.substr(c1 + 1, c2 - c1 - 1), "--whirl", kRate, "an angular speed");
  const std::string count = text.substr(c2 + 1);
  const auto first = count.find_first_not_of(' '), last = count.find_last_not_of(' ');
  const std::string digits =
      first == std::string::npos ? "" : count.substr(first, last - first + 1);
  if (digits.empty() || digits.size() > 4 ||
      digits.find_first_not_of("0123456789") != std::string::npos) {
    throw bad("has no whole number of points N");
  }
  const int n = std::stoi(digits);
  if (n < 2 || n > 1000) throw bad("needs 2 to 1,000 points");
  if (!(a >= 0.0) || !(b > a)) throw bad("needs 0 <= A < B");
  std::vector<double> out;
  for (int i = 0; i < n; ++i) out.push_back(i + 1 == n ? b : a + (b - a) * i / (n - 1));
  return out;
}

/// The whirl rows when the scene holds the rotor on elastic bearings (else none): over --whirl,
/// else 0 to twice --speed, else 0 to twice the highest whirl frequency at rest (21 spins).
std::optional<WhirlMap> CalcRotorWhirl(const Scene& scene, const Study& study, BodyIndex rotor,
                                       const Vec3& a_W, const BalanceArgs& args, double speed) {
  bool held = false;
  for (int i = 0; i < study.model->num_force_elements(); ++i) {
    const auto* bearing = dynamic_cast<const Bearing*>(&study.model->force_element(i));
    held = held || (bearing != nullptr && bearing->body() == rotor);
  }
  if (!held) {
    if (!args.whirl.empty()) {
      throw SceneError("command line", 0, 0, "--whirl",
                       fmt::format("no bearing element holds '{}': whirl needs the rotor on "
                                   "elastic bearings (forces, type bearing)",
                                   args.body));
    }
    return std::nullopt;
  }
  std::vector<double> speeds;
  if (!args.whirl.empty()) {
    speeds = ReadWhirlSpeeds(scene, args.whirl);
  } else {
    double top = std::isfinite(speed) ? speed : 0.0;
    if (!(top > 0.0)) {
      for (const WhirlMode& m :
           CalcWhirl(*study.model, study.initial, rotor, a_W, {0.0}).points[0].modes) {
        top = std::max(top, std::abs(m.eigenvalue.imag()));
      }
    }
    if (!(top > 0.0)) return std::nullopt;  // nothing whirls: no rows
    for (int i = 0; i <= 20; ++i) speeds.push_back(2.0 * top * i / 20.0);
  }
  return CalcWhirl(*study.model, study.initial, rotor, a_W, speeds);
}

nlohmann::json Vec(const Vec3& v) {
  return {v.x(), v.y(), v.z()};
}

nlohmann::json ReportJson(const std::string& body, const BalanceReport& r, const RotorAxis& axis) {
  nlohmann::json corrections = nlohmann::json::array();
  const char* names[2] = {"A", "B"};
  const double z[2] = {axis.z_A, axis.z_B};
  for (int k = 0; k < 2; ++k) {
    const BalanceCorrection& c = r.corrections[static_cast<size_t>(k)];
    corrections.push_back({{"plane", names[k]},
                           {"position", z[k]},
                           {"mass", c.mass},
                           {"radius", c.radius},
                           {"angle", c.angle},
                           {"point", Vec(c.p_W)}});
  }
  nlohmann::json j = {
      {"body", body},
      {"mass", r.mass},
      {"static_unbalance", r.static_unbalance_W.norm()},
      {"static_unbalance_vector", Vec(r.static_unbalance_W)},
      {"couple_unbalance", r.couple_unbalance_W.norm()},
      {"couple_unbalance_vector", Vec(r.couple_unbalance_W)},
      {"reference_directions", {Vec(r.e1_W), Vec(r.e2_W)}},
      {"corrections", corrections},
      {"residual_after", {{"static", r.residual_static}, {"couple", r.residual_couple}}},
      {"permissible", nullptr},
      {"bearing_reactions", nullptr}};
  if (std::isfinite(r.speed)) {
    j["speed"] = r.speed;
    j["bearing_reactions"] = {
        {"before", {{"A", Vec(r.bearing_forces_W[0])}, {"B", Vec(r.bearing_forces_W[1])}}},
        {"after",
         {{"A", Vec(r.bearing_forces_after_W[0])}, {"B", Vec(r.bearing_forces_after_W[1])}}}};
  }
  if (std::isfinite(r.permissible)) {
    j["permissible"] = {{"grade", r.grade},
                        {"total", r.permissible},
                        {"A", r.permissible_per_plane[0]},
                        {"B", r.permissible_per_plane[1]},
                        {"met", r.static_unbalance_W.norm() <= r.permissible}};
  }
  return j;
}

}  // namespace

CLI::App* AddBalanceCommand(CLI::App& app, BalanceArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "balance",
      "A rotor's static and couple unbalance about its spin axis, the two-plane correction "
      "masses, the bearing forces at speed and the ISO 21940-11 permissible residual "
      "unbalance");
  AddSceneArgs(*cmd, args.scene);
  cmd->add_option("--body", args.body, "The rotor: a body of the scene")->required();
  cmd->add_option("--axis", args.axis, "Spin axis in W, as in a scene: '[0, 0, 1]'");
  cmd->add_option("--through", args.through, "A point of the axis in W: '[0, 0, 0]'");
  cmd->add_option("--planes", args.planes,
                  "The two bearing and correction planes' positions along the axis from "
                  "--through: 'A, B', e.g. '-10 cm, 10 cm'")
      ->required();
  cmd->add_option("--radius", args.radius, "Radius of the correction masses, e.g. '8 cm'")
      ->required();
  cmd->add_option("--speed", args.speed,
                  "Spin for the bearing forces and the grade, e.g. '3000 rpm'");
  cmd->add_option("--grade", args.grade, "ISO 21940-11 balance grade G in mm/s (e.g. 6.3)");
  cmd->add_option("--whirl", args.whirl,
                  "With the rotor on elastic bearings: the spins of the whirl rows, 'A:B:N' "
                  "(default: 0 to twice --speed, 21 spins)");
  cmd->add_option("--format", args.format, "text or json")->check(CLI::IsMember({"text", "json"}));
  cmd->add_option("-o,--out", args.output, "Write the report here (default: standard output)");
  cmd->footer(
      "Example:\n"
      "  chasles balance examples/unbalanced-disk-rotor.yaml --body rotor --axis '[0, 0, 1]' "
      "--planes '-25 cm, 25 cm' --radius '15 cm' --speed '3000 rpm' --grade 6.3\n"
      "Theory: docs/modes.md, section Rotors. Exit codes: 0 success, 2 bad input.");
  return cmd;
}

int RunBalance(const BalanceArgs& args) {
  if (args.scene.scene.empty()) {
    throw InputError("chasles balance needs a scene file (chasles balance --help)");
  }
  OutputSet out;  // the target is checked before the scene is read
  out.Expect(ReportTarget(args.output), "-o");
  const Scene scene = LoadScene(args.scene);
  RotorAxis axis;
  axis.a_W = ReadPointOption(scene, args.axis, "--axis");
  axis.p_WO = ReadPointOption(scene, args.through, "--through");
  std::tie(axis.z_A, axis.z_B) = ReadPlanes(scene, args.planes);
  axis.radius = ReadQuantity(scene, args.radius, "--radius", kLength, "a length");
  const double speed = args.speed.empty()
                           ? std::numeric_limits<double>::quiet_NaN()
                           : ReadQuantity(scene, args.speed, "--speed", kRate, "an angular speed");
  if (args.grade < 0.0 || !std::isfinite(args.grade)) {
    throw SceneError("command line", 0, 0, "--grade",
                     "the balance grade G is a speed in mm/s, 0 or more (e.g. 6.3)");
  }
  if (args.grade > 0.0 && args.speed.empty()) {
    throw SceneError("command line", 0, 0, "--grade",
                     "a balance grade needs the service speed: give --speed");
  }
  std::vector<std::string> names;
  for (const SceneBody& b : scene.bodies) names.push_back(b.name);
  if (std::find(names.begin(), names.end(), args.body) == names.end()) {
    throw SceneError("command line", 0, 0, "--body",
                     fmt::format("no body named '{}'{}; the bodies are: {}", args.body,
                                 DidYouMean(args.body, names), fmt::join(names, ", ")));
  }
  BalanceReport r;
  std::optional<WhirlMap> whirl;
  try {
    Study study = BuildStudy(scene, 1.0);
    // On the constraints as a run starts (its warnings are the run's, not the balance's).
    std::vector<std::string> warnings;
    study.initial = SettleInitialState(*study.model, study.initial, study.settling, warnings);
    const Model& model = *study.model;
    const BodyIndex b = model.FindBody(args.body);
    const BodyState& s = study.initial.bodies[static_cast<size_t>(b)];
    const Mat3 R = s.q_WB.normalized().toRotationMatrix();
    r = CalcBalance(model.body(b).mass(), s.p_WBcm, R * model.body(b).I_BBcm_B() * R.transpose(),
                    axis, speed, args.grade > 0.0 ? args.grade : std::nan(""));
    whirl = CalcRotorWhirl(scene, study, b, axis.a_W, args, speed);
  } catch (const SceneError&) {
    throw;
  } catch (const InputError& e) {
    ThrowAtSceneEntry(scene, e);
  }
  nlohmann::json j = ReportJson(args.body, r, axis);
  j["whirl"] = whirl ? WhirlJson(*whirl) : nlohmann::json(nullptr);
  std::string report;
  if (args.format == "json") {
    report = DumpJson(j, "the balance report");
  } else {
    CheckFiniteJson(j, "the balance report");
    report = BalanceText(args.body, r, axis) + (whirl ? WhirlText(*whirl) : "");
  }
  out.Add(ReportTarget(args.output), std::move(report));
  out.Commit();
  return 0;
}

}  // namespace chasles::cli
