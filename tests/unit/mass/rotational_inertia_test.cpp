#include "chasles/mass/rotational_inertia.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/error.h"
#include "chasles/math/rotation.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::kExact;
using test::MatNear;
using test::Near;
using ::testing::HasSubstr;

TEST(RotationalInertia, DefaultIsNaN) {
  RotationalInertia I;
  EXPECT_TRUE(std::isnan(I.Ixx()));
  EXPECT_THAT(I.CheckPhysicallyValid(), HasSubstr("non-finite"));
}

TEST(RotationalInertia, ProductsAreStoredAsTensorEntries) {
  // Chapter convention: [I] holds Ixy = -∫xy dm. A point mass m at (1, 2, 0) has ∫xy dm = 2m.
  const double m = 3.0;
  const RotationalInertia I = RotationalInertia::FromMatrix(PointMassInertia(m, Vec3(1, 2, 0)));
  EXPECT_TRUE(Near(I.Ixy(), -2 * m, kExact));
  EXPECT_TRUE(Near(I.Ixx(), 4 * m, kExact));
  EXPECT_TRUE(Near(I.Iyy(), 1 * m, kExact));
  EXPECT_TRUE(Near(I.Izz(), 5 * m, kExact));
  // H = [I] w for rotation about z through the origin: the point moves at w x r.
  const Vec3 w(0, 0, 1.5);
  const Vec3 r(1, 2, 0);
  EXPECT_TRUE(MatNear(Vec3(I.matrix() * w), Vec3(m * r.cross(w.cross(r))), kExact));
}

TEST(RotationalInertia, TriangleInequalityRejected) {
  const RotationalInertia I(1, 1, 3);
  EXPECT_THAT(I.CheckPhysicallyValid(), HasSubstr("violate the triangle inequality: 1 + 1 < 3"));
  try {
    I.Validate("body 'wheel'");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("body 'wheel': principal moments 1, 1, 3"));
  }
}

TEST(RotationalInertia, LimitsOfThinBodiesAreValid) {
  // Flat plate: Izz = Ixx + Iyy exactly; slender rod: a zero moment.
  EXPECT_EQ(RotationalInertia(1.0 / 12, 4.0 / 12, 5.0 / 12).CheckPhysicallyValid(), "");
  EXPECT_EQ(RotationalInertia(1.0 / 3, 1.0 / 3, 0).CheckPhysicallyValid(), "");
}

TEST(RotationalInertia, NegativeAndAsymmetricRejected) {
  EXPECT_THAT(RotationalInertia(-1, 2, 2).CheckPhysicallyValid(), HasSubstr("negative"));
  Mat3 A = Mat3::Identity();
  A(0, 1) = 0.1;
  EXPECT_THAT(RotationalInertia::FromMatrix(A).CheckPhysicallyValid(), HasSubstr("not symmetric"));
}

TEST(RotationalInertia, ParallelAxisBothWays) {
  // Eq. 8.29 for a solid box a x b x c about a corner: Ixx = m(b²+c²)/3, Ixy = -m a b / 4.
  const double m = 2.5, a = 0.3, b = 0.5, c = 0.7;
  const RotationalInertia Icm(m * (b * b + c * c) / 12, m * (a * a + c * c) / 12,
                              m * (a * a + b * b) / 12);
  const Vec3 p_PCm(a / 2, b / 2, c / 2);
  const RotationalInertia Ip = Icm.ShiftFromCenterOfMass(m, p_PCm);
  const RotationalInertia expected(m * (b * b + c * c) / 3, m * (a * a + c * c) / 3,
                                   m * (a * a + b * b) / 3, -m * a * b / 4, -m * a * c / 4,
                                   -m * b * c / 4);
  EXPECT_TRUE(MatNear(Ip.matrix(), expected.matrix(), kExact));
  EXPECT_TRUE(MatNear(Ip.ShiftToCenterOfMass(m, p_PCm).matrix(), Icm.matrix(), kExact));
}

TEST(RotationalInertia, ReExpressionKeepsInvariants) {
  const RotationalInertia I(2, 3, 4, -0.3, 0.2, -0.1);
  const Mat3 R = RotationFromEuler("ZYX", Vec3(0.3, -1.1, 2.0));
  const RotationalInertia J = I.ReExpressedIn(R);
  EXPECT_TRUE(Near(J.Trace(), I.Trace(), kExact));
  EXPECT_TRUE(MatNear(J.CalcPrincipalAxes().moments, I.CalcPrincipalAxes().moments, kExact));
  EXPECT_TRUE(MatNear(J.ReExpressedIn(R.transpose()).matrix(), I.matrix(), kExact));
}

TEST(RotationalInertia, PrincipalAxesDiagonaliseAndAreRightHanded) {
  const RotationalInertia I(2, 3, 4, -0.3, 0.2, -0.1);
  const PrincipalAxes p = I.CalcPrincipalAxes();
  EXPECT_LE(p.moments[0], p.moments[1]);
  EXPECT_LE(p.moments[1], p.moments[2]);
  EXPECT_TRUE(Near(p.axes.determinant(), 1.0, kExact));
  const Mat3 D = p.axes.transpose() * I.matrix() * p.axes;
  EXPECT_TRUE(MatNear(D, Mat3(p.moments.asDiagonal()), 1e-14, 4.0));
}

TEST(RotationalInertia, PrincipalAxesOfKnownRotation) {
  // diag(1, 2, 3) rotated by 30 degrees about z: axes are the rotated frame axes.
  const Mat3 R = RotationFromAxisAngle(Vec3::UnitZ(), M_PI / 6);
  const PrincipalAxes p = RotationalInertia(1, 2, 3).ReExpressedIn(R).CalcPrincipalAxes();
  EXPECT_TRUE(MatNear(p.moments, Vec3(1, 2, 3), kExact));
  EXPECT_TRUE(MatNear(p.axes, R, 1e-14, 1.0));
}

TEST(RotationalInertia, RepeatedMomentsGiveFrameAxes) {
  // A sphere: every axis is principal, the identity is reported.
  const PrincipalAxes sphere = RotationalInertia(0.4, 0.4, 0.4).CalcPrincipalAxes();
  EXPECT_TRUE(MatNear(sphere.axes, Mat3::Identity(), 0, 1.0));
  // A cylinder about z: the distinct axis is z (largest or smallest), the others x and y.
  const PrincipalAxes disk = RotationalInertia(0.25, 0.25, 0.5).CalcPrincipalAxes();
  EXPECT_TRUE(MatNear(disk.moments, Vec3(0.25, 0.25, 0.5), kExact));
  EXPECT_TRUE(MatNear(disk.axes, Mat3::Identity(), 1e-15, 1.0));
  // A rod along z: the smallest moment's axis z first, then x and y in cyclic order.
  const PrincipalAxes rod = RotationalInertia(1.0 / 3, 1.0 / 3, 0.01).CalcPrincipalAxes();
  Mat3 zxy;
  zxy << 0, 1, 0, 0, 0, 1, 1, 0, 0;
  EXPECT_TRUE(MatNear(rod.axes, zxy, 1e-15, 1.0));
  // A disk whose axis lies along y: its largest moment's axis y last, after z and x (cyclic
  // order after y), so no axis comes out negative.
  const PrincipalAxes disk_y = RotationalInertia(0.25, 0.5, 0.25).CalcPrincipalAxes();
  Mat3 zxy_columns;
  zxy_columns << 0, 1, 0, 0, 0, 1, 1, 0, 0;
  EXPECT_TRUE(MatNear(disk_y.axes, zxy_columns, 1e-15, 1.0));
  EXPECT_TRUE(MatNear(disk_y.moments, Vec3(0.25, 0.25, 0.5), kExact));
}

TEST(RotationalInertia, RadiiOfGyration) {
  // Eq. 8.19 for a solid sphere: R = sqrt(2/5) r.
  const double m = 3, r = 0.2;
  const double I = 0.4 * m * r * r;
  EXPECT_TRUE(
      Near(RotationalInertia(I, I, I).CalcRadiiOfGyration(m)[2], std::sqrt(0.4) * r, kExact));
}

}  // namespace
}  // namespace chasles
