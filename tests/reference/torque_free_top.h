#pragma once
/// @file
/// The Dzhanibekov body as a reference for the integrators' round-off (the RK4 test and
/// bench/dzhanibekov_bench.cpp): principal moments I = (1, 2, 3) kg·m², no force,
/// ω₀ = (0.01, 10, 0.01) rad/s about the unstable middle axis. Euler's equations (chapter
/// eqs. 8.79-8.81) with M = 0,
///   I₁ ω̇₁ = (I₂ − I₃) ω₂ ω₃,  I₂ ω̇₂ = (I₃ − I₁) ω₃ ω₁,  I₃ ω̇₃ = (I₁ − I₂) ω₁ ω₂,
/// and q̇ = ½ q ⊗ (0, ω_B), integrated by a plain hand-written classical RK4 in any floating
/// type T: in long double it is the reference; in double, the uncompensated update.

#include <cmath>

#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles::reference {

inline constexpr double kI[3] = {1.0, 2.0, 3.0};      // principal moments [kg·m²]
inline constexpr double kW0[3] = {0.01, 10.0, 0.01};  // initial ω in B [rad/s]

/// ω in B (3) and q (w, x, y, z) (4).
template <typename T>
struct Top {
  T y[7];
};

template <typename T>
Top<T> Derivative(const Top<T>& s) {
  const T* w = s.y;
  const T* q = s.y + 3;
  const T I0 = kI[0], I1 = kI[1], I2 = kI[2];
  Top<T> d;
  d.y[0] = (I1 - I2) * w[1] * w[2] / I0;  // eqs. 8.79-8.81 with M = 0
  d.y[1] = (I2 - I0) * w[2] * w[0] / I1;
  d.y[2] = (I0 - I1) * w[0] * w[1] / I2;
  // q̇ = ½ q ⊗ (0, ω): scalar −½ q_v·ω, vector ½ (q_w ω + q_v × ω).
  d.y[3] = T(-0.5) * (q[1] * w[0] + q[2] * w[1] + q[3] * w[2]);
  d.y[4] = T(0.5) * (q[0] * w[0] + q[2] * w[2] - q[3] * w[1]);
  d.y[5] = T(0.5) * (q[0] * w[1] + q[3] * w[0] - q[1] * w[2]);
  d.y[6] = T(0.5) * (q[0] * w[2] + q[1] * w[1] - q[2] * w[0]);
  return d;
}

/// n classical RK4 steps of h from ω₀ and q = 1 with plain (uncompensated) updates, q
/// renormalised after each step as chasles does.
template <typename T>
Top<T> PlainRk4(T h, long n) {
  Top<T> s{{T(kW0[0]), T(kW0[1]), T(kW0[2]), T(1), T(0), T(0), T(0)}};
  const auto axpy = [](const Top<T>& a, T c, const Top<T>& k) {
    Top<T> r;
    for (int i = 0; i < 7; ++i) r.y[i] = a.y[i] + c * k.y[i];
    return r;
  };
  for (long step = 0; step < n; ++step) {
    const Top<T> k1 = Derivative(s);
    const Top<T> k2 = Derivative(axpy(s, h / 2, k1));
    const Top<T> k3 = Derivative(axpy(s, h / 2, k2));
    const Top<T> k4 = Derivative(axpy(s, h, k3));
    for (int i = 0; i < 7; ++i) s.y[i] += h / 6 * (k1.y[i] + 2 * (k2.y[i] + k3.y[i]) + k4.y[i]);
    const T norm = std::sqrt(s.y[3] * s.y[3] + s.y[4] * s.y[4] + s.y[5] * s.y[5] + s.y[6] * s.y[6]);
    for (int i = 3; i < 7; ++i) s.y[i] /= norm;
  }
  return s;
}

/// Angle of the rotation between two orientations, 2 atan2(|v|, |w|) of q_a* ⊗ q_b [rad].
template <typename A, typename B>
double Angle(const Top<A>& ra, const Top<B>& rb) {
  long double a[4], b[4];
  for (int i = 0; i < 4; ++i) a[i] = ra.y[3 + i], b[i] = rb.y[3 + i];
  const long double w = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
  const long double x = a[0] * b[1] - a[1] * b[0] - a[2] * b[3] + a[3] * b[2];
  const long double y = a[0] * b[2] + a[1] * b[3] - a[2] * b[0] - a[3] * b[1];
  const long double z = a[0] * b[3] - a[1] * b[2] + a[2] * b[1] - a[3] * b[0];
  return static_cast<double>(2 * std::atan2(std::sqrt(x * x + y * y + z * z), std::fabs(w)));
}

/// The state of chasles' body 0 as a Top.
inline Top<double> FromState(const State& s) {
  const BodyState& b = s.bodies[0];
  return {
      {b.w_WB_B.x(), b.w_WB_B.y(), b.w_WB_B.z(), b.q_WB.w(), b.q_WB.x(), b.q_WB.y(), b.q_WB.z()}};
}

/// The body as a chasles Model (unit mass at the origin), and its initial state.
inline Model DzhanibekovModel() {
  Model m;
  m.AddBody("top", MassProperties(1.0, Vec3::Zero(), RotationalInertia(kI[0], kI[1], kI[2])));
  return m;
}

inline State DzhanibekovStart(const Model& m) {
  State s = MakeRestState(m);
  s.bodies[0].w_WB_B = Vec3(kW0[0], kW0[1], kW0[2]);
  return s;
}

}  // namespace chasles::reference
