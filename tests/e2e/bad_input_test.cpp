// Every file in tests/bad_input/ is a malformed scene. Its first lines say what chasles must
// answer:
//   # expect: <text the error message must contain>
//   # line: <the line the message must point at>        (optional)
//   # args: <extra command-line arguments>                (optional)
//   # command: <the subcommand to run, default mass>       (optional; e.g. solve, simulate)
// chasles must exit with 2, name the file and line, and say the expected text; never crash.

#include <filesystem>
#include <fstream>
#include <regex>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_runner.h"

namespace chasles::test {
namespace {

struct Expectation {
  std::string expect;
  std::string line;
  std::string args;
  std::string command = "mass";
};

Expectation ReadHeader(const std::filesystem::path& file) {
  Expectation e;
  std::ifstream in(file);
  std::string text;
  const std::regex header("^# (expect|line|args|command): (.*)$");
  while (std::getline(in, text)) {
    std::smatch m;
    if (!std::regex_match(text, m, header)) break;
    if (m[1] == "expect") e.expect = m[2];
    if (m[1] == "line") e.line = m[2];
    if (m[1] == "args") e.args = m[2];
    if (m[1] == "command") e.command = m[2];
  }
  return e;
}

class BadInput : public ::testing::TestWithParam<std::string> {};

TEST_P(BadInput, GivesAClearErrorAndExitCode2) {
  const std::filesystem::path file = GetParam();
  const Expectation e = ReadHeader(file);
  ASSERT_FALSE(e.expect.empty()) << file << " has no '# expect:' line";
  const CliResult r = RunCli(e.command + " '" + file.string() + "' " + e.args);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, ::testing::HasSubstr(e.expect));
  EXPECT_THAT(r.err, ::testing::HasSubstr("chasles: error: "));
  EXPECT_THAT(r.err, ::testing::Not(::testing::HasSubstr("internal error")));
  if (!e.line.empty()) {
    EXPECT_THAT(r.err, ::testing::HasSubstr(file.string() + ":" + e.line + ":")) << r.err;
  }
  EXPECT_TRUE(r.out.empty()) << "a failed run must not print a report";
}

std::vector<std::string> BadFiles() {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(SourcePath("tests/bad_input"))) {
    if (entry.path().extension() == ".yaml") files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

INSTANTIATE_TEST_SUITE_P(Files, BadInput, ::testing::ValuesIn(BadFiles()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string name = std::filesystem::path(info.param).stem().string();
                           for (char& c : name) {
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           }
                           return name;
                         });

TEST(BadInputSet, HasAtLeastTwentyFiles) {
  EXPECT_GE(BadFiles().size(), 20u);
}

TEST(BadInputSet, MissingFileAndBadOptions) {
  const CliResult missing = RunCli("mass /nonexistent/scene.yaml");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_THAT(missing.err, ::testing::HasSubstr("cannot open"));
  const CliResult units =
      RunCli("mass '" + SourcePath("examples/section-8.5-cube.yaml") + "' --units furlongs");
  EXPECT_EQ(units.exit_code, 2);
  EXPECT_THAT(units.err, ::testing::HasSubstr("furlongs"));
  const CliResult set =
      RunCli("mass '" + SourcePath("examples/example-8.1-cylinder.yaml") + "' --set ratoi=0.3");
  EXPECT_EQ(set.exit_code, 2);
  EXPECT_THAT(set.err, ::testing::HasSubstr("did you mean 'ratio'"));
  const CliResult flag = RunCli("mass --frobnicate");
  EXPECT_EQ(flag.exit_code, 2);
}

}  // namespace
}  // namespace chasles::test
