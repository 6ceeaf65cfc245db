#include "chasles/scene/modes.h"

#include <cmath>

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/scene/scene_error.h"
#include "chasles/scene/study.h"
#include "chasles/scene/sweep.h"

namespace chasles {

SceneModes AnalyseSceneModes(const Scene& scene) {
  try {
    // The end time plays no part in small motions.
    const Study study = BuildStudy(scene, 1.0);
    const Model& model = *study.model;
    SceneModes out;
    for (int b = 0; b < model.num_bodies(); ++b) out.bodies.push_back(model.body(b).name());
    out.operating_point = FindOperatingPoint(model, study.initial);
    LinearizeOptions options;
    options.finite_difference_check = true;
    out.modes = AnalyseModes(model, out.operating_point, options);
    out.solution = SolveInstantaneous(model, out.operating_point.state);
    return out;
  } catch (const SceneError&) {
    throw;
  } catch (const InputError& e) {
    ThrowAtSceneEntry(scene, e);
  }
}

ModesSweep SweepSceneModes(const std::function<Scene(const SceneOptions&)>& load,
                           const SceneOptions& options, const SweepSpec& spec,
                           std::int64_t max_rows) {
  const Scene base = load(options);
  const SweepGrid grid = MakeSweepGrid(base, {spec}, max_rows);
  ModesSweep out;
  out.parameter = spec.name;
  out.unit = grid.parameters.units[0];
  const auto at = [&](double value) {
    SceneOptions o = options;
    o.parameter_overrides.emplace_back(spec.name, out.unit.empty()
                                                      ? fmt::format("{:.17g}", value)
                                                      : fmt::format("{:.17g} {}", value, out.unit));
    try {
      return AnalyseSceneModes(load(o));
    } catch (const SceneError& e) {
      throw SceneError(e.file(), e.line(), e.column(), e.key(),
                       fmt::format("at {} = {:.12g}{}: {}", spec.name, value,
                                   out.unit.empty() ? "" : " " + out.unit, e.message()));
    }
  };
  for (std::int64_t k = 0; k < grid.parameters.size(); ++k) {
    out.values.push_back(grid.parameters.Values(k)[0]);
    out.points.push_back(at(out.values.back()));
  }
  // The grid's points are analysed already: bisection loads the scene only between them.
  const auto analyse = [&](double value) {
    for (size_t k = 0; k < out.values.size(); ++k) {
      if (out.values[k] == value) return out.points[k].modes;
    }
    return at(value).modes;
  };
  out.changes = FindStabilityChanges(analyse, out.values);
  if (out.unit == "rad/s" || out.unit == "1/s") {
    out.critical_speeds = FindCriticalSpeeds(analyse, out.values);
  }
  return out;
}

}  // namespace chasles
