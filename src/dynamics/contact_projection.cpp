#include "chasles/dynamics/contact_projection.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "chasles/dynamics/newton_euler.h"
#include "chasles/error.h"
#include "chasles/math/quaternion.h"
#include "dynamics/internal/contact_geometry.h"
#include "dynamics/internal/generalized.h"
#include "dynamics/internal/sparse_solve.h"

namespace chasles {
namespace {

using internal::ContactPointGeometry;

ContactMode ModeOf(const State& state, int p) {
  return static_cast<size_t>(p) < state.contacts.size()
             ? state.contacts[static_cast<size_t>(p)].mode
             : ContactMode::kSeparated;
}

// Appends the row k·v_rel of a contact point (W = J) to `rows`.
void AppendPointRow(const ContactPointGeometry& g, const Vec3& k, internal::BlockRows& rows) {
  internal::Vec6 on_body = internal::Vec6::Zero(), on_other = internal::Vec6::Zero();
  g.AddBlocks(k, 1.0, on_body, on_other);
  rows.Add(g.body, on_body, on_body);
  if (g.other != kWorld) rows.Add(g.other, on_other, on_other);
  rows.EndRow();
}

// The velocity rows of the points in contact (W = J) with their residuals in c from row k on:
// the normal velocity, the slip of a sticking point, and the rolling of a held one
// (a·w_rel = 0 about each rolling axis).
void AppendVelocityRows(const Model& model, const State& state, const Data& data,
                        internal::BlockRows& rows, Eigen::VectorXd& c, Eigen::Index k) {
  for (int p = 0; p < model.num_contact_points(); ++p) {
    const ContactMode mode = ModeOf(state, p);
    if (mode == ContactMode::kSeparated) continue;
    const ContactPointGeometry g = internal::CalcContactPointGeometry(model, state, data, p);
    AppendPointRow(g, g.n, rows);
    c[k++] = g.v_n;
    if (mode != ContactMode::kSticking) continue;
    for (const Vec3* t : {&g.t1, &g.t2}) {
      AppendPointRow(g, *t, rows);
      c[k++] = t->dot(g.v_rel);
    }
    for (int i = 0; i < internal::HeldRows(model, state, p); ++i) {
      internal::Vec6 on_body = internal::Vec6::Zero(), on_other = internal::Vec6::Zero();
      g.AddRollingBlocks(g.rolling_axis[i], on_body, on_other);
      rows.Add(g.body, on_body, on_body);
      if (g.other != kWorld) rows.Add(g.other, on_other, on_other);
      rows.EndRow();
      c[k++] = g.rolling_axis[i].dot(g.w_rel);
    }
  }
}

// δ = -M⁻¹Gᵀ(G M⁻¹Gᵀ)⁺ r for the rows G in sp.rows with residual ws.c; the correction goes to
// `d`. Any λ with (G M⁻¹Gᵀ) λ = r gives the same δ (two differ by a vector of null(Gᵀ)), so
// the sparse path (dynamics/internal/sparse_solve.h: LDLᵀ, or its least-norm iteration for
// redundant rows) and the dense one agree to round-off; the dense one also takes what the
// sparse one leaves (an inconsistent r: gaps that cannot all close keep the least-squares
// remainder).
void MassWeightedCorrection(const Model& model, const Data& data, internal::SparseWorkspace& sp,
                            ContactWorkspace& ws, Eigen::VectorXd& d) {
  const int nb = model.num_bodies();
  if (internal::UseSparse(data.linear_solver, sp.rows.rows()) &&
      (internal::SolveSparse(model, data, true, sp, ws.c, ws.lambda) ||
       (sp.singular_symmetric && internal::SolveSparseLeastNorm(sp, ws.c, nullptr, ws.lambda)))) {
    ws.lambda = -ws.lambda;
    d.setZero(6 * nb);
    internal::AddMinvWTimes(sp, ws.lambda, d);
    return;
  }
  internal::ScatterBlocks(sp.rows, nb, ws.J);
  internal::TimesMassInverse(model, data, ws.J, ws.WMinv);
  ws.A.noalias() = ws.WMinv * ws.J.transpose();
  internal::SolveSquare(ws.A, ws.c, true, ws, ws.lambda);
  d.noalias() = -ws.WMinv.transpose() * ws.lambda;
}

}  // namespace

bool HasActiveContactRows(const Model& model, const State& state) {
  for (int p = 0; p < model.num_contact_points(); ++p) {
    if (ModeOf(state, p) != ContactMode::kSeparated) return true;
  }
  return false;
}

ContactViolation CalcContactViolation(const Model& model, const State& state, Data& data) {
  CheckDataFor(model, data);
  ContactViolation v;
  CalcKinematics(model, state, data);
  double worst = -1.0;
  for (int p = 0; p < model.num_contact_points(); ++p) {
    const ContactMode mode = ModeOf(state, p);
    if (mode == ContactMode::kSeparated) continue;
    const ContactPointGeometry g = internal::CalcContactPointGeometry(model, state, data, p);
    const double slip = mode == ContactMode::kSticking ? g.v_t.norm() : 0.0;
    v.gap = std::max(v.gap, std::abs(g.gap));
    v.normal_velocity = std::max(v.normal_velocity, std::abs(g.v_n));
    v.slip = std::max(v.slip, slip);
    const double here = std::max({std::abs(g.gap), std::abs(g.v_n), slip});
    if (here > worst) worst = here, v.worst = p;
  }
  return v;
}

void ProjectOntoContactModes(const Model& model, State& state, Data& data,
                             const ProjectionOptions& options) {
  CheckDataFor(model, data);
  if (!HasActiveContactRows(model, state)) {
    ProjectOntoConstraints(model, state, data, options);
    return;
  }
  const int nb = model.num_bodies();
  const int np = model.num_contact_points();
  const bool has_constraints = model.num_constraints() > 0;
  ContactProjectionWorkspace& pw = data.contact_projection;
  // Rows: the holonomic constraint rows (known after the first evaluation of the rows), then
  // one gap row per point in contact.
  int n_contact = 0, n_velocity_contact = 0;
  for (int p = 0; p < np; ++p) {
    const ContactMode m = ModeOf(state, p);
    if (m != ContactMode::kSeparated) ++n_contact;
    n_velocity_contact += m == ContactMode::kSticking ? 3 + internal::HeldRows(model, state, p)
                                                      : (m == ContactMode::kSliding ? 1 : 0);
  }
  for (int iter = 0; iter <= options.max_iterations; ++iter) {
    CalcKinematics(model, state, data);
    if (has_constraints) CalcConstraintRows(model, state, data);
    if (iter == 0) {
      pw.holonomic_rows.clear();
      pw.holonomic_owner.clear();
      for (int c = 0; c < model.num_constraints(); ++c) {
        const ConstraintEval& e = data.constraint_rows[static_cast<size_t>(c)];
        for (int k = 0; k < model.constraint(c).num_rows(); ++k) {
          if (e.holonomic[static_cast<size_t>(k)]) {
            pw.holonomic_rows.push_back(model.constraint_row_offset(c) + k);
            pw.holonomic_owner.push_back(c);
          }
        }
      }
    }
    ContactWorkspace& ws = pw.position;
    internal::SparseWorkspace& sp = internal::GetSparseWorkspace(pw.sparse_position);
    const auto nh = static_cast<Eigen::Index>(pw.holonomic_rows.size());
    ws.c.resize(nh + n_contact);
    sp.rows.Clear();
    for (Eigen::Index k = 0; k < nh; ++k) {
      const int row = pw.holonomic_rows[static_cast<size_t>(k)];
      const int c = pw.holonomic_owner[static_cast<size_t>(k)];
      internal::AppendConstraintRow(model, data, c, row - model.constraint_row_offset(c), sp.rows);
      ws.c[k] = data.position_error[row];
    }
    Eigen::Index k = nh;
    for (int p = 0; p < np; ++p) {
      if (ModeOf(state, p) == ContactMode::kSeparated) continue;
      // ġ = n·v_C (the envelope of the lowest point, contact_solve.cpp), so the normal row is
      // the gap's gradient in the generalised coordinates [δp; δθ].
      const ContactPointGeometry g = internal::CalcContactPointGeometry(model, state, data, p);
      AppendPointRow(g, g.n, sp.rows);
      ws.c[k++] = g.gap;
    }
    Eigen::Index worst = 0;
    const double g_max = ws.c.cwiseAbs().maxCoeff(&worst);
    if (g_max <= options.position_tolerance) break;
    if (iter == options.max_iterations) {
      // A constraint that cannot be assembled is an input error (as ProjectOntoConstraints);
      // contact gaps that cannot all close keep the least-squares remainder.
      if (worst < nh && g_max > options.assembly_tolerance) {
        throw InputError(
            fmt::format(
                "constraint '{}' cannot be satisfied: after {} Gauss-Newton steps its position "
                "error is still {:.3g}; check its attachment points and axes against the other "
                "constraints",
                model.constraint(pw.holonomic_owner[static_cast<size_t>(worst)]).name(),
                options.max_iterations, g_max),
            ErrorElement{ErrorElement::Kind::kConstraint,
                         pw.holonomic_owner[static_cast<size_t>(worst)]});
      }
      break;
    }
    MassWeightedCorrection(model, data, sp, ws, pw.dx);
    for (int b = 0; b < nb; ++b) {
      BodyState& bs = state.bodies[static_cast<size_t>(b)];
      bs.p_WBcm += pw.dx.segment<3>(6 * b);
      // δθ is a small rotation about W's axes: q ← exp(δθ) ⊗ q.
      bs.q_WB = (QuatExp(pw.dx.segment<3>(6 * b + 3)) * bs.q_WB).normalized();
    }
  }
  // Velocities: constraint rows J u = b and the active contact rows (target 0).
  CalcKinematics(model, state, data);
  if (has_constraints) CalcConstraintRows(model, state, data);
  ContactWorkspace& ws = pw.velocity;
  internal::SparseWorkspace& sp = internal::GetSparseWorkspace(pw.sparse_velocity);
  const int nc_rows = model.num_constraint_rows();
  ws.c.resize(nc_rows + n_velocity_contact);
  sp.rows.Clear();
  internal::GetVelocity(model, state, data, data.u);
  if (has_constraints) {
    internal::AppendConstraintRows(model, data, sp.rows);
    internal::ConstraintJacobianTimes(model, data, data.u, ws.c.head(nc_rows));
    ws.c.head(nc_rows) -= data.velocity_rhs;
  }
  AppendVelocityRows(model, state, data, sp.rows, ws.c, nc_rows);
  if (ws.c.size() == 0 || ws.c.cwiseAbs().maxCoeff() == 0.0) return;
  MassWeightedCorrection(model, data, sp, ws, pw.dx);
  for (int b = 0; b < nb; ++b) {
    const auto i = static_cast<size_t>(b);
    BodyState& bs = state.bodies[i];
    bs.v_WBcm_W += pw.dx.segment<3>(6 * b);
    bs.w_WB_B += data.R_WB[i].transpose() * pw.dx.segment<3>(6 * b + 3);
  }
  CalcKinematics(model, state, data);  // leave the kinematics stage consistent with `state`
}

}  // namespace chasles
