#include "chasles/dynamics/redundancy.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include "chasles/dynamics/constraint_residual.h"
#include "chasles/dynamics/constraint_solve.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/model/constraints.h"
#include "dynamics/internal/generalized.h"

namespace chasles {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using Wrench = Eigen::Matrix<double, 6, 1>;

// Relative size below which an eigenvalue of D A D, or a coefficient, counts as zero.
constexpr double kNullTolerance = 1e-10;
// A candidate support component adds to the rank when at least this fraction of its
// (mass-metric) norm is outside the span of those kept before it.
constexpr double kIndependence = 1e-6;

// The generalised force (per body [F; M about Bcm], in W) of a wrench (f, m about J) in the
// constraint's frame applied on the child at J, and its opposite on the parent.
VectorXd GeneralisedForce(const Model& model, const State& state, const Constraint& con,
                          const ConstraintEval& e, const Wrench& w_J) {
  VectorXd g = VectorXd::Zero(6 * model.num_bodies());
  const Vec3 F = e.R_WJ * w_J.head<3>();
  const Vec3 M = e.R_WJ * w_J.tail<3>();
  auto put = [&](BodyIndex b, double sign) {
    if (b == kWorld) return;
    const Vec3 r = e.p_WJ - state.bodies[static_cast<size_t>(b)].p_WBcm;
    g.segment<3>(6 * b) += sign * F;
    g.segment<3>(6 * b + 3) += sign * (M + r.cross(F));
  };
  put(con.child(), 1.0);
  put(con.parent(), -1.0);
  return g;
}

// Inner product with the inverse mass matrix, x M⁻¹ y: unit-consistent for generalised
// forces (N²/kg for forces, (N·m)²/(kg·m²) for moments).
double MetricDot(const Model& model, const Data& data, const VectorXd& x, const VectorXd& y) {
  MatrixXd yt = y.transpose();
  MatrixXd ym;
  internal::TimesMassInverse(model, data, yt, ym);
  return x.dot(ym.row(0).transpose());
}

// Gram–Schmidt in the metric: the part of g outside span(basis) (orthonormal).
VectorXd Residual(const Model& model, const Data& data, const std::vector<VectorXd>& basis,
                  VectorXd g) {
  for (int pass = 0; pass < 2; ++pass) {  // twice is enough (Kahan)
    for (const VectorXd& q : basis) g -= MetricDot(model, data, q, g) * q;
  }
  return g;
}

const char* AxisName(int axis) {
  return axis == 0 ? "x" : axis == 1 ? "y" : "z";
}

std::string ComponentName(const Model& model, const ReactionComponent& c) {
  return fmt::format("'{}' {} {}", model.constraint(c.constraint).name(), AxisName(c.axis),
                     c.moment ? "moment" : "force");
}

// A joint that carries exactly `kept` ([Fx Fy Fz Mx My Mz] in its frame), as a scene type.
std::string JointFor(const std::array<bool, 6>& kept) {
  using K = std::array<bool, 6>;
  struct Named {
    K mask;
    const char* text;
  };
  static const Named kNamed[] = {
      {{true, true, true, false, false, false}, "a `spherical` joint"},
      {{true, true, false, false, false, false}, "a `point_on_line` joint along its z axis"},
      {{false, false, true, false, false, false}, "a `point_on_plane` joint normal to its z axis"},
      {{true, true, false, true, true, false}, "a `cylindrical` joint along its z axis"},
      {{true, true, true, true, true, false}, "a `revolute` joint about its z axis"},
      {{true, true, false, true, true, true}, "a `prismatic` joint along its z axis"},
      {{false, false, true, true, true, false}, "a `planar` joint normal to its z axis"},
      {{true, true, true, true, true, true}, "a `weld`"},
  };
  for (const Named& n : kNamed) {
    if (n.mask == kept) return n.text;
  }
  std::string list;
  for (int i = 0; i < 6; ++i) {
    if (!kept[static_cast<size_t>(i)]) continue;
    list += fmt::format("{}{} {}", list.empty() ? "" : ", ", AxisName(i % 3),
                        i < 3 ? "force" : "moment");
  }
  return "a support that carries only its " + list;
}

}  // namespace

double CalcMechanismLength(const Model& model, const Data& data) {
  CheckDataFor(model, data);
  // The bodies' mean radius of gyration: the length when the joint points coincide.
  double k2 = 0.0;
  for (int b = 0; b < model.num_bodies(); ++b) {
    k2 += model.body(b).I_BBcm_B().trace() / (2.0 * model.body(b).mass());
  }
  const double gyration = std::sqrt(k2 / std::max(1, model.num_bodies()));
  const int nc = model.num_constraints();
  double ell = 0.0, reach = gyration;
  if (nc > 0) {
    Vec3 centroid = Vec3::Zero();
    for (int c = 0; c < nc; ++c) centroid += data.constraint_rows[static_cast<size_t>(c)].p_WJ;
    centroid /= nc;
    double sum = 0.0;
    for (int c = 0; c < nc; ++c) {
      const Vec3& p = data.constraint_rows[static_cast<size_t>(c)].p_WJ;
      sum += (p - centroid).squaredNorm();
      reach = std::max(reach, p.norm());
    }
    ell = std::sqrt(sum / nc);
  }
  // Joint points that coincide up to round-off (a cart that has moved from the origin with its
  // pin and rail at one point: a spread of 1e-16 m) coincide: a spread that small would weight
  // the moment rows by 1e16 and break the rank.
  if (ell > 1e-9 * reach) return ell;
  // Particles joined at one point have no moments to weigh: any length serves.
  return gyration > 0.0 ? gyration : 1.0;
}

VectorXd CalcReactionWeights(const Model& model, const Data& data) {
  CheckDataFor(model, data);
  VectorXd d = VectorXd::Ones(model.num_constraint_rows());
  const double ell = CalcMechanismLength(model, data);
  for (int c = 0; c < model.num_constraints(); ++c) {
    const ConstraintEval& e = data.constraint_rows[static_cast<size_t>(c)];
    for (int k = 0; k < model.constraint(c).num_rows(); ++k) {
      if (IsMomentRow(e, k)) d[model.constraint_row_offset(c) + k] = ell;
    }
  }
  return d;
}

namespace {

// The reaction components of each null vector (the columns of Lambda): per constraint
// [f; m/ℓ] in its frame.
MatrixXd NullReactionComponents(const Model& model, const State& state, const Data& data,
                                const MatrixXd& Lambda, double length) {
  const int nc = model.num_constraints();
  const auto null_dim = static_cast<int>(Lambda.cols());
  MatrixXd C = MatrixXd::Zero(null_dim, 6 * nc);
  for (int c = 0; c < nc; ++c) {
    const Constraint& con = model.constraint(c);
    const ConstraintEval& e = data.constraint_rows[static_cast<size_t>(c)];
    const Vec3 r_J = e.p_WJ - state.bodies[static_cast<size_t>(con.child())].p_WBcm;
    const int o = model.constraint_row_offset(c);
    for (int j = 0; j < null_dim; ++j) {
      const Wrench w =
          e.J_child.topRows(con.num_rows()).transpose() * Lambda.col(j).segment(o, con.num_rows());
      const Vec3 F = w.head<3>();
      const Vec3 M_J = w.tail<3>() - r_J.cross(F);
      C.block<1, 3>(j, 6 * c) = (e.R_WJ.transpose() * F).transpose();
      C.block<1, 3>(j, 6 * c + 3) = (e.R_WJ.transpose() * M_J).transpose() / length;
    }
  }
  return C;
}

// Reduced row echelon form of C in place: each row a combination touching as few components
// as possible. Returns the number of non-zero rows.
int ReduceToEchelon(MatrixXd& C) {
  const auto null_dim = static_cast<int>(C.rows());
  const double c_max = C.cwiseAbs().maxCoeff();
  int lead = 0;
  for (Eigen::Index col = 0; col < C.cols() && lead < null_dim; ++col) {
    Eigen::Index piv = lead;
    const double best = C.col(col).segment(lead, null_dim - lead).cwiseAbs().maxCoeff(&piv);
    if (best <= kNullTolerance * 1e2 * c_max) continue;
    piv += lead;
    C.row(lead).swap(C.row(piv));
    C.row(lead) /= C(lead, col);
    for (int i = 0; i < null_dim; ++i) {
      if (i != lead) C.row(i) -= C(i, col) * C.row(lead);
    }
    ++lead;
  }
  for (Eigen::Index i = 0; i < C.rows(); ++i) {
    for (Eigen::Index k = 0; k < C.cols(); ++k) {
      if (std::abs(C(i, k)) <= kNullTolerance * 1e2) C(i, k) = 0.0;
    }
  }
  return lead;
}

// Groups: components that appear in a common combination (the first `lead` rows of the
// echelon form C), by union-find.
void GroupComponents(const MatrixXd& C, int lead, int nc, Redundancy& r) {
  std::vector<int> parent(static_cast<size_t>(6 * nc));
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x) {
    while (parent[static_cast<size_t>(x)] != x) x = parent[static_cast<size_t>(x)];
    return x;
  };
  for (int i = 0; i < lead; ++i) {
    int first = -1;
    for (int k = 0; k < 6 * nc; ++k) {
      if (C(i, k) == 0.0) continue;
      if (first < 0) {
        first = k;
      } else {
        parent[static_cast<size_t>(find(k))] = find(first);
      }
    }
  }
  std::vector<int> group_of(static_cast<size_t>(6 * nc), -1);
  for (int i = 0; i < lead; ++i) {
    int root = -1;
    for (int k = 0; k < 6 * nc && root < 0; ++k) {
      if (C(i, k) != 0.0) root = find(k);
    }
    if (root < 0) continue;
    if (group_of[static_cast<size_t>(root)] < 0) {
      group_of[static_cast<size_t>(root)] = static_cast<int>(r.groups.size());
      r.groups.emplace_back();
      IndeterminateGroup& g = r.groups.back();
      for (int k = 0; k < 6 * nc; ++k) {
        if (find(k) != root) continue;
        bool used = false;
        for (int j = 0; j < lead; ++j) used = used || C(j, k) != 0.0;
        if (used) g.components.push_back({k / 6, k % 3, (k % 6) >= 3});
      }
    }
    IndeterminateGroup& g = r.groups[static_cast<size_t>(group_of[static_cast<size_t>(root)])];
    ++g.dimension;
    g.null_combination.clear();
    if (g.dimension == 1) {
      for (const ReactionComponent& rc : g.components) {
        g.null_combination.push_back(C(i, 6 * rc.constraint + (rc.moment ? 3 : 0) + rc.axis));
      }
    }
  }
}

// A candidate support component of a determinate set, with its generalised force.
struct Candidate {
  int constraint;
  int component;  // 0..5 for joints, the row for the others
  VectorXd g;
};

// The candidate support components, forces and moments, and per constraint what it carries.
void CollectSupportCandidates(const Model& model, const State& state, const Data& data,
                              std::vector<Candidate>& forces, std::vector<Candidate>& moments,
                              std::vector<SupportChange>& support) {
  const int nc = model.num_constraints();
  for (int c = 0; c < nc; ++c) {
    const Constraint& con = model.constraint(c);
    const ConstraintEval& e = data.constraint_rows[static_cast<size_t>(c)];
    SupportChange& s = support[static_cast<size_t>(c)];
    s.constraint = c;
    s.num_rows = con.num_rows();
    s.is_joint = dynamic_cast<const Joint*>(&con) != nullptr;
    const int o = model.constraint_row_offset(c);
    if (!s.is_joint) {
      for (int k = 0; k < con.num_rows(); ++k) {
        const VectorXd g = data.J.row(o + k).transpose();
        (IsMomentRow(e, k) ? moments : forces).push_back({c, k, g});
      }
      continue;
    }
    // The joint's own span, to tell which frame components it carries.
    std::vector<VectorXd> own;
    for (int k = 0; k < con.num_rows(); ++k) {
      VectorXd q = Residual(model, data, own, data.J.row(o + k).transpose());
      const double n = std::sqrt(MetricDot(model, data, q, q));
      if (n > 0.0) own.push_back(q / n);
    }
    for (int i = 0; i < 6; ++i) {
      const VectorXd g = GeneralisedForce(model, state, con, e, Wrench::Unit(i));
      const double n = std::sqrt(MetricDot(model, data, g, g));
      const VectorXd out = Residual(model, data, own, g);
      if (n == 0.0 || std::sqrt(MetricDot(model, data, out, out)) > kIndependence * n) continue;
      s.carried[static_cast<size_t>(i)] = true;
      (i < 3 ? forces : moments).push_back({c, i, g});
    }
  }
}

// A determinate set of supports: greedy over candidate components, forces first; the
// constraints that change.
std::vector<SupportChange> DeterminateSupports(const Model& model, const State& state,
                                               const Data& data) {
  std::vector<Candidate> forces, moments;
  std::vector<SupportChange> support(static_cast<size_t>(model.num_constraints()));
  CollectSupportCandidates(model, state, data, forces, moments, support);
  std::vector<VectorXd> basis;
  auto take = [&](const std::vector<Candidate>& list) {
    for (const Candidate& cand : list) {
      const double n = std::sqrt(MetricDot(model, data, cand.g, cand.g));
      if (n == 0.0) continue;
      const VectorXd q = Residual(model, data, basis, cand.g);
      const double nq = std::sqrt(MetricDot(model, data, q, q));
      if (nq <= kIndependence * n) continue;
      basis.push_back(q / nq);
      SupportChange& s = support[static_cast<size_t>(cand.constraint)];
      if (s.is_joint) {
        s.kept[static_cast<size_t>(cand.component)] = true;
      } else {
        s.kept_rows.push_back(cand.component);
      }
    }
  };
  take(forces);
  take(moments);
  std::vector<SupportChange> changes;
  for (const SupportChange& s : support) {
    const bool same =
        s.is_joint ? s.kept == s.carried : static_cast<int>(s.kept_rows.size()) == s.num_rows;
    if (!same) changes.push_back(s);
  }
  return changes;
}

}  // namespace

namespace {

// Tags the moment components about an axis along which the child's or the parent's spin is
// not a degree of freedom (Body::free_rotation_B: a slender rod's own axis, any axis of a
// particle): the constraint's moment there acts on no inertia, so equilibrium leaves it free.
void MarkFrozenSpins(const Model& model, const Data& data, Redundancy& r) {
  for (IndeterminateGroup& g : r.groups) {
    for (ReactionComponent& rc : g.components) {
      if (!rc.moment) continue;
      const Constraint& con = model.constraint(rc.constraint);
      const ConstraintEval& e = data.constraint_rows[static_cast<size_t>(rc.constraint)];
      const Vec3 a_W = e.R_WJ.col(rc.axis);
      for (const BodyIndex b : {con.child(), con.parent()}) {
        if (b == kWorld || model.body(b).num_zero_moments() == 0) continue;
        const Mat3& R = data.R_WB[static_cast<size_t>(b)];
        const Vec3 free = R * (model.body(b).free_rotation_B() * (R.transpose() * a_W));
        if (free.norm() <= 1e-9) {
          rc.frozen_spin_body = b;
          break;
        }
      }
    }
  }
}

}  // namespace

Redundancy AnalyseRedundancy(const Model& model, const State& state, Data& data) {
  CheckDataFor(model, data);
  Redundancy r;
  const int nc = model.num_constraints();
  r.rows = model.num_constraint_rows();
  if (nc == 0) return r;
  CalcKinematics(model, state, data);
  CalcConstraintRows(model, state, data);
  internal::EnsureDenseJacobian(model, data);  // a dense eigendecomposition over every row
  r.length = CalcMechanismLength(model, data);
  const VectorXd d = CalcReactionWeights(model, data);

  // Null space of Jᵀ, from the weighted Schur complement D J M⁻¹ Jᵀ D (positive
  // semi-definite; its null space is D⁻¹ null(Jᵀ), and the weighting makes "small" mean the
  // same in every unit).
  MatrixXd JMinv;
  internal::TimesMassInverse(model, data, data.J, JMinv);
  const MatrixXd A = d.asDiagonal() * (JMinv * data.J.transpose()) * d.asDiagonal();
  Eigen::SelfAdjointEigenSolver<MatrixXd> eig(A);
  const VectorXd& ev = eig.eigenvalues();
  const double ev_max = std::max(ev.cwiseAbs().maxCoeff(), 0.0);
  int null_dim = 0;
  while (null_dim < ev.size() && ev[null_dim] <= kNullTolerance * ev_max) ++null_dim;
  r.rank = r.rows - null_dim;
  if (null_dim == 0) return r;
  const MatrixXd Lambda = d.asDiagonal() * eig.eigenvectors().leftCols(null_dim);

  MatrixXd C = NullReactionComponents(model, state, data, Lambda, r.length);
  const int lead = ReduceToEchelon(C);
  GroupComponents(C, lead, nc, r);
  MarkFrozenSpins(model, data, r);
  r.changes = DeterminateSupports(model, state, data);
  return r;
}

std::vector<std::string> DescribeRedundancy(const Model& model, const Redundancy& r) {
  std::vector<std::string> out;
  if (r.rank >= r.rows) return out;
  out.push_back(fmt::format(
      "the constraints are redundant ({} rows, rank {}): their reactions are statically "
      "indeterminate; those reported are the least-norm ones with moments weighted by the "
      "mechanism's length {:.4g} m (docs/constraints.md, \"Redundant constraints\"); below, x, y "
      "and z are the axes of each joint's frame (z the joint's axis)",
      r.rows, r.rank, r.length));
  for (const IndeterminateGroup& g : r.groups) {
    std::string names;
    for (size_t i = 0; i < g.components.size(); ++i) {
      names += (i == 0                         ? ""
                : i + 1 == g.components.size() ? " and "
                                               : ", ") +
               ComponentName(model, g.components[i]);
    }
    const size_t n = g.components.size();
    if (n == 2 && g.dimension == 1 && g.components[0].moment == g.components[1].moment &&
        g.components[0].axis == g.components[1].axis &&
        std::abs(std::abs(g.null_combination[0]) - std::abs(g.null_combination[1])) <=
            1e-9 * std::abs(g.null_combination[0])) {
      const bool sum = g.null_combination[0] * g.null_combination[1] < 0.0;
      out.push_back(fmt::format("'{}' and '{}': only the {} of their {} {}s is determined",
                                model.constraint(g.components[0].constraint).name(),
                                model.constraint(g.components[1].constraint).name(),
                                sum ? "sum" : "difference", AxisName(g.components[0].axis),
                                g.components[0].moment ? "moment" : "force"));
    } else if (n == static_cast<size_t>(g.dimension)) {
      std::string why;
      for (const ReactionComponent& rc : g.components) {
        if (rc.frozen_spin_body == kWorld) continue;
        const Body& body = model.body(rc.frozen_spin_body);
        why = body.is_particle()
                  ? fmt::format(
                        " ('{}' is a particle: it has no moment of inertia, so no moment "
                        "on it is needed or carried)",
                        body.name())
                  : fmt::format(
                        " (about the own axis of '{}', a slender body with no moment of "
                        "inertia about it: its spin there is not a degree of freedom, so "
                        "no moment about it is needed or carried)",
                        body.name());
        break;
      }
      out.push_back(fmt::format("{}: not determined at all{}", names, why));
    } else {
      out.push_back(fmt::format(
          "{}: equilibrium fixes only {} combination{} of these {} (their resultant); {} "
          "{} statically indeterminate",
          names, n - static_cast<size_t>(g.dimension), n - g.dimension == 1 ? "" : "s", n,
          g.dimension, g.dimension == 1 ? "is" : "are"));
    }
  }
  std::string alt;
  for (size_t i = 0; i < r.changes.size(); ++i) {
    const SupportChange& s = r.changes[i];
    const std::string& name = model.constraint(s.constraint).name();
    std::string what;
    const bool none = s.is_joint
                          ? std::none_of(s.kept.begin(), s.kept.end(), [](bool b) { return b; })
                          : s.kept_rows.empty();
    if (none) {
      what = fmt::format("remove '{}'", name);
    } else if (s.is_joint) {
      // "make 'a' X and 'b' Y": the verb once for a run of joints.
      const bool run = i > 0 && r.changes[i - 1].is_joint &&
                       std::any_of(r.changes[i - 1].kept.begin(), r.changes[i - 1].kept.end(),
                                   [](bool b) { return b; });
      what = fmt::format("{}'{}' {}", run ? "" : "make ", name, JointFor(s.kept));
    } else {
      std::string rows;
      for (int k : s.kept_rows) rows += fmt::format("{}{}", rows.empty() ? "" : ", ", k);
      what = fmt::format("keep only rows {} of '{}' ({})", rows, name,
                         model.constraint(s.constraint).kind());
    }
    alt += (i == 0 ? "" : i + 1 == r.changes.size() ? " and " : ", ") + what;
  }
  if (!alt.empty()) {
    out.push_back("a determinate model (forces before moments): " + alt +
                  "; its reactions are then unique");
  }
  return out;
}

}  // namespace chasles
