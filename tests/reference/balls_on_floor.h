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

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include <fmt/format.h>

#include "chasles/model/contact.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

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

/// A sphere-sphere contact "pair<i>_<j>" between every two of bodies 0 … n-1, balls of `radius`.
inline void AddSpherePairs(Model& m, int n, double radius, double restitution, double mu = 0.0) {
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      ContactSpec c;
      c.name = fmt::format("pair{}_{}", i, j);
      c.shape = ContactShape::kSphereSphere;
      c.body = i;
      c.other_body = j;
      c.radius = c.other_radius = radius;
      c.restitution = restitution;
      c.mu_s = c.mu_k = mu;
      m.AddContact(c);
    }
  }
}

/// A pool break: balls 1 … n-1 of `radius` at rest in a triangle on the floor, 2 mm apart
/// (each centre moved up to 0.4 mm by a jitter drawn with `seed`), and the cue ball 0 rolling
/// into it at 2 m/s from x = -0.05 m.
inline void SetRack(const Model& m, int n, double radius, unsigned seed, State& s) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.4e-3, 0.4e-3);
  const double R = radius, pitch = 2 * R + 2e-3;
  int k = 1;
  for (int row = 0; k < n; ++row) {
    for (int j = 0; j <= row && k < n; ++j, ++k) {
      const Vec3 p(0.1 + row * pitch * std::sqrt(3.0) / 2 + jitter(rng),
                   (j - row / 2.0) * pitch + jitter(rng), R);
      SetBodyPose(m, k, p, Quat::Identity(), s);
      SetBodyVelocity(m, k, Vec3::Zero(), Vec3::Zero(), s);
    }
  }
  SetBodyPose(m, 0, Vec3(-0.05, 0.0, R), Quat::Identity(), s);
  SetBodyVelocity(m, 0, Vec3(2.0, 0, 0), Vec3(0, 2.0 / R, 0), s);
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
