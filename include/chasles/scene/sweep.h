#pragma once
/// @file
/// Sweeps of a scene's parameters over a grid, for `chasles simulate --sweep` and `chasles
/// mass --sweep` (docs/sweeps.md): the specifications read against a scene's parameters, the
/// scene's options at a point, the quantities of a run, and each point's StudyDefinition for
/// the analysis layer's SimulateSweep (chasles/analysis/study_sweep.h), which runs them. The
/// grid, the thread pool and the table are the analysis layer's generic sweep
/// (chasles/analysis/sweep.h): each point is loaded on its own, and a point that fails gives a
/// row with the reason, never a crash or a silent NaN.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "chasles/analysis/solve_report.h"
#include "chasles/analysis/study.h"
#include "chasles/analysis/study_sweep.h"
#include "chasles/analysis/sweep.h"
#include "chasles/scene/scene.h"
#include "chasles/scene/solve.h"
#include "chasles/scene/study.h"

namespace chasles {

/// A grid of a scene's parameters: the specifications as given, and the grid of their SI
/// values (names, SI units: "" for pure numbers, START and STOP, counts).
struct SweepGrid {
  std::vector<SweepSpec> specs;
  ParameterGrid parameters;
  /// `base` with one override per parameter for the point of `values` (a point of the grid):
  /// the value as the expression (START) + ((STOP) - (START)) * i / (COUNT - 1), so START and
  /// STOP keep their units. Throws std::logic_error for values that are not a point of it.
  SceneOptions PointOptions(const SceneOptions& base, const std::vector<double>& values) const;
};

/// Checks the specs against `scene` (each names one of its parameters, once; START and STOP
/// are expressions of its parameters with the parameter's dimension) and the grid's number of
/// points against `max_points` (--max-runs). Throws SceneError at each spec's source and key.
SweepGrid MakeSweepGrid(const Scene& scene, const std::vector<SweepSpec>& specs,
                        std::int64_t max_points);

/// Reads final(COLUMN), max(COLUMN), min(COLUMN), event(NAME), event(NAME, k),
/// event(NAME, k) - event(NAME2, k2) or t_end. Throws SceneError at (`source`, `key`) for
/// anything else.
SweepQuantity ParseSweepQuantity(const std::string& text, const std::string& source = "sweep",
                                 const std::string& key = "quantity");

struct StudySweepOptions {
  /// End time and limits of each run (its `progress` is not used).
  StudyOptions study;
  /// Run columns replacing the scene's output columns (--columns); empty: the scene's. The
  /// quantities' columns are added to them.
  std::vector<std::string> columns;
  /// Called (from the thread that ran it, possibly several at once) with each point's index,
  /// its scene and its result, e.g. to write the run's own files. An exception it throws fails
  /// that point's row.
  std::function<void(std::int64_t k, const Scene& scene, const StudyResult& r)> on_run;
};

/// A scene's sweep of runs, checked and ready for the analysis layer's SimulateSweep.
struct SceneStudySweep {
  SweepGrid grid;
  /// The quantities' SI units.
  std::vector<std::string> units;
  /// Point `values` of the grid: the scene loaded at it (SweepGrid::PointOptions), its
  /// parameters' values as read, and its StudyDefinition with the sweep's columns and options.
  /// Throws InputError (a SceneError) when the scene fails to load or to define its run there.
  std::function<StudySweepPoint(const std::vector<double>& values)> point;
};

/// The sweep of runs of the scene `load` reads with `options` over the grid of `specs`,
/// tabulating `quantities`. Unknown parameters, columns and events, and a grid of more than
/// `max_points`, are SceneErrors here, before any run.
SceneStudySweep MakeStudySweep(const std::function<Scene(const SceneOptions&)>& load,
                               const SceneOptions& options, const std::vector<SweepSpec>& specs,
                               const std::vector<SweepQuantity>& quantities,
                               const StudySweepOptions& sweep_options, std::int64_t max_points);

/// The quantities a mass sweep can tabulate per body, named as in the mass JSON report:
/// mass, volume, surface_area, center_of_mass_x/y/z, Ixx Iyy Izz Ixy Ixz Iyz (the central
/// inertia matrix, "inertia_about_center_of_mass"), I1 I2 I3 (principal moments, ascending),
/// k1 k2 k3 (radii of gyration about the principal axes) and kx ky kz (about the body axes).
std::vector<std::string> MassSweepQuantityNames();

/// The mass properties of every point of the grid of `specs`: each quantity is NAME for a scene
/// of one body or BODY.NAME (MassSweepQuantityNames). Rows and errors as in a sweep of runs
/// (SimulateSweep).
SweepTable MassSweep(const std::function<Scene(const SceneOptions&)>& load,
                     const SceneOptions& options, const std::vector<SweepSpec>& specs,
                     const std::vector<std::string>& quantities, int jobs,
                     const std::function<void(std::int64_t done, std::int64_t total)>& progress,
                     std::int64_t max_points, const SweepShare& share = {});

}  // namespace chasles
