#pragma once
/// @file
/// Balls set down on a floor (the spinning ball of Problems 8.26/8.27, many times over), for the
/// islands tests, the event-driven sphere tests and the benchmarks: each ball a uniform sphere,
/// I = 2/5 m R² (or kappa m R², a hollow one at 2/3), with a sphere contact on the world plane
/// z = 0, under uniform gravity. Set down spinning at w0 about
/// y with its centre at rest, a ball slides: friction mu_k m g gives v̇ = mu_k g and
/// ẇ = −5 mu_k g / (2 R), so the slip R w − v falls at 7/2 mu_k g and sliding ends at
/// t* = 2 R w0 / (7 mu_k g); it then rolls at v = 2/7 R w0 (the angular momentum about the
/// contact point, I w0 = (I + m R²) v / R, is kept).

#include <memory>
#include <vector>

#include <fmt/format.h>

#include "chasles/model/contact.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"

namespace chasles::reference {

struct Ball {
  double mass, radius, mu_s, mu_k;
  double mu_r = 0.0;         ///< rolling resistance
  double restitution = 0.0;  ///< with the floor
  double kappa = 0.4;        ///< I = kappa m R² (2/5 solid, 2/3 hollow)
};

/// Balls "ball0", … with contacts "floor0", … and one UniformGravity "gravity" of g down z.
inline Model MakeBallsOnFloor(const std::vector<Ball>& balls, double g) {
  Model m;
  for (size_t i = 0; i < balls.size(); ++i) {
    const Ball& ball = balls[i];
    const double I = ball.kappa * ball.mass * ball.radius * ball.radius;
    const int b = m.AddBody(fmt::format("ball{}", i),
                            MassProperties(ball.mass, Vec3::Zero(), RotationalInertia(I, I, I)));
    ContactSpec c;
    c.name = fmt::format("floor{}", i);
    c.shape = ContactShape::kSphere;
    c.body = b;
    c.radius = ball.radius;
    c.mu_s = ball.mu_s;
    c.mu_k = ball.mu_k;
    c.mu_r = ball.mu_r;
    c.restitution = ball.restitution;
    m.AddContact(c);
  }
  m.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -g)));
  return m;
}

/// n balls like `ball`.
inline Model MakeBallsOnFloor(int n, const Ball& ball, double g) {
  return MakeBallsOnFloor(std::vector<Ball>(static_cast<size_t>(n), ball), g);
}

/// t* = 2 R w0 / (7 mu_k g) (Problem 8.26).
inline double StickTime(const Ball& ball, double g, double w0) {
  return 2.0 * ball.radius * w0 / (7.0 * ball.mu_k * g);
}

/// v = 2/7 R w0 (Problem 8.27).
inline double RollingSpeed(const Ball& ball, double w0) {
  return 2.0 / 7.0 * ball.radius * w0;
}

}  // namespace chasles::reference
