#pragma once
/// @file
/// The instantaneous problem of a scene (what `chasles solve` reports, chapter 8.2-8.3): at the
/// scene's initial state, every body's acceleration, every constraint's reaction, the friction
/// rolling needs against mu_s, each contact point's mode and forces, the kinetic energy and
/// momenta, and the solve's checks of its own answer. A sweep (the analysis layer's SolveSweep)
/// repeats it over a range of one scene parameter, each value's definition made here. The report
/// types are the analysis layer's (chasles/analysis/solve_report.h); the report layer writes them
/// (chasles/report/solve_json.h).

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "chasles/analysis/solve.h"
#include "chasles/analysis/solve_report.h"
#include "chasles/analysis/sweep.h"
#include "chasles/scene/scene.h"

namespace chasles {

/// The scene's instantaneous problem for the analysis layer's SolveAtState: its Model and
/// initial state (BuildStudy; the solve settles it on the constraints, projected when
/// `project_initial: true`, each change a warning after the scene's own), its bodies' named
/// points, the rolling contacts'
/// mu_s, the contact point labels and the locator of the solve's errors. Errors, here or in
/// SolveAtState of it, are SceneErrors at the scene entry they concern (ThrowAtSceneEntry).
SolveDefinition MakeSolveDefinition(const Scene& scene);

/// A sweep of one scene parameter: COUNT values from START to STOP, both expressions with
/// units as in a scene file ("0 deg", "60 deg").
struct SweepSpec {
  std::string name, start, stop;
  int count = 0;
  /// Where the sweep was given, for errors (SceneError file and key), e.g. "command line" and
  /// "--sweep".
  std::string source = "sweep";
  std::string key = "sweep";
};

/// Reads NAME=START:STOP:COUNT (e.g. "theta=0 deg:60 deg:7"). Throws SceneError at
/// (`source`, `key`) for a malformed text or COUNT < 2.
SweepSpec ParseSweep(const std::string& text, const std::string& source = "sweep",
                     const std::string& key = "sweep");

/// The SI unit of a swept parameter of dimension `dim`, for its column: FormatUnit(dim), and
/// "rad" ("rad/s", ...) when the dimension can carry an angle and START or STOP is written
/// with an angle unit (rad, deg, rev, rpm, cps), e.g. 'theta=10 deg:50 deg:5' -> "rad".
std::string SweepParameterUnit(const SweepSpec& spec, const Dimension& dim);

/// Checks `spec` against the scene `load` reads with `options` (COUNT >= 2, a parameter of the
/// scene) and returns the parameter's SI unit (SweepParameterUnit), for SolveSweep. Throws
/// SceneError at the spec's source and key when the scene has no such parameter or COUNT < 2.
std::string SolveSweepUnit(const std::function<Scene(const SceneOptions&)>& load,
                           const SceneOptions& options, const SweepSpec& spec);

/// Value k of `spec` for the analysis layer's SolveSweep: the scene `load` reads with `options`
/// plus the override NAME = START + (STOP - START) k / (COUNT - 1) (so START and STOP keep
/// their units), its parameter's SI value and its solve definition (MakeSolveDefinition).
SolveSweepPoint MakeSolveSweepPoint(const std::function<Scene(const SceneOptions&)>& load,
                                    const SceneOptions& options, const SweepSpec& spec, int k);

}  // namespace chasles
