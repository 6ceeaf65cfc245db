#include "dynamics/internal/generalized.h"

#include <algorithm>

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/model/string_constraint.h"

namespace chasles::internal {

// Mass-matrix helpers over the 6-per-body generalised velocity u_b = [v_WBcm_W; w_WB_W].
// Linear block / m, angular block times I_W⁻¹ = R I_B⁻¹ Rᵀ (symmetric, so right and left
// products agree). Y is resized only when its shape differs.
void TimesMassInverse(const Model& model, const Data& data, const Eigen::MatrixXd& X,
                      Eigen::MatrixXd& Y) {
  Y.resize(X.rows(), X.cols());
  for (int b = 0; b < model.num_bodies(); ++b) {
    const auto i = static_cast<size_t>(b);
    const Body& body = model.body(b);
    const Mat3 I_inv_W = data.R_WB[i] * body.I_BBcm_B_inverse() * data.R_WB[i].transpose();
    Y.middleCols<3>(6 * b) = X.middleCols<3>(6 * b) / body.mass();
    Y.middleCols<3>(6 * b + 3).noalias() = X.middleCols<3>(6 * b + 3) * I_inv_W;
  }
}

void GetVelocity(const Model& model, const State& state, const Data& data, Eigen::VectorXd& u) {
  u.resize(6 * model.num_bodies());
  for (int b = 0; b < model.num_bodies(); ++b) {
    const auto i = static_cast<size_t>(b);
    u.segment<3>(6 * b) = state.bodies[i].v_WBcm_W;
    u.segment<3>(6 * b + 3) = data.w_WB_W[i];
  }
}

void SetVelocity(const Model& model, const Data& data, const Eigen::VectorXd& u, State& state) {
  for (int b = 0; b < model.num_bodies(); ++b) {
    const auto i = static_cast<size_t>(b);
    state.bodies[i].v_WBcm_W = u.segment<3>(6 * b);
    state.bodies[i].w_WB_B = data.R_WB[i].transpose() * u.segment<3>(6 * b + 3);
  }
}

void HoldReleasedRows(const std::vector<char>& released, Eigen::MatrixXd& A, Eigen::VectorXd& r) {
  for (size_t k = 0; k < released.size(); ++k) {
    if (released[k] == 0) continue;
    const auto i = static_cast<Eigen::Index>(k);
    A.row(i).setZero();
    A.col(i).setZero();
    A(i, i) = 1.0;
    r[i] = 0.0;
  }
}

void WriteConstraintBlocks(const Model& model, const Data& data, int c,
                           Eigen::Ref<Eigen::MatrixXd> J) {
  const Constraint& con = model.constraint(c);
  const ConstraintEval& e = data.constraint_rows[static_cast<size_t>(c)];
  const int o = model.constraint_row_offset(c);
  const int n = con.num_rows();
  if (data.row_released[static_cast<size_t>(o)] != 0) return;
  if (con.parent() != kWorld) J.block(o, 6 * con.parent(), n, 6) = e.J_parent.topRows(n);
  J.block(o, 6 * con.child(), n, 6) = e.J_child.topRows(n);
  for (int k = 0; k < e.num_extra; ++k) {
    const auto j = static_cast<size_t>(k);
    J.block(o, 6 * e.extra_body[j], n, 6) = e.J_extra[j].topRows(n);
  }
}

void EnsureDenseJacobian(const Model& model, Data& data) {
  const int rows = model.num_constraint_rows(), cols = 6 * model.num_bodies();
  if (data.J.rows() == rows && data.J.cols() == cols) return;
  data.J.setZero(rows, cols);
  for (int c = 0; c < model.num_constraints(); ++c) WriteConstraintBlocks(model, data, c, data.J);
}

void ConstraintJacobianTimes(const Model& model, const Data& data, const Eigen::VectorXd& x,
                             Eigen::Ref<Eigen::VectorXd> out) {
  const int rows = model.num_constraint_rows();
  if (rows < kSparseMinRows && data.J.rows() == rows && data.J.cols() == x.size()) {
    out.noalias() = data.J * x;
    return;
  }
  for (int c = 0; c < model.num_constraints(); ++c) {
    const Constraint& con = model.constraint(c);
    const ConstraintEval& e = data.constraint_rows[static_cast<size_t>(c)];
    const int o = model.constraint_row_offset(c);
    const int n = con.num_rows();
    auto y = out.segment(o, n);
    y.setZero();
    if (data.row_released[static_cast<size_t>(o)] != 0) continue;
    if (con.parent() != kWorld)
      y.noalias() += e.J_parent.topRows(n) * x.segment<6>(6 * con.parent());
    y.noalias() += e.J_child.topRows(n) * x.segment<6>(6 * con.child());
    for (int k = 0; k < e.num_extra; ++k) {
      const auto j = static_cast<size_t>(k);
      y.noalias() += e.J_extra[j].topRows(n) * x.segment<6>(6 * e.extra_body[j]);
    }
  }
}

double KineticEnergy(const Model& model, const State& state) {
  double T = 0.0;
  for (int b = 0; b < model.num_bodies(); ++b) {
    const BodyState& bs = state.bodies[static_cast<size_t>(b)];
    const Body& body = model.body(b);
    T += 0.5 * body.mass() * bs.v_WBcm_W.squaredNorm() +
         0.5 * bs.w_WB_B.dot(body.I_BBcm_B() * bs.w_WB_B);
  }
  return T;
}

namespace {

// A string's multiplier is its tension (model/string_constraint.h). A string wound on a drum
// cannot go slack (its row is velocity-level: the state holds the drum's angle only modulo a
// turn, so the slack could not be tracked), so a negative tension stops the run there (a
// tolerance of 1e-9 of the largest force in play absorbs round-off). Strings without drums go
// slack at an event instead (integrate/hybrid.cpp).
void CheckStringTaut(const Model& model, int c, double tension, const Data& data, double t) {
  const Constraint& con = model.constraint(c);
  if (dynamic_cast<const StringConstraint*>(&con) == nullptr || con.can_release()) return;
  double scale = data.lambda.size() > 0 ? data.lambda.cwiseAbs().maxCoeff() : 0.0;
  for (const Vec3& F : data.F_Bcm_W) scale = std::max(scale, F.norm());
  if (tension < -1e-9 * scale) {
    throw InputError(
        fmt::format(
            "string '{}' would go slack at t = {:.6g} s: its tension comes out {:.6g} N, and a "
            "string can only pull; a string wound on a drum is held taut (how far the drum has "
            "turned is known only modulo a turn, so its slack cannot be tracked): tie it to a "
            "point of the body instead of a drum",
            con.name(), t, tension),
        ErrorElement{ErrorElement::Kind::kConstraint, c});
  }
}

}  // namespace

void FillConstraintReactions(const Model& model, const State& state, Data& data) {
  GetVelocity(model, state, data, data.u);
  data.Ju.resize(model.num_constraint_rows());
  for (int c = 0; c < model.num_constraints(); ++c) {
    const Constraint& con = model.constraint(c);
    const auto ci = static_cast<size_t>(c);
    const ConstraintEval& e = data.constraint_rows[ci];
    ConstraintOutput& out = data.constraints[ci];
    const int o = model.constraint_row_offset(c);
    const int n = con.num_rows();
    // J u by the constraint's own blocks (its rows of Data::J; zero when released).
    auto Ju = data.Ju.segment(o, n);
    Ju.setZero();
    if (data.row_released[static_cast<size_t>(o)] == 0) {
      if (con.parent() != kWorld)
        Ju.noalias() += e.J_parent.topRows(n) * data.u.segment<6>(6 * con.parent());
      Ju.noalias() += e.J_child.topRows(n) * data.u.segment<6>(6 * con.child());
      for (int k = 0; k < e.num_extra; ++k) {
        const auto j = static_cast<size_t>(k);
        Ju.noalias() += e.J_extra[j].topRows(n) * data.u.segment<6>(6 * e.extra_body[j]);
      }
    }
    out.lambda.setZero();
    out.lambda.head(n) = data.lambda.segment(o, n);
    const Eigen::Matrix<double, 6, 1> Fc = e.J_child.topRows(n).transpose() * out.lambda.head(n);
    const auto bi = static_cast<size_t>(con.child());
    const Vec3 F = Fc.head<3>();
    const Vec3 r_J = e.p_WJ - state.bodies[bi].p_WBcm;
    out.p_WJ = e.p_WJ;
    out.F_Jc_W = F;
    out.M_Jc_W = Fc.tail<3>() - r_J.cross(F);
    out.F_Jc_B = data.R_WB[bi].transpose() * out.F_Jc_W;
    out.M_Jc_B = data.R_WB[bi].transpose() * out.M_Jc_W;
    out.power = data.lambda.segment(o, n).dot(data.Ju.segment(o, n));
    CheckStringTaut(model, c, out.lambda[0], data, state.t);
  }
}

}  // namespace chasles::internal
