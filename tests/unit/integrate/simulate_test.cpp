// Runtime guards of Simulate, without a scene: a force element that turns non-finite, an
// acceleration that overflows, a body whose state is not finite at the start. Every
// integrator path (Dormand-Prince, RK4, energy-momentum, the hybrid contact path) stops with
// an InputError naming the element or body, the quantity and the time.

#include "chasles/integrate/simulate.h"

#include <cmath>
#include <limits>
#include <memory>
#include <regex>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/error.h"
#include "chasles/model/contact.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"

namespace chasles {
namespace {

using testing::HasSubstr;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

enum class Path { kDormandPrince, kRk4, kEnergyMomentum, kHybrid };

const char* PathName(Path p) {
  switch (p) {
    case Path::kDormandPrince:
      return "dormand_prince";
    case Path::kRk4:
      return "rk4";
    case Path::kEnergyMomentum:
      return "energy_momentum";
    case Path::kHybrid:
      return "hybrid";
  }
  return "";
}

// A ball of mass `mass` at rest; on the hybrid path it rests on the plane z = 0 (a sphere
// contact of radius 0.1 m, its centre at z = 0.1 m) under gravity, so the contact stage is
// active while the guard fires.
struct BallRun {
  Model model;
  State initial;
  SimulationOptions options;
};

constexpr double kStep = 0.01;  // fixed step [s]

BallRun Ball(Path path, double mass) {
  BallRun s;
  s.model.AddBody("ball", MassProperties(mass, Vec3::Zero(), RotationalInertia(mass, mass, mass)));
  if (path == Path::kHybrid) {
    s.model.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -9.81)));
    ContactSpec c;
    c.name = "floor";
    c.shape = ContactShape::kSphere;
    c.body = 0;
    c.radius = 0.1;
    c.mu_s = 0.5;
    c.mu_k = 0.4;
    s.model.AddContact(c);
  }
  s.options.t_end = 1.0;
  s.options.fixed_step = kStep;
  s.options.store_samples = false;
  s.options.integrator = path == Path::kRk4              ? IntegratorKind::kRk4
                         : path == Path::kEnergyMomentum ? IntegratorKind::kEnergyMomentum
                                                         : IntegratorKind::kDormandPrince5;
  return s;
}

State Initial(const Model& model, Path path) {
  State s = MakeRestState(model);
  if (path == Path::kHybrid) s.bodies[0].p_WBcm = Vec3(0, 0, 0.1);
  return s;
}

// The message of the InputError Simulate throws ("" if none).
std::string RunMessage(const BallRun& s) {
  try {
    Simulate(s.model, s.initial, s.options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// The time "at t = T s" in a message (NaN if absent).
double TimeIn(const std::string& message) {
  std::smatch m;
  static const std::regex kTime("at t = ([-+0-9.eE]+) s");
  if (!std::regex_search(message, m, kTime)) return kNaN;
  return std::stod(m[1].str());
}

// The latest time an evaluation inside a step that starts before t_on can have: the adaptive
// step is not fixed, so only the end of the run bounds it there.
double LatestEvaluation(Path path, double t_on, double t_end) {
  return path == Path::kRk4 || path == Path::kEnergyMomentum ? t_on + kStep : t_end;
}

class Guards : public testing::TestWithParam<Path> {};

// A force that is 1 N until t_on = 0.5 s, then NaN: the run stops at the first evaluation at
// or after t_on, naming the element, its force and the time.
TEST_P(Guards, ForceThatTurnsNaN) {
  const Path path = GetParam();
  BallRun s = Ball(path, 1.0);
  constexpr double t_on = 0.5;
  s.model.AddForceElement(std::make_shared<AppliedForce>(
      "push", 0, Vec3::Zero(),
      [](auto&&, const State& st) { return st.t < t_on ? Vec3(1, 0, 0) : Vec3(kNaN, 0, 0); },
      VectorFrame::kWorld));
  s.initial = Initial(s.model, path);
  const std::string what = RunMessage(s);
  EXPECT_THAT(what, HasSubstr("force element 'push' evaluated to NaN at t = "));
  EXPECT_THAT(what, HasSubstr("(force [nan, 0, 0] N"));
  const double t = TimeIn(what);
  EXPECT_GE(t, t_on) << what;
  EXPECT_LE(t, LatestEvaluation(path, t_on, s.options.t_end)) << what;
}

// A finite force so large on so light a body that F/m overflows: the acceleration is named.
// F = 1e308 N on m = 1e-3 kg from t_on = 0.25 s gives a = 1e311 m/s² = inf.
TEST_P(Guards, AccelerationThatOverflows) {
  const Path path = GetParam();
  if (path == Path::kEnergyMomentum) {
    GTEST_SKIP() << "the energy-momentum integrator never forms the acceleration: the kick "
                    "v += h F / (2 m) overflows the velocity instead (next test)";
  }
  BallRun s = Ball(path, 1e-3);
  constexpr double t_on = 0.25;
  s.model.AddForceElement(std::make_shared<AppliedForce>(
      "blast", 0, Vec3::Zero(),
      [](auto&&, const State& st) { return st.t < t_on ? Vec3(0, 0, 0) : Vec3(1e308, 0, 0); },
      VectorFrame::kWorld));
  s.initial = Initial(s.model, path);
  const std::string what = RunMessage(s);
  if (path == Path::kHybrid) {
    // On the contact path the overflow shows first in the contact stage, which solves for the
    // forces with the infinite free acceleration (its normal force and friction are 0 · inf):
    // the contact point is named.
    EXPECT_THAT(what, HasSubstr("contact point 'floor': its force evaluated to NaN at t = "));
  } else {
    EXPECT_THAT(what, HasSubstr("the acceleration of body 'ball' became non-finite at t = "));
  }
  const double t = TimeIn(what);
  EXPECT_GE(t, t_on) << what;
  EXPECT_LE(t, LatestEvaluation(path, t_on, s.options.t_end)) << what;
}

// The energy-momentum kick: v += h F / (2 m) = 0.005 s * 1e308 N / 2e-3 kg = 2.5e308 = inf.
TEST(Guards, EnergyMomentumVelocityThatOverflows) {
  BallRun s = Ball(Path::kEnergyMomentum, 1e-3);
  constexpr double t_on = 0.25;
  s.model.AddForceElement(std::make_shared<AppliedForce>(
      "blast", 0, Vec3::Zero(),
      [](auto&&, const State& st) { return st.t < t_on ? Vec3(0, 0, 0) : Vec3(1e308, 0, 0); },
      VectorFrame::kWorld));
  s.initial = Initial(s.model, Path::kEnergyMomentum);
  const std::string what = RunMessage(s);
  EXPECT_THAT(what,
              testing::AnyOf(HasSubstr("the velocity of body 'ball' became infinite at t = "),
                             HasSubstr("the position of body 'ball' became infinite at t = ")));
  const double t = TimeIn(what);
  EXPECT_GE(t, t_on) << what;
  EXPECT_LE(t, t_on + kStep) << what;
}

// A body whose state is not finite at the start: refused before the first step, with the
// body, the quantity and the start time.
TEST_P(Guards, StateThatStartsNaN) {
  const Path path = GetParam();
  BallRun s = Ball(path, 1.0);
  s.initial = Initial(s.model, path);
  s.initial.t = 0.125;
  s.initial.bodies[0].v_WBcm_W = Vec3(0, kNaN, 0);
  const std::string what = RunMessage(s);
  EXPECT_THAT(what, HasSubstr("body 'ball': velocity is not finite at t = 0.125 s"));
}

// A central gravity whose centre is the ball's own centre of mass: r = 0, F = -mu m r/|r|³ is
// 0/0 at once. Named at the first evaluation, t = 0.
TEST_P(Guards, SingularForceAtTheStart) {
  const Path path = GetParam();
  BallRun s = Ball(path, 1.0);
  s.initial = Initial(s.model, path);
  s.model.AddForceElement(std::make_shared<CentralGravity>("sun", 1.0, s.initial.bodies[0].p_WBcm));
  s.initial = Initial(s.model, path);
  const std::string what = RunMessage(s);
  EXPECT_THAT(what, HasSubstr("force element 'sun' evaluated to "));
  EXPECT_THAT(what, HasSubstr(" at t = 0 s"));
}

INSTANTIATE_TEST_SUITE_P(EveryIntegrator, Guards,
                         testing::Values(Path::kDormandPrince, Path::kRk4, Path::kEnergyMomentum,
                                         Path::kHybrid),
                         [](const testing::TestParamInfo<Path>& info) {
                           return std::string(PathName(info.param));
                         });

}  // namespace
}  // namespace chasles
