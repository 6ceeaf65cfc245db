// The exit-code promise for files and encodings, the scene size limit, no non-finite number
// printed, and all-or-nothing outputs (docs/reliability-io.md).

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_runner.h"
#include "test_paths.h"
#include "test_support.h"

namespace chasles::test {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

const std::string kCube = "examples/section-8.5-cube.yaml";

void WriteText(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

std::vector<std::string> Entries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(OutputPaths, MassOutputIntoAMissingFolderOntoAFolderOrUnderAFileIsExit2) {
  const fs::path dir = OutDir("io_paths");
  const std::string scene = Quote(SourcePath(kCube));
  const CliResult missing = RunCli("mass " + scene + " -o " + Quote((dir / "nope/r.txt").string()));
  EXPECT_EQ(missing.exit_code, 2) << missing.err;
  EXPECT_THAT(missing.err,
              HasSubstr("cannot write '" + (dir / "nope/r.txt").string() + "' (-o): the folder '" +
                        (dir / "nope").string() + "' does not exist"));
  const CliResult folder = RunCli("mass " + scene + " -o " + Quote(dir.string()));
  EXPECT_EQ(folder.exit_code, 2) << folder.err;
  EXPECT_THAT(folder.err, HasSubstr("cannot write '" + dir.string() + "' (-o): it is a folder"));
  WriteText(dir / "plain", "x");
  const CliResult under = RunCli("mass " + scene + " -o " + Quote((dir / "plain/r.txt").string()));
  EXPECT_EQ(under.exit_code, 2) << under.err;
  EXPECT_THAT(under.err, HasSubstr("'" + (dir / "plain").string() + "' is a file, not a folder"));
  const CliResult deeper =
      RunCli("mass " + scene + " -o " + Quote((dir / "plain/a/b/r.txt").string()));
  EXPECT_EQ(deeper.exit_code, 2) << deeper.err;
  EXPECT_THAT(deeper.err, HasSubstr("'" + (dir / "plain").string() + "' is a file, not a folder"));
  for (const CliResult* r : {&missing, &folder, &under, &deeper}) {
    EXPECT_THAT(r->err, ::testing::Not(HasSubstr("internal error")));
    EXPECT_TRUE(r->out.empty());
  }
  EXPECT_EQ(Entries(dir), std::vector<std::string>{"plain"});  // nothing else was written
  fs::remove_all(dir);
}

TEST(OutputPaths, SimulateOutUnderAFileIsExit2) {
  const fs::path dir = OutDir("io_simout");
  WriteText(dir / "plain", "x");
  const std::string scene = Quote(SourcePath("examples/spring-mass.yaml"));
  const CliResult onto =
      RunCli("simulate " + scene + " --until 0.01 --out " + Quote((dir / "plain").string()));
  EXPECT_EQ(onto.exit_code, 2) << onto.err;
  EXPECT_THAT(onto.err,
              HasSubstr("cannot create the output folder '" + (dir / "plain").string() +
                        "' (--out): '" + (dir / "plain").string() + "' is a file, not a folder"));
  const CliResult under =
      RunCli("simulate " + scene + " --until 0.01 --out " + Quote((dir / "plain/sub").string()));
  EXPECT_EQ(under.exit_code, 2) << under.err;
  EXPECT_THAT(under.err, HasSubstr("'" + (dir / "plain").string() + "' is a file, not a folder"));
  fs::remove_all(dir);
}

TEST(CommandLine, AnEmptyArgumentThenAnUnknownOptionIsExit2) {
  // Once a parse that never ended (found by the command-line fuzz target; the input is in
  // fuzz/regressions/cli/): an empty extra argument, then an option mass does not know.
  const CliResult r = RunCli("mass fuzz/corpus/mesh/cube.off '' --unit mm --density@7850");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("--density@7850"));
  EXPECT_TRUE(r.out.empty());
}

TEST(CommandLine, UntilMustBeAPositiveFiniteTime) {
  const std::string scene = Quote(SourcePath("examples/spring-mass.yaml"));
  for (const std::string bad : {"nan", "inf", "-inf", "-1", "0", "1e999", "2s"}) {
    const CliResult r = RunCli("simulate " + scene + " --until " + bad);
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.err;
    EXPECT_THAT(r.err, HasSubstr("--until")) << bad;
    EXPECT_THAT(r.err, HasSubstr("--until must be a positive time in seconds (a positive, "
                                 "finite number), got '" +
                                 bad + "'"))
        << bad;
    EXPECT_TRUE(r.out.empty()) << bad;
  }
}

TEST(SceneFiles, EndlessOrNonRegularInputIsReadWithTheCap) {
  const CliResult zero = RunCli("check /dev/zero");
  EXPECT_EQ(zero.exit_code, 2) << zero.err;
  EXPECT_THAT(zero.err, HasSubstr("/dev/zero: the scene is longer than the maximum scene size "
                                  "of 16777216 bytes (16.0 MiB)"));
  EXPECT_THAT(zero.err, HasSubstr("--max-scene-bytes"));
  // A pipe is read too, within the cap.
  const std::string cube = Quote(SourcePath(kCube));
  const CliResult pipe = RunCli("check /dev/stdin < " + cube);
  EXPECT_EQ(pipe.exit_code, 0) << pipe.err;
  EXPECT_THAT(pipe.out, HasSubstr("/dev/stdin: ok"));
  const CliResult small = RunCli("check /dev/stdin --max-scene-bytes 100 < " + cube);
  EXPECT_EQ(small.exit_code, 2) << small.err;
  EXPECT_THAT(small.err, HasSubstr("more than the maximum scene size of 100 bytes"));
  const CliResult folder = RunCli("check " + Quote(SourcePath("examples")));
  EXPECT_EQ(folder.exit_code, 2) << folder.err;
  EXPECT_THAT(folder.err, HasSubstr("examples: this is a folder, not a scene file"));
}

/// A scene of `parts` spheres in one body, one flow-style line each.
std::string ManyParts(size_t parts) {
  std::string text = "bodies:\n  - name: cloud\n    parts:\n";
  for (size_t i = 0; i < parts; ++i) {
    text += "      - {shape: sphere, radius: 1 cm, mass: 1 g, position: [" + std::to_string(i) +
            " mm, " + std::to_string(i % 97) + " mm, 0]}\n";
  }
  return text;
}

TEST(SceneFiles, TheHundredMegabyteSceneIsRefusedBeforeParsingAndALargeOneLoads) {
  const fs::path dir = OutDir("io_size");
  // 1.2 million parts: some 100 MB. Refused by its size before a byte is parsed.
  const fs::path huge = dir / "huge.yaml";
  {
    std::ofstream out(huge, std::ios::binary);
    const std::string chunk = ManyParts(10000).substr(35);  // the lines of 10 000 parts
    out << "bodies:\n  - name: cloud\n    parts:\n";
    for (int k = 0; k < 120; ++k) out << chunk;
  }
  ASSERT_GT(fs::file_size(huge), size_t{90} << 20);
  const auto start = std::chrono::steady_clock::now();
  const CliResult refused = RunCli("check " + Quote(huge.string()));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(refused.exit_code, 2) << refused.err;
  EXPECT_THAT(refused.err, HasSubstr(huge.string() + ": the scene is " +
                                     std::to_string(fs::file_size(huge)) + " bytes"));
  EXPECT_THAT(refused.err, HasSubstr("more than the maximum scene size of 16777216 bytes"));
  EXPECT_LT(seconds, 5.0);  // refused by its size, not after reading and parsing it
  fs::remove(huge);
  // 10 000 parts (about 0.8 MB): loads, and every part is counted.
  const fs::path large = dir / "large.yaml";
  WriteText(large, ManyParts(10000));
  const CliResult loaded = RunCli("check " + Quote(large.string()));
  EXPECT_EQ(loaded.exit_code, 0) << loaded.err;
  EXPECT_THAT(loaded.out, HasSubstr("ok (1 body, 10000 parts"));
  const CliResult lowered = RunCli("check " + Quote(large.string()) + " --max-scene-bytes 100000");
  EXPECT_EQ(lowered.exit_code, 2);
  EXPECT_THAT(lowered.err, HasSubstr("more than the maximum scene size of 100000 bytes"));
  fs::remove_all(dir);
}

TEST(SceneFiles, InvalidUtf8InAnOverrideOrOptionIsExit2) {
  const std::string cube = Quote(SourcePath("examples/example-8.1-cylinder.yaml"));
  const CliResult set = RunCli("mass " + cube + " --set \"$(printf 'ratio=0.3\\377')\"");
  EXPECT_EQ(set.exit_code, 2) << set.err;
  EXPECT_THAT(set.err, HasSubstr("command line --set:1:10: the byte 0xFF is not valid UTF-8"));
}

TEST(PrintedValues, APartAt1e200MetresPrintsWhereItIs) {
  // One 1 kg sphere centred at x = 1e200 m: the body's centre of mass is there too, and its
  // central inertia is the sphere's own, 2/5 m r² = 0.4 kg*m^2 (r = 1 m).
  const fs::path dir = OutDir("io_far");
  const fs::path scene = dir / "far.yaml";
  WriteText(
      scene,
      "bodies:\n  - name: far\n    parts:\n"
      "      - {shape: sphere, radius: 1 m, mass: 1 kg, position: [1e200 m, -2e200 m, 3 m]}\n");
  const CliResult text = RunCli("mass " + Quote(scene.string()) + " --units SI");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_THAT(text.out, HasSubstr("Centre of mass      [1e+200, -2e+200, 0] m"));
  // The radii of gyration are the sphere's own, sqrt(0.4 / 1) m = 0.632455532 m, however far
  // the body is from its origin (they were once rounded against the 1e200 m position to 0).
  EXPECT_THAT(text.out, HasSubstr("centre of mass: [0.6324555, 0.6324555, 0.6324555] m"));
  const CliResult json = RunCli("mass " + Quote(scene.string()) + " --units SI --format json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const nlohmann::json b = nlohmann::json::parse(json.out)["bodies"][0];
  EXPECT_EQ(b["center_of_mass"][0].get<double>(), 1e200);
  EXPECT_EQ(b["center_of_mass"][1].get<double>(), -2e200);
  EXPECT_NEAR(b["principal_moments"][0].get<double>(), 0.4, 0.4e-12);
  fs::remove_all(dir);
}

TEST(PrintedValues, AUnitConversionThatOverflowsIsExit2NamingTheQuantity) {
  // 1e306 m is 1e309 mm: past the largest double (1.8e308) in the units asked for.
  const fs::path dir = OutDir("io_units");
  const fs::path scene = dir / "far.yaml";
  WriteText(scene,
            "bodies:\n  - name: far\n    parts:\n"
            "      - {shape: sphere, radius: 1 m, mass: 1 kg, position: [1e306 m, 0, 0]}\n");
  for (const std::string format : {"text", "json"}) {
    const CliResult r =
        RunCli("mass " + Quote(scene.string()) + " --units mm,kg --format " + format);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_THAT(r.err, HasSubstr("the mass report: bodies[0].center_of_mass[0] (body 'far') is "
                                 "inf, not a finite number"));
    EXPECT_TRUE(r.out.empty());
  }
  fs::remove_all(dir);
}

TEST(PrintedValues, SolveAndSimulateRefuseABodyPlaced1e200MetresOutAtItsPosition) {
  // A body at 1e200 m: its energies and the certificate's length scale (squared: 1e400) would
  // leave double precision. Refused at the position's value (line 4, column 25), for every
  // output format, before anything overflows.
  const fs::path dir = OutDir("io_solve");
  const fs::path scene = dir / "far.yaml";
  WriteText(scene,
            "bodies:\n  - name: far\n    parts: [{shape: sphere, radius: 1 m, mass: 1 kg}]\n"
            "    initial: {position: [1e200 m, 0, 0]}\n");
  const std::vector<std::string> commands = {"solve --format text", "solve --format json",
                                             "simulate --out " + Quote(dir.string())};
  for (const std::string& command : commands) {
    const CliResult r = RunCli(command.substr(0, command.find(' ')) + " " + Quote(scene.string()) +
                               command.substr(command.find(' ')));
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_THAT(r.err, HasSubstr(scene.string() + ":4:25: bodies[0].initial.position: the "
                                                  "initial position has a magnitude of 1e+200 m"));
    EXPECT_TRUE(r.out.empty());
  }
  EXPECT_EQ(Entries(dir), std::vector<std::string>{"far.yaml"});
  fs::remove_all(dir);
}

// --- all-or-nothing outputs -------------------------------------------------------------

/// Starts `chasles ARGS...` with its output thrown away; returns the process id.
pid_t Start(const std::vector<std::string>& args) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(chasles::test::CliPath()));
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    std::freopen("/dev/null", "w", stdout);
    std::freopen("/dev/null", "w", stderr);
    ::execv(chasles::test::CliPath(), argv.data());
    ::_exit(127);
  }
  return pid;
}

int Wait(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return status;
}

TEST(AllOrNothing, SigtermAtTwentyOffsetsLeavesAllTheFilesOrNone) {
  // spring-mass to 100 s at 10 ms output: 10 000 CSV rows (1.6 MB) and 318 events in the JSON,
  // about 0.2 s of work (more under load: the offsets follow the measured time, and 21 runs must
  // stay well inside the test's time limit). Under the sanitizers, ten times slower, to 20 s.
  const std::string scene = SourcePath("examples/spring-mass.yaml");
  const std::string until = kAddressSanitizer ? "20" : "100";
  const std::vector<std::string> base = {"simulate", scene, "--until", until, "--format", "json"};
  const fs::path dir = OutDir("io_sigterm");
  // A full run first: how long it takes and what it writes.
  const fs::path full = dir / "full";
  std::vector<std::string> args = base;
  args.insert(args.end(), {"--out", full.string()});
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_TRUE(WIFEXITED(Wait(Start(args))));
  const double duration =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const size_t rows = ReadCsv((full / "spring-mass.csv").string()).at("t").size();
  ASSERT_GT(rows, 1000u);
  int complete = 0, none = 0;
  for (int k = 0; k < 20; ++k) {
    const fs::path out = dir / ("run" + std::to_string(k));
    fs::create_directories(out);
    args = base;
    args.insert(args.end(), {"--out", out.string()});
    const pid_t pid = Start(args);
    if (k < 19) {
      // Offsets spread evenly from 6 % to 114 % of the full run's time: during the
      // integration, while the reports are made and the files written, and (on an idle
      // machine) after the run has ended.
      const double fraction = 0.06 * (k + 1);
      std::this_thread::sleep_for(std::chrono::duration<double>(fraction * duration));
    } else {
      // The last signal the moment both files are in place, however slow the machine is
      // today: they must stay complete.
      const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(120);
      while (!(fs::exists(out / "spring-mass.csv") && fs::exists(out / "spring-mass.json")) &&
             std::chrono::steady_clock::now() < give_up) {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
    }
    ::kill(pid, SIGTERM);
    const int status = Wait(pid);
    EXPECT_TRUE(WIFSIGNALED(status) || (WIFEXITED(status) && WEXITSTATUS(status) == 0));
    const std::vector<std::string> names = Entries(out);
    for (const auto& n : names) EXPECT_THAT(n, ::testing::Not(HasSubstr(".tmp"))) << k;
    if (names.empty()) {
      ++none;
      continue;
    }
    ASSERT_EQ(names, (std::vector<std::string>{"spring-mass.csv", "spring-mass.json"})) << k;
    ++complete;
    EXPECT_EQ(ReadCsv((out / "spring-mass.csv").string()).at("t").size(), rows) << k;
    std::ifstream in(out / "spring-mass.json");
    const nlohmann::json j = nlohmann::json::parse(in);  // throws (fails) if cut short
    EXPECT_EQ(j["t_end"].get<double>(), std::stod(until)) << k;
  }
  EXPECT_EQ(complete + none, 20);
  std::printf("SIGTERM at 20 offsets of a %.2f s run: %d left both files, %d left none\n", duration,
              complete, none);
  EXPECT_GT(none, 0);      // the early signals did stop runs
  EXPECT_GT(complete, 0);  // the late ones came after the files were in place
  fs::remove_all(dir);
}

TEST(AllOrNothing, SigtermWhileATemporaryExistsRemovesIt) {
  // The signal sent the moment a temporary appears (the files are being written): the
  // handler removes it and the process ends by the signal, leaving no file at all.
  const fs::path dir = OutDir("io_sigtmp");
  int caught = 0;
  for (int attempt = 0; attempt < 3; ++attempt) {
    const fs::path out = dir / ("run" + std::to_string(attempt));
    fs::create_directories(out);
    // A long run, so that the look for a temporary starts well before the files are written
    // (a fifth of it under the sanitizers, which are ten times slower).
    const pid_t pid = Start({"simulate", SourcePath("examples/spring-mass.yaml"), "--until",
                             kAddressSanitizer ? "80" : "400", "--out", out.string()});
    bool seen = false;
    int status = 0;
    while (!seen && ::waitpid(pid, &status, WNOHANG) == 0) {
      for (const auto& name : Entries(out)) seen = seen || name.find(".tmp") != std::string::npos;
      if (!seen) std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    if (!seen) continue;  // the run wrote its files between two looks: try again
    ::kill(pid, SIGTERM);
    status = Wait(pid);
    ++caught;
    const std::vector<std::string> names = Entries(out);
    // Killed while writing: nothing; or the renames had just been done: both files.
    if (!names.empty()) {
      EXPECT_EQ(names, (std::vector<std::string>{"spring-mass.csv", "spring-mass.json"}));
    }
    // (A run that finished between the look and the signal exits 0 with both files.)
    EXPECT_TRUE(WIFSIGNALED(status) ? WTERMSIG(status) == SIGTERM : WEXITSTATUS(status) == 0);
  }
  EXPECT_GT(caught, 0) << "never saw a temporary: the test did not test the handler";
  fs::remove_all(dir);
}

std::string ReadBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST(AllOrNothing, SigtermDuringASweepLeavesEachKeptRunWholeOrAbsent) {
  // A sweep of 60 spring-mass runs on 4 threads, each run's CSV and JSON kept, killed by
  // SIGTERM at 20 seeded random instants: whatever the instant (while runs integrate, while
  // several threads write their pairs, after the end), the folder holds no temporary, and
  // every run in it has both files, its CSV byte for byte that of an undisturbed sweep and
  // its JSON whole. Under the sanitizers, ten times slower, the runs are a fifth as long.
  const std::string until = kAddressSanitizer ? "1" : "5";
  const std::vector<std::string> base = {"simulate",
                                         SourcePath("examples/spring-mass.yaml"),
                                         "--quiet",
                                         "--until",
                                         until,
                                         "--sweep",
                                         "k=100 N/m:1000 N/m:60",
                                         "--quantity",
                                         "max(block_x)",
                                         "--jobs",
                                         "4",
                                         "--keep-runs"};
  const fs::path dir = OutDir("io_sigterm_sweep");
  std::vector<std::string> args = base;
  args.push_back((dir / "full").string());
  const auto t0 = std::chrono::steady_clock::now();
  const int full_status = Wait(Start(args));
  ASSERT_TRUE(WIFEXITED(full_status) && WEXITSTATUS(full_status) == 0);
  const double duration =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::vector<std::string> all = Entries(dir / "full");
  ASSERT_EQ(all.size(), 120u);  // a CSV and a JSON per point
  std::mt19937 rng(20261128);
  std::uniform_real_distribution<double> instant(0.0, 1.2);  // of the undisturbed sweep's time
  int none = 0, some = 0, every = 0;
  for (int k = 0; k < 20; ++k) {
    const fs::path out = dir / ("run" + std::to_string(k));
    args = base;
    args.push_back(out.string());
    const pid_t pid = Start(args);
    std::this_thread::sleep_for(std::chrono::duration<double>(instant(rng) * duration));
    ::kill(pid, SIGTERM);
    const int status = Wait(pid);
    EXPECT_TRUE(WIFSIGNALED(status) ? WTERMSIG(status) == SIGTERM : WEXITSTATUS(status) == 0) << k;
    const std::vector<std::string> names =
        fs::exists(out) ? Entries(out) : std::vector<std::string>{};
    for (const std::string& n : names) {
      EXPECT_THAT(n, ::testing::Not(HasSubstr(".tmp"))) << k;
      const fs::path stem = fs::path(n).stem();
      EXPECT_TRUE(fs::exists(out / (stem.string() + ".csv")) &&
                  fs::exists(out / (stem.string() + ".json")))
          << k << ": " << n << " without its pair";
      if (fs::path(n).extension() == ".csv") {
        EXPECT_EQ(ReadBytes(out / n), ReadBytes(dir / "full" / n)) << k << ": " << n;
      } else {
        const nlohmann::json j = nlohmann::json::parse(ReadBytes(out / n));  // throws if cut
        EXPECT_EQ(j.at("t_end").get<double>(), std::stod(until)) << k << ": " << n;
      }
    }
    ++(names.empty() ? none : names.size() == all.size() ? every : some);
  }
  std::printf("SIGTERM at 20 instants of a %.2f s sweep: %d left no run, %d some, %d all\n",
              duration, none, some, every);
  EXPECT_GT(none + some, 0);  // signals came before the sweep's end
  fs::remove_all(dir);
}

TEST(AllOrNothing, AJsonThatCannotBeWrittenLeavesNoCsv) {
  const fs::path dir = OutDir("io_fail");
  fs::create_directories(dir / "spring-mass.json");  // a folder where the JSON should go
  const CliResult r = RunCli("simulate " + Quote(SourcePath("examples/spring-mass.yaml")) +
                             " --until 0.1 --out " + Quote(dir.string()));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("cannot write '" + (dir / "spring-mass.json").string() +
                               "' (--out): it is a folder"));
  EXPECT_EQ(Entries(dir), std::vector<std::string>{"spring-mass.json"});  // no CSV, no .tmp
  EXPECT_TRUE(fs::is_empty(dir / "spring-mass.json"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace chasles::test
