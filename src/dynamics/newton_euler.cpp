#include "chasles/dynamics/newton_euler.h"

#include "chasles/dynamics/constraint_solve.h"
#include "chasles/dynamics/contact_solve.h"
#include "chasles/error.h"

namespace chasles {

void CalcKinematics(const Model& model, const State& state, Data& data) {
  CheckDataFor(model, data);
  for (int b = 0; b < model.num_bodies(); ++b) {
    const auto i = static_cast<size_t>(b);
    const BodyState& bs = state.bodies[i];
    // The integrators keep |q| = 1 to round-off; normalising here makes R exactly orthogonal
    // at intermediate stages too.
    data.R_WB[i] = bs.q_WB.normalized().toRotationMatrix();
    data.w_WB_W[i] = data.R_WB[i] * bs.w_WB_B;
  }
}

void CalcForces(const Model& model, const State& state, Data& data) {
  CheckDataFor(model, data);
  for (int b = 0; b < model.num_bodies(); ++b) {
    data.F_Bcm_W[static_cast<size_t>(b)].setZero();
    data.M_Bcm_W[static_cast<size_t>(b)].setZero();
  }
  WrenchAccumulator acc(state, data);
  for (int e = 0; e < model.num_force_elements(); ++e) {
    ForceElementOutput& out = data.elements[static_cast<size_t>(e)];
    acc.Begin(&out);
    const ForceElement& fe = model.force_element(e);
    try {
      const double p_nc = fe.AddForces(model, state, data, acc);
      out.power_nonconservative = fe.has_potential() ? p_nc : out.power;
    } catch (const InputError& x) {
      RethrowForElement(x, {ErrorElement::Kind::kForceElement, e});
    }
  }
}

Vec3 CalcEulerAngularAcceleration(const Mat3& I, const Mat3& I_inv, const Vec3& w,
                                  const Vec3& M_B) {
  return I_inv * (M_B - w.cross(I * w));
}

void CalcAccelerations(const Model& model, const State& state, Data& data) {
  CheckDataFor(model, data);
  CalcKinematics(model, state, data);
  CalcForces(model, state, data);
  for (int b = 0; b < model.num_bodies(); ++b) {
    const auto i = static_cast<size_t>(b);
    const Body& body = model.body(b);
    data.a_WBcm_W[i] = data.F_Bcm_W[i] / body.mass();
    const Vec3 M_B = data.R_WB[i].transpose() * data.M_Bcm_W[i];
    data.wdot_WB_B[i] = CalcEulerAngularAcceleration(body.I_BBcm_B(), body.I_BBcm_B_inverse(),
                                                     state.bodies[i].w_WB_B, M_B);
  }
  // One branch: unconstrained models pay nothing for the constraint stage. The contact stage
  // solves constraints and active contact rows together.
  if (model.num_contacts() > 0) {
    SolveContactForces(model, state, data);
  } else if (model.num_constraints() > 0) {
    SolveConstraintForces(model, state, data);
  }
}

}  // namespace chasles
