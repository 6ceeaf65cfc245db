#include "chasles/analysis/instantaneous.h"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "chasles/dynamics/constraint_modes.h"
#include "chasles/dynamics/constraint_solve.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/dynamics/redundancy.h"
#include "chasles/error.h"
#include "chasles/model/constraints.h"
#include "chasles/model/data.h"

namespace chasles {

namespace {
InstantaneousSolution SolveInChosenModes(const Model& model, const State& state,
                                         const InstantaneousOptions& options);
}  // namespace

InstantaneousSolution SolveInstantaneous(const Model& model, const State& state,
                                         const InstantaneousOptions& options) {
  ValidateState(model, state);
  // Strings that can go slack: taut or slack by the complementarity on their tensions
  // (SelectConstraintModes), never assumed.
  State chosen = state;
  for (int c = 0; c < model.num_constraints(); ++c) {
    if (model.constraint(c).can_release()) {
      SelectConstraintModes(model, chosen);
      break;
    }
  }
  return SolveInChosenModes(model, chosen, options);
}

namespace {
/// A force element whose force, moment or power is NaN or infinite (an expression dividing by
/// zero at this state) is named, as a run names it, rather than passed on as non-finite
/// accelerations.
void CheckFiniteForces(const Model& model, const State& state, const Data& data) {
  for (int e = 0; e < model.num_force_elements(); ++e) {
    const ForceElementOutput& o = data.elements[static_cast<size_t>(e)];
    if (o.force_W.allFinite() && o.moment_Wo_W.allFinite() && std::isfinite(o.power)) continue;
    const bool inf = o.force_W.array().isInf().any() || o.moment_Wo_W.array().isInf().any() ||
                     std::isinf(o.power);
    throw InputError(
        fmt::format("force element '{}' evaluated to {} at t = {:.9g} s (force [{:.6g}, {:.6g}, "
                    "{:.6g}] N): check its expression or the bodies' positions (a body at a force "
                    "centre, a logarithm or a division by zero)",
                    model.force_element(e).name(), inf ? "infinite" : "NaN", state.t, o.force_W.x(),
                    o.force_W.y(), o.force_W.z()),
        ErrorElement{ErrorElement::Kind::kForceElement, e, true});
  }
}

InstantaneousSolution SolveInChosenModes(const Model& model, const State& state,
                                         const InstantaneousOptions& options) {
  Data data = MakeData(model);
  const ConstraintViolation v = CalcConstraintViolation(model, state, data);
  if (v.position > options.tolerance || v.velocity > options.tolerance) {
    throw InputError(
        fmt::format(
            "the state violates constraint '{}' (position error {:.3g}, velocity error {:.3g}; "
            "tolerance {:.3g}): give positions and velocities that satisfy the constraints, or "
            "project the state with ProjectOntoConstraints first",
            model.constraint(v.worst).name(), v.position, v.velocity, options.tolerance),
        ErrorElement{ErrorElement::Kind::kConstraint, v.worst});
  }
  CalcAccelerations(model, state, data);
  CheckFiniteForces(model, state, data);
  InstantaneousSolution s;
  s.t = state.t;
  s.num_rows = model.num_constraint_rows();
  s.rank = model.num_constraints() > 0 ? data.constraint_rank : 0;
  if (s.rank < s.num_rows) {
    // Which reaction components are indeterminate, and a determinate set of supports.
    Data scratch = MakeData(model);
    const Redundancy red = AnalyseRedundancy(model, state, scratch);
    for (std::string& w : DescribeRedundancy(model, red)) s.warnings.push_back(std::move(w));
  }
  for (int b = 0; b < model.num_bodies(); ++b) {
    const auto i = static_cast<size_t>(b);
    BodyAccelerationReport r;
    r.name = model.body(b).name();
    r.a_WBcm_W = data.a_WBcm_W[i];
    r.alpha_WB_B = data.wdot_WB_B[i];
    r.alpha_WB_W = data.R_WB[i] * data.wdot_WB_B[i];
    s.bodies.push_back(r);
  }
  for (int c = 0; c < model.num_constraints(); ++c) {
    s.reactions.push_back(MakeReactionReport(model, data, c));
  }
  return s;
}
}  // namespace

ReactionReport MakeReactionReport(const Model& model, const Data& data, int c) {
  const Constraint& con = model.constraint(c);
  const ConstraintOutput& o = data.constraints[static_cast<size_t>(c)];
  ReactionReport r;
  r.name = con.name();
  r.kind = con.kind();
  r.parent = con.parent();
  r.child = con.child();
  r.p_WJ = o.p_WJ;
  r.F_Jc_W = o.F_Jc_W;
  r.M_Jc_W = o.M_Jc_W;
  r.F_Jc_B = o.F_Jc_B;
  r.M_Jc_B = o.M_Jc_B;
  // The parent's frame: P = W for the world (R_WP = E).
  if (con.parent() == kWorld) {
    r.F_Jc_P = o.F_Jc_W;
    r.M_Jc_P = o.M_Jc_W;
  } else {
    const Mat3& R_WP = data.R_WB[static_cast<size_t>(con.parent())];
    r.F_Jc_P = R_WP.transpose() * o.F_Jc_W;
    r.M_Jc_P = R_WP.transpose() * o.M_Jc_W;
  }
  r.power = o.power;
  for (int k = 0; k < con.num_rows(); ++k) r.lambda.push_back(o.lambda[k]);
  if (con.can_release()) {
    const bool slack = data.row_released[static_cast<size_t>(model.constraint_row_offset(c))] != 0;
    r.mode = slack ? ConstraintMode::kReleased : ConstraintMode::kEngaged;
    r.gap = data.constraint_gap[static_cast<size_t>(c)];
  }
  if (const auto* roll = dynamic_cast<const RollingContact*>(&con)) {
    r.is_rolling = true;
    r.normal_force = o.lambda[0];
    const Mat3 T = roll->CalcPlaneFrame(data);  // [t1 t2 n] in W now
    r.friction_W = o.lambda[1] * T.col(0) + o.lambda[2] * T.col(1);
    r.friction_needed = r.normal_force > 0.0 ? r.friction_W.norm() / r.normal_force
                                             : std::numeric_limits<double>::infinity();
  }
  return r;
}

}  // namespace chasles
