#pragma once
/// @file
/// Contact dynamics in each mode (chapter 8.3 with Coulomb friction), mode selection and
/// impacts. Per contact point C with normal n and tangents t1, t2, the rows are the velocity
/// of the body's material point at C relative to the plane (or the other sphere), as for
/// RollingContact:  k·v_C = J_k u  (k = n, t1, t2),  J_k u̇ = c_k at acceleration level.
///   separated: no rows.
///   sticking:  three rows n, t1, t2 (bilateral while the mode lasts) with multipliers
///              N (normal force) and f1, f2 (friction); |f| <= mu_s N is checked by events.
///   sliding:   the normal row only; friction -mu_k N s acts with it (s the unit slip
///              direction), so the force direction of that row is W = J_n - mu_k J_s and the
///              multiplier system (J M⁻¹ Wᵀ) λ = c - J u̇_free is not symmetric: it is solved
///              by LU (LDLᵀ when no point slides).
/// Rolling resistance: on a sticking round feature (sphere, rim) with rolling angular velocity
/// w_r (the part of the relative angular velocity along the plane), a moment -mu_r N R ŵ_r
/// joins the normal row's force direction.
/// Mode selection solves the normal complementarity 0 <= N ⟂ a_n >= 0 as an LCP (lcp.h) and
/// checks stick against mu_s. Impacts integrate the impulse (impact.h). docs/contact.md has
/// the derivations and the choices.

#include <vector>

#include "chasles/model/data.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {

/// The contact stage (called by CalcAccelerations for models with contacts, in place of the
/// constraint stage): solves the constraints and the active contact rows of the modes in
/// `state.contacts` together; overwrites the accelerations and fills Data::contact_points,
/// Data::constraints, Data::lambda. A state without contact entries reads as all separated.
void SolveContactForces(const Model& model, const State& state, Data& data);

/// Per contact point outputs (normal and friction force, slip velocity, gap, ...) at `state`
/// in the modes it carries: runs CalcAccelerations on a fresh Data. For reports.
std::vector<ContactPointOutput> CalcContactOutputs(const Model& model, const State& state);

/// A slip speed at or below this has no direction of its own [m/s]: the round-off of the
/// velocity of a body at rest. A sliding point keeps its mode's reference direction until its
/// slip exceeds this and 1e-10 of its material point's speed (ContactPointGeometry).
inline constexpr double kSlipSpeedRoundOff = 1e-14;

/// Tolerances of mode selection and impacts.
struct ContactTolerances {
  /// A point with gap at or below this is touching [m].
  double gap = 1e-9;
  /// Normal approach speed at or below this is resting contact, not an impact [m/s].
  double resting_speed = 1e-6;
  /// Slip speed at or below this may stick [m/s].
  double stick_speed = 1e-6;
  /// Relative tolerance of the sign tests (which points press, negative normal forces).
  double relative = 1e-9;
  /// Relative tolerance of the friction-cone test (round-off level): |f| within
  /// cone·max(|f|, mu_s N) of mu_s N is at the limit, decided by the motion (see
  /// SelectContactModes).
  double cone = 1e-12;
};

/// What changed at one contact point in SelectContactModes or ResolveImpacts.
struct ContactModeChange {
  /// Contact point index (see Model::contact_point_name).
  int point = -1;
  ContactMode from = ContactMode::kSeparated;
  ContactMode to = ContactMode::kSeparated;
  /// Rolling held before and after (ContactPointState::rolling_held).
  bool held_from = false, held_to = false;
};

/// A jam: sliding points whose contact forces had no consistent solution (a Painlevé-type
/// paradox) are stopped by an impulse, an impact without collision (docs/contact.md).
struct JamImpulse {
  /// Contact point index.
  int point = -1;
  /// Normal impulse [N·s] (>= 0) and the whole impulse on the body, in W [N·s].
  double normal_impulse = 0.0;
  Vec3 impulse_W = Vec3::Zero();
  /// Slip speed stopped [m/s].
  double slip_speed = 0.0;
  /// Kinetic energy the jam removed, this point's share [J] (>= 0).
  double energy_lost = 0.0;
};

/// What the caller knows about the instant SelectContactModes chooses modes at: the event that
/// led there. At an event the quantity that crossed zero is zero to round-off, so the choice
/// between the two modes it separates is degenerate; the hint breaks the tie towards the mode
/// the crossing enters (otherwise the old mode would be chosen again and the event would fire
/// again at once).
struct ModeHints {
  /// Points whose friction limit was just crossed (tried as slipping first).
  std::vector<int> slip_starts;
  /// Points whose normal force just fell through zero: they leave unless they would then
  /// press into the surface by more than round-off (normal acceleration below -tol.relative
  /// of the acceleration scale).
  std::vector<int> lift_offs;
  /// Points whose held rolling just reached its limit mu_r N R (tried as rolling first).
  std::vector<int> rolling_starts;
};

/// What SelectContactModes had to do beyond choosing modes.
struct ModeSelectionNotes {
  /// Jammed points (empty when the modes had consistent forces).
  std::vector<JamImpulse> jams;
};

/// Chooses a consistent mode for every contact point at `state` (positions and velocities
/// fixed): points apart or moving apart are separated; among the touching ones an LCP on the
/// normal forces decides which press (N > 0) and which lift off (N = 0, a_n >= 0); pressing
/// points with slip slide; the others stick if the friction they need (computed as the
/// contact stage computes it) is within mu_s N, and otherwise start to slide in the direction
/// of impending slip (against the needed friction, then along the slip acceleration: maximum
/// dissipation), one point at a time, largest excess first, then the LCP again. A point
/// within tol.cone of its cone, or listed in `hints.slip_starts` (its friction limit was just
/// crossed), is tried as sliding and slides if its slip then grows (for `slip_starts`: does
/// not shrink); otherwise it sticks. A touching point in `hints.lift_offs` leaves when its
/// normal acceleration is round-off (the LCP is degenerate where its force just vanished). Writes
/// state.contacts (sizing it if empty), sets the slip and rolling reference directions, and removes
/// the round-off normal (and sticking tangential) velocities of the touching points by a
/// mass-weighted velocity projection (the kinetic energy it changes goes to
/// ContactPointState::friction_work). When the normal forces have no consistent solution with the
/// sliding friction (Painlevé), the sliding points are jammed (stopped by the projection's impulse,
/// energy to impact_work, listed in `notes`); an InputError says so when that impulse lies outside
/// the friction cone. Returns the changes.
std::vector<ContactModeChange> SelectContactModes(const Model& model, State& state,
                                                  const ContactTolerances& tol = {},
                                                  const ModeHints& hints = {},
                                                  ModeSelectionNotes* notes = nullptr);

}  // namespace chasles

// Impacts (ResolveImpacts, ResolvePlasticImpact) use ContactTolerances above.
#include "chasles/dynamics/impact.h"  // IWYU pragma: export
