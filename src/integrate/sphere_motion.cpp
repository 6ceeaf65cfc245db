// A ball's motion on the plane in closed form between events: flight, sliding, rolling and
// rest, and its orientation (docs/contact.md, "Event-driven spheres").
#include "integrate/internal/sphere_runner.h"

namespace chasles::sphere_events_detail {

ContactMode ModeOfPhase(Phase p) {
  switch (p) {
    case Phase::kFlight:
      return ContactMode::kSeparated;
    case Phase::kSliding:
      return ContactMode::kSliding;
    default:
      return ContactMode::kSticking;
  }
}

// Orientation after τ of ω(s) = w0 + alpha s, q' = ½ ω q (ω in W). A fixed axis (alpha ∥ w0)
// is exact: the rotation vector is ∫ω. Otherwise fourth-order Magnus steps (Iserles and
// Nørsett 1999): over a step h from ω_k, Ω = h ω(h/2) + (h³/12) alpha × ω_k (the two terms are
// exact for a linear ω; the rest is about h⁵ |alpha||ω|(|ω| + |alpha| h) / 720), with h chosen
// so that each step's remainder is below 1e-12 rad. The orientation does not enter a ball's
// motion (isotropic inertia, sphere at the centre of mass); it is computed only for the output.
Quat Orient(const Vec3& w0, const Vec3& alpha, const Quat& q0, double tau) {
  if (tau <= 0.0) return q0;
  const Vec3 cross = alpha.cross(w0);
  if (cross.squaredNorm() <= 1e-30 * alpha.squaredNorm() * w0.squaredNorm()) {
    Quat q = QuatExp(w0 * tau + 0.5 * tau * tau * alpha) * q0;
    return q.normalized();
  }
  const double wa = w0.norm() + alpha.norm() * tau;
  const double bound = alpha.norm() * wa * wa;
  const double h_max = std::pow(720e-12 / bound, 0.2);
  const int n = std::max(1, static_cast<int>(std::ceil(tau / h_max)));
  const double h = tau / n;
  Quat q = q0;
  for (int k = 0; k < n; ++k) {
    const Vec3 wk = w0 + (k * h) * alpha;
    const Vec3 omega = h * (wk + 0.5 * h * alpha) + (h * h * h / 12.0) * alpha.cross(wk);
    q = QuatExp(omega) * q;
  }
  return q.normalized();
}

// The segment a ball starts at time t with (r, v, ω, q). `on_plane`: touching the plane with
// no normal velocity (n·v is removed); then sliding when the slip exceeds stick_speed,
// rolling (ω's part along the plane set to n × v / R) otherwise, rest when v = 0.
Segment StartSegment(const Ball& b, const World& w, double t, const Vec3& r, const Vec3& v,
                     const Vec3& om, const Quat& q, bool on_plane, bool force_roll) {
  Segment s;
  s.t0 = t;
  s.r0 = r;
  s.q0 = q;
  s.a = Vec3::Zero();
  s.alpha = Vec3::Zero();
  if (!on_plane) {
    // Flight: h(τ) = h0 + v_n τ - ½ g τ² reaches 0 at the larger root.
    s.phase = Phase::kFlight;
    s.v0 = v;
    s.w0 = om;
    s.a = w.g_W;
    const double h0 = std::max(w.n.dot(r - w.p0) - b.R, 0.0);
    const double vn = w.n.dot(v);
    s.dur = (vn + std::sqrt(vn * vn + 2.0 * w.g * h0)) / w.g;
    return s;
  }
  const Vec3 vh = v - w.n.dot(v) * w.n;
  const double spin = w.n.dot(om);
  const Vec3 u = vh - b.R * om.cross(w.n);  // slip of the material point at C
  const double slip = u.norm();
  if (!force_roll && slip > w.tol.stick_speed && b.mu_k > 0.0) {
    // Sliding (8.3): u̇ = -mu_k g (1 + m R²/I) ŝ, so ŝ stays and |u| falls linearly.
    s.phase = Phase::kSliding;
    s.v0 = vh;
    s.w0 = om;
    s.s_hat = u / slip;
    s.slip0 = slip;
    s.a = -b.mu_k * w.g * s.s_hat;
    s.alpha = (b.mu_k * b.m * w.g * b.R / b.I) * w.n.cross(s.s_hat);
    s.dur = slip / (b.mu_k * w.g * (1.0 + b.kappa));
    return s;
  }
  if (!force_roll && slip > w.tol.stick_speed) {
    // Frictionless plane: slides for ever with constant v and ω.
    s.phase = Phase::kSliding;
    s.v0 = vh;
    s.w0 = om;
    s.s_hat = u / slip;
    s.slip0 = slip;
    s.dur = kInf;
    return s;
  }
  const double speed = vh.norm();
  s.v0 = vh;
  s.w0 = spin * w.n + w.n.cross(vh) / b.R;
  if (speed == 0.0) {
    s.phase = Phase::kRest;
    s.dur = kInf;
    return s;
  }
  s.phase = Phase::kRolling;
  if (b.mu_r > 0.0) {
    // Rolling resistance mu_r N R against the rolling: v̇ = -mu_r g v̂ / (1 + I/(m R²)).
    s.a = -(b.mu_r * w.g / (1.0 + 1.0 / b.kappa)) * (vh / speed);
    s.alpha = w.n.cross(s.a) / b.R;
    s.dur = speed / s.a.norm();
  }
  return s;
}

// The deterministic continuation of a contact segment at its end (sliding → rolling →
// rest). Flight has none: its end is an impact.
Segment NextSegment(const Ball& b, const World& w, const Segment& s) {
  const double t = s.end();
  const Quat q = Quat::Identity();  // only a chain's first segment carries q (ChainOrient)
  if (s.phase == Phase::kSliding) {
    return StartSegment(b, w, t, s.Pos(t), s.Vel(t), s.Omega(t), q, true, true);
  }
  // Rolling stopped: rest, spinning about n.
  Segment r;
  r.phase = Phase::kRest;
  r.t0 = t;
  r.r0 = s.Pos(t);
  r.v0 = Vec3::Zero();
  r.w0 = w.n.dot(s.w0) * w.n;
  r.a = r.alpha = Vec3::Zero();
  r.q0 = q;
  r.dur = kInf;
  return r;
}

// The orientation at t along a chain, from its first segment's q0.
Quat ChainOrient(const Chain& c, double t) {
  Quat q = c.seg[0].q0;
  for (int k = 0; k < c.count; ++k) {
    const Segment& s = c.seg[static_cast<size_t>(k)];
    const double te = std::min(t, s.end());
    if (te > s.t0) q = Orient(s.w0, s.alpha, q, te - s.t0);
    if (t <= s.end()) break;
  }
  return q;
}

Chain MakeChain(const Ball& b, const World& w, const Segment& first) {
  Chain c;
  c.seg[0] = first;
  c.count = 1;
  if (first.phase == Phase::kFlight) {
    c.known_until = first.end();
    return c;
  }
  while (c.count < 3 && std::isfinite(c.seg[static_cast<size_t>(c.count - 1)].dur)) {
    c.seg[static_cast<size_t>(c.count)] =
        NextSegment(b, w, c.seg[static_cast<size_t>(c.count - 1)]);
    ++c.count;
  }
  return c;
}

}  // namespace chasles::sphere_events_detail
