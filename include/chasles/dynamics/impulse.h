#pragma once
/// @file
/// Impulsive motion (chapter 8.5). Over an instant the positions do not change and the
/// impulse-momentum principle (eqs. 8.118, 8.119) gives the jumps
///   m Δv_Bcm = J,    ΔH_Bcm = p_BcmP × J    (H_Bcm = I w about the centre of mass).

#include "chasles/mass/mass_properties.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {

/// Applies the impulse J_W [N·s] at point P of body `b` (p_BoP_B from Bo, in B [m]):
/// v += J/m, w_B += I⁻¹ Rᵀ (p_BcmP_W × J).
void ApplyImpulse(const Model& model, BodyIndex b, const Vec3& p_BoP_B, const Vec3& J_W,
                  State& state);

/// The same with P given by its world position p_WP [m].
void ApplyImpulseAtWorldPoint(const Model& model, BodyIndex b, const Vec3& p_WP, const Vec3& J_W,
                              State& state);

/// A body's motion at one instant, with its mass properties (in its frame B, from Bo).
struct BodyMotion {
  /// Mass properties in B: mass, Bcm from Bo, inertia about Bcm [kg, m, kg·m²].
  MassProperties mass_properties;
  /// Orientation of B in W.
  Mat3 R_WB = Mat3::Identity();
  /// Position of Bcm in W [m].
  Vec3 p_WBcm = Vec3::Zero();
  /// Velocity of Bcm in W [m/s].
  Vec3 v_WBcm_W = Vec3::Zero();
  /// Angular velocity in W [rad/s].
  Vec3 w_WB_W = Vec3::Zero();
};

/// Kinetic energy ½ m v² + ½ wᵀ I_W w (eqs. 8.115, 8.116) [J].
double CalcKineticEnergy(const BodyMotion& body);

/// Result of a projectile embedding itself in a target: one composite body afterwards.
struct EmbeddingResult {
  /// The composite body. Its frame is the target's frame B (same R_WB); its mass properties
  /// are expressed in B from the target's Bo.
  BodyMotion composite;
  /// Kinetic energy of the two bodies just before [J].
  double kinetic_energy_before = 0.0;
  /// Kinetic energy of the composite just after [J].
  double kinetic_energy_after = 0.0;
  /// Energy lost in the impact (to deformation and heat) [J], >= 0.
  double kinetic_energy_lost = 0.0;
};

/// Projectile and target become one body. Linear momentum and angular momentum about the
/// combined centre of mass C are conserved (no external impulse):
///   (m_t + m_p) v_C = m_t v_t + m_p v_p,
///   I_C w = Σ_i [I_i w_i + m_i (p_i - p_C) × v_i],
/// with I_C the composite inertia about C (parallel-axis theorem, eq. 8.29).
/// The projectile's position and orientation are those at impact (where it stays).
EmbeddingResult CalcEmbedding(const BodyMotion& target, const BodyMotion& projectile);

/// Result of a projectile passing through a body.
struct PassThroughResult {
  /// Impulse the projectile gave the target [N·s].
  Vec3 impulse_W = Vec3::Zero();
  /// Projectile velocity after it leaves [m/s].
  Vec3 projectile_exit_velocity_W = Vec3::Zero();
  /// Kinetic energy lost (target and projectile, before minus after) [J].
  double kinetic_energy_lost = 0.0;
};

/// A point projectile of mass `projectile_mass` [kg] with velocity `v_projectile_W` [m/s] hits
/// body `b` at world point p_WP and leaves with `exit_fraction` (in [0, 1]) of its velocity,
/// direction unchanged. The target takes the rest of the momentum, J = m (1 - f) v, at P, and
/// with it the angular momentum p_BcmP × J about its centre of mass. Updates `state`.
PassThroughResult ApplyPassThrough(const Model& model, BodyIndex b, const Vec3& p_WP,
                                   double projectile_mass, const Vec3& v_projectile_W,
                                   double exit_fraction, State& state);

}  // namespace chasles
