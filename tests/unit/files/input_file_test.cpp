#include "chasles/files/input_file.h"

#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "chasles/error.h"

namespace chasles {
namespace {

/// What the handler was called with, thrown back so the test can look at it.
struct Stopped {
  CappedReadFailure failure;
};

CappedReadFailure FailureOf(const std::string& path, size_t max_bytes) {
  try {
    ReadCappedFile(path, max_bytes, [](const CappedReadFailure& f) { throw Stopped{f}; });
  } catch (const Stopped& s) {
    return s.failure;
  }
  ADD_FAILURE() << path << " was read";
  return {};
}

class CappedRead : public ::testing::Test {
 protected:
  void SetUp() override {
    // One folder per process and test: ctest runs the tests of this file in parallel.
    dir_ = std::filesystem::temp_directory_path() /
           ("chasles_capped_read_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string Write(const std::string& name, const std::string& bytes) {
    const auto path = dir_ / name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path.string();
  }
  std::filesystem::path dir_;
};

TEST_F(CappedRead, AFileAtTheCapIsReadWhole) {
  const std::string bytes("line one\n\0line two", 18);
  EXPECT_EQ(ReadCappedFile(Write("at_cap", bytes), 18,
                           [](const CappedReadFailure&) { FAIL() << "refused"; }),
            bytes);
}

TEST_F(CappedRead, ARegularFileOneBytePastTheCapIsRefusedByItsSize) {
  const CappedReadFailure f = FailureOf(Write("past_cap", std::string(19, 'x')), 18);
  EXPECT_EQ(f.kind, CappedReadFailure::Kind::kTooLarge);
  ASSERT_TRUE(f.size.has_value());
  EXPECT_EQ(*f.size, 19u);
}

TEST_F(CappedRead, ADeviceThatNeverEndsIsRefusedWithoutASize) {
  const CappedReadFailure f = FailureOf("/dev/zero", 1000);
  EXPECT_EQ(f.kind, CappedReadFailure::Kind::kTooLarge);
  EXPECT_FALSE(f.size.has_value());
}

TEST_F(CappedRead, AFolderAndAMissingFileAreNamedAsSuch) {
  EXPECT_EQ(FailureOf(dir_.string(), 100).kind, CappedReadFailure::Kind::kFolder);
  const CappedReadFailure missing = FailureOf((dir_ / "absent").string(), 100);
  EXPECT_EQ(missing.kind, CappedReadFailure::Kind::kOpen);
  EXPECT_EQ(missing.error, ENOENT);
}

TEST_F(CappedRead, AHandlerThatDoesNotThrowIsAProgrammingError) {
  EXPECT_THROW(ReadCappedFile((dir_ / "absent").string(), 100, [](const CappedReadFailure&) {}),
               std::logic_error);
}

TEST_F(CappedRead, ReadInputFileWordsEachFailureWithWhatAndTheOption) {
  const std::string big = Write("big", std::string(2000, 'x'));
  try {
    ReadInputFile(big, "the table to plot", 1000, "--max-input-bytes N");
    FAIL() << "read";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              big +
                  ": the table to plot is 2000 bytes (0.0 MiB), more than the limit of 1000 "
                  "bytes (0.0 MiB); it is refused before it is parsed (raise the limit with "
                  "--max-input-bytes N if it is meant to be read)");
  }
}

TEST(FormatByteSize, GivesBytesAndMebibytes) {
  EXPECT_EQ(FormatByteSize(1048577), "1048577 bytes (1.0 MiB)");
  EXPECT_EQ(FormatByteSize(0), "0 bytes (0.0 MiB)");
}

}  // namespace
}  // namespace chasles
