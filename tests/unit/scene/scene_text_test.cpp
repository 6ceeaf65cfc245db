#include "scene/internal/scene_text.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/scene/scene_error.h"

namespace chasles::scene_internal {
namespace {

/// "LINE:COL MESSAGE" of the SceneError CheckSceneText throws, or "ok".
std::string Check(const std::string& text) {
  try {
    CheckSceneText(text, "s.yaml");
  } catch (const SceneError& e) {
    return std::to_string(e.line()) + ":" + std::to_string(e.column()) + " " + e.message();
  }
  return "ok";
}

TEST(SceneText, WellFormedUtf8OfEveryLengthPasses) {
  // 1 to 4 bytes: 'a' U+0061, 'é' U+00E9, '日' U+65E5, U+1F600; the extremes U+007F, U+07FF,
  // U+FFFF, U+10FFFF, and U+E000 just past the surrogates.
  EXPECT_EQ(Check("title: a\xC3\xA9\xE6\x97\xA5\xF0\x9F\x98\x80\n"), "ok");
  EXPECT_EQ(Check("\x7F\xDF\xBF\xEF\xBF\xBF\xF4\x8F\xBF\xBF\xEE\x80\x80"), "ok");
  EXPECT_EQ(Check(""), "ok");
}

TEST(SceneText, EveryIllFormedSequenceIsRefusedAtItsLineAndByteColumn) {
  EXPECT_EQ(Check("a: 1\nb: \xFF\n"),
            "2:4 the byte 0xFF is not valid UTF-8; a scene file must be UTF-8 text");
  // Overlong forms of '/' (2, 3, 4 bytes), a surrogate, beyond U+10FFFF, a lone continuation.
  EXPECT_THAT(Check("\xC0\xAF"), ::testing::StartsWith("1:1 the byte 0xC0 is not valid"));
  EXPECT_THAT(Check("x\xE0\x80\xAF"), ::testing::StartsWith("1:2 the bytes 0xE0 0x80 are"));
  EXPECT_THAT(Check("\xF0\x80\x80\xAF"), ::testing::StartsWith("1:1 the bytes 0xF0 0x80"));
  EXPECT_THAT(Check("\xED\xA0\x80"), ::testing::StartsWith("1:1 the bytes 0xED 0xA0"));
  EXPECT_THAT(Check("\xF4\x90\x80\x80"), ::testing::StartsWith("1:1 the bytes 0xF4 0x90"));
  EXPECT_THAT(Check("\xF5\x80\x80\x80"), ::testing::StartsWith("1:1 the byte 0xF5"));
  EXPECT_THAT(Check("ab\x80"), ::testing::StartsWith("1:3 the byte 0x80"));
  // A character cut short: by the end of the text, and by a plain byte.
  EXPECT_THAT(Check("\n\nab\xE6\x97"), ::testing::StartsWith("3:3 the text ends inside"));
  EXPECT_THAT(Check("\xE6\x97z"),
              ::testing::StartsWith("1:1 the bytes 0xE6 0x97 0x7A are not valid"));
}

TEST(SceneText, NulBytesAreRefused) {
  EXPECT_EQ(Check(std::string("a: 1\nbb\0", 8)),
            "2:3 a NUL byte (0x00); a scene file must be UTF-8 text");
}

}  // namespace
}  // namespace chasles::scene_internal
