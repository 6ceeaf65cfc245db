#pragma once
/// @file
/// A round body on an inclined plane with rolling resistance, pushed along the slope at its
/// centre by F(t) = F0 + c t: the closed forms of its regimes (held, rolling up, rolling down)
/// and a Model of it, shared by the scenario, property and end-to-end tests.
///
/// Coordinates: x up the slope, n the plane's normal, the slope at θ to the horizontal; the
/// body (mass m, radius R, moment of inertia β m R² about its rolling axis) rolls without
/// slipping (Coulomb friction holds it: mu_s is taken large enough). Rolling resistance is a
/// moment of at most mu_r N R at the contact, N = m g cosθ (chapter 8.3, with the resisting
/// moment of a rolling body). Per unit mass the body is driven along x by
///   P(t) = F(t)/m - g sinθ,
/// and rolling resistance can give r = mu_r g cosθ:
///   - held (at rest): the contact holds the moment R |m P| (the friction f = -m P acts at the
///     contact, R below the centre), which it can while |P| <= r;
///   - rolling with velocity v: (m + I/R²) a = m P - sign(v) mu_r N, so
///       a = (P - sign(v) r) / (1 + β).
/// From rest it starts to roll when |P| first exceeds r, in the direction of P; rolling, it
/// stops when v reaches zero, and then holds if |P| <= r (on a slope without push:
/// tanθ <= mu_r), else rolls back.

#include <cmath>
#include <memory>

#include "chasles/model/contact.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles::test {

/// The round body of a case and how it touches the plane.
enum class RollingBody {
  kBall,            ///< uniform sphere, β = 2/5, a sphere contact
  kSphericalShell,  ///< thin spherical shell, β = 2/3, a sphere contact
  kCylinder,        ///< uniform cylinder on its side, β = 1/2, both end rims touch
  kHoop,            ///< thin hoop, β = 1, its rim touches
};

/// β = I / (m R²) about the rolling axis.
inline double RollingInertiaFactor(RollingBody b) {
  switch (b) {
    case RollingBody::kBall:
      return 0.4;
    case RollingBody::kSphericalShell:
      return 2.0 / 3.0;
    case RollingBody::kCylinder:
      return 0.5;
    case RollingBody::kHoop:
      return 1.0;
  }
  return 0.0;
}

struct RollingCase {
  RollingBody body = RollingBody::kBall;
  double m = 0.4, R = 0.05, g = 9.80665;
  double mu_s = 0.8, mu_k = 0.6, mu_r = 0.05;
  /// Slope [rad] (0: level floor).
  double theta = 0.0;
  /// Push along the slope at the centre, F(t) = F0 + c t [N, N/s].
  double F0 = 0.0, c = 0.0;
  /// Initial velocity along the slope (rolling without slipping) [m/s].
  double v0 = 0.0;

  double beta() const { return RollingInertiaFactor(body); }
  /// Drive per unit mass P(t) [m/s²] and what rolling resistance can hold, r [m/s²].
  double P(double t) const { return (F0 + c * t) / m - g * std::sin(theta); }
  double r() const { return mu_r * g * std::cos(theta); }
  /// Acceleration along the slope while rolling in direction `sign` (+1 up, -1 down) [m/s²].
  double RollingAcceleration(double t, double sign) const {
    return (P(t) - sign * r()) / (1.0 + beta());
  }
  /// Whether the body, at rest at time t, is held.
  bool HeldAt(double t) const { return std::abs(P(t)) <= r(); }
  /// With a ramp (c != 0) from rest, held at t = 0: the time |P| reaches r [s] (infinity when
  /// the ramp moves P away from the limit).
  double StartTime() const {
    if (c == 0.0) return INFINITY;
    const double target = c > 0.0 ? r() : -r();
    const double t = (target - P(0.0)) * m / c;
    return t >= 0.0 ? t : INFINITY;
  }
  /// With a constant push (c = 0), rolling at v0: the time the rolling stops [s] (infinity
  /// when it does not decelerate).
  double StopTime() const {
    const double a = RollingAcceleration(0.0, v0 > 0.0 ? 1.0 : -1.0);
    return a * v0 < 0.0 ? -v0 / a : INFINITY;
  }

  /// Plane normal n (towards the body), the slope direction x (up the slope) and the rolling
  /// axis y = n × x (horizontal), in W.
  Vec3 n() const { return {-std::sin(theta), 0.0, std::cos(theta)}; }
  Vec3 x() const { return {std::cos(theta), 0.0, std::sin(theta)}; }

  /// The Model: the body (0) under gravity, its contact with the plane through the origin,
  /// and the push.
  Model BuildModel() const {
    Model model;
    const double I = beta() * m * R * R;
    const double L = 2.0 * R;  // the cylinder's length
    Vec3 diag(I, I, I);
    if (body == RollingBody::kCylinder) {
      const double Ia = m * (3 * R * R + L * L) / 12.0;
      diag = Vec3(Ia, I, Ia);
    } else if (body == RollingBody::kHoop) {
      diag = Vec3(I / 2, I, I / 2);
    }
    model.AddBody(
        "wheel", MassProperties(m, Vec3::Zero(), RotationalInertia::FromMatrix(diag.asDiagonal())));
    model.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -g)));
    ContactSpec spec;
    spec.name = "plane";
    spec.body = 0;
    spec.radius = R;
    spec.mu_s = mu_s, spec.mu_k = mu_k, spec.mu_r = mu_r;
    spec.plane_point_W = Vec3::Zero();
    spec.plane_normal_W = n();
    spec.axis_B = Vec3::UnitY();
    switch (body) {
      case RollingBody::kBall:
      case RollingBody::kSphericalShell:
        spec.shape = ContactShape::kSphere;
        break;
      case RollingBody::kCylinder:
        spec.shape = ContactShape::kCylinder;
        spec.length = L;
        break;
      case RollingBody::kHoop:
        spec.shape = ContactShape::kDiskRim;
        break;
    }
    model.AddContact(spec);
    const Vec3 dir = x();
    const double F0_ = F0, c_ = c;
    model.AddForceElement(std::make_shared<AppliedForce>(
        "push", 0, Vec3::Zero(),
        [dir, F0_, c_](const Model&, const State& s) { return Vec3((F0_ + c_ * s.t) * dir); },
        VectorFrame::kWorld));
    return model;
  }

  /// The initial state: centre at R n, rolling at v0 along x (ω = v0/R about y).
  State InitialState(const Model& model) const {
    State s = MakeRestState(model);
    SetBodyPose(model, 0, R * n(), Quat::Identity(), s);
    SetBodyVelocity(model, 0, v0 * x(), Vec3(0, v0 / R, 0), s);
    return s;
  }
};

}  // namespace chasles::test
