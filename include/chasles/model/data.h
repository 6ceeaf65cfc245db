#pragma once
/// @file
/// Data: a workspace of derived, recomputable quantities for one Model. Each field says which
/// step fills it. Make it once with MakeData and reuse it: the hot loops never allocate.
///
/// A Data belongs to the Model it was made for: MakeData(model) records model.id(), and every
/// algorithm that takes (model, ..., data) throws UsageError (error.h: a bug in the calling
/// code, not bad input) when `data` was made for another Model (a copy of the Model too, or
/// the same Model before a body, force element, constraint or contact was added). A copy of a
/// Data belongs to the same Model as the original.

#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/QR>

#include "chasles/math/types.h"
#include "chasles/model/constraint.h"
#include "chasles/model/contact.h"

namespace chasles {

class Model;

/// What one force element did at the evaluated state (filled by CalcForces).
struct ForceElementOutput {
  /// Power of all its forces and moments on all bodies [W].
  double power = 0.0;
  /// Power of its non-conservative part [W] (equal to `power` unless it has a potential).
  double power_nonconservative = 0.0;
  /// Sum of its forces, in W [N].
  Vec3 force_W = Vec3::Zero();
  /// Sum of the moments of its forces about the world origin plus its pure moments, in W [N·m].
  Vec3 moment_Wo_W = Vec3::Zero();
};

/// What one constraint does at the evaluated state (filled by the constraint stage of
/// CalcAccelerations). The reaction is the force and moment the parent (or the world) exerts
/// on the child at the joint point J: the child's share of Jᵀλ, with its moment moved from the
/// child's centre of mass to J.
struct ConstraintOutput {
  /// Multipliers of its rows (the first num_rows() entries) [N or N·m per row].
  ConstraintEval::Column lambda = ConstraintEval::Column::Zero();
  /// Joint (or contact) point J on the child, in W [m].
  Vec3 p_WJ = Vec3::Zero();
  /// Reaction force on the child at J, in W [N].
  Vec3 F_Jc_W = Vec3::Zero();
  /// Reaction moment on the child about J, in W [N·m].
  Vec3 M_Jc_W = Vec3::Zero();
  /// Reaction force on the child at J, in the child's frame B [N].
  Vec3 F_Jc_B = Vec3::Zero();
  /// Reaction moment on the child about J, in the child's frame B [N·m].
  Vec3 M_Jc_B = Vec3::Zero();
  /// Power of the constraint's forces on all its bodies, λᵀ J u [W] (0 for ideal joints and
  /// rolling; a driver's power otherwise).
  double power = 0.0;
};

/// Factorisation workspace of the constraint solve. Eigen's LDLT leaves its status flag unset
/// until compute() yet copies it with the object, which is undefined behaviour (UBSan reports
/// it). Every solve refactorises, so a copy of Data starts with a fresh, empty factorisation
/// instead of copying one; the first compute() sizes it and later ones reuse its storage.
struct SchurFactorization {
  Eigen::LDLT<Eigen::MatrixXd> ldlt;
  SchurFactorization() = default;
  SchurFactorization(const SchurFactorization&) {}
  SchurFactorization& operator=(const SchurFactorization&) { return *this; }
};

/// Which factorisation the constraint and contact stages use for J M⁻¹ Wᵀ (docs/design.md,
/// "Sparse constraint and contact solves").
enum class LinearSolver {
  kAuto,    ///< sparse from kSparseMinRows active rows on, dense below
  kDense,   ///< dense J, dense J M⁻¹ Wᵀ, dense LDLᵀ / LU (least-norm COD when singular)
  kSparse,  ///< J by body blocks, sparse J M⁻¹ Wᵀ, sparse LDLᵀ / LU; when singular, the
            ///< same least-norm answer sparsely if W = J, else the dense path's
};

/// Fewest active rows (40) for which LinearSolver::kAuto takes the sparse path. The sparse path
/// measured faster from 10 rows on, twice as fast at 40 (bench/solve_bench.cpp,
/// docs/benchmarks.md); below 40 small models keep the dense path's exact numbers.
extern const int kSparseMinRows;

namespace internal {
struct SparseWorkspace;
}

/// Owner of a sparse-solve workspace (dynamics/internal/sparse_solve.h), made on first use.
/// Copies start empty (see SchurFactorization).
struct SparseWorkspaceHandle {
  std::unique_ptr<internal::SparseWorkspace, void (*)(internal::SparseWorkspace*)> ptr{nullptr,
                                                                                       nullptr};
  SparseWorkspaceHandle() = default;
  SparseWorkspaceHandle(const SparseWorkspaceHandle&) {}
  SparseWorkspaceHandle& operator=(const SparseWorkspaceHandle&) { return *this; }
};

/// What one contact point does at the evaluated state (filled by the contact stage of
/// CalcAccelerations for models with contacts, in the modes the State carries).
struct ContactPointOutput {
  /// Mode the point was evaluated in.
  ContactMode mode = ContactMode::kSeparated;
  /// Gap between the shape and the plane (or the other sphere) [m] (< 0: penetration).
  double gap = 0.0;
  /// Contact point on the body, in W [m].
  Vec3 p_WC = Vec3::Zero();
  /// Contact normal (from the plane or other sphere towards the body), in W.
  Vec3 n_W = Vec3::UnitZ();
  /// Normal force on the body, N >= 0 in a consistent mode [N].
  double normal_force = 0.0;
  /// Friction force on the body (tangential), in W [N].
  Vec3 friction_force_W = Vec3::Zero();
  /// Normal velocity of the body's material point at C relative to the plane (other body)
  /// [m/s] (< 0 approaching).
  double normal_velocity = 0.0;
  /// Tangential (slip) velocity of the body's material point at C relative to the plane
  /// (other body), in W [m/s].
  Vec3 slip_velocity_W = Vec3::Zero();
  /// Rolling-resistance moment on the body, in W [N·m]: -mu_r N R ŵ_r while the point rolls,
  /// the holding moment (|M| <= mu_r N R) while its rolling is held.
  Vec3 rolling_moment_W = Vec3::Zero();
  /// Whether the point was evaluated with its rolling held (ContactPointState::rolling_held).
  bool rolling_held = false;
  /// Rolling angular velocity of the body relative to the plane (other body), in W [rad/s]:
  /// the part of the relative angular velocity about the feature's rolling axes (both
  /// tangents for a sphere, the rim's axis projected on the plane for a rim; zero for a
  /// point).
  Vec3 rolling_velocity_W = Vec3::Zero();
  /// Largest rolling-resistance moment the point can hold, mu_r N R [N·m] (0 without rolling
  /// resistance).
  double rolling_moment_capacity = 0.0;
  /// Power of sliding friction, f·v_slip [W] (<= 0).
  double friction_power = 0.0;
  /// Power of the rolling-resistance moment [W] (<= 0).
  double rolling_power = 0.0;
  /// |f| / N of a sticking point (compare with mu_s); 0 otherwise.
  double friction_needed = 0.0;
  /// Tangential acceleration of the body's material point at C relative to the plane (other
  /// body), in W [m/s²]: zero for a sticking point; for a sliding point whose slip is zero it
  /// says where the slip goes (used to check that a slip that starts is consistent).
  Vec3 slip_acceleration_W = Vec3::Zero();
  /// Rolling angular acceleration (the rate of rolling_velocity_W about the fixed rolling
  /// axes), in W [rad/s²]: zero while the rolling is held; for a rolling point whose rolling
  /// is zero it says where the rolling goes (a rolling start is checked with it).
  Vec3 rolling_acceleration_W = Vec3::Zero();
};

/// Workspace of the contact stage: the stacked active rows of constraints and contacts, the
/// force directions W (equal to J except for sliding rows, where W = J_n - mu_k J_s), and the
/// factorisations. Copies start empty (see SchurFactorization); each solve refactorises.
struct ContactWorkspace {
  /// Active rows J, their force directions W, right-hand sides c, multipliers λ.
  Eigen::MatrixXd J, W, WMinv, A;
  Eigen::VectorXd c, rhs, lambda;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;
  Eigen::LDLT<Eigen::MatrixXd> ldlt;
  /// Least-norm solve of redundant rows and its vectors (sized with A: no allocation while
  /// the modes stay; cod_x also holds the pivot order of the pivoted LDLᵀ below).
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;
  Eigen::VectorXd cod_c, cod_x, cod_temp;
  /// A singular symmetric system's orthonormal null-space basis (its first null_rank columns,
  /// kept for the weighted solve of the same system), a particular solution, the pivoted LDLᵀ
  /// (null_gram, then the weighted step's Gram matrix), a scratch (dynamics/contact_solve.cpp).
  Eigen::MatrixXd null_basis, null_weighted, null_gram;
  Eigen::VectorXd null_particular;
  Eigen::Index null_rank = 0;
  bool null_ready = false;
  /// Column scales of a weighted least-norm solve (friction shared by capacity) and the
  /// column-scaled matrix A D.
  Eigen::VectorXd scale;
  Eigen::MatrixXd AD;
  ContactWorkspace() = default;
  ContactWorkspace(const ContactWorkspace&) {}
  ContactWorkspace& operator=(const ContactWorkspace&) { return *this; }
};

/// Workspace of the projection onto the active contact rows (ProjectOntoContactModes): the
/// position rows (holonomic constraint rows, gap rows) and the velocity rows (all active rows)
/// each with its own factorisation, so that alternating between them does not reallocate.
struct ContactProjectionWorkspace {
  /// Position rows G, residual g in `c`; velocity rows J, residual J u - b in `c`.
  ContactWorkspace position, velocity;
  /// Holonomic constraint rows (indices into Data::J) and their constraints.
  std::vector<int> holonomic_rows, holonomic_owner;
  /// Correction of the positions [m, rad] or velocities [m/s, rad/s], 6 per body.
  Eigen::VectorXd dx;
  /// The rows by body blocks and the sparse factorisations of the two stages (systems of
  /// kSparseMinRows rows and more).
  SparseWorkspaceHandle sparse_position, sparse_velocity;
};

struct Data {
  /// Model::id() of the Model MakeData made this Data for (0: not made by MakeData).
  std::uint64_t model_id = 0;

  // --- Position and velocity stage: CalcKinematics(model, state, data) ---
  /// Rotation matrix of each body, R_WB (from the normalised quaternion).
  std::vector<Mat3> R_WB;
  /// Angular velocity of each body, expressed in W [rad/s].
  std::vector<Vec3> w_WB_W;

  // --- Force stage: CalcForces(model, state, data) ---
  /// Resultant force on each body, in W [N].
  std::vector<Vec3> F_Bcm_W;
  /// Resultant moment about each body's centre of mass, in W [N·m].
  std::vector<Vec3> M_Bcm_W;
  /// Per force element (Model order).
  std::vector<ForceElementOutput> elements;

  // --- Acceleration stage: CalcAccelerations(model, state, data) ---
  /// Acceleration of each centre of mass, in W [m/s²].
  std::vector<Vec3> a_WBcm_W;
  /// Angular acceleration of each body, expressed in B [rad/s²].
  std::vector<Vec3> wdot_WB_B;

  // --- Constraint stage: CalcAccelerations, after the free accelerations (models with
  //     constraints only); the rows alone: CalcConstraintRows ---
  /// Per constraint (Model order): its rows at the evaluated state.
  std::vector<ConstraintEval> constraint_rows;
  /// Per constraint (Model order): multipliers and reactions.
  std::vector<ConstraintOutput> constraints;
  /// Stacked Jacobian J (rows × 6 num_bodies; columns per body [v_WBcm_W, w_WB_W]), dense, sized
  /// only where a dense solve reads it: by MakeData below kSparseMinRows rows, else by the first
  /// dense consumer (kDense, ProjectOntoConstraints, impacts, AnalyseRedundancy); till then 0 × 0
  /// (the rows are in constraint_rows). Sized, CalcConstraintRows keeps it current in O(rows).
  Eigen::MatrixXd J;
  /// Stacked velocity right-hand side b, acceleration right-hand side c, position error g.
  Eigen::VectorXd velocity_rhs, acceleration_rhs, position_error;
  /// Stacked multipliers λ (generalised constraint force Jᵀλ).
  Eigen::VectorXd lambda;
  /// Per row: 1 when its constraint is released (a slack string): its row in J, b, c and g is
  /// zero and its multiplier is held at 0 (CalcConstraintRows).
  std::vector<char> row_released;
  /// Per constraint: the gap g >= 0 of one that can let go (a string's slack L0 - L), in
  /// either mode; 0 for the others [m] (CalcConstraintRows).
  std::vector<double> constraint_gap;
  /// Rank of J M⁻¹ Jᵀ found by the solve (< rows when constraints are redundant).
  int constraint_rank = 0;
  /// Workspace of the constraint solve, sized once by MakeData so that the derivative
  /// evaluations do not allocate: J M⁻¹, J M⁻¹ Jᵀ and its factorisation (dense path; sized as
  /// J is), the generalised velocity u and acceleration u̇, J u, and the right-hand side of the
  /// multiplier system.
  Eigen::MatrixXd JMinv, schur;
  SchurFactorization schur_ldlt;
  Eigen::VectorXd u, u_dot, Ju, schur_rhs;

  // --- Contact stage: CalcAccelerations for models with contacts (includes the constraint
  //     stage: constraints and active contact rows are solved together) ---
  /// Per contact point (Model::num_contact_points()): forces, velocities, gap.
  std::vector<ContactPointOutput> contact_points;
  /// Workspace of the contact stage.
  ContactWorkspace contact_work;
  /// Workspace of ProjectOntoContactModes (contact_projection.h).
  ContactProjectionWorkspace contact_projection;

  // --- Linear solver of the constraint and contact stages ---
  /// Dense or sparse (LinearSolver); both give the same answer to round-off.
  LinearSolver linear_solver = LinearSolver::kAuto;
  /// Workspaces of the sparse constraint stage and contact stage.
  SparseWorkspaceHandle sparse_constraints, sparse_contacts;
};

/// A Data sized for `model` (and bound to it).
Data MakeData(const Model& model);

/// Throws UsageError ("this Data was made for another Model; make one with MakeData(model)")
/// unless `data` was made by MakeData(model). Every algorithm taking (model, ..., data) calls it
/// first: one comparison.
void CheckDataFor(const Model& model, const Data& data);

}  // namespace chasles
