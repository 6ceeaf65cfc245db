#include "chasles/integrate/energy_momentum.h"

#include <cmath>
#include <cstring>
#include <limits>

#include <fmt/format.h>

#include "chasles/dynamics/newton_euler.h"
#include "chasles/error.h"
#include "chasles/math/quaternion.h"
#include "chasles/math/rotation.h"
#include "integrate/internal/compensated.h"
#include "integrate/internal/ode.h"

namespace chasles {

namespace {
// Adds `dt` times each force element's power, force and moment to its running integrals (one
// half of the trapezoidal rule).
void AddHalfStepIntegrals(const Data& data, double dt, State& s) {
  for (size_t e = 0; e < data.elements.size(); ++e) {
    const ForceElementOutput& o = data.elements[e];
    ForceIntegrals& fi = s.force_integrals[e];
    fi.work += dt * o.power;
    fi.work_nonconservative += dt * o.power_nonconservative;
    fi.linear_impulse_W += dt * o.force_W;
    fi.angular_impulse_Wo_W += dt * o.moment_Wo_W;
  }
}
}  // namespace

namespace {
// The rotation Q = cay(h ω̄) of one free-rotation step from the body-frame angular momentum M0
// (see StepFreeRotation), as a unit quaternion.
Quat FreeRotationIncrement(const Mat3& I_inv, double h, const Vec3& M0) {
  // Solve G(X) = X - M₀ - (h/2) X × (I⁻¹X) = 0 for the midpoint X = M̄.
  // dG = dX - (h/2)(dX × I⁻¹X + X × I⁻¹dX) = (E - (h/2)(-[I⁻¹X]× + [X]× I⁻¹)) dX.
  Vec3 X = M0 + 0.5 * h * M0.cross(I_inv * M0);  // explicit predictor
  const double scale = M0.norm();
  // Newton until the correction stops shrinking: a residual left in X would break the exact
  // energy balance (E₁ - E₀ = (M₁ - M₀)·I⁻¹X needs X = (M₀ + M₁)/2) by its size every step.
  double last = std::numeric_limits<double>::infinity();
  for (int iter = 0; iter < 50; ++iter) {
    const Vec3 w = I_inv * X;
    const Vec3 G = X - M0 - 0.5 * h * X.cross(w);
    const Mat3 J = Mat3::Identity() - 0.5 * h * (Skew(X) * I_inv - Skew(w));
    const Vec3 dX = J.partialPivLu().solve(G);
    const double n = dX.norm();
    if (n >= last) break;
    X -= dX;
    last = n;
    if (n <= 1e-17 * scale) break;
  }
  const Vec3 w_bar = I_inv * X;
  // M₁ = Qᵀ M₀ and R₁ = R₀ Q with Q = cay(h ω̄), Gibbs vector h ω̄ / 2.
  return QuatFromGibbs(0.5 * h * w_bar);
}
}  // namespace

void StepFreeRotation(const Mat3& I, const Mat3& I_inv, double h, Vec3& M, Quat& q) {
  (void)I;
  const Quat dq = FreeRotationIncrement(I_inv, h, M);
  M = dq.conjugate() * M;
  q = (q * dq).normalized();
}

EnergyMomentumIntegrator::EnergyMomentumIntegrator(const Model& model)
    : model_(model), data_(MakeData(model)) {
  if (model.num_constraints() > 0) {
    throw InputError(
        fmt::format(
            "the energy-momentum integrator handles free bodies only, and this model has {} "
            "constraints (first: '{}'); choose the Dormand-Prince or RK4 integrator",
            model.num_constraints(), model.constraint(0).name()),
        ErrorElement{ErrorElement::Kind::kConstraint, 0});
  }
}

namespace {
bool SameState(const State& a, const State& b) {
  if (a.t != b.t || a.bodies.size() != b.bodies.size()) return false;
  for (size_t i = 0; i < a.bodies.size(); ++i) {
    const BodyState &x = a.bodies[i], &y = b.bodies[i];
    if (x.p_WBcm != y.p_WBcm || x.q_WB.coeffs() != y.q_WB.coeffs() || x.v_WBcm_W != y.v_WBcm_W ||
        x.w_WB_B != y.w_WB_B) {
      return false;
    }
  }
  return true;
}
}  // namespace

void EnergyMomentumIntegrator::Step(State& s, double h) {
  if (!(h > 0.0) || !std::isfinite(h)) {
    throw InputError(
        fmt::format("energy-momentum step is {:.6g} s; it must be a positive time step", h));
  }
  const int nb = model_.num_bodies();
  const bool reuse = cached_valid_ && SameState(s, cached_);
  if (!reuse) {
    // A state from elsewhere: its compensations start from zero (internal/compensated.h).
    compensation_.assign(static_cast<size_t>(nb), BodyCompensation{});
    M_B_.resize(static_cast<size_t>(nb));
    for (int b = 0; b < nb; ++b) {
      M_B_[static_cast<size_t>(b)] =
          model_.body(b).I_BBcm_B() * s.bodies[static_cast<size_t>(b)].w_WB_B;
    }
    CalcKinematics(model_, s, data_);
    CalcForces(model_, s, data_);
    internal::CheckFiniteEvaluation(model_, s, data_, false);
    ++stats_.function_evaluations;
  }
  // Trapezoidal force integrals: first half with the start-of-step outputs.
  AddHalfStepIntegrals(data_, 0.5 * h, s);
  for (int b = 0; b < nb; ++b) {
    const auto i = static_cast<size_t>(b);
    const Body& body = model_.body(b);
    BodyState& bs = s.bodies[i];
    BodyCompensation& c = compensation_[i];
    // Kick, drift and free rotation, each update added with compensation.
    internal::CompensatedAdd(bs.v_WBcm_W, (0.5 * h / body.mass()) * data_.F_Bcm_W[i], c.v);
    Vec3& M_B = M_B_[i];
    internal::CompensatedAdd(M_B, 0.5 * h * (data_.R_WB[i].transpose() * data_.M_Bcm_W[i]), c.M);
    internal::CompensatedAdd(bs.p_WBcm, h * bs.v_WBcm_W, c.p);
    // M₁ = Qᵀ M₀ (its compensation rotated with it; the rounding of the rotation itself is not
    // recovered), q₁ = q₀ ⊗ Q with the product's rounding recovered, then normalised.
    const Quat dq = FreeRotationIncrement(body.I_BBcm_B_inverse(), h, M_B);
    M_B = dq.conjugate() * M_B;
    c.M = dq.conjugate() * c.M;
    const Eigen::Vector4d q_wxyz(bs.q_WB.w(), bs.q_WB.x(), bs.q_WB.y(), bs.q_WB.z());
    const Eigen::Vector4d dq_wxyz(dq.w(), dq.x(), dq.y(), dq.z());
    Eigen::Vector4d q1 = internal::CompensatedQuatProduct(q_wxyz, dq_wxyz, c.q);
    internal::NormalizeCompensated(q1, c.q);
    bs.q_WB = Quat(q1[0], q1[1], q1[2], q1[3]);
  }
  if (s.t != t_end_) c_t_ = 0.0;
  internal::CompensatedAdd(s.t, h, c_t_);
  t_end_ = s.t;
  CalcKinematics(model_, s, data_);
  CalcForces(model_, s, data_);
  internal::CheckFiniteEvaluation(model_, s, data_, false);
  ++stats_.function_evaluations;
  for (int b = 0; b < nb; ++b) {
    const auto i = static_cast<size_t>(b);
    const Body& body = model_.body(b);
    BodyState& bs = s.bodies[i];
    // Second kick with the end-of-step forces (moment taken into B at the new orientation).
    BodyCompensation& c = compensation_[i];
    internal::CompensatedAdd(bs.v_WBcm_W, (0.5 * h / body.mass()) * data_.F_Bcm_W[i], c.v);
    if (data_.M_Bcm_W[i].squaredNorm() != 0.0) {
      internal::CompensatedAdd(M_B_[i], 0.5 * h * (data_.R_WB[i].transpose() * data_.M_Bcm_W[i]),
                               c.M);
    }
    bs.w_WB_B = body.I_BBcm_B_inverse() * M_B_[i];
  }
  // Second half with the end-of-step outputs.
  AddHalfStepIntegrals(data_, 0.5 * h, s);
  internal::CheckFiniteState(model_, s);
  // The forces in data_ were evaluated before the second kick; they are the next step's
  // first-kick forces only for position- and time-dependent forces. Velocity-dependent ones
  // are re-evaluated there only if the caller changed the state; otherwise the half-step
  // velocities are used, as in velocity Verlet.
  cached_ = s;
  cached_valid_ = true;
  ++stats_.steps;
}

}  // namespace chasles
