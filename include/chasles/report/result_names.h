#pragma once
/// @file
/// The names the outputs (JSON, text reports, the browser report's data, Python) give the
/// enums of the study's results, and their reading back from a written JSON summary.

#include <string>

#include "chasles/analysis/study.h"

namespace chasles {

/// "impulse", "embedding" or "pass-through".
const char* StudyJumpKindName(StudyJumpKind kind);

/// The kind a summary names `name` (StudyJumpKindName's inverse); throws InputError naming
/// `where` and the names it knows for any other.
StudyJumpKind ParseStudyJumpKind(const std::string& name, const std::string& where);

}  // namespace chasles
