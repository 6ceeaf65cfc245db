#include "chasles/math/quaternion.h"

#include <cmath>

#include <gtest/gtest.h>

#include "chasles/math/rotation.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::kExact;
using test::MatNear;
using test::Near;

TEST(Quaternion, WxyzOrderRoundTrips) {
  const Quat q = QuatFromWxyz(1, 2, 3, 4);
  EXPECT_EQ(q.w(), 1);
  EXPECT_EQ(q.x(), 2);
  EXPECT_EQ(QuatToWxyz(q), Eigen::Vector4d(1, 2, 3, 4));
}

TEST(Quaternion, ExpMatchesAxisAngle) {
  const Vec3 axis = Vec3(1, -2, 0.5).normalized();
  for (double angle : {1e-9, 1e-5, 0.3, 2.0, 3.1}) {
    const Mat3 R = QuatExp(angle * axis).toRotationMatrix();
    EXPECT_TRUE(MatNear(R, RotationFromAxisAngle(axis, angle), kExact, 1.0)) << angle;
    EXPECT_TRUE(MatNear(QuatLog(QuatExp(angle * axis)), angle * axis, kExact, 1e-300)) << angle;
  }
}

TEST(Quaternion, GibbsIsCayley) {
  // Cayley transform (E - [g])⁻¹ (E + [g]) is the rotation by 2 atan|g| about g.
  const Vec3 g(0.2, -0.1, 0.4);
  const Mat3 cay = (Mat3::Identity() - Skew(g)).inverse() * (Mat3::Identity() + Skew(g));
  EXPECT_TRUE(MatNear(QuatFromGibbs(g).toRotationMatrix(), cay, kExact, 1.0));
  EXPECT_TRUE(MatNear(cay, RotationFromAxisAngle(g, 2 * std::atan(g.norm())), kExact, 1.0));
}

TEST(Quaternion, BodyRateIntegrationIsExactForConstantRate) {
  // Constant body rate w for time t: R(t) = R0 exp([w] t).
  const Quat q0 = QuatExp(Vec3(0.3, 0.2, -0.1));
  const Vec3 w(0.5, -1.0, 2.0);
  const Quat q1 = IntegrateBodyAngularVelocity(q0, w, 0.7);
  EXPECT_TRUE(MatNear(q1.toRotationMatrix(),
                      q0.toRotationMatrix() * RotationFromAxisAngle(w, w.norm() * 0.7), kExact,
                      1.0));
  EXPECT_TRUE(Near(q1.norm(), 1.0, kExact));
}

TEST(Quaternion, DerivativeIsHalfProductWithBodyRate) {
  const Quat q = QuatExp(Vec3(0.3, 0.2, -0.1));
  const Vec3 w(0.5, -1.0, 2.0);
  const Quat expected = Quat(q * Quat(0, w.x(), w.y(), w.z()));
  EXPECT_TRUE(
      MatNear(QuatDerivativeWxyz(QuatToWxyz(q), w), 0.5 * QuatToWxyz(expected), kExact, 1.0));
}

}  // namespace
}  // namespace chasles
