// End-to-end: driven and braked wheels as bodies on revolute joints of a car (the chapter's
// Problems 8.11-8.14 and 8.28-8.30, examples/*-wheels.yaml), a drive torque across the axle
// that ramps past the traction limit and back (examples/driven-wheel-ramp.yaml), and a torque
// across a joint held by a locked driver (statics). Closed forms are derived here.
//
// The car examples: car and wheels together have mass M and centre of mass G at height h,
// the rear contact lr behind G and the front one lf ahead (L = lr + lf); a wheel turns at a
// constant rate relative to the level car (100 rad/s: the tyre spins; 0: the brake locks
// it), so no wheel has an angular acceleration and the moment balance about G is the
// textbook's: l_r N_r - l_f N_f - h Σf = 0, N_r + N_f = M g (plus a box's weight), with
// f = mu N on a sliding tyre and mu = 0 on a free-rolling axle.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "cli_runner.h"
#include "test_support.h"

namespace chasles::test {
namespace {

// Accelerations and forces from the contact solve (exact up to round-off in a constant
// acceleration) and event times located to 1e-12 s: 1e-9 relative.
constexpr double kRel = 1e-9;
constexpr double kG = 9.80665;  // gravity: standard
constexpr double kLb = 0.45359237, kIn = 0.0254;

struct RunOut {
  nlohmann::json json;
  std::map<std::string, std::vector<double>> csv;
};

RunOut Simulate(const std::string& example, const std::string& extra = "") {
  RunOut r;
  r.json = SimulateJson(SourcePath(example), OutDir("drives"), "--strict " + extra);
  r.csv = ReadCsv(r.json.at("csv").get<std::string>());
  return r;
}

// The value of a CSV column at the sample nearest to t.
double At(const RunOut& r, const std::string& column, double t) {
  const std::vector<double>& ts = r.csv.at("t");
  size_t best = 0;
  for (size_t i = 0; i < ts.size(); ++i) {
    if (std::abs(ts[i] - t) < std::abs(ts[best] - t)) best = i;
  }
  return r.csv.at(column).at(best);
}

// Time of the first change of `point` from `from` to `to`.
double ModeChange(const RunOut& r, const std::string& point, const std::string& from,
                  const std::string& to) {
  for (const auto& e : r.json.at("contact_events")) {
    if (e.at("point") == point && e.at("from") == from && e.at("to") == to) {
      return e.at("t").get<double>();
    }
  }
  throw std::runtime_error("no change of " + point + " from " + from + " to " + to);
}

std::string Mode(const RunOut& r, const std::string& point) {
  for (const auto& e : r.json.at("contact_events")) {
    if (e.at("point") == point && e.at("reason") == "initial") return e.at("to");
  }
  throw std::runtime_error("no initial mode of " + point);
}

// Problems 8.11/8.12, rear-wheel drive: moments about G with N_f = M g - N_r give
// N_r = M (g lf + a h) / L, and M a = mu N_r: a = mu g lf / (L - mu h).
TEST(Drives, RearWheelDriveAtTheTractionLimit) {
  const double M = 1805, h = 1, lf = 1.20, lr = 1.67, mu = 0.8, L = lf + lr;
  const RunOut r = Simulate("examples/problem-8.12-rear-wheel-drive-wheels.yaml");
  EXPECT_EQ(Mode(r, "rear"), "sliding");
  const double a = mu * kG * lf / (L - mu * h);
  EXPECT_NEAR(a, 4.548, 5e-4);  // the textbook's answer to 8.12
  for (double t : {0.1, 0.3, 0.5}) {
    EXPECT_NEAR(At(r, "car_ax", t), a, kRel * a) << t;
    EXPECT_NEAR(At(r, "rear_N", t), M * (kG * lf + a * h) / L, kRel * M * kG) << t;
    EXPECT_NEAR(At(r, "rear_wheel_ax", t), a, kRel * a) << t;
  }
}

// Problem 8.28: four-wheel drive, both tyres spin: M a = mu (N_r + N_f) = mu M g. Front-wheel
// drive (rear mu = 0): N_f = M (g lr - a h) / L, M a = mu N_f: a = mu g lr / (L + mu h), with
// lr = 3h, lf = 2h, mu = 4/5: a = (12/29) g.
TEST(Drives, FourAndFrontWheelDriveAtTheTractionLimit) {
  const double mu = 0.8, h = 0.6, lr = 3 * h, lf = 2 * h, L = lr + lf;
  const RunOut four = Simulate("examples/problem-8.28-traction-wheels.yaml");
  EXPECT_NEAR(At(four, "car_ax", 0.25), mu * kG, kRel * kG);
  const RunOut front = Simulate("examples/problem-8.28-traction-wheels.yaml",
                                "--set mu_rear=0 --set 'w_rear=0 rad/s'");
  const double a = mu * kG * lr / (L + mu * h);
  EXPECT_NEAR(a, 12.0 / 29.0 * kG, 1e-15 * kG);
  EXPECT_NEAR(At(front, "car_ax", 0.25), a, kRel * a);
}

// Problem 8.14, all wheels locked: a = -mu g; moments about G: N_r = M g (lf - mu h) / L,
// N_f = M g (lr + mu h) / L; each brake holds its wheel with mu N r (the wheel does not turn:
// 0 = brake torque + friction's moment r f). The car stops at v0 / (mu g) and the tyres stick.
TEST(Drives, BrakingWithLockedWheels) {
  const double M = 1805, h = 1, lf = 1.20, lr = 1.47, mu = 0.8, L = lf + lr, v0 = 20, r = 0.3;
  const RunOut run = Simulate("examples/problem-8.14-braking-wheels.yaml");
  const double Nr = M * kG * (lf - mu * h) / L, Nf = M * kG * (lr + mu * h) / L;
  for (double t : {0.5, 2.0}) {
    EXPECT_NEAR(At(run, "car_ax", t), -mu * kG, kRel * kG) << t;
    EXPECT_NEAR(At(run, "rear_N", t), Nr, kRel * M * kG) << t;
    EXPECT_NEAR(At(run, "front_N", t), Nf, kRel * M * kG) << t;
    EXPECT_NEAR(std::abs(At(run, "rear_drive_My", t)), mu * Nr * r, kRel * M * kG * r) << t;
    EXPECT_NEAR(std::abs(At(run, "front_drive_My", t)), mu * Nf * r, kRel * M * kG * r) << t;
  }
  const double t_stop = v0 / (mu * kG);
  EXPECT_NEAR(ModeChange(run, "rear", "sliding", "sticking"), t_stop, kRel * t_stop);
  EXPECT_NEAR(ModeChange(run, "front", "sliding", "sticking"), t_stop, kRel * t_stop);
}

// Problem 8.13: a box of mass m with its centre 2h above the road over G. Moments about the
// front contact with a = -mu g: N_r L = M g lf + m g lf - mu g h (M + 2m) (the box's
// inertial force acts 2h up); N_r = 0 at m = M (lf - mu h) / (2 mu h - lf), the example's k = 1.
TEST(Drives, BrakingWithABoxOnTheRoofUnloadsTheRearWheels) {
  const double M = 4043 * kLb, h = 39 * kIn, lf = 47 * kIn, mu = 0.8;
  const double m = M * (lf - mu * h) / (2 * mu * h - lf);
  EXPECT_NEAR(m / kLb, 4148, 0.5);  // the textbook's 4148 lb
  const RunOut run = Simulate("examples/problem-8.13-braking-box-on-roof-wheels.yaml");
  EXPECT_NEAR(At(run, "rear_N", 0.5), 0.0, kRel * (M + m) * kG);
  EXPECT_NEAR(At(run, "front_N", 0.5), (M + m) * kG, kRel * (M + m) * kG);
  EXPECT_NEAR(At(run, "car_ax", 0.5), -mu * kG, kRel * kG);
}

// Problems 8.29 and 8.30: a box m just above the rear contact at G's height.
// 8.29 (front drive): moments about the rear contact: N_f L = M g lr - (M + m) h a and
// (M + m) a = mu N_f: a = mu g lr M / ((M + m)(L + mu h)).
// 8.30 (rear drive): moments about the front contact: N_r L = M g lf + m g L + (M + m) h a
// and (M + m) a = mu N_r: a = mu g ((M + m) L - M lr) / ((M + m)(L - mu h)).
TEST(Drives, DrivenWheelsWithABoxOverTheRearAxle) {
  const double m = 500 * kLb, h = 22 * kIn, lr = 3 * h, lf = 2 * h, L = lr + lf;
  {
    const double M = 3600 * kLb, mu = 0.8;
    const double a = mu * kG * lr * M / ((M + m) * (L + mu * h));
    const RunOut run = Simulate("examples/problem-8.29-front-wheel-drive-box-wheels.yaml");
    EXPECT_NEAR(At(run, "car_ax", 0.25), a, kRel * a);
    EXPECT_NEAR(At(run, "front_N", 0.25), (M + m) * a / mu, kRel * (M + m) * kG);
  }
  {
    const double M = 3300 * kLb, mu = 0.7;
    const double a = mu * kG * ((M + m) * L - M * lr) / ((M + m) * (L - mu * h));
    const RunOut run = Simulate("examples/problem-8.30-rear-wheel-drive-box-wheels.yaml");
    EXPECT_NEAR(At(run, "car_ax", 0.25), a, kRel * a);
    EXPECT_NEAR(At(run, "rear_N", 0.25), (M + m) * a / mu, kRel * (M + m) * kG);
  }
}

// examples/driven-wheel-ramp.yaml (its header has the derivation): tau = k (t1 - |t - t1|)
// across the rear axle; rolling, then spinning from t_slip = tau*/k, gripping again at
// t_grip = 2 t1 - t_slip + sqrt(2) (t1 - t_slip).
TEST(Drives, RampedDriveTorqueLosesAndRegainsTraction) {
  const double M = 20, m_w = 2, r = 0.3, h_c = 0.5, l_r0 = 1, l_f0 = 1.2, mu = 0.8, k = 25,
               t1 = 1.9, g = 9.81;
  const double I_w = 0.5 * m_w * r * r, M_t = M + m_w;
  // The system's centre of mass G (car's at x = 0, height h_c; wheel's at -l_r0, height r).
  const double x_G = -m_w * l_r0 / M_t, h = (M * h_c + m_w * r) / M_t;
  const double l_r = l_r0 + x_G, l_f = l_f0 - x_G, L = l_r + l_f;
  // Rolling: a = tau r / (I_w + M_t r²), f = M_t a, and l_r N_r - l_f (M_t g - N_r) - h f =
  // I_w a / r (the wheel's spin is the only angular momentum about G).
  auto rolling_a = [&](double tau) { return tau * r / (I_w + M_t * r * r); };
  auto rolling_N = [&](double tau) {
    const double a = rolling_a(tau);
    return (l_f * M_t * g + h * M_t * a + I_w * a / r) / L;
  };
  // The limit f = mu N_r: a* = mu l_f M_t g / (M_t L - mu (h M_t + I_w / r)).
  const double a_star = mu * l_f * M_t * g / (M_t * L - mu * (h * M_t + I_w / r));
  const double tau_star = a_star * (I_w + M_t * r * r) / r;
  EXPECT_NEAR(M_t * rolling_a(tau_star), mu * rolling_N(tau_star), 1e-12 * M_t * g);
  // tau* = mu N_r r + I_w alpha, alpha = a*/r: the wheel's own inertia raises the limit.
  EXPECT_NEAR(tau_star, mu * rolling_N(tau_star) * r + I_w * a_star / r, 1e-12 * tau_star);
  // Spinning: I_w alpha = tau - mu N_r r and l_r N_r - l_f N_f - h mu N_r = I_w alpha give
  // N_r = (l_f M_t g + tau) / (L - mu h + mu r); slip s = r w - v with
  // s' = r alpha - a = r (tau - mu N_r r) / I_w - mu N_r / M_t, zero at tau* (the two regimes
  // meet there) and linear in tau, so s' = c1 (tau - tau*).
  auto sliding_N = [&](double tau) { return (l_f * M_t * g + tau) / (L - mu * h + mu * r); };
  auto slip_rate = [&](double tau) {
    return r * (tau - mu * sliding_N(tau) * r) / I_w - mu * sliding_N(tau) / M_t;
  };
  EXPECT_NEAR(slip_rate(tau_star), 0.0, 1e-12 * g);
  EXPECT_GT(slip_rate(tau_star + 1), 0.0);
  const double t_slip = tau_star / k;
  const double t_grip = 2 * t1 - t_slip + std::sqrt(2.0) * (t1 - t_slip);
  ASSERT_LT(t_slip, t1);
  ASSERT_LT(t_grip, 2 * t1);  // the torque is still >= 0 when the tyre grips again

  const RunOut run = Simulate("examples/driven-wheel-ramp.yaml");
  EXPECT_EQ(Mode(run, "tyre"), "sticking");
  EXPECT_NEAR(ModeChange(run, "tyre", "sticking", "sliding"), t_slip, kRel * t_slip);
  EXPECT_NEAR(ModeChange(run, "tyre", "sliding", "sticking"), t_grip, kRel * t_grip);
  auto tau = [&](double t) { return k * (t1 - std::abs(t - t1)); };
  // Rolling before the slip, spinning between, rolling after.
  for (double t : {0.2, 1.0, 3.0, 3.6}) {
    EXPECT_NEAR(At(run, "car_ax", t), rolling_a(tau(t)), kRel * a_star) << t;
    EXPECT_NEAR(At(run, "tyre_N", t), rolling_N(tau(t)), kRel * M_t * g) << t;
  }
  for (double t : {1.8, 2.2, 2.6}) {
    EXPECT_NEAR(At(run, "car_ax", t), mu * sliding_N(tau(t)) / M_t, kRel * a_star) << t;
    EXPECT_NEAR(At(run, "tyre_N", t), sliding_N(tau(t)), kRel * M_t * g) << t;
  }
  // The transitions are the only ones.
  int changes = 0;
  for (const auto& e : run.json.at("contact_events")) changes += e.at("reason") != "initial";
  EXPECT_EQ(changes, 2);
}

// examples/drive-layouts-ramp.yaml (its header has the equations): a car on two wheel bodies,
// the drive torque tau = k t split s_r : s_f between the axles. While both wheels roll,
// a = tau r / (M_t r² + 2 I_w); wheel i's road force f_i = (s_i tau - I_w a / r) / r (the
// undriven wheel's is the small backward force that spins it up); N_r from the moments about
// G, l_r N_r - l_f N_f - h (f_r + f_f) = 2 I_w a / r with N_f = M_t g - N_r. All are linear in
// tau, so each wheel's limit |f_i| = mu N_i is reached at its own tau*_i; the smaller one is
// the wheel that spins, at t = tau*/k. Rear, front and four-wheel (even split) drive.
struct Layout {
  double s_r, s_f;
  const char* spins;  // the contact expected to reach its limit first
};

class DriveLayouts : public ::testing::TestWithParam<Layout> {};

TEST_P(DriveLayouts, ReachTheTractionLimitAtTheClosedFormTorque) {
  const Layout lay = GetParam();
  const double M = 900, m_w = 20, r = 0.3, h_c = 0.55, l_r0 = 1.4, l_f0 = 1.1, mu = 0.7, k = 400,
               g = 9.81;
  const double I_w = 0.5 * m_w * r * r, M_t = M + 2 * m_w;
  // G: the car's centre at x = 0, height h_c; the wheels' at -l_r0 and l_f0, height r.
  const double x_G = m_w * (l_f0 - l_r0) / M_t, h = (M * h_c + 2 * m_w * r) / M_t;
  const double l_r = l_r0 + x_G, l_f = l_f0 - x_G, L = l_r + l_f;
  auto acc = [&](double tau) { return tau * r / (M_t * r * r + 2 * I_w); };
  auto f = [&](double share, double tau) { return (share * tau - I_w * acc(tau) / r) / r; };
  auto N_r = [&](double tau) {
    const double a = acc(tau);
    return (l_f * M_t * g + h * M_t * a + 2 * I_w * a / r) / L;
  };
  auto N_f = [&](double tau) { return M_t * g - N_r(tau); };
  // The limit of a wheel, |f(tau)| = mu N(tau), both linear in tau: the root of
  // |f| - mu N = c0 + c1 tau with c1 > 0 (infinity when the margin never closes).
  auto limit = [&](auto margin) {
    const double c0 = margin(0.0), c1 = margin(1.0) - c0;
    return c1 > 0 ? -c0 / c1 : std::numeric_limits<double>::infinity();
  };
  const double tau_r = limit([&](double t) { return std::abs(f(lay.s_r, t)) - mu * N_r(t); });
  const double tau_f = limit([&](double t) { return std::abs(f(lay.s_f, t)) - mu * N_f(t); });
  const bool rear_first = tau_r < tau_f;
  ASSERT_EQ(std::string(rear_first ? "rear_tyre" : "front_tyre"), lay.spins);
  const double tau_star = std::min(tau_r, tau_f);
  const double t_star = tau_star / k;

  const RunOut run =
      Simulate("examples/drive-layouts-ramp.yaml",
               "--set s_r=" + std::to_string(lay.s_r) + " --set s_f=" + std::to_string(lay.s_f));
  EXPECT_EQ(Mode(run, "rear_tyre"), "sticking");
  EXPECT_EQ(Mode(run, "front_tyre"), "sticking");
  EXPECT_NEAR(ModeChange(run, lay.spins, "sticking", "sliding"), t_star, kRel * t_star);
  ASSERT_TRUE(run.json.at("stopped_by_event").get<bool>());
  ASSERT_EQ(run.json.at("events").size(), 1u);
  EXPECT_NEAR(run.json.at("events")[0].at("t").get<double>(), t_star, kRel * t_star);
  // Rolling up to the limit: the acceleration, both normal forces and both road forces.
  for (size_t i = 0; i < run.csv.at("t").size(); ++i) {
    const double t = run.csv.at("t")[i];
    if (t >= t_star) break;
    const double tau = k * t;
    EXPECT_NEAR(run.csv.at("car_ax")[i], acc(tau), kRel * g) << t;
    EXPECT_NEAR(run.csv.at("rear_tyre_N")[i], N_r(tau), kRel * M_t * g) << t;
    EXPECT_NEAR(run.csv.at("front_tyre_N")[i], N_f(tau), kRel * M_t * g) << t;
    EXPECT_NEAR(run.csv.at("rear_tyre_f")[i], std::abs(f(lay.s_r, tau)), kRel * M_t * g) << t;
    EXPECT_NEAR(run.csv.at("front_tyre_f")[i], std::abs(f(lay.s_f, tau)), kRel * M_t * g) << t;
  }
}

INSTANTIATE_TEST_SUITE_P(Drives, DriveLayouts,
                         ::testing::Values(Layout{1.0, 0.0, "rear_tyre"},
                                           Layout{0.0, 1.0, "front_tyre"},
                                           Layout{0.5, 0.5, "front_tyre"}),
                         [](const ::testing::TestParamInfo<Layout>& info) {
                           return info.param.s_f == 0.0   ? std::string("RearWheelDrive")
                                  : info.param.s_r == 0.0 ? std::string("FrontWheelDrive")
                                                          : std::string("FourWheelDrive");
                         });

// Statics of a torque across a joint: a disk on a fixed axle, a joint_torque tau and a brake
// that locks the disk (a rotation driver at rate 0). Moments about the axle: the brake's
// moment is -tau; the axle carries the weight: (0, 0, m g).
TEST(Drives, LockedBrakeHoldsAJointTorque) {
  const double m = 3, tau = 12;
  const std::filesystem::path dir = OutDir("drives");
  const std::filesystem::path file = dir / "brake-statics.yaml";
  std::ofstream(file) << R"(
bodies:
  - name: disk
    parts: [{shape: cylinder, radius: 0.2 m, length: 2 cm, mass: 3 kg, axis: [0, 1, 0]}]
gravity: 9.81 m/s^2
joints:
  - {name: axle, type: revolute, parent: world, child: disk, at: [0, 0, 0], axis: [0, 1, 0]}
drivers:
  - {name: brake, type: rotation, parent: world, child: disk, at: [0, 0, 0], axis: [0, 1, 0],
     value: {velocity: 0 rad/s}}
forces:
  - {type: joint_torque, name: motor, joint: axle, value: 12 N*m}
)";
  const CliResult r = RunCli("solve " + Quote(file.string()) + " --format json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const auto& x : j.at("reactions")) {
    if (x.at("name") == "brake") {
      EXPECT_NEAR(ToVec(x.at("moment")).y(), -tau, kRel * tau);
    } else {
      EXPECT_NEAR(ToVec(x.at("force")).z(), m * 9.81, kRel * m * 9.81);
      EXPECT_NEAR(ToVec(x.at("moment")).norm(), 0.0, kRel * tau);
    }
  }
  EXPECT_NEAR(ToVec(j.at("bodies").at(0).at("angular_acceleration")).norm(), 0.0, kRel);
}

// A joint torque in a planar scene acts about z: a rod (m, I_cm, centre of mass d from the
// pin) driven by tau from rest without gravity: alpha = tau / (I_cm + m d²) (parallel axes),
// the pin supplies the centre's tangential acceleration m alpha d along y.
TEST(Drives, JointTorqueInAPlanarScene) {
  const double m = 2, I_cm = 1.0 / 6.0, d = 0.5, tau = 3;
  const std::filesystem::path file = OutDir("drives") / "planar-motor.yaml";
  std::ofstream(file) << R"(
planar: true
bodies:
  - name: rod
    parts:
      - {shape: planar, mass: 2 kg, inertia_z: 1/6 kg*m^2, center_of_mass: [0.5 m, 0]}
joints:
  - {name: pin, type: revolute, parent: world, child: rod, at: [0, 0]}
forces:
  - {type: joint_torque, name: motor, joint: pin, value: 3 N*m}
)";
  const CliResult r = RunCli("solve " + Quote(file.string()) + " --format json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const double alpha = tau / (I_cm + m * d * d);
  EXPECT_NEAR(j.at("bodies").at(0).at("planar").at("alpha").get<double>(), alpha, kRel * alpha);
  EXPECT_NEAR(j.at("reactions").at(0).at("planar").at("Fy").get<double>(), m * alpha * d,
              kRel * m * alpha);
}

}  // namespace
}  // namespace chasles::test
