#pragma once
/// @file
/// State: the plain, copyable data an integrator advances. Snapshots, checkpoints and sweeps
/// are copies of it. Quaternions are (w, x, y, z) wherever read or printed.

#include <limits>
#include <vector>

#include "chasles/math/types.h"
#include "chasles/model/contact.h"

namespace chasles {

class Model;

/// Motion of one free body. Default-constructed values are NaN so a forgotten one shows.
struct BodyState {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  /// Position of the centre of mass Bcm in the world W [m].
  Vec3 p_WBcm = Vec3::Constant(kNaN);
  /// Orientation of B in W, unit quaternion; rotates B-expressed vectors into W.
  Quat q_WB = Quat(kNaN, kNaN, kNaN, kNaN);
  /// Velocity of Bcm in W, expressed in W [m/s].
  Vec3 v_WBcm_W = Vec3::Constant(kNaN);
  /// Angular velocity of B in W, expressed in B [rad/s].
  Vec3 w_WB_B = Vec3::Constant(kNaN);
};

/// Running integrals of one force element along the solution. Integrators carry them as extra
/// ODE states so they are as accurate as the motion itself (the ledger reads them).
struct ForceIntegrals {
  /// Work done by the element, ∫ P dt [J].
  double work = 0.0;
  /// Work done by its non-conservative part (all of it unless it has a potential) [J].
  double work_nonconservative = 0.0;
  /// Linear impulse ∫ ΣF dt of the element's forces on all bodies, in W [N·s].
  Vec3 linear_impulse_W = Vec3::Zero();
  /// Angular impulse ∫ Σ(p × F + M) dt about the world origin Wo, in W [N·m·s].
  Vec3 angular_impulse_Wo_W = Vec3::Zero();
};

/// Discrete state and running integrals of one contact point (Model::num_contact_points()
/// entries). The mode is carried with the continuous state so samples and events show it.
struct ContactPointState {
  /// Current mode.
  ContactMode mode = ContactMode::kSeparated;
  /// Reference slip direction of a sliding point, in W (unit): the slip direction when the
  /// mode began; friction is -mu_k N along the slip, whose sign is taken relative to this
  /// direction so that the force stays smooth while the slip passes through zero.
  Vec3 slip_direction_W = Vec3::Zero();
  /// Reference rolling direction (unit angular velocity of rolling, in W) for rolling
  /// resistance, fixed like slip_direction_W when the mode began; zero when not rolling.
  Vec3 rolling_direction_W = Vec3::Zero();
  /// A sticking round point with rolling resistance whose rolling is held (static rolling
  /// resistance): its rolling angular velocity is held at zero by a resisting moment of at
  /// most mu_r N R (docs/contact.md, "Rolling resistance"). False in every other mode.
  bool rolling_held = false;
  /// Work done by sliding friction on the bodies since the start, ∫ f·v_slip dt [J] (<= 0).
  double friction_work = 0.0;
  /// Work done by the rolling-resistance moment since the start [J] (<= 0).
  double rolling_work = 0.0;
  /// Kinetic-energy change at impacts (and accumulated bounces) since the start [J] (<= 0).
  double impact_work = 0.0;
};

/// Work done at contacts the model does not list [J] (each <= 0): the event-driven path's
/// collisions between balls under SphereEventOptions::pair_law (collide_all_pairs), which have
/// no contact point of their own. Simulate never sets it.
struct ContactWork {
  double friction_work = 0.0;
  double rolling_work = 0.0;
  double impact_work = 0.0;
};

/// Mode of a constraint that can let go (Constraint::can_release): a string is taut
/// (kEngaged: its rows hold, its multiplier is the tension >= 0) or slack (kReleased: no rows,
/// no force). Other switching constraints (a brake that locks or slips) can use the same list.
enum class ConstraintMode { kEngaged, kReleased };

/// Discrete state and running integrals of one constraint.
struct ConstraintModeState {
  /// Current mode.
  ConstraintMode mode = ConstraintMode::kEngaged;
  /// Kinetic-energy change at its impacts (a string snapping taut) since the start [J] (<= 0).
  double impact_work = 0.0;
};

struct State {
  /// Time [s].
  double t = 0.0;
  /// One entry per body, in the Model's body order.
  std::vector<BodyState> bodies;
  /// One entry per force element, in the Model's force order.
  std::vector<ForceIntegrals> force_integrals;
  /// One entry per constraint, in the Model's order: work done by its forces on all its
  /// bodies since the start, ∫ λᵀ J u dt [J] (zero for ideal joints and rolling; what a
  /// prescribed-motion driver puts in). Carried as ODE states like the force integrals.
  /// May be left empty (read as zeros), e.g. for a state made before the constraints were
  /// added to the model.
  std::vector<double> constraint_work;
  /// One entry per contact point (Model::num_contact_points()): mode and dissipated work.
  /// May be left empty: Simulate then chooses the initial modes (SelectContactModes).
  std::vector<ContactPointState> contacts;
  /// One entry per constraint, in the Model's order: its mode (taut or slack for a string) and
  /// the energy its impacts took. May be left empty: every constraint is then engaged, and
  /// Simulate chooses the modes of those that can let go (SelectConstraintModes).
  std::vector<ConstraintModeState> constraint_modes;
  /// Works at contacts the model does not list, since the start (see ContactWork).
  ContactWork unlisted_contact_work;
};

/// Whether constraint `c` is released (slack) in `state` (an empty list: none is).
inline bool IsReleased(const State& state, int c) {
  const auto i = static_cast<size_t>(c);
  return i < state.constraint_modes.size() &&
         state.constraint_modes[i].mode == ConstraintMode::kReleased;
}

/// A state for `model` at t = 0 with every body at rest at the world origin, identity
/// orientation, and zero force integrals and constraint work.
State MakeRestState(const Model& model);

/// Places body `b`'s own frame origin Bo at p_WBo [m] with orientation q_WB (normalised here):
/// sets p_WBcm = p_WBo + R_WB p_BoBcm_B. Throws InputError for a zero or non-finite quaternion.
void SetBodyPose(const Model& model, int b, const Vec3& p_WBo, const Quat& q_WB, State& state);

/// Sets body `b`'s motion from the velocity of its frame origin Bo and its angular velocity,
/// both expressed in W: v_WBcm = v_WBo + w × (R_WB p_BoBcm_B); w_WB_B = R_WBᵀ w_WB_W.
/// Call after SetBodyPose.
void SetBodyVelocity(const Model& model, int b, const Vec3& v_WBo_W, const Vec3& w_WB_W,
                     State& state);

/// Position of body `b`'s frame origin Bo in W [m].
Vec3 CalcBodyOriginPosition(const Model& model, const State& state, int b);

/// Throws InputError naming the body and value when `state` does not fit `model` or holds a
/// non-finite number or a quaternion far (1e-6) from unit length.
void ValidateState(const Model& model, const State& state);

}  // namespace chasles
