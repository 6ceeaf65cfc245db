// Sweeps of runs over a grid of parameters (chasles/analysis/study_sweep.h).

#include "chasles/analysis/study_sweep.h"

#include <algorithm>
#include <limits>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "chasles/error.h"

namespace chasles {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The time of the k-th firing of event `name` in `r`.
double EventTime(const StudyResult& r, const std::string& name, int k) {
  int seen = 0;
  for (const StudyEvent& e : r.events) {
    if (e.name == name && ++seen == k) return e.t;
  }
  throw InputError(
      fmt::format("event '{}' fired {} time{} by the run's end at t = {:.9g} s; "
                  "event({}, {}) needs {}",
                  name, seen, seen == 1 ? "" : "s", r.t_end, name, k, k));
}

}  // namespace

double SweepQuantityValue(const StudyResult& r, const SweepQuantity& q) {
  using Kind = SweepQuantity::Kind;
  switch (q.kind) {
    case Kind::kTEnd:
      return r.t_end;
    case Kind::kEvent:
      return EventTime(r, q.event, q.k);
    case Kind::kEventDifference:
      return EventTime(r, q.event, q.k) - EventTime(r, q.event2, q.k2);
    case Kind::kFinal:
    case Kind::kMax:
    case Kind::kMin:
      break;
  }
  const auto c = std::find(r.columns.begin(), r.columns.end(), q.column);
  if (c == r.columns.end()) throw InputError(fmt::format("the run has no column '{}'", q.column));
  const auto i = static_cast<size_t>(c - r.columns.begin());
  if (r.rows.empty()) throw InputError("the run recorded no rows");
  if (q.kind == Kind::kFinal) return r.rows.back()[i];
  // Extremes over the samples and the events' states (an event may fall between samples).
  double v = r.rows.front()[i];
  const auto take = [&](double x) { v = q.kind == Kind::kMax ? std::max(v, x) : std::min(v, x); };
  for (const auto& row : r.rows) take(row[i]);
  for (const StudyEvent& e : r.events) {
    if (i < e.row.size()) take(e.row[i]);
  }
  return v;
}

SweepTable SimulateSweep(
    const ParameterGrid& grid, const std::vector<SweepQuantity>& quantities,
    const std::vector<std::string>& units,
    const std::function<StudySweepPoint(const std::vector<double>& values)>& point,
    const SweepRunOptions& options) {
  std::vector<std::string> names;
  for (const SweepQuantity& q : quantities) names.push_back(q.text);
  const SweepFunction row_at = [&](const std::vector<double>& values) {
    SweepRow row;
    row.values = values;
    try {
      const StudySweepPoint p = point(values);
      row.values = p.values;
      if (!p.error.empty()) throw InputError(p.error);
      const StudyResult r = RunStudy(p.definition);
      // A quantity the run cannot give (an event that fired too few times) leaves its own
      // cell empty, with the reason; the others are the run's.
      std::vector<std::string> missing;
      for (const SweepQuantity& q : quantities) {
        try {
          row.values.push_back(SweepQuantityValue(r, q));
        } catch (const InputError& e) {
          row.values.push_back(kNaN);
          missing.push_back(fmt::format("{}: {}", q.text, OneLine(e.what())));
        }
      }
      row.error = fmt::format("{}", fmt::join(missing, "; "));
      if (p.on_run) p.on_run(r);
    } catch (const InputError& e) {
      row.values.resize(grid.names.size());
      row.values.resize(grid.names.size() + quantities.size(), kNaN);
      row.error = OneLine(e.what());
    }
    return row;
  };
  return RunSweep(grid, names, units, row_at, options);
}

}  // namespace chasles
