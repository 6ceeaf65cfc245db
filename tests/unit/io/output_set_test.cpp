#include "chasles/io/output_set.h"

#include <filesystem>
#include <fstream>
#include <sstream>

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

TEST(OutputSet, ATargetThatCannotBeWrittenLeavesNoFileOfTheSet) {
  const fs::path dir = Scratch("fail");
  fs::create_directories(dir / "b.json");  // a folder in the second file's place
  OutputSet set;
  set.Add((dir / "b.csv").string(), "t\n0\n");
  set.Add((dir / "b.json").string(), "{}\n");
  EXPECT_THAT([&] { set.Commit(); },
              ::testing::ThrowsMessage<InputError>(::testing::HasSubstr(
                  "cannot write '" + (dir / "b.json").string() + "': it is a folder")));
  EXPECT_EQ(Count(dir), 1u);  // only the folder that was there
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
