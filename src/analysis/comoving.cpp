#include "analysis/internal/comoving.h"

#include <algorithm>
#include <cmath>

#include "chasles/dynamics/newton_euler.h"
#include "chasles/math/quaternion.h"
#include "chasles/model/bearing.h"
#include "chasles/model/forces.h"

namespace chasles::internal {

Eigen::VectorXd CalcComovingRates(const Model& model, const State& state, const SteadyGenerator& xi,
                                  Data& data) {
  CalcAccelerations(model, state, data);
  const int n = model.num_bodies();
  Eigen::VectorXd r(12 * n);
  for (int b = 0; b < n; ++b) {
    const auto i = static_cast<size_t>(b);
    const BodyState& s = state.bodies[i];
    const Mat3& R = data.R_WB[i];
    const Vec3 w = data.w_WB_W[i];
    const Vec3 spin = xi.spin.empty() ? Vec3::Zero() : Vec3(xi.spin[i] * (R * xi.spin_axis_B[i]));
    r.segment<3>(6 * b) = s.v_WBcm_W - xi.w_W.cross(s.p_WBcm) - xi.v_W;
    r.segment<3>(6 * b + 3) = w - xi.w_W - spin;
    r.segment<3>(6 * n + 6 * b) = data.a_WBcm_W[i] - xi.w_W.cross(s.v_WBcm_W);
    r.segment<3>(6 * n + 6 * b + 3) = R * data.wdot_WB_B[i] - xi.w_W.cross(w);
  }
  return r;
}

RateScales CalcRateScales(const Model& model, const State& state, const Data& data) {
  RateScales k;
  double length = 0.0;
  for (int b = 0; b < model.num_bodies(); ++b) {
    const Body& body = model.body(b);
    length = std::max({length, std::sqrt(body.I_BBcm_B().trace() / body.mass()),
                       state.bodies[static_cast<size_t>(b)].p_WBcm.norm()});
  }
  k.length = length > 0.0 ? length : 1.0;
  double g = 0.0;
  for (int i = 0; i < model.num_force_elements(); ++i) {
    if (const auto* u = dynamic_cast<const UniformGravity*>(&model.force_element(i))) {
      g = std::max(g, u->g_W().norm());
    }
  }
  for (int b = 0; b < model.num_bodies(); ++b) {
    const auto i = static_cast<size_t>(b);
    k.speed = std::max(k.speed, state.bodies[i].v_WBcm_W.norm());
    k.rate = std::max(k.rate, data.w_WB_W[i].norm());
    g = std::max({g, data.a_WBcm_W[i].norm(), data.wdot_WB_B[i].norm() * k.length});
  }
  k.accel = std::max({g, k.speed * k.speed / k.length, k.rate * k.rate * k.length});
  return k;
}

double ScaledResidual(const Eigen::VectorXd& rates, const RateScales& s) {
  const int n = static_cast<int>(rates.size()) / 12;
  const double v = std::max(s.speed, s.rate * s.length);
  const double a = s.accel;
  double worst = 0.0;
  for (int b = 0; b < n; ++b) {
    const double dv =
        std::max(rates.segment<3>(6 * b).norm(), rates.segment<3>(6 * b + 3).norm() * s.length);
    const double da = std::max(rates.segment<3>(6 * n + 6 * b).norm(),
                               rates.segment<3>(6 * n + 6 * b + 3).norm() * s.length);
    // Nothing moves and nothing pushes: the rates are the values themselves.
    worst = std::max(worst, v > 0.0 ? dv / v : dv);
    worst = std::max(worst, a > 0.0 ? da / a : da);
  }
  return worst;
}

State PerturbState(const Model& model, const State& state, const Eigen::VectorXd& z, double h) {
  State s = state;
  const int n = model.num_bodies();
  for (int b = 0; b < n; ++b) {
    BodyState& bs = s.bodies[static_cast<size_t>(b)];
    const Vec3 w_W = bs.q_WB * bs.w_WB_B;
    bs.p_WBcm += h * z.segment<3>(6 * b);
    bs.q_WB = (QuatExp(h * Vec3(z.segment<3>(6 * b + 3))) * bs.q_WB).normalized();
    bs.v_WBcm_W += h * z.segment<3>(6 * n + 6 * b);
    bs.w_WB_B = bs.q_WB.conjugate() * (w_W + h * Vec3(z.segment<3>(6 * n + 6 * b + 3)));
  }
  return s;
}

SteadyGenerator ZeroGenerator(const Model& model) {
  SteadyGenerator g;
  g.spin.assign(static_cast<size_t>(model.num_bodies()), 0.0);
  g.spin_axis_B.assign(static_cast<size_t>(model.num_bodies()), Vec3::Zero());
  return g;
}

// Whether nothing ties the system to a place: no constraint, spring or bearing to the world (then
// its centre of mass moves freely, and in a turning frame its drift is a frame's artefact).
bool TranslationInvariant(const Model& model) {
  for (int c = 0; c < model.num_constraints(); ++c) {
    if (model.constraint(c).parent() == kWorld) return false;
  }
  for (int i = 0; i < model.num_force_elements(); ++i) {
    const ForceElement& e = model.force_element(i);
    if (const auto* s = dynamic_cast<const SpringDamper*>(&e)) {
      if (s->body_b() == kWorld) return false;
    }
    if (dynamic_cast<const Bearing*>(&e) != nullptr) return false;
  }
  return true;
}

bool TorqueFree(const Model& model) {
  if (!TranslationInvariant(model)) return false;
  for (int i = 0; i < model.num_force_elements(); ++i) {
    const ForceElement& e = model.force_element(i);
    if (dynamic_cast<const SpringDamper*>(&e) != nullptr) continue;  // between two bodies
    const auto* g = dynamic_cast<const UniformGravity*>(&e);
    if (g == nullptr || g->g_W().norm() > 0.0) return false;
  }
  return true;
}

}  // namespace chasles::internal
