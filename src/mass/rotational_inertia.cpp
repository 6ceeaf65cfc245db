#include "chasles/mass/rotational_inertia.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include "chasles/error.h"

namespace chasles {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Relative tolerance (times the trace) for symmetry, non-negativity and the triangle
// inequality: generous enough for tensors assembled from many parts, far below any physical
// difference.
constexpr double kValidityTolerance = 1e-10;
// Principal moments closer than this (times the trace) are treated as repeated.
constexpr double kRepeatedTolerance = 1e-9;
}  // namespace

RotationalInertia::RotationalInertia() : I_(Mat3::Constant(kNaN)) {}

RotationalInertia::RotationalInertia(double Ixx, double Iyy, double Izz, double Ixy, double Ixz,
                                     double Iyz) {
  I_ << Ixx, Ixy, Ixz, Ixy, Iyy, Iyz, Ixz, Iyz, Izz;
}

RotationalInertia RotationalInertia::FromMatrix(const Mat3& I) {
  return RotationalInertia(I);
}

std::string RotationalInertia::CheckPhysicallyValid() const {
  if (!I_.allFinite()) {
    // Nothing finite in, nothing infinite out, except by overflow: m d² of a distance past
    // ~1e154 m (d² past 1.8e308), or an infinite mass or size.
    return fmt::format(
        "the inertia tensor has a non-finite entry ({}): a value overflowed the range of a "
        "double (about 1.8e308), e.g. m d² for parts very far apart; check for very large "
        "positions, sizes, masses or densities",
        I_.cwiseAbs().maxCoeff());
  }
  const double scale = std::max(std::abs(I_.trace()), I_.cwiseAbs().maxCoeff());
  const double tol = kValidityTolerance * scale;
  if ((I_ - I_.transpose()).cwiseAbs().maxCoeff() > tol) {
    return fmt::format(
        "the inertia tensor is not symmetric (Ixy={:.6g} vs Iyx={:.6g}, "
        "Ixz={:.6g} vs Izx={:.6g}, Iyz={:.6g} vs Izy={:.6g})",
        I_(0, 1), I_(1, 0), I_(0, 2), I_(2, 0), I_(1, 2), I_(2, 1));
  }
  const Mat3 S = 0.5 * (I_ + I_.transpose());
  const Vec3 p = Eigen::SelfAdjointEigenSolver<Mat3>(S, Eigen::EigenvaluesOnly).eigenvalues();
  if (p[0] < -tol) {
    return fmt::format(
        "principal moment {:.6g} is negative (principal moments {:.6g}, {:.6g}, "
        "{:.6g}); a real body has none below zero",
        p[0], p[0], p[1], p[2]);
  }
  if (p[0] + p[1] < p[2] - tol) {
    return fmt::format(
        "principal moments {:.6g}, {:.6g}, {:.6g} violate the triangle inequality: "
        "{:.6g} + {:.6g} < {:.6g}; a real body cannot have this tensor",
        p[0], p[1], p[2], p[0], p[1], p[2]);
  }
  return {};
}

void RotationalInertia::Validate(std::string_view what) const {
  const std::string why = CheckPhysicallyValid();
  if (!why.empty()) throw InputError(fmt::format("{}: {}", what, why));
}

RotationalInertia RotationalInertia::ReExpressedIn(const Mat3& R_AB) const {
  return RotationalInertia(Mat3(R_AB * I_ * R_AB.transpose()));
}

Mat3 PointMassInertia(double mass, const Vec3& d) {
  return mass * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
}

RotationalInertia RotationalInertia::ShiftFromCenterOfMass(double mass, const Vec3& p_PCm) const {
  return RotationalInertia(Mat3(I_ + PointMassInertia(mass, p_PCm)));
}

RotationalInertia RotationalInertia::ShiftToCenterOfMass(double mass, const Vec3& p_PCm) const {
  return RotationalInertia(Mat3(I_ - PointMassInertia(mass, p_PCm)));
}

PrincipalAxes RotationalInertia::CalcPrincipalAxes() const {
  PrincipalAxes out;
  if (!I_.allFinite()) return out;
  const Mat3 S = 0.5 * (I_ + I_.transpose());
  Eigen::SelfAdjointEigenSolver<Mat3> solver(S);
  const Vec3 m = solver.eigenvalues();  // ascending
  Mat3 V = solver.eigenvectors();
  const double tol = kRepeatedTolerance * std::max(std::abs(S.trace()), 1e-300);
  const bool eq01 = std::abs(m[1] - m[0]) <= tol;
  const bool eq12 = std::abs(m[2] - m[1]) <= tol;

  if (eq01 && eq12) {
    // Spherical tensor: every direction is principal; keep the frame's own axes.
    V.setIdentity();
  } else if (eq01 || eq12) {
    // Axisymmetric tensor: the distinct axis u is well defined; within the repeated plane pick
    // the frame axis with the largest projection so that the answer does not depend on the
    // eigensolver's arbitrary choice. Frame axes are tried in cyclic order after u's own
    // (u ~ y tries z, then x), so that u ~ y gives (y, z, x): right-handed, all positive.
    const int distinct = eq01 ? 2 : 0;
    Vec3 u = V.col(distinct).normalized();
    Eigen::Index k = 0;
    u.cwiseAbs().maxCoeff(&k);
    if (u[k] < 0) u = -u;
    Vec3 best = Vec3::Zero();
    for (int step = 1; step <= 3; ++step) {
      const Vec3 e = Vec3::Unit((k + step) % 3);
      const Vec3 proj = e - u * u.dot(e);
      if (proj.norm() > best.norm() + 1e-12) best = proj;
    }
    best.normalize();
    if (distinct == 0) {  // u is e1: e2 in the plane, e3 = e1 x e2
      V.col(0) = u;
      V.col(1) = best;
      V.col(2) = u.cross(best);
    } else {  // u is e3: e1 in the plane, e2 = e3 x e1
      V.col(0) = best;
      V.col(1) = u.cross(best);
      V.col(2) = u;
    }
  }
  // Deterministic signs: the largest-magnitude component of each axis is positive (ties go to
  // the earlier component), then the third axis is fixed by right-handedness.
  for (int c = 0; c < 2; ++c) {
    Eigen::Index k = 0;
    V.col(c).cwiseAbs().maxCoeff(&k);
    if (V(k, c) < 0) V.col(c) = -V.col(c);
  }
  V.col(2) = V.col(0).cross(V.col(1));
  out.moments = m;
  out.axes = V;
  return out;
}

Vec3 RotationalInertia::CalcRadiiOfGyration(double mass) const {
  return Vec3(std::sqrt(Ixx() / mass), std::sqrt(Iyy() / mass), std::sqrt(Izz() / mass));
}

RotationalInertia RotationalInertia::operator+(const RotationalInertia& o) const {
  return RotationalInertia(Mat3(I_ + o.I_));
}
RotationalInertia RotationalInertia::operator-(const RotationalInertia& o) const {
  return RotationalInertia(Mat3(I_ - o.I_));
}
RotationalInertia RotationalInertia::operator*(double s) const {
  return RotationalInertia(Mat3(I_ * s));
}

}  // namespace chasles
