#pragma once
/// @file
/// A sweep of runs (`chasles simulate --sweep`, docs/sweeps.md): at every point of a grid of
/// parameters a study is run (RunStudy) and quantities of its result are tabulated. Each
/// point's StudyDefinition comes from a function of the parameters' values alone (the scene
/// layer loads its scene at the point; a program builds its Model in code), so the sweep is the
/// generic RunSweep's: in parallel, in grid order, the same for any number of threads, and a
/// point whose run fails gives a row with the reason, never a crash or a silent NaN.

#include <functional>
#include <string>
#include <vector>

#include "chasles/analysis/study.h"
#include "chasles/analysis/sweep.h"

namespace chasles {

/// What a sweep of runs tabulates of each run (`--quantity`).
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

/// The quantity's value in run `r` [SI]: the last row's, the largest or smallest over the rows
/// and the events' states, an event's time, a difference of two, or the end time. Throws
/// InputError when the run has no such column or the event did not fire that many times.
double SweepQuantityValue(const StudyResult& r, const SweepQuantity& q);

/// One point of a sweep of runs.
struct StudySweepPoint {
  /// The parameters' values the definition was made with [SI] (a scene's as it read them),
  /// the row's first values.
  std::vector<double> values;
  StudyDefinition definition;
  /// Why the point has no run (its definition could not be made at `values`): the row's
  /// quantities are NaN and this is its reason; "" when it has one.
  std::string error;
  /// Called (from the thread that ran it, possibly several at once) with the run's result,
  /// e.g. to write the run's own files; null: nothing. An exception it throws fails the row.
  std::function<void(const StudyResult& r)> on_run;
};

/// Runs `point(values)`'s definition at every point of `grid` (`options.share`'s) and
/// tabulates `quantities` (with their SI `units`): columns the parameters then the quantities
/// (their text as the name), one row per point in grid order. A point whose definition cannot
/// be made (`point` throws an InputError: the grid's values are the row's; or it gives an
/// error) or whose run fails (an InputError: bad input at that point, a limit reached) has its
/// parameters, NaN values and the reason in SweepTable::errors; a quantity its run cannot give
/// (an event that did not fire as often as asked) is NaN alone, the others computed, with its
/// reason in SweepTable::errors.
SweepTable SimulateSweep(
    const ParameterGrid& grid, const std::vector<SweepQuantity>& quantities,
    const std::vector<std::string>& units,
    const std::function<StudySweepPoint(const std::vector<double>& values)>& point,
    const SweepRunOptions& options = {});

}  // namespace chasles
