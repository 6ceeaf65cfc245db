// Redundant supports: which reaction components are statically indeterminate, the determinate
// model suggested, and reactions that do not depend on the unit of length.

#include "chasles/dynamics/redundancy.h"

#include <cmath>
#include <memory>
#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/analysis/instantaneous.h"
#include "chasles/math/rotation.h"
#include "chasles/model/constraints.h"
#include "chasles/model/forces.h"
#include "test_support.h"

namespace chasles {
namespace {

using ::testing::HasSubstr;

// A door (box 1 m wide along x, 40 mm thick, 2 m tall along z, 30 kg) on two revolute hinges
// on the line x = y = 0 at e = 0.2 m from its top and bottom edges, turning at 1 rad/s about
// that line, everything turned by R0 and every length measured in units of `unit` metres
// (unit = 1e-3: millimetres, so lengths are 1000 times larger, inertia 1e6, g 1000, forces in
// kg·mm/s² = 1e-3 N and moments in kg·mm²/s² = 1e-6 N·m).
struct Door {
  Model model;
  State state;
  Door(double unit, const Mat3& R0, JointKind top = JointKind::kRevolute,
       JointKind bottom = JointKind::kRevolute) {
    const double s = 1.0 / unit, m = 30.0, w = 1.0 * s, t = 0.04 * s, H = 2.0 * s, e = 0.2 * s;
    const RotationalInertia I(m * (t * t + H * H) / 12, m * (w * w + H * H) / 12,
                              m * (w * w + t * t) / 12);
    model.AddBody("door", MassProperties(m, Vec3(w / 2, 0, H / 2), I));
    model.AddForceElement(
        std::make_shared<UniformGravity>("gravity", R0 * Vec3(0, 0, -9.80665 * s)));
    state = MakeRestState(model);
    SetBodyPose(model, 0, Vec3::Zero(), Quat(R0), state);
    SetBodyVelocity(model, 0, Vec3::Zero(), R0 * Vec3(0, 0, 1.0), state);
    const Mat3 R_WJ = FrameWithZAxis(R0 * Vec3::UnitZ());
    for (const auto& [name, z, kind] :
         {std::tuple{"top", H - e, top}, std::tuple{"bottom", e, bottom}}) {
      const Vec3 p = R0 * Vec3(0, 0, z);
      model.AddConstraint(
          std::make_shared<Joint>(name, kind, kWorld, AttachmentFrame{p, R_WJ}, 0,
                                  AttachmentFrameAtWorldPose(model, state, 0, p, R_WJ)));
    }
  }
};

Mat3 RandomRotation(std::mt19937& rng) {
  std::normal_distribution<double> n;
  std::uniform_real_distribution<double> a(0.0, 3.0);
  return RotationFromAxisAngle(Vec3(n(rng), n(rng), n(rng)).normalized(), a(rng));
}

TEST(Redundancy, TwoHingesLeaveTheAxialSplitAndTheCouplesIndeterminate) {
  Door door(1.0, Mat3::Identity());
  Data data = MakeData(door.model);
  const Redundancy r = AnalyseRedundancy(door.model, door.state, data);
  EXPECT_EQ(r.rows, 10);
  EXPECT_EQ(r.rank, 5);
  // ℓ: RMS distance of the hinge points from their midpoint, half their spacing 1.6 m.
  EXPECT_NEAR(r.length, 0.8, 1e-15);
  // Null space of Jᵀ (10 - 5 = 5): the axial split (1), and per transverse direction a force
  // pair and the two moments with 2 equilibrium conditions (2 each).
  ASSERT_EQ(r.groups.size(), 3u);
  int dims = 0;
  for (const IndeterminateGroup& g : r.groups) dims += g.dimension;
  EXPECT_EQ(dims, 5);
  const std::vector<std::string> words = DescribeRedundancy(door.model, r);
  std::string all;
  for (const std::string& w : words) all += w + "\n";
  EXPECT_THAT(all, HasSubstr("'top' and 'bottom': only the sum of their z forces is determined"));
  EXPECT_THAT(all, HasSubstr("make 'top' a `spherical` joint and 'bottom' a `point_on_line` "
                             "joint along its z axis"));
}

TEST(Redundancy, NamesTheSameSupportsForAnyOrientationOfTheHingeLine) {
  std::mt19937 rng(20261123);
  for (int trial = 0; trial < 5; ++trial) {
    Door door(1.0, RandomRotation(rng));
    Data data = MakeData(door.model);
    const Redundancy r = AnalyseRedundancy(door.model, door.state, data);
    ASSERT_EQ(r.changes.size(), 2u) << trial;
    // Components in each joint's frame (z the hinge line): top keeps its three forces, bottom
    // its two transverse forces.
    EXPECT_EQ(r.changes[0].kept, (std::array<bool, 6>{true, true, true, false, false, false}));
    EXPECT_EQ(r.changes[1].kept, (std::array<bool, 6>{true, true, false, false, false, false}));
  }
}

TEST(Redundancy, TheDeterminateModelIsNotRedundant) {
  Door door(1.0, Mat3::Identity(), JointKind::kSpherical, JointKind::kPointOnLine);
  Data data = MakeData(door.model);
  const Redundancy r = AnalyseRedundancy(door.model, door.state, data);
  EXPECT_EQ(r.rows, 5);
  EXPECT_EQ(r.rank, 5);
  EXPECT_TRUE(r.groups.empty());
  EXPECT_TRUE(r.changes.empty());
  EXPECT_TRUE(DescribeRedundancy(door.model, r).empty());
}

// The weighted least-norm reactions are the same physical forces and moments whatever the
// unit of length the numbers are in: the weight ℓ scales with the unit, so Σ F² + Σ (M/ℓ)²
// changes by one common factor. (A plain Σλ² would weigh moments 10⁶ times less in mm and
// shift the split towards them.) Random orientations exercise every row.
TEST(Redundancy, ReactionsDoNotDependOnTheUnitOfLength) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 3; ++trial) {
    const Mat3 R0 = trial == 0 ? Mat3::Identity() : RandomRotation(rng);
    Door si(1.0, R0), mm(1e-3, R0);
    const InstantaneousSolution a = SolveInstantaneous(si.model, si.state);
    const InstantaneousSolution b = SolveInstantaneous(mm.model, mm.state);
    ASSERT_EQ(a.rank, 5);
    ASSERT_EQ(b.rank, 5);
    const double scale = 30.0 * 9.80665;  // the weight [N]
    for (size_t c = 0; c < 2; ++c) {
      EXPECT_TRUE(test::MatNear(a.reactions[c].F_Jc_W, 1e-3 * b.reactions[c].F_Jc_W, 1e-9, scale))
          << trial << " " << c;
      EXPECT_TRUE(test::MatNear(a.reactions[c].M_Jc_W, 1e-6 * b.reactions[c].M_Jc_W, 1e-9, scale))
          << trial << " " << c;
    }
  }
}

}  // namespace
}  // namespace chasles
