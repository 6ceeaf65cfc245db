#pragma once
/// @file
/// Geometry and kinematics of one contact point at one state, shared by the contact stage,
/// mode selection, impacts and the event functions of the hybrid run.

#include <Eigen/Core>

#include "chasles/model/data.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"
#include "dynamics/internal/generalized.h"

namespace chasles::internal {

/// A row of a column-major matrix (strided) or a row vector.
using RowRef = Eigen::Ref<Eigen::RowVectorXd, 0, Eigen::InnerStride<>>;

struct ContactPointGeometry {
  /// The body carrying the feature, and the other body (kWorld for a plane).
  BodyIndex body = kWorld, other = kWorld;
  /// Feature radius [m] and whether it is round (sphere, rim).
  double radius = 0.0;
  bool round = false;
  /// Gap [m], contact point on the body in W [m].
  double gap = 0.0;
  Vec3 p_WC = Vec3::Zero();
  /// Normal (towards the body) and tangents, in W.
  Vec3 n = Vec3::UnitZ(), t1 = Vec3::UnitX(), t2 = Vec3::UnitY();
  /// Rate of the normal (sphere-sphere only) [1/s].
  Vec3 n_dot = Vec3::Zero();
  /// Offsets from each body's centre of mass to the contact point, in W [m].
  Vec3 r = Vec3::Zero(), r_other = Vec3::Zero();
  /// Relative velocity of the material points at C (body minus other), in W [m/s]; its normal
  /// and tangential parts.
  Vec3 v_rel = Vec3::Zero();
  double v_n = 0.0;
  Vec3 v_t = Vec3::Zero();
  /// Speed scale of the material points at C, |v_cm| + |w| |r| of each side [m/s]: slips
  /// below its round-off have no direction (SlipDirection).
  double speed_scale = 0.0;
  /// Relative angular velocity (body minus other), in W [rad/s].
  Vec3 w_rel = Vec3::Zero();
  /// w × ṙ of each side (the velocity-product terms of the rows) [m/s²].
  Vec3 w_x_rdot = Vec3::Zero(), w_x_rdot_other = Vec3::Zero();
  /// Rolling axes (unit, in W) of a round feature: the rolling angular velocity is
  /// Σ (a_i·w_rel) a_i. A sphere rolls about both tangents, a rim about its axis projected on
  /// the plane (its lean and its turn about the normal are not rolling); a point, or a rim
  /// lying flat, has none (num_rolling_axes = 0).
  int num_rolling_axes = 0;
  Vec3 rolling_axis[2] = {Vec3::Zero(), Vec3::Zero()};
  /// Acceleration right-hand side of the row a_i·w_rel (a held rolling): -ȧ_i·w_rel [rad/s²].
  double rolling_bias[2] = {0.0, 0.0};

  /// Acceleration right-hand side c_k of the row k·v_rel (k = n, t1 or t2).
  double AccelerationBias(const Vec3& k) const;
  /// Adds the Jacobian row of k·v_rel to `row` (6 columns per body).
  void SetRow(const Vec3& k, RowRef row) const;
  /// Adds `scale` times the blocks of the row k·v_rel (as SetRow writes them: [k; r × k] on
  /// the body, minus [k; r_O × k] on the other) to `on_body` and `on_other`.
  void AddBlocks(const Vec3& k, double scale, Eigen::Matrix<double, 6, 1>& on_body,
                 Eigen::Matrix<double, 6, 1>& on_other) const;
  /// Adds `scale` times the Jacobian row of k·v_rel to `row` (no temporary row).
  void AddRow(const Vec3& k, double scale, RowRef row) const;
  /// J_k u̇ for the row k·v_rel and generalised accelerations u̇ (6 per body; no temporary row).
  double RowTimes(const Vec3& k, const Eigen::VectorXd& u_dot) const;
  /// Adds the generalised force of a moment M on the body (-M on the other) to `row`.
  void AddMoment(const Vec3& M, RowRef row) const;
  /// Unit slip direction, sign relative to the reference `s_ref` (see ContactPointState).
  Vec3 SlipDirection(const Vec3& s_ref) const;
  /// Rolling angular velocity Σ (a_i·w_rel) a_i over the rolling axes [rad/s].
  Vec3 RollingVelocity() const;
  /// Unit rolling direction, sign relative to `r_ref`; zero when r_ref is zero. A rolling
  /// speed at round-off (|w_r| R within 1e-10 of speed_scale) has no direction of its own:
  /// the reference holds, as for SlipDirection.
  Vec3 RollingDirection(const Vec3& r_ref) const;
  /// Rolling angular acceleration Σ a_i (a_i·ẇ_rel - bias_i) for generalised accelerations
  /// u̇ (the rate of the rolling about axes held fixed) [rad/s²].
  Vec3 RollingAcceleration(const Eigen::VectorXd& u_dot) const;
  /// Adds the blocks of the row a·w_rel ([0; a] on the body, [0; -a] on the other).
  void AddRollingBlocks(const Vec3& a, Eigen::Matrix<double, 6, 1>& on_body,
                        Eigen::Matrix<double, 6, 1>& on_other) const;
};

/// Rows that hold the rolling of point p (ContactPointGeometry::num_rolling_axes: 2 for a
/// sphere, 1 for a rim) when it sticks with its rolling held; 0 otherwise.
int HeldRows(const Model& model, const State& state, int p);

/// Needs the kinematics stage (Data::R_WB, Data::w_WB_W).
ContactPointGeometry CalcContactPointGeometry(const Model& model, const State& state,
                                              const Data& data, int point);

/// A x = r: LDLᵀ (symmetric) or LU; when singular the least-norm solution, from the LDLᵀ's
/// null space when A is symmetric semidefinite (the null space kept in `ws`), by complete
/// orthogonal decomposition otherwise. With `column_scale` D the singular case is the weighted
/// least-norm solution, which minimises Σ (x_i / D_i)²: on the null space kept by the
/// unweighted solve of the same symmetric A just before, else x = D y with y the least-norm
/// solution of (A D) y = r. Uses the factorisations and vectors of `ws`: no allocation once
/// they have A's size. Returns true when the least-norm branch was taken (A singular, or
/// `column_scale` given: the caller knows A is singular).
bool SolveSquare(const Eigen::MatrixXd& A, const Eigen::VectorXd& r, bool symmetric,
                 ContactWorkspace& ws, Eigen::VectorXd& x,
                 const Eigen::VectorXd* column_scale = nullptr);

}  // namespace chasles::internal
