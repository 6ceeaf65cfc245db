#pragma once
/// @file
/// The automatic choice between the two contact engines (`integrator: auto`; docs/contact.md,
/// "Choosing the engine"): the event-driven hybrid engine (Simulate: every regime change located
/// and integrated exactly) while its regime changes come slower than one per kStepsPerChange
/// steps of the time-stepping engine, time stepping (SimulateTimeStepping, step h) while they
/// come faster, and back once no regime has changed for a quiet span.
///
/// Why the bound is in steps: where it pays, each engine costs what it does per unit of
/// simulated time. The event-driven engine pays per regime change (a restart, the event's
/// location by bisection on the dense output, the impacts and the mode selection), time
/// stepping per step (three contact problems with the step-doubling estimate). On the cube that
/// chatters on its corners (examples/contact-cube-tumbles-auto.yaml) one change costs about 130
/// µs and one step 55 to 70 µs: events stop paying at about one change per two steps. The bound
/// is one per kStepsPerChange = 2 steps, held over kWindowChanges = 8 consecutive changes, so
/// that a burst of changes at one impact (a box landing on an edge: its points re-selected after
/// the impact) does not switch. The window is short because the rate it measures lags: over
/// changes that come ever faster (flights shrinking by e per bounce) it sees the oldest of them,
/// so it yields once the last 8 fall within 16 steps, when the current flight is
/// e⁷ (1 - e)/(1 - e⁷) of that span: about a sixteenth of a step for e = 0.5 (a window of 32
/// changes would wait for flights of 2⁻²⁶ of a step).

#include "chasles/model/model.h"

namespace chasles {

/// The event-driven engine yields when its regime changes come faster than one per this many
/// steps of the time-stepping engine.
inline constexpr double kStepsPerChange = 2.0;
/// ... sustained over this many consecutive regime changes.
inline constexpr int kWindowChanges = 8;
/// Time stepping hands the run back after this many steps without a regime change (the
/// window's span: a state as quiet for as long as the bound looks back).
inline constexpr double kQuietSteps = kStepsPerChange * kWindowChanges;
/// The default step is this fraction of the time sqrt(ρ / g) a body takes to fall through
/// its own size (DefaultEngineStep).
inline constexpr double kStepOfFallTime = 1e-2;

/// The rule `integrator: auto` follows, for a time-stepping step h.
struct EngineChoiceRule {
  /// Step of the time-stepping segments h [s].
  double step = 0.0;
  /// Yield to time stepping when `changes` consecutive regime changes fall within `window`
  /// [s] = changes × kStepsPerChange × h (ContactOptions::yield_changes, yield_window).
  int changes = 0;
  double window = 0.0;
  /// Back to the event-driven engine after this long without a regime change [s]
  /// (TimeSteppingOptions::quiet_span).
  double quiet_span = 0.0;
};

/// The rule for step `step` (> 0, finite; InputError otherwise).
EngineChoiceRule MakeEngineChoiceRule(double step);

/// The time-stepping step `integrator: auto` takes when the scene gives none:
///   h = kStepOfFallTime sqrt(ρ / g),
/// ρ the smallest radius of gyration √(I_max / m) (I_max the largest central moment) of the
/// bodies that carry contacts, g the model's uniform gravity. A body falling from rest for one
/// step moves g h² = 1e-4 ρ: the first-order position error of a step, and the penetration of a
/// landing that starts within the step, stay at 1e-4 of the smallest body's size. Without
/// gravity (or contacts): a tenth of `output_interval` (> 0).
double DefaultEngineStep(const Model& model, double output_interval);

}  // namespace chasles
