#pragma once
/// @file
/// A sweep split over several processes (`mpirun -np N chasles ... --sweep`, docs/sweeps.md):
/// each runs its SweepShare of the points, sends rank 0 a SweepPart (its rows, their warnings,
/// or the failure that stopped it) as bytes, and rank 0 puts the parts back in grid order, into
/// the very table the serial sweep makes. Pure C++: the transport is the caller's.

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "chasles/analysis/solve_report.h"
#include "chasles/scene/solve.h"

namespace chasles {

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

/// `share`'s rows of `table` (as SimulateSweep, MassSweep or SolveSweep left them) with their
/// warnings.
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
