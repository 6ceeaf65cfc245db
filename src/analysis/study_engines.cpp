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
  into.steps += add.steps;
  into.max_residual_impulse = std::max(into.max_residual_impulse, add.max_residual_impulse);
  into.max_residual_velocity = std::max(into.max_residual_velocity, add.max_residual_velocity);
  into.max_momentum_residual = std::max(into.max_momentum_residual, add.max_momentum_residual);
  into.max_angular_momentum_residual =
      std::max(into.max_angular_momentum_residual, add.max_angular_momentum_residual);
  into.max_penetration = std::max(into.max_penetration, add.max_penetration);
  into.max_gap_drift = std::max(into.max_gap_drift, add.max_gap_drift);
  into.max_velocity_error = std::max(into.max_velocity_error, add.max_velocity_error);
  into.max_angular_velocity_error =
      std::max(into.max_angular_velocity_error, add.max_angular_velocity_error);
  into.accumulated_velocity_error += add.accumulated_velocity_error;
  into.final_energy = add.final_energy;
  into.work_nonconservative += add.work_nonconservative;
  into.work_normal += add.work_normal;
  into.work_friction += add.work_friction;
  into.numerical_energy_error += add.numerical_energy_error;
  into.regime_changes += add.regime_changes;
  into.newton_iterations += add.newton_iterations;
  into.sweeps += add.sweeps;
  into.largest_island = std::max(into.largest_island, add.largest_island);
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
