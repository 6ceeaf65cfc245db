#include "chasles/report/json_report.h"

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/error.h"

namespace chasles {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

std::string MessageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}

TEST(CheckFiniteJson, NamesTheKeyPathOfTheFirstNonFiniteNumber) {
  nlohmann::json j = {{"a", 1.0}, {"b", {{"c", {0.5, 2.0, kNaN}}}}};
  const std::string m = MessageOf([&] { CheckFiniteJson(j, "the test report"); });
  EXPECT_THAT(m, StartsWith("the test report: b.c[2] is nan, not a finite number"));
}

TEST(CheckFiniteJson, NamesTheBodyOfABodiesPath) {
  nlohmann::json j;
  j["bodies"] = {{{"name", "wheel"}, {"mass", 2.0}, {"inertia", {{1.0, kInf}}}}};
  const std::string m = MessageOf([&] { CheckFiniteJson(j, "the mass report"); });
  EXPECT_THAT(m, StartsWith("the mass report: bodies[0].inertia[0][1] (body 'wheel') is inf"));
}

TEST(CheckFiniteJson, AcceptsFiniteNumbersIntegersStringsAndBooleans) {
  const nlohmann::json j = {{"n", 3}, {"s", "nan"}, {"b", true}, {"x", {1e308, -1e-308}}};
  EXPECT_NO_THROW(CheckFiniteJson(j, "r"));
}

TEST(DumpJson, IndentsByTwoEndsWithANewlineAndChecksFirst) {
  const nlohmann::json j = {{"a", 0.1}, {"b", {1, 2}}};
  EXPECT_EQ(DumpJson(j, "r"), "{\n  \"a\": 0.1,\n  \"b\": [\n    1,\n    2\n  ]\n}\n");
  const nlohmann::json bad = {{"a", {{"x", -kInf}}}};
  EXPECT_THAT(MessageOf([&] { DumpJson(bad, "r"); }), StartsWith("r: a.x is -inf"));
}

TEST(DumpJson, ReplacesTextThatIsNotUtf8) {
  const nlohmann::json j = {{"file", std::string("a\xff.yaml")}};
  EXPECT_EQ(DumpJson(j, "r"), "{\n  \"file\": \"a\xEF\xBF\xBD.yaml\"\n}\n");
}

TEST(CheckFiniteTable, NamesTheColumnAndTheRowCountedFromOne) {
  const std::vector<std::string> columns = {"t", "x"};
  const std::vector<std::vector<double>> rows = {{0.0, 1.0}, {0.1, kNaN}};
  EXPECT_THAT(MessageOf([&] { CheckFiniteTable(columns, rows, "the table"); }),
              StartsWith("the table: column 'x' of row 2 is nan"));
  EXPECT_NO_THROW(CheckFiniteTable(columns, {{0.0, 1.0}}, "the table"));
}

TEST(Finite, ReturnsAFiniteValueAndNamesANonFiniteOne) {
  EXPECT_EQ(Finite(2.5, "x"), 2.5);
  EXPECT_THAT(MessageOf([] { Finite(kInf, "the speed"); }),
              AllOf(StartsWith("the speed is inf"), HasSubstr("overflowed the range of a double")));
}

TEST(VecJsonMatJson, WriteComponentsInOrderAndMatricesByRows) {
  EXPECT_EQ(VecJson(Vec3(1, 2, 3)).dump(), "[1.0,2.0,3.0]");
  Mat3 m;
  m << 1, 2, 3, 4, 5, 6, 7, 8, 9;
  EXPECT_EQ(MatJson(m).dump(), "[[1.0,2.0,3.0],[4.0,5.0,6.0],[7.0,8.0,9.0]]");
}

}  // namespace
}  // namespace chasles
