#pragma once
/// @file
/// Impacts with Coulomb friction by integrating the impulse (Routh, Dynamics of a System of
/// Rigid Bodies, 1905, §§ 183-189; Stronge, Impact Mechanics, 2000, ch. 4-5). Over the impact
/// instant positions are fixed and the relative velocities of the contact points are linear in
/// the impulses P (normal and tangential, per point):
///   v(P) = v⁻ + K P,   K = J M_c⁻¹ Jᵀ
/// with J the rows n, t1, t2 of every touching point and M_c⁻¹ the inverse mass restricted to
/// the model's constraints (joints move with the bodies). The impulse is integrated along the
/// normal impulse: while a point slides, dP_t = -mu_k dP_n ŝ with ŝ the current slip
/// direction; when its slip reaches zero it sticks if the tangential rate it needs is within
/// mu_s, else slides in the direction the sticking demand sets. Compression ends at v_n = 0;
/// restitution ends by the contact's RestitutionLaw. Several points: one common impulse
/// parameter, the normal impulse rates from an LCP at each step (docs/contact.md, Impacts).

#include <vector>

#include "chasles/dynamics/contact_solve.h"
#include "chasles/model/contact.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {

/// One impact at one contact point.
struct ContactImpulse {
  /// Contact point index.
  int point = -1;
  /// Normal approach speed before, -v_n⁻ > 0 [m/s].
  double approach_speed = 0.0;
  /// Normal impulse P_n >= 0 [N·s].
  double normal_impulse = 0.0;
  /// Normal impulse at the end of compression [N·s].
  double compression_impulse = 0.0;
  /// Work of the normal impulse in compression (<= 0) and in total [J].
  double compression_work = 0.0;
  double normal_work = 0.0;
  /// Impulse on the body (normal + friction), in W [N·s].
  Vec3 impulse_W = Vec3::Zero();
  /// True when the point ends the impulse sticking (no slip after).
  bool sticking = false;
  /// The restitution law used at this point.
  RestitutionLaw law = RestitutionLaw::kEnergetic;
};

/// Result of ResolveImpacts.
struct ImpactResult {
  /// Impulses of the points that took part (empty: no impact).
  std::vector<ContactImpulse> impulses;
  /// Kinetic energy before and after [J].
  double kinetic_energy_before = 0.0;
  double kinetic_energy_after = 0.0;
  /// True when the integrated impulse with friction would have raised the kinetic energy
  /// (possible with Newton's and Poisson's laws, never with the energetic one) or could not be
  /// completed, and the frictionless impulse (which never raises it for e <= 1) was used
  /// instead. Reports say so.
  bool frictionless_fallback = false;
  /// Integration steps taken (pieces of the piecewise-smooth impulse path).
  int steps = 0;
};

/// Impacts at `state`: every touching point (gap <= tol.gap) approaching faster than
/// tol.resting_speed makes an impact; every touching point not moving apart takes part.
/// Updates the velocities and ContactPointState::impact_work of the points (ΔT split by
/// normal impulse share).
ImpactResult ResolveImpacts(const Model& model, State& state, const ContactTolerances& tol = {});

/// ResolveImpacts with restitution 0 at contact point `point` (the others keep theirs): ends a
/// bounce sequence at once, as its accumulation limit does (docs/contact.md, Zeno).
ImpactResult ResolvePlasticImpact(const Model& model, State& state, int point,
                                  const ContactTolerances& tol = {});

}  // namespace chasles
