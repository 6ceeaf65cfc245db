// The engines of a study's run under integrator: auto (include/chasles/analysis/study.h,
// docs/contact.md "Choosing the engine"): what keeps a run event-driven, a time-stepped
// segment's certificate over several stretches, and the handover back to events.

#include <algorithm>

#include "chasles/analysis/ledger.h"
#include "chasles/dynamics/contact_projection.h"
#include "chasles/model/data.h"
#include "internal/study_steps.h"

namespace chasles {

const char* StudyEngineName(StudyEngine engine) {
  switch (engine) {
    case StudyEngine::kAdaptive:
      return "adaptive";
    case StudyEngine::kStepping:
      return "stepping";
  }
  return "unknown";
}

const char* EngineSwitchName(EngineSwitch reason) {
  switch (reason) {
    case EngineSwitch::kStart:
      return "start";
    case EngineSwitch::kRegimeChanges:
      return "regime changes";
    case EngineSwitch::kQuiet:
      return "quiet";
  }
  return "unknown";
}

namespace study_internal {

void AddSteppingSummary(TimeSteppingSummary& into, const TimeSteppingSummary& add) {
  if (into.steps == 0) {
    into = add;
    return;
  }
  MergeSteppingSummary(into, add);
  into.final_energy = add.final_energy;
}

EventsHandover ProjectForEvents(const Model& model, State& state) {
  EventsHandover out;
  if (!HasActiveContactRows(model, state)) return out;
  Data data = MakeData(model);
  out.depth = CalcContactViolation(model, state, data).gap;
  const double before = CalcMechanicalEnergy(model, state);
  ProjectOntoContactModes(model, state, data);
  out.energy = CalcMechanicalEnergy(model, state) - before;
  return out;
}

}  // namespace study_internal
}  // namespace chasles
