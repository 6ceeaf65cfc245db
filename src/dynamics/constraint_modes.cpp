#include "chasles/dynamics/constraint_modes.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <Eigen/QR>

#include "chasles/dynamics/constraint_solve.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/error.h"
#include "dynamics/internal/generalized.h"

namespace chasles {
namespace {

// Row 0 of constraint c (kept in Data::constraint_rows in either mode) times a generalised
// vector x (6 per body): the gap rate ġ = J u for x = u, J u̇ for x = u̇.
double RowTimes(const Model& model, const Data& data, int c, const Eigen::VectorXd& x) {
  const Constraint& con = model.constraint(c);
  const ConstraintEval& e = data.constraint_rows[static_cast<size_t>(c)];
  double v = e.J_child.row(0).dot(x.segment<6>(6 * con.child()));
  if (con.parent() != kWorld) v += e.J_parent.row(0).dot(x.segment<6>(6 * con.parent()));
  // Rows on further bodies (a pulley carried by a body neither end is on).
  for (int k = 0; k < e.num_extra; ++k) {
    const auto j = static_cast<size_t>(k);
    v += e.J_extra[j].row(0).dot(x.segment<6>(6 * e.extra_body[j]));
  }
  return v;
}

// Σ |J_row 0| over every body the constraint's row acts on (a scale for round-off tests).
double RowSize(const ConstraintEval& e) {
  double s = e.J_child.row(0).cwiseAbs().sum() + e.J_parent.row(0).cwiseAbs().sum();
  for (int k = 0; k < e.num_extra; ++k) {
    s += e.J_extra[static_cast<size_t>(k)].row(0).cwiseAbs().sum();
  }
  return s;
}

void SetMode(State& state, int c, ConstraintMode m) {
  state.constraint_modes[static_cast<size_t>(c)].mode = m;
}

}  // namespace

void EnsureConstraintModes(const Model& model, State& state) {
  state.constraint_modes.resize(static_cast<size_t>(model.num_constraints()));
}

std::vector<ConstraintModeChange> SelectConstraintModes(const Model& model, State& state,
                                                        const ContactTolerances& tol,
                                                        const std::vector<int>& force_release) {
  EnsureConstraintModes(model, state);
  std::vector<ConstraintMode> before;
  for (const ConstraintModeState& m : state.constraint_modes) before.push_back(m.mode);
  Data data = MakeData(model);
  CalcKinematics(model, state, data);
  CalcConstraintRows(model, state, data);
  Eigen::VectorXd u;
  internal::GetVelocity(model, state, data, u);
  // Apart or opening: released. At g = 0 and not opening: candidates of the LCP.
  std::vector<int> cand;
  for (int c = 0; c < model.num_constraints(); ++c) {
    if (!model.constraint(c).can_release()) continue;
    const double g = data.constraint_gap[static_cast<size_t>(c)];
    const double rate = RowTimes(model, data, c, u);
    if (g > tol.gap || rate > tol.resting_speed) {
      SetMode(state, c, ConstraintMode::kReleased);
    } else {
      cand.push_back(c);
      const bool forced =
          std::find(force_release.begin(), force_release.end(), c) != force_release.end();
      SetMode(state, c, forced ? ConstraintMode::kReleased : ConstraintMode::kEngaged);
    }
  }
  // Murty's least-index principal pivoting on λ >= 0, g̈ >= 0, λ g̈ = 0: flip the first
  // candidate that violates its sign (an engaged one pulling with λ < 0, a released one whose
  // gap would close, g̈ < 0), until none does. Finite for a P-matrix (Murty 1974).
  const int max_pivots = 50 + 10 * static_cast<int>(cand.size() * cand.size());
  for (int pivot = 0; !cand.empty(); ++pivot) {
    CalcAccelerations(model, state, data);
    Eigen::VectorXd u_dot(6 * model.num_bodies());
    double force = 0.0;
    for (int b = 0; b < model.num_bodies(); ++b) {
      const auto i = static_cast<size_t>(b);
      u_dot.segment<3>(6 * b) = data.a_WBcm_W[i];
      u_dot.segment<3>(6 * b + 3) = data.R_WB[i] * data.wdot_WB_B[i];
      force = std::max(force, data.F_Bcm_W[i].norm());
    }
    if (data.lambda.size() > 0) force = std::max(force, data.lambda.cwiseAbs().maxCoeff());
    int flip = -1;
    for (int c : cand) {
      if (IsReleased(state, c)) {
        // g̈ = J u̇ - c (c = -J̇ u, the row's acceleration right-hand side).
        const ConstraintEval& e = data.constraint_rows[static_cast<size_t>(c)];
        const double g_dd = RowTimes(model, data, c, u_dot) - e.acceleration_rhs[0];
        const double scale = std::abs(e.acceleration_rhs[0]) + RowSize(e) * u_dot.norm();
        if (g_dd < -tol.relative * scale) flip = c;
      } else {
        const double lambda = data.constraints[static_cast<size_t>(c)].lambda[0];
        if (lambda < -tol.relative * force) flip = c;
      }
      if (flip >= 0) break;
    }
    if (flip < 0) break;
    if (pivot >= max_pivots) {
      throw InputError(fmt::format(
          "the modes of the strings at t = {:.9g} s could not be chosen in {} pivots (the "
          "strings' rows may be dependent: two strings doing the same job)",
          state.t, max_pivots));
    }
    SetMode(state, flip,
            IsReleased(state, flip) ? ConstraintMode::kEngaged : ConstraintMode::kReleased);
  }
  std::vector<ConstraintModeChange> changes;
  for (int c = 0; c < model.num_constraints(); ++c) {
    const ConstraintMode to = state.constraint_modes[static_cast<size_t>(c)].mode;
    if (to != before[static_cast<size_t>(c)])
      changes.push_back({c, before[static_cast<size_t>(c)], to});
  }
  return changes;
}

std::vector<ConstraintImpulse> ResolveConstraintImpacts(const Model& model, State& state,
                                                        const ContactTolerances& tol) {
  EnsureConstraintModes(model, state);
  std::vector<ConstraintImpulse> out;
  Data data = MakeData(model);
  CalcKinematics(model, state, data);
  CalcConstraintRows(model, state, data);
  Eigen::VectorXd u;
  internal::GetVelocity(model, state, data, u);
  std::vector<double> rate_before(static_cast<size_t>(model.num_constraints()), 0.0);
  for (int c = 0; c < model.num_constraints(); ++c) {
    if (!model.constraint(c).can_release()) continue;
    const double g = data.constraint_gap[static_cast<size_t>(c)];
    const double rate = RowTimes(model, data, c, u);
    if (g > tol.gap || !(rate < -tol.resting_speed)) continue;
    rate_before[static_cast<size_t>(c)] = rate;
    out.push_back({c, -rate, 0.0, 0.0});
    SetMode(state, c, ConstraintMode::kEngaged);  // its row takes part in the impulse
  }
  if (out.empty()) return out;
  CalcConstraintRows(model, state, data);
  // Targets: the engaged rows keep J u⁺ = b; a closing row ends at ġ⁺ = -e ġ⁻.
  Eigen::VectorXd target = data.velocity_rhs;
  for (const ConstraintImpulse& ci : out) {
    const int o = model.constraint_row_offset(ci.constraint);
    target[o] = -model.constraint(ci.constraint).restitution() *
                rate_before[static_cast<size_t>(ci.constraint)];
  }
  // A dense least-norm solve over every row.
  internal::EnsureDenseJacobian(model, data);
  Eigen::VectorXd r = target - data.J * u;
  internal::TimesMassInverse(model, data, data.J, data.JMinv);
  Eigen::MatrixXd A = data.JMinv * data.J.transpose();
  internal::HoldReleasedRows(data.row_released, A, r);
  // Least-norm solution: redundant engaged rows (two hinges on one door) share the impulse.
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;
  cod.setThreshold(1e-10);
  cod.compute(A);
  const Eigen::VectorXd P = cod.solve(r);
  const double T_before = internal::KineticEnergy(model, state);
  const Eigen::VectorXd u_after = u + data.JMinv.transpose() * P;
  internal::SetVelocity(model, data, u_after, state);
  const double lost = T_before - internal::KineticEnergy(model, state);
  double p_sum = 0.0;
  for (ConstraintImpulse& ci : out) {
    ci.impulse = P[model.constraint_row_offset(ci.constraint)];
    p_sum += std::abs(ci.impulse);
  }
  for (ConstraintImpulse& ci : out) {
    ci.energy_lost = p_sum > 0.0 ? lost * std::abs(ci.impulse) / p_sum : 0.0;
    state.constraint_modes[static_cast<size_t>(ci.constraint)].impact_work -= ci.energy_lost;
  }
  return out;
}

}  // namespace chasles
