#pragma once
/// @file
/// Simulate: runs a Model from an initial State to an end time with one of the integrators,
/// samples the solution on a regular output grid, and locates events.
///
/// Which integrator:
///  - kDormandPrince5 (default): adaptive, error-controlled, dense output; the only one that
///    locates events (on the dense output, to `event_time_tolerance`).
///  - kEnergyMomentum: fixed step; exact conservation of energy and angular momentum of free
///    rotation; for long torque-free or conservative runs.
///  - kRk4: fixed step, fourth order; for a fixed output grid at predictable cost.
/// Fixed-step integrators shorten `fixed_step` so that it divides the output interval evenly.

#include <functional>
#include <string>
#include <vector>

#include "chasles/integrate/dormand_prince.h"
#include "chasles/integrate/stats.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {

enum class IntegratorKind { kDormandPrince5, kRk4, kEnergyMomentum };

/// Which zero crossings of g count: g going from < 0 to >= 0 (kRising), from > 0 to <= 0
/// (kFalling), or both.
enum class EventDirection { kRising, kFalling, kEither };
/// What happens at an event: the run stops there, or it is recorded and the run goes on.
enum class EventAction { kStop, kRecord };

struct EventSpec {
  /// Name used in reports.
  std::string name;
  /// The event function g(t, state); an event is a zero crossing in `direction`.
  std::function<double(double t, const State& state)> g;
  EventDirection direction = EventDirection::kEither;
  EventAction action = EventAction::kStop;
};

struct EventRecord {
  /// Index into SimulationOptions::events.
  int event = -1;
  /// Name of the event.
  std::string name;
  /// Time of the crossing [s] (within event_time_tolerance).
  double t = 0.0;
  /// State at that time (from the dense output).
  State state;
};

struct SimulationOptions {
  IntegratorKind integrator = IntegratorKind::kDormandPrince5;
  /// End time [s] (> initial t).
  double t_end = 0.0;
  /// Spacing of output samples [s]; 0 records only the initial and final states.
  double output_interval = 0.0;
  /// Step for the fixed-step integrators [s].
  double fixed_step = 1e-3;
  /// Tolerances and step limits of the adaptive integrator.
  AdaptiveOptions adaptive;
  /// Events to locate (adaptive integrator only).
  std::vector<EventSpec> events;
  /// Width of the final bracket around an event time [s].
  double event_time_tolerance = 1e-10;
  /// Keep every sample in SimulationResult::samples (turn off when streaming via on_sample).
  bool store_samples = true;
  /// Called with every output sample, in time order (optional).
  std::function<void(const State&)> on_sample;
};

struct SimulationResult {
  /// Output samples: the initial state, every output time, and the final state.
  std::vector<State> samples;
  /// Events in time order.
  std::vector<EventRecord> events;
  /// The state where the run ended (t_end or a stopping event).
  State final_state;
  /// True when a kStop event ended the run.
  bool stopped_by_event = false;
  IntegratorStats stats;
};

/// Runs the simulation. Throws InputError for an invalid initial state or options (the message
/// names the option and the fix). For a model with constraints the initial state is first
/// projected onto them (ProjectOntoConstraints), and so are the output samples and event
/// states taken from the dense output.
SimulationResult Simulate(const Model& model, const State& initial,
                          const SimulationOptions& options);

}  // namespace chasles
