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
///  - kRk4: fixed step, fourth order; for a fixed output grid at predictable cost (free bodies
///    under uniform gravity alone run on the structure-of-arrays batch, free_body_batch.h).
///  - kSplitting: fixed step, second-order symplectic splitting on the free-body batch; only for
///    models FreeBodyBatchObstacle accepts (an InputError names what does not qualify).
/// Fixed-step integrators shorten `fixed_step` so that it divides the output interval evenly.

#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "chasles/dynamics/contact_solve.h"
#include "chasles/integrate/dormand_prince.h"
#include "chasles/integrate/integrator.h"
#include "chasles/integrate/run_path.h"
#include "chasles/integrate/stats.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {

/// Which zero crossings of g count: g going from < 0 to >= 0 (kRising), from > 0 to <= 0
/// (kFalling), or both.
enum class EventDirection { kRising, kFalling, kEither };
/// What happens at an event: the run stops there, or it is recorded and the run goes on.
enum class EventAction { kStop, kRecord };

/// Why a contact point changed mode.
enum class ContactEventReason {
  kInitial,         ///< mode chosen at the start of the run
  kTouchDown,       ///< gap reached zero (an impact or a gentle landing)
  kLiftOff,         ///< normal force reached zero
  kSlipStopped,     ///< slip speed reached zero (then stick, or slide the other way)
  kFrictionLimit,   ///< sticking needed more friction than mu_s N
  kRollingStopped,  ///< rolling angular velocity reached zero (rolling resistance)
  kRollingLimit,    ///< a held rolling needed more moment than mu_r N R (starts to roll)
  kAccumulation,    ///< bounces shrinking geometrically summed to rest (Zeno limit)
  kCollision,       ///< a collision between balls changed the velocities (SimulateSphereEvents)
  kOther,           ///< re-selection after another point's event changed the forces
  kImpulse,         ///< an impulse on a body, applied by a study between its segments
  kEngineSwitch,    ///< a study's run handing over from time stepping to the hybrid engine
  kTimeStep,        ///< a step of time stepping (SimulateTimeStepping) changed the regime
};

/// Name of a reason ("touch-down", "lift-off", ...).
const char* ContactEventReasonName(ContactEventReason reason);

/// One mode change of one contact point.
struct ContactEvent {
  /// Time [s] (located to event_time_tolerance).
  double t = 0.0;
  /// Contact point index (Model::contact_point_name gives its name).
  int point = -1;
  ContactMode from = ContactMode::kSeparated;
  ContactMode to = ContactMode::kSeparated;
  ContactEventReason reason = ContactEventReason::kOther;
  /// Whether the point's rolling was held before and after (ContactPointState::rolling_held).
  bool held_from = false, held_to = false;
};

struct EventSpec {
  /// Name used in reports.
  std::string name;
  /// The event function g(model, state) (time state.t); an event is a zero crossing in
  /// `direction`. Like a VectorFunction it keeps no mutable state of its own.
  std::function<double(const Model& model, const State& state)> g;
  EventDirection direction = EventDirection::kEither;
  EventAction action = EventAction::kStop;
  /// Instead of g, a contact-mode event (models with contacts): it fires at each mode change
  /// of a contact point during the run for which this returns true (not at the initial choice
  /// of modes); its record's state is the one just after the change, in the new modes.
  std::function<bool(const ContactEvent& change)> on_mode_change = nullptr;
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

/// A mode change of a constraint that can let go (a string going slack or snapping taut), or
/// its initial mode (reason "initial").
/// Why a constraint that can let go (a string) changed mode.
enum class ConstraintEventReason {
  kInitial,      ///< mode chosen at the start of the run
  kWentSlack,    ///< the tension fell through 0
  kSnappedTaut,  ///< an impact: the gap closed while closing
  kWentTaut,     ///< the gap closed at zero speed
};

struct ConstraintEvent {
  /// Time [s] (located to the event time tolerance).
  double t = 0.0;
  /// Constraint index (Model order).
  int constraint = -1;
  ConstraintMode from = ConstraintMode::kEngaged;
  ConstraintMode to = ConstraintMode::kEngaged;
  ConstraintEventReason reason = ConstraintEventReason::kInitial;
  /// For "snapped taut": closing speed before [m/s], impulse [N·s], kinetic energy lost [J].
  double approach_speed = 0.0;
  double impulse = 0.0;
  double energy_lost = 0.0;
};

/// One impact (or accumulated bounce sequence) at one contact point.
struct ImpactRecord {
  /// Time [s].
  double t = 0.0;
  /// Contact point index.
  int point = -1;
  /// Normal approach speed before [m/s] (> 0).
  double approach_speed = 0.0;
  /// Normal impulse [N·s].
  double normal_impulse = 0.0;
  /// Total impulse on the body, in W [N·s].
  Vec3 impulse_W = Vec3::Zero();
  /// Kinetic energy lost by the whole system in this impact [J] (>= 0).
  double energy_lost = 0.0;
  /// True for the impact that ends a geometric bounce sequence (restitution 0 there).
  bool accumulation = false;
  /// True for a jam: sliding without consistent contact forces (Painlevé), stopped by an
  /// impulse at zero approach speed (docs/contact.md).
  bool jam = false;
  /// For that impact: the analytic time the bounces accumulate to rest,
  /// t + t_flight e / (1 - e) [s] (NaN otherwise).
  double accumulation_time = std::numeric_limits<double>::quiet_NaN();
  /// The restitution law used at this point.
  RestitutionLaw law = RestitutionLaw::kEnergetic;
  /// True when the frictionless impulse replaced one that would have raised the energy.
  bool frictionless_fallback = false;
};

/// An interval of constant mode of one contact point.
struct ContactModeInterval {
  double t_begin = 0.0, t_end = 0.0;  ///< [s]
  ContactMode mode = ContactMode::kSeparated;
  /// Why the interval began.
  ContactEventReason reason = ContactEventReason::kInitial;
};

/// Settings of contact handling in Simulate (models with contacts; Dormand-Prince only).
struct ContactOptions {
  /// Tolerances of mode selection and impacts.
  ContactTolerances tolerances;
  /// Sum a bounce sequence whose approach speeds shrink by the restitution coefficient to
  /// its accumulation time (t_flight e / (1 - e)) instead of integrating every bounce.
  bool accumulate_bounces = true;
  /// Relative agreement of two successive bounce ratios with e needed to accumulate.
  double accumulation_ratio_tolerance = 1e-6;
  /// Accumulate only once the remaining bounces last at most this long, τ e / (1 - e) [s]:
  /// the bounces before are integrated one by one, so the rest the run skips is invisible
  /// (heights below g τ² / 8, about 1e-13 m for 1e-6 s under gravity).
  double accumulation_remaining_time = 1e-6;
  /// The run stops with an InputError after this many mode switches (chattering guard).
  int max_mode_switches = 100000;
  /// A bound on the rate of regime changes (integrator: auto; docs/contact.md, "Choosing the
  /// engine"): the run yields, ending early at the state just after a transition, when the
  /// last `yield_changes` transitions (each located event that switches modes counts once; a
  /// touch-down that continues a geometric bounce sequence, which the run sums in closed form,
  /// does not count) all fall within `yield_window` [s]. 0: never (the default).
  int yield_changes = 0;
  double yield_window = 0.0;
};

/// Why a hybrid run yielded (ContactOptions::yield_changes): its last `changes` transitions
/// fell within [t_first, t_last], faster than the bound.
struct RegimeChangeYield {
  /// Times of the first and the last transition of the window [s].
  double t_first = 0.0, t_last = 0.0;
  int changes = 0;
  /// The contact point (or string) whose event made the last one, by name.
  std::string where;
};

/// One island of a run split into islands (RunPath::kIslands), as the island form of the
/// transition hook sees it: the island's own Model (its bodies, force elements, constraints and
/// contacts renumbered, every name kept), its initial State (local indices; an element acting on
/// each body alone, gravity, carries its integrals from zero in every island but the first),
/// and the index in the whole Model of each of its bodies, force elements, constraints and
/// contact points. Valid only during the call it is handed to.
struct IslandView {
  /// Island index (islands in order of their smallest body index).
  int island = 0;
  const Model* model = nullptr;
  const State* initial = nullptr;
  std::vector<BodyIndex> bodies;
  std::vector<int> forces, constraints, points;
};

/// A check at a contact transition: the state just before it (old modes) and just after it.
using TransitionCheck = std::function<void(const State& before, const State& after)>;

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
  double event_time_tolerance = 1e-12;
  /// Keep every sample in SimulationResult::samples (turn off when streaming via on_sample).
  bool store_samples = true;
  /// Called with every output sample, in time order (optional).
  std::function<void(const State&)> on_sample;
  /// Called at every contact transition during the run with the state just before it (old
  /// modes) and just after it (impacts applied, new modes) (optional; models with contacts).
  TransitionCheck on_transition = nullptr;
  /// The island form of on_transition, for a run split into islands: called once per island,
  /// from the thread that runs it (so from several threads at once), with the island's view;
  /// returns the check the island's transitions are given (its own States, local indices).
  /// With it set, on_transition no longer keeps the run one system; a run that stays one system
  /// calls on_transition.
  std::function<TransitionCheck(const IslandView& island)> island_transition = nullptr;
  /// Contact handling (models with contacts).
  ContactOptions contact;
  /// Called after every accepted integration step with the time it reached (optional): the
  /// caller counts the work and stops a run that exceeds its limits by throwing (LimitError).
  std::function<void(double t)> on_step = nullptr;
  /// Split a model with contacts into islands (bodies linked by constraints, sphere-sphere
  /// contacts or force elements between bodies), each run as its own hybrid system with its
  /// own integrator and events (docs/contact.md, "Islands"); false: always one system. Where a
  /// run needs the whole State at arbitrary times (user events, on_transition without
  /// island_transition) it is one system anyway; SimulationResult::islands says which ran and
  /// why.
  bool islands = true;
  /// Threads over the islands, or over the free-body batch's blocks of bodies (>= 1); the
  /// result is bitwise the same for any number. With islands on_step is then called from
  /// several threads, one call at a time.
  int threads = 1;
};

/// How a hybrid run (a model with contacts or strings) was split into islands.
struct IslandReport {
  /// True when the islands ran separately; false: the model ran as one system.
  bool split = false;
  /// Number of islands the bodies form (0 when not looked for: a model without contacts).
  int count = 0;
  /// Why the run was one system although the bodies form several islands, or why they were
  /// not looked for (empty when split).
  std::string reason;
  /// When split: each island's bodies (Model order) and its integrator's work, in island
  /// order (by the smallest body index).
  std::vector<std::vector<BodyIndex>> bodies;
  std::vector<IntegratorStats> stats;
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
  /// Contact mode changes in time order, with the initial modes (reason kInitial) first.
  std::vector<ContactEvent> contact_events;
  /// Impacts in time order.
  std::vector<ImpactRecord> impacts;
  /// Mode changes of the constraints that can let go (strings), in time order, with their
  /// initial modes first.
  std::vector<ConstraintEvent> constraint_events;
  /// What the run had to decide or change that the user should know (jams, ...).
  std::vector<std::string> warnings;
  /// How the hybrid paths split the bodies: islands or one system, and why.
  IslandReport islands;
  /// The path that ran and why (ChooseRunPath).
  RunPathChoice run_path;
  /// Set when the run yielded because its regime changes came faster than
  /// ContactOptions::yield_changes allows: final_state is the state just after the transition
  /// that exceeded the bound (not a sample: the caller goes on from it with another engine).
  std::optional<RegimeChangeYield> yielded;
};

/// The mode timeline of contact point `point` from a run's contact events, from the first
/// sample's time to the final state's.
std::vector<ContactModeInterval> CalcModeTimeline(const SimulationResult& result, int point);

/// Runs the simulation on the path ChooseRunPath picks (run_path.h; SimulationResult::run_path
/// names it). Throws InputError for an invalid initial state or options (the message
/// names the option and the fix), and when a force, an acceleration or the state becomes
/// non-finite (the message names the force element, constraint, contact point or body and the
/// time; see OdeSystem::Derivative). A model with contacts runs as a hybrid system (adaptive
/// integrator only): the contact modes switch at events located on the dense output, with
/// impacts at touch-down, and the integrator restarts after each switch (docs/contact.md). For a
/// model with constraints the initial state is first projected onto them (ProjectOntoConstraints),
/// and so are the output samples and event states taken from the dense output.
SimulationResult Simulate(const Model& model, const State& initial,
                          const SimulationOptions& options);

/// The integrator Simulate steps for `options` on a run starting at `t_start`: the
/// Dormand–Prince integrator with `options.adaptive`, or a fixed-step one whose step is
/// `options.fixed_step` shortened to divide the output interval (the whole run when it is 0)
/// evenly. `model` must outlive it. Throws InputError for a fixed step that is not positive.
std::unique_ptr<Integrator> MakeIntegrator(const Model& model, const SimulationOptions& options,
                                           double t_start);

}  // namespace chasles
