#include "chasles/model/state.h"

#include <cmath>

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/model/model.h"

namespace chasles {

State MakeRestState(const Model& model) {
  State s;
  s.t = 0.0;
  BodyState rest;
  rest.p_WBcm.setZero();
  rest.q_WB = Quat::Identity();
  rest.v_WBcm_W.setZero();
  rest.w_WB_B.setZero();
  s.bodies.assign(static_cast<size_t>(model.num_bodies()), rest);
  s.force_integrals.assign(static_cast<size_t>(model.num_force_elements()), ForceIntegrals{});
  s.constraint_work.assign(static_cast<size_t>(model.num_constraints()), 0.0);
  s.contacts.assign(static_cast<size_t>(model.num_contact_points()), ContactPointState{});
  return s;
}

void SetBodyPose(const Model& model, int b, const Vec3& p_WBo, const Quat& q_WB, State& state) {
  const double n = q_WB.norm();
  if (!std::isfinite(n) || n == 0.0) {
    throw InputError(fmt::format("body '{}': orientation quaternion has no direction; give a "
                                 "non-zero (w, x, y, z)",
                                 model.body(b).name()),
                     ErrorElement{ErrorElement::Kind::kBody, b});
  }
  BodyState& bs = state.bodies[static_cast<size_t>(b)];
  bs.q_WB = q_WB.normalized();
  bs.p_WBcm = p_WBo + bs.q_WB * model.body(b).p_BoBcm_B();
}

void SetBodyVelocity(const Model& model, int b, const Vec3& v_WBo_W, const Vec3& w_WB_W,
                     State& state) {
  BodyState& bs = state.bodies[static_cast<size_t>(b)];
  const Vec3 p_BoBcm_W = bs.q_WB * model.body(b).p_BoBcm_B();
  bs.v_WBcm_W = v_WBo_W + w_WB_W.cross(p_BoBcm_W);
  bs.w_WB_B = bs.q_WB.conjugate() * w_WB_W;
}

Vec3 CalcBodyOriginPosition(const Model& model, const State& state, int b) {
  const BodyState& bs = state.bodies[static_cast<size_t>(b)];
  return bs.p_WBcm - bs.q_WB.normalized() * model.body(b).p_BoBcm_B();
}

void ValidateState(const Model& model, const State& state) {
  if (state.bodies.size() != static_cast<size_t>(model.num_bodies()) ||
      state.force_integrals.size() != static_cast<size_t>(model.num_force_elements()) ||
      (!state.constraint_work.empty() &&
       state.constraint_work.size() != static_cast<size_t>(model.num_constraints()))) {
    throw InputError(fmt::format(
        "state has {} bodies, {} force integrals and {} constraint work entries but the model "
        "has {} bodies, {} force elements and {} constraints; make the state with "
        "MakeRestState(model)",
        state.bodies.size(), state.force_integrals.size(), state.constraint_work.size(),
        model.num_bodies(), model.num_force_elements(), model.num_constraints()));
  }
  if (!state.contacts.empty() &&
      state.contacts.size() != static_cast<size_t>(model.num_contact_points())) {
    throw InputError(fmt::format(
        "state has {} contact point entries but the model has {} contact points; make the "
        "state with MakeRestState(model) or leave its contacts empty",
        state.contacts.size(), model.num_contact_points()));
  }
  if (!std::isfinite(state.t)) throw InputError("state time is not a finite number");
  for (int b = 0; b < model.num_bodies(); ++b) {
    const BodyState& bs = state.bodies[static_cast<size_t>(b)];
    const char* bad = !bs.p_WBcm.allFinite()          ? "position"
                      : !bs.q_WB.coeffs().allFinite() ? "orientation"
                      : !bs.v_WBcm_W.allFinite()      ? "velocity"
                      : !bs.w_WB_B.allFinite()        ? "angular velocity"
                                                      : nullptr;
    if (bad) {
      throw InputError(
          fmt::format("body '{}': {} is not finite at t = {:.9g} s; set every component",
                      model.body(b).name(), bad, state.t),
          ErrorElement{ErrorElement::Kind::kBody, b});
    }
    if (std::abs(bs.q_WB.norm() - 1.0) > 1e-6) {
      throw InputError(
          fmt::format(
              "body '{}': orientation quaternion has norm {:.9g}; it must be a unit quaternion "
              "(within 1e-6): use SetBodyPose, which normalises it",
              model.body(b).name(), bs.q_WB.norm()),
          ErrorElement{ErrorElement::Kind::kBody, b});
    }
  }
}

}  // namespace chasles
