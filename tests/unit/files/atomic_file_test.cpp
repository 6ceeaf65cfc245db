#include "chasles/files/atomic_file.h"

#include "chasles/error.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace chasles {
namespace {

std::string Read(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(AtomicFile, WritesAndReplacesLeavingNoTemporary) {
  const auto dir = std::filesystem::temp_directory_path() / "chasles_atomic_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto file = dir / "report.txt";
  WriteFileAtomically(file.string(), "first");
  EXPECT_EQ(Read(file), "first");
  WriteFileAtomically(file.string(), "second, longer");
  EXPECT_EQ(Read(file), "second, longer");
  size_t entries = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++entries;
  EXPECT_EQ(entries, 1u);  // only the report: the temporary was renamed over it
  std::filesystem::remove_all(dir);
}

TEST(AtomicFile, UnwritablePlaceIsAnErrorNamingThePath) {
  EXPECT_THAT(
      [] { WriteFileAtomically("/nonexistent-dir/x/report.txt", "data"); },
      ::testing::ThrowsMessage<InputError>(::testing::HasSubstr("/nonexistent-dir/x/report.txt")));
}

}  // namespace
}  // namespace chasles
