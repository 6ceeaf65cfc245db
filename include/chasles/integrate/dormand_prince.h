#pragma once
/// @file
/// Adaptive explicit Runge–Kutta 5(4) of Dormand & Prince (J. Comput. Appl. Math. 6, 1980)
/// with local extrapolation, FSAL, and Shampine's free continuous extension of order 4
/// (Math. Comp. 46, 1986; the coefficients of Hairer's DOPRI5) for dense output: values
/// between steps cost no extra evaluations and events are located on it.
/// Error control: err = RMS_i(e_i / (atol + rtol max(|y0_i|, |y1_i|))) over all components
/// (positions, quaternions, velocities, angular velocities and the force integrals the ledger
/// reads), accept when err <= 1, next step h·min(5, max(0.2, 0.9 err^(-1/5))).
/// Quaternions are renormalised after each accepted step; the FSAL derivative is rescaled with
/// them (q̇ is linear in q), so the projection costs no evaluation.
/// The accepted increment y₁ − y₀ = h Σ b_i k_i is added with compensation
/// (src/integrate/internal/compensated.h), carried from step to step until Initialize or a
/// projection starts it again from zero.
/// Models with constraints, or with contact points in contact in the current modes: the state
/// is projected onto the constraints and the active contact rows after each accepted step
/// (ProjectOntoConstraints, ProjectOntoContactModes) and the FSAL derivative re-evaluated
/// there.
/// This is the default integrator: use it for accuracy and whenever events are located.

#include <limits>
#include <memory>

#include "chasles/integrate/integrator.h"
#include "chasles/integrate/stats.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {

namespace internal {
class OdeSystem;
}

struct AdaptiveOptions {
  /// Relative tolerance per component (> 0).
  double rtol = 1e-9;
  /// Absolute tolerance per component, in the component's SI unit (> 0).
  double atol = 1e-12;
  /// First step [s]; 0 chooses it from the derivatives (Hairer, Nørsett & Wanner II.4).
  double initial_step = 0.0;
  /// Largest step [s].
  double max_step = std::numeric_limits<double>::infinity();
  /// Throws LimitError (kMinStep) when control asks for a step smaller than this [s] (a stiff
  /// or singular problem).
  double min_step = 1e-14;
  /// Project onto the active contact rows of the current modes after each step (false: they
  /// are projected only at mode switches and drift with the integration error in between;
  /// for drift studies).
  bool project_contacts = true;
};

class DormandPrince5Integrator final : public Integrator {
 public:
  /// `model` must outlive the integrator. Throws InputError for bad tolerances.
  DormandPrince5Integrator(const Model& model, const AdaptiveOptions& options);
  ~DormandPrince5Integrator() override;

  /// Starts (or restarts, e.g. after an impulse changed the state) from `state`.
  void Initialize(const State& state) override;
  /// Takes one accepted step, not past `t_limit`; rejected attempts are retried inside.
  /// Afterwards the dense output covers [t_previous(), t()].
  void Step(double t_limit) override;
  /// Takes one step of exactly `h` [s] without error control (for convergence studies).
  void StepFixed(double h);

  /// The state at the end of the last step.
  const State& state() const override { return state_; }
  /// Time at the start of the last step [s].
  double t_previous() const override { return t_prev_; }
  /// Dense output: the state at `t` in [t_previous(), t()] (quaternions normalised; projected
  /// onto the constraints and the active contact rows, as the step ends are), written into
  /// `out` (resized to the model).
  void Interpolate(double t, State& out) override;
  bool has_dense_output() const override { return true; }
  /// Step size the controller proposes next [s].
  double next_step() const { return h_next_; }
  const IntegratorStats& stats() const override { return stats_; }

 private:
  struct Work;
  void Attempt(double h);
  void PrepareDense();
  void ProjectAfterStep();

  std::unique_ptr<internal::OdeSystem> ode_;
  std::unique_ptr<Work> work_;
  AdaptiveOptions options_;
  State state_;
  double t_prev_ = 0.0;
  double h_next_ = 0.0;
  double h_last_ = 0.0;
  bool dense_ready_ = false;
  IntegratorStats stats_;
};

}  // namespace chasles
