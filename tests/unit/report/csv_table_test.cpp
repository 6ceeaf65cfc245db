#include "chasles/report/csv_table.h"

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/error.h"

namespace chasles {
namespace {

using ::testing::HasSubstr;

TEST(CsvHeader, NameOneSpaceAndTheUnitInBrackets) {
  EXPECT_EQ(CsvHeaderField("car_ax", "m/s^2"), "car_ax [m/s^2]");
  EXPECT_EQ(CsvHeaderField("qw", ""), "qw");
  const CsvColumnName a = CsvHeaderName("theta [rad]");
  EXPECT_EQ(a.name, "theta");
  EXPECT_EQ(a.unit, "rad");
  // Only a trailing " [...]" is a unit; brackets inside a name stay.
  EXPECT_EQ(CsvHeaderName("qw").name, "qw");
  EXPECT_EQ(CsvHeaderName("qw").unit, "");
  EXPECT_EQ(CsvHeaderName("a[1]").name, "a[1]");
  EXPECT_EQ(CsvHeaderName("a [1] x").name, "a [1] x");
  EXPECT_EQ(CsvHeaderName("H [kg*m^2/s]").unit, "kg*m^2/s");
}

TEST(CsvTable, WritesAndReadsBackByName) {
  const CsvTable t{{"t", "x,y", "mode"}, {"s", "m", ""}, {{0.0, 0.1, 2.0}, {0.5, -3e-9, 1.0}}, {}};
  const std::string text = CsvText(t, 0, "the table");
  EXPECT_EQ(text, "t [s],\"x,y [m]\",mode\n0,0.1,2\n0.5,-3e-09,1\n");
  const CsvTable back = ReadCsvTable(text, "run.csv");
  EXPECT_EQ(back.columns, t.columns);
  EXPECT_EQ(back.units, t.units);
  EXPECT_EQ(back.rows, t.rows);
  EXPECT_EQ(CsvColumnIndex(back, "mode", "run.csv"), 2u);
}

TEST(CsvTable, AFailedRowHasEmptyValuesAndItsReasonInTheErrorColumn) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const CsvTable t{{"L", "T"}, {"m", "s"}, {{1.0, 2.0}, {2.0, nan}}, {"", "step size, too small"}};
  const std::string text = CsvText(t, 12, "the sweep table");
  EXPECT_EQ(text, "L [m],T [s],error\n1,2,\n2,,\"step size, too small\"\n");
  const CsvTable back = ReadCsvTable(text, "sweep.csv");
  EXPECT_EQ(back.columns, t.columns);  // "error" is not a column of numbers
  EXPECT_EQ(back.errors, t.errors);
  EXPECT_EQ(back.rows[1][0], 2.0);
  EXPECT_TRUE(std::isnan(back.rows[1][1]));
  // A non-finite value in a row that ran is refused, and an empty field without a reason.
  CsvTable bad = t;
  bad.errors[1] = "";
  EXPECT_THROW(CsvText(bad, 12, "the sweep table"), InputError);
  EXPECT_THROW(ReadCsvTable("L [m],T [s],error\n2,,\n", "sweep.csv"), InputError);
  EXPECT_THROW(ReadCsvTable("L [m],T [s]\n2,nan\n", "sweep.csv"), InputError);
  EXPECT_THROW(ReadCsvTable("L [m],T [s]\n2,1e999\n", "sweep.csv"), InputError);
}

// Hostile bytes: seeded mutations of a sweep table (bytes replaced, inserted, deleted; quotes,
// commas, newlines, NUL) either read as a table whose every row has one value per column and
// whose values are finite (or NaN only in a failed row), or throw InputError; nothing else.
TEST(CsvTable, HostileBytesReadOrGiveInputError) {
  const std::string good =
      "L [m],theta0 [rad],event(bottom) [s],error\n0.5,0.1,0.36,\n1,0.2,,\"no, event\"\n";
  static const char kBytes[] = "0123456789.,-+e\"\n\r []nai\x00\xff";
  const std::string alphabet(kBytes, sizeof kBytes - 1);  // with the NUL byte
  std::mt19937 rng(20261124);
  int read = 0, refused = 0;
  for (int k = 0; k < 3000; ++k) {
    std::string text = good;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits && !text.empty(); ++e) {
      const size_t at = rng() % text.size();
      const char c = alphabet[rng() % alphabet.size()];
      switch (rng() % 3) {
        case 0:
          text[at] = c;
          break;
        case 1:
          text.insert(text.begin() + static_cast<long>(at), c);
          break;
        default:
          text.erase(at, 1);
      }
    }
    try {
      const CsvTable t = ReadCsvTable(text, "hostile.csv");
      ++read;
      for (size_t r = 0; r < t.rows.size(); ++r) {
        ASSERT_EQ(t.rows[r].size(), t.columns.size()) << text;
        const bool failed = r < t.errors.size() && !t.errors[r].empty();
        for (double v : t.rows[r])
          ASSERT_TRUE(std::isfinite(v) || (failed && std::isnan(v))) << text;
      }
    } catch (const InputError& e) {
      ++refused;
      EXPECT_THAT(e.what(), HasSubstr("hostile.csv")) << text;
    }
  }
  // Both outcomes occur: the mutations reach past the reader's first check.
  EXPECT_GT(read, 100);
  EXPECT_GT(refused, 100);
}

TEST(CsvTable, AMissingColumnNamesTheColumns) {
  const CsvTable t{{"t", "x"}, {"s", "m"}, {}, {}};
  try {
    CsvColumnIndex(t, "y", "run.csv");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("run.csv: no column 'y'; columns: t, x"));
  }
}

TEST(CsvTable, ABadValueNamesLineAndColumn) {
  try {
    ReadCsvTable("t [s],x [m]\n0,1\n0.1,abc\n", "run.csv");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("run.csv:3: column 'x': expected a number, got 'abc'"));
  }
  EXPECT_THROW(ReadCsvTable("t,x\n0\n", "run.csv"), InputError);
  EXPECT_THROW(ParseCsvPrecision("max"), InputError);
  EXPECT_EQ(ParseCsvPrecision("full"), CsvPrecision::kFull);
}

}  // namespace
}  // namespace chasles
