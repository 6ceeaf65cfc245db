#pragma once
/// @file
/// The one stepping interface that Simulate drives. Each kind of integrator implements it:
/// the adaptive Dormand–Prince integrator directly (DormandPrince5Integrator), the fixed-step
/// ones (Rk4Integrator, EnergyMomentumIntegrator) through a grid that divides each stretch
/// [t, t_limit] into equal steps no longer than the nominal one, so that output times are hit
/// exactly. MakeIntegrator (simulate.h) builds the one a SimulationOptions asks for.

#include "chasles/integrate/stats.h"
#include "chasles/model/state.h"

namespace chasles {

enum class IntegratorKind { kDormandPrince5, kRk4, kEnergyMomentum, kSplitting };

/// Name of an integrator kind as reports print it ("adaptive Dormand-Prince 5(4)", "RK4 (fixed
/// step)", ...).
const char* IntegratorName(IntegratorKind kind);

class Integrator {
 public:
  virtual ~Integrator() = default;
  Integrator() = default;
  Integrator(const Integrator&) = delete;
  Integrator& operator=(const Integrator&) = delete;

  /// Starts (or restarts, e.g. after an impulse changed the state) from `state`.
  virtual void Initialize(const State& state) = 0;
  /// Takes one step, not past `t_limit`. A fixed-step integrator lands on `t_limit` exactly
  /// after the last step of its grid; an adaptive one lands on it when its step reaches it.
  virtual void Step(double t_limit) = 0;
  /// The state after the last step.
  virtual const State& state() const = 0;
  /// Time at the start of the last step [s].
  virtual double t_previous() const = 0;
  double t() const { return state().t; }
  /// True when Interpolate gives the state anywhere in [t_previous(), t()] (dense output);
  /// false when only the step's ends are known.
  virtual bool has_dense_output() const = 0;
  /// The state at `t` in [t_previous(), t()]. Without dense output only t == t() and
  /// t == t_previous() are allowed (a UsageError otherwise).
  virtual void Interpolate(double t, State& out) = 0;
  /// Steps, rejected steps and right-hand-side evaluations since construction.
  virtual const IntegratorStats& stats() const = 0;
};

}  // namespace chasles
