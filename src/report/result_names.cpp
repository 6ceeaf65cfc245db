#include "chasles/report/result_names.h"

#include <array>

#include <fmt/format.h>

#include "chasles/error.h"

namespace chasles {

const char* StudyJumpKindName(StudyJumpKind kind) {
  switch (kind) {
    case StudyJumpKind::kEmbedding:
      return "embedding";
    case StudyJumpKind::kPassThrough:
      return "pass-through";
    case StudyJumpKind::kImpulse:
      break;
  }
  return "impulse";
}

StudyJumpKind ParseStudyJumpKind(const std::string& name, const std::string& where) {
  for (const StudyJumpKind k :
       {StudyJumpKind::kImpulse, StudyJumpKind::kEmbedding, StudyJumpKind::kPassThrough}) {
    if (name == StudyJumpKindName(k)) return k;
  }
  throw InputError(
      fmt::format("{}: unknown jump kind '{}'; expected 'impulse', 'embedding' or 'pass-through'",
                  where, name));
}

namespace {

constexpr std::array<StudyContactMode, 4> kContactModes{{{ContactMode::kSeparated, false},
                                                         {ContactMode::kSliding, false},
                                                         {ContactMode::kSticking, false},
                                                         {ContactMode::kSticking, true}}};

constexpr std::array<ContactEventReason, 13> kContactEventReasons{
    ContactEventReason::kInitial,       ContactEventReason::kTouchDown,
    ContactEventReason::kLiftOff,       ContactEventReason::kSlipStopped,
    ContactEventReason::kFrictionLimit, ContactEventReason::kRollingStopped,
    ContactEventReason::kRollingLimit,  ContactEventReason::kAccumulation,
    ContactEventReason::kCollision,     ContactEventReason::kOther,
    ContactEventReason::kImpulse,       ContactEventReason::kEngineSwitch,
    ContactEventReason::kTimeStep};

}  // namespace

const char* StudyContactModeName(const StudyContactMode& mode) {
  return ContactRegimeName(mode.mode, mode.rolling_held);
}

StudyContactMode ParseStudyContactMode(const std::string& name, const std::string& where) {
  std::string known;
  for (const StudyContactMode& m : kContactModes) {
    if (name == StudyContactModeName(m)) return m;
    known += fmt::format("{}'{}'", known.empty() ? "" : ", ", StudyContactModeName(m));
  }
  throw InputError(
      fmt::format("{}: unknown contact mode '{}'; expected one of {}", where, name, known));
}

ContactEventReason ParseContactEventReason(const std::string& name, const std::string& where) {
  std::string known;
  for (const ContactEventReason r : kContactEventReasons) {
    if (name == ContactEventReasonName(r)) return r;
    known += fmt::format("{}'{}'", known.empty() ? "" : ", ", ContactEventReasonName(r));
  }
  throw InputError(fmt::format("{}: unknown contact mode change reason '{}'; expected one of {}",
                               where, name, known));
}

const char* StringModeName(ConstraintMode mode) {
  return mode == ConstraintMode::kReleased ? "slack" : "taut";
}

const char* ConstraintEventReasonName(ConstraintEventReason reason) {
  switch (reason) {
    case ConstraintEventReason::kWentSlack:
      return "went slack";
    case ConstraintEventReason::kSnappedTaut:
      return "snapped taut";
    case ConstraintEventReason::kWentTaut:
      return "went taut";
    case ConstraintEventReason::kInitial:
      break;
  }
  return "initial";
}

const char* StabilityChangeKindName(StabilityChangeKind kind) {
  return kind == StabilityChangeKind::kOscillatory ? "oscillatory" : "divergent";
}

const char* StudyIntegratorName(EngineRequest engine, IntegratorKind integrator) {
  switch (engine) {
    case EngineRequest::kEvents:
      return "events";
    case EngineRequest::kStepping:
      return "stepping";
    case EngineRequest::kAuto:
      return "auto";
    case EngineRequest::kIntegrator:
      break;
  }
  return IntegratorName(integrator);
}

}  // namespace chasles
