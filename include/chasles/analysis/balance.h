#pragma once
/// @file
/// Rotor balancing (docs/modes.md, "Rotors"): a rigid body spinning at ω about a fixed axis a
/// through a point O, held in two bearing planes at axial positions z_A and z_B along a from O.
/// With r⊥ a mass element's offset from the axis and z its axial position,
///   U = ∫ r⊥ dm = m e             (static unbalance, kg·m; e the centre of mass's offset)
///   C = ∫ z' r'⊥ dm = -(E - a aᵀ) I_cm a  (couple unbalance, kg·m²: the products of inertia
///                                           about the axis through the centre of mass)
///   D = ∫ z r⊥ dm = C + m z_cm e  (the same about O).
/// Turning at constant ω the body needs (chapter 8.3, Euler's equations about the fixed axis)
/// the force m a_cm = -ω² U and the moment dH_O/dt = ω a × H_O = -ω² a × D from the bearings,
/// so the bearing forces on the rotor F_A + F_B = -ω² U, z_A F_A + z_B F_B = -ω² D. Two masses
/// u_A = m_A r_A and u_B = m_B r_B in the planes cancel both when
///   u_A + u_B = -U,  z_A u_A + z_B u_B = -D,
///   u_A = (z_B U - D)/(z_A - z_B),  u_B = (D - z_A U)/(z_A - z_B),
/// which are also the bearing forces before correction divided by ω² (F_A = ω² u_A: the
/// bearings pull the rotor towards where the correction goes).
/// ISO 21940-11: a balance grade G [mm/s] allows the residual specific unbalance
/// e_per = G/ω, U_per = m e_per, shared between the planes in inverse proportion to their
/// distances from the centre of mass.

#include <array>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "chasles/analysis/error_locator.h"
#include "chasles/analysis/initial_state.h"
#include "chasles/analysis/whirl.h"
#include "chasles/math/types.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {

struct RotorAxis {
  /// Spin axis, in W (normalised here).
  Vec3 a_W = Vec3::UnitZ();
  /// A point O of the axis, in W [m].
  Vec3 p_WO = Vec3::Zero();
  /// The two bearing (and correction) planes' axial positions from O along a [m].
  double z_A = 0.0, z_B = 0.0;
  /// Radius at which the correction masses are placed [m].
  double radius = std::numeric_limits<double>::quiet_NaN();
};

struct BalanceCorrection {
  /// Mass to add [kg] at `radius` [m] and `angle` [rad] about a from the reference direction
  /// e1 (W's x projected onto the plane normal to a, or y when x is along a; e2 = a × e1).
  double mass = 0.0, radius = 0.0, angle = 0.0;
  /// Its position in W [m].
  Vec3 p_W = Vec3::Zero();
};

struct BalanceReport {
  double mass = 0.0;
  /// Static unbalance U (kg·m) and couple unbalance C (kg·m²) as vectors in W, normal to a.
  Vec3 static_unbalance_W = Vec3::Zero(), couple_unbalance_W = Vec3::Zero();
  /// The reference directions of the angles, in W.
  Vec3 e1_W = Vec3::UnitX(), e2_W = Vec3::UnitY();
  std::array<BalanceCorrection, 2> corrections;
  /// |U| and |D| left after adding the corrections [kg·m, kg·m²] (round-off).
  double residual_static = 0.0, residual_couple = 0.0;
  /// Spin [rad/s] (NaN: none given), and the bearing forces on the rotor at that spin in W at
  /// the present angle, before and after the correction [N] (the rotating part; the weight's
  /// share is not included).
  double speed = std::numeric_limits<double>::quiet_NaN();
  std::array<Vec3, 2> bearing_forces_W{Vec3::Zero(), Vec3::Zero()};
  std::array<Vec3, 2> bearing_forces_after_W{Vec3::Zero(), Vec3::Zero()};
  /// ISO 21940-11 permissible residual unbalance [kg·m] for the grade at the speed, in all
  /// and per plane (NaN without a grade and a speed).
  double grade = std::numeric_limits<double>::quiet_NaN();
  double permissible = std::numeric_limits<double>::quiet_NaN();
  std::array<double, 2> permissible_per_plane{std::numeric_limits<double>::quiet_NaN(),
                                              std::numeric_limits<double>::quiet_NaN()};
};

/// The unbalance of a body of mass m [kg] with centre of mass p_WBcm [m] and inertia I_cm_W
/// about it in W [kg·m²] spinning about `axis`, its two-plane correction, and with a speed
/// [rad/s] > 0 the bearing forces and with a grade G [mm/s] > 0 as well the permissible
/// residual unbalance. Throws InputError for coincident planes, a radius that is not positive
/// or a zero axis.
BalanceReport CalcBalance(double mass, const Vec3& p_WBcm, const Mat3& I_cm_W,
                          const RotorAxis& axis,
                          double speed = std::numeric_limits<double>::quiet_NaN(),
                          double grade = std::numeric_limits<double>::quiet_NaN());

/// A rotor of a Model to balance (`chasles balance`; the scene layer's MakeBalanceDefinition
/// makes one from a scene and the command's options).
struct RotorBalanceDefinition {
  std::shared_ptr<const Model> model;
  /// The state whose pose of the rotor is balanced (and the whirl starts from).
  State initial;
  /// Settle `initial` onto the constraints first, as a run starts (SettleInitialState; its
  /// warnings are the run's, not the balance's); none: as it is.
  std::optional<InitialSettling> settle_initial;
  BodyIndex rotor = 0;
  RotorAxis axis;
  /// Spin [rad/s] for the bearing forces and the grade (NaN: none) and the ISO 21940-11 grade G
  /// [mm/s] (NaN: none).
  double speed = std::numeric_limits<double>::quiet_NaN();
  double grade = std::numeric_limits<double>::quiet_NaN();
  /// The spins of the whirl rows [rad/s, ascending]; empty: chosen by CalcRotorWhirl.
  std::vector<double> whirl_speeds;
  /// Places the analysis's errors at their source (the scene layer's file:line:col); null:
  /// they are thrown as they are.
  ErrorLocator locate_error;
};

struct RotorBalance {
  /// The rotor's name and the axis and planes as the definition gives them.
  std::string body;
  RotorAxis axis;
  BalanceReport balance;
  /// The whirl rows when a bearing holds the rotor and something whirls (CalcRotorWhirl).
  std::optional<WhirlMap> whirl;
};

/// The definition's rotor at its settled initial pose: CalcBalance of its mass, centre of mass
/// and inertia in W about `axis`, and CalcRotorWhirl about the axis's direction. Throws
/// InputError (coincident planes, a radius that is not positive, whirl speeds for a rotor no
/// bearing holds, ...) through the definition's `locate_error` when it has one.
RotorBalance AnalyseRotorBalance(const RotorBalanceDefinition& definition);

}  // namespace chasles
