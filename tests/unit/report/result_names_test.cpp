// The names the outputs give the study results' enums, and their reading back.

#include "chasles/report/result_names.h"

#include <gmock/gmock.h>
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

TEST(ResultNames, ContactModesHaveTheSummaryNamesAndReadBack) {
  const std::pair<StudyContactMode, const char*> modes[] = {
      {{ContactMode::kSeparated, false}, "separated"},
      {{ContactMode::kSliding, false}, "sliding"},
      {{ContactMode::kSticking, false}, "sticking"},
      {{ContactMode::kSticking, true}, "sticking, rolling held"}};
  for (const auto& [mode, name] : modes) {
    EXPECT_STREQ(StudyContactModeName(mode), name);
    EXPECT_EQ(ParseStudyContactMode(name, "run.json: contact_events: from"), mode);
  }
  EXPECT_THROW(ParseStudyContactMode("rolling", "run.json"), InputError);
}

TEST(ResultNames, ContactEventReasonsReadBack) {
  const std::pair<ContactEventReason, const char*> reasons[] = {
      {ContactEventReason::kInitial, "initial"},
      {ContactEventReason::kSlipStopped, "slip stopped"},
      {ContactEventReason::kOther, "re-selection"},
      {ContactEventReason::kImpulse, "impulse"},
      {ContactEventReason::kEngineSwitch, "engine switch"},
      {ContactEventReason::kTimeStep, "time step"}};
  for (const auto& [reason, name] : reasons) {
    EXPECT_STREQ(ContactEventReasonName(reason), name);
    EXPECT_EQ(ParseContactEventReason(name, "run.json: contact_events: reason"), reason);
  }
  try {
    ParseContactEventReason("slipped", "run.json: contact_events: reason");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), ::testing::StartsWith("run.json: contact_events: reason: unknown contact "
                                                "mode change reason 'slipped'; expected one of "
                                                "'initial', 'touch-down', "));
  }
}

TEST(ResultNames, StringsAndIntegratorsHaveTheSummaryNames) {
  EXPECT_STREQ(StringModeName(ConstraintMode::kEngaged), "taut");
  EXPECT_STREQ(StringModeName(ConstraintMode::kReleased), "slack");
  EXPECT_STREQ(ConstraintEventReasonName(ConstraintEventReason::kInitial), "initial");
  EXPECT_STREQ(ConstraintEventReasonName(ConstraintEventReason::kWentSlack), "went slack");
  EXPECT_STREQ(ConstraintEventReasonName(ConstraintEventReason::kSnappedTaut), "snapped taut");
  EXPECT_STREQ(ConstraintEventReasonName(ConstraintEventReason::kWentTaut), "went taut");
  EXPECT_STREQ(StudyIntegratorName(EngineRequest::kEvents, IntegratorKind::kRk4), "events");
  EXPECT_STREQ(StudyIntegratorName(EngineRequest::kStepping, IntegratorKind::kRk4), "stepping");
  EXPECT_STREQ(StudyIntegratorName(EngineRequest::kAuto, IntegratorKind::kRk4), "auto");
  EXPECT_STREQ(StudyIntegratorName(EngineRequest::kIntegrator, IntegratorKind::kRk4),
               "RK4 (fixed step)");
}

}  // namespace
}  // namespace chasles
