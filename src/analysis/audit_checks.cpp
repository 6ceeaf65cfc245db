// A link's inertial checked on its own and against its geometry (analysis/internal/
// audit_steps.h); the rules and thresholds are those of docs/audit.md.

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include "analysis/internal/audit_steps.h"

namespace chasles::internal {

namespace {

using T = AuditThresholds;

/// Eigenvalues of a symmetric tensor, ascending.
Vec3 Moments(const Mat3& I) {
  return Eigen::SelfAdjointEigenSolver<Mat3>(I, Eigen::EigenvaluesOnly).eigenvalues();
}

/// True when `v` is exactly a power of ten (1e-3, 0.01, 1, 10: the numbers people type as a
/// placeholder).
bool PowerOfTen(double v) {
  if (!(v > 0.0)) return false;
  const double e = std::round(std::log10(v));
  return std::abs(v / std::pow(10.0, e) - 1.0) < 1e-12;
}

}  // namespace

std::string TensorText(const Mat3& I) {
  return fmt::format("[Ixx {:.4g}, Iyy {:.4g}, Izz {:.4g}, Ixy {:.4g}, Ixz {:.4g}, Iyz {:.4g}]",
                     I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2));
}

void AddFinding(LinkAudit& audit, Severity severity, FindingCode code, int line,
                std::string message, std::optional<MassProperties> fix, std::string rule) {
  Finding f;
  f.severity = severity;
  f.code = code;
  f.line = line;
  f.message = std::move(message);
  if (fix && audit.has_inertial) {
    f.effect = DynamicEffect(audit.given.I_BBcm_B().matrix(), fix->I_BBcm_B().matrix());
  }
  f.fix = std::move(fix);
  f.fix_rule = std::move(rule);
  audit.findings.push_back(std::move(f));
}

Vec3 TensorRatios(const Mat3& given, const Mat3& computed) {
  // Generalised eigenvalues of given x = λ computed x: with computed = L Lᵀ (Cholesky), the
  // eigenvalues of L⁻¹ given L⁻ᵀ.
  const Eigen::LLT<Mat3> llt(computed);
  const Mat3 Linv = llt.matrixL().solve(Mat3::Identity());
  return Moments(Linv * given * Linv.transpose());
}

double TensorFactor(const Mat3& given, const Mat3& computed) {
  const Vec3 r = TensorRatios(given, computed);
  if (!(r[0] > 0.0)) return std::numeric_limits<double>::infinity();
  return std::max(r[2], 1.0 / r[0]);
}

Mat3 NearestValidTensor(const Mat3& I) {
  // Keep the principal axes and the moments' magnitudes; project them onto the cone λ_i >= 0, λ_i +
  // λ_j >= λ_k (alternating projections onto the half-spaces, Dykstra's correction for the nearest
  // point), then keep the smallest above 1e-6 of the largest so the tensor is invertible.
  const Eigen::SelfAdjointEigenSolver<Mat3> es(I);
  // A negative moment is most often a sign slip: its magnitude is kept.
  Vec3 x = es.eigenvalues().cwiseAbs();
  const double scale = std::max(x.cwiseAbs().maxCoeff(), 1e-300);
  std::vector<Vec3> normals = {Vec3(1, 0, 0),  Vec3(0, 1, 0),  Vec3(0, 0, 1),
                               Vec3(1, 1, -1), Vec3(1, -1, 1), Vec3(-1, 1, 1)};
  std::vector<Vec3> corr(normals.size(), Vec3::Zero());
  for (int iter = 0; iter < 500; ++iter) {
    for (std::size_t k = 0; k < normals.size(); ++k) {
      const Vec3 y = x + corr[k];
      const double v = normals[k].dot(y);
      const Vec3 proj = v < 0 ? Vec3(y - v / normals[k].squaredNorm() * normals[k]) : y;
      corr[k] = y - proj;
      x = proj;
    }
  }
  const double floor = 1e-6 * std::max(x.maxCoeff(), 1e-12 * scale);
  x = x.cwiseMax(floor);
  // Raising a small moment may break the triangle inequality by that much: restore it.
  // Kept 1e-4 inside the cone, so that it stays valid once written with 6 digits.
  std::sort(x.data(), x.data() + 3);
  x[2] = std::min(x[2], (1 - 1e-4) * (x[0] + x[1]));
  return es.eigenvectors() * x.asDiagonal() * es.eigenvectors().transpose();
}

std::string DynamicEffect(const Mat3& before, const Mat3& after) {
  // Angular acceleration about each link axis under a unit moment about it: α_k = (I⁻¹)_kk.
  const Vec3 m = Moments(before);
  if (!(m[0] > 0.0) || m[0] + m[1] < m[2] * (1 - 1e-9)) {
    return "the given tensor has no physical motion to compare (a simulator refuses it or "
           "accelerates without bound)";
  }
  const Mat3 a0 = before.inverse(), a1 = after.inverse();
  int axis = 0;
  double worst = 1.0;
  for (int k = 0; k < 3; ++k) {
    const double r = a0(k, k) / a1(k, k);
    if (std::max(r, 1 / r) > worst) worst = std::max(r, 1 / r), axis = k;
  }
  static constexpr const char* kAxis[3] = {"x", "y", "z"};
  return fmt::format(
      "angular acceleration about the link's {} axis under 1 N·m: {:.4g} → "
      "{:.4g} rad/s² ({:.3g}×)",
      kAxis[axis], a0(axis, axis), a1(axis, axis), a1(axis, axis) / a0(axis, axis));
}

void CheckInertialAlone(const RobotLink& link, LinkAudit& audit) {
  if (!link.has_inertial) return;
  const RobotInertial& in = link.inertial;
  const double m = in.mass;
  const Mat3 I = audit.given.I_BBcm_B().matrix();
  const bool all_zero = I.isZero(0.0);
  if (!(m > 0.0) && (m < 0.0 || !link.geometries.empty())) {
    AddFinding(audit, m < 0 ? Severity::kError : Severity::kWarning, FindingCode::kZeroMass,
               in.mass_line > 0 ? in.mass_line : in.line,
               fmt::format("mass {:g} kg: {}", m,
                           m < 0 ? "a negative mass has no physical meaning"
                                 : "a link with geometry but no mass; simulators drop it, or "
                                   "refuse it when a joint moves it"));
  }
  if (all_zero && !(m > 0.0)) return;
  const Vec3 lambda = Moments(I);
  const double tol = T::kValidity * std::max(std::abs(I.trace()), lambda.cwiseAbs().maxCoeff());
  const MassProperties nearest(m, audit.given.p_BoBcm_B(),
                               RotationalInertia::FromMatrix(NearestValidTensor(I)));
  const std::string rule = "the nearest valid tensor keeping the principal axes";
  if (lambda[0] <= tol) {
    AddFinding(audit, Severity::kError, FindingCode::kNotPositiveDefinite, in.inertia_line,
               fmt::format("the inertia {} has principal moments {:.4g}, {:.4g}, {:.4g} kg·m²: a "
                           "moment <= 0 is not a body's (every moment of a real body is a sum of "
                           "m r² > 0); write {} instead",
                           TensorText(I), lambda[0], lambda[1], lambda[2],
                           TensorText(nearest.I_BBcm_B().matrix())),
               nearest, rule);
  } else if (lambda[0] + lambda[1] < lambda[2] - tol) {
    AddFinding(audit, Severity::kError, FindingCode::kTriangleInequality, in.inertia_line,
               fmt::format("principal moments {:.4g}, {:.4g}, {:.4g} kg·m² violate the triangle "
                           "inequality: {:.4g} + {:.4g} < {:.4g} (I1 + I2 = 2∫z² dm + I3 >= I3 for "
                           "any body); write {} instead",
                           lambda[0], lambda[1], lambda[2], lambda[0], lambda[1], lambda[2],
                           TensorText(nearest.I_BBcm_B().matrix())),
               nearest, rule);
  }
  const Mat3& W = in.I_LcmI_I;
  if (W(0, 0) == W(1, 1) && W(1, 1) == W(2, 2) && W(0, 1) == 0 && W(0, 2) == 0 && W(1, 2) == 0 &&
      PowerOfTen(W(0, 0))) {
    AddFinding(audit, Severity::kWarning, FindingCode::kPlaceholderInertia, in.inertia_line,
               fmt::format("the inertia is {:g}·E, a placeholder: a body whose moments are all a "
                           "round {:g} kg·m² (radius of gyration {:.3g} m at {:.4g} kg) was "
                           "typed, not computed",
                           W(0, 0), W(0, 0), m > 0 ? std::sqrt(W(0, 0) / m) : NAN, m));
  }
}

}  // namespace chasles::internal
