#include "chasles/files/output_set.h"

#include <sys/stat.h>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/error.h"

namespace chasles {
namespace {

namespace fs = std::filesystem;

std::string Read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path Scratch(const std::string& tag) {
  const fs::path dir = fs::temp_directory_path() / ("chasles_output_set_" + tag);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

size_t Count(const fs::path& dir) {
  size_t n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
  return n;
}

TEST(OutputSet, WritesEveryFileOnCommitAndNothingBefore) {
  const fs::path dir = Scratch("commit");
  OutputSet set;
  set.Add((dir / "a.csv").string(), "t\n0\n");
  set.Add((dir / "a.json").string(), "{}\n");
  EXPECT_EQ(Count(dir), 0u);
  set.Commit();
  EXPECT_EQ(Read(dir / "a.csv"), "t\n0\n");
  EXPECT_EQ(Read(dir / "a.json"), "{}\n");
  EXPECT_EQ(Count(dir), 2u);  // no temporary left
  fs::remove_all(dir);
}

TEST(OutputSet, ATargetThatBecomesAFolderDuringTheRunLeavesNoFileOfTheSet) {
  const fs::path dir = Scratch("fail");
  OutputSet set;
  set.Add((dir / "b.csv").string(), "t\n0\n");
  set.Add((dir / "b.json").string(), "{}\n");
  fs::create_directories(dir / "b.json");  // a folder in the second file's place
  EXPECT_THAT([&] { set.Commit(); },
              ::testing::ThrowsMessage<InputError>(::testing::HasSubstr(
                  "cannot write '" + (dir / "b.json").string() + "': it is a folder")));
  EXPECT_EQ(Count(dir), 1u);  // only the folder that was there
  fs::remove_all(dir);
}

// Two names of one file, standard output twice, and every kind of node that is not a regular
// file are refused when expected, before any work, naming the options.
TEST(OutputSet, ExpectRefusesTwoNamesOfOneFileAndNodesThatAreNotRegularFiles) {
  const fs::path dir = Scratch("expect");
  const auto message = [](const std::function<void()>& f) {
    try {
      f();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string a = (dir / "a.txt").string(), a2 = (dir / "." / "a.txt").string();
  EXPECT_EQ(
      message([&] {
        OutputSet set;
        set.Expect(a, "-o");
        set.Expect(a2, "--html");
      }),
      "-o '" + a + "' and --html '" + a2 + "' name the same file; give each output its own name");
  EXPECT_THAT(message([&] {
                OutputSet set;
                set.Expect("-", "-o");
                set.Expect("-", "--html");
              }),
              ::testing::HasSubstr("name the same output, standard output"));
  std::ofstream(dir / "real") << "x";
  fs::create_symlink(dir / "real", dir / "link");
  ASSERT_EQ(::mkfifo((dir / "fifo").c_str(), 0666), 0);
  EXPECT_THAT(message([&] { OutputSet().Expect((dir / "link").string(), "-o"); }),
              ::testing::HasSubstr("(-o): it is a symbolic link"));
  EXPECT_THAT(message([&] { OutputSet().Expect((dir / "fifo").string(), "-o"); }),
              ::testing::HasSubstr("(-o): it is a FIFO"));
  EXPECT_THAT(message([&] { OutputSet().Expect("/dev/null", "-o"); }),
              ::testing::HasSubstr("'/dev/null' (-o): it is a device"));
  EXPECT_THAT(message([&] { OutputSet().Expect(dir.string(), "-o"); }),
              ::testing::HasSubstr("it is a folder; give a file name"));
  EXPECT_EQ(Count(dir), 3u);  // real, link, fifo: nothing was written, no probe left
  fs::remove_all(dir);
}

// An --out folder is made at the commit, with its parents, and taken back if the commit fails.
TEST(OutputSet, AnExpectedFolderIsMadeAtCommitAndRemovedWhenTheCommitFails) {
  const fs::path dir = Scratch("folder");
  {
    OutputSet set;
    set.ExpectFolder((dir / "a/b").string(), "--out");
    set.Expect((dir / "a/b/r.csv").string(), "--out");
    EXPECT_FALSE(fs::exists(dir / "a"));
    set.Add((dir / "a/b/r.csv").string(), "t\n");
    set.Commit();
    EXPECT_EQ(Read(dir / "a/b/r.csv"), "t\n");
  }
  {
    OutputSet set;
    set.ExpectFolder((dir / "c/d").string(), "--out");
    set.Add((dir / "c/d/r.csv").string(), "t\n");
    set.Add((dir / "c/d/r.json").string(), "{}\n");
    fs::create_directories(dir / "c/d/r.json");  // made during the run: the commit fails
    EXPECT_THROW(set.Commit(), InputError);
    EXPECT_EQ(Count(dir / "c/d"), 1u);  // the folder put there; the set made none of it
  }
  fs::remove_all(dir);
}

// The state is per set: 64 threads committing 300 sets of three files at once all succeed
// and leave no temporary (a fixed table of 32 temporaries once refused most of them).
TEST(OutputSet, ManySetsCommitFromManyThreadsAtOnce) {
  const fs::path dir = Scratch("threads");
  constexpr int kThreads = 64, kSets = 300;
  std::atomic<int> next{0}, failed{0};
  std::vector<std::thread> pool;
  for (int t = 0; t < kThreads; ++t) {
    pool.emplace_back([&] {
      for (int k; (k = next++) < kSets;) {
        try {
          OutputSet set;
          for (const char* ext : {".csv", ".json", ".html"}) {
            set.Add((dir / (std::to_string(k) + ext)).string(), std::string(4096, 'x'));
          }
          set.Commit();
        } catch (const InputError&) {
          ++failed;
        }
      }
    });
  }
  for (std::thread& t : pool) t.join();
  EXPECT_EQ(failed, 0);
  EXPECT_EQ(Count(dir), 3u * kSets);
  fs::remove_all(dir);
}

TEST(OutputSet, SetsThatAreNeverCommittedWriteNothing) {
  const fs::path dir = Scratch("abandon");
  {
    OutputSet set;
    set.Add((dir / "c.csv").string(), "t\n");
  }
  EXPECT_EQ(Count(dir), 0u);
  fs::remove_all(dir);
}

TEST(CheckOutputTarget, NamesTheReason) {
  const fs::path dir = Scratch("target");
  std::ofstream(dir / "plain") << "x";
  const auto message = [](const std::string& path) {
    try {
      CheckOutputTarget(path);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message((dir / "r.txt").string()), "no error");
  EXPECT_EQ(Count(dir), 1u);  // the probe of the folder was removed
  EXPECT_EQ(message((dir / "none/r.txt").string()),
            "cannot write '" + (dir / "none/r.txt").string() + "': the folder '" +
                (dir / "none").string() + "' does not exist (create it first)");
  EXPECT_EQ(message(dir.string()),
            "cannot write '" + dir.string() + "': it is a folder; give a file name");
  EXPECT_EQ(message((dir / "plain/x/r.txt").string()),
            "cannot write '" + (dir / "plain/x/r.txt").string() + "': '" +
                (dir / "plain").string() + "' is a file, not a folder");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace chasles
