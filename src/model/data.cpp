#include "chasles/model/data.h"

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/model/model.h"

namespace chasles {

// The sparse path is already twice as fast at 40 rows (docs/benchmarks.md, "Sparse constraint
// and contact solves"); smaller systems keep the dense path.
const int kSparseMinRows = 40;

Data MakeData(const Model& model) {
  const auto nb = static_cast<size_t>(model.num_bodies());
  Data d;
  d.model_id = model.id();
  d.R_WB.assign(nb, Mat3::Identity());
  d.w_WB_W.assign(nb, Vec3::Zero());
  d.F_Bcm_W.assign(nb, Vec3::Zero());
  d.M_Bcm_W.assign(nb, Vec3::Zero());
  d.elements.assign(static_cast<size_t>(model.num_force_elements()), ForceElementOutput{});
  d.a_WBcm_W.assign(nb, Vec3::Zero());
  d.wdot_WB_B.assign(nb, Vec3::Zero());
  const auto nc = static_cast<size_t>(model.num_constraints());
  const int rows = model.num_constraint_rows();
  d.constraint_rows.assign(nc, ConstraintEval{});
  d.constraints.assign(nc, ConstraintOutput{});
  d.velocity_rhs = Eigen::VectorXd::Zero(rows);
  d.acceleration_rhs = Eigen::VectorXd::Zero(rows);
  d.position_error = Eigen::VectorXd::Zero(rows);
  d.lambda = Eigen::VectorXd::Zero(rows);
  d.row_released.assign(static_cast<size_t>(rows), 0);
  d.constraint_gap.assign(nc, 0.0);
  d.constraint_rank = rows;
  // The dense Jacobian and the dense path's workspace only where LinearSolver::kAuto takes that
  // path (the sparse path keeps its own rows and workspace; a dense solve of a larger system
  // sizes these on first use, J through internal::EnsureDenseJacobian). A chain of 1,000 links
  // would otherwise zero a 5,000 × 6,000 J for every Data made.
  if (rows < kSparseMinRows) {
    d.J = Eigen::MatrixXd::Zero(rows, 6 * model.num_bodies());
    d.JMinv = Eigen::MatrixXd::Zero(rows, 6 * model.num_bodies());
    d.schur = Eigen::MatrixXd::Zero(rows, rows);
  }
  d.u = Eigen::VectorXd::Zero(6 * model.num_bodies());
  d.u_dot = Eigen::VectorXd::Zero(6 * model.num_bodies());
  d.Ju = Eigen::VectorXd::Zero(rows);
  d.schur_rhs = Eigen::VectorXd::Zero(rows);
  d.contact_points.assign(static_cast<size_t>(model.num_contact_points()), ContactPointOutput{});
  return d;
}

void CheckDataFor(const Model& model, const Data& data) {
  if (data.model_id == model.id()) return;
  if (data.model_id == 0) {
    throw UsageError(
        "this Data was not made by MakeData; make one with MakeData(model) for the Model it is "
        "used with");
  }
  throw UsageError(fmt::format(
      "this Data was made for another Model (id {}; the Model given has id {}, with {} bodies); "
      "make one with MakeData(model). A copy of a Model is another Model, and adding a body, "
      "force element, constraint or contact makes the Data made before it stale",
      data.model_id, model.id(), model.num_bodies()));
}

}  // namespace chasles
