#pragma once
/// @file
/// The names the outputs (JSON, text reports, the browser report's data, Python) give the
/// enums of the study's results, and their reading back from a written JSON summary.

#include <string>

#include "chasles/analysis/modes.h"
#include "chasles/analysis/study.h"

namespace chasles {

/// "impulse", "embedding" or "pass-through".
const char* StudyJumpKindName(StudyJumpKind kind);

/// The kind a summary names `name` (StudyJumpKindName's inverse); throws InputError naming
/// `where` and the names it knows for any other.
StudyJumpKind ParseStudyJumpKind(const std::string& name, const std::string& where);

/// A contact point's regime: ContactRegimeName ("separated", "sliding", "sticking" or
/// "sticking, rolling held").
const char* StudyContactModeName(const StudyContactMode& mode);

/// The regime a summary names `name` (StudyContactModeName's inverse); throws InputError naming
/// `where` and the names it knows for any other.
StudyContactMode ParseStudyContactMode(const std::string& name, const std::string& where);

/// The reason a summary names `name` (ContactEventReasonName's inverse); throws InputError
/// naming `where` and the names it knows for any other.
ContactEventReason ParseContactEventReason(const std::string& name, const std::string& where);

/// A string's mode: "taut" (kEngaged) or "slack" (kReleased).
const char* StringModeName(ConstraintMode mode);

/// "initial", "went slack", "snapped taut" or "went taut".
const char* ConstraintEventReasonName(ConstraintEventReason reason);

/// The run's integrator as the reports name it: "events", "stepping", "auto" for the contact
/// engines a scene names, else IntegratorName(integrator).
const char* StudyIntegratorName(EngineRequest engine, IntegratorKind integrator);

/// "oscillatory" or "divergent".
const char* StabilityChangeKindName(StabilityChangeKind kind);

}  // namespace chasles
