#pragma once
/// @file
/// What an instantaneous solve reports (chapter 8.2-8.3; `chasles solve`, the scene layer's
/// SolveScene): every body's acceleration and every constraint's reaction, the kinetic energy
/// and momenta, each contact point in its chosen mode, and the solve's checks of its own
/// answer; and the table a sweep of one parameter makes of such reports. Plain results: no
/// scene, no units (SI throughout). The report layer writes them as the program's JSON and CSV
/// (chasles/report/solve_json.h).

#include <limits>
#include <string>
#include <vector>

#include "chasles/analysis/certificate.h"
#include "chasles/analysis/instantaneous.h"
#include "chasles/math/types.h"
#include "chasles/model/contact.h"
#include "chasles/model/data.h"

namespace chasles {

/// A named point of a body (its `points:` entry) at the solved state: the rigid-body velocity
/// and acceleration fields of rigid-body kinematics, with r from the centre of mass to P,
///   v_P = v_cm + ω × r,   a_P = a_cm + α × r + ω × (ω × r).
struct PointMotionReport {
  std::string name;
  /// Position, velocity and acceleration of the point, in W [m, m/s, m/s²].
  Vec3 p_WP = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  Vec3 v_WP_W = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  Vec3 a_WP_W = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
};

/// Kinetic energy and momenta of one body (or, for the total, of all of them) at the solved
/// state (eqs. 8.115, 8.116): T = ½ m v² + ½ ωᵀ I ω, p = m v, H about the centre of mass
/// I ω and about the world origin H_O = H + p_cm × m v. With the accelerations also their
/// rates, the chapter's ΣM = dH/dt (eq. 8.30): about the centre of mass, in body axes
/// dH/dt = I α + ω × I ω (the left sides of Euler's equations, eqs. 8.75-8.81), expressed in W;
/// about the fixed origin O, dH_O/dt = dH_cm/dt + r_cm × m a_cm (the term v_cm × m v_cm vanishes).
struct BodyMotionReport {
  /// Body name ("" for the total).
  std::string name;
  /// Translational and rotational kinetic energy [J].
  double T_trans = 0.0, T_rot = 0.0;
  /// Linear momentum in W [kg·m/s].
  Vec3 P = Vec3::Zero();
  /// Angular momentum about the body's own centre of mass (for the total, about the system's
  /// centre of mass), in W [kg·m²/s].
  Vec3 H_cm = Vec3::Zero();
  /// Angular momentum about the world origin, in W [kg·m²/s].
  Vec3 H_O = Vec3::Zero();
  /// Rates of H_cm and H_O, in W [N·m] (for the total: about the system's centre of mass and
  /// about O, the sums over the bodies).
  Vec3 Hdot_cm = Vec3::Zero();
  Vec3 Hdot_O = Vec3::Zero();
  /// Per body (empty for the total): the angular velocity in W [rad/s], the velocity of the
  /// centre of mass in W [m/s] and the body's named points.
  Vec3 w_WB_W = Vec3::Zero();
  Vec3 v_WBcm_W = Vec3::Zero();
  std::vector<PointMotionReport> points;
};

/// One contact point at the solved state, in the mode SelectContactModes chose.
struct ContactPointReport {
  /// The point's name ("floor", "incline_0", "rear") and its contact's name.
  std::string point, contact;
  /// Mode, normal and friction force, slip velocity, gap, point and normal in W.
  ContactPointOutput out;
  /// The contact's coefficients of static and kinetic friction and of rolling resistance.
  double mu_s = 0.0, mu_k = 0.0, mu_r = 0.0;
  /// A round feature (sphere, rim): a sticking one rolls without slipping.
  bool round = false;
  /// "rolls", "rolling held" (a round point whose rolling resistance holds it) or "sticks"
  /// (sticking), "slides", "separated".
  std::string Regime() const;
  /// |f| / N: the friction a sticking point needs (compare with mu_s), mu_k when sliding, 0
  /// when separated.
  double FrictionRatio() const;
};

/// Everything an instantaneous solve reports.
struct SolveReport {
  /// Accelerations, reactions (a planar scene's plane constraints left out), rank, warnings
  /// (e.g. initial values changed by a projection onto the constraints).
  InstantaneousSolution solution;
  /// mu_s of each reaction (NaN when not a rolling contact with `mu_s`), in reaction order.
  std::vector<double> mu_s;
  /// Per body (Model order).
  std::vector<BodyMotionReport> motion;
  /// All bodies together.
  BodyMotionReport total;
  /// A planar problem: reports in x, y and about z (a_x, a_y, alpha; Fx, Fy, Mz).
  bool planar = false;
  /// Contact points in their chosen modes.
  std::vector<ContactPointReport> contacts;
  /// The solve's checks of its own answer (friction, N, gaps, residuals, Newton–Euler).
  Certificate certificate;
};

/// One row of a sweep table: the report's values in table order, with their names and SI
/// units ("m/s^2", "N", ...) when the pointers are given. Per body a and alpha (planar: a_x,
/// a_y, alpha), v and omega (planar: v_x, v_y, omega), each named point's velocity and
/// acceleration ("<body>_<point>_vx", "_ax"; planar x and y), dH/dt about the centre of mass
/// and about O ("<body>_dHx", "_dHOx"; planar z), the kinetic energy and momenta per body and
/// in total (named as the simulation's ledger columns) with the totals' dH/dt, per constraint F and
/// M (planar: Fx, Fy, Mz) and for rolling N, |f| and f/N, per contact point mode (0 separated, 1
/// sliding, 2 sticking), N, |f|, f/N.
void SolutionTableRow(const SolveReport& s, std::vector<std::string>* names,
                      std::vector<std::string>* units, std::vector<double>* values);

/// A sweep's result: one row per value of the swept parameter (per point of a grid of
/// several), the parameters first (SI).
struct SweepTable {
  /// The swept parameter's name (a grid's names joined by ", ").
  std::string parameter;
  /// A grid's parameter names, in column order (empty for a sweep of one parameter by solve).
  std::vector<std::string> parameters;
  /// Column names: the parameter, then SolutionTableRow's names.
  std::vector<std::string> columns;
  /// SI unit of each column ("" for pure numbers and angles in rad).
  std::vector<std::string> units;
  std::vector<std::vector<double>> rows;
  /// Failed checks, one per failed check of one value: "theta = 0.5: ...".
  std::vector<std::string> warnings;
  /// True when a check failed at some value.
  bool failed = false;
  /// Per row, why a value is missing ("" when none is); empty when no row can fail (solve).
  /// A failed row has its parameters and NaN for every other value; a row whose run could
  /// not give a quantity has NaN for that one alone. The writers print NaN as empty CSV fields
  /// and JSON nulls, with the reasons in an "error" column.
  std::vector<std::string> errors;
};

}  // namespace chasles
