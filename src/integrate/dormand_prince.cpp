#include "chasles/integrate/dormand_prince.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "chasles/error.h"
#include "integrate/internal/compensated.h"
#include "integrate/internal/ode.h"

namespace chasles {
namespace {
// Dormand–Prince 5(4) tableau.
constexpr double c2 = 1.0 / 5, c3 = 3.0 / 10, c4 = 4.0 / 5, c5 = 8.0 / 9;
constexpr double a21 = 1.0 / 5;
constexpr double a31 = 3.0 / 40, a32 = 9.0 / 40;
constexpr double a41 = 44.0 / 45, a42 = -56.0 / 15, a43 = 32.0 / 9;
constexpr double a51 = 19372.0 / 6561, a52 = -25360.0 / 2187, a53 = 64448.0 / 6561,
                 a54 = -212.0 / 729;
constexpr double a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247, a64 = 49.0 / 176,
                 a65 = -5103.0 / 18656;
constexpr double a71 = 35.0 / 384, a73 = 500.0 / 1113, a74 = 125.0 / 192, a75 = -2187.0 / 6784,
                 a76 = 11.0 / 84;
// e = b (5th order) - b̂ (4th order embedded).
constexpr double e1 = 71.0 / 57600, e3 = -71.0 / 16695, e4 = 71.0 / 1920, e5 = -17253.0 / 339200,
                 e6 = 22.0 / 525, e7 = -1.0 / 40;
// Shampine's continuous extension (fourth order, uses the FSAL stage k7).
constexpr double d1 = -12715105075.0 / 11282082432, d3 = 87487479700.0 / 32700410799,
                 d4 = -10690763975.0 / 1880347072, d5 = 701980252875.0 / 199316789632,
                 d6 = -1453857185.0 / 822651844, d7 = 69997945.0 / 29380423;
}  // namespace

struct DormandPrince5Integrator::Work {
  internal::Vector y0, y1, yt, k1, k2, k3, k4, k5, k6, k7, err;
  internal::Vector r1, r2, r3, r4, r5;  // dense-output coefficients
  // Compensation of y0 (integrate/internal/compensated.h) and of the attempted y1; reset by
  // Initialize and by a projection.
  internal::Vector c0, c1;
  double err_norm = 0.0;
};

DormandPrince5Integrator::DormandPrince5Integrator(const Model& model,
                                                   const AdaptiveOptions& options)
    : ode_(std::make_unique<internal::OdeSystem>(model)),
      work_(std::make_unique<Work>()),
      options_(options) {
  if (!(options.rtol > 0.0) || !(options.atol > 0.0) || !std::isfinite(options.rtol) ||
      !std::isfinite(options.atol)) {
    throw InputError(fmt::format(
        "integrator tolerances rtol = {:.3g}, atol = {:.3g}: both must be positive and finite "
        "(e.g. rtol 1e-9, atol 1e-12)",
        options.rtol, options.atol));
  }
  if (options.rtol < 1e-14) {
    throw InputError(fmt::format(
        "integrator rtol = {:.3g} is below what double precision can deliver; use 1e-14 or "
        "more",
        options.rtol));
  }
  if (!(options.initial_step >= 0.0) || !(options.max_step > 0.0) || !(options.min_step >= 0.0)) {
    throw InputError(
        "integrator step limits must be: initial_step >= 0, max_step > 0, "
        "min_step >= 0 [s]");
  }
}

DormandPrince5Integrator::~DormandPrince5Integrator() = default;

void DormandPrince5Integrator::Initialize(const State& state) {
  ValidateState(ode_->model(), state);
  state_ = state;
  Work& w = *work_;
  ode_->SetDiscreteState(state_);
  ode_->Pack(state_, w.y0);
  ode_->NormalizeQuaternions(w.y0, nullptr);
  ode_->Unpack(state_.t, w.y0, state_);
  if (ode_->projects(options_.project_contacts)) {
    ode_->Project(state_, options_.project_contacts);
    ode_->Pack(state_, w.y0);
  }
  w.c0.setZero(ode_->size());
  ode_->Derivative(state_.t, w.y0, w.k1);
  ++stats_.function_evaluations;
  t_prev_ = state_.t;
  dense_ready_ = false;
  h_last_ = 0.0;
  if (options_.initial_step > 0.0) {
    h_next_ = options_.initial_step;
  } else {
    // Starting step from the size of y and y' (Hairer, Nørsett & Wanner, Solving ODE I, II.4).
    const internal::Vector sc = (options_.atol + options_.rtol * w.y0.array().abs()).matrix();
    const double n = static_cast<double>(std::max(1, ode_->size()));
    const double d0 = std::sqrt((w.y0.array() / sc.array()).square().sum() / n);
    const double d1n = std::sqrt((w.k1.array() / sc.array()).square().sum() / n);
    double h0 = (d0 < 1e-5 || d1n < 1e-5) ? 1e-6 : 0.01 * d0 / d1n;
    w.yt = w.y0 + h0 * w.k1;
    ode_->Derivative(state_.t + h0, w.yt, w.k2);
    ++stats_.function_evaluations;
    const double d2 = std::sqrt(((w.k2 - w.k1).array() / sc.array()).square().sum() / n) / h0;
    const double dm = std::max(d1n, d2);
    const double h1 = dm <= 1e-15 ? std::max(1e-6, h0 * 1e-3) : std::pow(0.01 / dm, 1.0 / 5.0);
    h_next_ = std::min(100.0 * h0, h1);
  }
  h_next_ = std::min(h_next_, options_.max_step);
}

void DormandPrince5Integrator::Attempt(double h) {
  Work& w = *work_;
  const double t = state_.t;
  internal::OdeSystem& f = *ode_;
  w.yt = w.y0 + h * a21 * w.k1;
  f.Derivative(t + c2 * h, w.yt, w.k2);
  w.yt = w.y0 + h * (a31 * w.k1 + a32 * w.k2);
  f.Derivative(t + c3 * h, w.yt, w.k3);
  w.yt = w.y0 + h * (a41 * w.k1 + a42 * w.k2 + a43 * w.k3);
  f.Derivative(t + c4 * h, w.yt, w.k4);
  w.yt = w.y0 + h * (a51 * w.k1 + a52 * w.k2 + a53 * w.k3 + a54 * w.k4);
  f.Derivative(t + c5 * h, w.yt, w.k5);
  w.yt = w.y0 + h * (a61 * w.k1 + a62 * w.k2 + a63 * w.k3 + a64 * w.k4 + a65 * w.k5);
  f.Derivative(t + h, w.yt, w.k6);
  // y₁ = y₀ + h Σ b_i k_i, added with compensation (kept in c1 until the step is accepted).
  w.yt = h * (a71 * w.k1 + a73 * w.k3 + a74 * w.k4 + a75 * w.k5 + a76 * w.k6);
  w.y1 = w.y0;
  w.c1 = w.c0;
  internal::CompensatedAdd(w.y1, w.yt, w.c1);
  f.Derivative(t + h, w.y1, w.k7);
  stats_.function_evaluations += 6;
  w.err = h * (e1 * w.k1 + e3 * w.k3 + e4 * w.k4 + e5 * w.k5 + e6 * w.k6 + e7 * w.k7);
  double sum = 0.0;
  for (int i = 0; i < f.size(); ++i) {
    const double sc =
        options_.atol + options_.rtol * std::max(std::abs(w.y0[i]), std::abs(w.y1[i]));
    const double r = w.err[i] / sc;
    sum += r * r;
  }
  w.err_norm = std::sqrt(sum / std::max(1, f.size()));
}

void DormandPrince5Integrator::Step(double t_limit) {
  Work& w = *work_;
  const double t = state_.t;
  if (!(t_limit > t)) {
    throw InputError(
        fmt::format("integration end time {:.17g} s is not after the current time "
                    "{:.17g} s",
                    t_limit, t));
  }
  double h = std::min(h_next_, t_limit - t);
  // Land exactly on t_limit rather than leave a sliver of a step.
  if (t + 1.01 * h >= t_limit) h = t_limit - t;
  while (true) {
    Attempt(h);
    const double err = work_->err_norm;
    if (err <= 1.0 && std::isfinite(err)) break;
    ++stats_.rejected_steps;
    const double fac = std::isfinite(err) ? std::max(0.2, 0.9 * std::pow(err, -0.2)) : 0.2;
    h *= fac;
    if (h < options_.min_step) {
      // Derivatives are finite here (OdeSystem::Derivative stops the run on a non-finite
      // one), so the error estimate is a number: the motion needs ever shorter steps.
      throw LimitError(LimitError::Limit::kMinStep,
                       fmt::format("the adaptive step fell below the smallest step {:.3g} s at "
                                   "t = {:.9g} s (error estimate {:.3g}); the motion is singular "
                                   "or too stiff here (a body passing through a force centre, "
                                   "an extreme stiffness or mass ratio)",
                                   options_.min_step, t, err));
    }
  }
  const double err = std::max(work_->err_norm, 1e-10);
  double fac = std::min(5.0, std::max(0.2, 0.9 * std::pow(err, -0.2)));
  if (stats_.rejected_steps > 0 && h < h_last_) fac = std::min(fac, 1.0);
  h_last_ = h;
  h_next_ = std::min(options_.max_step, h * fac);
  ++stats_.steps;
  t_prev_ = t;
  const double t_new = (h == t_limit - t) ? t_limit : t + h;
  ode_->NormalizeQuaternions(w.y1, &w.k7, &w.c1);
  dense_ready_ = false;
  // Keep y0/k1 of the step for the dense output: swap rather than copy.
  std::swap(w.y0, w.y1);
  std::swap(w.k1, w.k7);
  std::swap(w.c0, w.c1);
  ode_->Unpack(t_new, w.y0, state_);
  ProjectAfterStep();
  internal::CheckFiniteState(ode_->model(), state_);
}

void DormandPrince5Integrator::ProjectAfterStep() {
  if (!ode_->projects(options_.project_contacts)) return;
  // Project the accepted end state onto the constraint manifold and the active contact rows;
  // the FSAL derivative is then re-evaluated there (one evaluation per step). The dense output
  // is built after this, between the projected ends of the step.
  Work& w = *work_;
  ode_->Project(state_, options_.project_contacts);
  ode_->Pack(state_, w.y0);
  w.c0.setZero();  // the projection moved y0 by far more than its compensation
  ode_->Derivative(state_.t, w.y0, w.k1);
  ++stats_.function_evaluations;
}

void DormandPrince5Integrator::StepFixed(double h) {
  Work& w = *work_;
  const double t = state_.t;
  Attempt(h);
  h_last_ = h;
  ++stats_.steps;
  t_prev_ = t;
  ode_->NormalizeQuaternions(w.y1, &w.k7, &w.c1);
  dense_ready_ = false;
  std::swap(w.y0, w.y1);
  std::swap(w.k1, w.k7);
  std::swap(w.c0, w.c1);
  ode_->Unpack(t + h, w.y0, state_);
  ProjectAfterStep();
  internal::CheckFiniteState(ode_->model(), state_);
}

void DormandPrince5Integrator::PrepareDense() {
  // After the swap in Step: y1 holds the step's start, y0 its end; k7 its first stage and k1
  // the FSAL stage at the end.
  Work& w = *work_;
  const double h = h_last_;
  w.r1 = w.y1;
  w.r2 = w.y0 - w.y1;
  w.r3 = h * w.k7 - w.r2;
  w.r4 = w.r2 - h * w.k1 - w.r3;
  w.r5 = h * (d1 * w.k7 + d3 * w.k3 + d4 * w.k4 + d5 * w.k5 + d6 * w.k6 + d7 * w.k1);
  dense_ready_ = true;
}

void DormandPrince5Integrator::Interpolate(double t, State& out) {
  if (out.bodies.size() != state_.bodies.size() ||
      out.force_integrals.size() != state_.force_integrals.size()) {
    out = state_;
  }
  if (t == state_.t) {
    out = state_;
    return;
  }
  if (!dense_ready_) PrepareDense();
  Work& w = *work_;
  const double theta = (t - t_prev_) / h_last_;
  const double theta1 = 1.0 - theta;
  w.yt = w.r1 + theta * (w.r2 + theta1 * (w.r3 + theta * (w.r4 + theta1 * w.r5)));
  ode_->NormalizeQuaternions(w.yt, nullptr);
  ode_->Unpack(t, w.yt, out);
  // The interpolant meets the constraints (and contact rows) only to its own error; put the
  // output back on them.
  if (ode_->projects(options_.project_contacts)) ode_->Project(out, options_.project_contacts);
  internal::CheckFiniteState(ode_->model(), out);
}

}  // namespace chasles
