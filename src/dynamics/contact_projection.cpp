#include "chasles/dynamics/contact_projection.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "chasles/dynamics/newton_euler.h"
#include "chasles/error.h"
#include "chasles/math/quaternion.h"
#include "dynamics/internal/contact_geometry.h"

namespace chasles {
namespace {

using internal::ContactPointGeometry;

ContactMode ModeOf(const State& state, int p) {
  return static_cast<size_t>(p) < state.contacts.size()
             ? state.contacts[static_cast<size_t>(p)].mode
             : ContactMode::kSeparated;
}

// δ = -M⁻¹Gᵀ(G M⁻¹Gᵀ)⁺ r for the rows in ws.J with residual ws.c; the correction goes to `d`.
void MassWeightedCorrection(const Model& model, const Data& data, ContactWorkspace& ws,
                            Eigen::VectorXd& d) {
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
    n_velocity_contact += m == ContactMode::kSticking ? 3 : (m == ContactMode::kSliding ? 1 : 0);
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
    const auto nh = static_cast<Eigen::Index>(pw.holonomic_rows.size());
    const Eigen::Index rows = nh + n_contact;
    if (ws.J.rows() != rows || ws.J.cols() != 6 * nb) ws.J.resize(rows, 6 * nb), ws.c.resize(rows);
    ws.J.setZero();
    for (Eigen::Index k = 0; k < nh; ++k) {
      ws.J.row(k) = data.J.row(pw.holonomic_rows[static_cast<size_t>(k)]);
      ws.c[k] = data.position_error[pw.holonomic_rows[static_cast<size_t>(k)]];
    }
    Eigen::Index k = nh;
    for (int p = 0; p < np; ++p) {
      if (ModeOf(state, p) == ContactMode::kSeparated) continue;
      // ġ = n·v_C (the envelope of the lowest point, contact_solve.cpp), so the normal row is
      // the gap's gradient in the generalised coordinates [δp; δθ].
      const ContactPointGeometry g = internal::CalcContactPointGeometry(model, state, data, p);
      g.SetRow(g.n, ws.J.row(k));
      ws.c[k++] = g.gap;
    }
    Eigen::Index worst = 0;
    const double g_max = ws.c.cwiseAbs().maxCoeff(&worst);
    if (g_max <= options.position_tolerance) break;
    if (iter == options.max_iterations) {
      // A constraint that cannot be assembled is an input error (as ProjectOntoConstraints);
      // contact gaps that cannot all close keep the least-squares remainder.
      if (worst < nh && g_max > options.assembly_tolerance) {
        throw InputError(fmt::format(
            "constraint '{}' cannot be satisfied: after {} Gauss-Newton steps its position "
            "error is still {:.3g}; check its attachment points and axes against the other "
            "constraints",
            model.constraint(pw.holonomic_owner[static_cast<size_t>(worst)]).name(),
            options.max_iterations, g_max));
      }
      break;
    }
    MassWeightedCorrection(model, data, ws, pw.dx);
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
  const int nc_rows = model.num_constraint_rows();
  const Eigen::Index rows = nc_rows + n_velocity_contact;
  if (ws.J.rows() != rows || ws.J.cols() != 6 * nb) ws.J.resize(rows, 6 * nb), ws.c.resize(rows);
  ws.J.setZero();
  internal::GetVelocity(model, state, data, data.u);
  if (has_constraints) {
    ws.J.topRows(nc_rows) = data.J;
    ws.c.head(nc_rows).noalias() = data.J * data.u;
    ws.c.head(nc_rows) -= data.velocity_rhs;
  }
  Eigen::Index k = nc_rows;
  for (int p = 0; p < np; ++p) {
    const ContactMode mode = ModeOf(state, p);
    if (mode == ContactMode::kSeparated) continue;
    const ContactPointGeometry g = internal::CalcContactPointGeometry(model, state, data, p);
    g.SetRow(g.n, ws.J.row(k));
    ws.c[k++] = g.v_n;
    if (mode == ContactMode::kSticking) {
      for (const Vec3* t : {&g.t1, &g.t2}) {
        g.SetRow(*t, ws.J.row(k));
        ws.c[k++] = t->dot(g.v_rel);
      }
    }
  }
  if (ws.c.cwiseAbs().maxCoeff() == 0.0) return;
  MassWeightedCorrection(model, data, ws, pw.dx);
  for (int b = 0; b < nb; ++b) {
    const auto i = static_cast<size_t>(b);
    BodyState& bs = state.bodies[i];
    bs.v_WBcm_W += pw.dx.segment<3>(6 * b);
    bs.w_WB_B += data.R_WB[i].transpose() * pw.dx.segment<3>(6 * b + 3);
  }
  CalcKinematics(model, state, data);  // leave the kinematics stage consistent with `state`
}

}  // namespace chasles
