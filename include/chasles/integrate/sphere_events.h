#pragma once
/// @file
/// Event-driven simulation of spheres on a level plane (a break shot on a billiard table):
/// between events every ball moves in closed form, so regimes change at exact times and the
/// cost is per event, not per step.
///
/// A ball (a body with isotropic central inertia I and one sphere contact centred at its centre
/// of mass) on a plane normal to uniform gravity g is in one of four phases (chapter 8.3,
/// Problems 8.26-8.27 in three dimensions; docs/contact.md, "Event-driven spheres"):
///  - flight: r = r0 + v0 t + ½ g t², ω constant, until it lands (an impact);
///  - sliding: the slip u = v - R ω × n keeps its direction ŝ, friction -mu_k m g ŝ:
///    v̇ = -mu_k g ŝ, ω̇ = (mu_k m g R / I) n × ŝ, u̇ = -mu_k g (1 + m R²/I) ŝ, until u = 0 at
///    t* = |u0| / (mu_k g (1 + m R²/I));
///  - rolling: v = R ω × n; rolling resistance mu_r N R gives v̇ = -mu_r g v̂ / (1 + I/(m R²)),
///    until the ball stops;
///  - rest: v = 0, spinning about n only (no spin friction at a point contact).
/// Two balls meet when |r_a(t) - r_b(t)| = R_a + R_b, a quartic in t within their current
/// segments, solved exactly; a broadphase grid in the plane proposes the pairs. An impact
/// (ball-ball or ball-plane) is resolved by ResolveImpacts on the balls touching at that
/// instant, their plane contacts included, so friction, restitution laws and simultaneous
/// impacts are the hybrid engine's. Balls that come to press on each other (no closed form)
/// run as a group on the hybrid engine, in windows no other ball can reach, until they part.

#include <functional>
#include <string>
#include <vector>

#include "chasles/dynamics/contact_solve.h"
#include "chasles/integrate/obstacle.h"
#include "chasles/integrate/simulate.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {

/// Coefficients of the collisions between balls that the model does not list as sphere-sphere
/// contacts (when `SphereEventOptions::collide_all_pairs`).
struct SphereCollisionLaw {
  double restitution = 0.0;
  double mu_s = 0.0;
  double mu_k = 0.0;
  RestitutionLaw law = RestitutionLaw::kEnergetic;
};

struct SphereEventOptions {
  /// End time [s].
  double t_end = 0.0;
  /// Output interval [s]; 0: only the initial and final states.
  double output_interval = 0.0;
  /// Every pair of balls may collide (with `pair_law`, or a listed sphere-sphere contact's
  /// coefficients for its pair); false: only the pairs the model lists.
  bool collide_all_pairs = false;
  SphereCollisionLaw pair_law;
  ContactTolerances tolerances;
  /// Integrator tolerances for balls pressing on each other, which run as a group on the
  /// hybrid engine (Dormand-Prince) until they part.
  AdaptiveOptions hybrid = {1e-10, 1e-13};
  /// Called with the time after every event handled and every step of a pressing group's
  /// hybrid run (optional): the caller shows progress, counts the work and stops a run that
  /// exceeds its limits by throwing (LimitError).
  std::function<void(double t)> on_progress = nullptr;
};

/// One ball-ball impact.
struct SphereCollision {
  double t = 0.0;
  BodyIndex body_a = kWorld;
  BodyIndex body_b = kWorld;
  /// Normal approach speed before [m/s].
  double approach_speed = 0.0;
  /// Impulse on a (b takes its opposite), in W [N·s].
  double normal_impulse = 0.0;
  Vec3 impulse_on_a_W = Vec3::Zero();
  /// Kinetic energy lost in the whole impact (every ball in it) [J] (>= 0).
  double energy_lost = 0.0;
  /// The restitution law of the pair.
  RestitutionLaw law = RestitutionLaw::kEnergetic;
  /// Balls in the impact (2 for a pair; more when others touched at that instant).
  int cluster_size = 0;
};

struct SphereEventStats {
  /// Phase changes without an impact (slip stopped, rolling stopped).
  long phase_events = 0;
  /// Impacts resolved (each may involve several balls).
  long impacts = 0;
  /// Broadphase box renewals and exact pair tests (quartic root isolations).
  long box_renewals = 0;
  long pair_tests = 0;
  /// Pressing groups formed, and the windows the hybrid engine ran them for.
  long groups = 0;
  long group_windows = 0;
  /// The hybrid engine's work over all the groups' runs.
  IntegratorStats hybrid;
};

/// The run's own check: energy at the end against the initial energy plus the work of
/// friction, rolling resistance and the impacts' losses, each from its closed form.
struct SphereEnergyCheck {
  double initial = 0.0;   ///< kinetic + potential at the start [J]
  double final = 0.0;     ///< at the end [J]
  double friction = 0.0;  ///< sliding friction's work (<= 0) [J]
  double rolling = 0.0;   ///< rolling resistance's work (<= 0) [J]
  double impacts = 0.0;   ///< kinetic energy change in impacts (<= 0) [J]
  double residual = 0.0;  ///< final - (initial + friction + rolling + impacts) [J]
};

struct SphereEventResult {
  /// Initial state, one per output time, final state.
  std::vector<State> samples;
  State final_state;
  /// Mode changes of the plane contacts (initial modes first, then in time order).
  std::vector<ContactEvent> contact_events;
  /// Impacts with the plane, in time order.
  std::vector<ImpactRecord> plane_impacts;
  /// Ball-ball impacts, in time order.
  std::vector<SphereCollision> collisions;
  SphereEventStats stats;
  SphereEnergyCheck energy;
  /// What the run adjusted in the given state (a normal velocity or a slip within the contact
  /// tolerances, taken as zero).
  std::vector<std::string> warnings;
};

/// Why `model` cannot run event-driven: names the first body, contact or force element that
/// does not fit (see the file comment); empty when it can.
ModelObstacle SphereEventObstacle(const Model& model);

/// Runs the balls of `model` from `initial` to options.t_end. Throws InputError when the model
/// does not fit (SphereEventObstacle), the initial state has a ball below the plane or two
/// balls overlapping, or more than 200 balls come to press on each other at once.
SphereEventResult SimulateSphereEvents(const Model& model, const State& initial,
                                       const SphereEventOptions& options);

}  // namespace chasles
