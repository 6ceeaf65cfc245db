#include "chasles/dynamics/constraint_residual.h"

#include <algorithm>
#include <cmath>

#include "chasles/dynamics/constraint_solve.h"
#include "chasles/dynamics/newton_euler.h"
#include "dynamics/internal/generalized.h"

namespace chasles {

bool IsMomentRow(const ConstraintEval& eval, int k) {
  return eval.J_child.block<1, 3>(k, 0).isZero(0.0) && eval.J_parent.block<1, 3>(k, 0).isZero(0.0);
}

ConstraintScales CalcConstraintScales(const Model& model, const State& state, Data& data) {
  CheckDataFor(model, data);
  ConstraintScales s;
  CalcKinematics(model, state, data);
  CalcConstraintRows(model, state, data);
  double w_max = 0.0, v_max = 0.0;
  for (int b = 0; b < model.num_bodies(); ++b) {
    const Body& body = model.body(b);
    const BodyState& bs = state.bodies[static_cast<size_t>(b)];
    s.length =
        std::max({s.length, std::sqrt(body.I_BBcm_B().trace() / body.mass()), bs.p_WBcm.norm()});
    v_max = std::max(v_max, bs.v_WBcm_W.norm());
    w_max = std::max(w_max, bs.w_WB_B.norm());
  }
  double rate_linear = 0.0, rate_angular = 0.0;
  for (int c = 0; c < model.num_constraints(); ++c) {
    const ConstraintEval& e = data.constraint_rows[static_cast<size_t>(c)];
    s.length = std::max(s.length, e.p_WJ.norm());
    for (int k = 0; k < model.constraint(c).num_rows(); ++k) {
      double& rate = IsMomentRow(e, k) ? rate_angular : rate_linear;
      rate = std::max(rate, std::abs(e.velocity_rhs[k]));
    }
  }
  s.velocity = std::max({v_max, w_max * s.length, rate_linear, rate_angular * s.length});
  return s;
}

std::vector<ConstraintResidual> FindConstraintViolations(const Model& model, const State& state,
                                                         Data& data, const ConstraintScales& scales,
                                                         double relative_tolerance) {
  CheckDataFor(model, data);
  std::vector<ConstraintResidual> out;
  if (model.num_constraints() == 0) return out;
  CalcKinematics(model, state, data);
  CalcConstraintRows(model, state, data);
  internal::GetVelocity(model, state, data, data.u);
  Eigen::VectorXd res(model.num_constraint_rows());
  internal::ConstraintJacobianTimes(model, data, data.u, res);  // O(rows) on the sparse path
  res -= data.velocity_rhs;
  const double tol_length = relative_tolerance * scales.length;
  const double tol_angle = relative_tolerance;
  const double tol_speed = relative_tolerance * scales.velocity;
  const double tol_rate = scales.length > 0.0 ? tol_speed / scales.length : tol_speed;
  for (int c = 0; c < model.num_constraints(); ++c) {
    const ConstraintEval& e = data.constraint_rows[static_cast<size_t>(c)];
    const int o = model.constraint_row_offset(c);
    ConstraintResidual r;
    r.constraint = c;
    for (int k = 0; k < model.constraint(c).num_rows(); ++k) {
      const bool moment = IsMomentRow(e, k);
      const double g = e.holonomic[static_cast<size_t>(k)] ? std::abs(e.position_error[k]) : 0.0;
      const double dv = std::abs(res[o + k]);
      if (moment) {
        r.position_angle = std::max(r.position_angle, g);
        r.velocity_angular = std::max(r.velocity_angular, dv);
      } else {
        r.position_length = std::max(r.position_length, g);
        r.velocity_linear = std::max(r.velocity_linear, dv);
      }
    }
    r.position_violated = r.position_length > tol_length || r.position_angle > tol_angle;
    r.velocity_violated = r.velocity_linear > tol_speed || r.velocity_angular > tol_rate;
    if (r.position_violated || r.velocity_violated) out.push_back(r);
  }
  return out;
}

}  // namespace chasles
