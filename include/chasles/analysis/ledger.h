#pragma once
/// @file
/// The energy / work / momentum ledger of a run (chapter 8.4 work-energy, 8.5
/// impulse-momentum). The work and impulse of each force element are integrals carried as
/// extra ODE states (State::force_integrals), so they are as accurate as the motion.
/// Work-energy balance: (T + V) - (T₀ + V₀) = W_nc (the non-conservative work); the residual
/// of that equation measures the integration error. Impulse-momentum: P - P₀ = Σ Imp and
/// H_Wo - H_Wo₀ = Σ AngImp_Wo. Constraints: their work (zero for ideal joints and rolling, a
/// driver's input otherwise) counts as non-conservative work; their impulses are not carried,
/// so the momentum residuals of a constrained model include the supports' impulses.

#include <string>
#include <vector>

#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {

struct ForceLedger {
  /// Name of the force element.
  std::string name;
  /// Whether it has a potential energy / only dissipates.
  bool has_potential = false;
  bool dissipative = false;
  /// Potential energy at this state [J] (0 without one).
  double potential_energy = 0.0;
  /// Work done by it since the initial state [J].
  double work = 0.0;
  /// Work of its non-conservative part since the initial state [J].
  double work_nonconservative = 0.0;
  /// Linear impulse since the initial state, in W [N·s].
  Vec3 linear_impulse_W = Vec3::Zero();
  /// Angular impulse about the world origin since the initial state, in W [N·m·s].
  Vec3 angular_impulse_Wo_W = Vec3::Zero();
};

struct ConstraintLedger {
  /// Name of the constraint.
  std::string name;
  /// Work done by its forces on all its bodies since the initial state [J] (zero for ideal
  /// joints and rolling up to the integration error; a driver's input otherwise).
  double work = 0.0;
  /// Kinetic-energy change at its impacts (a string snapping taut) since the initial state
  /// [J] (<= 0).
  double impact_work = 0.0;
};

struct ContactLedger {
  /// Name of the contact point.
  std::string name;
  /// Work of sliding friction since the initial state [J] (<= 0).
  double friction_work = 0.0;
  /// Work of the rolling-resistance moment since the initial state [J] (<= 0).
  double rolling_work = 0.0;
  /// Kinetic-energy change at impacts since the initial state [J] (<= 0).
  double impact_work = 0.0;
};

struct LedgerSample {
  /// Time [s].
  double t = 0.0;
  /// Kinetic energy, translational (eq. 8.115) and rotational (eq. 8.115) parts [J].
  double kinetic_translational = 0.0;
  double kinetic_rotational = 0.0;
  /// Total potential energy (gravity, springs, central gravity) [J].
  double potential = 0.0;
  /// T + V [J].
  double mechanical_energy = 0.0;
  /// Non-conservative work of all elements and constraints since the initial state [J].
  double work_nonconservative = 0.0;
  /// Energy removed by dissipative elements (dampers, drag) since the initial state [J] >= 0.
  double dissipated = 0.0;
  /// (T + V) - (T₀ + V₀) - W_nc [J]: zero for the exact solution.
  double energy_residual = 0.0;
  /// Energy scale for judging the residual: max(|T₀| + |V₀|, |T| + |V|, Σ|W_nc|) [J].
  double energy_scale = 0.0;
  /// Linear momentum, in W [kg·m/s].
  Vec3 linear_momentum_W = Vec3::Zero();
  /// Centre of mass of the system, in W [m].
  Vec3 p_WScm = Vec3::Zero();
  /// Angular momentum about the system's centre of mass, in W [kg·m²/s].
  Vec3 angular_momentum_Scm_W = Vec3::Zero();
  /// Angular momentum about the world origin, in W [kg·m²/s].
  Vec3 angular_momentum_Wo_W = Vec3::Zero();
  /// P - P₀ - Σ linear impulses [N·s]: zero for the exact solution.
  Vec3 momentum_residual_W = Vec3::Zero();
  /// H_Wo - H_Wo₀ - Σ angular impulses about Wo [N·m·s]: zero for the exact solution.
  Vec3 angular_momentum_residual_W = Vec3::Zero();
  /// Per force element, in Model order.
  std::vector<ForceLedger> forces;
  /// Work of all constraint forces since the initial state [J] (part of work_nonconservative).
  double constraint_work = 0.0;
  /// Per constraint, in Model order.
  std::vector<ConstraintLedger> constraints;
  /// Work of sliding friction at all contacts since the initial state [J] (<= 0; part of
  /// work_nonconservative, and its negative part of dissipated).
  double contact_friction_work = 0.0;
  /// Work of rolling resistance at all contacts [J] (<= 0; likewise).
  double contact_rolling_work = 0.0;
  /// Kinetic energy lost in impacts, as work [J] (<= 0; likewise).
  double contact_impact_work = 0.0;
  /// Per contact point, in Model order.
  std::vector<ContactLedger> contacts;
  /// Kinetic energy lost when strings snap taut, as work [J] (<= 0; part of
  /// work_nonconservative, and its negative part of dissipated).
  double constraint_impact_work = 0.0;
};

/// The ledger at `state` relative to `initial` (the run's first state; its force integrals
/// are subtracted, so they need not be zero).
LedgerSample CalcLedgerSample(const Model& model, const State& state, const State& initial);

}  // namespace chasles
