#pragma once
/// @file
/// A study: a Model run from an initial State with impulses, impacts and events, sampled on an
/// output grid, with the energy ledger carried across the whole run and a certificate of its
/// own checks. This is what `chasles simulate` reports; a C++ caller builds a StudyDefinition
/// in code (docs/cpp.md) and calls RunStudy, without a scene file.
///
/// Impulses and impacts split the run into segments. Between them Simulate integrates the
/// current Model; at each instant the state jumps (ApplyImpulse, ApplyPassThrough) or, when a
/// projectile embeds, a new Model is built with the composite body by the definition's
/// ModelBuilder (Models are immutable). The ledger is carried across the segments: each
/// segment's work-energy residual adds up, and the kinetic-energy jumps are booked separately,
/// so that
///   E - E0 = W_nc + jumps + residual.
/// Output samples lie on one grid t = k * output_interval from 0 whatever the segments.
///
/// Bodies are the caller's ("user bodies"): one Model body each until an embedding merges two;
/// a BodyMap says where each user body sits in the current Model's bodies.

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "chasles/analysis/certificate.h"
#include "chasles/analysis/error_locator.h"
#include "chasles/analysis/initial_state.h"
#include "chasles/analysis/instantaneous.h"
#include "chasles/integrate/engine_choice.h"
#include "chasles/integrate/integrator.h"
#include "chasles/integrate/run_path.h"
#include "chasles/integrate/simulate.h"
#include "chasles/integrate/sphere_events.h"
#include "chasles/integrate/time_stepping.h"
#include "chasles/mass/mass_properties.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {

/// Where a user body sits in a Model body: the same body, or a part of a composite after an
/// embedding. R_MB and p_MoBo_M place the user body's frame B in the model body's frame M.
struct BodyPlacement {
  int model_body = 0;
  Mat3 R_MB = Mat3::Identity();
  Vec3 p_MoBo_M = Vec3::Zero();
};

/// User bodies mapped to the current Model, with each user body's own centre of mass.
struct BodyMap {
  std::vector<BodyPlacement> place;
  std::vector<Vec3> p_BoBcm_B;
  /// Each user body's own mass [kg] and central inertia in its B [kg·m²] (its momenta and
  /// dH/dt columns; empty when no column asks).
  std::vector<double> mass;
  std::vector<Mat3> I_BBcm_B;
  /// A point fixed in user body b, given in B, in the model body's frame M.
  Vec3 PointInModelBody(int b, const Vec3& p_BoP_B) const;
};

/// Kinematics of one user body at a state (exact for a part of a composite too).
struct MappedBodyMotion {
  Mat3 R_WB = Mat3::Identity();
  Vec3 p_WBo = Vec3::Zero(), p_WBcm = Vec3::Zero(), v_WBcm_W = Vec3::Zero(), w_WB_W = Vec3::Zero();
};
MappedBodyMotion CalcMappedBodyMotion(const Model& model, const State& state, const BodyMap& map,
                                      int b);

/// A named body's mass properties (a Model body to be).
struct NamedBody {
  std::string name;
  MassProperties mass_properties;
};

/// Builds the Model of a segment from its bodies and the map of the user bodies onto them
/// (force elements, constraints and contacts placed through the map). Called once at the
/// start (identity map) and after every embedding.
using ModelBuilder = std::function<Model(const std::vector<NamedBody>& bodies, const BodyMap& map)>;

/// The events of a segment, for its map (their functions read user-body quantities).
using EventBuilder = std::function<std::vector<EventSpec>(const BodyMap& map)>;

/// An impulse J [N·s] at a point P of a user body at time t.
struct StudyImpulseSpec {
  double t = 0.0;
  int body = 0;
  /// P in the body's frame B [m].
  Vec3 p_BoP_B = Vec3::Zero();
  /// The impulse, in W or in B (`frame`) [N·s].
  Vec3 J = Vec3::Zero();
  VectorFrame frame = VectorFrame::kWorld;
};

/// A projectile (user body) striking a target (user body) at time t: it embeds
/// (exit_fraction = 0, the two become one composite body) or passes through keeping
/// exit_fraction of its velocity (docs/scene-format.md, "Impacts").
struct StudyImpactSpec {
  double t = 0.0;
  int target = 0;
  int projectile = 0;
  double exit_fraction = 0.0;
};

/// One output column: a user-body quantity, a ledger quantity, a reaction component or a
/// contact point's value (names as in docs/scene-format.md, "Output columns").
struct StudyColumn {
  /// Column name in the CSV header.
  std::string name;
  /// Group it belongs to ("position", "energy", "reactions", "contacts", ...).
  std::string group;
  /// User body index for per-body columns; -1 for t and ledger columns.
  int body = -1;
  /// A body quantity suffix ("x", "qw", "ax", "theta", ...), a ledger name ("T_trans", "W_nc",
  /// "Px", ...), "W" with `force` set for an element's work, a reaction component ("Fx",
  /// "My_B", ...) with `force` naming the constraint, or a contact value ("N", "slip", ...).
  std::string quantity;
  /// Force element or constraint name (per-element work, reactions).
  std::string force;
  /// Contact point index (Model order) for the "contacts" group; -1 otherwise.
  int point = -1;
  /// The body point of a point column ("pvx", "pax", ...): from the body origin, in B [m].
  Vec3 p_BoP_B = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
};

/// A rolling constraint whose friction the run watches against μ_s (it holds the rolling
/// whatever friction it takes; the result's notes say when more was needed).
struct RollingWatch {
  std::string name;
  /// Model index of the constraint.
  int constraint = 0;
  double mu_s = 0.0;
};

/// Limits on a run's work (docs/reliability-limits.md): LimitError when reached.
struct StudyLimits {
  std::int64_t max_steps = 10'000'000;
  std::int64_t max_rows = 1'000'000;
  /// Wall time [s]; 0: none.
  double timeout = 0.0;
};

/// Everything a study needs. `bodies`, `model` or `build_model`, `initial` and `options.t_end`
/// are required; the rest has defaults.
struct StudyDefinition {
  /// The user bodies, one Model body each at the start.
  std::vector<NamedBody> bodies;
  /// The first segment's Model, when the caller has built it (one Model body per user body, in
  /// their order); null: the run builds it with `build_model` and the identity map. A run
  /// builds each Model once.
  std::shared_ptr<const Model> model;
  /// Builds the Model of each segment after an embedding, and the first when `model` is null
  /// (see ModelBuilder). Optional when `model` is given and no impact embeds.
  ModelBuilder build_model;
  /// The initial state (on the constraints, or settled onto them by `settle_initial`; the run
  /// chooses the contact modes, after any impact at the start).
  State initial;
  /// Settle `initial` onto the constraints before the run (SettleInitialState, on `model`,
  /// which is then required): within round-off silently, else an error or, when asked, the
  /// nearest consistent state with each change a warning after `warnings`. None: `initial` is
  /// used as it is.
  std::optional<InitialSettling> settle_initial;
  /// Integrator, end time (t_end), output interval, fixed step, adaptive tolerances and the
  /// smallest step (options.adaptive.min_step). Its events are ignored: use `events`.
  SimulationOptions options;
  /// Events of each segment (optional).
  EventBuilder events;
  /// Balls on a table run event-driven (SimulateSphereEvents with these options; t_end and
  /// output_interval are taken from `options`) instead of by `options.integrator`. The Model
  /// must be balls only (SphereEventObstacle); no events, impulses or impacts.
  std::optional<SphereEventOptions> sphere_events;
  /// Time stepping (SimulateTimeStepping with these options; t_end and output_interval are
  /// taken from `options`) instead of `options.integrator`. The Model must pass
  /// TimeSteppingObstacle; no events, impulses or impacts.
  std::optional<TimeSteppingOptions> time_stepping;
  /// `integrator: auto`: the run chooses its engine (docs/contact.md, "Choosing the engine"):
  /// the hybrid event-driven run of `options` (Dormand–Prince) while regime changes come slower
  /// than `rule` allows, time stepping (`stepping`, with the rule's step) while they come
  /// faster, and back after the rule's quiet span; StudyResult::segments says which ran when
  /// and why. The switch needs a Model time stepping can run (TimeSteppingObstacle) and no
  /// events; otherwise the run stays event-driven and its first segment says why.
  struct AutoEngine {
    EngineChoiceRule rule;
    /// Time stepping's other settings (its step, end, output interval and quiet span are the
    /// run's). With collide_all_pairs the run is time stepped throughout.
    TimeSteppingOptions stepping;
    /// The run chose auto because its definition named no engine (a scene of format version
    /// 3 with contacts and no integrator); the report says so.
    bool by_default = false;
  };
  std::optional<AutoEngine> auto_engine;
  /// Output columns (t first, by convention).
  std::vector<StudyColumn> columns;
  std::vector<StudyImpulseSpec> impulses;
  std::vector<StudyImpactSpec> impacts;
  /// Contact point labels in Model order (empty: Model::contact_point_name).
  std::vector<std::string> contact_point_labels;
  /// Force elements whose work the ledger lists, in this order (empty: every element of the
  /// first Model).
  std::vector<std::string> reported_forces;
  /// Number of the Model's constraints (the first ones) reported in reactions and the ledger
  /// (-1: all). A planar scene's plane constraints come after its own and are left out.
  int num_reported_constraints = -1;
  /// Planar runs: each user body's initial angle θ about z [rad], for a continuous θ column
  /// and the bodies' θ in the snapshots (empty: not planar).
  std::vector<double> initial_theta;
  std::vector<RollingWatch> rolling_watch;
  CertificateTolerances certificate;
  StudyLimits limits;
  /// Called with the time of every output sample and every accepted step (optional).
  std::function<void(double t)> progress;
  /// Places the run's errors at their source (the scene layer's file:line:col); null: they
  /// are thrown as they are.
  ErrorLocator locate_error;
  /// The SI unit of each result column by its name, for StudyResult::units (the scene layer's
  /// StudyColumnUnits); null: no units.
  std::function<std::vector<std::string>(const std::vector<std::string>& columns)> column_units;
  /// Warnings about the initial state (e.g. values projected onto the constraints), passed
  /// on into the result.
  std::vector<std::string> warnings;
  /// Also record the reactions and contact points at every output row
  /// (StudyResult::row_snapshots; the browser report draws their forces).
  bool record_row_snapshots = false;
  /// Also record every user body's frame at every output row (StudyResult::row_poses; the
  /// browser report's replay draws them, whatever the columns are).
  bool record_row_poses = false;
};

/// The reaction of one constraint (name, kind, point, force and moment in W, in the child's frame
/// and in the parent's, power): the same record `SolveInstantaneous` reports, made from the
/// constraint stage's ConstraintOutput by MakeReactionReport.
using StudyReaction = ReactionReport;

/// What a jump of the state was.
enum class StudyJumpKind {
  kImpulse,      ///< an impulse applied to a body
  kEmbedding,    ///< a projectile that stays in its target (one composite body after)
  kPassThrough,  ///< a projectile that passes through its target, keeping part of its velocity
};

/// An impulse or impact applied during the run.
struct StudyJump {
  StudyJumpKind kind = StudyJumpKind::kImpulse;
  /// What happened, for the report ("bullet embeds in block").
  std::string description;
  /// Time [s].
  double t = 0.0;
  /// Mechanical energy just before and just after [J].
  double energy_before = 0.0;
  double energy_after = 0.0;
  /// Velocity of the (composite) target's centre of mass and its angular velocity just after,
  /// in W [m/s, rad/s].
  Vec3 v_after_W = Vec3::Zero();
  Vec3 w_after_W = Vec3::Zero();
  /// The supports' impulsive reaction over the instant, for every reported joint, rolling
  /// contact, driver and gear (Model order, as StudySnapshot::reactions): the impulse of the
  /// parent's reaction on the child, a force impulse [N·s] and a moment impulse about J
  /// [N·m·s], in W (F_Jc_W, M_Jc_W), in the child's frame and in the parent's; `lambda` the
  /// rows' impulses, a rolling contact's normal and friction impulses in `normal_force` and
  /// `friction_W`; `power` 0 (docs/constraints.md, "Impulsive reactions").
  std::vector<StudyReaction> reactions;
  /// Every body of the Model after the instant, with its velocity jumps and every impulse on
  /// it: the applied one, each constraint's share (a planar scene's plane constraints too) and
  /// each contact impact's, so that its impulse-momentum balance is checkable from these alone
  /// (the certificate checks it).
  std::vector<BodyImpulseBalance> bodies;
  /// Indices into StudyResult::impacts of the contact impacts and jams of this instant.
  std::vector<int> impacts;
};

/// A contact point's regime: its mode and, when sticking, whether its rolling is held by
/// rolling resistance (ContactPointState::rolling_held; ContactRegimeName names the pair).
struct StudyContactMode {
  ContactMode mode = ContactMode::kSeparated;
  bool rolling_held = false;
  /// The same regime: the same mode, and when sticking the same held rolling (a point that
  /// does not stick has no held rolling, whatever the flag says).
  bool operator==(const StudyContactMode& o) const {
    return mode == o.mode && (mode != ContactMode::kSticking || rolling_held == o.rolling_held);
  }
};

/// A mode change of one contact point (the mode timeline; the initial modes come first, with
/// reason kInitial).
struct StudyContactEvent {
  /// Time [s] (located to 1e-12 s).
  double t = 0.0;
  /// Contact point label (ContactPointLabels) and its contact's name.
  std::string point;
  std::string contact;
  /// Modes before and after, and why.
  StudyContactMode from, to;
  ContactEventReason reason = ContactEventReason::kInitial;
};

/// A string's mode: its initial mode, going slack, snapping taut (an impact along it).
struct StudyStringEvent {
  double t = 0.0;
  std::string string;
  /// Taut (kEngaged) or slack (kReleased) before and after, and why.
  ConstraintMode from = ConstraintMode::kEngaged, to = ConstraintMode::kEngaged;
  ConstraintEventReason reason = ConstraintEventReason::kInitial;
  /// For kSnappedTaut: closing speed before [m/s], impulse [N·s], kinetic energy lost [J].
  double approach_speed = 0.0;
  double impulse = 0.0;
  double energy_lost = 0.0;
};

/// One impact (or accumulated bounce sequence) at a contact point.
struct StudyImpact {
  double t = 0.0;
  std::string point;
  /// Normal approach speed before [m/s]; normal impulse [N·s]; kinetic energy lost [J].
  double approach_speed = 0.0;
  double normal_impulse = 0.0;
  double energy_lost = 0.0;
  /// True for the impact that ends a geometric bounce sequence: it is made plastic, and the
  /// bounces it stands for would end at `rest_time` (docs/contact.md, bouncing to rest).
  bool accumulation = false;
  /// Limit of the bounce sequence, t + t_flight e / (1 - e) [s] (NaN unless `accumulation`).
  double rest_time = std::numeric_limits<double>::quiet_NaN();
  /// True for a jam: a slip without consistent contact forces (Painlevé) stopped by an
  /// impulse at zero approach speed.
  bool jam = false;
  /// The restitution law used; none for a jam.
  std::optional<RestitutionLaw> restitution_law;
  /// True when the impulse with friction would have raised the kinetic energy and the
  /// frictionless one was used (ImpactResult::frictionless_fallback).
  bool frictionless_fallback = false;
};

/// One contact point at the end of the run.
struct StudyContactPoint {
  std::string point;
  StudyContactMode mode;
  /// The contact point on the body and the contact normal (towards the body), in W [m].
  Vec3 p_WC = Vec3::Zero();
  Vec3 n_W = Vec3::UnitZ();
  /// Normal force [N], friction force in W [N], slip velocity in W [m/s], gap [m].
  double normal_force = 0.0;
  Vec3 friction_force_W = Vec3::Zero();
  Vec3 slip_velocity_W = Vec3::Zero();
  double gap = 0.0;
  /// Work of sliding friction, of rolling resistance, and energy lost in impacts at this point
  /// since t = 0 [J] (each <= 0).
  double friction_work = 0.0, rolling_work = 0.0, impact_work = 0.0;
  /// Rolling-resistance moment on the body, in W [N·m] (holding or resisting the rolling).
  Vec3 rolling_moment_W = Vec3::Zero();
};

/// Motion of one body of the final Model.
struct StudyBodyState {
  /// Name ("target+projectile" for a composite).
  std::string name;
  /// Mass [kg].
  double mass = 0.0;
  /// Largest moment of inertia about the axes of B through the centre of mass [kg·m²].
  double inertia_max = 0.0;
  /// Centre of mass and frame origin in W [m].
  Vec3 p_WBcm = Vec3::Zero();
  Vec3 p_WBo = Vec3::Zero();
  /// Orientation.
  Quat q_WB = Quat::Identity();
  /// Velocity of Bcm in W [m/s]; angular velocity in W and in B [rad/s].
  Vec3 v_WBcm_W = Vec3::Zero();
  Vec3 w_WB_W = Vec3::Zero();
  Vec3 w_WB_B = Vec3::Zero();
  /// Planar scenes: angle of B about z, continuous from the initial one [rad] (NaN otherwise).
  double theta = std::numeric_limits<double>::quiet_NaN();
};

/// The ledger at the end of the run, relative to the initial state, across all segments.
struct StudyLedger {
  /// Kinetic energy, translational and rotational [J]; potential [J]; E = T + V [J].
  double kinetic_translational = 0.0;
  double kinetic_rotational = 0.0;
  double potential = 0.0;
  double energy = 0.0;
  /// Mechanical energy at the start [J].
  double energy_initial = 0.0;
  /// Non-conservative work of all force elements [J], and of each (scene order) [J].
  double work_nonconservative = 0.0;
  std::vector<std::pair<std::string, double>> work_by_force;
  /// The potential energy of each force element that has one (gravity, a spring) [J]; their
  /// sum is `potential`. Such an element's work is -ΔV, in the energy, not in W_nc.
  std::vector<std::pair<std::string, double>> potential_by_force;
  /// Work of each joint, rolling contact and driver (Model order) [J]: zero for the ideal
  /// ones up to the integration error, a driver's input otherwise (part of W_nc).
  std::vector<std::pair<std::string, double>> work_by_constraint;
  /// Work of sliding friction, of rolling resistance, and the kinetic-energy change at
  /// impacts at all contacts and strings snapping taut, since t = 0 [J] (each <= 0; part of
  /// W_nc).
  double friction_work = 0.0;
  double rolling_work = 0.0;
  double impact_work = 0.0;
  /// Energy removed by dampers, drag, friction and impacts [J] >= 0.
  double dissipated = 0.0;
  /// Sum of the energy jumps at impulses and impacts [J].
  double jumps = 0.0;
  /// E - E0 - W_nc - jumps [J]: zero for the exact solution.
  double residual = 0.0;
  /// integrator: auto: the part of `residual` that is time stepping's own [J] (its scheme's
  /// energy error, and the energy the projections of its penetration changed at its handovers
  /// to the event-driven engine); the ledger check takes it out. 0 otherwise.
  double time_stepping_error = 0.0;
  /// Energy scale for the residual [J].
  double energy_scale = 0.0;
  /// Linear momentum, angular momentum about the system's centre of mass and about the
  /// origin, in W [kg·m/s, kg·m²/s].
  Vec3 linear_momentum_W = Vec3::Zero();
  Vec3 angular_momentum_Scm_W = Vec3::Zero();
  Vec3 angular_momentum_Wo_W = Vec3::Zero();
};

/// One force (or pure moment) a force element applies at one instant (AppliedForceRecord with
/// names): gravity on each body, an applied force, each end of a spring, a drive's moment.
struct StudyAppliedForce {
  std::string element, body;
  /// The point it acts at (the centre of mass for a pure moment), the force and the moment, W.
  Vec3 p_WP = Vec3::Zero();
  Vec3 F_W = Vec3::Zero();
  Vec3 M_W = Vec3::Zero();
  /// True for a pure moment, false for a force.
  bool is_moment = false;
};

/// Where a user body's frame B is at one instant: its origin Bo and its orientation, from the
/// state (CalcMappedBodyMotion: exact for a part of a composite too).
struct StudyBodyPose {
  /// Origin Bo of B in W [m].
  Vec3 p_WBo = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  /// Orientation of B in W, with w >= 0 (as the quaternion columns print it).
  Quat q_WB = Quat(Eigen::Vector4d::Constant(std::numeric_limits<double>::quiet_NaN()));
};

/// Bodies, reactions and contact points at one instant (an event, the end of the run).
struct StudySnapshot {
  std::vector<StudyBodyState> bodies;
  /// Reaction of every joint, rolling contact and driver (Model order; a planar scene's plane
  /// constraints left out).
  std::vector<StudyReaction> reactions;
  /// Every contact point (Model order), in the modes of that instant.
  std::vector<StudyContactPoint> contacts;
  /// What every force element applies (Model order; per element in the order it adds them).
  std::vector<StudyAppliedForce> forces;
};

struct StudyEvent {
  std::string name;
  /// Time of the crossing [s].
  double t = 0.0;
  /// True when it stopped the run.
  bool stopped = false;
  /// The full state at the event: bodies, reactions and contact points (for a contact-mode
  /// event, just after the change, in the new modes).
  StudySnapshot snapshot;
  /// The output columns at the event's state (StudyResult::columns; not a row of the CSV):
  /// extremes over a run (a sweep's max(COLUMN)) see the event instants as well as the samples.
  std::vector<double> row;
};

/// The engines a study's run can switch between (StudyDefinition::auto_engine).
enum class StudyEngine {
  kAdaptive,  ///< the hybrid event-driven engine (Simulate, Dormand–Prince between events)
  kStepping,  ///< Moreau–Jean time stepping (SimulateTimeStepping)
};
/// "adaptive", "stepping" (the scene's names of the two integrators).
const char* StudyEngineName(StudyEngine engine);

/// Why an engine took over the run.
enum class EngineSwitch {
  kStart,          ///< the run starts event-driven
  kRegimeChanges,  ///< regime changes came faster than the bound (EngineChoiceRule)
  kQuiet,          ///< no regime changed for the quiet span
};
/// "start", "regime changes", "quiet".
const char* EngineSwitchName(EngineSwitch reason);

/// One stretch of a run on one engine (integrator: auto).
struct StudyEngineSegment {
  /// From and to [s].
  double t_begin = 0.0, t_end = 0.0;
  StudyEngine engine = StudyEngine::kAdaptive;
  EngineSwitch reason = EngineSwitch::kStart;
  /// kRegimeChanges: the consecutive regime changes counted, the span they fell in [s] (less
  /// than the rule's window), and the contact point (or string) of the last.
  int changes = 0;
  double span = 0.0;
  std::string where;
  /// kQuiet: how long no regime had changed [s] (at least the rule's quiet span).
  double quiet = 0.0;
  /// A segment that cannot hand over to the other engine: why (empty when it can). An
  /// event-driven one where time stepping cannot run; a time-stepped one (from the start) where
  /// every pair of balls may collide (TimeSteppingOptions::collide_all_pairs), which only time
  /// stepping finds.
  std::string stays;
  /// An event-driven segment: the most islands its runs split the model into, each island run
  /// as its own hybrid system counting its own regime changes (1: one system; docs/contact.md,
  /// "Choosing the engine").
  int islands = 1;
  /// The engine's work in this segment: an event-driven one's integration steps, rejected steps
  /// and evaluations; a time-stepped one's steps and contact solves.
  IntegratorStats stats;
  /// A time-stepped segment: the certificate of its steps (the worst step and the totals, as
  /// TimeSteppingResult gives them) and whether every step met its tolerances.
  TimeSteppingSummary stepping;
  bool tolerance_met = true;
  /// An event-driven segment after a time-stepped one: its start projects the touching points
  /// onto their planes (the scheme leaves them up to half a step times their approach speed
  /// deep): the largest penetration removed [m] and the energy it changed [J] (booked with the
  /// scheme's own energy error, not as work).
  double projection_depth = 0.0;
  double projection_energy = 0.0;
};

/// What an event-driven run did (StudyDefinition::sphere_events): its counts, its ball-ball
/// collisions and its own energy balance, each term from its closed form.
struct StudyEventDriven {
  SphereEventStats stats;
  long collisions = 0;
  SphereEnergyCheck energy;
};

struct StudyResult {
  /// CSV column names and one row per output sample (plus the states just after jumps).
  std::vector<std::string> columns;
  /// SI unit of each column ("s", "m/s^2", "rad"; "" for a pure number), from the
  /// definition's `column_units` (a scene's: chasles/scene/column_units.h); empty when it has
  /// none (the CSV header then has no units).
  std::vector<std::string> units;
  std::vector<std::vector<double>> rows;
  std::vector<StudyEvent> events;
  std::vector<StudyJump> jumps;
  /// Contact mode changes and impacts in time order.
  std::vector<StudyContactEvent> contact_events;
  std::vector<StudyImpact> impacts;
  /// Mode changes of the strings that can go slack, with their initial modes, in time order.
  std::vector<StudyStringEvent> string_events;
  /// Every contact point at the end (Model order).
  std::vector<StudyContactPoint> final_contacts;
  /// Time the run ended [s] (the end time, or a stopping event's time).
  double t_end = 0.0;
  bool stopped_by_event = false;
  std::vector<StudyBodyState> final_bodies;
  /// Reaction of every joint, rolling contact and driver at the final state (Model order).
  std::vector<StudyReaction> final_reactions;
  StudyLedger ledger;
  /// The engine the run was asked for (a scene's `integrator: events`, `stepping`, `auto`, or
  /// the integrator of its options), that integrator, and the work counters summed over the
  /// segments.
  EngineRequest engine = EngineRequest::kIntegrator;
  IntegratorKind integrator = IntegratorKind::kDormandPrince5;
  IntegratorStats stats;
  /// How the last hybrid run was split into islands (count 0: no contacts or strings).
  IslandReport islands;
  /// The run's path and why (ChooseRunPath; for a hybrid run, its last Simulate's).
  RunPathChoice run_path;
  /// Set for an event-driven run (StudyDefinition::sphere_events); `stats` then counts its
  /// pressing groups' hybrid runs.
  std::optional<StudyEventDriven> event_driven;
  /// Set for a time-stepped run (StudyDefinition::time_stepping): its step [s], the worst of
  /// its steps' certificates and its ledger's totals, whether every step met its tolerances,
  /// and each contact point's regime changes over the run (by label, in the model's order).
  struct TimeStepped {
    double step = 0.0;
    TimeSteppingSummary summary;
    bool tolerance_met = true;
    std::vector<std::pair<std::string, int>> regime_changes;
  };
  std::optional<TimeStepped> time_stepping;
  /// integrator: auto: the engines in time order, each with why it took over (empty for a run
  /// on the engine its definition names).
  std::vector<StudyEngineSegment> segments;
  /// integrator: auto: the rule it followed (step, bound on regime changes, quiet span).
  std::optional<EngineChoiceRule> engine_rule;
  /// integrator: auto because the definition named no engine (AutoEngine::by_default).
  bool engine_by_default = false;
  /// Things to tell the user (impulses after the end time, ...).
  std::vector<std::string> notes;
  /// Things the user must know: initial values changed to satisfy the constraints
  /// (`project_initial: true`), statically indeterminate reactions (redundant constraints),
  /// jams (sliding without consistent contact forces).
  std::vector<std::string> warnings;
  /// The run's checks of its own answer at every sample and event (analysis/certificate.h).
  Certificate certificate;
  /// With StudyDefinition::record_row_snapshots: the reactions and contact points at each row
  /// of `rows` (same order and count; bodies left empty: the rows hold the poses).
  std::vector<StudySnapshot> row_snapshots;
  /// With StudyDefinition::record_row_poses: every user body's pose (definition order) at each
  /// row of `rows` (same order and count), taken from the state whatever the columns are.
  std::vector<std::vector<StudyBodyPose>> row_poses;
};

/// Runs a study. Throws InputError for bad settings, and for a force, reaction, acceleration
/// or state that becomes non-finite (naming the element, the quantity and the time: nothing
/// non-finite is ever returned); LimitError when a limit on the work is reached. An
/// InputError's element (InputError::element) that is a body is a user body (an index into
/// definition.bodies), whatever segment's Model the run was on; the other kinds are Model
/// indices, the same in every segment (the ModelBuilder places them alike). Every error goes
/// through the definition's `locate_error` when it has one (a scene's: a SceneError at the
/// file:line:col of the entry it concerns, a limit at the `simulation` key that sets it).
StudyResult RunStudy(const StudyDefinition& definition);

/// Mechanical energy T + V of the whole Model at `state` [J].
double CalcMechanicalEnergy(const Model& model, const State& state);

}  // namespace chasles
