// An initial state that violates the constraints is an error, or, when the caller asks for
// it, projected with every change reported (chasles/analysis/initial_state.h).

#include "chasles/analysis/initial_state.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "chasles/dynamics/constraint_modes.h"
#include "chasles/dynamics/constraint_residual.h"
#include "chasles/dynamics/constraint_solve.h"
#include "chasles/error.h"
#include "chasles/model/constraints.h"
#include "chasles/model/data.h"

namespace chasles {
namespace {

// Components at round-off of the vector's size print as 0.
std::string VecText(Vec3 v, bool planar, double size = 0.0) {
  const double floor = kRoundOffResidual * std::max(size, v.norm());
  for (int i = 0; i < 3; ++i) {
    if (std::abs(v[i]) <= floor) v[i] = 0.0;
  }
  if (planar) return fmt::format("[{:.6g}, {:.6g}]", v.x(), v.y());
  return fmt::format("[{:.6g}, {:.6g}, {:.6g}]", v.x(), v.y(), v.z());
}

// The residuals of one violated constraint beyond round-off, with units.
std::string ResidualText(const ConstraintResidual& r, const ConstraintScales& s) {
  const double tol_speed = kRoundOffResidual * s.velocity;
  std::vector<std::string> parts;
  if (r.position_length > kRoundOffResidual * s.length) {
    parts.push_back(fmt::format("position {:.4g} m", r.position_length));
  }
  if (r.position_angle > kRoundOffResidual) {
    parts.push_back(fmt::format("axis {:.4g} rad", r.position_angle));
  }
  if (r.velocity_linear > tol_speed) {
    parts.push_back(fmt::format("velocity {:.4g} m/s", r.velocity_linear));
  }
  if (r.velocity_angular > (s.length > 0.0 ? tol_speed / s.length : tol_speed)) {
    parts.push_back(fmt::format("angular velocity {:.4g} rad/s", r.velocity_angular));
  }
  std::string out;
  for (size_t i = 0; i < parts.size(); ++i) out += (i == 0 ? "" : ", ") + parts[i];
  return out;
}

// What to give so that `con` holds, in the scene format's own keys.
std::string Hint(bool planar, const Model& model, const Constraint& con,
                 const ConstraintResidual& r) {
  const std::string body = model.body(con.child()).name();
  const std::string what = fmt::format("{} '{}'", con.kind(), con.name());
  std::vector<std::string> give;
  if (r.position_violated) {
    give.push_back(planar
                       ? fmt::format("`position` and `theta` of '{}' that satisfy {}", body, what)
                       : fmt::format("`position` and the orientation (`rotation`, `euler` or "
                                     "`quaternion`) of '{}' that satisfy {}",
                                     body, what));
  }
  if (r.velocity_violated) {
    std::string v = fmt::format(
        "`velocity` (of `velocity_point`) and `{}` of '{}' consistent "
        "with {}",
        planar ? "omega" : "angular_velocity", body, what);
    const auto* joint = dynamic_cast<const Joint*>(&con);
    if (joint != nullptr && con.parent() == kWorld &&
        joint->joint_kind() != JointKind::kPointOnPlane &&
        joint->joint_kind() != JointKind::kPointOnLine &&
        joint->joint_kind() != JointKind::kPlanar && joint->joint_kind() != JointKind::kPrismatic &&
        joint->joint_kind() != JointKind::kCylindrical) {
      v += " (its joint point is at rest: e.g. `velocity_point` at the joint with `velocity: "
           "[0, 0, 0]`)";
    } else if (dynamic_cast<const RollingContact*>(&con) != nullptr) {
      v += " (the contact point moves with the surface it rolls on: the centre's velocity is "
           "omega x (centre - contact point) on a fixed plane)";
    }
    give.push_back(v);
  }
  std::string out;
  for (size_t i = 0; i < give.size(); ++i) out += (i == 0 ? "give " : " and ") + give[i];
  return out;
}

// Every value of the user's initial state that the projection changed, in the user's terms
// (the frame origin's position, the orientation, the velocity of the given point, the angular
// velocity), beyond round-off.
std::vector<std::string> Changes(const InitialSettling& settling, const Model& model,
                                 const State& given, const State& used,
                                 const ConstraintScales& scales) {
  const bool planar = settling.planar;
  std::vector<std::string> out;
  const double tol_length = kRoundOffResidual * scales.length;
  const double tol_speed = kRoundOffResidual * scales.velocity;
  const double tol_rate = scales.length > 0.0 ? tol_speed / scales.length : tol_speed;
  for (size_t b = 0; b < given.bodies.size(); ++b) {
    const int i = static_cast<int>(b);
    const std::string& name = model.body(i).name();
    const BodyState& g = given.bodies[b];
    const BodyState& u = used.bodies[b];
    const Vec3 p_given = CalcBodyOriginPosition(model, given, i);
    const Vec3 p_used = CalcBodyOriginPosition(model, used, i);
    if ((p_used - p_given).norm() > tol_length) {
      const double size = std::max(p_given.norm(), p_used.norm());
      out.push_back(fmt::format("body '{}': position {} m -> {} m", name,
                                VecText(p_given, planar, size), VecText(p_used, planar, size)));
    }
    const Eigen::AngleAxisd turn(u.q_WB * g.q_WB.conjugate());
    if (std::abs(turn.angle()) > kRoundOffResidual) {
      if (planar) {
        const double theta = b < settling.theta.size() ? settling.theta[b] : 0.0;
        out.push_back(fmt::format("body '{}': theta {:.6g} rad -> {:.6g} rad", name, theta,
                                  theta + turn.angle() * turn.axis().z()));
      } else {
        out.push_back(fmt::format("body '{}': orientation turned by {:.6g} rad about {}", name,
                                  turn.angle(), VecText(turn.axis(), false)));
      }
    }
    // Velocity of the point the user gave (the centre of mass by default).
    const Vec3 w_given = g.q_WB * g.w_WB_B, w_used = u.q_WB * u.w_WB_B;
    const Vec3 p_BoP_B = b < settling.p_BoP_B.size() ? settling.p_BoP_B[b] : Vec3::Zero();
    const Vec3 r_B = p_BoP_B - model.body(i).p_BoBcm_B();
    const Vec3 v_given = g.v_WBcm_W + w_given.cross(g.q_WB * r_B);
    const Vec3 v_used = u.v_WBcm_W + w_used.cross(u.q_WB * r_B);
    if ((v_used - v_given).norm() > tol_speed) {
      const bool at_cm = r_B.norm() <= tol_length;
      const double size = std::max(v_given.norm(), v_used.norm());
      out.push_back(fmt::format("body '{}': velocity {} {} m/s -> {} m/s", name,
                                at_cm ? "of its centre of mass" : "of `velocity_point`",
                                VecText(v_given, planar, size), VecText(v_used, planar, size)));
    }
    if ((w_used - w_given).norm() > tol_rate) {
      if (planar) {
        out.push_back(fmt::format("body '{}': omega {:.6g} rad/s -> {:.6g} rad/s", name,
                                  w_given.z(), w_used.z()));
      } else {
        const double size = std::max(w_given.norm(), w_used.norm());
        out.push_back(fmt::format("body '{}': angular velocity {} rad/s -> {} rad/s", name,
                                  VecText(w_given, false, size), VecText(w_used, false, size)));
      }
    }
  }
  return out;
}

}  // namespace

namespace {
State SettleOnConstraints(const Model& model, const State& given, const InitialSettling& settling,
                          std::vector<std::string>& warnings);
}  // namespace

State SettleInitialState(const Model& model, const State& given, const InitialSettling& settling,
                         std::vector<std::string>& warnings) {
  if (model.num_constraints() == 0) return given;
  // A string whose length exceeds its path (or whose ends move to slacken it, or whose tension
  // would come out negative) starts slack: its row is not held, so it is no violation.
  State with_modes = given;
  SelectConstraintModes(model, with_modes);
  return SettleOnConstraints(model, with_modes, settling, warnings);
}

namespace {
State SettleOnConstraints(const Model& model, const State& given, const InitialSettling& settling,
                          std::vector<std::string>& warnings) {
  Data data = MakeData(model);
  const ConstraintScales scales = CalcConstraintScales(model, given, data);
  const std::vector<ConstraintResidual> violations =
      FindConstraintViolations(model, given, data, scales);
  State used = given;
  // Mass-weighted closest consistent state (positions by Gauss-Newton, then velocities);
  // throws when the positions cannot be assembled at all.
  ProjectOntoConstraints(model, used, data);
  if (violations.empty()) return used;  // round-off only: corrected without a word
  const std::vector<std::string> changes = Changes(settling, model, given, used, scales);
  if (settling.project) {
    for (const std::string& c : changes) {
      warnings.push_back("initial state projected onto the constraints: " + c);
    }
    return used;
  }
  std::string list, hints;
  for (const ConstraintResidual& r : violations) {
    const Constraint& con = model.constraint(r.constraint);
    list += fmt::format("\n  {} '{}' (body '{}'): residual {}", con.kind(), con.name(),
                        model.body(con.child()).name(), ResidualText(r, scales));
    hints += "\n  " + Hint(settling.planar, model, con, r);
  }
  std::string nearest;
  for (const std::string& c : changes) nearest += "\n  " + c;
  // At the initial state of the first violated constraint's body.
  const int body = model.constraint(violations.front().constraint).child();
  throw InputError(
      fmt::format("the initial state violates the constraints (beyond round-off, {:g} of the "
                  "scene's scales {:.4g} m and {:.4g} m/s):{}\nTo fix it:{}\nor add "
                  "`project_initial: true` to start from the nearest consistent state "
                  "(mass-weighted), which changes:{}",
                  kRoundOffResidual, scales.length, scales.velocity, list, hints, nearest),
      ErrorElement{ErrorElement::Kind::kInitialState, body});
}

}  // namespace

}  // namespace chasles
