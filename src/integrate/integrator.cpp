#include "chasles/integrate/integrator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/integrate/energy_momentum.h"
#include "chasles/integrate/free_body_batch.h"
#include "chasles/integrate/rk4.h"
#include "chasles/integrate/run_path.h"
#include "chasles/integrate/simulate.h"
#include "integrate/internal/free_body_run.h"

namespace chasles {
namespace {

/// A fixed-step integrator behind the Integrator interface. Each stretch [t, t_limit] is cut
/// into n = ceil((t_limit - t) / h) equal steps (the 1e-9 forgives a ratio that round-off put
/// just above an integer), and the last one lands on t_limit exactly, so the time grid does
/// not drift by round-off over a long run.
template <typename Stepper>
class FixedGridIntegrator final : public Integrator {
 public:
  template <typename... StepperArgs>
  FixedGridIntegrator(const Model& model, double h, StepperArgs... args)
      : stepper_(model, args...), h_(h) {}

  void Initialize(const State& state) override {
    state_ = state;
    previous_ = state;
    remaining_ = 0;
  }

  void Step(double t_limit) override {
    if (!(t_limit > state_.t)) {
      throw UsageError(fmt::format("a step to t = {:.17g} s from t = {:.17g} s goes backwards",
                                   t_limit, state_.t));
    }
    if (remaining_ == 0 || t_limit != target_) {
      const double span = t_limit - state_.t;
      remaining_ = std::max(1LL, static_cast<long long>(std::ceil(span / h_ - 1e-9)));
      step_ = span / static_cast<double>(remaining_);
      target_ = t_limit;
    }
    previous_ = state_;
    stepper_.Step(state_, step_);
    if (--remaining_ == 0) state_.t = target_;
  }

  const State& state() const override { return state_; }
  double t_previous() const override { return previous_.t; }
  bool has_dense_output() const override { return false; }

  void Interpolate(double t, State& out) override {
    if (t == state_.t) {
      out = state_;
    } else if (t == previous_.t) {
      out = previous_;
    } else {
      throw UsageError(fmt::format(
          "a fixed-step integrator knows the state only at the ends of its step ({:.17g} s and "
          "{:.17g} s), not at {:.17g} s",
          previous_.t, state_.t, t));
    }
  }

  const IntegratorStats& stats() const override { return stepper_.stats(); }

 private:
  Stepper stepper_;
  double h_;
  State state_, previous_;
  long long remaining_ = 0;
  double step_ = 0.0;
  double target_ = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace

const char* IntegratorName(IntegratorKind kind) {
  switch (kind) {
    case IntegratorKind::kDormandPrince5:
      return "adaptive Dormand-Prince 5(4)";
    case IntegratorKind::kRk4:
      return "RK4 (fixed step)";
    case IntegratorKind::kEnergyMomentum:
      return "energy-momentum (fixed step)";
    case IntegratorKind::kSplitting:
      return "symplectic splitting (fixed step, free bodies)";
  }
  return "";
}

std::unique_ptr<Integrator> MakeIntegrator(const Model& model, const SimulationOptions& options,
                                           double t_start) {
  if (options.integrator == IntegratorKind::kDormandPrince5) {
    return std::make_unique<DormandPrince5Integrator>(model, options.adaptive);
  }
  const double h = internal::FixedGridStep(options, t_start);
  if (options.integrator == IntegratorKind::kEnergyMomentum) {
    return std::make_unique<FixedGridIntegrator<EnergyMomentumIntegrator>>(model, h);
  }
  // RK4 or the splitting: on the free-body batch where the run path is that (free bodies under
  // uniform gravity alone; the splitting takes no other), else RK4 on the general equations.
  if (ChooseRunPath(model, options).path == RunPath::kFreeBodyBatch) {
    return std::make_unique<FixedGridIntegrator<FreeBodyBatchIntegrator>>(
        model, h,
        options.integrator == IntegratorKind::kRk4 ? FreeBodyStepper::kRk4
                                                   : FreeBodyStepper::kSplitting);
  }
  return std::make_unique<FixedGridIntegrator<Rk4Integrator>>(model, h);
}

}  // namespace chasles
