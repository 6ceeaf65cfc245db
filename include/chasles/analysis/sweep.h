#pragma once
/// @file
/// Sweeps over a grid of parameter values (docs/sweeps.md): every combination of the values of
/// one or several parameters, each point computed by a function of the parameter values alone
/// (std::vector<double> -> row), run in parallel with the results in grid order and the same
/// for any number of threads, into one table of parameters and quantities. A point that fails
/// gives a row with the reason, never a crash or a silent NaN. A sweep split over several
/// processes (`mpirun -np N chasles ... --sweep`) runs a SweepShare of the points in each and
/// puts the parts back together, bit for bit the serial table (the share encoding below; the
/// transport is the caller's).
///
/// Nothing here knows what a point computes: a scene's sweeps (the scene layer reads their
/// specifications against a scene's parameters) and a Python function of the parameters run
/// alike.

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "chasles/analysis/solve_report.h"

namespace chasles {

/// The points of a sweep that one of several processes runs (a rank of `mpirun -np N chasles
/// ... --sweep`, docs/sweeps.md): point k when k % size == rank. Dealt out in turn, the points
/// of a grid whose cost grows along it spread evenly, and rank 0 always has point 0.
struct SweepShare {
  int rank = 0;
  int size = 1;
  bool Has(std::int64_t k) const { return k % size == rank; }
  /// How many of the points 0 .. total-1 are this share's.
  std::int64_t Count(std::int64_t total) const {
    return total > rank ? (total - rank + size - 1) / size : 0;
  }
  /// The i-th point of this share.
  std::int64_t Point(std::int64_t i) const { return rank + i * size; }
};

/// The combinations of the values of several parameters, the last varying fastest: point k
/// has index i_j of parameter j with k = ((i_0 n_1 + i_1) n_2 + i_2) ..., and parameter j's
/// value START_j + (STOP_j - START_j) i_j / (COUNT_j - 1).
struct ParameterGrid {
  /// Each parameter's name and SI unit ("" for a pure number), for the table's columns.
  std::vector<std::string> names, units;
  /// SI value of each parameter's START and STOP, and its number of values (>= 2).
  std::vector<double> start, stop;
  std::vector<int> counts;
  /// Number of points (the product of the counts; 1 for no parameter).
  std::int64_t size() const;
  /// The index of each parameter at point k.
  std::vector<int> Indices(std::int64_t k) const;
  /// The SI value of each parameter at point k.
  std::vector<double> Values(std::int64_t k) const;
  /// The point whose values are exactly `values` (as Values gave them); -1 when none is.
  std::int64_t PointOf(const std::vector<double>& values) const;
};

/// Checks a grid (names given, one START, STOP and COUNT per name, COUNT >= 2, finite ends)
/// and its number of points against `max_points`. Throws InputError naming what is wrong.
void CheckParameterGrid(const ParameterGrid& grid, std::int64_t max_points);

/// One point's row: its parameters' values, then its quantities (NaN for a quantity that could
/// not be had, every quantity when the point failed), and why values are missing ("" when
/// none is).
struct SweepRow {
  std::vector<double> values;
  std::string error;
};

/// What a point computes, from the values of the grid's parameters (in the grid's order).
/// Called from several threads at once when the sweep runs on several.
using SweepFunction = std::function<SweepRow(const std::vector<double>& values)>;

struct SweepRunOptions {
  /// Threads (< 1: the hardware's concurrency).
  int jobs = 0;
  /// Called with the number of points finished and the total, one call at a time.
  std::function<void(std::int64_t done, std::int64_t total)> progress;
  /// The points run here (the others' rows are left empty, with no values); `progress`
  /// counts this share's points.
  SweepShare share;
};

/// Calls `point` at every point of `grid` that is `options.share`'s, in parallel, and returns
/// the table: columns the parameters then `quantities` (with `units`), one row per point in
/// grid order (empty for the points of other shares), and each row's error. A point whose
/// function throws InputError has its parameters, NaN quantities and the message (on one line)
/// as its error; any other exception stops the sweep and is thrown again here.
SweepTable RunSweep(const ParameterGrid& grid, const std::vector<std::string>& quantities,
                    const std::vector<std::string>& units, const SweepFunction& point,
                    const SweepRunOptions& options = {});

/// `text` on one line (a CSV field, a JSON string): line breaks become "; ".
std::string OneLine(std::string text);

/// Calls run(k) for k = 0 .. count-1 on `jobs` threads (< 1: the hardware's concurrency),
/// each k once; `done` (may be empty) is called after each, one call at a time, with the
/// number finished. An exception thrown by run stops the others from starting and is thrown
/// again here once all threads have ended.
void RunParallel(std::int64_t count, int jobs, const std::function<void(std::int64_t k)>& run,
                 const std::function<void(std::int64_t done)>& done = {});

/// Warnings of a sweep's points (failed checks of a run or a solve), by point index.
using SweepWarnings = std::map<std::int64_t, std::vector<std::string>>;

/// One point's row as a process computed it.
struct SweepPoint {
  std::int64_t k = 0;
  std::vector<double> values;
  /// Why the point failed ("" when it did not; SweepTable::errors).
  std::string error;
  std::vector<std::string> warnings;
};

/// What one process sends rank 0.
struct SweepPart {
  /// A failure that stopped this process (bad input, exit code 2, ...): its exit code (0 for
  /// none) and message, and the point it stopped at (-1: before any point).
  int code = 0;
  std::string message;
  std::int64_t failed_at = -1;
  /// A check of a run failed somewhere in this share (--strict).
  bool check_failed = false;
  /// The share's points, in grid order.
  std::vector<SweepPoint> points;
};

/// `share`'s rows of `table` (as a sweep left them) with their warnings.
SweepPart TakeSweepPart(const SweepTable& table, const SweepShare& share,
                        const SweepWarnings& warnings);

/// The part as bytes (doubles bit for bit) and back. DecodeSweepPart throws InputError on bytes
/// that are not a whole part.
std::string EncodeSweepPart(const SweepPart& part);
SweepPart DecodeSweepPart(std::string_view bytes);

/// The failure the serial sweep would have stopped at: the part that failed at the earliest
/// point (before any point first), the lowest rank among equals; null when none failed.
const SweepPart* FirstFailure(const std::vector<SweepPart>& parts);

/// Puts every part's rows into `table` at their points (its errors too when it has them, and
/// each point's warnings into `warnings`, in grid order); for a solve sweep (no errors) the
/// table's warnings are remade from the points' in grid order. Throws std::logic_error unless
/// every row is given exactly once.
void MergeSweepParts(const std::vector<SweepPart>& parts, SweepTable* table,
                     SweepWarnings* warnings);

}  // namespace chasles
