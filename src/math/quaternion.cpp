#include "chasles/math/quaternion.h"

#include <cmath>

namespace chasles {

Quat QuatFromWxyz(double w, double x, double y, double z) {
  return Quat(w, x, y, z);
}

Eigen::Vector4d QuatToWxyz(const Quat& q) {
  return {q.w(), q.x(), q.y(), q.z()};
}

Quat QuatExp(const Vec3& v) {
  const double angle = v.norm();
  const double half = 0.5 * angle;
  // sin(a/2)/a by its Taylor series for small a: 1/2 - a²/48 + a⁴/3840; the next term is
  // below 1e-20 for a < 1e-4, i.e. below round-off.
  const double s = angle < 1e-4
                       ? 0.5 - angle * angle / 48.0 + angle * angle * angle * angle / 3840.0
                       : std::sin(half) / angle;
  return Quat(std::cos(half), s * v.x(), s * v.y(), s * v.z());
}

Vec3 QuatLog(const Quat& q_in) {
  Quat q = q_in.normalized();
  if (q.w() < 0) q.coeffs() = -q.coeffs();  // the short way round
  const Vec3 u = q.vec();
  const double s = u.norm();
  // angle = 2 atan2(|u|, w) is accurate for every angle (acos(w) loses digits near 0).
  const double angle = 2.0 * std::atan2(s, q.w());
  if (s < 1e-300) return Vec3::Zero();
  return (angle / s) * u;
}

Quat QuatFromGibbs(const Vec3& g) {
  const double n = 1.0 / std::sqrt(1.0 + g.squaredNorm());
  return Quat(n, n * g.x(), n * g.y(), n * g.z());
}

Quat IntegrateBodyAngularVelocity(const Quat& q_WB, const Vec3& w_WB_B, double dt) {
  return (q_WB * QuatExp(w_WB_B * dt)).normalized();
}

Eigen::Vector4d QuatDerivativeWxyz(const Eigen::Vector4d& q, const Vec3& w) {
  // ½ q ⊗ (0, w) with q = (q0, qv): (-qv·w, q0 w + qv × w) / 2.
  const Vec3 qv(q[1], q[2], q[3]);
  const Vec3 d = q[0] * w + qv.cross(w);
  return 0.5 * Eigen::Vector4d(-qv.dot(w), d.x(), d.y(), d.z());
}

}  // namespace chasles
