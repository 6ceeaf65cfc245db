#pragma once
/// @file
/// The equations of motion as a first-order ODE y' = f(t, y) over a flat vector, for the
/// Runge–Kutta integrators. Layout per body: p_WBcm (3), q_WB (w, x, y, z) (4), v_WBcm_W (3),
/// w_WB_B (3); then per force element the integrals of its power, non-conservative power,
/// force (3) and moment about Wo (3); then per constraint the work of its forces; then per
/// contact point the work of sliding friction and of rolling resistance. The contact modes
/// and reference directions are discrete: set with SetDiscreteState, copied by Unpack.

#include <Eigen/Core>

#include "chasles/model/data.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles::internal {

/// Throws InputError naming the first part of an evaluation at `state` that is not finite: a
/// body's state (CheckFiniteState), a force element's force, moment or power, a constraint's
/// reaction, a contact point's forces, or (with `accelerations`) a body's acceleration; the message
/// names it by its name (the scene layer adds its line) and gives the time. Does nothing when all
/// are finite. Integration cannot recover from a non-finite value (every later step inherits it),
/// so the run stops at the first one instead of shrinking its step to nothing.
void CheckFiniteEvaluation(const Model& model, const State& state, const Data& data,
                           bool accelerations);

/// Throws InputError naming the first body whose state at `state.t` is not finite, which of
/// its quantities (position, orientation, velocity, angular velocity) and the time. Every
/// integrator calls it on the state it ends a step with and on every state it hands out
/// (samples, event states), so no non-finite state leaves Simulate.
void CheckFiniteState(const Model& model, const State& state);

inline constexpr int kBodySize = 13;
inline constexpr int kForceSize = 8;

using Vector = Eigen::VectorXd;

class OdeSystem {
 public:
  explicit OdeSystem(const Model& model);

  int size() const { return size_; }
  const Model& model() const { return model_; }

  void Pack(const State& state, Vector& y) const;
  /// Takes the discrete contact state (modes, reference directions, impact work) of `state`;
  /// the derivative and Unpack use it until the next call.
  void SetDiscreteState(const State& state);
  /// Copies y into `state` (already sized); quaternions as they stand.
  void Unpack(double t, const Vector& y, State& state) const;
  /// ydot = f(t, y). Uses an internal State and Data (no allocation).
  void Derivative(double t, const Vector& y, Vector& ydot);
  /// Scales each body's quaternion in y to unit length and the matching entries of `ydot` by
  /// the same factor (q̇ = ½ q ⊗ w is linear in q, so ydot stays f(t, y) exactly). With a
  /// `compensation` of y (internal/compensated.h), carries it across the normalisation: its
  /// quaternion part becomes its tangential part scaled by 1/|q| plus the rounding error of
  /// the scaling.
  void NormalizeQuaternions(Vector& y, Vector* ydot, Vector* compensation = nullptr) const;
  /// True when the model has constraints (then the state is projected after each step).
  bool has_constraints() const { return model_.num_constraints() > 0; }
  /// True when the state is projected after each step: the model has constraints, or (with
  /// `contacts`) a contact point is in contact in the discrete state (SetDiscreteState).
  bool projects(bool contacts) const;
  /// Projects `state` onto the constraint manifold and, with `contacts`, onto the active
  /// contact rows of its modes (positions, then velocities); see ProjectOntoConstraints and
  /// ProjectOntoContactModes.
  void Project(State& state, bool contacts);
  /// Number of derivative evaluations so far.
  long long evaluations() const { return evaluations_; }

 private:
  const Model& model_;
  int size_;
  int body_offset_end_;
  int contact_offset_;
  State state_;
  Data data_;
  long long evaluations_ = 0;
};

}  // namespace chasles::internal
