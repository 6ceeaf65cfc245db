// The instantaneous problem of a scene and its sweep (chasles/scene/solve.h).

#include "chasles/scene/solve.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/model/model.h"
#include "chasles/scene/scene_error.h"
#include "chasles/scene/study.h"
#include "chasles/suggest.h"
#include "internal/definition_start.h"

namespace chasles {

SolveDefinition MakeSolveDefinition(const Scene& scene) {
  SolveDefinition def;
  const Study study = scene_internal::StartDefinition(scene, def);
  def.planar = scene.planar;
  // The scene's own warnings (version-1 spellings, mesh repairs) come first, then a string
  // modelled the other way round; the solve adds the initial values its projection changes
  // (`project_initial: true`).
  def.warnings = scene.warnings;
  def.warnings.insert(def.warnings.end(), study.warnings.begin(), study.warnings.end());
  // A scene body is Model body b, frames alike: BuildStudy starts from the identity map.
  for (const SceneBody& b : scene.bodies) {
    std::vector<NamedBodyPoint>& points = def.points.emplace_back();
    for (const ScenePoint& p : b.points) points.push_back({p.name, p.p_BoP_B});
  }
  // A planar scene's plane constraints follow its own in Model order and are not reported.
  const SceneConstraints& c = scene.dynamics.constraints;
  def.mu_s.assign(c.names().size(), std::numeric_limits<double>::quiet_NaN());
  for (size_t i = 0; i < c.rolling.size(); ++i) def.mu_s[c.joints.size() + i] = c.rolling[i].mu_s;
  def.contact_point_labels = scene.dynamics.contacts.point_labels();
  return def;
}

std::string SweepParameterUnit(const SweepSpec& spec, const Dimension& dim) {
  // An identifier of START or STOP that names an angle unit marks the parameter as an angle
  // (the Dimension alone cannot: an angle is a pure number).
  bool angle = false;
  for (const std::string* text : {&spec.start, &spec.stop}) {
    std::string word;
    for (size_t i = 0; i <= text->size(); ++i) {
      const char c = i < text->size() ? (*text)[i] : ' ';
      if (std::isalnum(static_cast<unsigned char>(c)) || c == '_') {
        word += c;
        continue;
      }
      angle = angle || word == "rad" || word == "deg" || word == "rev" || word == "rpm" ||
              word == "cps";
      word.clear();
    }
  }
  return UnitSystem().FormatUnit(dim, angle ? Angular::kYes : Angular::kNo);
}

SweepSpec ParseSweep(const std::string& text, const std::string& source, const std::string& key) {
  const auto fail = [&](const std::string& why) { throw SceneError(source, 0, 0, key, why); };
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) {
    fail("expected NAME=START:STOP:COUNT, e.g. --sweep 'theta=0 deg:60 deg:7', got '" + text + "'");
  }
  SweepSpec s;
  s.source = source;
  s.key = key;
  s.name = text.substr(0, eq);
  const std::string rest = text.substr(eq + 1);
  const auto c1 = rest.find(':');
  const auto c2 = c1 == std::string::npos ? c1 : rest.find(':', c1 + 1);
  if (c2 == std::string::npos || rest.find(':', c2 + 1) != std::string::npos) {
    fail("expected NAME=START:STOP:COUNT (three fields after '='), got '" + text + "'");
  }
  s.start = rest.substr(0, c1);
  s.stop = rest.substr(c1 + 1, c2 - c1 - 1);
  const std::string count = rest.substr(c2 + 1);
  try {
    size_t used = 0;
    s.count = std::stoi(count, &used);
    if (used != count.size()) s.count = 0;
  } catch (const std::exception&) {
    s.count = 0;
  }
  if (s.count < 2) fail("COUNT must be a whole number >= 2, got '" + count + "'");
  return s;
}

std::string SolveSweepUnit(const std::function<Scene(const SceneOptions&)>& load,
                           const SceneOptions& options, const SweepSpec& spec) {
  if (spec.count < 2) {
    throw SceneError(spec.source, 0, 0, spec.key,
                     fmt::format("COUNT must be a whole number >= 2, got {}", spec.count));
  }
  const Scene scene = load(options);
  std::vector<std::string> known;
  for (const auto& [n, q] : scene.parameters) {
    known.push_back(n);
    if (n == spec.name) return SweepParameterUnit(spec, q.dim);
  }
  throw SceneError(spec.source, 0, 0, spec.key,
                   fmt::format("the scene has no parameter '{}'{}; parameters: {}", spec.name,
                               DidYouMean(spec.name, known), fmt::join(known, ", ")));
}

SolveSweepPoint MakeSolveSweepPoint(const std::function<Scene(const SceneOptions&)>& load,
                                    const SceneOptions& options, const SweepSpec& spec, int k) {
  // The k-th value as an expression, so START and STOP keep their units.
  SceneOptions o = options;
  o.parameter_overrides.emplace_back(
      spec.name, fmt::format("({}) + (({}) - ({})) * {} / {}", spec.start, spec.stop, spec.start, k,
                             spec.count - 1));
  const Scene scene = load(o);
  SolveSweepPoint point;
  point.value = std::numeric_limits<double>::quiet_NaN();
  for (const auto& [n, q] : scene.parameters) {
    if (n == spec.name) point.value = q.value;
  }
  point.definition = MakeSolveDefinition(scene);
  return point;
}

}  // namespace chasles
