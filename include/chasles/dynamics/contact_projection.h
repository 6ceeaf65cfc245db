#pragma once
/// @file
/// Projection onto the active contact rows during a contact mode. Between events the contact
/// rows of the current modes hold only at acceleration level (J u̇ = c), so, like the joints
/// (constraint_solve.h, "Drift"), their position and velocity violations wander with the
/// integration error. After every accepted step the adaptive integrator projects the state
/// back, the constraints and the contact rows together (one mass-weighted problem, so the two
/// kinds of rows do not fight):
///   positions: Gauss–Newton on the holonomic constraint rows and the gap g of every point in
///     contact (sliding or sticking; the gap's gradient is the normal row, ġ = n·v_C):
///     δx = -M⁻¹Gᵀ(G M⁻¹Gᵀ)⁺ g;
///   velocities: all active rows, constraint rows J u = b, normal rows n·v_C = 0, and the
///     tangential rows t·v_C = 0 of sticking points (exact in one step, linear in u):
///     δu = -M⁻¹Jᵀ(J M⁻¹Jᵀ)⁺(J u - b).
/// The tangential rows of a sticking point are nonholonomic for a round feature and are held
/// at velocity level only (a body point that sticks has no stored anchor to return to: its
/// position drift is the integral of a slip kept at round-off). Redundant rows (a box on four
/// coplanar vertices) take the least-norm correction. The projection changes the kinetic
/// energy by a quantity of second order in the violation (mass-weighted projection), far below
/// the ledger's round-off; it is not booked.

#include "chasles/dynamics/constraint_solve.h"
#include "chasles/model/data.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {

/// How far `state` is from the active contact rows of the modes it carries.
struct ContactViolation {
  /// Largest |gap| of a point in contact (sliding or sticking) [m].
  double gap = 0.0;
  /// Largest |n·v_C| of a point in contact [m/s].
  double normal_velocity = 0.0;
  /// Largest slip speed |v_t| of a sticking point [m/s].
  double slip = 0.0;
  /// Contact point with the largest violation of any kind (-1 when none is in contact).
  int worst = -1;
};

/// Violations of the active contact rows at `state` (fills the kinematics stage of `data`).
ContactViolation CalcContactViolation(const Model& model, const State& state, Data& data);

/// True when `state` has a contact point in contact (sliding or sticking).
bool HasActiveContactRows(const Model& model, const State& state);

/// Projects `state` onto the constraints and the active contact rows of its modes: positions
/// (Gauss–Newton, mass-weighted), then velocities (exact). Without a point in contact this is
/// ProjectOntoConstraints. Throws InputError naming the constraint when a constraint's position
/// error stays above options.assembly_tolerance; contact gaps that cannot all close (four
/// vertices not quite coplanar) keep the least-squares remainder.
void ProjectOntoContactModes(const Model& model, State& state, Data& data,
                             const ProjectionOptions& options = {});

}  // namespace chasles
