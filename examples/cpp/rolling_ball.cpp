// A ball set on a floor with its contact point slipping — a bowling ball thrown without spin,
// or a ball set down spinning in place (Problems 8.26/8.27) — slides, and friction turns the
// sliding into rolling.
//
// Closed forms, derived here. A uniform ball (I = 2/5 m R²), radius R, on the floor z = 0
// with gravity -g z, moving along x with velocity v and spin ω about y. The contact point
// C = centre - R z slips at s = v - ω R (ω ŷ × (-R ẑ) = -ω R x̂). While it slides, kinetic
// friction mu_k m g opposes the slip (N = m g: no vertical motion):
//   m v̇ = -mu_k m g sgn(s0),   I ω̇ = +mu_k m g R sgn(s0)     (eqs. 8.76, 8.40)
// so ṡ = -mu_k g sgn(s0) (1 + m R²/I) = -7/2 mu_k g sgn(s0), and the slip is zero at
//   t* = 2 |s0| / (7 mu_k g),
// where v* = v0 - mu_k g t* sgn(s0) = (5 v0 + 2 R ω0) / 7 and ω* = v*/R. From then on the ball
// rolls: no slip, no friction, constant speed and kinetic energy 7/10 m v*². The energy lost
// is the work of friction (eq. 8.112): W_f = 7/10 m v*² - (½ m v0² + 1/5 m R² ω0²).
// For the thrown ball (ω0 = 0): t* = 2 v0/(7 mu_k g), v* = 5/7 v0, W_f = -m v0²/7; it slid
// x* = v0 t* - ½ mu_k g t*² = 12 v0²/(49 mu_k g).
// The program exits 1 if any value differs from its closed form by more than 1e-9 relative.
#include <cmath>
#include <cstdio>
#include <memory>

#include "chasles/chasles.h"

namespace {

bool all_ok = true;

void Check(const char* what, double value, double expected, double scale = 0) {
  const double ref = scale > 0 ? scale : std::abs(expected);
  const double rel = std::abs(value - expected) / ref;
  const bool ok = rel <= 1e-9;
  all_ok = all_ok && ok;
  std::printf("  %-26s %16.12f   closed form %16.12f   rel. error %.1e %s\n", what, value, expected,
              rel, ok ? "" : "  <-- FAILED");
}

// Runs one ball with centre velocity v0 [m/s] along x and spin w0 [rad/s] about y, and
// compares the run with the closed forms above.
void RunBall(const char* title, double v0, double w0) {
  using namespace chasles;
  const double R = 0.108;  // bowling ball radius [m]
  const double m = 7.0;    // [kg]
  const double g = 9.81, mu_s = 0.3, mu_k = 0.2;

  // 1. The ball: a solid sphere's mass properties, centre of mass at its frame's origin.
  Model model;
  const BodyIndex ball = model.AddBody("ball", MakeSolidSphere(R)->CalcMassProperties(m));
  model.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -g)));

  // 2. Its contact with the floor: a sphere of radius R at Bo against the plane z = 0 (the
  //    ContactSpec defaults), with Coulomb friction.
  ContactSpec floor;
  floor.name = "floor";
  floor.shape = ContactShape::kSphere;
  floor.body = ball;
  floor.radius = R;
  floor.mu_s = mu_s;
  floor.mu_k = mu_k;
  model.AddContact(floor);

  // 3. Set down touching the floor, with its velocity and spin. The contact modes are left to
  //    Simulate to choose (sliding here: the contact point slips).
  State start = MakeRestState(model);
  SetBodyPose(model, ball, Vec3(0, 0, R), Quat::Identity(), start);
  SetBodyVelocity(model, ball, Vec3(v0, 0, 0), Vec3(0, w0, 0), start);

  const double s0 = v0 - w0 * R;
  const double t_star = 2 * std::abs(s0) / (7 * mu_k * g);
  const double v_star = (5 * v0 + 2 * R * w0) / 7;
  const double T0 = 0.5 * m * v0 * v0 + 0.2 * m * R * R * w0 * w0;

  // 4. Run to twice t*: the mode change (sliding -> sticking, i.e. rolling) is an event
  //    located on the dense output.
  SimulationOptions options;
  options.t_end = 2 * t_star;
  options.adaptive.rtol = 1e-12;
  options.adaptive.atol = 1e-14;
  const SimulationResult run = Simulate(model, start, options);

  std::printf("%s: v0 = %g m/s, w0 = %g rad/s, mu_k = %g\n", title, v0, w0, mu_k);
  const ContactEvent* stop = nullptr;
  for (const ContactEvent& e : run.contact_events) {
    std::printf("  t = %.12f s  %s: %s -> %s\n", e.t, ContactEventReasonName(e.reason),
                ContactModeName(e.from), ContactModeName(e.to));
    if (e.reason == ContactEventReason::kSlipStopped && stop == nullptr) stop = &e;
  }
  if (stop == nullptr || stop->to != ContactMode::kSticking) {
    std::printf("  the ball never stopped slipping  <-- FAILED\n");
    all_ok = false;
    return;
  }
  Check("t* [s]", stop->t, t_star);

  // 5. At the end (rolling since t*): speed, spin, energy and the work of friction.
  const State& end = run.final_state;
  const BodyState& b = end.bodies[ball];
  Check("v at the end [m/s]", b.v_WBcm_W.x(), v_star);
  Check("w at the end [rad/s]", b.w_WB_B.y(), v_star / R);
  const LedgerSample ledger = CalcLedgerSample(model, end, start);
  const double T_star = 0.7 * m * v_star * v_star;
  Check("kinetic energy [J]", ledger.kinetic_translational + ledger.kinetic_rotational, T_star);
  Check("friction work [J]", ledger.contact_friction_work, T_star - T0);
  if (w0 == 0) {
    // Where it started to roll: x(t*) = x_end - v* (t_end - t*).
    const double x_star = b.p_WBcm.x() - v_star * (end.t - t_star);
    Check("x* [m]", x_star, 12 * v0 * v0 / (49 * mu_k * g));
  }
}

}  // namespace

int main() {
  RunBall("Bowling ball thrown without spin", 8.0, 0.0);
  RunBall("Ball set down spinning in place", 0.0, 60.0);
  std::printf(all_ok ? "all values agree with the closed forms\n"
                     : "SOME VALUES DISAGREE WITH THE CLOSED FORMS\n");
  return all_ok ? 0 : 1;
}
