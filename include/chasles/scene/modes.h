#pragma once
/// @file
/// A scene's small motions (`chasles modes`, docs/modes.md): its operating point (a static
/// equilibrium found from the initial state, or the steady motion the initial state begins),
/// the linearisation and the modes, and sweeps of a parameter with the values where the
/// stability changes found by bisection. Errors come back at the scene entry they concern.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "chasles/analysis/instantaneous.h"
#include "chasles/analysis/modes.h"
#include "chasles/scene/scene.h"
#include "chasles/scene/solve.h"

namespace chasles {

struct SceneModes {
  /// Body names, Model order (for the operating point's state).
  std::vector<std::string> bodies;
  OperatingPoint operating_point;
  /// The modes (their linearisation inside, with the finite-difference check done).
  ModalAnalysis modes;
  /// The reactions at the operating point (chapter 8.2: what the supports exert there).
  InstantaneousSolution solution;
};

/// The scene's operating point and modes. Throws SceneError at the entry an error concerns.
SceneModes AnalyseSceneModes(const Scene& scene);

struct ModesSweep {
  /// The swept parameter and its SI unit ("" for a number).
  std::string parameter, unit;
  /// The grid's SI values and each point's modes.
  std::vector<double> values;
  std::vector<SceneModes> points;
  /// Where the stability changes, to 1e-12 of the span.
  std::vector<StabilityChange> changes;
  /// When the parameter is an angular speed (rad/s): the critical speeds, where a whirl
  /// frequency equals it (a rotor's Campbell diagram), to 1e-12 of the span.
  std::vector<CriticalSpeed> critical_speeds;
};

/// `spec` (one parameter) over its grid, each point loaded by `load` with `options` and the
/// parameter's value; the changes of stability between points narrowed by bisection (each
/// bisection step loads and analyses the scene again). Throws SceneError at the spec's source
/// for a bad spec, and at the scene entry for a point that cannot be analysed (naming the
/// parameter's value).
ModesSweep SweepSceneModes(const std::function<Scene(const SceneOptions&)>& load,
                           const SceneOptions& options, const SweepSpec& spec,
                           std::int64_t max_rows);

}  // namespace chasles
