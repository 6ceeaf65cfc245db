#include "chasles/dynamics/constraint_solve.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Cholesky>
#include <Eigen/QR>

#include "chasles/dynamics/newton_euler.h"
#include "chasles/dynamics/redundancy.h"
#include "chasles/error.h"
#include "chasles/math/quaternion.h"
#include "dynamics/internal/generalized.h"
#include "dynamics/internal/sparse_solve.h"

namespace chasles {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

std::vector<int> RowOwners(const Model& model);

// Solves A x = r for symmetric positive semi-definite A = J M⁻¹ Jᵀ with the factorisation
// object `ldlt` (reused: no allocation at a fixed size). Returns the rank. LDLᵀ when A is
// well conditioned; otherwise the least-norm least-squares solution. With `what` given,
// throws when the least-squares residual shows that the rows cannot all hold (inconsistent
// constraints); `r_scale` is the size of the terms r was formed from, so that a right-hand
// side that cancels to round-off is not mistaken for an inconsistency. `row_owner` maps rows
// to constraints (all rows of the model when null). With `weigh` (the Data whose rows A was
// formed from) a singular system gets the weighted least-norm solution, min Σ (x_k / d_k)²
// (docs/constraints.md, "Redundant constraints"): x = D y with y the least-norm solution of (D A D)
// y = D r, since the solutions of A x = r are x₀ + null(A) and D⁻¹ maps them onto those of the
// scaled system.
int SolveSchur(const Model& model, const std::vector<int>* row_owner, const MatrixXd& A,
               Eigen::LDLT<MatrixXd>& ldlt, const VectorXd& r, VectorXd& x, const char* what,
               double r_scale, const Data* weigh = nullptr) {
  const Eigen::Index n = A.rows();
  if (n == 0) {
    x.resize(0);
    return 0;
  }
  const double a_max = A.diagonal().cwiseAbs().maxCoeff();
  ldlt.compute(A);
  if (ldlt.info() == Eigen::Success && a_max > 0.0 && ldlt.vectorD().minCoeff() > 1e-10 * a_max) {
    x = ldlt.solve(r);
    return static_cast<int>(n);
  }
  // d_k from CalcReactionWeights (1 for force rows, ℓ for moment rows); only here, off the
  // allocation-free path of well-posed systems.
  const VectorXd d = weigh != nullptr ? CalcReactionWeights(model, *weigh) : VectorXd::Ones(n);
  const auto D = d.asDiagonal();
  Eigen::CompleteOrthogonalDecomposition<MatrixXd> cod(D * A * D);
  cod.setThreshold(1e-10);
  x = D * cod.solve(D * r);
  if (what == nullptr) return static_cast<int>(cod.rank());
  const VectorXd res = A * x - r;
  const double scale = std::max(r_scale, r.cwiseAbs().maxCoeff()) + a_max * x.cwiseAbs().maxCoeff();
  const double tol = 1e-8 * scale;
  if (res.cwiseAbs().maxCoeff() > tol) {
    const std::vector<int> all = row_owner ? std::vector<int>() : RowOwners(model);
    const std::vector<int>& owner = row_owner ? *row_owner : all;
    std::string names;
    int first = -1;  // the first constraint named
    for (Eigen::Index k = 0; k < n; ++k) {
      const int c = owner[static_cast<size_t>(k)];
      const std::string quoted = "'" + model.constraint(c).name() + "'";
      if (std::abs(res[k]) > tol && names.find(quoted) == std::string::npos) {
        names += (names.empty() ? "" : ", ") + quoted;
        if (first < 0) first = c;
      }
    }
    throw InputError(
        fmt::format(
            "constraints {} are inconsistent: no {} satisfies all of them (least-squares residual "
            "{:.3g}); remove or change one of them (two drivers on the same coordinate, or a "
            "joint that contradicts another)",
            names, what, res.cwiseAbs().maxCoeff()),
        first >= 0 ? std::optional(ErrorElement{ErrorElement::Kind::kConstraint, first})
                   : std::nullopt);
  }
  return static_cast<int>(cod.rank());
}

// The sparse path of SolveConstraintForces (dynamics/internal/sparse_solve.h): the same
// system (J M⁻¹ Jᵀ) λ = c - J u̇_free with J by body blocks; redundant rows get the weighted
// least-norm λ of SolveSchur (weights CalcReactionWeights) from SolveSparseLeastNorm. Returns
// false, leaving the dense path to solve it (and to report an inconsistency), when that gives
// up or the rank is unknown (an exactly zero pivot).
bool SolveSparse(const Model& model, Data& data) {
  internal::SparseWorkspace& ws = internal::GetSparseWorkspace(data.sparse_constraints);
  ws.rows.Clear();
  internal::AppendConstraintRows(model, data, ws.rows);
  const int n = ws.rows.rows();
  data.schur_rhs.resize(n);
  for (int i = 0; i < n; ++i)
    data.schur_rhs[i] = data.acceleration_rhs[i] - ws.rows.RowTimes(i, data.u_dot);
  data.constraint_rank = n;
  if (!internal::SolveSparse(model, data, true, ws, data.schur_rhs, data.lambda)) {
    if (!ws.singular_symmetric || ws.nullity < 0) return false;
    const VectorXd d = CalcReactionWeights(model, data);
    if (!internal::SolveSparseLeastNorm(ws, data.schur_rhs, &d, data.lambda)) return false;
    data.constraint_rank = n - ws.nullity;
  }
  internal::AddMinvWTimes(ws, data.lambda, data.u_dot);  // u̇ = u̇_free + M⁻¹ Jᵀ λ
  return true;
}

// Data::a_WBcm_W and Data::wdot_WB_B from Data::u_dot.
void StoreAccelerations(const Model& model, Data& data) {
  for (int b = 0; b < model.num_bodies(); ++b) {
    const auto i = static_cast<size_t>(b);
    data.a_WBcm_W[i] = data.u_dot.segment<3>(6 * b);
    data.wdot_WB_B[i] = data.R_WB[i].transpose() * data.u_dot.segment<3>(6 * b + 3);
  }
}

std::vector<int> RowOwners(const Model& model) {
  std::vector<int> owner(static_cast<size_t>(model.num_constraint_rows()));
  for (int c = 0; c < model.num_constraints(); ++c) {
    const int o = model.constraint_row_offset(c);
    for (int k = 0; k < model.constraint(c).num_rows(); ++k) owner[static_cast<size_t>(o + k)] = c;
  }
  return owner;
}

}  // namespace

void CalcConstraintRows(const Model& model, const State& state, Data& data) {
  CheckDataFor(model, data);
  // The dense Data::J only where it is sized (MakeData below kSparseMinRows rows, a dense
  // consumer through internal::EnsureDenseJacobian); otherwise the rows live in `e` alone.
  const bool dense = data.J.size() != 0;
  for (int c = 0; c < model.num_constraints(); ++c) {
    const Constraint& con = model.constraint(c);
    ConstraintEval& e = data.constraint_rows[static_cast<size_t>(c)];
    const int o = model.constraint_row_offset(c);
    const int n = con.num_rows();
    // J's only non-zero entries are the blocks written here last time (its parent's, child's
    // and extra bodies' columns, still named by `e`); zeroing just those keeps J's fill O(rows).
    if (dense) {
      if (con.parent() != kWorld) data.J.block(o, 6 * con.parent(), n, 6).setZero();
      data.J.block(o, 6 * con.child(), n, 6).setZero();
      for (int k = 0; k < e.num_extra; ++k)
        data.J.block(o, 6 * e.extra_body[static_cast<size_t>(k)], n, 6).setZero();
    }
    e = ConstraintEval{};
    try {
      con.Evaluate(model, state, data, e);
    } catch (const InputError& x) {
      RethrowForElement(x, {ErrorElement::Kind::kConstraint, c});
    }
    // A constraint that can let go keeps its gap (its row's g) for the events; released, its
    // rows leave the system (zero in J, b, c, g; its multiplier is held at 0 by
    // internal::HoldReleasedRows) but `e` keeps its Jacobian rows for the gap rate.
    const bool released = con.can_release() && IsReleased(state, c);
    data.constraint_gap[static_cast<size_t>(c)] = con.can_release() ? e.position_error[0] : 0.0;
    for (int k = 0; k < n; ++k) data.row_released[static_cast<size_t>(o + k)] = released ? 1 : 0;
    if (released) {
      e.position_error.setZero();
      e.holonomic.fill(false);
      data.velocity_rhs.segment(o, n).setZero();
      data.acceleration_rhs.segment(o, n).setZero();
      data.position_error.segment(o, n).setZero();
      continue;
    }
    if (dense) internal::WriteConstraintBlocks(model, data, c, data.J);
    data.velocity_rhs.segment(o, n) = e.velocity_rhs.head(n);
    data.acceleration_rhs.segment(o, n) = e.acceleration_rhs.head(n);
    data.position_error.segment(o, n) = e.position_error.head(n);
  }
}

void SolveConstraintForces(const Model& model, const State& state, Data& data) {
  CheckDataFor(model, data);
  const int nb = model.num_bodies();
  CalcConstraintRows(model, state, data);
  // Free accelerations u̇_free = [a_WBcm_W; R ẇ_B] from the Newton–Euler stage.
  VectorXd& u_dot = data.u_dot;
  for (int b = 0; b < nb; ++b) {
    const auto i = static_cast<size_t>(b);
    u_dot.segment<3>(6 * b) = data.a_WBcm_W[i];
    u_dot.segment<3>(6 * b + 3) = data.R_WB[i] * data.wdot_WB_B[i];
  }
  if (internal::UseSparse(data.linear_solver, model.num_constraint_rows()) &&
      SolveSparse(model, data)) {
    StoreAccelerations(model, data);
    internal::FillConstraintReactions(model, state, data);
    return;
  }
  internal::EnsureDenseJacobian(model, data);
  internal::TimesMassInverse(model, data, data.J, data.JMinv);
  data.schur.noalias() = data.JMinv * data.J.transpose();
  data.Ju.noalias() = data.J * u_dot;  // J u̇_free here; J u below
  data.schur_rhs = data.acceleration_rhs - data.Ju;
  internal::HoldReleasedRows(data.row_released, data.schur, data.schur_rhs);
  const double r_scale =
      std::max(data.acceleration_rhs.cwiseAbs().maxCoeff(), data.Ju.cwiseAbs().maxCoeff());
  // Redundant rows: the reactions least in the norm Σ F² + Σ (M / ℓ)² (moments over the
  // mechanism's length ℓ, so that newtons are never traded against newton-metres).
  data.constraint_rank =
      SolveSchur(model, nullptr, data.schur, data.schur_ldlt.ldlt, data.schur_rhs, data.lambda,
                 "set of reactions", r_scale, &data);
  u_dot.noalias() += data.JMinv.transpose() * data.lambda;  // M⁻¹ Jᵀ λ (M⁻¹ symmetric)
  StoreAccelerations(model, data);
  // Reactions: the child's share of Jᵀλ moved to the joint point J.
  internal::FillConstraintReactions(model, state, data);
}

ConstraintViolation CalcConstraintViolation(const Model& model, const State& state, Data& data) {
  CheckDataFor(model, data);
  ConstraintViolation v;
  if (model.num_constraints() == 0) return v;
  CalcKinematics(model, state, data);
  CalcConstraintRows(model, state, data);
  internal::GetVelocity(model, state, data, data.u);
  VectorXd res(model.num_constraint_rows());
  internal::ConstraintJacobianTimes(model, data, data.u, res);  // O(rows) on the sparse path
  res -= data.velocity_rhs;
  double worst = -1.0;
  for (int c = 0; c < model.num_constraints(); ++c) {
    const ConstraintEval& e = data.constraint_rows[static_cast<size_t>(c)];
    const int o = model.constraint_row_offset(c);
    for (int k = 0; k < model.constraint(c).num_rows(); ++k) {
      const double g = e.holonomic[static_cast<size_t>(k)] ? std::abs(e.position_error[k]) : 0.0;
      const double dv = std::abs(res[o + k]);
      v.position = std::max(v.position, g);
      v.velocity = std::max(v.velocity, dv);
      if (std::max(g, dv) > worst) worst = std::max(g, dv), v.worst = c;
    }
  }
  return v;
}

void ProjectOntoConstraints(const Model& model, State& state, Data& data,
                            const ProjectionOptions& options, VectorXd* velocity_impulse) {
  CheckDataFor(model, data);
  if (velocity_impulse != nullptr) velocity_impulse->setZero(model.num_constraint_rows());
  if (model.num_constraints() == 0) return;
  const int nb = model.num_bodies();
  std::vector<int> hol;  // holonomic rows
  std::vector<int> hol_owner;
  VectorXd mu, dx;
  MatrixXd G, GMinv;
  Eigen::LDLT<MatrixXd> ldlt;
  for (int iter = 0; iter <= options.max_iterations; ++iter) {
    CalcKinematics(model, state, data);
    CalcConstraintRows(model, state, data);
    // A dense solve over every row (the Gauss-Newton steps and the velocity projection).
    internal::EnsureDenseJacobian(model, data);
    if (iter == 0) {
      for (int c = 0; c < model.num_constraints(); ++c) {
        const ConstraintEval& e = data.constraint_rows[static_cast<size_t>(c)];
        for (int k = 0; k < model.constraint(c).num_rows(); ++k) {
          if (e.holonomic[static_cast<size_t>(k)]) {
            hol.push_back(model.constraint_row_offset(c) + k);
            hol_owner.push_back(c);
          }
        }
      }
      if (hol.empty()) break;
    }
    const auto nh = static_cast<Eigen::Index>(hol.size());
    G.resize(nh, 6 * nb);
    VectorXd g(nh);
    for (Eigen::Index k = 0; k < nh; ++k) {
      G.row(k) = data.J.row(hol[static_cast<size_t>(k)]);
      g[k] = data.position_error[hol[static_cast<size_t>(k)]];
    }
    Eigen::Index worst = 0;
    const double g_max = g.cwiseAbs().maxCoeff(&worst);
    if (g_max <= options.position_tolerance) break;
    if (iter == options.max_iterations) {
      // Not converged: fine while the remainder is round-off of a large model, an input error
      // when the constraints cannot be assembled at all (wrong lengths, a closed loop that
      // does not close).
      if (g_max > options.assembly_tolerance) {
        throw InputError(
            fmt::format(
                "constraint '{}' cannot be satisfied: after {} Gauss-Newton steps its position "
                "error is still {:.3g}; check its attachment points and axes against the other "
                "constraints",
                model.constraint(hol_owner[static_cast<size_t>(worst)]).name(),
                options.max_iterations, g_max),
            ErrorElement{ErrorElement::Kind::kConstraint, hol_owner[static_cast<size_t>(worst)]});
      }
      break;
    }
    internal::TimesMassInverse(model, data, G, GMinv);
    // Least squares without the consistency check: an inconsistent set is reported by the
    // acceleration solve, and here the right-hand side is only the drift.
    SolveSchur(model, &hol_owner, GMinv * G.transpose(), ldlt, g, mu, nullptr, 0.0);
    dx = -GMinv.transpose() * mu;
    for (int b = 0; b < nb; ++b) {
      BodyState& bs = state.bodies[static_cast<size_t>(b)];
      bs.p_WBcm += dx.segment<3>(6 * b);
      // δθ is a small rotation about W's axes: q ← exp(δθ) ⊗ q.
      bs.q_WB = (QuatExp(dx.segment<3>(6 * b + 3)) * bs.q_WB).normalized();
    }
  }
  // Velocities: J u = b at the projected configuration.
  CalcKinematics(model, state, data);
  CalcConstraintRows(model, state, data);
  internal::EnsureDenseJacobian(model, data);
  internal::GetVelocity(model, state, data, data.u);
  const VectorXd res = data.J * data.u - data.velocity_rhs;
  if (res.size() == 0 || res.cwiseAbs().maxCoeff() == 0.0) return;
  internal::TimesMassInverse(model, data, data.J, data.JMinv);
  data.schur.noalias() = data.JMinv * data.J.transpose();
  VectorXd r = res;
  internal::HoldReleasedRows(data.row_released, data.schur, r);
  // Asked for the impulse, redundant rows get the reactions' weighted least-norm split
  // (SolveSchur): du is the same whatever the split.
  SolveSchur(model, nullptr, data.schur, data.schur_ldlt.ldlt, r, mu, nullptr, 0.0,
             velocity_impulse != nullptr ? &data : nullptr);
  const VectorXd du = -data.JMinv.transpose() * mu;
  if (velocity_impulse != nullptr) *velocity_impulse = -mu;  // du = M⁻¹ Jᵀ (-mu)
  for (int b = 0; b < nb; ++b) {
    const auto i = static_cast<size_t>(b);
    BodyState& bs = state.bodies[i];
    bs.v_WBcm_W += du.segment<3>(6 * b);
    bs.w_WB_B += data.R_WB[i].transpose() * du.segment<3>(6 * b + 3);
  }
  CalcKinematics(model, state, data);  // leave the kinematics stage consistent with `state`
}

void CalcConstraintReactions(const Model& model, const State& state, const VectorXd& lambda,
                             Data& data) {
  CheckDataFor(model, data);
  if (lambda.size() != model.num_constraint_rows()) {
    throw UsageError(fmt::format("CalcConstraintReactions: {} multipliers for {} constraint rows",
                                 lambda.size(), model.num_constraint_rows()));
  }
  data.lambda = lambda;
  internal::FillConstraintReactions(model, state, data);
}

}  // namespace chasles
