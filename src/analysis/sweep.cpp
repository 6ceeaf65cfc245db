// Sweeps over a grid of parameter values (chasles/analysis/sweep.h).

#include "chasles/analysis/sweep.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <thread>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "chasles/error.h"
#include "chasles/integrate/parallel.h"

namespace chasles {

std::int64_t ParameterGrid::size() const {
  std::int64_t n = 1;
  for (const int c : counts) n *= c;
  return n;
}

std::vector<int> ParameterGrid::Indices(std::int64_t k) const {
  std::vector<int> i(counts.size());
  for (size_t j = counts.size(); j-- > 0;) {
    const auto n = static_cast<std::int64_t>(counts[j]);
    i[j] = static_cast<int>(k % n);
    k /= n;
  }
  return i;
}

std::vector<double> ParameterGrid::Values(std::int64_t k) const {
  const std::vector<int> i = Indices(k);
  std::vector<double> v;
  for (size_t j = 0; j < counts.size(); ++j) {
    v.push_back(start[j] + (stop[j] - start[j]) * i[j] / (counts[j] - 1));
  }
  return v;
}

std::int64_t ParameterGrid::PointOf(const std::vector<double>& values) const {
  if (values.size() != counts.size()) return -1;
  std::int64_t k = 0;
  for (size_t j = 0; j < counts.size(); ++j) {
    int at = -1;
    for (int i = 0; i < counts[j] && at < 0; ++i) {
      if (start[j] + (stop[j] - start[j]) * i / (counts[j] - 1) == values[j]) at = i;
    }
    if (at < 0) return -1;
    k = k * counts[j] + at;
  }
  return k;
}

void CheckParameterGrid(const ParameterGrid& grid, std::int64_t max_points) {
  const size_t n = grid.names.size();
  if (n == 0) throw InputError("a sweep needs at least one parameter");
  if (grid.units.size() != n || grid.start.size() != n || grid.stop.size() != n ||
      grid.counts.size() != n) {
    throw InputError(
        fmt::format("a sweep's grid has {} names but {} units, {} starts, {} stops and {} counts",
                    n, grid.units.size(), grid.start.size(), grid.stop.size(), grid.counts.size()));
  }
  std::int64_t size = 1;
  for (size_t j = 0; j < n; ++j) {
    if (grid.counts[j] < 2) {
      throw InputError(fmt::format("parameter '{}': the number of values must be >= 2, got {}",
                                   grid.names[j], grid.counts[j]));
    }
    if (!std::isfinite(grid.start[j]) || !std::isfinite(grid.stop[j])) {
      throw InputError(fmt::format("parameter '{}': START and STOP must be finite, got {} and {}",
                                   grid.names[j], grid.start[j], grid.stop[j]));
    }
    if (size > max_points / grid.counts[j]) {
      throw InputError(
          fmt::format("the grid has more points than the limit of {} runs", max_points));
    }
    size *= grid.counts[j];
  }
}

std::string OneLine(std::string text) {
  std::string out;
  for (const char c : text) {
    if (c == '\n') {
      if (!out.empty()) out += "; ";
    } else if (c != '\r') {
      out += c;
    }
  }
  return out;
}

SweepTable RunSweep(const ParameterGrid& grid, const std::vector<std::string>& quantities,
                    const std::vector<std::string>& units, const SweepFunction& point,
                    const SweepRunOptions& options) {
  SweepTable table;
  table.parameter = fmt::format("{}", fmt::join(grid.names, ", "));
  table.parameters = grid.names;
  table.columns = grid.names;
  table.units = grid.units;
  table.columns.insert(table.columns.end(), quantities.begin(), quantities.end());
  table.units.insert(table.units.end(), units.begin(), units.end());
  const std::int64_t size = grid.size();
  std::vector<SweepRow> rows(static_cast<size_t>(size));
  const std::int64_t mine = options.share.Count(size);
  if (options.progress) options.progress(0, mine);
  RunParallel(
      mine, options.jobs,
      [&](std::int64_t i) {
        const std::int64_t k = options.share.Point(i);
        const std::vector<double> values = grid.Values(k);
        SweepRow& row = rows[static_cast<size_t>(k)];
        try {
          row = point(values);
        } catch (const InputError& e) {
          // The point's own failure: its parameters, no quantities, and why.
          row.values = values;
          row.values.resize(values.size() + quantities.size(),
                            std::numeric_limits<double>::quiet_NaN());
          row.error = OneLine(e.what());
        }
      },
      [&](std::int64_t done) {
        if (options.progress) options.progress(done, mine);
      });
  for (SweepRow& r : rows) {
    table.rows.push_back(std::move(r.values));
    table.errors.push_back(std::move(r.error));
  }
  return table;
}

void RunParallel(std::int64_t count, int jobs, const std::function<void(std::int64_t k)>& run,
                 const std::function<void(std::int64_t done)>& done) {
  if (jobs < 1) jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const auto threads =
      static_cast<int>(std::min<std::int64_t>(jobs, std::max<std::int64_t>(count, 1)));
  std::atomic<std::int64_t> next{0};
  std::atomic<bool> stop{false};
  std::mutex mutex;
  std::int64_t finished = 0;
  std::exception_ptr failure;
  const auto work = [&]() {
    for (std::int64_t k; !stop && (k = next++) < count;) {
      try {
        run(k);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (!failure) failure = std::current_exception();
        stop = true;
        return;
      }
      const std::lock_guard<std::mutex> lock(mutex);
      ++finished;
      if (done) done(finished);
    }
  };
  // As many threads as the system starts (chasles/integrate/parallel.h); `work` catches its own.
  RunOnThreads(threads, work);
  if (failure) std::rethrow_exception(failure);
}

}  // namespace chasles
