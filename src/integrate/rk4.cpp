#include "chasles/integrate/rk4.h"

#include <cmath>

#include <fmt/format.h>

#include "chasles/error.h"
#include "integrate/internal/ode.h"

namespace chasles {

struct Rk4Integrator::Work {
  internal::Vector y, yt, k1, k2, k3, k4;
};

Rk4Integrator::Rk4Integrator(const Model& model)
    : ode_(std::make_unique<internal::OdeSystem>(model)), work_(std::make_unique<Work>()) {}

Rk4Integrator::~Rk4Integrator() = default;

void Rk4Integrator::Step(State& state, double h) {
  if (!(h > 0.0) || !std::isfinite(h)) {
    throw InputError(fmt::format("RK4 step is {:.6g} s; it must be a positive time step", h));
  }
  Work& w = *work_;
  const double t = state.t;
  // Contact modes are discrete: they hold over the step (a fixed-step run switches them
  // itself, between steps).
  ode_->SetDiscreteState(state);
  ode_->Pack(state, w.y);
  ode_->Derivative(t, w.y, w.k1);
  w.yt = w.y + (0.5 * h) * w.k1;
  ode_->Derivative(t + 0.5 * h, w.yt, w.k2);
  w.yt = w.y + (0.5 * h) * w.k2;
  ode_->Derivative(t + 0.5 * h, w.yt, w.k3);
  w.yt = w.y + h * w.k3;
  ode_->Derivative(t + h, w.yt, w.k4);
  w.y += (h / 6.0) * (w.k1 + 2.0 * (w.k2 + w.k3) + w.k4);
  ode_->NormalizeQuaternions(w.y, nullptr);
  ode_->Unpack(t + h, w.y, state);
  // Constrained models: back onto the constraint manifold (removes the drift of g and J u).
  if (ode_->has_constraints()) ode_->Project(state, false);
  internal::CheckFiniteState(ode_->model(), state);
  ++stats_.steps;
  stats_.function_evaluations += 4;
}

}  // namespace chasles
