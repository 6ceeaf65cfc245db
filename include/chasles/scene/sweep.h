#pragma once
/// @file
/// Sweeps of a scene's parameters over a grid, for `chasles simulate --sweep` and `chasles
/// mass --sweep` (docs/sweeps.md): the specifications read against a scene's parameters, the
/// scene's options at a point, and the quantities of a run. The grid, the thread pool and the
/// table are the analysis layer's generic sweep (chasles/analysis/sweep.h): each point is
/// loaded and run on its own, and a point whose run fails gives a row with the reason, never a
/// crash or a silent NaN.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "chasles/analysis/solve_report.h"
#include "chasles/analysis/study.h"
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

/// What a simulate sweep tabulates of each run (`--quantity`).
struct SweepQuantity {
  enum class Kind { kFinal, kMax, kMin, kEvent, kEventDifference, kTEnd };
  Kind kind = Kind::kTEnd;
  /// As written, white space around ( ) , - removed ("event(bottom)-event(release)"): the
  /// table's column name.
  std::string text;
  /// The run column of final/max/min.
  std::string column;
  /// event(NAME, k): the k-th firing (from 1) of NAME; a difference subtracts event(NAME2, k2).
  std::string event, event2;
  int k = 1, k2 = 1;
};

/// Reads final(COLUMN), max(COLUMN), min(COLUMN), event(NAME), event(NAME, k),
/// event(NAME, k) - event(NAME2, k2) or t_end. Throws SceneError at (`source`, `key`) for
/// anything else.
SweepQuantity ParseSweepQuantity(const std::string& text, const std::string& source = "sweep",
                                 const std::string& key = "quantity");

/// The quantity's value in run `r` [SI]. Throws InputError when the run has no such column or
/// the event did not fire that many times.
double SweepQuantityValue(const StudyResult& r, const SweepQuantity& q);

struct SimulateSweepOptions {
  /// End time and limits of each run (its `progress` is not used).
  StudyOptions study;
  /// Run columns replacing the scene's output columns (--columns); empty: the scene's. The
  /// quantities' columns are added to them.
  std::vector<std::string> columns;
  /// Threads (< 1: the hardware's concurrency).
  int jobs = 0;
  /// Called with the number of runs finished and the total, one call at a time.
  std::function<void(std::int64_t done, std::int64_t total)> progress;
  /// Called (from the thread that ran it, possibly several at once) with each point's index,
  /// its scene and its result, e.g. to write the run's own files. An exception it throws fails
  /// that point's row.
  std::function<void(std::int64_t k, const Scene& scene, const StudyResult& r)> on_run;
  /// The points run here (the others' rows are left empty, with no values); `progress`
  /// counts this share's runs.
  SweepShare share;
};

/// Runs the scene at every point of the grid of `specs` and tabulates `quantities`: columns
/// the parameters then the quantities (their text as the name), one row per point in grid
/// order. A point whose scene fails to load or whose run fails (bad input at that point, a
/// limit reached) has its parameters, NaN values and the reason in SweepTable::errors; a
/// quantity its run cannot give (an event that did not fire as often as asked) is NaN alone,
/// the others computed, with its reason in SweepTable::errors. Unknown parameters, columns and
/// events are SceneErrors before any run.
SweepTable SimulateSweep(const std::function<Scene(const SceneOptions&)>& load,
                         const SceneOptions& options, const std::vector<SweepSpec>& specs,
                         const std::vector<SweepQuantity>& quantities,
                         const SimulateSweepOptions& sweep_options, std::int64_t max_points);

/// The quantities a mass sweep can tabulate per body, named as in the mass JSON report:
/// mass, volume, surface_area, center_of_mass_x/y/z, Ixx Iyy Izz Ixy Ixz Iyz (the central
/// inertia matrix, "inertia_about_center_of_mass"), I1 I2 I3 (principal moments, ascending),
/// k1 k2 k3 (radii of gyration about the principal axes) and kx ky kz (about the body axes).
std::vector<std::string> MassSweepQuantityNames();

/// The mass properties of every point of the grid of `specs`: each quantity is NAME for a scene
/// of one body or BODY.NAME (MassSweepQuantityNames). Rows and errors as SimulateSweep.
SweepTable MassSweep(const std::function<Scene(const SceneOptions&)>& load,
                     const SceneOptions& options, const std::vector<SweepSpec>& specs,
                     const std::vector<std::string>& quantities, int jobs,
                     const std::function<void(std::int64_t done, std::int64_t total)>& progress,
                     std::int64_t max_points, const SweepShare& share = {});

}  // namespace chasles
