// The names the outputs give the study results' enums, and their reading back.

#include "chasles/report/result_names.h"

#include <gtest/gtest.h>

#include "chasles/error.h"

namespace chasles {
namespace {

// The names are those the JSON summary and Python give: fixed strings.
TEST(ResultNames, JumpKindsHaveTheSummaryNamesAndReadBack) {
  const std::pair<StudyJumpKind, const char*> kinds[] = {
      {StudyJumpKind::kImpulse, "impulse"},
      {StudyJumpKind::kEmbedding, "embedding"},
      {StudyJumpKind::kPassThrough, "pass-through"}};
  for (const auto& [kind, name] : kinds) {
    EXPECT_STREQ(StudyJumpKindName(kind), name);
    EXPECT_EQ(ParseStudyJumpKind(name, "run.json: jumps"), kind);
  }
}

TEST(ResultNames, AnUnknownJumpKindIsAnInputErrorNamingWhere) {
  try {
    ParseStudyJumpKind("bounce", "run.json: jumps");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "run.json: jumps: unknown jump kind 'bounce'; expected 'impulse', 'embedding' or "
                 "'pass-through'");
  }
}

}  // namespace
}  // namespace chasles
