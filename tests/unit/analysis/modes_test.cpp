// Small motions about operating points (analysis/operating_point.h, linearize.h, modes.h):
// natural frequencies and growth rates against closed forms derived here.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "chasles/analysis/initial_state.h"
#include "chasles/analysis/modes.h"
#include "chasles/error.h"
#include "chasles/scene/scene.h"
#include "chasles/scene/study.h"
#include "test_paths.h"

namespace chasles {
namespace {

/// The scene's study with its initial state settled on the constraints (SettleInitialState),
/// as a run or a solve starts from it.
Study Settled(Study s) {
  std::vector<std::string> warnings;
  s.initial = SettleInitialState(*s.model, s.initial, s.settling, warnings);
  return s;
}

constexpr double kTol = 1e-10;  // relative, on frequencies and growth rates
constexpr double kG = 9.80665;

Study Build(const std::string& text) {
  return Settled(BuildStudy(LoadSceneText(text, "modes.yaml"), 1.0));
}

/// The non-rigid modes' |Im λ| (rad/s), ascending.
std::vector<double> Frequencies(const ModalAnalysis& a) {
  std::vector<double> w;
  for (const Mode& m : a.modes) {
    if (!m.rigid) w.push_back(std::abs(m.eigenvalue.imag()));
  }
  std::sort(w.begin(), w.end());
  return w;
}

/// The modes, for failure messages.
std::string Describe(const ModalAnalysis& a) {
  std::string out;
  for (const Mode& m : a.modes) {
    out += fmt::format("  {:.12g} {:+.12g}i {}{}\n", m.eigenvalue.real(), m.eigenvalue.imag(),
                       m.rigid ? "rigid " : "", m.rigid_coordinate);
  }
  return out;
}

int CountRigid(const ModalAnalysis& a) {
  return static_cast<int>(
      std::count_if(a.modes.begin(), a.modes.end(), [](const Mode& m) { return m.rigid; }));
}

// A compound pendulum: a bar a × b × L pinned at one end about y. About the pin
// I_O = m (a² + L²)/12 + m (L/2)² (parallel axes), and I_O θ̈ = -m g (L/2) θ, so
// ω² = m g (L/2) / I_O.
TEST(Modes, CompoundPendulumFromDisplacedGuess) {
  const double m = 2.0, a = 0.04, b = 0.03, L = 0.8;
  const std::string scene = fmt::format(R"(
chasles: 1
bodies:
  - name: bar
    parts: [{{shape: box, size: [{a}, {b}, {L}], mass: {m}, position: [0, 0, {h}]}}]
    initial: {{rotation: {{axis: [0, 1, 0], angle: 25 deg}}}}
gravity: standard
joints:
  - {{name: pin, type: revolute, parent: world, child: bar, at: [0, 0, 0], axis: [0, 1, 0]}}
)",
                                        fmt::arg("a", a), fmt::arg("b", b), fmt::arg("L", L),
                                        fmt::arg("m", m), fmt::arg("h", -L / 2));
  const Study s = Build(scene);
  const OperatingPoint op = FindEquilibrium(*s.model, s.initial);
  EXPECT_GT(op.iterations, 0);
  EXPECT_LT(op.residual, 1e-12);
  EXPECT_NEAR(op.state.bodies[0].p_WBcm.z(), -L / 2, 1e-12);
  LinearizeOptions opts;
  opts.finite_difference_check = true;
  const ModalAnalysis modes = AnalyseModes(*s.model, op, opts);
  const double I_O = m * (a * a + L * L) / 12.0 + m * L * L / 4.0;
  const double w = std::sqrt(m * kG * L / 2.0 / I_O);
  ASSERT_EQ(modes.linearization.coordinates.size(), 1u);
  EXPECT_EQ(modes.linearization.coordinates[0].name, "pin");
  ASSERT_EQ(Frequencies(modes).size(), 1u);
  EXPECT_NEAR(Frequencies(modes)[0], w, kTol * w);
  EXPECT_TRUE(modes.stable);
  EXPECT_LT(modes.linearization.consistency, 1e-12);
  EXPECT_LT(modes.linearization.finite_difference_check, 1e-6);
}

// The same search from any starting angle, in a planar scene (a ball of radius r on a light arm
// L, I_O = (2/5) m r² + m L², ω² = m g L / I_O, eq. 8.39): Newton ends at the hanging
// equilibrium (stable, frequency ω) or the inverted one (growth rate ω), never in an error —
// also at 90°, where the restoring stiffness m g L cos θ is 0 and the first Newton step is
// unbounded (the search's trust region), and from angles whose reduced state once came out as
// two coordinates and no speed (a readout seeing 1e-10 of the reduced space, counted as a
// coordinate). Seeded angles in (-175°, 175°), and 29°, 30°, 90° by name.
TEST(Modes, PlanarPendulumEquilibriumFromAnyAngle) {
  const double m = 1.5, L = 1.0, r = 0.05;
  const double w = std::sqrt(m * kG * L / (0.4 * m * r * r + m * L * L));
  std::vector<double> angles = {29.0, 30.0, 90.0, -90.0};
  std::uint64_t x = 0x9e3779b97f4a7c15ULL;  // splitmix64, seeded
  for (int i = 0; i < 24; ++i) {
    x += 0x9e3779b97f4a7c15ULL;
    std::uint64_t z = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    angles.push_back(-175.0 + 350.0 * static_cast<double>(z >> 11) * 0x1.0p-53);
  }
  for (const double deg : angles) {
    SCOPED_TRACE(fmt::format("theta0 = {} deg", deg));
    const double th = deg * std::numbers::pi / 180.0;
    const Study s =
        Build(fmt::format(R"(
chasles: 3
planar: true
bodies:
  - name: ball
    parts: [{{shape: sphere, radius: {r}, mass: {m}, position: [{x}, {y}]}}]
gravity: standard
joints:
  - {{name: pin, type: revolute, parent: world, child: ball, at: [0, 0]}}
)",
                          fmt::arg("r", r), fmt::arg("m", m), fmt::arg("x", L * std::sin(th)),
                          fmt::arg("y", -L * std::cos(th))));
    const OperatingPoint op = FindEquilibrium(*s.model, s.initial);
    EXPECT_LT(op.residual, 1e-12);
    const Vec3 p = op.state.bodies[0].p_WBcm;
    EXPECT_NEAR(std::abs(p.y()), L, 1e-12);
    EXPECT_NEAR(p.x(), 0.0, 1e-12);
    const ModalAnalysis modes = AnalyseModes(*s.model, op, LinearizeOptions{});
    ASSERT_EQ(modes.linearization.coordinates.size(), 1u) << Describe(modes);
    ASSERT_EQ(modes.linearization.speeds.size(), 1u) << Describe(modes);
    ASSERT_EQ(modes.modes.size(), p.y() < 0.0 ? 1u : 2u) << Describe(modes);
    if (p.y() < 0.0) {  // hanging: one neutral pair ±iω
      EXPECT_TRUE(modes.stable);
      EXPECT_TRUE(modes.modes[0].neutral);
      EXPECT_NEAR(modes.modes[0].eigenvalue.imag(), w, kTol * w);
    } else {  // inverted: λ = ±ω, real
      EXPECT_FALSE(modes.stable);
      double growth = 0.0;
      for (const Mode& mode : modes.modes) growth = std::max(growth, mode.growth_rate);
      EXPECT_NEAR(growth, w, kTol * w);
    }
  }
}

// A double pendulum of two bodies on hinges about y: link 1 (mass m1, centre c1 below pin 1,
// inertia J1 about its centre), pin 2 at L1 below pin 1, link 2 (m2, c2, J2). Lagrange with
// small angles: M q̈ + K q = 0,
//   M = [[J1 + m1 c1² + m2 L1², m2 L1 c2], [m2 L1 c2, J2 + m2 c2²]],
//   K = g diag(m1 c1 + m2 L1, m2 c2),
// ω² the roots of det(K - ω² M) = 0.
TEST(Modes, DoublePendulumBothFrequencies) {
  const double m1 = 1.5, c1 = 0.3, J1 = 0.02, L1 = 0.6, m2 = 0.9, c2 = 0.25, J2 = 0.01;
  const std::string scene =
      fmt::format(R"(
chasles: 1
bodies:
  - name: upper
    parts: [{{shape: custom, mass: {m1}, center_of_mass: [0, 0, {z1}], inertia: {{Ixx: {J1}, Iyy: {J1}, Izz: {J1}}}}}]
  - name: lower
    parts: [{{shape: custom, mass: {m2}, center_of_mass: [0, 0, {z2}], inertia: {{Ixx: {J2}, Iyy: {J2}, Izz: {J2}}}}}]
gravity: standard
joints:
  - {{name: shoulder, type: revolute, parent: world, child: upper, at: [0, 0, 0], axis: [0, 1, 0]}}
  - {{name: elbow, type: revolute, parent: upper, child: lower, at: [0, 0, {zp}], axis: [0, 1, 0]}}
)",
                  fmt::arg("m1", m1), fmt::arg("z1", -c1), fmt::arg("J1", J1), fmt::arg("m2", m2),
                  fmt::arg("z2", -L1 - c2), fmt::arg("J2", J2), fmt::arg("zp", -L1));
  const Study s = Build(scene);
  const ModalAnalysis modes = AnalyseModes(*s.model, FindEquilibrium(*s.model, s.initial));
  const double M11 = J1 + m1 * c1 * c1 + m2 * L1 * L1, M12 = m2 * L1 * c2, M22 = J2 + m2 * c2 * c2;
  const double K1 = kG * (m1 * c1 + m2 * L1), K2 = kG * m2 * c2;
  // det(K - w² M) = (M11 M22 - M12²) w⁴ - (K1 M22 + K2 M11) w² + K1 K2.
  const double qa = M11 * M22 - M12 * M12, qb = -(K1 * M22 + K2 * M11), qc = K1 * K2;
  const double disc = std::sqrt(qb * qb - 4.0 * qa * qc);
  const double w1 = std::sqrt((-qb - disc) / (2.0 * qa)), w2 = std::sqrt((-qb + disc) / (2.0 * qa));
  const std::vector<double> w = Frequencies(modes);
  ASSERT_EQ(w.size(), 2u);
  EXPECT_NEAR(w[0], w1, kTol * w1);
  EXPECT_NEAR(w[1], w2, kTol * w2);
}

// A ball (mass m, radius r) held at the origin by six springs of rest length L0 = L/2 to the
// points ±L along each axis, no gravity. A spring along x of stiffness k and length L pulls
// with T = k (L - L0): axially it stiffens by k, across by T/L = k/2. So
//   ω_x² = (2 k_x + k_y + k_z)/m, and cyclically; the ball's rotation is free (3 rigid modes,
// each of the 3 angles and its rate: 6 rigid entries).
TEST(Modes, MassOnSpringsIn3D) {
  const double m = 3.0, r = 0.05, L = 0.4, kx = 100.0, ky = 250.0, kz = 420.0;
  std::string springs;
  const double k[3] = {kx, ky, kz};
  for (int i = 0; i < 3; ++i) {
    for (int s = -1; s <= 1; s += 2) {
      Vec3 p = Vec3::Zero();
      p[i] = s * L;
      springs += fmt::format(
          "  - {{type: spring, name: s{}{}, from: {{body: ball}}, to: {{world: [{}, {}, {}]}}, "
          "rest_length: {}, stiffness: {}}}\n",
          i, s > 0 ? "p" : "m", p.x(), p.y(), p.z(), L / 2, k[i]);
    }
  }
  const std::string scene =
      fmt::format(R"(
chasles: 1
bodies:
  - name: ball
    parts: [{{shape: sphere, radius: {r}, mass: {m}}}]
gravity: [0, 0, 0]
forces:
{springs})",
                  fmt::arg("r", r), fmt::arg("m", m), fmt::arg("springs", springs));
  const Study s = Build(scene);
  const ModalAnalysis modes = AnalyseModes(*s.model, FindEquilibrium(*s.model, s.initial));
  std::vector<double> expect = {std::sqrt((2 * kx + ky + kz) / m),
                                std::sqrt((kx + 2 * ky + kz) / m),
                                std::sqrt((kx + ky + 2 * kz) / m)};
  std::sort(expect.begin(), expect.end());
  const std::vector<double> w = Frequencies(modes);
  ASSERT_EQ(w.size(), 3u);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(w[i], expect[i], kTol * expect[i]);
  EXPECT_EQ(CountRigid(modes), 6);
  EXPECT_TRUE(modes.stable);
}

// A free body at rest: all 12 entries are rigid (drift in position and attitude).
TEST(Modes, FreeBodyIsAllRigid) {
  const Study s = Build(R"(
chasles: 1
bodies:
  - name: block
    parts: [{shape: box, size: [0.1, 0.2, 0.3], mass: 2}]
gravity: [0, 0, 0]
)");
  const ModalAnalysis modes = AnalyseModes(*s.model, FindEquilibrium(*s.model, s.initial));
  EXPECT_EQ(CountRigid(modes), 12);
  EXPECT_TRUE(modes.stable);
  for (const Mode& mode : modes.modes) {
    EXPECT_FALSE(mode.rigid_coordinate.empty());
    EXPECT_TRUE(std::isfinite(mode.damping_ratio));
  }
}

// Under gravity with nothing to hold it, a body has no equilibrium: a clear error.
TEST(Modes, NoEquilibriumIsAnError) {
  const Study s = Build(R"(
chasles: 1
bodies:
  - name: block
    parts: [{shape: box, size: [0.1, 0.2, 0.3], mass: 2}]
gravity: standard
)");
  try {
    FindEquilibrium(*s.model, s.initial);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no static equilibrium"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("block"), std::string::npos) << e.what();
  }
}

// Torque-free rotation of a box with I1 < I2 < I3 at rate Ω about a principal axis (Euler's
// equations linearised, chapter 8.3): about axis 3 (or 1) a neutral oscillation at
//   ω_n = Ω √((I3 - I1)(I3 - I2)/(I1 I2)),
// about axis 2 a growth rate σ = Ω √((I2 - I1)(I3 - I2)/(I1 I3)).
std::string SpinningBox(double a, double b, double c, const std::string& w) {
  return fmt::format(R"(
chasles: 1
bodies:
  - name: box
    parts: [{{shape: box, size: [{}, {}, {}], mass: 2}}]
    initial: {{angular_velocity: {}}}
gravity: [0, 0, 0]
)",
                     a, b, c, w);
}

TEST(Modes, TorqueFreeRotationMajorMinorIntermediate) {
  const double a = 0.3, b = 0.2, c = 0.1, m = 2.0, W = 7.0;
  // Box a × b × c: I1 about x = m (b² + c²)/12 (the smallest: x is the longest side).
  const double I1 = m * (b * b + c * c) / 12, I2 = m * (a * a + c * c) / 12,
               I3 = m * (a * a + b * b) / 12;
  LinearizeOptions opts;
  opts.finite_difference_check = true;
  {  // about the minor axis of inertia... the axis of largest moment, z (I3): stable
    const Study s = Build(SpinningBox(a, b, c, fmt::format("[0, 0, {}]", W)));
    const OperatingPoint op = MakeSteadyMotion(*s.model, s.initial);
    EXPECT_LT(op.residual, 1e-14);
    const ModalAnalysis modes = AnalyseModes(*s.model, op, opts);
    const double wn = W * std::sqrt((I3 - I1) * (I3 - I2) / (I1 * I2));
    EXPECT_TRUE(modes.stable);
    const std::vector<double> w = Frequencies(modes);
    EXPECT_TRUE(
        std::any_of(w.begin(), w.end(), [&](double x) { return std::abs(x - wn) < kTol * wn; }))
        << "no mode at " << wn;
    EXPECT_LT(modes.linearization.finite_difference_check, 1e-6);
  }
  {  // about x (I1): stable
    const Study s = Build(SpinningBox(a, b, c, fmt::format("[{}, 0, 0]", W)));
    const ModalAnalysis modes = AnalyseModes(*s.model, MakeSteadyMotion(*s.model, s.initial));
    const double wn = W * std::sqrt((I2 - I1) * (I3 - I1) / (I2 * I3));
    EXPECT_TRUE(modes.stable) << Describe(modes);
    const std::vector<double> w = Frequencies(modes);
    EXPECT_TRUE(
        std::any_of(w.begin(), w.end(), [&](double x) { return std::abs(x - wn) < kTol * wn; }))
        << "no mode at " << wn;
  }
  {  // about y (I2): unstable
    const Study s = Build(SpinningBox(a, b, c, fmt::format("[0, {}, 0]", W)));
    const ModalAnalysis modes = AnalyseModes(*s.model, MakeSteadyMotion(*s.model, s.initial));
    const double sigma = W * std::sqrt((I2 - I1) * (I3 - I2) / (I1 * I3));
    EXPECT_FALSE(modes.stable);
    EXPECT_NEAR(modes.max_real_part, sigma, kTol * sigma);
  }
}

// A torque-free precession of an axisymmetric body (ω off its axis of symmetry) is a steady
// motion: a turn about the angular momentum H (conserved) plus a spin about the axis. Found
// as one (residual at round-off, no warning), and stable (the axis cones about H; a nearby
// motion is another such precession).
TEST(Modes, TorqueFreePrecessionIsASteadyMotion) {
  const Study s = Build(R"(
chasles: 3
bodies:
  - name: disk
    parts: [{shape: cylinder, radius: 0.2, length: 0.05, mass: 3}]
    initial: {angular_velocity: [1.5, 0, 8], angular_velocity_frame: body}
gravity: [0, 0, 0]
)");
  const OperatingPoint op = MakeSteadyMotion(*s.model, s.initial);
  EXPECT_LT(op.residual, 1e-14);
  EXPECT_TRUE(op.warnings.empty());
  const ModalAnalysis modes = AnalyseModes(*s.model, op);
  EXPECT_TRUE(modes.stable) << Describe(modes);
}

// A box (1, 2, 3 kg m²) turning at (0.01, 10, 0.01) rad/s in its frame is near the steady
// rotation about its intermediate axis but not on it: analysed as given with a warning whose
// rate bound (residual × |ω|) covers the slow mode the unsteadiness makes, and the growth rate
// Ω √((I2 - I1)(I3 - I2)/(I1 I3)) = 10/√3 within that bound.
TEST(Modes, NearlySteadyMotionIsAnalysedWithAWarning) {
  const Study s = Build(R"(
chasles: 3
bodies:
  - name: handle
    parts: [{shape: custom, mass: 1 kg, inertia: {Ixx: 1 kg*m^2, Iyy: 2 kg*m^2, Izz: 3 kg*m^2}}]
    initial: {angular_velocity: [0.01, 10, 0.01], angular_velocity_frame: body}
gravity: [0, 0, 0]
)");
  const OperatingPoint op = MakeSteadyMotion(*s.model, s.initial);
  EXPECT_GT(op.residual, kSteadyResidual);
  ASSERT_EQ(op.warnings.size(), 1u);
  EXPECT_NE(op.warnings[0].find("near a steady one but not one"), std::string::npos);
  const ModalAnalysis modes = AnalyseModes(*s.model, op);
  const double bound = op.residual * 10.0, sigma = 10.0 / std::sqrt(3.0);
  EXPECT_NEAR(modes.max_real_part, sigma, 10 * bound);
}

// A motion that is no steady one (a ball thrown through viscous drag: its velocity decays at
// c/m) has no modes: an error, not a linearisation about a state that does not stay.
TEST(Modes, MotionThatIsNotSteadyIsAnError) {
  const Study s = Build(R"(
chasles: 3
bodies:
  - name: ball
    parts: [{shape: sphere, radius: 0.1, mass: 1}]
    initial: {velocity: [3, 0, 0]}
gravity: [0, 0, 0]
forces:
  - {type: drag, name: air, body: ball, linear: 0.5 N*s/m}
)");
  try {
    MakeSteadyMotion(*s.model, s.initial);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not a steady motion"), std::string::npos) << e.what();
  }
}

// A sleeping top: a solid cylinder (radius ρ, length h, mass m) on a spherical joint at its
// lower end, its centre of mass l = h/2 above, spinning at Ω about the vertical. With
// I₁ = m (3ρ² + h²)/12 + m l² about the pivot and I₃ = m ρ²/2, the tilt obeys
//   I₁ λ² - i I₃ Ω λ... : λ = i (I₃ Ω ± √(I₃² Ω² - 4 I₁ m g l)) / (2 I₁),
// neutral exactly when Ω² >= 4 m g l I₁ / I₃² (the sleeping top's threshold).
std::string SleepingTop(double rho, double h, double m, double W) {
  return fmt::format(R"(
chasles: 1
bodies:
  - name: top
    parts: [{{shape: cylinder, radius: {rho}, length: {h}, mass: {m}, position: [0, 0, {l}]}}]
    initial: {{angular_velocity: [0, 0, {W}]}}
gravity: standard
joints:
  - {{name: tip, type: spherical, parent: world, child: top, at: [0, 0, 0]}}
)",
                     fmt::arg("rho", rho), fmt::arg("h", h), fmt::arg("m", m), fmt::arg("l", h / 2),
                     fmt::arg("W", W));
}

TEST(Modes, SleepingTopThresholdAndFrequencies) {
  const double rho = 0.04, h = 0.06, m = 0.7, l = h / 2;
  const double I1 = m * (3 * rho * rho + h * h) / 12 + m * l * l, I3 = m * rho * rho / 2;
  const double Wc = std::sqrt(4 * m * kG * l * I1 / (I3 * I3));
  const auto analyse = [&](double W) {
    const Study s = Build(SleepingTop(rho, h, m, W));
    return AnalyseModes(*s.model, MakeSteadyMotion(*s.model, s.initial));
  };
  {
    const double W = 1.5 * Wc;
    const ModalAnalysis modes = analyse(W);
    EXPECT_TRUE(modes.stable);
    const double root = std::sqrt(I3 * I3 * W * W - 4 * I1 * m * kG * l);
    const double slow = (I3 * W - root) / (2 * I1), fast = (I3 * W + root) / (2 * I1);
    const std::vector<double> w = Frequencies(modes);
    ASSERT_EQ(w.size(), 2u);
    EXPECT_NEAR(w[0], slow, kTol * slow);
    EXPECT_NEAR(w[1], fast, kTol * fast);
  }
  EXPECT_FALSE(analyse(0.9 * Wc).stable);
  std::vector<double> grid;
  for (int i = 0; i <= 6; ++i) grid.push_back(Wc * (0.5 + 0.25 * i));
  const std::vector<StabilityChange> changes = FindStabilityChanges(analyse, grid);
  ASSERT_EQ(changes.size(), 1u);
  EXPECT_NEAR(changes[0].value, Wc, kTol * Wc);
  EXPECT_TRUE(changes[0].stable_after);
}

// A heavy symmetric top in steady precession (examples/heavy-top.yaml): tilt θ₀, precession
// rate Ω_p, spin ω₃ along the axis, A and C about the tip. With p_φ = C ω₃ and
// p_ψ = A Ω_p sin²θ₀ + C ω₃ cos θ₀ conserved, Routh's reduced potential
//   U(θ) = N² / (2 A sin²θ) + m g l cos θ,  N = p_ψ - p_φ cos θ,
// has U'(θ₀) = 0 and the nutation frequency is ω² = U''(θ₀)/A. With s = sin θ, c = cos θ,
// N' = p_φ s, P = p_φ s² - N c, P' = p_φ s c + N s, the first term's derivative is
// g/A with g = N P / s³ and g' = N' P / s³ + N P' / s³ - 3 N P c / s⁴, so
//   ω² = (g'(θ₀)/A - m g l c) / A.
TEST(Modes, HeavyTopNutationFrequency) {
  const double m = 0.5, R = 0.03, hh = 0.08, l = 0.75 * hh, th = 0.5, w3 = 600.0;
  const double A = 3.0 / 20 * m * R * R + 3.0 / 80 * m * hh * hh + m * l * l, C = 0.3 * m * R * R;
  const double Op = (C * w3 - std::sqrt(C * C * w3 * w3 - 4 * A * std::cos(th) * m * kG * l)) /
                    (2 * A * std::cos(th));
  const std::string scene = fmt::format(
      R"(
chasles: 1
bodies:
  - name: top
    points: {{tip: [0, 0, 0]}}
    parts: [{{shape: custom, mass: {m}, center_of_mass: [0, 0, {l}], inertia: {{Ixx: {Acm}, Iyy: {Acm}, Izz: {C}}}}}]
    initial:
      velocity_point: tip
      velocity: [0, 0, 0]
      rotation: {{axis: [0, 1, 0], angle: {th}}}
      angular_velocity: [{wx}, 0, {wz}]
gravity: standard
joints:
  - {{name: tip, type: spherical, parent: world, child: top, at: [0, 0, 0]}}
)",
      fmt::arg("m", m), fmt::arg("l", l), fmt::arg("Acm", A - m * l * l), fmt::arg("C", C),
      fmt::arg("th", th), fmt::arg("wx", (w3 - Op * std::cos(th)) * std::sin(th)),
      fmt::arg("wz", Op + (w3 - Op * std::cos(th)) * std::cos(th)));
  const Study s = Build(scene);
  const OperatingPoint op = MakeSteadyMotion(*s.model, s.initial);
  EXPECT_LT(op.residual, 1e-12);
  EXPECT_NEAR(op.generator.w_W.z(), Op, 1e-12 * Op);
  LinearizeOptions opts;
  opts.finite_difference_check = true;
  const ModalAnalysis modes = AnalyseModes(*s.model, op, opts);
  const double sn = std::sin(th), cs = std::cos(th);
  const double pphi = C * w3, N = A * Op * sn * sn;
  const double P = pphi * sn * sn - N * cs, Pd = pphi * sn * cs + N * sn, Nd = pphi * sn;
  const double gd =
      Nd * P / std::pow(sn, 3) + N * Pd / std::pow(sn, 3) - 3 * N * P * cs / std::pow(sn, 4);
  const double wnut = std::sqrt((gd / A - m * kG * l * cs) / A);
  const std::vector<double> w = Frequencies(modes);
  EXPECT_TRUE(
      std::any_of(w.begin(), w.end(), [&](double x) { return std::abs(x - wnut) < kTol * wnut; }))
      << "no mode at " << wnut << "; first " << (w.empty() ? 0.0 : w.back());
  EXPECT_TRUE(modes.stable) << Describe(modes);
  EXPECT_LT(modes.linearization.finite_difference_check, 1e-6);
}

// A thin uniform disk (mass m, radius r) rolling upright at speed v on a plane: with
// I₁ = m r²/4 about a diameter and I₃ = m r²/2 about the axle, the lean is neutral exactly when
//   ω² = (v/r)² >= m g r I₁ / (I₃ (I₃ + m r²)) = g / (3 r)
// (Routh; the rolling disk's linearised lean and steer equations).
std::string RollingDisk(double r, double m, double v) {
  return fmt::format(R"(
chasles: 1
bodies:
  - name: disk
    parts: [{{shape: disk, radius: {r}, mass: {m}}}]
    initial:
      position: [0, 0, {r}]
      rotation: {{axis: [1, 0, 0], angle: 90 deg}}
      velocity: [{v}, 0, 0]
      angular_velocity: [0, {w}, 0]
gravity: standard
rolling:
  - {{name: floor, body: disk, shape: disk, radius: {r}, axis: [0, 0, 1],
     plane: {{point: [0, 0, 0], normal: [0, 0, 1]}}}}
)",
                     fmt::arg("r", r), fmt::arg("m", m), fmt::arg("v", v), fmt::arg("w", v / r));
}

TEST(Modes, RollingDiskStableAboveTheClosedFormSpeed) {
  const double r = 0.3, m = 2.0;
  const double vc = r * std::sqrt(kG / (3 * r));
  const auto analyse = [&](double v) {
    const Study s = Build(RollingDisk(r, m, v));
    return AnalyseModes(*s.model, MakeSteadyMotion(*s.model, s.initial));
  };
  EXPECT_TRUE(analyse(1.3 * vc).stable) << Describe(analyse(1.3 * vc));
  EXPECT_FALSE(analyse(0.7 * vc).stable) << Describe(analyse(0.7 * vc));
  std::vector<double> grid;
  for (int i = 0; i <= 4; ++i) grid.push_back(vc * (0.6 + 0.2 * i));
  const std::vector<StabilityChange> changes = FindStabilityChanges(analyse, grid);
  ASSERT_EQ(changes.size(), 1u);
  EXPECT_NEAR(changes[0].value, vc, kTol * vc);
  EXPECT_TRUE(changes[0].stable_after);
}

// A solid cylinder (radius r, mass m) rolling without slipping inside a fixed trough of radius
// R (a circular cylinder, axes parallel): with θ the angle of its centre from the bottom,
// the rolling gives its spin (R - r) θ̇ / r, so T = ½ m (R - r)² θ̇² + ½ (½ m r²)((R - r) θ̇/r)²
// = ¾ m (R - r)² θ̇², V = m g (R - r)(1 - cos θ), and ω² = 2 g / (3 (R - r)).
TEST(Modes, CylinderInATrough) {
  const double r = 0.05, R = 0.4, m = 1.2, len = 0.1;
  const std::string scene =
      fmt::format(R"(
chasles: 1
bodies:
  - name: roller
    parts: [{{shape: cylinder, radius: {r}, length: {len}, mass: {m}, position: [0, 0, {r}],
              rotation: {{axis: [1, 0, 0], angle: 90 deg}}}}]
gravity: standard
rolling:
  - {{name: trough, body: roller, shape: cylinder, radius: {r}, axis: [0, 1, 0],
     surface: {{shape: cylinder, center: [0, 0, {R}], axis: [0, 1, 0], radius: {R}, side: inside}}}}
)",
                  fmt::arg("r", r), fmt::arg("len", len), fmt::arg("m", m), fmt::arg("R", R));
  const Study s = Build(scene);
  LinearizeOptions opts;
  opts.finite_difference_check = true;
  const ModalAnalysis modes = AnalyseModes(*s.model, FindEquilibrium(*s.model, s.initial), opts);
  const double w = std::sqrt(2 * kG / (3 * (R - r)));
  const std::vector<double> f = Frequencies(modes);
  ASSERT_EQ(f.size(), 1u) << Describe(modes);
  EXPECT_NEAR(f[0], w, kTol * w);
  EXPECT_LT(modes.linearization.finite_difference_check, 1e-6);
}

// A solid ball (radius r) rolling in a spherical bowl (radius R): T = ½ (7/5) m (R - r)² θ̇²,
// so ω² = 5 g / (7 (R - r)) in both directions across the bottom.
TEST(Modes, BallInABowl) {
  const double r = 0.03, R = 0.5, m = 0.4;
  const std::string scene = fmt::format(R"(
chasles: 1
bodies:
  - name: ball
    parts: [{{shape: sphere, radius: {r}, mass: {m}, position: [0, 0, {r}]}}]
gravity: standard
rolling:
  - {{name: bowl, body: ball, shape: sphere, radius: {r},
     surface: {{shape: sphere, center: [0, 0, {R}], radius: {R}, side: inside}}}}
)",
                                        fmt::arg("r", r), fmt::arg("m", m), fmt::arg("R", R));
  const Study s = Build(scene);
  LinearizeOptions opts;
  opts.finite_difference_check = true;
  const ModalAnalysis modes = AnalyseModes(*s.model, FindEquilibrium(*s.model, s.initial), opts);
  const double w = std::sqrt(5 * kG / (7 * (R - r)));
  const std::vector<double> f = Frequencies(modes);
  ASSERT_EQ(f.size(), 2u) << Describe(modes);
  for (double x : f) EXPECT_NEAR(x, w, kTol * w);
  EXPECT_LT(modes.linearization.finite_difference_check, 1e-6);
}

// Each body's motion in a mode (CalcBodyModeShapes) against the rigid kinematics of the
// closed forms: relative to the mode's largest displacement or rotation.
constexpr double kShapeTol = 1e-9;

/// The non-rigid modes.
std::vector<const Mode*> Moving(const ModalAnalysis& a) {
  std::vector<const Mode*> out;
  for (const Mode& m : a.modes) {
    if (!m.rigid) out.push_back(&m);
  }
  return out;
}

// examples/pendulum.yaml hanging at rest (theta0 = 0): a ball (m, radius r) whose centre is at
// (0, -L) from the pin at Wo, axis z. One mode, ω² = m g L / I_O, I_O = (2/5) m r² + m L² (eq.
// 8.39), shaped by the pin angle φ alone (its entry 1): the ball turns by δθ = φ z about the pin,
// so δθ = [0, 0, 1] and its centre moves by δp = δθ × p_WBcm = [L, 0, 0]: tangent to its
// circle about the pin, |δp| = L |δθ|.
TEST(Modes, PendulumBodyMotionTurnsAboutThePin) {
  const double m = 1.5, L = 0.8, r = 0.05;
  SceneOptions options;
  options.parameter_overrides = {
      {"theta0", "0 deg"}, {"L", "0.8 m"}, {"m", "1.5 kg"}, {"r", "5 cm"}};
  const Study s = Settled(BuildStudy(
      LoadSceneFile(std::string(test::SourceDir()) + "/examples/pendulum.yaml", options), 1.0));
  const OperatingPoint op = FindEquilibrium(*s.model, s.initial);
  const ModalAnalysis modes = AnalyseModes(*s.model, op);
  const std::vector<const Mode*> moving = Moving(modes);
  ASSERT_EQ(moving.size(), 1u) << Describe(modes);
  const double w = std::sqrt(m * kG * L / (0.4 * m * r * r + m * L * L));
  EXPECT_NEAR(moving[0]->eigenvalue.imag(), w, kTol * w);
  const std::vector<BodyModeShape> body = CalcBodyModeShapes(modes.linearization, *moving[0]);
  ASSERT_EQ(body.size(), 1u);
  const Eigen::Vector3cd dtheta(0.0, 0.0, 1.0), dp(L, 0.0, 0.0);
  EXPECT_LT((body[0].dtheta - dtheta).norm(), kShapeTol) << body[0].dtheta.transpose();
  EXPECT_LT((body[0].dp - dp).norm(), kShapeTol * L) << body[0].dp.transpose();
  // Tangent to the circle and |δp| = L |δθ|, read off the answer itself.
  const Vec3 radius = op.state.bodies[0].p_WBcm;
  EXPECT_NEAR(radius.norm(), L, kShapeTol * L);
  EXPECT_LT(std::abs(body[0].dp.dot(radius.cast<std::complex<double>>())),
            kShapeTol * L * body[0].dp.norm());
  EXPECT_NEAR(body[0].dp.norm(), L * body[0].dtheta.norm(), kShapeTol * L);
}

// The double pendulum of DoublePendulumBothFrequencies: with the bodies' absolute angles θ1, θ2
// about y, (K - ω² M) φ = 0 gives the shape's ratio φ2 / φ1 = (K1 - ω² M11) / (ω² M12). Each
// body turns by its angle, δθ = θ_i y, and with y × z = x its centre of mass moves by
// δp_upper = -c1 θ1 x and δp_lower = -(L1 θ1 + c2 θ2) x.
TEST(Modes, DoublePendulumBodyMotionAgainstTheEigenvector) {
  const double m1 = 1.5, c1 = 0.3, J1 = 0.02, L1 = 0.6, m2 = 0.9, c2 = 0.25, J2 = 0.01;
  const std::string scene =
      fmt::format(R"(
chasles: 1
bodies:
  - name: upper
    parts: [{{shape: custom, mass: {m1}, center_of_mass: [0, 0, {z1}], inertia: {{Ixx: {J1}, Iyy: {J1}, Izz: {J1}}}}}]
  - name: lower
    parts: [{{shape: custom, mass: {m2}, center_of_mass: [0, 0, {z2}], inertia: {{Ixx: {J2}, Iyy: {J2}, Izz: {J2}}}}}]
gravity: standard
joints:
  - {{name: shoulder, type: revolute, parent: world, child: upper, at: [0, 0, 0], axis: [0, 1, 0]}}
  - {{name: elbow, type: revolute, parent: upper, child: lower, at: [0, 0, {zp}], axis: [0, 1, 0]}}
)",
                  fmt::arg("m1", m1), fmt::arg("z1", -c1), fmt::arg("J1", J1), fmt::arg("m2", m2),
                  fmt::arg("z2", -L1 - c2), fmt::arg("J2", J2), fmt::arg("zp", -L1));
  const Study s = Build(scene);
  const ModalAnalysis modes = AnalyseModes(*s.model, FindEquilibrium(*s.model, s.initial));
  const double M11 = J1 + m1 * c1 * c1 + m2 * L1 * L1, M12 = m2 * L1 * c2;
  const double K1 = kG * (m1 * c1 + m2 * L1);
  const std::vector<const Mode*> moving = Moving(modes);
  ASSERT_EQ(moving.size(), 2u) << Describe(modes);
  for (const Mode* mode : moving) {
    const double w2 = std::norm(mode->eigenvalue);
    const double ratio = (K1 - w2 * M11) / (w2 * M12);
    const std::vector<BodyModeShape> b = CalcBodyModeShapes(modes.linearization, *mode);
    ASSERT_EQ(b.size(), 2u);
    const std::complex<double> theta1 = b[0].dtheta.y(), theta2 = b[1].dtheta.y();
    EXPECT_NEAR(std::abs(theta2 / theta1 - ratio), 0.0, kShapeTol * std::abs(ratio));
    const double scale = std::max(std::abs(theta1), std::abs(theta2));
    EXPECT_LT(std::abs(b[0].dtheta.x()) + std::abs(b[0].dtheta.z()), kShapeTol * scale);
    EXPECT_LT(std::abs(b[1].dtheta.x()) + std::abs(b[1].dtheta.z()), kShapeTol * scale);
    const Eigen::Vector3cd dp_upper(-c1 * theta1, 0.0, 0.0);
    const Eigen::Vector3cd dp_lower(-(L1 * theta1 + c2 * theta2), 0.0, 0.0);
    EXPECT_LT((b[0].dp - dp_upper).norm(), kShapeTol * L1 * scale);
    EXPECT_LT((b[1].dp - dp_lower).norm(), kShapeTol * L1 * scale);
  }
}

// examples/cylinder-in-trough.yaml: with φ the angle of the centre from the trough's bottom,
// the centre moves by δp = (R - r) δφ x and rolling turns the cylinder by δθ = (R - r) δφ / r
// about y (the contact point p + r n, n = [sin φ, 0, -cos φ], has v - ω_y r [cos φ, 0, sin φ]
// = 0), so δp = r δθ_y x exactly, and nothing else moves.
TEST(Modes, CylinderInATroughBodyMotionRolls) {
  const double r = 0.05;  // the example's
  const Study s = Settled(BuildStudy(
      LoadSceneFile(std::string(test::SourceDir()) + "/examples/cylinder-in-trough.yaml"), 1.0));
  const ModalAnalysis modes = AnalyseModes(*s.model, FindEquilibrium(*s.model, s.initial));
  const std::vector<const Mode*> moving = Moving(modes);
  ASSERT_EQ(moving.size(), 1u) << Describe(modes);
  const std::vector<BodyModeShape> b = CalcBodyModeShapes(modes.linearization, *moving[0]);
  ASSERT_EQ(b.size(), 1u);
  const std::complex<double> spin = b[0].dtheta.y();
  ASSERT_GT(std::abs(spin), 0.0);
  EXPECT_NEAR(std::abs(b[0].dp.x() / spin - r), 0.0, kShapeTol * r);
  EXPECT_LT(std::abs(b[0].dp.y()) + std::abs(b[0].dp.z()), kShapeTol * r * std::abs(spin));
  EXPECT_LT(std::abs(b[0].dtheta.x()) + std::abs(b[0].dtheta.z()), kShapeTol * std::abs(spin));
}

TEST(Modes, BodyMotionOfAShapeOfAnotherSizeIsAUsageError) {
  Linearization lin;
  lin.basis = Eigen::MatrixXd::Identity(12, 2);
  Mode mode;
  mode.shape = Eigen::VectorXcd::Ones(3);
  EXPECT_THROW(CalcBodyModeShapes(lin, mode), UsageError);
}

}  // namespace
}  // namespace chasles
