#include "chasles/math/rotation.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/error.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::kExact;
using test::MatNear;
using ::testing::HasSubstr;

Mat3 Rz(double a) {
  Mat3 R;
  R << std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1;
  return R;
}
Mat3 Ry(double a) {
  Mat3 R;
  R << std::cos(a), 0, std::sin(a), 0, 1, 0, -std::sin(a), 0, std::cos(a);
  return R;
}
Mat3 Rx(double a) {
  Mat3 R;
  R << 1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a);
  return R;
}

TEST(Rotation, SkewIsTheCrossProduct) {
  const Vec3 v(1, -2, 3), w(0.5, 4, -1);
  EXPECT_TRUE(MatNear(Vec3(Skew(v) * w), Vec3(v.cross(w)), kExact));
}

TEST(Rotation, AxisAngleAgainstElementaryRotations) {
  EXPECT_TRUE(MatNear(RotationFromAxisAngle(Vec3(0, 0, 2), 0.3), Rz(0.3), kExact, 1.0));
  EXPECT_TRUE(MatNear(RotationFromAxisAngle(Vec3(0, -1, 0), 0.3), Ry(-0.3), kExact, 1.0));
  EXPECT_THAT([] { RotationFromAxisAngle(Vec3::Zero(), 1.0); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("no direction")));
}

TEST(Rotation, EulerIntrinsicAndExtrinsic) {
  const Vec3 a(0.3, -0.7, 1.1);
  // Intrinsic Z-Y-X: R = Rz(a0) Ry(a1) Rx(a2); extrinsic z-y-x: R = Rx(a2) Ry(a1) Rz(a0).
  EXPECT_TRUE(
      MatNear(RotationFromEuler("ZYX", a), Mat3(Rz(a[0]) * Ry(a[1]) * Rx(a[2])), kExact, 1.0));
  EXPECT_TRUE(
      MatNear(RotationFromEuler("zyx", a), Mat3(Rx(a[2]) * Ry(a[1]) * Rz(a[0])), kExact, 1.0));
  // Proper Euler angles Z-X-Z.
  EXPECT_TRUE(
      MatNear(RotationFromEuler("ZXZ", a), Mat3(Rz(a[0]) * Rx(a[1]) * Rz(a[2])), kExact, 1.0));
  for (const char* bad : {"ZZX", "XY", "ZYx", "ABC"}) {
    EXPECT_THROW(RotationFromEuler(bad, a), InputError) << bad;
  }
}

TEST(Rotation, QuaternionIsWxyz) {
  // 90 degrees about z: (w, x, y, z) = (cos 45°, 0, 0, sin 45°).
  const double c = std::sqrt(0.5);
  EXPECT_TRUE(MatNear(RotationFromQuaternion(c, 0, 0, c), Rz(M_PI / 2), kExact, 1.0));
  EXPECT_THAT([] { RotationFromQuaternion(1, 1, 0, 0); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("length")));
}

TEST(Rotation, TakingZToADirection) {
  for (const Vec3& d :
       {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(1, 2, -3)}) {
    const Mat3 R = RotationTakingZTo(d);
    EXPECT_TRUE(IsRotation(R, 1e-14)) << d.transpose();
    EXPECT_TRUE(MatNear(Vec3(R * Vec3::UnitZ()), Vec3(d.normalized()), 1e-15, 1.0))
        << d.transpose();
  }
  EXPECT_FALSE(IsRotation(2 * Mat3::Identity()));
}

}  // namespace
}  // namespace chasles
