// Contact specs: validation messages and the reduction of shapes to contact points.

#include "chasles/model/contact.h"

#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/dynamics/lcp.h"
#include "chasles/error.h"
#include "chasles/model/model.h"
#include "test_support.h"

namespace chasles {
namespace {

using ::testing::HasSubstr;

Model OneBody() {
  Model model;
  model.AddBody("b", MassProperties(1.0, Vec3::Zero(),
                                    RotationalInertia::FromMatrix(Mat3::Identity() * 0.1)));
  return model;
}

ContactSpec Sphere(std::string name = "c") {
  ContactSpec s;
  s.name = std::move(name);
  s.shape = ContactShape::kSphere;
  s.body = 0;
  s.radius = 0.1;
  s.mu_s = 0.5;
  s.mu_k = 0.4;
  return s;
}

void ExpectError(const ContactSpec& spec, const char* text) {
  try {
    ValidateContactSpec(spec);
    FAIL() << "no error for " << text;
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr(text));
  }
}

TEST(ContactSpec, RejectsBadCoefficientsAndDimensions) {
  ContactSpec s = Sphere();
  s.mu_s = -0.1;
  ExpectError(s, "mu_s (static friction) is -0.1; a friction coefficient must be >= 0");
  s = Sphere();
  s.mu_k = 0.6;
  ExpectError(s, "mu_k = 0.6 exceeds static friction mu_s = 0.5");
  s = Sphere();
  s.restitution = 1.2;
  ExpectError(s, "e = 1.2 is outside [0, 1]");
  s = Sphere();
  s.radius = 0.0;
  ExpectError(s, "radius is 0 m; it must be a positive length");
  s = Sphere();
  s.shape = ContactShape::kPointSet;
  ExpectError(s, "no points given");
  s = Sphere();
  s.plane_normal_W = Vec3::Zero();
  ExpectError(s, "plane normal is zero");
}

TEST(ContactSpec, ShapesReduceToPoints) {
  Model model = OneBody();
  ContactSpec s = Sphere();
  EXPECT_EQ(Contact(model, s).num_points(), 1);
  s.shape = ContactShape::kBox;
  s.half_extents = Vec3(1, 2, 3);
  const Contact box(model, s);
  ASSERT_EQ(box.num_points(), 8);
  EXPECT_TRUE(test::MatNear(box.feature(7).p_BcmF_B, Vec3(1, 2, 3), test::kExact));
  EXPECT_EQ(box.point_name(3), "c_3");
  s.shape = ContactShape::kCylinder;
  s.length = 0.4;
  EXPECT_EQ(Contact(model, s).num_points(), 2);
  s.shape = ContactShape::kDiskFace;
  EXPECT_EQ(Contact(model, s).num_points(), 8);
  model.AddContact(Sphere());
  EXPECT_EQ(model.num_contact_points(), 1);
  try {
    model.AddContact(Sphere());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("contact 'c' is defined twice"));
  }
}

// Lemke on a 2×2 LCP with a known solution: A = [2 1; 1 2], q = (-5, -6):
// both z > 0, A z = -q gives z = (4/3, 7/3).
TEST(Lcp, SolvesSmallProblem) {
  Eigen::MatrixXd A(2, 2);
  A << 2, 1, 1, 2;
  const LcpResult r = SolveLcp(A, Eigen::Vector2d(-5, -6));
  ASSERT_TRUE(r.solved);
  EXPECT_TRUE(test::Near(r.z[0], 4.0 / 3.0, 1e-14));
  EXPECT_TRUE(test::Near(r.z[1], 7.0 / 3.0, 1e-14));
  // q = (-1, 3): z = (1/2, 0), w = (0, 3.5).
  const LcpResult r2 = SolveLcp(A, Eigen::Vector2d(-1, 3));
  ASSERT_TRUE(r2.solved);
  EXPECT_TRUE(test::Near(r2.z[0], 0.5, 1e-14));
  EXPECT_EQ(r2.z[1], 0.0);
  EXPECT_TRUE(test::Near(r2.w[1], 3.5, 1e-14));
}

}  // namespace
}  // namespace chasles
