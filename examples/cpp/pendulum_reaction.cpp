// The reaction at the pivot of a pendulum: a uniform steel bar (a solid cylinder of length L
// and radius r) on a revolute joint at one end, released at rest from horizontal.
//
// Closed forms, derived here (gravity -g along y, the bar along +x at release, the pin's axis
// z). About the pivot O the bar's moment of inertia is, with the parallel-axis theorem
// (eq. 8.29) on a cylinder's transverse moment m (L²/12 + r²/4):
//   I_O = m (L²/3 + r²/4)      (m L²/3 for a slender rod, r -> 0).
//  - At release (ω = 0): I_O α = m g L/2 (moment of gravity about O), so
//    α = m g L / (2 I_O)  (= 3g/(2L) for a slender rod); the centre of mass, at L/2 from O,
//    accelerates downwards at α L/2, and Newton's second law (eqs. 8.76-8.78) on the bar,
//    R - m g = -m α L/2, gives the pivot's upward reaction R = m g - m α L/2 (= m g/4),
//    with no horizontal component (ω = 0: no centripetal acceleration).
//  - Hanging straight down, having fallen by L/2 (work-energy, eq. 8.112):
//    ½ I_O ω² = m g L/2, so ω² = m g L / I_O (= 3g/L); there α = 0 (gravity has no moment
//    about O) and the centre of mass accelerates upwards at ω² L/2 towards O:
//    R = m g + m ω² L/2 (= 5/2 m g).
// The first comes from SolveInstantaneous at the release state, the second from Simulate
// with an event that stops the run where the bar passes the vertical, then SolveInstantaneous
// at the located state. The program exits 1 if any value differs from its closed form by
// more than 1e-9 relative.
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
  std::printf("  %-26s %16.10f   closed form %16.10f   rel. error %.1e %s\n", what, value, expected,
              rel, ok ? "" : "  <-- FAILED");
}

}  // namespace

int main() {
  using namespace chasles;
  const double L = 1.2;         // length [m]
  const double r = 0.01;        // radius [m]
  const double density = 7850;  // steel [kg/m^3]
  const double g = 9.81;        // [m/s^2]

  // 1. The bar's mass properties in its body frame B, whose origin Bo is the pivot end: a
  //    cylinder (axis z of its own frame S) turned so that its axis is B's x, centred at
  //    (L/2, 0, 0).
  const std::unique_ptr<Shape> cylinder = MakeSolidCylinder(r, L);
  const double m = density * cylinder->CalcMeasure();
  const MassProperties bar = cylinder->CalcMassProperties(m).ExpressedInParent(
      RotationTakingZTo(Vec3::UnitX()), Vec3(L / 2, 0, 0));

  // 2. The model: one body, gravity, and a revolute joint whose axis (z of the joint frame)
  //    is W's z, at the world origin on the ground and at Bo on the bar.
  Model model;
  const BodyIndex b = model.AddBody("bar", bar);
  model.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, -g, 0)));
  model.AddConstraint(std::make_shared<Joint>("pivot", JointKind::kRevolute, kWorld,
                                              AttachmentFrame{Vec3::Zero()}, b,
                                              AttachmentFrame{Vec3::Zero()}));

  // 3. The release state: Bo at the pivot, B aligned with W (the bar along +x), at rest.
  State released = MakeRestState(model);
  SetBodyPose(model, b, Vec3::Zero(), Quat::Identity(), released);

  const double I_O = m * (L * L / 3 + r * r / 4);
  std::printf("Steel bar on a pin: L = %g m, r = %g m, m = %.6f kg\n", L, r, m);

  // 4. At release: angular acceleration and the pivot's reaction on the bar.
  const InstantaneousSolution at_release = SolveInstantaneous(model, released);
  const double alpha = m * g * L / (2 * I_O);
  std::printf(
      "at release (horizontal, at rest); slender rod: alpha = 3g/(2L) = %.6f rad/s^2, "
      "R = m g/4 = %.6f N\n",
      1.5 * g / L, m * g / 4);
  Check("alpha_z [rad/s^2]", at_release.bodies[b].alpha_WB_W.z(), -alpha);
  Check("R_x [N]", at_release.reactions[0].F_Jc_W.x(), 0, m * g);
  Check("R_y [N]", at_release.reactions[0].F_Jc_W.y(), m * g - m * alpha * L / 2);

  // 5. Simulate the fall and stop where the centre of mass passes below the pivot (its x
  //    falls through zero); the event time is located to 1e-12 s on the dense output.
  SimulationOptions options;
  options.t_end = 5.0;  // longer than the quarter swing; the event ends the run
  options.adaptive.rtol = 1e-12;
  options.adaptive.atol = 1e-14;
  EventSpec vertical;
  vertical.name = "vertical";
  vertical.g = [b](const Model&, const State& s) { return s.bodies[b].p_WBcm.x(); };
  vertical.direction = EventDirection::kFalling;
  vertical.action = EventAction::kStop;
  options.events.push_back(vertical);
  const SimulationResult run = Simulate(model, released, options);
  if (!run.stopped_by_event) {
    std::printf("the bar never reached the vertical\n");
    return 1;
  }
  const State& down = run.final_state;
  const InstantaneousSolution at_bottom = SolveInstantaneous(model, down);
  const double omega2 = m * g * L / I_O;
  std::printf(
      "hanging straight down, reached at t = %.9f s; slender rod: omega^2 = 3g/L, "
      "R = 5/2 m g = %.6f N\n",
      down.t, 2.5 * m * g);
  Check("omega^2 [rad^2/s^2]", down.bodies[b].w_WB_B.squaredNorm(), omega2);
  Check("alpha_z [rad/s^2]", at_bottom.bodies[b].alpha_WB_W.z(), 0, alpha);
  Check("R_x [N]", at_bottom.reactions[0].F_Jc_W.x(), 0, m * g);
  Check("R_y [N]", at_bottom.reactions[0].F_Jc_W.y(), m * g + m * omega2 * L / 2);

  std::printf(all_ok ? "all values agree with the closed forms\n"
                     : "SOME VALUES DISAGREE WITH THE CLOSED FORMS\n");
  return all_ok ? 0 : 1;
}
