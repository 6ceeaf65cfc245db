#pragma once
/// @file
/// Compensated state updates for the integrators: y ← y + d, where d = h Σ b_i k_i is the
/// step's increment, rounds every component to the precision of y. Over many steps with
/// |d| ≪ |y| those roundings add up (a random walk at best, a drift when they are biased) and
/// set a floor under the error that no smaller step or tighter tolerance can go through: for
/// the Dzhanibekov body (I = 1, 2, 3 kg·m², ω = 10 rad/s) about 6.5e-9 rad of orientation after
/// 100 s with plain double updates.
///
/// Each state component y_i carries a compensation c_i: the part of the exact running sum that
/// y_i could not hold, so that y_i + c_i is the sum to about twice double precision. The update
/// adds c_i to the increment first and keeps the new rounding error, found exactly by Knuth's
/// TwoSum (any magnitudes, no branch; Neumaier's variant of Kahan's summation without its
/// test; Higham, Accuracy and Stability of Numerical Algorithms, 2nd ed., §4.3):
///   b = d_i + c_i,  s = y_i + b,  b' = s − y_i,  c_i = (y_i − (s − b')) + (b − b'),  y_i = s.
/// The derivative is evaluated at y alone (c is below y's last bit): the compensation keeps
/// the sum of increments exact, not the increments themselves (the method's truncation error
/// is unchanged).
///
/// The quaternion q (four components of y) is renormalised after every step, q ← q/|q|. With
/// its compensation the quaternion stands for q + c, and the normalised value of that is, to
/// first order in c (|c| ~ 1e-16),
///   (q + c)/|q + c| = q/|q| + (c − q̂ (q̂·c))/|q| + O(|c|²),   q̂ = q/|q|:
/// the normalisation drops the radial part of c (the norm is reset anyway) and scales the
/// tangential part, which is the part that turns the body, by 1/|q|. The rounding of the
/// product q_i·(1/|q|) itself is recovered exactly with a fused multiply-add and added to c.
/// So across a renormalisation c is carried over as the tangential error of the orientation
/// that the stored quaternion cannot hold, and |q| = 1 to round-off as before.
///
/// The compensation belongs to the state it was accumulated with: an integrator keeps it only
/// while the state it is handed is the one it produced (bit for bit) and starts again from
/// zero otherwise (a state set by the caller, a projection onto constraints, an impulse).

#include <cmath>

#include <Eigen/Core>

#include "integrate/internal/ode.h"

namespace chasles::internal {

/// y ← y + d with compensation c: one component (see the file comment).
inline void CompensatedAdd(double& y, double d, double& c) {
  const double b = d + c;
  const double s = y + b;
  const double bb = s - y;
  c = (y - (s - bb)) + (b - bb);
  y = s;
}

/// The same component by component, for vectors of one size (Vector, Vec3).
template <typename Y, typename D, typename C>
void CompensatedAdd(Eigen::DenseBase<Y>& y, const Eigen::DenseBase<D>& d, Eigen::DenseBase<C>& c) {
  for (Eigen::Index i = 0; i < y.size(); ++i)
    CompensatedAdd(y.coeffRef(i), d.coeff(i), c.coeffRef(i));
}

/// Normalises the quaternion q (w, x, y, z) and carries its compensation c across (see the
/// file comment): (q + c)/|q + c| = q s + s (c − q̂ (q̂·c)) + O(|c|²), s = 1/|q|, q̂ = q s; the
/// rounding of each q_i s is fma(q_i, s, −fl(q_i s)) exactly.
template <typename Q, typename C>
void NormalizeCompensated(Eigen::MatrixBase<Q>& q, Eigen::MatrixBase<C>& c) {
  const double s = 1.0 / q.norm();
  const Eigen::Vector4d qn = q * s;
  Eigen::Vector4d e;
  for (int i = 0; i < 4; ++i) e[i] = std::fma(q[i], s, -qn[i]);
  c = s * (c - qn * qn.dot(c)) + e;
  q = qn;
}

/// a·b over four terms with the rounding error of the result in `err`: Ogita, Rump & Oishi's
/// Dot2 (SIAM J. Sci. Comput. 26, 2005): each product split exactly by a fused multiply-add,
/// each sum by TwoSum.
inline double Dot4(const double (&a)[4], const double (&b)[4], double& err) {
  double p = a[0] * b[0];
  double e = std::fma(a[0], b[0], -p);
  for (int i = 1; i < 4; ++i) {
    const double h = a[i] * b[i];
    const double s = p + h;
    const double z = s - p;
    e += ((p - (s - z)) + (h - z)) + std::fma(a[i], b[i], -h);
    p = s;
  }
  err = e;
  return p;
}

/// q ⊗ r (w, x, y, z) with the product's rounding error added to the compensation c of q,
/// which is carried through the product as c ⊗ r (the product is linear in q).
inline Eigen::Vector4d CompensatedQuatProduct(const Eigen::Vector4d& q, const Eigen::Vector4d& r,
                                              Eigen::Vector4d& c) {
  const auto product = [](const Eigen::Vector4d& a, const Eigen::Vector4d& b) {
    return Eigen::Vector4d(a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
                           a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
                           a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
                           a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]);
  };
  Eigen::Vector4d out, err;
  out[0] = Dot4({q[0], -q[1], -q[2], -q[3]}, {r[0], r[1], r[2], r[3]}, err[0]);
  out[1] = Dot4({q[0], q[1], q[2], -q[3]}, {r[1], r[0], r[3], r[2]}, err[1]);
  out[2] = Dot4({q[0], -q[1], q[2], q[3]}, {r[2], r[3], r[0], r[1]}, err[2]);
  out[3] = Dot4({q[0], q[1], -q[2], q[3]}, {r[3], r[2], r[1], r[0]}, err[3]);
  c = product(c, r) + err;
  return out;
}

}  // namespace chasles::internal
