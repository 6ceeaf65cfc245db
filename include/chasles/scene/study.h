#pragma once
/// @file
/// A study: a scene's dynamics turned into a Model, an initial State and SimulationOptions,
/// and the run of it with impulses and impacts (docs/scene-format.md, "Dynamics").
///
/// Impulses and impacts split the run into segments. Between them Simulate integrates the
/// current Model; at each instant the state jumps (ApplyImpulse, ApplyPassThrough) or, when a
/// projectile embeds, a new Model is built with the composite body (Models are immutable).
/// The ledger is carried across the segments: each segment's work-energy residual adds up, and
/// the kinetic-energy jumps are booked separately, so that
///   E - E0 = W_nc + jumps + residual.
/// Output samples lie on one grid t = k * output_interval from 0 whatever the segments.

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "chasles/analysis/certificate.h"
#include "chasles/error.h"
#include "chasles/integrate/simulate.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"
#include "chasles/scene/scene.h"

namespace chasles {

/// The first segment of a scene's run, ready for Simulate.
struct Study {
  /// Held by pointer: the force and event functions read it, so its address must not change.
  std::shared_ptr<const Model> model;
  State initial;
  /// Integrator, end time, output interval, tolerances and events from the scene.
  SimulationOptions options;
  /// Initial values changed to satisfy the constraints (`project_initial: true`), one each.
  std::vector<std::string> warnings;
};

/// Builds the Model (one body per scene body, gravity, the scene's force elements, and its
/// joints, rolling contacts and drivers with attachment frames taken from their world poses at
/// the initial State), the initial State and the options. `until` [s] overrides the scene's end
/// time when finite. Throws InputError when there is no end time or a value is invalid.
Study BuildStudy(const Scene& scene, double until = std::numeric_limits<double>::quiet_NaN());

struct StudyOptions {
  /// End time [s], overriding the scene's when finite.
  double until = std::numeric_limits<double>::quiet_NaN();
  /// Called with the time of every output sample and every accepted step (e.g. for a
  /// progress display).
  std::function<void(double t)> progress;
  /// Limits on the run's work replacing the scene's `simulation:` keys (command-line flags;
  /// docs/reliability-limits.md): accepted integration steps and output rows (< 1: the
  /// scene's), wall time [s] (0: none; NaN: the scene's) and the smallest step [s] (NaN: the
  /// scene's, or 1e-12 of the span).
  std::int64_t max_steps = 0;
  std::int64_t max_rows = 0;
  double timeout = std::numeric_limits<double>::quiet_NaN();
  double min_step = std::numeric_limits<double>::quiet_NaN();
};

/// An impulse or impact applied during the run.
struct StudyJump {
  /// "impulse", "embedding" or "pass-through".
  std::string kind;
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
};

/// A mode change of one contact point (the mode timeline; the initial modes come first, with
/// reason "initial").
struct StudyContactEvent {
  /// Time [s] (located to 1e-12 s).
  double t = 0.0;
  /// Contact point label (ContactPointLabels) and its contact's name.
  std::string point;
  std::string contact;
  /// Modes before and after ("separated", "sliding", "sticking") and why ("slip stopped", ...).
  std::string from, to, reason;
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
  /// The restitution law used ("energetic", "newton", "poisson").
  std::string restitution_law;
  /// True when the impulse with friction would have raised the kinetic energy and the
  /// frictionless one was used (ImpactResult::frictionless_fallback).
  bool frictionless_fallback = false;
};

/// One contact point at the end of the run.
struct StudyContactPoint {
  std::string point;
  std::string mode;
  /// Normal force [N], friction force in W [N], slip velocity in W [m/s], gap [m].
  double normal_force = 0.0;
  Vec3 friction_force_W = Vec3::Zero();
  Vec3 slip_velocity_W = Vec3::Zero();
  double gap = 0.0;
  /// Work of sliding friction, of rolling resistance, and energy lost in impacts at this point
  /// since t = 0 [J] (each <= 0).
  double friction_work = 0.0, rolling_work = 0.0, impact_work = 0.0;
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
  /// Work of each joint, rolling contact and driver (Model order) [J]: zero for the ideal
  /// ones up to the integration error, a driver's input otherwise (part of W_nc).
  std::vector<std::pair<std::string, double>> work_by_constraint;
  /// Work of sliding friction, of rolling resistance, and the kinetic-energy change at
  /// impacts, at all contacts since t = 0 [J] (each <= 0; part of W_nc).
  double friction_work = 0.0;
  double rolling_work = 0.0;
  double impact_work = 0.0;
  /// Energy removed by dampers, drag, friction and impacts [J] >= 0.
  double dissipated = 0.0;
  /// Sum of the energy jumps at impulses and impacts [J].
  double jumps = 0.0;
  /// E - E0 - W_nc - jumps [J]: zero for the exact solution.
  double residual = 0.0;
  /// Energy scale for the residual [J].
  double energy_scale = 0.0;
  /// Linear momentum, angular momentum about the system's centre of mass and about the
  /// origin, in W [kg·m/s, kg·m²/s].
  Vec3 linear_momentum_W = Vec3::Zero();
  Vec3 angular_momentum_Scm_W = Vec3::Zero();
  Vec3 angular_momentum_Wo_W = Vec3::Zero();
};

/// The reaction of one constraint at the end of the run.
struct StudyReaction {
  /// Name and kind ("revolute", "rolling sphere", ...).
  std::string name;
  std::string kind;
  /// Joint or contact point on the child, in W [m].
  Vec3 p_WJ = Vec3::Zero();
  /// Force and moment about J the parent (or the world) exerts on the child, in W [N, N·m].
  Vec3 F_Jc_W = Vec3::Zero();
  Vec3 M_Jc_W = Vec3::Zero();
  /// The same force and moment in the child's frame B [N, N·m].
  Vec3 F_Jc_B = Vec3::Zero();
  Vec3 M_Jc_B = Vec3::Zero();
  /// Power of its forces [W] (0 for ideal joints and rolling).
  double power = 0.0;
};

/// Bodies, reactions and contact points at one instant (an event, the end of the run).
struct StudySnapshot {
  std::vector<StudyBodyState> bodies;
  /// Reaction of every joint, rolling contact and driver (Model order; a planar scene's plane
  /// constraints left out).
  std::vector<StudyReaction> reactions;
  /// Every contact point (Model order), in the modes of that instant.
  std::vector<StudyContactPoint> contacts;
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
};

struct StudyResult {
  /// CSV column names and one row per output sample (plus the states just after jumps).
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
  std::vector<StudyEvent> events;
  std::vector<StudyJump> jumps;
  /// Contact mode changes and impacts in time order.
  std::vector<StudyContactEvent> contact_events;
  std::vector<StudyImpact> impacts;
  /// Every contact point at the end (Model order).
  std::vector<StudyContactPoint> final_contacts;
  /// Time the run ended [s] (the end time, or a stopping event's time).
  double t_end = 0.0;
  bool stopped_by_event = false;
  std::vector<StudyBodyState> final_bodies;
  /// Reaction of every joint, rolling contact and driver at the final state (Model order).
  std::vector<StudyReaction> final_reactions;
  StudyLedger ledger;
  /// Integrator name and work counters summed over the segments.
  std::string integrator;
  IntegratorStats stats;
  /// Things to tell the user (impulses after the end time, ...).
  std::vector<std::string> notes;
  /// Things the user must know: initial values changed to satisfy the constraints
  /// (`project_initial: true`), statically indeterminate reactions (redundant constraints),
  /// jams (sliding without consistent contact forces).
  std::vector<std::string> warnings;
  /// The run's checks of its own answer at every sample and event (analysis/certificate.h).
  Certificate certificate;
};

/// Runs the scene's study. Every error is a SceneError with the scene file's line and column
/// (ThrowAtSceneEntry): bad settings; a force, reaction, acceleration or state that becomes
/// non-finite (the element and the time are named; nothing non-finite is ever returned); a
/// limit on the work reached (steps, rows, wall time, smallest step: the message names the
/// limit and the flag and scene key that raise it). Limits that the run would exceed for sure
/// (rows from the span and the output interval, fixed steps, a spring too stiff for the step
/// budget) are refused before it starts.
StudyResult RunStudy(const Scene& scene, const StudyOptions& options = {});

/// Rethrows an InputError found after the scene was read (building the Model, assembling or
/// solving the constraints, during the run) as a SceneError at the entry of the first scene
/// element it names in quotes: a force element, constraint, contact (or contact point), body
/// or event; at the `simulation` key when it names none. A SceneError is rethrown as it is.
[[noreturn]] void ThrowAtSceneEntry(const Scene& scene, const InputError& error);

/// The CSV columns named on the command line (groups or single columns, as in the scene's
/// `output.columns`), with `t` first. Throws SceneError naming --columns for an unknown name.
std::vector<std::string> SelectColumns(const Scene& scene, const std::vector<std::string>& names);

}  // namespace chasles
