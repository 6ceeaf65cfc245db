// The generic sweep (chasles/analysis/sweep.h): the grid's order and values, the thread pool,
// and a table in grid order that is the same for any number of threads.

#include "chasles/analysis/sweep.h"

#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "chasles/error.h"

namespace chasles {
namespace {

TEST(ParameterGrid, LastParameterVariesFastestAndPointsAreFoundFromTheirValues) {
  ParameterGrid grid;
  grid.names = {"a", "b"};
  grid.units = {"m", ""};
  grid.start = {1.0, 0.0};
  grid.stop = {3.0, 0.3};
  grid.counts = {3, 4};
  ASSERT_EQ(grid.size(), 12);
  for (std::int64_t k = 0; k < grid.size(); ++k) {
    const std::vector<int> i = grid.Indices(k);
    EXPECT_EQ(i[0], k / 4);
    EXPECT_EQ(i[1], k % 4);
    // START + (STOP - START) i / (COUNT - 1).
    const std::vector<double> v = grid.Values(k);
    EXPECT_EQ(v[0], 1.0 + i[0]);
    EXPECT_NEAR(v[1], 0.1 * i[1], 1e-16);
    EXPECT_EQ(grid.PointOf(v), k);
  }
  EXPECT_EQ(grid.PointOf({1.5, 0.0}), -1);
  EXPECT_NO_THROW(CheckParameterGrid(grid, 12));
  EXPECT_THROW(CheckParameterGrid(grid, 11), InputError);
  ParameterGrid bad = grid;
  bad.counts[1] = 1;
  EXPECT_THROW(CheckParameterGrid(bad, 100), InputError);
  bad = grid;
  bad.stop[0] = std::nan("");
  EXPECT_THROW(CheckParameterGrid(bad, 100), InputError);
  bad = grid;
  bad.units.pop_back();
  EXPECT_THROW(CheckParameterGrid(bad, 100), InputError);
}

bool SameBits(double x, double y) {
  return std::memcmp(&x, &y, sizeof(double)) == 0;
}

// A projectile launched at speed v and angle theta over flat ground lands at
// R = v^2 sin(2 theta) / g (no drag); the sweep's rows are the function's in grid order, bit
// for bit the same on 1 to 4 threads, and a point whose function throws InputError is a row
// with its parameters, NaN and the reason on one line.
TEST(RunSweep, RowsInGridOrderTheSameForAnyThreadCount) {
  constexpr double kG = 9.81;
  ParameterGrid grid;
  grid.names = {"v", "theta"};
  grid.units = {"m/s", "rad"};
  grid.start = {0.0, 0.1};
  grid.stop = {20.0, 1.4};
  grid.counts = {5, 7};
  const SweepFunction range = [](const std::vector<double>& p) {
    if (p[0] == 0.0) throw InputError("no launch\nat v = 0");
    return SweepRow{{p[0], p[1], p[0] * p[0] * std::sin(2 * p[1]) / kG}, ""};
  };
  std::vector<SweepTable> tables;
  for (int jobs = 1; jobs <= 4; ++jobs) {
    std::int64_t last = -1, total = -1;
    SweepRunOptions o;
    o.jobs = jobs;
    o.progress = [&](std::int64_t done, std::int64_t n) { last = done, total = n; };
    tables.push_back(RunSweep(grid, {"range"}, {"m"}, range, o));
    EXPECT_EQ(last, 35);
    EXPECT_EQ(total, 35);
  }
  const SweepTable& t = tables.front();
  EXPECT_EQ(t.columns, (std::vector<std::string>{"v", "theta", "range"}));
  EXPECT_EQ(t.units, (std::vector<std::string>{"m/s", "rad", "m"}));
  EXPECT_EQ(t.parameter, "v, theta");
  ASSERT_EQ(t.rows.size(), 35u);
  for (std::int64_t k = 0; k < 35; ++k) {
    const std::vector<double> p = grid.Values(k);
    const auto row = static_cast<size_t>(k);
    EXPECT_EQ(t.rows[row][0], p[0]);
    EXPECT_EQ(t.rows[row][1], p[1]);
    if (p[0] == 0.0) {
      EXPECT_TRUE(std::isnan(t.rows[row][2]));
      EXPECT_EQ(t.errors[row], "no launch; at v = 0");
    } else {
      EXPECT_EQ(t.errors[row], "");
      const double exact = p[0] * p[0] * std::sin(2 * p[1]) / kG;
      EXPECT_NEAR(t.rows[row][2], exact, 1e-15 * exact);
    }
    for (const SweepTable& other : tables) {
      for (size_t c = 0; c < 3; ++c) EXPECT_TRUE(SameBits(other.rows[row][c], t.rows[row][c]));
    }
  }
}

// Every index runs once whatever the thread count; results land by index; an exception stops
// the pool and comes back to the caller.
TEST(RunParallel, EachIndexOnceAndErrorsPropagate) {
  std::mt19937 random(7);
  for (int trial = 0; trial < 5; ++trial) {
    const auto count = static_cast<std::int64_t>(random() % 200);
    const int jobs = 1 + static_cast<int>(random() % 4);
    std::vector<std::atomic<int>> seen(static_cast<size_t>(count));
    std::vector<double> out(static_cast<size_t>(count));
    std::int64_t last_done = 0;
    RunParallel(
        count, jobs,
        [&](std::int64_t k) {
          ++seen[static_cast<size_t>(k)];
          out[static_cast<size_t>(k)] = 0.5 * static_cast<double>(k);
        },
        [&](std::int64_t done) { last_done = done; });
    EXPECT_EQ(last_done, count);
    for (std::int64_t k = 0; k < count; ++k) {
      EXPECT_EQ(seen[static_cast<size_t>(k)], 1);
      EXPECT_EQ(out[static_cast<size_t>(k)], 0.5 * static_cast<double>(k));
    }
  }
  EXPECT_THROW(RunParallel(50, 3,
                           [](std::int64_t k) {
                             if (k == 17) throw std::runtime_error("point 17");
                           }),
               std::runtime_error);
}

}  // namespace
}  // namespace chasles
