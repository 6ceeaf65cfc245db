#include "chasles/integrate/rk4.h"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "chasles/error.h"
#include "integrate/internal/compensated.h"
#include "integrate/internal/ode.h"

namespace chasles {

struct Rk4Integrator::Work {
  internal::Vector y, yt, k1, k2, k3, k4;
  /// Compensation of y (integrate/internal/compensated.h) and y as the last step left it: the
  /// compensation is carried into the next step only when it is handed that same state.
  internal::Vector c, y_end;
  bool carried = false;
  /// The same for the time [s].
  double c_t = 0.0, t_end = std::numeric_limits<double>::quiet_NaN();
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
  if (!(w.carried && w.y == w.y_end)) w.c.setZero(ode_->size());
  if (t != w.t_end) w.c_t = 0.0;  // e.g. a fixed grid that set t to its output time
  ode_->Derivative(t, w.y, w.k1);
  w.yt = w.y + (0.5 * h) * w.k1;
  ode_->Derivative(t + 0.5 * h, w.yt, w.k2);
  w.yt = w.y + (0.5 * h) * w.k2;
  ode_->Derivative(t + 0.5 * h, w.yt, w.k3);
  w.yt = w.y + h * w.k3;
  ode_->Derivative(t + h, w.yt, w.k4);
  // y₁ = y₀ + (h/6)(k₁ + 2k₂ + 2k₃ + k₄), added with compensation (internal/compensated.h).
  w.yt = (h / 6.0) * (w.k1 + 2.0 * (w.k2 + w.k3) + w.k4);
  internal::CompensatedAdd(w.y, w.yt, w.c);
  ode_->NormalizeQuaternions(w.y, nullptr, &w.c);
  double t_new = t;
  internal::CompensatedAdd(t_new, h, w.c_t);
  ode_->Unpack(t_new, w.y, state);
  w.t_end = t_new;
  // Constrained models: back onto the constraint manifold (removes the drift of g and J u).
  // The projection moves the state by far more than the compensation: start it again.
  w.carried = !ode_->has_constraints();
  if (w.carried) {
    w.y_end = w.y;
  } else {
    ode_->Project(state, false);
  }
  internal::CheckFiniteState(ode_->model(), state);
  ++stats_.steps;
  stats_.function_evaluations += 4;
}

}  // namespace chasles
