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
#include "chasles/integrate/simulate.h"

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
  if (!(options.fixed_step > 0.0) || !std::isfinite(options.fixed_step)) {
    throw InputError(fmt::format("fixed step {:.6g} s must be positive", options.fixed_step));
  }
  // The step shortened to divide the output interval evenly: every output time is a step end.
  const double span =
      options.output_interval > 0.0 ? options.output_interval : options.t_end - t_start;
  const auto n = static_cast<long long>(std::ceil(span / options.fixed_step - 1e-9));
  const double h = span / static_cast<double>(std::max(1LL, n));
  if (options.integrator == IntegratorKind::kRk4) {
    // Free bodies under uniform gravity alone: the same RK4 on the structure-of-arrays batch.
    if (FreeBodyBatchObstacle(model).empty()) {
      return std::make_unique<FixedGridIntegrator<FreeBodyBatchIntegrator>>(model, h,
                                                                            FreeBodyStepper::kRk4);
    }
    return std::make_unique<FixedGridIntegrator<Rk4Integrator>>(model, h);
  }
  if (options.integrator == IntegratorKind::kSplitting) {
    const ModelObstacle obstacle = FreeBodyBatchObstacle(model);
    if (!obstacle.empty()) {
      throw InputError(
          fmt::format("the splitting integrator steps free bodies under uniform gravity only, and "
                      "{}; choose rk4 or the adaptive integrator",
                      obstacle.why),
          obstacle.element);
    }
    return std::make_unique<FixedGridIntegrator<FreeBodyBatchIntegrator>>(
        model, h, FreeBodyStepper::kSplitting);
  }
  return std::make_unique<FixedGridIntegrator<EnergyMomentumIntegrator>>(model, h);
}

}  // namespace chasles
