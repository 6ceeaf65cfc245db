#include "chasles/dynamics/impulse.h"

#include <cmath>

#include <fmt/format.h>

#include "chasles/error.h"

namespace chasles {

void ApplyImpulseAtWorldPoint(const Model& model, BodyIndex b, const Vec3& p_WP, const Vec3& J_W,
                              State& state) {
  if (b < 0 || b >= model.num_bodies()) {
    throw InputError(
        fmt::format("impulse on body index {}: the model has {} bodies", b, model.num_bodies()));
  }
  if (!J_W.allFinite() || !p_WP.allFinite()) {
    throw InputError(
        fmt::format("impulse on body '{}': impulse and point must be finite", model.body(b).name()),
        ErrorElement{ErrorElement::Kind::kBody, b});
  }
  const Body& body = model.body(b);
  BodyState& bs = state.bodies[static_cast<size_t>(b)];
  // Eq. 8.118: m Δv = J. Eq. 8.119 about the centre of mass: I Δw = p_BcmP × J (in B).
  bs.v_WBcm_W += J_W / body.mass();
  const Quat q = bs.q_WB.normalized();
  const Vec3 dH_B = q.conjugate() * (p_WP - bs.p_WBcm).cross(J_W);
  bs.w_WB_B += body.I_BBcm_B_inverse() * dH_B;
}

void ApplyImpulse(const Model& model, BodyIndex b, const Vec3& p_BoP_B, const Vec3& J_W,
                  State& state) {
  if (b < 0 || b >= model.num_bodies()) {
    throw InputError(
        fmt::format("impulse on body index {}: the model has {} bodies", b, model.num_bodies()));
  }
  const BodyState& bs = state.bodies[static_cast<size_t>(b)];
  const Vec3 p_WP = bs.p_WBcm + bs.q_WB.normalized() * model.body(b).PointFromCenterOfMass(p_BoP_B);
  ApplyImpulseAtWorldPoint(model, b, p_WP, J_W, state);
}

namespace {
Mat3 WorldInertia(const BodyMotion& b) {
  return b.R_WB * b.mass_properties.I_BBcm_B().matrix() * b.R_WB.transpose();
}
}  // namespace

double CalcKineticEnergy(const BodyMotion& b) {
  return 0.5 * b.mass_properties.mass() * b.v_WBcm_W.squaredNorm() +
         0.5 * b.w_WB_W.dot(WorldInertia(b) * b.w_WB_W);
}

EmbeddingResult CalcEmbedding(const BodyMotion& target, const BodyMotion& projectile) {
  target.mass_properties.Validate("embedding target");
  if (!(projectile.mass_properties.mass() > 0.0)) {
    throw InputError(fmt::format("embedding projectile: mass is {:.6g} kg; it must be positive",
                                 projectile.mass_properties.mass()));
  }
  const double mt = target.mass_properties.mass(), mp = projectile.mass_properties.mass();
  const double m = mt + mp;
  // Projectile's mass properties in the target frame B. Its own frame P: R_BP = R_WBᵀ R_WP; its
  // Po sits where its centre of mass sits minus R_WP p_PoPcm.
  const Mat3 R_BW = target.R_WB.transpose();
  const Mat3 R_BP = R_BW * projectile.R_WB;
  const Vec3 p_WBo = target.p_WBcm - target.R_WB * target.mass_properties.p_BoBcm_B();
  const Vec3 p_WPo = projectile.p_WBcm - projectile.R_WB * projectile.mass_properties.p_BoBcm_B();
  const MassProperties combined =
      target.mass_properties +
      projectile.mass_properties.ExpressedInParent(R_BP, R_BW * (p_WPo - p_WBo));

  EmbeddingResult r;
  BodyMotion& c = r.composite;
  c.mass_properties = combined;
  c.R_WB = target.R_WB;
  c.p_WBcm = (mt * target.p_WBcm + mp * projectile.p_WBcm) / m;
  // Linear momentum (eq. 8.118 with no external impulse).
  c.v_WBcm_W = (mt * target.v_WBcm_W + mp * projectile.v_WBcm_W) / m;
  // Angular momentum about C (eq. 8.119): each body's spin plus the moment of its momentum.
  const Vec3 H_C = WorldInertia(target) * target.w_WB_W +
                   (target.p_WBcm - c.p_WBcm).cross(mt * target.v_WBcm_W) +
                   WorldInertia(projectile) * projectile.w_WB_W +
                   (projectile.p_WBcm - c.p_WBcm).cross(mp * projectile.v_WBcm_W);
  c.w_WB_W = WorldInertia(c).ldlt().solve(H_C);
  r.kinetic_energy_before = CalcKineticEnergy(target) + CalcKineticEnergy(projectile);
  r.kinetic_energy_after = CalcKineticEnergy(c);
  r.kinetic_energy_lost = r.kinetic_energy_before - r.kinetic_energy_after;
  return r;
}

PassThroughResult ApplyPassThrough(const Model& model, BodyIndex b, const Vec3& p_WP,
                                   double projectile_mass, const Vec3& v_projectile_W,
                                   double exit_fraction, State& state) {
  if (!(projectile_mass > 0.0) || !std::isfinite(projectile_mass)) {
    throw InputError(fmt::format("pass-through: projectile mass is {:.6g} kg; it must be positive",
                                 projectile_mass));
  }
  if (!(exit_fraction >= 0.0 && exit_fraction <= 1.0)) {
    throw InputError(fmt::format(
        "pass-through: exit fraction is {:.6g}; it must be in [0, 1] (0.8 = leaves at 80% of "
        "its speed)",
        exit_fraction));
  }
  const Body& body = model.body(b);
  auto target_ke = [&] {
    const BodyState& bs = state.bodies[static_cast<size_t>(b)];
    return 0.5 * body.mass() * bs.v_WBcm_W.squaredNorm() +
           0.5 * bs.w_WB_B.dot(body.I_BBcm_B() * bs.w_WB_B);
  };
  PassThroughResult r;
  r.projectile_exit_velocity_W = exit_fraction * v_projectile_W;
  r.impulse_W = projectile_mass * (v_projectile_W - r.projectile_exit_velocity_W);
  const double before = target_ke() + 0.5 * projectile_mass * v_projectile_W.squaredNorm();
  ApplyImpulseAtWorldPoint(model, b, p_WP, r.impulse_W, state);
  const double after =
      target_ke() + 0.5 * projectile_mass * r.projectile_exit_velocity_W.squaredNorm();
  r.kinetic_energy_lost = before - after;
  return r;
}

}  // namespace chasles
