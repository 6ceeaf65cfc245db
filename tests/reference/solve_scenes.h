#pragma once
/// @file
/// The chains and piles of the sparse-solve tests and bench/solve_bench.cpp: n bodies whose
/// constraint or contact rows each touch one or two bodies.
///  - Hanging chain: n rods linked by revolute joints, the first hinged to the world at the
///    origin; at rest along -z, or (seeded) in a random zig-zag with random axes, masses,
///    inertias and velocities (the velocities projected onto the joints).
///  - Row pile: n spheres on the floor z = 0, each touching the next (sphere-sphere contacts),
///    radii random or equal; every point sticking, or the floor points sliding.

#include <cmath>
#include <memory>
#include <random>
#include <string>

#include "chasles/dynamics/constraint_solve.h"
#include "chasles/math/quaternion.h"
#include "chasles/math/rotation.h"
#include "chasles/model/constraints.h"
#include "chasles/model/contact.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles::reference {

inline constexpr double kGravity = 9.81;

struct Scene {
  Model model;
  State state;
};

inline Vec3 RandomUnit(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Vec3(n(rng), n(rng), n(rng)).normalized();
}

/// A rod of mass m, length L along its body z, as a box of small cross-section.
inline MassProperties Rod(double m, double L, double a) {
  const double Ix = m * (L * L + a * a) / 12;
  return MassProperties(m, Vec3::Zero(), RotationalInertia(Ix, Ix, m * a * a / 6));
}

/// The chain of `n` rods of length `L`; `masses[i]` (size n) the rods' masses. With `rng`
/// null it hangs at rest straight down (joint i at z = -i L, axes along x); otherwise the
/// rods point in random directions, the joint axes are random, the inertias are perturbed and
/// the velocities are random (then projected onto the constraints).
inline Scene MakeChain(int n, const std::vector<double>& masses, double L,
                       std::mt19937* rng = nullptr) {
  Scene s;
  std::uniform_real_distribution<double> u(0.5, 1.5);
  for (int i = 0; i < n; ++i) {
    const double m = masses[static_cast<size_t>(i)];
    MassProperties mp = Rod(m, L, 0.05 * L);
    if (rng != nullptr) {
      // A box of random sides (a, b, c): I = m (b² + c², c² + a², a² + b²) / 12.
      const double a = 0.1 * L * u(*rng), b = 0.5 * L * u(*rng), c = L * u(*rng);
      mp = MassProperties(m, Vec3::Zero(),
                          RotationalInertia(m * (b * b + c * c) / 12, m * (c * c + a * a) / 12,
                                            m * (a * a + b * b) / 12));
    }
    s.model.AddBody("link" + std::to_string(i), mp);
  }
  s.model.AddForceElement(std::make_shared<UniformGravity>("g", Vec3(0, 0, -kGravity)));
  s.state = MakeRestState(s.model);
  Vec3 top = Vec3::Zero();
  std::vector<Vec3> tops;
  for (int i = 0; i < n; ++i) {
    const Vec3 d = rng != nullptr ? RandomUnit(*rng) : Vec3(0, 0, -1);
    const Quat q = rng != nullptr ? QuatExp(3.0 * RandomUnit(*rng)) : Quat::Identity();
    // Body z along d: the rod's axis (only the inertia's orientation depends on q otherwise).
    const Mat3 R = FrameWithZAxis(d) * q.toRotationMatrix();
    SetBodyPose(s.model, i, top + 0.5 * L * d, Quat(rng != nullptr ? R : Mat3::Identity()),
                s.state);
    tops.push_back(top);
    top += L * d;
  }
  for (int i = 0; i < n; ++i) {
    const Mat3 axes =
        rng != nullptr ? FrameWithZAxis(RandomUnit(*rng)) : FrameWithZAxis(Vec3::UnitX());
    const Vec3 p = tops[static_cast<size_t>(i)];
    const BodyIndex parent = i == 0 ? kWorld : i - 1;
    const AttachmentFrame Xp = parent == kWorld
                                   ? AttachmentFrame{p, axes}
                                   : AttachmentFrameAtWorldPose(s.model, s.state, parent, p, axes);
    s.model.AddConstraint(
        std::make_shared<Joint>("joint" + std::to_string(i), JointKind::kRevolute, parent, Xp, i,
                                AttachmentFrameAtWorldPose(s.model, s.state, i, p, axes)));
  }
  s.state = [&] {
    State st = MakeRestState(s.model);
    for (int i = 0; i < n; ++i)
      st.bodies[static_cast<size_t>(i)] = s.state.bodies[static_cast<size_t>(i)];
    return st;
  }();
  if (rng != nullptr) {
    std::uniform_real_distribution<double> v(-1.0, 1.0);
    for (BodyState& b : s.state.bodies) {
      b.v_WBcm_W = Vec3(v(*rng), v(*rng), v(*rng));
      b.w_WB_B = 3.0 * Vec3(v(*rng), v(*rng), v(*rng));
    }
    Data data = MakeData(s.model);
    ProjectOntoConstraints(s.model, s.state, data);
  }
  return s;
}

/// MakeChain(n, masses, L) hanging at rest, the far end of its last rod touching a frictionless
/// wall with normal ŷ (the direction its joints, axes along x, let it swing): 5 n joint rows and
/// one normal row. The end stays on the wall with no force (nothing pushes it against the wall)
/// and each joint carries the weight below it.
inline Scene MakeChainOnWall(int n, const std::vector<double>& masses, double L) {
  Scene s = MakeChain(n, masses, L);
  const BodyState& b = s.state.bodies[static_cast<size_t>(n - 1)];
  const Vec3 tip(0, 0, -n * L);
  ContactSpec c;
  c.name = "wall";
  c.shape = ContactShape::kPointSet;
  c.body = n - 1;
  c.points_B = {b.q_WB.toRotationMatrix().transpose() * (tip - b.p_WBcm)};
  c.plane_point_W = tip;
  c.plane_normal_W = Vec3::UnitY();
  s.model.AddContact(c);
  s.state.contacts.assign(1, ContactPointState{});
  return s;
}

/// The row of `n` spheres of radius radii[i] and mass masses[i] on the floor z = 0, each
/// touching the next: centres at height R_i, 2 √(R_i R_{i+1}) apart along x. The floor points
/// stick, or slide along +x (each sphere moving at 1 m/s along x without spin) with
/// `sliding`; the sphere-sphere points stick. mu_s = 0.6, mu_k = 0.3.
inline Scene MakeRowPile(int n, const std::vector<double>& radii, const std::vector<double>& masses,
                         bool sliding) {
  Scene s;
  for (int i = 0; i < n; ++i) {
    const double R = radii[static_cast<size_t>(i)], m = masses[static_cast<size_t>(i)];
    const double I = 0.4 * m * R * R;
    s.model.AddBody("ball" + std::to_string(i),
                    MassProperties(m, Vec3::Zero(), RotationalInertia(I, I, I)));
  }
  for (int i = 0; i < n; ++i) {
    ContactSpec c;
    c.name = "floor" + std::to_string(i);
    c.shape = ContactShape::kSphere;
    c.body = i;
    c.radius = radii[static_cast<size_t>(i)];
    c.mu_s = 0.6;
    c.mu_k = 0.3;
    s.model.AddContact(c);
  }
  for (int i = 0; i + 1 < n; ++i) {
    ContactSpec c;
    c.name = "touch" + std::to_string(i);
    c.shape = ContactShape::kSphereSphere;
    c.body = i + 1;
    c.other_body = i;
    c.radius = radii[static_cast<size_t>(i) + 1];
    c.other_radius = radii[static_cast<size_t>(i)];
    c.mu_s = 0.6;
    c.mu_k = 0.3;
    s.model.AddContact(c);
  }
  s.model.AddForceElement(std::make_shared<UniformGravity>("g", Vec3(0, 0, -kGravity)));
  s.state = MakeRestState(s.model);
  double x = 0.0;
  for (int i = 0; i < n; ++i) {
    const double R = radii[static_cast<size_t>(i)];
    if (i > 0) x += 2.0 * std::sqrt(R * radii[static_cast<size_t>(i) - 1]);
    SetBodyPose(s.model, i, Vec3(x, 0, R), Quat::Identity(), s.state);
    if (sliding) SetBodyVelocity(s.model, i, Vec3(1, 0, 0), Vec3::Zero(), s.state);
  }
  s.state.contacts.assign(static_cast<size_t>(s.model.num_contact_points()), ContactPointState{});
  for (int p = 0; p < s.model.num_contact_points(); ++p) {
    ContactPointState& ps = s.state.contacts[static_cast<size_t>(p)];
    const bool floor = p < n;
    ps.mode = floor && sliding ? ContactMode::kSliding : ContactMode::kSticking;
    if (ps.mode == ContactMode::kSliding) ps.slip_direction_W = Vec3::UnitX();
  }
  return s;
}

}  // namespace chasles::reference
