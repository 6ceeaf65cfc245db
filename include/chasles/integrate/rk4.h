#pragma once
/// @file
/// Classical fixed-step Runge–Kutta of order 4 on the first-order equations of motion
/// (positions, quaternions, velocities, body-frame angular velocities, force integrals).
/// The quaternion is integrated as four numbers with q̇ = ½ q ⊗ (0, w_WB_B) and renormalised
/// after every step: the projection changes it by O(h⁵) (the norm's drift is a local error
/// term) so the order stays 4 and |q| = 1 to round-off at every output.
/// Models with constraints: the state is projected onto the constraint manifold after each
/// step (ProjectOntoConstraints), so positions and velocities do not drift.
/// The increment y₁ − y₀ = (h/6)(k₁ + 2k₂ + 2k₃ + k₄) and the time step are added with
/// compensation (src/integrate/internal/compensated.h): the integrator keeps, per state
/// component, the round-off the stored state could not hold and adds it back next step, as
/// long as Step is handed the state the previous Step produced (otherwise, e.g. after a
/// projection onto constraints, it starts again from zero). Round-off then no longer limits
/// long runs of small steps.
/// Use it for a fixed output grid and for predictable cost per step; use the adaptive
/// Dormand–Prince integrator when accuracy must be guaranteed or events located.

#include <memory>

#include "chasles/integrate/stats.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {

namespace internal {
class OdeSystem;
}

class Rk4Integrator {
 public:
  /// `model` must outlive the integrator.
  explicit Rk4Integrator(const Model& model);
  ~Rk4Integrator();
  Rk4Integrator(const Rk4Integrator&) = delete;
  Rk4Integrator& operator=(const Rk4Integrator&) = delete;

  /// Advances `state` (t, bodies, force integrals) by one step of `h` [s] > 0.
  void Step(State& state, double h);
  /// Work done so far.
  const IntegratorStats& stats() const { return stats_; }

 private:
  struct Work;
  std::unique_ptr<internal::OdeSystem> ode_;
  std::unique_ptr<Work> work_;
  IntegratorStats stats_;
};

}  // namespace chasles
