#pragma once
/// @file
/// Modes of the constraints that can let go (Constraint::can_release: a string without drums)
/// and their impacts (docs/constraints.md, "Strings that go slack").
///
/// Such a constraint has one row: the gap g >= 0 (a string's slack L0 - L), its rate ġ = J u
/// (positive while the gap opens) and the multiplier λ (the tension). Engaged (taut) it holds
/// g̈ = 0 with λ >= 0; released (slack) λ = 0 and g̈ is free. At one instant with g = 0 and
/// ġ = 0 the choice is the complementarity
///   λ >= 0,  g̈ >= 0,  λ g̈ = 0,
/// an LCP over all such rows with g̈ = W λ + g̈_free, W = J_u M_c⁻¹ J_uᵀ the Delassus matrix of
/// the rows with the other constraints held (positive definite for independent rows, so the
/// LCP has one solution: Cottle, Pang & Stone, The Linear Complementarity Problem, 1992,
/// Thm. 3.3.7). It is solved by Murty's least-index principal pivoting (ibid. § 4.2), each
/// trial set solved by the constraint solve itself, so W never has to be formed.

#include <string>
#include <vector>

#include "chasles/dynamics/contact_solve.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {

/// A change of mode of one constraint.
struct ConstraintModeChange {
  /// Constraint index (Model order).
  int constraint = -1;
  ConstraintMode from = ConstraintMode::kEngaged;
  ConstraintMode to = ConstraintMode::kEngaged;
};

/// One constraint's share of an impact (a string snapping taut).
struct ConstraintImpulse {
  int constraint = -1;
  /// Closing speed before, -ġ⁻ > 0 [m/s].
  double approach_speed = 0.0;
  /// Impulse of its multiplier (the string's impulsive tension) [N·s] (>= 0).
  double impulse = 0.0;
  /// Its share of the kinetic energy lost (by impulse) [J] (>= 0).
  double energy_lost = 0.0;
};

/// Sizes state.constraint_modes for `model` (an empty list: every constraint engaged).
void EnsureConstraintModes(const Model& model, State& state);

/// Modes of every constraint that can let go at `state` (positions and velocities fixed): one
/// with gap g > tol.gap or opening (ġ > tol.resting_speed) is released; the others (at g = 0,
/// not closing faster than the resting speed) by the LCP above. `force_release` lists
/// constraints whose multiplier has just fallen through zero (an event): they are released
/// unless the LCP needs them. Returns the changes. Call ResolveConstraintImpacts first when a
/// gap may be closing.
std::vector<ConstraintModeChange> SelectConstraintModes(const Model& model, State& state,
                                                        const ContactTolerances& tol = {},
                                                        const std::vector<int>& force_release = {});

/// Impact of the constraints that can let go whose gap is closed (g <= tol.gap) and closing
/// faster than tol.resting_speed (a string snapping taut), with every engaged constraint held:
/// the impulse Λ = Jᵀ P over the rows of the engaged constraints and the closing ones, such
/// that after it the engaged rows keep J u⁺ = b and each closing row has ġ⁺ = -e ġ⁻ (Newton's
/// restitution, e = Constraint::restitution(); e = 0 plastic):
///   (J M⁻¹ Jᵀ) P = target - J u⁻,   u⁺ = u⁻ + M⁻¹ Jᵀ P.
/// The kinetic energy lost is added to the closing constraints' impact_work (split by impulse).
/// Contacts take no part (their impacts follow in the contact stage). Returns the impulses
/// (empty: no impact).
std::vector<ConstraintImpulse> ResolveConstraintImpacts(const Model& model, State& state,
                                                        const ContactTolerances& tol = {});

}  // namespace chasles
