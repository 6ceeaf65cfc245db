#pragma once
/// @file
/// A planar double pendulum of two uniform rods at rest, struck by an impulse (chapter 8.5),
/// with its closed form: the impulse-momentum principle on each rod (eqs. 8.118, 8.119) with
/// the two pins' impulses as unknowns. Shared by tests/scenarios (the library) and tests/e2e
/// (examples/double-pendulum-struck.yaml).
///
/// The upper rod (m1, L1) is pinned to the world at O = 0 and points along
/// e1 = (cos θ1, sin θ1); the lower rod (m2, L2) is pinned to its end at the elbow E = L1 e1 and
/// points along e2. The impulse J strikes the lower rod at P = E + s e2. Unknowns: the angular
/// velocity jumps ω1, ω2 (about z) and the impulses R_O (the world's on the upper rod at O) and
/// R_E (the upper rod's on the lower one at E). With k × r = (-r_y, r_x) and
/// a × b = a_x b_y - a_y b_x, r1 = (L1/2) e1, h2 = (L2/2) e2, I_i = m_i L_i²/12:
///   upper rod:  m1 ω1 (k × r1) = R_O - R_E,       I1 ω1 = -r1 × R_O - r1 × R_E,
///   lower rod:  m2 (ω1 (k × L1 e1) + ω2 (k × h2)) = R_E + J,
///               I2 ω2 = -h2 × R_E + (s e2 - h2) × J,
/// six linear equations in the six unknowns.

#include <cmath>
#include <numbers>

#include <Eigen/Dense>

namespace chasles::reference {

struct StruckDoublePendulum {
  double m1 = 2.0, L1 = 1.0, m2 = 1.0, L2 = 0.8;
  /// Angles of the rods from +x, counterclockwise [rad].
  double theta1 = -std::numbers::pi / 2, theta2 = -std::numbers::pi / 2;
  /// The struck point's distance from the elbow along the lower rod [m].
  double s = 0.6;
  /// The impulse [N·s].
  Eigen::Vector2d J = Eigen::Vector2d(3.0, 0.0);

  struct Answer {
    /// Angular velocity jumps about z [rad/s].
    double w1 = 0.0, w2 = 0.0;
    /// Pin impulses on the child of each pin (upper rod at O, lower rod at E) [N·s].
    Eigen::Vector2d R_O = Eigen::Vector2d::Zero(), R_E = Eigen::Vector2d::Zero();
    /// Velocity jumps of the centres of mass [m/s].
    Eigen::Vector2d dv1 = Eigen::Vector2d::Zero(), dv2 = Eigen::Vector2d::Zero();
  };

  static Eigen::Vector2d Perp(const Eigen::Vector2d& r) { return {-r.y(), r.x()}; }
  static double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() * b.y() - a.y() * b.x();
  }
  Eigen::Vector2d e1() const { return {std::cos(theta1), std::sin(theta1)}; }
  Eigen::Vector2d e2() const { return {std::cos(theta2), std::sin(theta2)}; }
  Eigen::Vector2d Elbow() const { return L1 * e1(); }

  /// The six impulse-momentum equations above, solved.
  Answer Solve() const {
    const Eigen::Vector2d r1 = 0.5 * L1 * e1(), h2 = 0.5 * L2 * e2();
    const Eigen::Vector2d k_r1 = Perp(r1), k_E = Perp(L1 * e1()), k_h2 = Perp(h2);
    const double I1 = m1 * L1 * L1 / 12, I2 = m2 * L2 * L2 / 12;
    // Unknowns x = [ω1, ω2, R_Ox, R_Oy, R_Ex, R_Ey]; a × R = (-a_y, a_x)·R.
    Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> b = Eigen::Matrix<double, 6, 1>::Zero();
    for (int i = 0; i < 2; ++i) {
      A(i, 0) = m1 * k_r1[i];
      A(i, 2 + i) = -1.0;
      A(i, 4 + i) = 1.0;
      A(3 + i, 0) = m2 * k_E[i];
      A(3 + i, 1) = m2 * k_h2[i];
      A(3 + i, 4 + i) = -1.0;
      b[3 + i] = J[i];
    }
    A(2, 0) = I1;
    A(2, 2) = -r1.y(), A(2, 3) = r1.x();
    A(2, 4) = -r1.y(), A(2, 5) = r1.x();
    A(5, 1) = I2;
    A(5, 4) = -h2.y(), A(5, 5) = h2.x();
    b[5] = Cross(s * e2() - h2, J);
    const Eigen::Matrix<double, 6, 1> x = A.fullPivLu().solve(b);
    Answer a;
    a.w1 = x[0], a.w2 = x[1];
    a.R_O = x.segment<2>(2), a.R_E = x.segment<2>(4);
    a.dv1 = a.w1 * k_r1;
    a.dv2 = a.w1 * k_E + a.w2 * k_h2;
    return a;
  }

  /// Hanging (θ1 = θ2 = -90°) and struck along x, in closed form: with the angles φ from the
  /// downward vertical, T = ½ φ̇ᵀ M φ̇, M11 = (m1/3 + m2) L1², M12 = m2 L1 L2 / 2,
  /// M22 = m2 L2²/3, and the impulse's generalised components (J L1, J s): Δφ̇ = M⁻¹ (J L1, J s);
  /// then R_E = m2 (L1 Δφ̇1 + L2 Δφ̇2 / 2) - J and R_O = m1 (L1/2) Δφ̇1 + R_E along x.
  Answer Hanging() const {
    const double M11 = (m1 / 3 + m2) * L1 * L1, M12 = m2 * L1 * L2 / 2, M22 = m2 * L2 * L2 / 3;
    const double D = M11 * M22 - M12 * M12, Jx = J.x();
    Answer a;
    a.w1 = Jx * (L1 * M22 - s * M12) / D;
    a.w2 = Jx * (s * M11 - L1 * M12) / D;
    a.R_E = {m2 * (L1 * a.w1 + L2 * a.w2 / 2) - Jx, 0.0};
    a.R_O = {m1 * L1 / 2 * a.w1 + a.R_E.x(), 0.0};
    a.dv1 = {L1 / 2 * a.w1, 0.0};
    a.dv2 = {L1 * a.w1 + L2 / 2 * a.w2, 0.0};
    return a;
  }
};

}  // namespace chasles::reference
