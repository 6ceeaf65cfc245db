// ChooseRunPath (chasles/integrate/run_path.h): each path chosen for a model built for it, the
// reason it gives, the refusals it makes, and Simulate running the path it names.

#include "chasles/integrate/run_path.h"

#include <memory>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/error.h"
#include "chasles/integrate/simulate.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"
#include "reference/balls_on_floor.h"

namespace chasles {
namespace {

using testing::HasSubstr;

constexpr double kG = 9.81;
constexpr reference::Ball kBall{0.2, 0.03, 0.5, 0.3};

// One free body (principal moments 1, 2, 3 kg·m²), with gravity or with a spring-like applied
// force that is not uniform gravity.
Model FreeBody(bool only_gravity) {
  Model m;
  m.AddBody("box", MassProperties(1.0, Vec3::Zero(), RotationalInertia(1, 2, 3)));
  m.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -kG)));
  if (!only_gravity) m.AddForceElement(std::make_shared<CentralGravity>("sun", 1.0, Vec3(5, 0, 0)));
  return m;
}

SimulationOptions Options(IntegratorKind kind) {
  SimulationOptions o;
  o.integrator = kind;
  o.t_end = 0.1;
  o.output_interval = 0.05;
  o.fixed_step = 1e-3;
  return o;
}

TEST(RunPath, NoContactsRunSmoothUnlessTheBatchCanStepThem) {
  const Model free = FreeBody(true), pulled = FreeBody(false);
  const RunPathChoice adaptive = ChooseRunPath(free, Options(IntegratorKind::kDormandPrince5));
  EXPECT_EQ(adaptive.path, RunPath::kSmooth);
  EXPECT_THAT(adaptive.reason, HasSubstr("no contacts or strings"));
  const RunPathChoice batch = ChooseRunPath(free, Options(IntegratorKind::kRk4));
  EXPECT_EQ(batch.path, RunPath::kFreeBodyBatch);
  EXPECT_THAT(batch.reason, HasSubstr("free bodies under uniform gravity alone"));
  EXPECT_EQ(ChooseRunPath(free, Options(IntegratorKind::kSplitting)).path, RunPath::kFreeBodyBatch);
  EXPECT_EQ(ChooseRunPath(free, Options(IntegratorKind::kEnergyMomentum)).path, RunPath::kSmooth);
  const RunPathChoice rk4 = ChooseRunPath(pulled, Options(IntegratorKind::kRk4));
  EXPECT_EQ(rk4.path, RunPath::kSmooth);
  EXPECT_THAT(rk4.reason, HasSubstr("force element 'sun' is not uniform gravity"));
  EXPECT_THROW(ChooseRunPath(pulled, Options(IntegratorKind::kSplitting)), InputError);
}

TEST(RunPath, ContactsRunHybridAsIslandsWhereTheyCan) {
  const Model one = reference::MakeBallsOnFloor(1, kBall, kG);
  const Model three = reference::MakeBallsOnFloor(3, kBall, kG);
  SimulationOptions o = Options(IntegratorKind::kDormandPrince5);
  const RunPathChoice single = ChooseRunPath(one, o);
  EXPECT_EQ(single.path, RunPath::kHybrid);
  EXPECT_EQ(single.islands, 1);
  EXPECT_EQ(single.one_system, "the bodies form one island");
  const RunPathChoice split = ChooseRunPath(three, o);
  EXPECT_EQ(split.path, RunPath::kIslands);
  EXPECT_EQ(split.islands, 3);
  EXPECT_THAT(split.reason, HasSubstr("3 islands"));
  o.islands = false;
  EXPECT_EQ(ChooseRunPath(three, o).one_system, "islands turned off");
  o.islands = true;
  o.on_transition = [](const State&, const State&) {};
  const RunPathChoice watched = ChooseRunPath(three, o);
  EXPECT_EQ(watched.path, RunPath::kHybrid);
  EXPECT_THAT(watched.one_system, HasSubstr("on_transition"));
  EXPECT_THROW(ChooseRunPath(three, Options(IntegratorKind::kRk4)), InputError);
}

TEST(RunPath, NamedEnginesAreCheckedAgainstTheModel) {
  const Model balls = reference::MakeBallsOnFloor(2, kBall, kG);
  const SimulationOptions o = Options(IntegratorKind::kDormandPrince5);
  EXPECT_EQ(ChooseRunPath(balls, o, EngineRequest::kEvents).path, RunPath::kSphereEvents);
  EXPECT_EQ(ChooseRunPath(balls, o, EngineRequest::kStepping).path, RunPath::kTimeStepping);
  const RunPathChoice automatic = ChooseRunPath(balls, o, EngineRequest::kAuto);
  EXPECT_EQ(automatic.path, RunPath::kAuto);
  EXPECT_THAT(automatic.reason, HasSubstr("time stepping while they come faster"));
  Model tilted = reference::MakeBallsOnFloor(1, kBall, kG);
  tilted.AddForceElement(std::make_shared<UniformGravity>("wind", Vec3(0.1, 0, 0)));
  try {
    ChooseRunPath(tilted, o, EngineRequest::kEvents);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("'integrator: events' runs balls on a table only: "));
    EXPECT_THAT(e.what(), HasSubstr("tilted"));
  }
  SimulationOptions with_event = o;
  with_event.events.push_back({"high", [](const Model&, const State& s) { return s.t - 1.0; }});
  EXPECT_THAT(ChooseRunPath(balls, with_event, EngineRequest::kAuto).reason,
              HasSubstr("the hybrid run throughout: the run's events"));
}

TEST(RunPath, SimulateRunsAndReportsThePathItChose) {
  const Model free = FreeBody(true);
  const State s = MakeRestState(free);
  for (const IntegratorKind kind : {IntegratorKind::kDormandPrince5, IntegratorKind::kRk4}) {
    const SimulationResult r = Simulate(free, s, Options(kind));
    const RunPathChoice c = ChooseRunPath(free, Options(kind));
    EXPECT_EQ(r.run_path.path, c.path);
    EXPECT_EQ(r.run_path.reason, c.reason);
    EXPECT_EQ(r.stats.free_body_batch, c.path == RunPath::kFreeBodyBatch);
  }
  const Model three = reference::MakeBallsOnFloor(3, kBall, kG);
  State balls = MakeRestState(three);
  for (int b = 0; b < 3; ++b) {
    SetBodyPose(three, b, Vec3(0, b, kBall.radius), Quat::Identity(), balls);
  }
  const SimulationResult r = Simulate(three, balls, Options(IntegratorKind::kDormandPrince5));
  EXPECT_EQ(r.run_path.path, RunPath::kIslands);
  EXPECT_TRUE(r.islands.split);
  EXPECT_EQ(r.islands.count, 3);
}

TEST(RunPath, NamesEveryPath) {
  EXPECT_STREQ(RunPathName(RunPath::kSmooth), "smooth");
  EXPECT_STREQ(RunPathName(RunPath::kFreeBodyBatch), "free-body batch");
  EXPECT_STREQ(RunPathName(RunPath::kHybrid), "hybrid");
  EXPECT_STREQ(RunPathName(RunPath::kIslands), "islands");
  EXPECT_STREQ(RunPathName(RunPath::kSphereEvents), "event-driven spheres");
  EXPECT_STREQ(RunPathName(RunPath::kTimeStepping), "time stepping");
  EXPECT_STREQ(RunPathName(RunPath::kAuto), "auto");
}

}  // namespace
}  // namespace chasles
