// The certificate's transition checks per island (src/analysis/internal/island_checks.h): a run
// split into islands checks each island at its own transitions, and a violation in one island
// is caught and named by its bodies, its time and its phase.

#include "analysis/internal/island_checks.h"

#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "chasles/integrate/simulate.h"
#include "chasles/model/force_element.h"
#include "chasles/model/forces.h"
#include "reference/balls_on_floor.h"

namespace chasles {
namespace {

constexpr double kG = 9.80665;
const reference::Ball kBall{0.17, 0.028575, 0.5, 0.2};
constexpr double kW0 = 100.0 * 2.0 * 3.14159265358979323846 / 60.0;  // 100 rpm [rad/s]

// A constant push along x on one ball that says it is conservative with a potential of zero
// (no non-conservative power, V = 0): the work it does is energy the ledger does not know of.
class UnbookedPush final : public ForceElement {
 public:
  UnbookedPush(BodyIndex body, double force) : ForceElement("push"), body_(body), f_(force) {}
  double AddForces(const Model&, const State&, const Data&, WrenchAccumulator& out) const override {
    out.AddForceAtCenterOfMass(body_, Vec3(f_, 0, 0));
    return 0.0;
  }
  bool has_potential() const override { return true; }
  std::vector<BodyIndex> bodies() const override { return {body_}; }
  std::shared_ptr<const ForceElement> Renumbered(
      const std::vector<BodyIndex>& new_index) const override {
    return std::make_shared<UnbookedPush>(new_index[static_cast<size_t>(body_)], f_);
  }

 private:
  BodyIndex body_;
  double f_;
};

// Three balls set down spinning at w0 (1 + i/3), each its own island.
SimulationResult RunThree(const Model& m, study_internal::IslandChecks& checks) {
  State s = MakeRestState(m);
  for (int i = 0; i < 3; ++i) {
    SetBodyPose(m, i, Vec3(0, i, kBall.radius), Quat::Identity(), s);
    SetBodyVelocity(m, i, Vec3::Zero(), Vec3(0, kW0 * (1 + i / 3.0), 0), s);
  }
  SimulationOptions o;
  o.t_end = 0.08;  // past every t* (the last 0.073 s)
  o.adaptive.rtol = 1e-12;
  o.adaptive.atol = 1e-14;
  o.threads = 2;
  o.on_transition = [](const State&, const State&) {
    ADD_FAILURE() << "the whole-model check was called on a run split into islands";
  };
  o.island_transition = checks.Hook();
  return Simulate(m, s, o);
}

// The slip stop of point p.
double SlipStop(const SimulationResult& r, int p) {
  for (const ContactEvent& e : r.contact_events) {
    if (e.point == p && e.reason == ContactEventReason::kSlipStopped) return e.t;
  }
  ADD_FAILURE() << "no slip stop at point " << p;
  return -1.0;
}

const CheckResult& Ledger(const Certificate& c) {
  for (const CheckResult& x : c.checks) {
    if (x.name == "ledger") return x;
  }
  throw std::logic_error("no ledger check");
}

TEST(IslandChecks, EachIslandIsCheckedBeforeAndAfterEachOfItsTransitions) {
  const Model m = reference::MakeBallsOnFloor(3, kBall, kG);
  study_internal::IslandChecks checks(CertificateTolerances{});
  const SimulationResult r = RunThree(m, checks);
  ASSERT_TRUE(r.islands.split) << r.islands.reason;
  EXPECT_EQ(r.run_path.path, RunPath::kIslands);
  CertificateBuilder builder;
  checks.AddTo(builder);
  const Certificate c = builder.Finish();
  for (const std::string& msg : c.FailureMessages()) ADD_FAILURE() << msg;
  // One slip stop per ball, each checked before and after.
  EXPECT_EQ(Ledger(c).count, 3 * 2);
}

// A push on ball 1 that the ledger does not book: its island's ledger fails, named by the
// ball, at its transition (the slip stop), and the other islands are not blamed.
TEST(IslandChecks, AnEnergyErrorInOneIslandIsCaughtAndNamed) {
  Model m = reference::MakeBallsOnFloor(3, kBall, kG);
  m.AddForceElement(std::make_shared<UnbookedPush>(1, 0.05));
  study_internal::IslandChecks checks(CertificateTolerances{});
  const SimulationResult r = RunThree(m, checks);
  ASSERT_TRUE(r.islands.split) << r.islands.reason;
  CertificateBuilder builder;
  checks.AddTo(builder);
  const Certificate c = builder.Finish();
  const CheckResult& ledger = Ledger(c);
  EXPECT_FALSE(ledger.passed());
  EXPECT_EQ(ledger.where, "island of body 'ball1'");
  EXPECT_EQ(ledger.t, SlipStop(r, 1));
  EXPECT_TRUE(ledger.phase == CheckPhase::kBeforeTransition ||
              ledger.phase == CheckPhase::kAfterTransition);
  // The forces are all there: the balances pass; only the ledger fails.
  for (const CheckResult& x : c.checks) {
    if (x.name == "ledger") continue;
    EXPECT_TRUE(x.passed()) << x.name << " at " << x.where;
  }
}

}  // namespace
}  // namespace chasles
