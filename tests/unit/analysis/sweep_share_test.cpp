// A sweep split over processes (chasles/analysis/sweep.h): each share runs its points, its
// part goes through bytes, and the merged table is the serial one bit for bit; without MPI.

#include "chasles/analysis/sweep.h"

#include <algorithm>
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

// A box of mass m and sides a, 1 m, 1 m: its central Izz = m (a² + (1 m)²) / 12 (Appendix A).
// A side a <= 0 is bad input at that point: a failed row.
SweepTable Sweep(const SweepShare& share) {
  ParameterGrid grid;
  grid.names = {"a", "m"};
  grid.units = {"m", "kg"};
  grid.start = {-1.0, 1.0};
  grid.stop = {3.0, 4.0};
  grid.counts = {5, 3};
  const SweepFunction box = [](const std::vector<double>& v) {
    const double a = v[0], m = v[1];
    if (a <= 0) throw InputError("side a must be > 0\nat this point");
    return SweepRow{{a, m, m * (a * a + 1) / 12, m}, ""};
  };
  SweepRunOptions options;
  options.jobs = 2;
  options.share = share;
  return RunSweep(grid, {"Izz", "mass"}, {"kg*m^2", "kg"}, box, options);
}

bool SameBits(double x, double y) {
  return std::memcmp(&x, &y, sizeof(double)) == 0;
}

TEST(SweepShare, DealsThePointsInTurn) {
  for (int size = 1; size <= 7; ++size) {
    for (std::int64_t total = 0; total <= 20; ++total) {
      std::vector<int> owner(static_cast<size_t>(total), -1);
      for (int rank = 0; rank < size; ++rank) {
        const SweepShare s{rank, size};
        for (std::int64_t i = 0; i < s.Count(total); ++i) {
          const std::int64_t k = s.Point(i);
          ASSERT_LT(k, total);
          EXPECT_TRUE(s.Has(k));
          EXPECT_EQ(owner[static_cast<size_t>(k)], -1);
          owner[static_cast<size_t>(k)] = rank;
        }
      }
      for (std::int64_t k = 0; k < total; ++k) EXPECT_EQ(owner[static_cast<size_t>(k)], k % size);
    }
  }
}

TEST(SweepShare, MergedPartsAreTheSerialTableBitForBit) {
  const SweepTable serial = Sweep({});
  ASSERT_EQ(serial.rows.size(), 15u);
  // The closed form at the points that ran: a = -1 + i m, m = 1 + 1.5 j kg (point 3 i + j).
  int failed = 0;
  for (size_t k = 0; k < serial.rows.size(); ++k) {
    const double a = -1.0 + static_cast<double>(k / 3), m = 1.0 + 1.5 * static_cast<double>(k % 3);
    if (a <= 0) {
      EXPECT_FALSE(serial.errors[k].empty()) << k;
      EXPECT_TRUE(std::isnan(serial.rows[k][2]));
      ++failed;
      continue;
    }
    EXPECT_TRUE(serial.errors[k].empty()) << serial.errors[k];
    EXPECT_NEAR(serial.rows[k][2], m * (a * a + 1) / 12, 1e-12 * m * (a * a + 1) / 12);
    EXPECT_NEAR(serial.rows[k][3], m, 1e-15 * m);
  }
  EXPECT_EQ(failed, 6);  // a = -1 m and a = 0 at each of the 3 masses
  for (int size = 1; size <= 17; size += 4) {
    SweepTable table;
    std::vector<SweepPart> parts;
    for (int rank = 0; rank < size; ++rank) {
      const SweepTable mine = Sweep({rank, size});
      if (rank == 0) table = mine;
      // Warnings ride along with their point: one at each rank's first point (k = rank).
      SweepWarnings w;
      w[rank] = {"check " + std::to_string(rank)};
      parts.push_back(DecodeSweepPart(EncodeSweepPart(TakeSweepPart(mine, {rank, size}, w))));
    }
    SweepWarnings warnings;
    MergeSweepParts(parts, &table, &warnings);
    ASSERT_EQ(table.rows.size(), serial.rows.size());
    EXPECT_EQ(table.columns, serial.columns);
    EXPECT_EQ(table.units, serial.units);
    EXPECT_EQ(table.errors, serial.errors);
    for (size_t k = 0; k < serial.rows.size(); ++k) {
      ASSERT_EQ(table.rows[k].size(), serial.rows[k].size());
      for (size_t c = 0; c < serial.rows[k].size(); ++c) {
        EXPECT_TRUE(SameBits(table.rows[k][c], serial.rows[k][c])) << size << " " << k << " " << c;
      }
    }
    // Every rank below the 15 points has one; a rank beyond them has no point to carry it.
    ASSERT_EQ(warnings.size(), static_cast<size_t>(std::min(size, 15)));
    for (const auto& [k, list] : warnings) {
      EXPECT_EQ(list, std::vector<std::string>{"check " + std::to_string(k)});
    }
  }
}

TEST(SweepShare, ASolveTablesWarningsAreRemadeInGridOrder) {
  // A solve sweep has no errors column: its warnings are the table's, in grid order.
  SweepTable table;
  table.rows = {{0.0}, {}, {}};
  SweepPart p0, p1;
  p0.points = {{0, {0.0}, "", {"t = 0: a"}}, {2, {2.0}, "", {"t = 2: c", "t = 2: d"}}};
  p1.points = {{1, {1.0}, "", {"t = 1: b"}}};
  SweepWarnings w;
  MergeSweepParts({p0, p1}, &table, &w);
  EXPECT_EQ(table.warnings,
            (std::vector<std::string>{"t = 0: a", "t = 1: b", "t = 2: c", "t = 2: d"}));
  EXPECT_TRUE(table.failed);
  EXPECT_EQ(table.rows, (std::vector<std::vector<double>>{{0.0}, {1.0}, {2.0}}));
  // A row given twice, or none, is a fault of the caller.
  SweepTable again;
  again.rows.resize(3);
  EXPECT_THROW(MergeSweepParts({p0, p0}, &again, &w), std::logic_error);
  EXPECT_THROW(MergeSweepParts({p0}, &again, &w), std::logic_error);
}

TEST(SweepShare, TheFirstFailureIsTheOneTheSerialSweepStopsAt) {
  std::vector<SweepPart> parts(4);
  EXPECT_EQ(FirstFailure(parts), nullptr);
  parts[1] = {2, "at 7", 7, false, {}};
  parts[2] = {2, "at 3", 3, false, {}};
  parts[3] = {1, "at 3 too", 3, false, {}};
  EXPECT_EQ(FirstFailure(parts)->message, "at 3");  // earliest point, then lowest rank
  parts[3] = {2, "before any", -1, false, {}};
  EXPECT_EQ(FirstFailure(parts)->message, "before any");
}

TEST(SweepShare, CutOrAlteredBytesAreRefused) {
  SweepPart part;
  part.code = 2;
  part.message = "chasles: error: x";
  part.failed_at = 4;
  part.check_failed = true;
  part.points = {{4, {1.5, std::nan(""), -0.0}, "why", {"w1", "w2"}}};
  const std::string bytes = EncodeSweepPart(part);
  const SweepPart back = DecodeSweepPart(bytes);
  EXPECT_EQ(back.code, 2);
  EXPECT_EQ(back.message, part.message);
  EXPECT_EQ(back.failed_at, 4);
  EXPECT_TRUE(back.check_failed);
  ASSERT_EQ(back.points.size(), 1u);
  for (size_t c = 0; c < 3; ++c)
    EXPECT_TRUE(SameBits(back.points[0].values[c], part.points[0].values[c]));
  EXPECT_EQ(back.points[0].warnings, part.points[0].warnings);
  // Every shorter prefix, and seeded byte flips, either read back or are refused with
  // InputError, never read past the end.
  for (size_t n = 0; n < bytes.size(); ++n) {
    EXPECT_THROW(DecodeSweepPart(std::string_view(bytes).substr(0, n)), InputError) << n;
  }
  EXPECT_THROW(DecodeSweepPart(bytes + "x"), InputError);
  std::mt19937 rng(15);
  for (int i = 0; i < 2000; ++i) {
    std::string b = bytes;
    b[rng() % b.size()] = static_cast<char>(rng());
    try {
      DecodeSweepPart(b);
    } catch (const InputError&) {
    }
  }
}

}  // namespace
}  // namespace chasles
