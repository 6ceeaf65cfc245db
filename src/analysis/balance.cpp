#include "chasles/analysis/balance.h"

#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/model/body.h"

namespace chasles {

BalanceReport CalcBalance(double mass, const Vec3& p_WBcm, const Mat3& I_cm_W,
                          const RotorAxis& axis, double speed, double grade) {
  if (!(axis.a_W.norm() > 0.0) || !axis.a_W.allFinite()) {
    throw InputError("balance: the spin axis is zero or not finite; give its direction");
  }
  if (!(axis.radius > 0.0) || !std::isfinite(axis.radius)) {
    throw InputError(fmt::format(
        "balance: the correction radius is {:.6g} m; it must be a positive length", axis.radius));
  }
  if (!(std::abs(axis.z_A - axis.z_B) > 0.0) || !std::isfinite(axis.z_A - axis.z_B)) {
    throw InputError(fmt::format(
        "balance: the two planes are at {:.6g} m and {:.6g} m along the axis; they must differ",
        axis.z_A, axis.z_B));
  }
  BalanceReport r;
  r.mass = mass;
  const Vec3 a = axis.a_W.normalized();
  const Mat3 P = Mat3::Identity() - a * a.transpose();  // projection normal to the axis
  const Vec3 d = p_WBcm - axis.p_WO;
  const double z_cm = d.dot(a);
  const Vec3 U = mass * (P * d);
  const Vec3 C = -(P * (I_cm_W * a));
  const Vec3 D = C + z_cm * U;
  r.static_unbalance_W = U;
  r.couple_unbalance_W = C;
  r.e1_W = std::abs(a.x()) < 0.9 ? Vec3(P * Vec3::UnitX()).normalized()
                                 : Vec3(P * Vec3::UnitY()).normalized();
  r.e2_W = a.cross(r.e1_W);
  const double zA = axis.z_A, zB = axis.z_B;
  const Vec3 u[2] = {(zB * U - D) / (zA - zB), (D - zA * U) / (zA - zB)};
  const double z[2] = {zA, zB};
  for (int k = 0; k < 2; ++k) {
    BalanceCorrection& c = r.corrections[static_cast<size_t>(k)];
    c.radius = axis.radius;
    c.mass = u[k].norm() / axis.radius;
    c.angle = std::atan2(u[k].dot(r.e2_W), u[k].dot(r.e1_W));
    // In (-pi, pi]: a component of -0 along e2 gives atan2's -pi, the same place as +pi.
    if (c.angle <= -std::numbers::pi) c.angle = std::numbers::pi;
    if (c.mass == 0.0) c.angle = 0.0;  // a balanced plane: no direction (atan2 of ±0 is ±pi)
    const Vec3 dir = std::cos(c.angle) * r.e1_W + std::sin(c.angle) * r.e2_W;
    c.p_W = axis.p_WO + z[k] * a + axis.radius * dir;
  }
  // What is left, from the masses as placed (their angles and radii, not u itself).
  Vec3 U_after = U, D_after = D;
  for (int k = 0; k < 2; ++k) {
    const BalanceCorrection& c = r.corrections[static_cast<size_t>(k)];
    const Vec3 uk = c.mass * (P * (c.p_W - axis.p_WO));
    U_after += uk;
    D_after += z[k] * uk;
  }
  r.residual_static = U_after.norm();
  r.residual_couple = D_after.norm();
  if (speed > 0.0 && std::isfinite(speed)) {
    r.speed = speed;
    const double w2 = speed * speed;
    // F_A + F_B = -ω² U and z_A F_A + z_B F_B = -ω² D: F = ω² u (u the corrections).
    r.bearing_forces_W = {w2 * u[0], w2 * u[1]};
    const Vec3 uA = (zB * U_after - D_after) / (zA - zB), uB = (D_after - zA * U_after) / (zA - zB);
    r.bearing_forces_after_W = {w2 * uA, w2 * uB};
    if (grade > 0.0 && std::isfinite(grade)) {
      r.grade = grade;
      r.permissible = mass * grade * 1e-3 / speed;
      r.permissible_per_plane = {r.permissible * (zB - z_cm) / (zB - zA),
                                 r.permissible * (z_cm - zA) / (zB - zA)};
    }
  }
  return r;
}

RotorBalance AnalyseRotorBalance(const RotorBalanceDefinition& definition) {
  try {
    if (!definition.model)
      throw InputError("a rotor balance needs its Model (RotorBalanceDefinition::model)");
    const Model& model = *definition.model;
    const BodyIndex b = definition.rotor;
    if (b < 0 || b >= model.num_bodies()) {
      throw InputError(fmt::format("a rotor balance's rotor is body {}, but the Model has {}", b,
                                   model.num_bodies()));
    }
    std::vector<std::string> warnings;
    const State initial =
        definition.settle_initial
            ? SettleInitialState(model, definition.initial, *definition.settle_initial, warnings)
            : definition.initial;
    const BodyState& s = initial.bodies[static_cast<size_t>(b)];
    const Mat3 R = s.q_WB.normalized().toRotationMatrix();
    RotorBalance out;
    out.body = model.body(b).name();
    out.axis = definition.axis;
    out.balance =
        CalcBalance(model.body(b).mass(), s.p_WBcm, R * model.body(b).I_BBcm_B() * R.transpose(),
                    definition.axis, definition.speed, definition.grade);
    out.whirl = CalcRotorWhirl(model, initial, b, definition.axis.a_W, definition.whirl_speeds,
                               definition.speed);
    return out;
  } catch (const InputError& e) {
    if (!definition.locate_error) throw;
    definition.locate_error(e);
    throw;  // a locator that returns leaves the error as it is
  }
}

}  // namespace chasles
