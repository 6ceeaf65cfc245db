#include "chasles/analysis/linearize.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <Eigen/Dense>

#include "analysis/internal/comoving.h"
#include "analysis/internal/linear_kernels.h"
#include "chasles/dynamics/constraint_solve.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/error.h"
#include "chasles/math/dual.h"
#include "chasles/model/bearing.h"
#include "chasles/model/constraints.h"
#include "chasles/model/forces.h"

namespace chasles {
namespace {

/// Name of the whole system's centre of mass among the coordinates.
constexpr const char* kSystem = "system";

using Eigen::MatrixXd;
using Eigen::VectorXd;

Mat3 Skew(const Vec3& a) {
  Mat3 S;
  S << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return S;
}

/// The exact first derivatives of the descriptor system (linearize.h) at the base state.
struct Jacobians {
  MatrixXd A0, M0, Dq_r, Du_r, Dq_h;
  VectorXd u0;
  std::vector<bool> holonomic;
};

internal::LinearBase MakeBase(const Model& model, const State& state, Data& data) {
  CalcAccelerations(model, state, data);
  internal::LinearBase base;
  for (int b = 0; b < model.num_bodies(); ++b) {
    const auto i = static_cast<size_t>(b);
    base.p.push_back(state.bodies[i].p_WBcm);
    base.R.push_back(data.R_WB[i]);
    base.v.push_back(state.bodies[i].v_WBcm_W);
    base.w_W.push_back(data.w_WB_W[i]);
    base.a.push_back(data.a_WBcm_W[i]);
    base.alpha_W.push_back(data.R_WB[i] * data.wdot_WB_B[i]);
  }
  return base;
}

Jacobians CalcJacobians(const Model& model, const State& state) {
  Data data = MakeData(model);
  const internal::LinearBase base = MakeBase(model, state, data);
  const int n = model.num_bodies(), N = 6 * n;
  Jacobians J;
  internal::KernelOutput<double> out;
  internal::EvaluateKernels<double>(model, base, VectorXd::Zero(2 * N), out);
  J.A0 = out.A;
  J.u0.resize(N);
  J.M0 = MatrixXd::Zero(N, N);
  for (int b = 0; b < n; ++b) {
    const auto i = static_cast<size_t>(b);
    J.u0.segment<3>(6 * b) = base.v[i];
    J.u0.segment<3>(6 * b + 3) = base.w_W[i];
    J.M0.block<3, 3>(6 * b, 6 * b) = model.body(b).mass() * Mat3::Identity();
    J.M0.block<3, 3>(6 * b + 3, 6 * b + 3) =
        base.R[i] * model.body(b).I_BBcm_B() * base.R[i].transpose();
  }
  // λ₀ in the kernels' rows: A₀ᵀλ₀ = M u̇₀ - f (u̇₀ the engine's: one intrinsic motion).
  const VectorXd lambda0 =
      J.A0.rows() > 0
          ? VectorXd(J.A0.transpose().completeOrthogonalDecomposition().solve(out.Mud - out.f))
          : VectorXd();
  J.Dq_r.resize(N, N), J.Du_r.resize(N, N), J.Dq_h.resize(J.A0.rows(), N);
  internal::KernelOutput<Dual> d;
  internal::VecX<Dual> x = internal::VecX<Dual>::Zero(2 * N);
  for (int j = 0; j < 2 * N; ++j) {
    x[j].d = 1.0;
    internal::EvaluateKernels<Dual>(model, base, x, d);
    x[j].d = 0.0;
    const auto dA = d.A.unaryExpr([](const Dual& v) { return v.d; }).eval();
    const auto df = d.f.unaryExpr([](const Dual& v) { return v.d; }).eval();
    if (j < N) {
      const VectorXd dMud = d.Mud.unaryExpr([](const Dual& v) { return v.d; });
      J.Dq_r.col(j) =
          dMud - df - (dA.rows() > 0 ? VectorXd(dA.transpose() * lambda0) : VectorXd::Zero(N));
      J.Dq_h.col(j) = dA * J.u0;
    } else {
      J.Du_r.col(j - N) = -df;
    }
  }
  CalcConstraintRows(model, state, data);
  for (int c = 0; c < model.num_constraints(); ++c) {
    for (int k = 0; k < model.constraint(c).num_rows(); ++k) {
      J.holonomic.push_back(
          data.constraint_rows[static_cast<size_t>(c)].holonomic[static_cast<size_t>(k)]);
    }
  }
  return J;
}

/// An orthonormal basis of the null space of C (columns), rank by singular values relative
/// to the largest.
MatrixXd NullSpace(const MatrixXd& C, int cols) {
  if (C.rows() == 0) return MatrixXd::Identity(cols, cols);
  Eigen::JacobiSVD<MatrixXd> svd(C, Eigen::ComputeFullV);
  const VectorXd& s = svd.singularValues();
  const double tol = 1e-10 * std::max(1.0, s.size() > 0 ? s[0] : 0.0);
  int rank = 0;
  while (rank < s.size() && s[rank] > tol) ++rank;
  return svd.matrixV().rightCols(cols - rank);
}

/// A candidate readout of the reduced state: a named linear function of δq (6n).
struct Readout {
  std::string name, unit;
  Eigen::RowVectorXd row;
};

std::vector<Readout> Readouts(const Model& model, const State& state) {
  const int n = model.num_bodies(), N = 6 * n;
  Data data = MakeData(model);
  CalcKinematics(model, state, data);
  std::vector<Readout> out;
  const auto rel = [&](const std::string& name, const char* unit, BodyIndex p, BodyIndex c,
                       int offset, const Eigen::RowVector3d& a) {
    Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(N);
    row.segment<3>(6 * c + offset) += a;
    if (p != kWorld) row.segment<3>(6 * p + offset) -= a;
    out.push_back({name, unit, row});
  };
  for (int c = 0; c < model.num_constraints(); ++c) {
    const auto* j = dynamic_cast<const Joint*>(&model.constraint(c));
    if (j == nullptr) continue;
    const Mat3 R_P =
        j->parent() == kWorld ? Mat3::Identity() : data.R_WB[static_cast<size_t>(j->parent())];
    const Vec3 axis = R_P * j->X_PJ().R_BJ.col(2);
    const JointKind k = j->joint_kind();
    if (k == JointKind::kRevolute || k == JointKind::kCylindrical ||
        k == JointKind::kRevoluteInPlane) {
      rel(j->name(), "rad", j->parent(), j->child(), 3, axis.transpose());
    }
    if (k == JointKind::kPrismatic || k == JointKind::kCylindrical) {
      // The slide of the child's J origin relative to the parent's point there, along z.
      Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(N);
      const Vec3 pJ = data.R_WB[static_cast<size_t>(j->child())] *
                          model.body(j->child()).PointFromCenterOfMass(j->X_CJ().p_BoJ_B) +
                      state.bodies[static_cast<size_t>(j->child())].p_WBcm;
      const auto add = [&](BodyIndex b, double sign) {
        if (b == kWorld) return;
        const Vec3 r = pJ - state.bodies[static_cast<size_t>(b)].p_WBcm;
        row.segment<3>(6 * b) += sign * axis.transpose();
        row.segment<3>(6 * b + 3) += sign * r.cross(axis).transpose();
      };
      add(j->child(), 1.0), add(j->parent(), -1.0);
      out.push_back({k == JointKind::kCylindrical ? j->name() + ".slide" : j->name(), "m", row});
    }
  }
  static const char* kAxes[3] = {"x", "y", "z"};
  if (internal::TranslationInvariant(model)) {
    // The whole system's centre of mass: free, and apart from everything else.
    double mass = 0.0;
    for (int b = 0; b < n; ++b) mass += model.body(b).mass();
    for (int i = 0; i < 3; ++i) {
      Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(N);
      for (int b = 0; b < n; ++b) row[6 * b + i] = model.body(b).mass() / mass;
      out.insert(out.begin() + i, Readout{std::string(kSystem) + "." + kAxes[i], "m", row});
    }
  }
  for (int b = 0; b < n; ++b) {
    for (int i = 0; i < 3; ++i) {
      rel(model.body(b).name() + ".r" + kAxes[i], "rad", kWorld, b, 3, Eigen::RowVector3d::Unit(i));
    }
  }
  for (int b = 0; b < n; ++b) {
    for (int i = 0; i < 3; ++i) {
      rel(model.body(b).name() + "." + kAxes[i], "m", kWorld, b, 0, Eigen::RowVector3d::Unit(i));
    }
  }
  return out;
}

/// Greedy choice of independent readouts on the reduced space: positions on V_q, then speeds
/// — the rates of the same readouts, on δq̇ = K V_q + V_u, so that a coordinate's rate is its
/// speed exactly and an ignorable coordinate's column of A is zero — each accepted when
/// independent of those before it. Returns S (d × d) and fills the names.
MatrixXd ChooseCoordinates(const std::vector<Readout>& ro, const MatrixXd& V, const MatrixXd& K,
                           int N, Linearization& lin) {
  const int d = static_cast<int>(V.cols());
  MatrixXd S(d, d), Q(d, d);
  int k = 0;
  // A readout is a candidate where it sees more than 1e-8 of itself on the reduced space (V's
  // columns are orthonormal, so |row V| <= |row|): below that its projection is the constraints'
  // own residual (a joint axis tilted by the projection's 1e-10), not a direction of motion.
  const auto try_add = [&](const Eigen::RowVectorXd& row, const MatrixXd& Vpart) {
    if (k == d) return false;
    const Eigen::RowVectorXd y = row * Vpart;
    VectorXd r = y.transpose();
    const double norm = r.norm();
    if (!(norm > 1e-8 * row.norm())) return false;
    for (int pass = 0; pass < 2; ++pass) r -= Q.leftCols(k) * (Q.leftCols(k).transpose() * r);
    if (r.norm() <= 1e-7 * norm) return false;
    Q.col(k) = r / r.norm();
    S.row(k++) = y;
    return true;
  };
  const MatrixXd Vq = V.topRows(N), Vu = K * V.topRows(N) + V.bottomRows(N);
  for (const Readout& r : ro) {
    if (try_add(r.row, Vq)) lin.coordinates.push_back({r.name, r.unit});
  }
  for (const Readout& r : ro) {
    if (try_add(r.row, Vu)) lin.speeds.push_back({"d(" + r.name + ")/dt", r.unit + "/s"});
  }
  if (k < d) {
    throw InputError(
        fmt::format("linearisation: only {} of the {} reduced coordinates could be named", k, d));
  }
  return S;
}

/// Central differences of the engine's co-moving rates along each basis column, against
/// basis · A: the largest difference relative to the largest column (a column that is nearly
/// zero is a difference of large rates, whose round-off is relative to them, not to it).
double FiniteDifferenceCheck(const Model& model, const OperatingPoint& op,
                             const Linearization& lin) {
  Data data = MakeData(model);
  const double h = 1e-6;
  double worst = 0.0, largest = 1e-300;
  for (int j = 0; j < lin.basis.cols(); ++j) {
    const VectorXd z = lin.basis.col(j) / lin.basis.col(j).norm();
    const VectorXd plus = internal::CalcComovingRates(
        model, internal::PerturbState(model, op.state, z, h), op.generator, data);
    const VectorXd minus = internal::CalcComovingRates(
        model, internal::PerturbState(model, op.state, z, -h), op.generator, data);
    const VectorXd fd = (plus - minus) / (2.0 * h);
    const VectorXd exact = lin.basis * lin.A.col(j) / lin.basis.col(j).norm();
    largest = std::max(largest, exact.norm());
    worst = std::max(worst, (fd - exact).norm());
  }
  return worst / largest;
}

}  // namespace

Linearization Linearize(const Model& model, const OperatingPoint& op,
                        const LinearizeOptions& options) {
  internal::CheckLinearisable(model);
  ValidateState(model, op.state);
  const int n = model.num_bodies(), N = 6 * n;
  const Jacobians J = CalcJacobians(model, op.state);
  const int rows = static_cast<int>(J.A0.rows());
  // K = -∂(ξ·q)/∂q and the co-moving turn of the velocities (w_ξ ×).
  MatrixXd K = MatrixXd::Zero(N, N), Wx = MatrixXd::Zero(N, N);
  Data data = MakeData(model);
  CalcKinematics(model, op.state, data);
  for (int b = 0; b < n; ++b) {
    const auto i = static_cast<size_t>(b);
    K.block<3, 3>(6 * b, 6 * b) = -Skew(op.generator.w_W);
    if (!op.generator.spin.empty()) {
      K.block<3, 3>(6 * b + 3, 6 * b + 3) =
          op.generator.spin[i] * Skew(data.R_WB[i] * op.generator.spin_axis_B[i]);
    }
    Wx.block<3, 3>(6 * b, 6 * b) = Skew(op.generator.w_W);
    Wx.block<3, 3>(6 * b + 3, 6 * b + 3) = Skew(op.generator.w_W);
  }
  int holonomic = 0;
  for (bool h : J.holonomic) holonomic += h ? 1 : 0;
  MatrixXd C = MatrixXd::Zero(holonomic + rows, 2 * N);
  for (int r = 0, k = 0; r < rows; ++r) {
    if (J.holonomic[static_cast<size_t>(r)]) C.block(k++, 0, 1, N) = J.A0.row(r);
  }
  C.block(holonomic, 0, rows, N) = J.Dq_h;
  C.block(holonomic, N, rows, N) = J.A0;
  const MatrixXd V = NullSpace(C, 2 * N);
  const int d = static_cast<int>(V.cols());
  MatrixXd E = MatrixXd::Identity(2 * N, 2 * N);
  E.bottomRightCorner(N, N) = J.M0;
  MatrixXd F = MatrixXd::Zero(2 * N, 2 * N);
  F.topLeftCorner(N, N) = K;
  F.topRightCorner(N, N) = MatrixXd::Identity(N, N);
  F.bottomLeftCorner(N, N) = -J.Dq_r;
  F.bottomRightCorner(N, N) = -J.Du_r - J.M0 * Wx;
  MatrixXd L(2 * N, d + rows);
  L.leftCols(d) = E * V;
  if (rows > 0) {
    L.rightCols(rows).topRows(N).setZero();
    L.rightCols(rows).bottomRows(N) = -J.A0.transpose();
  }
  const MatrixXd rhs = F * V;
  const MatrixXd X = L.completeOrthogonalDecomposition().solve(rhs);
  Linearization lin;
  lin.consistency = (L * X - rhs).norm() / std::max(rhs.norm(), 1e-300);
  const MatrixXd Aw = X.topRows(d);
  const MatrixXd S = ChooseCoordinates(Readouts(model, op.state), V, K, N, lin);
  const Eigen::PartialPivLU<MatrixXd> Slu(S);
  lin.A = S * Aw * Slu.inverse();
  lin.basis = V * Slu.inverse();
  if (options.finite_difference_check)
    lin.finite_difference_check = FiniteDifferenceCheck(model, op, lin);
  return lin;
}

}  // namespace chasles
