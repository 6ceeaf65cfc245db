// A scene's rotor balance (chasles/scene/balance.h): the options of `chasles balance` read as
// in the scene, and the definition for the analysis layer's AnalyseRotorBalance.

#include "chasles/scene/balance.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "chasles/analysis/whirl.h"
#include "chasles/error.h"
#include "chasles/scene/expression.h"
#include "chasles/scene/scene_error.h"
#include "chasles/scene/units.h"
#include "chasles/suggest.h"
#include "internal/definition_start.h"

namespace chasles {
namespace {

/// An option's quantity written as in the scene (its parameters and units known), checked
/// against `dim`; SceneError at the option otherwise.
double ReadQuantity(const Scene& scene, const std::string& text, const std::string& source,
                    const std::string& option, const Dimension& dim, const char* what) {
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
    throw SceneError(source, 0, 0, option, e.what());
  }
  if (!(q.dim == dim)) {
    throw SceneError(source, 0, 0, option,
                     fmt::format("'{}' is not {} (e.g. {})", text, what,
                                 dim == kLength ? "'12 cm'" : "'3000 rpm'"));
  }
  return q.value;
}

/// "A, B": the two planes' positions along the axis.
std::pair<double, double> ReadPlanes(const Scene& scene, const std::string& text,
                                     const std::string& source, const std::string& option) {
  const size_t comma = text.find(',');
  if (text.empty() || comma == std::string::npos ||
      text.find(',', comma + 1) != std::string::npos) {
    throw SceneError(source, 0, 0, option,
                     fmt::format("'{}' is not two positions along the axis 'A, B' "
                                 "(e.g. '-10 cm, 10 cm')",
                                 text));
  }
  return {ReadQuantity(scene, text.substr(0, comma), source, option, kLength, "a length"),
          ReadQuantity(scene, text.substr(comma + 1), source, option, kLength, "a length")};
}

/// 'A:B:N': N spins (2 to 1,000) from A to B, 0 <= A < B (angular speeds, e.g. '0 rpm:6000
/// rpm:31').
std::vector<double> ReadWhirlSpeeds(const Scene& scene, const std::string& text,
                                    const std::string& source, const std::string& option) {
  const size_t c1 = text.find(':'), c2 = c1 == std::string::npos ? c1 : text.find(':', c1 + 1);
  const auto bad = [&](const std::string& why) {
    return SceneError(source, 0, 0, option,
                      fmt::format("'{}' {}: give 'A:B:N', N spins from A to B (e.g. "
                                  "'0 rpm:6000 rpm:31')",
                                  text, why));
  };
  if (c2 == std::string::npos || text.find(':', c2 + 1) != std::string::npos) {
    throw bad("is not three fields");
  }
  const double a =
      ReadQuantity(scene, text.substr(0, c1), source, option, kRate, "an angular speed");
  const double b = ReadQuantity(scene, text.substr(c1 + 1, c2 - c1 - 1), source, option, kRate,
                                "an angular speed");
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
  return WhirlSpeedGrid(a, b, n);
}

}  // namespace

RotorBalanceDefinition MakeBalanceDefinition(const Scene& scene, const BalanceOptions& options) {
  const auto option = [&](const char* name) { return options.option_prefix + name; };
  const std::string& source = options.source;
  RotorBalanceDefinition def;
  def.axis.a_W = ReadPointOption(scene, options.axis, option("axis"));
  def.axis.p_WO = ReadPointOption(scene, options.through, option("through"));
  std::tie(def.axis.z_A, def.axis.z_B) =
      ReadPlanes(scene, options.planes, source, option("planes"));
  def.axis.radius =
      ReadQuantity(scene, options.radius, source, option("radius"), kLength, "a length");
  if (!options.speed.empty()) {
    def.speed =
        ReadQuantity(scene, options.speed, source, option("speed"), kRate, "an angular speed");
  }
  if (options.grade < 0.0 || !std::isfinite(options.grade)) {
    throw SceneError(source, 0, 0, option("grade"),
                     "the balance grade G is a speed in mm/s, 0 or more (e.g. 6.3)");
  }
  if (options.grade > 0.0 && options.speed.empty()) {
    throw SceneError(
        source, 0, 0, option("grade"),
        fmt::format("a balance grade needs the service speed: give {}", option("speed")));
  }
  if (options.grade > 0.0) def.grade = options.grade;
  std::vector<std::string> names;
  for (const SceneBody& b : scene.bodies) names.push_back(b.name);
  if (std::find(names.begin(), names.end(), options.body) == names.end()) {
    throw SceneError(source, 0, 0, option("body"),
                     fmt::format("no body named '{}'{}; the bodies are: {}", options.body,
                                 DidYouMean(options.body, names), fmt::join(names, ", ")));
  }
  scene_internal::StartDefinition(scene, def);
  def.rotor = def.model->FindBody(options.body);
  if (!options.whirl.empty()) {
    if (!HeldByBearing(*def.model, def.rotor)) {
      throw SceneError(source, 0, 0, option("whirl"),
                       fmt::format("no bearing element holds '{}': whirl needs the rotor on "
                                   "elastic bearings (forces, type bearing)",
                                   options.body));
    }
    def.whirl_speeds = ReadWhirlSpeeds(scene, options.whirl, source, option("whirl"));
  }
  return def;
}

}  // namespace chasles
