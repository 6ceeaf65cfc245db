#include "chasles/report/result_names.h"

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

}  // namespace chasles
