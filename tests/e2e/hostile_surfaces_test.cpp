// The exit-code promise on the later surfaces: output targets checked before any work (two
// options naming one file, devices, FIFOs, links, /proc), sweeps with many jobs and kept runs,
// counts past their range, and the files plot and report read back (size and depth caps,
// texts PLplot cannot take, failed rows). Bad input is exit 2 with a message naming the file or
// option, and leaves nothing behind (docs/reliability.md).

#include <sys/stat.h>
#include <unistd.h>
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_runner.h"
#include "test_paths.h"

namespace chasles::test {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
namespace fs = std::filesystem;

const std::string kSpring = "examples/spring-mass.yaml";

void WriteText(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

std::string ReadText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> Entries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

/// Exit 2, the message says `text`, nothing on standard output, no internal error.
void ExpectRefused(const CliResult& r, const std::string& text) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr(text));
  EXPECT_THAT(r.err, Not(HasSubstr("internal error")));
  EXPECT_TRUE(r.out.empty()) << r.out;
}

bool HaveHtmlReport() {
  static const bool have =
      RunCli("mass " + Quote(SourcePath(kSpring)) + " --format json --html /dev/null")
          .err.find("has no browser report") == std::string::npos;
  return have;
}

TEST(OutputTargets, TwoOptionsNamingOneFileAreRefusedBeforeAnyWork) {
  if (!HaveHtmlReport()) GTEST_SKIP() << "built without the browser report";
  const fs::path dir = OutDir("hostile_same");
  const std::string scene = Quote(SourcePath(kSpring));
  const std::string a = (dir / "a.txt").string(), a2 = (dir / "." / "a.txt").string();
  ExpectRefused(RunCli("mass " + scene + " -o " + Quote(a) + " --html " + Quote(a2)),
                "-o '" + a + "' and --html '" + a2 + "' name the same file");
  // simulate --out DIR and --html DIR/spring-mass.csv: the page would replace the run's CSV.
  const std::string csv = (dir / "spring-mass.csv").string();
  ExpectRefused(RunCli("simulate " + scene + " --until 0.01 --out " + Quote(dir.string()) +
                       " --html " + Quote(csv)),
                "--out '" + csv + "' and --html '" + csv + "' name the same file");
  // solve -o and --html on one file, through a second name of the folder.
  ExpectRefused(RunCli("solve " + scene + " -o " + Quote(a) + " --html " +
                       Quote((dir / ".." / dir.filename() / "a.txt").string())),
                "name the same file");
  EXPECT_TRUE(Entries(dir).empty());
  fs::remove_all(dir);
}

TEST(OutputTargets, DevicesFifosLinksAndFoldersWithoutRoomAreRefusedAndLeftAlone) {
  const fs::path dir = OutDir("hostile_nodes");
  const std::string scene = Quote(SourcePath(kSpring));
  WriteText(dir / "real", "kept");
  fs::create_symlink(dir / "real", dir / "link");
  ASSERT_EQ(::mkfifo((dir / "fifo").c_str(), 0666), 0);
  ExpectRefused(RunCli("mass " + scene + " -o " + Quote((dir / "link").string())),
                "(-o): it is a symbolic link");
  ExpectRefused(RunCli("mass " + scene + " -o " + Quote((dir / "fifo").string())),
                "(-o): it is a FIFO");
  ExpectRefused(RunCli("mass " + scene + " -o /dev/null"), "'/dev/null' (-o): it is a device");
  ExpectRefused(RunCli("mass " + scene + " -o /proc/chasles-report.txt"),
                "no file can be created in the folder '/proc'");
  // The nodes are as they were: the link still a link to the untouched file, the FIFO a FIFO.
  EXPECT_TRUE(fs::is_symlink(dir / "link"));
  EXPECT_EQ(ReadText(dir / "real"), "kept");
  EXPECT_TRUE(fs::is_fifo(dir / "fifo"));
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  EXPECT_EQ(Entries(dir), (std::vector<std::string>{"fifo", "link", "real"}));
  // "-" is standard output where a report may go there.
  const CliResult out = RunCli("mass " + scene + " -o -");
  EXPECT_EQ(out.exit_code, 0) << out.err;
  EXPECT_THAT(out.out, HasSubstr("block"));
  fs::remove_all(dir);
}

TEST(CommandLine, CountsPastTheirRangeAreRefusedNamingTheOption) {
  const std::string sweep =
      "simulate " + Quote(SourcePath(kSpring)) +
      " --until 0.01 --quiet --sweep 'k=100 N/m:1000 N/m:3' --quantity 'max(block_x)' ";
  for (const char* bad : {"99999999999999999999", "0", "-1", "1e3", "2.5"}) {
    ExpectRefused(RunCli(sweep + "--max-runs " + bad), "--max-runs");
    ExpectRefused(RunCli(sweep + "--jobs " + std::string(bad)), "--jobs");
  }
  ExpectRefused(RunCli(sweep + "--jobs 65537"), "expected a whole number from 1 to 65536");
  // A grid past --max-runs names --max-runs, not --max-rows.
  const CliResult grid = RunCli(sweep + "--max-runs 2");
  ExpectRefused(grid, "raise the limit with --max-runs N");
  EXPECT_THAT(grid.err, Not(HasSubstr("--max-rows")));
}

/// The sweep over 300 stiffnesses of the spring-mass, with `options`, its table.
CliResult SpringSweep(const std::string& options) {
  return RunCli("simulate " + Quote(SourcePath(kSpring)) +
                " --until 0.05 --quiet --sweep 'k=100 N/m:1000 N/m:300' --quantity "
                "'max(block_x)' --quantity 'final(block_vx)' " +
                options);
}

TEST(Sweeps, KeepRunsWithSixtyFourJobsGivesTheTableAndFilesOfOneJob) {
  // The output set's state is per set: 64 threads writing kept runs at once all succeed (a
  // fixed table of 32 temporaries once failed most rows), and the table does not depend on
  // --jobs.
  const fs::path dir = OutDir("hostile_jobs");
  const CliResult one = SpringSweep("--jobs 1 --keep-runs " + Quote((dir / "one").string()));
  const CliResult many = SpringSweep("--jobs 64 --keep-runs " + Quote((dir / "many").string()));
  ASSERT_EQ(one.exit_code, 0) << one.err;
  ASSERT_EQ(many.exit_code, 0) << many.err;
  EXPECT_EQ(many.out, one.out);
  EXPECT_THAT(many.err, Not(HasSubstr("warning")));
  const std::vector<std::string> files = Entries(dir / "one");
  EXPECT_EQ(files.size(), 600u);  // a CSV and a JSON per point, no temporary
  EXPECT_EQ(Entries(dir / "many"), files);
  for (const std::string& f : files) {
    if (f.size() > 4 && f.substr(f.size() - 4) == ".csv") {
      EXPECT_EQ(ReadText(dir / "many" / f), ReadText(dir / "one" / f)) << f;
    }
  }
  fs::remove_all(dir);
}

TEST(OutputTargets, TwoRunsIntoOneOutFolderAtOnceNeverLeaveAMixedPair) {
  // Two stiffnesses written into one --out folder at the same moment, 20 times: the folder's
  // lock makes each pair of renames whole, so the CSV and the JSON left are of one run (the
  // JSON's final position is the CSV's last x, bit for bit).
  const fs::path dir = OutDir("hostile_pair");
  const std::string run = "'" + std::string(chasles::test::CliPath()) + "' simulate " +
                          Quote(SourcePath(kSpring)) + " --quiet --until 0.5 --out " +
                          Quote(dir.string()) + " --set ";
  for (int round = 0; round < 20; ++round) {
    const std::string both =
        run + "'k=100 N/m' >/dev/null 2>&1 & " + run + "'k=900 N/m' >/dev/null 2>&1 & wait";
    ASSERT_EQ(std::system(both.c_str()), 0);
    const nlohmann::json j = nlohmann::json::parse(ReadText(dir / "spring-mass.json"));
    const double json_x = j.at("final").at("bodies").at(0).at("center_of_mass").at(0).get<double>();
    const std::vector<double> csv_x = ReadCsv((dir / "spring-mass.csv").string()).at("block_x");
    ASSERT_FALSE(csv_x.empty());
    EXPECT_EQ(csv_x.back(), json_x) << "round " << round;
    EXPECT_EQ(Entries(dir), (std::vector<std::string>{"spring-mass.csv", "spring-mass.json"}));
  }
  fs::remove_all(dir);
}

TEST(OutputTargets, TwoSweepsKeepingRunsInOneFolderAtOnceNeverLeaveAMixedPair) {
  // Two sweeps over the same stiffnesses with different masses, keeping their runs in one
  // folder at the same moment, 10 times: each point's CSV and JSON are renamed into place
  // together under the folder's lock, so every pair left is of one run (the JSON's final
  // position is the CSV's last x, bit for bit), whichever sweep wrote it last.
  const fs::path dir = OutDir("hostile_kept_pair");
  const std::string run = "'" + std::string(chasles::test::CliPath()) + "' simulate " +
                          Quote(SourcePath(kSpring)) +
                          " --quiet --until 0.3 --sweep 'k=100 N/m:900 N/m:3' --quantity "
                          "'max(block_x)' --jobs 3 --keep-runs " +
                          Quote(dir.string()) + " --set ";
  for (int round = 0; round < 10; ++round) {
    const std::string both =
        run + "'m=2 kg' >/dev/null 2>&1 & " + run + "'m=7 kg' >/dev/null 2>&1 & wait";
    ASSERT_EQ(std::system(both.c_str()), 0);
    const std::vector<std::string> names = Entries(dir);
    ASSERT_EQ(names.size(), 6u) << "round " << round;
    for (const std::string& n : names) {
      if (fs::path(n).extension() != ".json") continue;
      const nlohmann::json j = nlohmann::json::parse(ReadText(dir / n));
      const double json_x =
          j.at("final").at("bodies").at(0).at("center_of_mass").at(0).get<double>();
      const fs::path csv = dir / (fs::path(n).stem().string() + ".csv");
      const std::vector<double> csv_x = ReadCsv(csv.string()).at("block_x");
      ASSERT_FALSE(csv_x.empty());
      EXPECT_EQ(csv_x.back(), json_x) << "round " << round << ": " << n;
    }
  }
  fs::remove_all(dir);
}

/// A run of the spring-mass with its summary naming the scene by its full path.
struct SpringFiles {
  fs::path dir, json, csv;
};

SpringFiles SpringRun(const std::string& tag) {
  SpringFiles r;
  r.dir = OutDir(tag);
  SimulateJson(SourcePath(kSpring), r.dir, "--quiet");
  r.json = r.dir / "spring-mass.json";
  r.csv = r.dir / "spring-mass.csv";
  return r;
}

TEST(Sweeps, KeptRunsOfPointsEqualToTwelveDigitsAreNamedInFullAndNoneIsReplaced) {
  // Three stiffnesses within 1e-10 N/m of each other print alike at 12 digits: the names are
  // then the values in full, three runs, six files. A grid whose 12-digit names differ keeps
  // them (docs/sweeps.md).
  const fs::path dir = OutDir("hostile_names");
  const CliResult close = RunCli("simulate " + Quote(SourcePath(kSpring)) +
                                 " --quiet --until 0.01 --sweep 'k=100 N/m:100.0000000002 N/m:3' "
                                 "--quantity 'max(block_x)' --keep-runs " +
                                 Quote((dir / "close").string()));
  ASSERT_EQ(close.exit_code, 0) << close.err;
  EXPECT_EQ(Entries(dir / "close"),
            (std::vector<std::string>{
                "spring-mass_k=100.0000000001.csv", "spring-mass_k=100.0000000001.json",
                "spring-mass_k=100.0000000002.csv", "spring-mass_k=100.0000000002.json",
                "spring-mass_k=100.csv", "spring-mass_k=100.json"}));
  const CliResult apart = RunCli("simulate " + Quote(SourcePath(kSpring)) +
                                 " --quiet --until 0.01 --sweep 'k=100 N/m:400 N/m:4' --quantity "
                                 "'max(block_x)' --keep-runs " +
                                 Quote((dir / "apart").string()));
  ASSERT_EQ(apart.exit_code, 0) << apart.err;
  EXPECT_EQ(Entries(dir / "apart").size(), 8u);
  EXPECT_TRUE(fs::exists(dir / "apart" / "spring-mass_k=200.csv"));
  fs::remove_all(dir);
}

TEST(FullDisk, EveryCommandThatWritesIsExit2AndLeavesNothing) {
  // A 64 KiB tmpfs filled to the last byte (mounting needs root: skipped otherwise); standard
  // output on /dev/full, which always answers ENOSPC.
  const fs::path dir = OutDir("hostile_full");
  const fs::path disk = dir / "disk";
  fs::create_directories(disk);
  if (std::system(
          ("mount -t tmpfs -o size=64k tmpfs " + Quote(disk.string()) + " 2>/dev/null").c_str()) !=
      0) {
    GTEST_SKIP() << "no tmpfs can be mounted here (not root)";
  }
  {
    std::ofstream filler(disk / "filler", std::ios::binary);
    const std::string block(4096, 'x');
    for (int k = 0; k < 64 && filler.write(block.data(), block.size()); ++k) {
    }
  }
  const std::string scene = Quote(SourcePath(kSpring));
  std::string v1 = ReadText(SourcePath(kSpring));
  v1.replace(v1.find("chasles: 3"), 10, "chasles: 1");  // a scene upgrade rewrites
  WriteText(dir / "v1.yaml", v1);
  const auto in = [&](const std::string& name) { return Quote((disk / name).string()); };
  const std::vector<std::string> commands = {
      "simulate " + scene + " --quiet --until 2 --out " + Quote(disk.string()),
      "mass " + scene + " -o " + in("mass.txt"),
      "solve " + scene + " -o " + in("solve.txt"),
      "mass " + scene + " --quiet --sweep 'm=1 kg:2 kg:50' --quantity mass -o " + in("t.csv"),
      "upgrade " + Quote((dir / "v1.yaml").string()) + " -o " + in("up.yaml"),
  };
  for (const std::string& c : commands) {
    const CliResult r = RunCli(c);
    EXPECT_EQ(r.exit_code, 2) << c << "\n" << r.err;
    EXPECT_THAT(r.err, HasSubstr("No space left on device")) << c;
    EXPECT_EQ(Entries(disk), std::vector<std::string>{"filler"}) << c;
  }
#ifdef CHASLES_HAVE_PLOT
  const SpringFiles run = SpringRun("hostile_full_plot");
  const CliResult plot =
      RunCli("plot " + Quote(run.json.string()) + " t block_x -o " + in("p.svg"));
  EXPECT_EQ(plot.exit_code, 2) << plot.err;
  EXPECT_EQ(Entries(disk), std::vector<std::string>{"filler"});
#endif
  const CliResult full = RunCli("mass " + scene + " >/dev/full");
  EXPECT_EQ(full.exit_code, 2);
  EXPECT_THAT(full.err, HasSubstr("cannot write to standard output: No space left on device"));
  EXPECT_EQ(std::system(("umount " + Quote(disk.string())).c_str()), 0);
  fs::remove_all(dir);
}

TEST(ReadBack, ReportRefusesEndlessDeepAndFailedInputNamingTheFile) {
  if (!HaveHtmlReport()) GTEST_SKIP() << "built without the browser report";
  const SpringFiles run = SpringRun("hostile_report");
  const std::string page = Quote((run.dir / "r.html").string());
  ExpectRefused(RunCli("report /dev/zero --max-input-bytes 100000 -o " + page),
                "/dev/zero: the run's JSON summary is longer than the limit of 100000 bytes");
  ExpectRefused(RunCli("report " + Quote(run.dir.string()) + " -o " + page),
                run.dir.string() + ": this is a folder, not the run's JSON summary");
  // A summary whose events hold 300 000 nested arrays: refused by depth, not by the stack.
  nlohmann::json j = nlohmann::json::parse(ReadText(run.json));
  const std::string deep = std::string(300000, '[') + std::string(300000, ']');
  j["events"] = nlohmann::json::array();
  std::string text = j.dump();
  text.replace(text.find("\"events\":[]") + 9, 2, deep);
  WriteText(run.dir / "deep.json", text);
  ExpectRefused(RunCli("report " + Quote((run.dir / "deep.json").string()) + " -o " + page),
                "deep.json: arrays and objects are nested deeper than 64 levels");
  // A number past a double's range is the summary's fault, named with its file (the JSON
  // library's own error once escaped as "the report cannot be written as JSON").
  WriteText(run.dir / "huge.json", "{\"scene\": \"s.yaml\", \"t_end\": 1e99999}");
  for (const std::string command : {"report", "plot"}) {
    const std::string target =
        command == "plot" ? " t x -o " + Quote((run.dir / "p.svg").string()) : " -o " + page;
    ExpectRefused(RunCli(command + " " + Quote((run.dir / "huge.json").string()) + target),
                  "huge.json: not a chasles summary: [json.exception.out_of_range.406] number "
                  "overflow parsing '1e99999'");
  }
  // A run's CSV with a failed row (empty values, a reason) is refused at its line, not drawn
  // as NaN poses.
  std::string csv = ReadText(run.csv);
  std::vector<std::string> lines;
  for (std::stringstream s(csv); std::getline(s, csv);) lines.push_back(csv);
  const size_t fields = std::count(lines[0].begin(), lines[0].end(), ',') + 1;
  std::string failed = lines[0] + ",error\n" + lines[1] + ",\n" + lines[2] + ",\n" +
                       std::string(fields, ',') + "\"the run failed\"\n";
  for (size_t k = 3; k < lines.size(); ++k) failed += lines[k] + ",\n";
  WriteText(run.dir / "failed.csv", failed);
  j["csv"] = (run.dir / "failed.csv").string();
  WriteText(run.dir / "failed.json", j.dump());
  ExpectRefused(RunCli("report " + Quote((run.dir / "failed.json").string()) + " -o " + page),
                (run.dir / "failed.csv").string() + ":4: the row has no values (the run failed)");
  EXPECT_FALSE(fs::exists(run.dir / "r.html"));
  for (const std::string& f : Entries(run.dir)) EXPECT_THAT(f, Not(HasSubstr(".tmp")));
}

#ifdef CHASLES_HAVE_PLOT

TEST(ReadBack, PlotRefusesTextsPlplotCannotTakeAndWritesOnlyItsTarget) {
  const SpringFiles run = SpringRun("hostile_plot");
  const std::string json = Quote(run.json.string());
  const std::string svg = Quote((run.dir / "p.svg").string());
  ExpectRefused(
      RunCli("plot " + json + " t block_x -o " + svg + " --title " + Quote(std::string(2000, 'a'))),
      "--title: 2000 bytes, more than the 200");
  ExpectRefused(
      RunCli("plot " + json + " t block_x -o " + svg + " --title " + Quote(std::string(520, '#'))),
      "--title: 520 bytes");
  ExpectRefused(
      RunCli("plot " + json + " t block_x -o " + svg + " --title \"$(printf '\\377\\376')\""),
      "--title: the byte 1 (0xFF) is not valid UTF-8");
  // A column name of 1100 bytes in the CSV's header: named, refused before PLplot sees it.
  std::string csv = ReadText(run.csv);
  csv.replace(csv.find("block_x"), 7, std::string(1100, 'c'));
  WriteText(run.dir / "long.csv", csv);
  ExpectRefused(RunCli("plot " + Quote((run.dir / "long.csv").string()) + " t " +
                       std::string(1100, 'c') + " -o " + svg),
                "long.csv: the label of column 'cccc");
  ExpectRefused(RunCli("plot " + json + " t block_y -o " + svg + " --log"),
                "no point has x > 0 and y > 0");
  ExpectRefused(RunCli("plot " + json + " t block_x -o /proc/p.svg"),
                "no file can be created in the folder '/proc'");
  ExpectRefused(RunCli("plot /dev/zero t block_x -o " + svg + " --max-input-bytes 100000"),
                "/dev/zero: the table to plot is longer than the limit");
  ExpectRefused(RunCli("plot " + Quote(run.dir.string()) + " t block_x -o " + svg),
                ": this is a folder, not the table to plot");
  EXPECT_EQ(Entries(run.dir),
            (std::vector<std::string>{"long.csv", "spring-mass.csv", "spring-mass.json"}));
  // A name with '%' is the file's name, not a pattern PLplot expands.
  const CliResult percent =
      RunCli("plot " + json + " t block_x -o " + Quote((run.dir / "p%n.svg").string()));
  EXPECT_EQ(percent.exit_code, 0) << percent.err;
  EXPECT_THAT(ReadText(run.dir / "p%n.svg"), HasSubstr("<svg"));
  EXPECT_EQ(Entries(run.dir).size(), 4u);
}

#endif  // CHASLES_HAVE_PLOT

}  // namespace
}  // namespace chasles::test
