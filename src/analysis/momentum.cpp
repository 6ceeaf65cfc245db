#include "chasles/analysis/momentum.h"

namespace chasles {

double CalcTranslationalKineticEnergy(const Model& model, const State& s) {
  double T = 0.0;
  for (int b = 0; b < model.num_bodies(); ++b) {
    T += 0.5 * model.body(b).mass() * s.bodies[static_cast<size_t>(b)].v_WBcm_W.squaredNorm();
  }
  return T;
}

double CalcRotationalKineticEnergy(const Model& model, const State& s) {
  double T = 0.0;
  for (int b = 0; b < model.num_bodies(); ++b) {
    const Vec3& w = s.bodies[static_cast<size_t>(b)].w_WB_B;
    T += 0.5 * w.dot(model.body(b).I_BBcm_B() * w);
  }
  return T;
}

Vec3 CalcLinearMomentum(const Model& model, const State& s) {
  Vec3 P = Vec3::Zero();
  for (int b = 0; b < model.num_bodies(); ++b) {
    P += model.body(b).mass() * s.bodies[static_cast<size_t>(b)].v_WBcm_W;
  }
  return P;
}

Vec3 CalcSystemCenterOfMass(const Model& model, const State& s) {
  Vec3 c = Vec3::Zero();
  double m = 0.0;
  for (int b = 0; b < model.num_bodies(); ++b) {
    c += model.body(b).mass() * s.bodies[static_cast<size_t>(b)].p_WBcm;
    m += model.body(b).mass();
  }
  return m > 0.0 ? Vec3(c / m) : Vec3::Zero();
}

Vec3 CalcAngularMomentum(const Model& model, const State& s, const Vec3& p_WQ) {
  Vec3 H = Vec3::Zero();
  for (int b = 0; b < model.num_bodies(); ++b) {
    const BodyState& bs = s.bodies[static_cast<size_t>(b)];
    const Body& body = model.body(b);
    H += bs.q_WB.normalized() * (body.I_BBcm_B() * bs.w_WB_B) +
         (bs.p_WBcm - p_WQ).cross(body.mass() * bs.v_WBcm_W);
  }
  return H;
}

}  // namespace chasles
