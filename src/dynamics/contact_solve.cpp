#include "chasles/dynamics/contact_solve.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <Eigen/QR>

#include "chasles/dynamics/constraint_solve.h"
#include "chasles/dynamics/contact_frame.h"
#include "chasles/dynamics/lcp.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/dynamics/redundancy.h"
#include "chasles/error.h"
#include "chasles/model/constraints.h"
#include "dynamics/internal/contact_geometry.h"
#include "dynamics/internal/mode_selection.h"
#include "dynamics/internal/sparse_solve.h"

namespace chasles {
namespace internal {

// ---------------------------------------------------------------------------------------
// Geometry of one contact point (see contact_geometry.h for the derivations).
ContactPointGeometry CalcContactPointGeometry(const Model& model, const State& state,
                                              const Data& data, int point) {
  const int ci = model.contact_of_point(point);
  const Contact& con = model.contact(ci);
  const ContactFeature& f = con.feature(point - model.contact_point_offset(ci));
  ContactPointGeometry g;
  g.body = con.body();
  g.other = con.other_body();
  g.radius = f.radius;
  g.round = f.kind != ContactFeatureKind::kPoint;
  const auto a = static_cast<size_t>(g.body);
  const Mat3& R = data.R_WB[a];
  const Vec3& w = data.w_WB_W[a];
  const Vec3 p_cm = state.bodies[a].p_WBcm;
  const Vec3 v_cm = state.bodies[a].v_WBcm_W;
  const Vec3 r_c = R * f.p_BcmF_B;  // Bcm to the feature's centre (or the point)
  Vec3 r_c_dot = w.cross(r_c);
  if (g.other == kWorld) {
    const Vec3& n = con.n_W();
    const Vec3& p_O = con.spec().plane_point_W;
    g.n = n, g.t1 = con.t1_W(), g.t2 = con.t2_W();
    // Unit vector m from C to the feature's centre, C = centre - R m:
    //   point: R = 0; sphere: m = n; rim (plane ⊥ e): m = u/|u|, u = n - (n·e) e, the rim's
    //   lowest point (as RollingContact's disk, whose derivation of ṁ this repeats).
    Vec3 m = n, m_dot = Vec3::Zero();
    double s = 1.0;
    if (f.kind == ContactFeatureKind::kSphere) {
      g.num_rolling_axes = 2;
      g.rolling_axis[0] = g.t1, g.rolling_axis[1] = g.t2;  // fixed in W: no bias
    }
    if (f.kind == ContactFeatureKind::kRim) {
      const Vec3 e = R * f.axis_B;
      const double sigma = n.dot(e);
      const Vec3 u = n - sigma * e;
      s = u.norm();
      const Vec3 e_dot = w.cross(e);
      if (s > 1e-12) {
        m = u / s;
        const double sigma_dot = n.dot(e_dot);
        const Vec3 u_dot = -sigma_dot * e - sigma * e_dot;
        const double s_dot = -sigma * sigma_dot / s;
        m_dot = u_dot / s - u * (s_dot / (s * s));
        // Rolling axis a = (e - σ n)/s, the rim's axis in the plane (|e - σ n| = s);
        // ȧ = (ė - σ̇ n)/s - a ṡ/s, and the row a·w has the bias -ȧ·w.
        const Vec3 a = (e - sigma * n) / s;
        const Vec3 a_dot = (e_dot - sigma_dot * n) / s - a * (s_dot / s);
        g.num_rolling_axes = 1;
        g.rolling_axis[0] = a;
        g.rolling_bias[0] = -a_dot.dot(w);
      } else {
        // Rim flat on the plane: every rim point is equally low; take a fixed one (a rim
        // lying flat should be modelled as a disk face). Its rolling axis, along the plane
        // and across the radius to that point, turns with the body.
        m = R * FrameWithZAxis(f.axis_B).col(0);
        m_dot = w.cross(m);
        s = 0.0;
        // (ȧ = w × a, so the bias -ȧ·w is zero.)
        g.num_rolling_axes = 1;
        g.rolling_axis[0] = R * FrameWithZAxis(f.axis_B).col(1);
      }
    }
    const double Rf = f.kind == ContactFeatureKind::kPoint ? 0.0 : f.radius;
    g.r = r_c - Rf * m;
    g.p_WC = p_cm + g.r;
    // Height of the lowest point: h = (centre - p_O)·n - R s (envelope: ḣ = n·v_C).
    g.gap = (p_cm + r_c - p_O).dot(n) - (f.kind == ContactFeatureKind::kRim ? Rf * s : Rf);
    const Vec3 r_dot = r_c_dot - Rf * m_dot;
    g.v_rel = v_cm + w.cross(g.r);
    g.w_rel = w;
    // Rows k·v_C, k fixed in W: d/dt k·(v + w × r) = k·(a + ẇ × r) + k·(w × ṙ), so the
    // acceleration right-hand side is c_k = -k·(w × ṙ).
    g.w_x_rdot = w.cross(r_dot);
    g.w_x_rdot_other = Vec3::Zero();
  } else {
    // Sphere on body A against sphere on body O: d = c_A - c_O, n = d/|d|, gap |d| - R_A - R_O;
    // C_A = c_A - R_A n, C_O = c_O + R_O n. ṅ = (ḋ - n (n·ḋ))/|d|.
    const auto o = static_cast<size_t>(g.other);
    const Mat3& RO = data.R_WB[o];
    const Vec3& wO = data.w_WB_W[o];
    const Vec3 r_cO = RO * con.p_OcmC_O();
    const Vec3 d = (p_cm + r_c) - (state.bodies[o].p_WBcm + r_cO);
    const double dn = d.norm();
    if (!(dn > 0.0)) {
      throw InputError(
          fmt::format(
              "contact '{}': the two sphere centres coincide; the contact normal is undefined",
              con.name()),
          ErrorElement{ErrorElement::Kind::kContact, ci});
    }
    const double RO_rad = con.spec().other_radius;
    g.n = d / dn;
    const Mat3 T = FrameWithZAxis(g.n);
    g.t1 = T.col(0), g.t2 = T.col(1);
    g.gap = dn - f.radius - RO_rad;
    const Vec3 d_dot = v_cm + r_c_dot - state.bodies[o].v_WBcm_W - wO.cross(r_cO);
    const Vec3 n_dot = (d_dot - g.n * g.n.dot(d_dot)) / dn;
    g.r = r_c - f.radius * g.n;
    g.r_other = r_cO + RO_rad * g.n;
    g.p_WC = p_cm + g.r;
    g.v_rel = (v_cm + w.cross(g.r)) - (state.bodies[o].v_WBcm_W + wO.cross(g.r_other));
    g.w_rel = w - wO;
    g.w_x_rdot = w.cross(r_c_dot - f.radius * n_dot);
    g.w_x_rdot_other = wO.cross(wO.cross(r_cO) + RO_rad * n_dot);
    g.n_dot = n_dot;
    // Rolling about the tangents, which turn with n: on the held manifold w_rel = (n·w_rel) n,
    // so the bias -k̇·w_rel = -(n·w_rel)(k̇·n) = (n·w_rel)(k·ṅ).
    g.num_rolling_axes = 2;
    g.rolling_axis[0] = g.t1, g.rolling_axis[1] = g.t2;
    g.rolling_bias[0] = g.n.dot(g.w_rel) * g.t1.dot(n_dot);
    g.rolling_bias[1] = g.n.dot(g.w_rel) * g.t2.dot(n_dot);
  }
  g.v_n = g.n.dot(g.v_rel);
  g.v_t = g.v_rel - g.v_n * g.n;
  g.speed_scale = v_cm.norm() + w.norm() * g.r.norm();
  if (g.other != kWorld) {
    const auto o = static_cast<size_t>(g.other);
    g.speed_scale += state.bodies[o].v_WBcm_W.norm() + data.w_WB_W[o].norm() * g.r_other.norm();
  }
  return g;
}

double ContactPointGeometry::AccelerationBias(const Vec3& k) const {
  // c_k = -[k̇·v_rel + k·(w_A × ṙ_A - w_O × ṙ_O)]. The normal rotates only between two
  // spheres (k̇ = ṅ); the tangents' k̇·v_rel vanishes on the sticking manifold (v_rel = 0), the
  // only mode with tangential rows, and is left out.
  const double kdot_v = (k == n) ? n_dot.dot(v_rel) : 0.0;
  return -(kdot_v + k.dot(w_x_rdot - w_x_rdot_other));
}

void ContactPointGeometry::SetRow(const Vec3& k, RowRef row) const {
  // k·v_C = k·v + (r × k)·w on the body; minus the same on the other body.
  row.segment<3>(6 * body) += k.transpose();
  row.segment<3>(6 * body + 3) += r.cross(k).transpose();
  if (other != kWorld) {
    row.segment<3>(6 * other) -= k.transpose();
    row.segment<3>(6 * other + 3) -= r_other.cross(k).transpose();
  }
}

void ContactPointGeometry::AddRow(const Vec3& k, double scale, RowRef row) const {
  // scale × (SetRow of k), term by term as SetRow forms it.
  row.segment<3>(6 * body) += scale * k.transpose();
  row.segment<3>(6 * body + 3) += scale * r.cross(k).transpose();
  if (other != kWorld) {
    row.segment<3>(6 * other) -= scale * k.transpose();
    row.segment<3>(6 * other + 3) -= scale * r_other.cross(k).transpose();
  }
}

void ContactPointGeometry::AddBlocks(const Vec3& k, double scale,
                                     Eigen::Matrix<double, 6, 1>& on_body,
                                     Eigen::Matrix<double, 6, 1>& on_other) const {
  on_body.head<3>() += scale * k;
  on_body.tail<3>() += scale * r.cross(k);
  on_other.head<3>() -= scale * k;
  on_other.tail<3>() -= scale * r_other.cross(k);
}

double ContactPointGeometry::RowTimes(const Vec3& k, const Eigen::VectorXd& u_dot) const {
  double a = k.dot(u_dot.segment<3>(6 * body)) + r.cross(k).dot(u_dot.segment<3>(6 * body + 3));
  if (other != kWorld) {
    a -= k.dot(u_dot.segment<3>(6 * other)) + r_other.cross(k).dot(u_dot.segment<3>(6 * other + 3));
  }
  return a;
}

void ContactPointGeometry::AddMoment(const Vec3& M, RowRef row) const {
  row.segment<3>(6 * body + 3) += M.transpose();
  if (other != kWorld) row.segment<3>(6 * other + 3) -= M.transpose();
}

Vec3 ContactPointGeometry::SlipDirection(const Vec3& s_ref) const {
  // Unit slip direction, its sign taken relative to the mode's reference direction so that
  // the friction force stays smooth while the slip passes through zero along s_ref.
  // A slip at round-off level (a slip that starts from zero, a state just projected) has no
  // direction of its own: the reference holds until the slip stands out of the round-off of
  // the material point's velocity: 1e-10 of speed_scale, and at least 1e-14 m/s (the
  // round-off of a body at rest, whose own speed scale is round-off).
  const double vt = v_t.norm();
  const bool has_ref = s_ref.squaredNorm() > 0.0;
  if (!(vt > 0.0) || (has_ref && vt <= std::max(1e-10 * speed_scale, kSlipSpeedRoundOff)))
    return has_ref ? s_ref : Vec3::Zero();
  Vec3 s = v_t / vt;
  if (has_ref && s.dot(s_ref) < 0.0) s = -s;
  return s;
}

Vec3 ContactPointGeometry::RollingVelocity() const {
  Vec3 wr = Vec3::Zero();
  for (int i = 0; i < num_rolling_axes; ++i) wr += rolling_axis[i].dot(w_rel) * rolling_axis[i];
  return wr;
}

Vec3 ContactPointGeometry::RollingDirection(const Vec3& r_ref) const {
  if (r_ref.squaredNorm() == 0.0) return Vec3::Zero();
  const Vec3 wr = RollingVelocity();
  const double m = wr.norm();
  // As SlipDirection: a rolling speed |w_r| R at round-off of the material points' speeds
  // (a rolling that starts from rest, a state just projected) keeps the reference.
  if (!(m > 0.0) || m * radius <= std::max(1e-10 * speed_scale, kSlipSpeedRoundOff)) return r_ref;
  Vec3 d = wr / m;
  if (d.dot(r_ref) < 0.0) d = -d;
  return d;
}

Vec3 ContactPointGeometry::RollingAcceleration(const Eigen::VectorXd& u_dot) const {
  Vec3 a_r = Vec3::Zero();
  for (int i = 0; i < num_rolling_axes; ++i) {
    const Vec3& a = rolling_axis[i];
    double rate = a.dot(u_dot.segment<3>(6 * body + 3));
    if (other != kWorld) rate -= a.dot(u_dot.segment<3>(6 * other + 3));
    a_r += (rate - rolling_bias[i]) * a;
  }
  return a_r;
}

void ContactPointGeometry::AddRollingBlocks(const Vec3& a, Eigen::Matrix<double, 6, 1>& on_body,
                                            Eigen::Matrix<double, 6, 1>& on_other) const {
  on_body.tail<3>() += a;
  on_other.tail<3>() -= a;
}

int HeldRows(const Model& model, const State& state, int p) {
  if (static_cast<size_t>(p) >= state.contacts.size()) return 0;
  const ContactPointState& ps = state.contacts[static_cast<size_t>(p)];
  if (ps.mode != ContactMode::kSticking || !ps.rolling_held) return 0;
  const int ci = model.contact_of_point(p);
  switch (model.contact(ci).feature(p - model.contact_point_offset(ci)).kind) {
    case ContactFeatureKind::kSphere:
      return 2;
    case ContactFeatureKind::kRim:
      return 1;
    case ContactFeatureKind::kPoint:
      return 0;
  }
  return 0;
}

namespace {

// The rank decision. A complete orthogonal decomposition keeps the columns of its pivoted QR
// with |R_kk| > 1e-10 |R_00| (Eigen's ColPivHouseholderQR::rank, the threshold set in
// LeastNormCod). A pivoted LDLᵀ of the same A ⪰ 0 whose pivot at each step is the largest
// diagonal of the Schur complement left (Higham, Accuracy and Stability of Numerical
// Algorithms, 2nd ed., §10.3, Cholesky with complete pivoting; Eigen's LDLT pivots on A's own
// diagonal and is not rank revealing) estimates the same numbers. Its pivots are A's (not those
// of a factor B of A = B Bᵀ, whose QR would give d_k = R_kk²): d_0 = max a_ii = max |a_ij|
// within √n of |R_00|, and after k steps the Schur complement S ⪰ 0 has |s_ij| <= d_k, so
// σ_{k+1}(A) <= ‖S‖₂ <= (n - k) d_k, while |R_kk| >= σ_k(A) / √(n - k + 1) (Golub & Van Loan,
// Matrix Computations, 4th ed., §5.4.2); both track σ_k(A) within factors of order n in
// practice, though neither is bound to it in the worst case. So the LDLᵀ decides only when its
// pivots leave the threshold τ = 1e-10 d_0 by kRankMargin (factors n, √n for the systems solved
// densely) on both sides; a pivot nearer τ, or a Schur complement not ⪰ 0 to round-off, leaves
// the system to the decomposition, whose decision is then COD's by construction.
constexpr double kRankThreshold = 1e-10;
constexpr double kRankMargin = 1e3;

// min(d_{rank-1} / τ, τ / max |s_ij|) with S the Schur complement left after `rank` steps of
// the factor in ws.null_gram (below: its trailing block).
double RankMargin(const ContactWorkspace& ws, Eigen::Index rank) {
  const Eigen::Index n = ws.null_gram.rows();
  const double tau = kRankThreshold * ws.null_gram(0, 0);
  const double dropped = ws.null_gram.bottomRightCorner(n - rank, n - rank).cwiseAbs().maxCoeff();
  return std::min(ws.null_gram(rank - 1, rank - 1) / tau,
                  dropped > 0.0 ? tau / dropped : std::numeric_limits<double>::infinity());
}

// Right-looking LDLᵀ of A with complete (diagonal) pivoting, P A Pᵀ = L D Lᵀ, stopped at the
// first step whose largest remaining diagonal is at or below τ: the unit lower L below the
// diagonal of ws.null_gram, D on it (the first `rank` entries), the Schur complement left in
// its trailing block, and the order P (position i holds row P[i] of A) in ws.cod_x, which the
// decomposition route alone uses otherwise. Returns the rank when it is clear, else -1.
Eigen::Index PivotedLdlt(const Eigen::MatrixXd& A, ContactWorkspace& ws) {
  const Eigen::Index n = A.rows();
  Eigen::MatrixXd& F = ws.null_gram;
  Eigen::VectorXd& order = ws.cod_x;
  F = A;
  for (Eigen::Index i = 0; i < n; ++i) order[i] = static_cast<double>(i);
  Eigen::Index p = 0;
  const double tau = kRankThreshold * F.diagonal().maxCoeff();
  Eigen::Index rank = 0;
  for (; rank < n; ++rank) {
    const double d = F.diagonal().tail(n - rank).maxCoeff(&p);
    if (!(d > tau)) break;
    p += rank;
    if (p != rank) {  // symmetric swap of rows and columns rank and p
      F.row(rank).swap(F.row(p));
      F.col(rank).swap(F.col(p));
      std::swap(order[rank], order[p]);
    }
    const Eigen::Index m = n - rank - 1;
    auto l = F.col(rank).tail(m);
    l /= d;
    // S ← S - d l lᵀ on the lower triangle and the diagonal, kept symmetric for the pivots.
    for (Eigen::Index j = 0; j < m; ++j) {
      F.col(rank + 1 + j).tail(m - j) -= (d * l[j]) * l.tail(m - j);
      F.row(rank + 1 + j).tail(m - j) = F.col(rank + 1 + j).tail(m - j).transpose();
    }
  }
  if (rank == 0 || rank == n) return -1;
  return RankMargin(ws, rank) >= kRankMargin ? rank : -1;
}

// Least-norm solution of a singular A ⪰ 0 from the factor of PivotedLdlt, P A Pᵀ = L D Lᵀ of
// rank r (L11 r × r, L21 below it, S ≈ 0 dropped):
//   the null space  span Pᵀ [-L11⁻ᵀ L21ᵀ; I]            ([L11ᵀ L21ᵀ] v = 0),
//   made orthonormal (Q, n × k, k = n - r, modified Gram–Schmidt twice),
//   a particular x  x_p = Pᵀ [L11⁻ᵀ D1⁻¹ L11⁻¹ (P r)_1; 0],
//   and the least-norm x = x_p - Q (Qᵀ W Q)⁻¹ Qᵀ W x_p, which minimises xᵀ W x over x_p + Q z
// (W = I: x = x_p - Q Qᵀ x_p; W = D⁻² for the weighted split: min Σ (x_i / D_i)²). Q and x_p
// stay in `ws` for the weighted solve of the same A that may follow: one factorisation serves
// both, where a complete orthogonal decomposition costs one QR each.
void NullSpaceFromLdlt(ContactWorkspace& ws, const Eigen::VectorXd& r, Eigen::Index rank) {
  const Eigen::MatrixXd& F = ws.null_gram;
  const Eigen::VectorXd& order = ws.cod_x;
  const Eigen::Index n = F.rows(), k = n - rank;
  const auto L11 = F.topLeftCorner(rank, rank).triangularView<Eigen::UnitLower>();
  auto V = ws.null_weighted.leftCols(k);  // in pivot order, then scattered into Q
  V.topRows(rank) = -F.bottomLeftCorner(k, rank).transpose();
  V.bottomRows(k).setIdentity();
  L11.transpose().solveInPlace(V.topRows(rank));
  auto Q = ws.null_basis.leftCols(k);
  for (Eigen::Index i = 0; i < n; ++i) Q.row(static_cast<Eigen::Index>(order[i])) = V.row(i);
  for (int pass = 0; pass < 2; ++pass) {
    for (Eigen::Index j = 0; j < k; ++j) {
      for (Eigen::Index i = 0; i < j; ++i) Q.col(j) -= Q.col(i).dot(Q.col(j)) * Q.col(i);
      Q.col(j).normalize();
    }
  }
  auto y = ws.cod_temp.head(rank);
  for (Eigen::Index i = 0; i < rank; ++i) y[i] = r[static_cast<Eigen::Index>(order[i])];
  L11.solveInPlace(y);
  y.array() /= F.diagonal().head(rank).array();
  L11.transpose().solveInPlace(y);
  Eigen::VectorXd& x_p = ws.null_particular;
  x_p.setZero();
  for (Eigen::Index i = 0; i < rank; ++i) x_p[static_cast<Eigen::Index>(order[i])] = y[i];
  ws.null_rank = k;
}

// x = x_p - Q (Qᵀ W Q)⁻¹ Qᵀ W x_p (NullSpaceFromLdlt) with W = diag(1 / D²) (D = column_scale) or
// I.
void LeastNormInNullSpace(ContactWorkspace& ws, const Eigen::VectorXd* column_scale,
                          Eigen::VectorXd& x) {
  const Eigen::Index k = ws.null_rank;
  const auto Q = ws.null_basis.leftCols(k);
  auto c = ws.cod_c.head(k);
  x = ws.null_particular;
  if (column_scale == nullptr) {
    c.noalias() = Q.transpose() * x;
    x.noalias() -= Q * c;
    return;
  }
  auto WQ = ws.null_weighted.leftCols(k);
  for (Eigen::Index j = 0; j < k; ++j) {  // column by column: colwise() would allocate D²
    WQ.col(j) = Q.col(j).cwiseQuotient(column_scale->cwiseAbs2());
  }
  Eigen::Ref<Eigen::MatrixXd> gram = ws.null_gram.topLeftCorner(k, k);
  gram.noalias() = Q.transpose() * WQ;
  Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>> llt(gram);  // in place: no allocation
  c.noalias() = WQ.transpose() * x;
  llt.solveInPlace(c);
  x.noalias() -= Q * c;
}

// The null-space basis Q checked against A: the k smallest singular values of A are at most
// ‖A Q‖₂ (Courant–Fischer, Q orthonormal), so every ‖A q‖ should be of round-off size; one at
// or above the threshold τ means the pivots misled, and the decomposition decides.
bool NullSpaceHolds(const Eigen::MatrixXd& A, ContactWorkspace& ws) {
  const Eigen::Index k = ws.null_rank;
  const double tau = kRankThreshold * ws.null_gram(0, 0);
  auto AQ = ws.null_weighted.leftCols(k);
  AQ.noalias() = A * ws.null_basis.leftCols(k);
  return AQ.colwise().norm().maxCoeff() < tau;
}

// Least-norm (weighted with `column_scale`) by complete orthogonal decomposition: any square
// A, the route of a singular system that is not symmetric positive semidefinite.
void LeastNormCod(const Eigen::MatrixXd& A_in, const Eigen::VectorXd& r, ContactWorkspace& ws,
                  Eigen::VectorXd& x, const Eigen::VectorXd* column_scale) {
  const Eigen::Index n = A_in.rows();
  // Weighted least norm: the same steps on A D (columns scaled), then x = D y.
  const Eigen::MatrixXd* A_ptr = &A_in;
  if (column_scale != nullptr) {
    ws.AD = A_in;
    for (Eigen::Index j = 0; j < n; ++j) ws.AD.col(j) *= (*column_scale)[j];
    A_ptr = &ws.AD;
  }
  const Eigen::MatrixXd& A = *A_ptr;
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>& cod = ws.cod;
  cod.setThreshold(1e-10);
  cod.compute(A);
  const Eigen::Index rank = cod.rank();
  x.resize(n);
  if (rank == 0) {
    x.setZero();
    return;
  }
  // c = Qᵀ r = H_{k-1} ... H_0 r, one reflector at a time on a column segment (Eigen's
  // HouseholderSequence applies them to a dynamic-size block, whose product allocates).
  ws.cod_c = r;
  ws.cod_temp.resize(n);
  for (Eigen::Index j = 0; j < rank; ++j) {
    ws.cod_c.segment(j, n - j).applyHouseholderOnTheLeft(cod.matrixQTZ().col(j).tail(n - j - 1),
                                                         cod.hCoeffs()(j), ws.cod_temp.data());
  }
  Eigen::VectorXd& y = ws.cod_x;
  y.resize(n);
  y.head(rank) = cod.matrixT()
                     .topLeftCorner(rank, rank)
                     .triangularView<Eigen::Upper>()
                     .solve(ws.cod_c.head(rank));
  if (rank < n) {
    y.tail(n - rank).setZero();
    for (Eigen::Index k = 0; k < rank; ++k) {
      if (k != rank - 1) std::swap(y[k], y[rank - 1]);
      y.segment(rank - 1, n - rank + 1)
          .applyHouseholderOnTheLeft(cod.matrixQTZ().row(k).tail(n - rank).adjoint(),
                                     cod.zCoeffs()(k), ws.cod_temp.data());
      if (k != rank - 1) std::swap(y[k], y[rank - 1]);
    }
  }
  x.noalias() = cod.colsPermutation() * y;
  if (column_scale != nullptr) x.array() *= column_scale->array();
}

// Sizes the least-norm members of `ws` for n × n systems, all at once when n changes, so that
// an evaluation taking the null-space route after one that took the decomposition (or the
// other way round) allocates nothing.
void SizeLeastNormWorkspace(ContactWorkspace& ws, Eigen::Index n) {
  if (ws.null_basis.rows() == n && ws.null_basis.cols() == n) return;
  ws.null_basis.resize(n, n);
  ws.null_weighted.resize(n, n);
  ws.null_gram.resize(n, n);
  ws.null_particular.resize(n);
  ws.cod_c.resize(n);
  ws.cod_x.resize(n);
  ws.cod_temp.resize(n);
  ws.cod = Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(n, n);
}

// The least-norm solution of a singular A ⪰ 0 from its pivoted LDLᵀ when its rank is clear
// (PivotedLdlt) and its null space checked; false leaves A to the decomposition.
bool LeastNormFromLdlt(const Eigen::MatrixXd& A, const Eigen::VectorXd& r, ContactWorkspace& ws,
                       Eigen::VectorXd& x) {
  const Eigen::Index rank = PivotedLdlt(A, ws);
  if (rank < 0) return false;
  NullSpaceFromLdlt(ws, r, rank);
  if (!NullSpaceHolds(A, ws)) return false;
  LeastNormInNullSpace(ws, nullptr, x);
  ws.null_ready = true;
  return true;
}

// The weighted solve may keep the unweighted one's null space when the rank of A D is as clear
// as A's: σ_k(A D) / σ_0(A D) is within D_max / D_min of σ_k(A) / σ_0(A) either way, so the
// margin of A's pivots must exceed kRankMargin by that ratio too (read before the weighted
// step overwrites the factor with its Gram matrix).
bool WeightedRankAsClear(const ContactWorkspace& ws, const Eigen::VectorXd& column_scale) {
  const double spread = column_scale.maxCoeff() / column_scale.minCoeff();
  return RankMargin(ws, ws.null_basis.rows() - ws.null_rank) >= kRankMargin * spread;
}

}  // namespace

// Solves A x = r, LDLᵀ / LU when well conditioned, (weighted) least-norm otherwise: from the
// LDLᵀ's null space when A is symmetric semidefinite with a clear rank, by complete orthogonal
// decomposition when not.
bool SolveSquare(const Eigen::MatrixXd& A_in, const Eigen::VectorXd& r, bool symmetric,
                 ContactWorkspace& ws, Eigen::VectorXd& x, const Eigen::VectorXd* column_scale) {
  const Eigen::Index n = A_in.rows();
  if (n == 0) {
    x.resize(0);
    return false;
  }
  // The weighted solve after an unweighted one of the same symmetric A: its null space.
  if (column_scale != nullptr && symmetric && ws.null_ready &&
      WeightedRankAsClear(ws, *column_scale)) {
    LeastNormInNullSpace(ws, column_scale, x);
    return true;
  }
  ws.null_ready = false;
  // With column scales the caller knows A is singular: straight to the least-norm branch.
  const double a_max = A_in.cwiseAbs().maxCoeff();
  if (a_max > 0.0 && column_scale == nullptr) {
    if (symmetric) {
      ws.ldlt.compute(A_in);
      if (ws.ldlt.info() == Eigen::Success &&
          ws.ldlt.vectorD().minCoeff() > kRankThreshold * a_max) {
        x = ws.ldlt.solve(r);
        return false;
      }
      SizeLeastNormWorkspace(ws, n);
      if (LeastNormFromLdlt(A_in, r, ws, x)) return true;
    } else {
      ws.lu.compute(A_in);
      if (ws.lu.matrixLU().diagonal().cwiseAbs().minCoeff() > kRankThreshold * a_max) {
        x = ws.lu.solve(r);
        return false;
      }
    }
  }
  SizeLeastNormWorkspace(ws, n);
  LeastNormCod(A_in, r, ws, x, column_scale);
  return true;
}

}  // namespace internal

ContactFrame CalcContactFrame(const Model& model, const State& state, const Data& data, int point) {
  const internal::ContactPointGeometry g =
      internal::CalcContactPointGeometry(model, state, data, point);
  ContactFrame f;
  f.body = g.body;
  f.other = g.other;
  f.gap = g.gap;
  f.p_WC = g.p_WC;
  f.n = g.n;
  f.t1 = g.t1;
  f.t2 = g.t2;
  f.r_BcmC_W = g.r;
  f.r_OcmC_W = g.r_other;
  f.v_rel_W = g.v_rel;
  f.v_t_W = g.v_t;
  return f;
}

using Eigen::MatrixXd;
using Eigen::VectorXd;
using internal::ContactPointGeometry;
using internal::RowRef;

namespace {

// Free accelerations u̇_free = M⁻¹ f (Newton–Euler without constraints), from the force stage.
void FreeAccelerations(const Model& model, const State& state, Data& data, VectorXd& u_dot) {
  u_dot.resize(6 * model.num_bodies());
  for (int b = 0; b < model.num_bodies(); ++b) {
    const auto i = static_cast<size_t>(b);
    const Body& body = model.body(b);
    u_dot.segment<3>(6 * b) = data.F_Bcm_W[i] / body.mass();
    const Vec3 M_B = data.R_WB[i].transpose() * data.M_Bcm_W[i];
    u_dot.segment<3>(6 * b + 3) =
        data.R_WB[i] * CalcEulerAngularAcceleration(body.I_BBcm_B(), body.I_BBcm_B_inverse(),
                                                    state.bodies[i].w_WB_B, M_B);
  }
}

ContactMode ModeOf(const State& state, int p) {
  return static_cast<size_t>(p) < state.contacts.size()
             ? state.contacts[static_cast<size_t>(p)].mode
             : ContactMode::kSeparated;
}

const ContactPointState& PointStateOf(const State& state, int p) {
  static const ContactPointState none{};
  return static_cast<size_t>(p) < state.contacts.size() ? state.contacts[static_cast<size_t>(p)]
                                                        : none;
}

using internal::HeldRows;

// Whether the rolling-resistance moment -mu_r N R ŵ_r of a rolling point enters its normal
// row (then the system J M⁻¹ Wᵀ is not symmetric).
bool RollsWithResistance(const ContactPointState& ps) {
  return ps.mode == ContactMode::kSticking && !ps.rolling_held &&
         ps.rolling_direction_W.squaredNorm() > 0.0;
}

// The force direction of a pressing point's normal row, by blocks: J_n, minus mu_k J_s when it
// slides (friction -mu_k N s), minus mu_r R ŵ_r in the angular part when a round feature rolls
// (sticks) with rolling resistance (moment -mu_r N R ŵ_r). A sliding point has no rolling
// resistance: its friction is mu_k N alone, as in the closed-form sliding of
// integrate/sphere_motion.cpp (and a rolling direction fixed for a whole sliding stretch
// would push the wrong way once the rolling velocity passes through zero, with no event).
void NormalForceBlocks(const Contact& con, const ContactPointGeometry& g, ContactMode mode,
                       const ContactPointState& ps, internal::Vec6& on_body,
                       internal::Vec6& on_other) {
  on_body.setZero(), on_other.setZero();
  g.AddBlocks(g.n, 1.0, on_body, on_other);
  if (mode == ContactMode::kSliding) {
    const Vec3 s = g.SlipDirection(ps.slip_direction_W);
    if (s.squaredNorm() > 0.0 && con.mu_k() > 0.0) g.AddBlocks(s, -con.mu_k(), on_body, on_other);
  }
  if (con.mu_r() > 0.0 && g.round && mode == ContactMode::kSticking && !ps.rolling_held) {
    const Vec3 roll_dir = g.RollingDirection(ps.rolling_direction_W);
    if (roll_dir.squaredNorm() > 0.0) {
      const Vec3 M = -con.mu_r() * g.radius * roll_dir;  // ContactPointGeometry::AddMoment
      on_body.tail<3>() += M;
      on_other.tail<3>() -= M;
    }
  }
}

// Redundant rows: weights D for the least-norm split, from the unweighted least-norm
// multipliers `lambda` (shared by the dense and the sparse path, which then re-solve for the
// weighted least-norm x = D y). Returns whether any weight differs from 1.
// - Sticking rows of several points (a box on four vertices, a cylinder on both end rims)
//   leave the friction split among the points undetermined; only the resultant is fixed. The
//   plain least-norm split shares it equally, so the least loaded point would reach its cone
//   first and the body would start to slip early, in steps. A rigid body held at several
//   points slips when the resultant exceeds what all of them can hold together, so the split
//   is the weighted least-norm one, min Σ |f_i|² / (mu_s N_i): friction in proportion to each
//   point's capacity, every point reaching its cone at the same instant under a pure
//   translation, when |Σ f| = mu_s Σ N. The N_i come from the unweighted solve (the weights
//   act inside the null space, which for coplanar points does not couple normal and
//   tangential rows). Normal rows keep weight 1.
// - Constraint rows take the constraint stage's weights (CalcReactionWeights: a moment row
//   weighs as a force at the mechanism's length), so no newton is traded against a
//   newton-metre here either.
bool CalcRedundantRowWeights(const Model& model, const State& state, const Data& data, int nc_rows,
                             const VectorXd& lambda, VectorXd& scale) {
  scale.resize(lambda.size());
  scale.setOnes();
  bool any = false;
  if (nc_rows > 0) {
    scale.head(nc_rows) = CalcReactionWeights(model, data);
    any = (scale.head(nc_rows).array() != 1.0).any();
  }
  double n_ref = 0.0;
  int k = nc_rows;
  for (int p = 0; p < model.num_contact_points(); ++p) {
    const ContactMode m = ModeOf(state, p);
    if (m == ContactMode::kSeparated) continue;
    n_ref = std::max(n_ref, lambda[k]);
    k += m == ContactMode::kSticking ? 3 + HeldRows(model, state, p) : 1;
  }
  k = nc_rows;
  for (int p = 0; p < model.num_contact_points(); ++p) {
    const ContactMode m = ModeOf(state, p);
    if (m == ContactMode::kSeparated) continue;
    if (m == ContactMode::kSticking) {
      const int ci = model.contact_of_point(p);
      const Contact& con = model.contact(ci);
      const double N = std::max(lambda[k], 0.0);
      // A floor keeps the column alive (a point carrying nothing still closes the rows).
      // Column scale D = √(capacity): the solve minimises Σ (f_i / D_i)² = Σ f_i² / c_i.
      if (n_ref > 0.0 && con.mu_s() > 0.0) {
        const double w = std::sqrt(std::max(con.mu_s() * N / n_ref, 1e-12));
        scale[k + 1] = scale[k + 2] = w;
        any = true;
      }
      // Held rolling shared the same way by capacity mu_r N R, a moment weighing as a force
      // at the feature's radius (as the constraint weights do): D = R √(mu_r N / n_ref).
      const int held = HeldRows(model, state, p);
      if (held > 0 && n_ref > 0.0) {
        const double R = con.feature(p - model.contact_point_offset(ci)).radius;
        const double w = R * std::sqrt(std::max(con.mu_r() * N / n_ref, 1e-12));
        for (int i = 0; i < held; ++i) scale[k + 3 + i] = w;
        any = true;
      }
      k += 3 + held;
    } else {
      k += 1;
    }
  }
  return any;
}

// The contact rows of the current modes, appended to `rows` with their right-hand sides in
// c (from row `k` on); fills the kinematic part of Data::contact_points.
void AppendContactRows(const Model& model, const State& state, Data& data,
                       internal::BlockRows& rows, VectorXd& c, int k) {
  using internal::Vec6;
  for (int p = 0; p < model.num_contact_points(); ++p) {
    const Contact& con = model.contact(model.contact_of_point(p));
    const ContactMode mode = ModeOf(state, p);
    const ContactPointGeometry g = internal::CalcContactPointGeometry(model, state, data, p);
    ContactPointOutput& out = data.contact_points[static_cast<size_t>(p)];
    out = ContactPointOutput{};
    out.mode = mode;
    out.gap = g.gap;
    out.p_WC = g.p_WC;
    out.n_W = g.n;
    out.normal_velocity = g.v_n;
    out.slip_velocity_W = g.v_t;
    if (mode == ContactMode::kSeparated) continue;
    // Row k: J = [J_body, J_other] of n·v_rel; W its force direction (NormalForceBlocks).
    Vec6 jb = Vec6::Zero(), jo = Vec6::Zero(), wb, wo;
    g.AddBlocks(g.n, 1.0, jb, jo);
    NormalForceBlocks(con, g, mode, PointStateOf(state, p), wb, wo);
    const auto add = [&](const Vec6& j_body, const Vec6& j_other, const Vec6& w_body,
                         const Vec6& w_other) {
      rows.Add(g.body, j_body, w_body);
      if (g.other != kWorld) rows.Add(g.other, j_other, w_other);
      rows.EndRow();
    };
    add(jb, jo, wb, wo);
    c[k++] = g.AccelerationBias(g.n);
    if (mode == ContactMode::kSticking) {
      for (const Vec3* t : {&g.t1, &g.t2}) {
        jb.setZero(), jo.setZero();
        g.AddBlocks(*t, 1.0, jb, jo);
        add(jb, jo, jb, jo);
        c[k++] = g.AccelerationBias(*t);
      }
      // Held rolling: a_i·ẇ_rel = bias_i, multipliers the holding moment about a_i.
      for (int i = 0; i < HeldRows(model, state, p); ++i) {
        jb.setZero(), jo.setZero();
        g.AddRollingBlocks(g.rolling_axis[i], jb, jo);
        add(jb, jo, jb, jo);
        c[k++] = g.rolling_bias[i];
      }
    }
  }
}

// Dense path: the rows scattered into J and W (rows × 6 n_bodies), A = J M⁻¹ Wᵀ formed and
// factored whole (least-norm when singular, friction then shared by CalcRedundantRowWeights).
void SolveContactDense(const Model& model, const State& state, Data& data, bool symmetric) {
  const int nb = model.num_bodies();
  const int nc_rows = model.num_constraint_rows();
  ContactWorkspace& ws = data.contact_work;
  const internal::BlockRows& br = internal::GetSparseWorkspace(data.sparse_contacts).rows;
  internal::ScatterBlocks(br, nb, ws.J, &ws.W);
  internal::TimesMassInverse(model, data, ws.W, ws.WMinv);
  ws.A.noalias() = ws.J * ws.WMinv.transpose();
  ws.rhs.noalias() = ws.c - ws.J * data.u_dot;
  if (nc_rows > 0) internal::HoldReleasedRows(data.row_released, ws.A, ws.rhs);
  const bool redundant = internal::SolveSquare(ws.A, ws.rhs, symmetric, ws, ws.lambda);
  if (redundant && CalcRedundantRowWeights(model, state, data, nc_rows, ws.lambda, ws.scale))
    internal::SolveSquare(ws.A, ws.rhs, symmetric, ws, ws.lambda, &ws.scale);
  data.u_dot.noalias() += ws.WMinv.transpose() * ws.lambda;
}

// Sparse path (dynamics/internal/sparse_solve.h). A singular symmetric system (every point
// sticking, redundant: a pile) gets the dense path's answer sparsely: the least-norm
// multipliers, then the weighted least-norm ones with CalcRedundantRowWeights. False when the
// system is singular and not symmetric (sliding), or the least-norm iteration gives up: then
// the dense path solves it.
bool SolveContactSparse(const Model& model, const State& state, Data& data, bool symmetric) {
  ContactWorkspace& ws = data.contact_work;
  internal::SparseWorkspace& sp = internal::GetSparseWorkspace(data.sparse_contacts);
  const int rows = sp.rows.rows();
  ws.rhs.resize(rows);
  for (int i = 0; i < rows; ++i) ws.rhs[i] = ws.c[i] - sp.rows.RowTimes(i, data.u_dot);
  if (!internal::SolveSparse(model, data, symmetric, sp, ws.rhs, ws.lambda)) {
    if (!symmetric || !internal::SolveSparseLeastNorm(sp, ws.rhs, nullptr, ws.lambda)) return false;
    if (CalcRedundantRowWeights(model, state, data, model.num_constraint_rows(), ws.lambda,
                                ws.scale) &&
        !internal::SolveSparseLeastNorm(sp, ws.rhs, &ws.scale, ws.lambda))
      return false;
  }
  internal::AddMinvWTimes(sp, ws.lambda, data.u_dot);
  return true;
}

}  // namespace

// ---------------------------------------------------------------------------------------
void SolveContactForces(const Model& model, const State& state, Data& data) {
  CheckDataFor(model, data);
  const int nb = model.num_bodies();
  const int nc_rows = model.num_constraint_rows();
  ContactWorkspace& ws = data.contact_work;
  // Count the active rows of the current modes.
  int rows = nc_rows;
  bool symmetric = true;
  for (int p = 0; p < model.num_contact_points(); ++p) {
    const ContactMode m = ModeOf(state, p);
    if (m == ContactMode::kSticking) rows += 3 + HeldRows(model, state, p);
    if (m == ContactMode::kSliding) rows += 1, symmetric = false;
    if (RollsWithResistance(PointStateOf(state, p))) symmetric = false;
  }
  // The active rows by body blocks: constraints, then contact points.
  internal::BlockRows& br = internal::GetSparseWorkspace(data.sparse_contacts).rows;
  br.Clear();
  ws.c.resize(rows);
  if (nc_rows > 0) {
    CalcConstraintRows(model, state, data);
    internal::AppendConstraintRows(model, data, br);
    ws.c.head(nc_rows) = data.acceleration_rhs;
  }
  AppendContactRows(model, state, data, br, ws.c, nc_rows);
  // (J M⁻¹ Wᵀ) λ = c - J u̇_free; u̇ = u̇_free + M⁻¹ Wᵀ λ.
  VectorXd& u_dot = data.u_dot;
  u_dot.resize(6 * nb);
  for (int b = 0; b < nb; ++b) {
    const auto i = static_cast<size_t>(b);
    u_dot.segment<3>(6 * b) = data.a_WBcm_W[i];
    u_dot.segment<3>(6 * b + 3) = data.R_WB[i] * data.wdot_WB_B[i];
  }
  if (!(internal::UseSparse(data.linear_solver, rows) &&
        SolveContactSparse(model, state, data, symmetric)))
    SolveContactDense(model, state, data, symmetric);
  for (int b = 0; b < nb; ++b) {
    const auto i = static_cast<size_t>(b);
    data.a_WBcm_W[i] = u_dot.segment<3>(6 * b);
    data.wdot_WB_B[i] = data.R_WB[i].transpose() * u_dot.segment<3>(6 * b + 3);
  }
  // Constraint reactions as in SolveConstraintForces (child's share of Jᵀλ, moved to J).
  if (nc_rows > 0) {
    data.lambda = ws.lambda.head(nc_rows);
    internal::FillConstraintReactions(model, state, data);
  }
  // Contact forces from the multipliers.
  int k = nc_rows;
  for (int p = 0; p < model.num_contact_points(); ++p) {
    ContactPointOutput& out = data.contact_points[static_cast<size_t>(p)];
    if (out.mode == ContactMode::kSeparated) continue;
    const Contact& con = model.contact(model.contact_of_point(p));
    const ContactPointState& ps = PointStateOf(state, p);
    const ContactPointGeometry g = internal::CalcContactPointGeometry(model, state, data, p);
    const double N = ws.lambda[k++];
    out.normal_force = N;
    out.slip_acceleration_W = (g.RowTimes(g.t1, u_dot) - g.AccelerationBias(g.t1)) * g.t1 +
                              (g.RowTimes(g.t2, u_dot) - g.AccelerationBias(g.t2)) * g.t2;
    if (out.mode == ContactMode::kSticking) {
      const double f1 = ws.lambda[k++], f2 = ws.lambda[k++];
      out.friction_force_W = f1 * g.t1 + f2 * g.t2;
      out.friction_needed = N > 0.0 ? out.friction_force_W.norm() / N : 0.0;
    } else {
      const Vec3 s = g.SlipDirection(ps.slip_direction_W);
      out.friction_force_W = -con.mu_k() * N * s;
      out.friction_power = out.friction_force_W.dot(g.v_t);
    }
    out.rolling_velocity_W = g.RollingVelocity();
    out.rolling_acceleration_W = g.RollingAcceleration(u_dot);
    if (con.mu_r() > 0.0 && g.round) out.rolling_moment_capacity = con.mu_r() * N * g.radius;
    const int held = HeldRows(model, state, p);
    out.rolling_held = held > 0;
    for (int i = 0; i < held; ++i) out.rolling_moment_W += ws.lambda[k++] * g.rolling_axis[i];
    if (held == 0 && out.mode == ContactMode::kSticking && con.mu_r() > 0.0 && g.round) {
      const Vec3 roll = g.RollingDirection(ps.rolling_direction_W);
      out.rolling_moment_W = -con.mu_r() * N * g.radius * roll;
      out.rolling_power = out.rolling_moment_W.dot(g.w_rel);
    }
  }
}

std::vector<ContactPointOutput> CalcContactOutputs(const Model& model, const State& state) {
  Data data = MakeData(model);
  CalcAccelerations(model, state, data);
  return data.contact_points;
}

// ---------------------------------------------------------------------------------------
// Mode selection and impacts share one problem: bilateral rows E (constraints, sticking
// tangents) and complementary normal rows of the touching points, at acceleration level
// (base = u̇_free, targets c) or velocity level (base = u⁻, targets the wanted velocities):
//   u' = base + M⁻¹ (W_Eᵀ λ_E + W_nᵀ N),  J_E u' = c_E,  w = J_n u' - c_n >= 0 ⟂ N >= 0.
// Eliminating λ_E = S⁺ (c_E - J_E base - J_E M⁻¹ W_nᵀ N) with S = J_E M⁻¹ W_Eᵀ leaves the
// LCP w = (D - C S⁺ B) N + (J_n base - c_n + C S⁺ r_E), D = J_n M⁻¹ W_nᵀ, B = J_E M⁻¹ W_nᵀ,
// C = J_n M⁻¹ W_Eᵀ, r_E = c_E - J_E base.
namespace {

struct PointPlan {
  int point = -1;
  ContactMode mode = ContactMode::kSticking;  // kSticking: tangential rows; kSliding: friction
  Vec3 s = Vec3::Zero();                      // slip direction of a sliding point
  bool held = false;                          // sticking with its rolling held: rolling rows
  double target_n = 0.0;                      // c_n
  Vec3 target_t = Vec3::Zero();               // c_t1, c_t2 (first two entries)
  Vec3 target_r = Vec3::Zero();               // held rolling rows' targets (first entries)
};

struct PlanSolution {
  VectorXd N;         // normal multipliers per plan entry
  VectorXd lambda_E;  // bilateral multipliers: constraint rows, then 2 per sticking point
  VectorXd w;         // complementary slacks
  VectorXd u_new;     // base + M⁻¹ Wᵀ λ
  bool solved = false;
};

// The plan's normal forces act along W_n, as in the contact stage (NormalForceBlocks): the
// normal, less mu_k s where a point slides, and, where `rolling` is given (its contact states
// hold the reference rolling directions), the rolling-resistance moment -mu_r N R ŵ_r of a
// round feature that rolls. Without that moment here, a pair of balls rolling on a floor with
// rolling resistance would be planned as parting while the contact stage presses them together.
PlanSolution SolvePlanDense(const Model& model, const Data& data,
                            const std::vector<ContactPointGeometry>& geo,
                            const std::vector<PointPlan>& plan, const VectorXd& base,
                            const VectorXd& c_constraints, bool complementary,
                            const State* rolling) {
  const int nb = model.num_bodies();
  const int ncr = model.num_constraint_rows();
  int n_bilateral = 0;
  for (const PointPlan& pp : plan) {
    if (pp.mode != ContactMode::kSticking) continue;
    n_bilateral += 2 + (pp.held ? geo[static_cast<size_t>(pp.point)].num_rolling_axes : 0);
  }
  const auto nE = static_cast<Eigen::Index>(ncr + n_bilateral);
  const auto nN = static_cast<Eigen::Index>(plan.size());
  MatrixXd JE = MatrixXd::Zero(nE, 6 * nb), Jn = MatrixXd::Zero(nN, 6 * nb);
  MatrixXd Wn = MatrixXd::Zero(nN, 6 * nb);
  VectorXd cE(nE), cn(nN);
  // The constraint rows from their blocks (Data::J, which may be empty: a sparse selection's
  // Data keeps none).
  for (int c = 0; c < model.num_constraints(); ++c)
    internal::WriteConstraintBlocks(model, data, c, JE.topRows(ncr));
  if (ncr > 0) cE.head(ncr) = c_constraints;
  Eigen::Index e = ncr;
  for (Eigen::Index i = 0; i < nN; ++i) {
    const PointPlan& pp = plan[static_cast<size_t>(i)];
    const ContactPointGeometry& g = geo[static_cast<size_t>(pp.point)];
    const Contact& con = model.contact(model.contact_of_point(pp.point));
    g.SetRow(g.n, Jn.row(i));
    Wn.row(i) = Jn.row(i);
    cn[i] = pp.target_n;
    if (pp.mode == ContactMode::kSliding && con.mu_k() > 0.0)
      g.AddRow(pp.s, -con.mu_k(), Wn.row(i));
    if (rolling != nullptr && pp.mode == ContactMode::kSticking && con.mu_r() > 0.0 && g.round) {
      const Vec3 roll_dir =
          g.RollingDirection(PointStateOf(*rolling, pp.point).rolling_direction_W);
      if (roll_dir.squaredNorm() > 0.0) g.AddMoment(-con.mu_r() * g.radius * roll_dir, Wn.row(i));
    }
    if (pp.mode == ContactMode::kSticking) {
      g.SetRow(g.t1, JE.row(e));
      cE[e++] = pp.target_t[0];
      g.SetRow(g.t2, JE.row(e));
      cE[e++] = pp.target_t[1];
      for (int a = 0; pp.held && a < g.num_rolling_axes; ++a) {
        g.AddMoment(g.rolling_axis[a], JE.row(e));  // the row a·w_rel
        cE[e++] = pp.target_r[a];
      }
    }
  }
  MatrixXd JEMi, WnMi;
  internal::TimesMassInverse(model, data, JE, JEMi);  // J_E M⁻¹ = (M⁻¹ W_Eᵀ)ᵀ, W_E = J_E
  internal::TimesMassInverse(model, data, Wn, WnMi);
  const MatrixXd S = JE * JEMi.transpose();
  const MatrixXd B = JE * WnMi.transpose();
  const MatrixXd C = Jn * JEMi.transpose();
  const MatrixXd D = Jn * WnMi.transpose();
  const VectorXd rE = cE - JE * base;
  Eigen::CompleteOrthogonalDecomposition<MatrixXd> cod;
  MatrixXd SB = MatrixXd::Zero(nE, nN);
  VectorXd Sr = VectorXd::Zero(nE);
  if (nE > 0) {
    cod.setThreshold(1e-10);
    cod.compute(S);
    SB = cod.solve(B);
    Sr = cod.solve(rE);
  }
  const MatrixXd A = D - C * SB;
  const VectorXd q = Jn * base - cn + C * Sr;
  PlanSolution sol;
  if (complementary) {
    const LcpResult lcp = SolveLcp(A, q);
    sol.N = lcp.z;
    sol.solved = lcp.solved;
  } else {
    ContactWorkspace ws;
    internal::SolveSquare(A, -q, false, ws, sol.N);
    sol.solved = true;
  }
  sol.w = A * sol.N + q;
  sol.lambda_E = Sr - SB * sol.N;
  sol.u_new = base + JEMi.transpose() * sol.lambda_E + WnMi.transpose() * sol.N;
  return sol;
}

// How the plan solves of one SelectContactModes choose their path, and the round-off of the
// sparse LCP's sign tests (forces and accelerations).
struct PlanOptions {
  LinearSolver solver = LinearSolver::kAuto;
  SparseWorkspaceHandle* workspace = nullptr;
  double f_tol = 0.0, a_tol = 0.0;
};

thread_local internal::ModeSelectionStats mode_selection_stats;

// The plan's rows by body blocks, as SolvePlanDense forms them: the constraint rows, then per
// point its normal row when it is in the pressing set `in` (force direction W_n: the normal,
// less mu_k s where it slides, with the rolling-resistance moment where it rolls), its two
// tangent rows when it sticks and its held rolling rows. `normal_row[i]` is the row of plan
// entry i's normal (-1 outside the set). Returns whether W = J on every row.
bool AppendPlanRows(const Model& model, const Data& data,
                    const std::vector<ContactPointGeometry>& geo,
                    const std::vector<PointPlan>& plan, const std::vector<char>& in,
                    const VectorXd& c_constraints, const State* rolling, internal::BlockRows& rows,
                    VectorXd& c, std::vector<int>& normal_row) {
  using internal::Vec6;
  const int ncr = model.num_constraint_rows();
  int n_rows = ncr;
  for (size_t i = 0; i < plan.size(); ++i) {
    n_rows += in[i] != 0 ? 1 : 0;
    if (plan[i].mode == ContactMode::kSticking) {
      n_rows += 2 + (plan[i].held ? geo[static_cast<size_t>(plan[i].point)].num_rolling_axes : 0);
    }
  }
  rows.Clear();
  c.resize(n_rows);
  if (ncr > 0) {
    internal::AppendConstraintRows(model, data, rows);
    c.head(ncr) = c_constraints;
  }
  normal_row.assign(plan.size(), -1);
  bool symmetric = true;
  int k = ncr;
  for (size_t i = 0; i < plan.size(); ++i) {
    const PointPlan& pp = plan[i];
    const ContactPointGeometry& g = geo[static_cast<size_t>(pp.point)];
    const Contact& con = model.contact(model.contact_of_point(pp.point));
    const auto add = [&](const Vec6& jb, const Vec6& jo, const Vec6& wb, const Vec6& wo) {
      rows.Add(g.body, jb, wb);
      if (g.other != kWorld) rows.Add(g.other, jo, wo);
      rows.EndRow();
    };
    Vec6 jb = Vec6::Zero(), jo = Vec6::Zero();
    if (in[i] != 0) {
      g.AddBlocks(g.n, 1.0, jb, jo);
      Vec6 wb = jb, wo = jo;
      if (pp.mode == ContactMode::kSliding && con.mu_k() > 0.0 && pp.s.squaredNorm() > 0.0) {
        g.AddBlocks(pp.s, -con.mu_k(), wb, wo);
        symmetric = false;
      }
      if (rolling != nullptr && pp.mode == ContactMode::kSticking && con.mu_r() > 0.0 && g.round) {
        const Vec3 roll_dir =
            g.RollingDirection(PointStateOf(*rolling, pp.point).rolling_direction_W);
        if (roll_dir.squaredNorm() > 0.0) {
          const Vec3 M = -con.mu_r() * g.radius * roll_dir;
          wb.tail<3>() += M;
          wo.tail<3>() -= M;
          symmetric = false;
        }
      }
      normal_row[i] = k;
      add(jb, jo, wb, wo);
      c[k++] = pp.target_n;
    }
    if (pp.mode != ContactMode::kSticking) continue;
    for (int a = 0; a < 2; ++a) {
      jb.setZero(), jo.setZero();
      g.AddBlocks(a == 0 ? g.t1 : g.t2, 1.0, jb, jo);
      add(jb, jo, jb, jo);
      c[k++] = pp.target_t[a];
    }
    for (int a = 0; pp.held && a < g.num_rolling_axes; ++a) {
      jb.setZero(), jo.setZero();
      g.AddRollingBlocks(g.rolling_axis[a], jb, jo);
      add(jb, jo, jb, jo);
      c[k++] = pp.target_r[a];
    }
  }
  return symmetric;
}

// The plan with the points of `in` pressing: the multipliers x of its rows (sparse LDLᵀ or LU;
// a singular symmetric system by its least-norm solution, which leaves the velocities or
// accelerations u unique) and u = base + M⁻¹ Wᵀ x. False where the dense path must answer.
bool SolvePlanRows(const Model& model, const Data& data,
                   const std::vector<ContactPointGeometry>& geo, const std::vector<PointPlan>& plan,
                   const std::vector<char>& in, const VectorXd& base, const VectorXd& c_constraints,
                   const State* rolling, internal::SparseWorkspace& sp,
                   std::vector<int>& normal_row, VectorXd& x, VectorXd& u) {
  VectorXd c;
  const bool symmetric =
      AppendPlanRows(model, data, geo, plan, in, c_constraints, rolling, sp.rows, c, normal_row);
  const int rows = sp.rows.rows();
  VectorXd r(rows);
  for (int i = 0; i < rows; ++i) r[i] = c[i] - sp.rows.RowTimes(i, base);
  if (!internal::SolveSparse(model, data, symmetric, sp, r, x) &&
      !(symmetric && sp.singular_symmetric && internal::SolveSparseLeastNorm(sp, r, nullptr, x)))
    return false;
  u = base;
  internal::AddMinvWTimes(sp, x, u);
  return true;
}

// Sparse plan solve (docs/design.md, "Sparse mode selection"): the rows by body blocks through
// the sparse factorisation, never the Schur complement D - C S⁺ B (dense even for a chain). The
// LCP 0 <= N ⟂ w >= 0 by principal pivoting on the pressing set P (Murty's least-index rule,
// finite for a P-matrix): solve the plan with the normal rows of P as equalities; the first
// point with N < 0 in P or w < 0 outside it (beyond round-off) changes sides; repeat. Its end
// is an LCP solution, checked as such: N >= 0 and w = 0 in P, w >= 0 outside. For the
// symmetric semidefinite LCP (no sliding friction, no rolling resistance) w is the same for
// every solution, so the points that stay are those of Lemke's method; the least-norm N of a
// redundant set is never read for it. False (the dense path answers) when a system is singular
// and not symmetric, when a row is released, or after 4 n + 20 pivots.
bool SolvePlanSparse(const Model& model, const Data& data,
                     const std::vector<ContactPointGeometry>& geo,
                     const std::vector<PointPlan>& plan, const VectorXd& base,
                     const VectorXd& c_constraints, bool complementary, const State* rolling,
                     const PlanOptions& opt, PlanSolution& sol) {
  for (char released : data.row_released) {
    if (released != 0) return false;
  }
  internal::SparseWorkspace& sp = internal::GetSparseWorkspace(*opt.workspace);
  const size_t nN = plan.size();
  std::vector<char> in(nN, 1);
  std::vector<int> normal_row;
  VectorXd x, u;
  sol.w.resize(static_cast<Eigen::Index>(nN));
  for (size_t pivots = 0;; ++pivots) {
    if (pivots > 4 * nN + 20) return false;
    if (!SolvePlanRows(model, data, geo, plan, in, base, c_constraints, rolling, sp, normal_row, x,
                       u))
      return false;
    for (size_t i = 0; i < nN; ++i) {
      const ContactPointGeometry& g = geo[static_cast<size_t>(plan[i].point)];
      sol.w[static_cast<Eigen::Index>(i)] = g.RowTimes(g.n, u) - plan[i].target_n;
    }
    if (!complementary) break;
    size_t flip = nN;
    for (size_t i = 0; i < nN && flip == nN; ++i) {
      const bool violated = in[i] != 0 ? x[normal_row[i]] < -opt.f_tol
                                       : sol.w[static_cast<Eigen::Index>(i)] < -opt.a_tol;
      if (violated) flip = i;
    }
    if (flip == nN) break;
    in[flip] = in[flip] != 0 ? 0 : 1;
    ++mode_selection_stats.sparse_pivots;
  }
  sol.N = VectorXd::Zero(static_cast<Eigen::Index>(nN));
  std::vector<char> is_normal(static_cast<size_t>(x.size()), 0);
  for (size_t i = 0; i < nN; ++i) {
    if (in[i] == 0) continue;
    sol.N[static_cast<Eigen::Index>(i)] = x[normal_row[i]];
    is_normal[static_cast<size_t>(normal_row[i])] = 1;
  }
  sol.lambda_E.resize(x.size() - static_cast<Eigen::Index>(std::count(in.begin(), in.end(), 1)));
  Eigen::Index e = 0;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    if (is_normal[static_cast<size_t>(i)] == 0) sol.lambda_E[e++] = x[i];
  }
  sol.u_new = std::move(u);
  sol.solved = true;
  return true;
}

// The plan solve on the path `opt` chooses (kAuto: sparse from kSparseMinRows rows on).
PlanSolution SolvePlan(const Model& model, const Data& data,
                       const std::vector<ContactPointGeometry>& geo,
                       const std::vector<PointPlan>& plan, const VectorXd& base,
                       const VectorXd& c_constraints, bool complementary, const State* rolling,
                       const PlanOptions& opt) {
  int rows = model.num_constraint_rows() + static_cast<int>(plan.size());
  for (const PointPlan& pp : plan) {
    if (pp.mode != ContactMode::kSticking) continue;
    rows += 2 + (pp.held ? geo[static_cast<size_t>(pp.point)].num_rolling_axes : 0);
  }
  if (opt.workspace != nullptr && internal::UseSparse(opt.solver, rows)) {
    PlanSolution sol;
    if (SolvePlanSparse(model, data, geo, plan, base, c_constraints, complementary, rolling, opt,
                        sol)) {
      ++mode_selection_stats.sparse_solves;
      return sol;
    }
  }
  ++mode_selection_stats.dense_solves;
  return SolvePlanDense(model, data, geo, plan, base, c_constraints, complementary, rolling);
}

bool Contains(const std::vector<int>& v, int p) {
  return std::find(v.begin(), v.end(), p) != v.end();
}

// The working set of SelectContactModes: the evaluated state's geometry and free
// accelerations, the plan of candidate points, and what each pass learned about them.
class ModeSelector {
 public:
  ModeSelector(const Model& model, const State& state, const ContactTolerances& tol,
               const ModeHints& hints, LinearSolver solver);
  // Candidates: touching and not moving apart.
  void PlanCandidates();
  // Passes over the plan until the modes are consistent; leaves the points in contact.
  void SelectModes();
  // Writes the modes and reference directions into `state`.
  void WriteModes(State& state) const;
  // Velocity projection onto the chosen rows (see the definition).
  void ProjectVelocities(State& state, ModeSelectionNotes* notes) const;
  // Whether either Data ended with its dense Data::J sized (ModeSelectionStats).
  bool DenseJacobianSized() const { return data_.J.size() != 0 || tdata_.J.size() != 0; }

 private:
  bool TakeSlidingAsSticking();
  const std::vector<ContactPointOutput>& EvaluateActive();
  bool DropPullingPoint(const std::vector<ContactPointOutput>& out);
  bool StartSlips(const std::vector<ContactPointOutput>& out);
  bool SettleStartingSlips(const std::vector<ContactPointOutput>& out);
  bool StartRollings(const std::vector<ContactPointOutput>& out);
  bool SettleStartingRollings(const std::vector<ContactPointOutput>& out);
  // Whether point p, sticking, holds its rolling: a round feature with rolling resistance
  // that is not rolling (no rolling reference).
  bool HoldsRolling(int p) const;
  void SetSticking(PointPlan& pp) const;
  void BookJams(State& state, const std::vector<PointPlan>& vplan, const PlanSolution& sol,
                double dT, ModeSelectionNotes* notes) const;

  const Model& model_;
  const ContactTolerances& tol_;
  const std::vector<int>& slip_starts_;
  const std::vector<int>& lift_offs_;
  const std::vector<int>& rolling_starts_;
  int np_;
  Data data_;
  VectorXd u_free_, u_, c_con_;
  std::vector<ContactPointGeometry> geo_;
  double a_scale_ = 0.0, f_scale_ = 0.0, a_tol_ = 0.0, a_cone_ = 0.0;
  std::vector<PointPlan> plan_, active_;
  // Per point: 0 untouched, 1 switched to sliding at zero slip (slip starting), 2 tried as
  // starting to slip and found to stick (not tried again).
  std::vector<int> starting_;
  std::vector<int> turns_;  // direction updates of a starting slip
  // The same for rolling: 1 a held rolling released to roll, 2 tried and found to hold; and
  // whether it was released with a crossed limit (rolling_starts): a body held at several
  // points shares its rolling by capacity, so they reach their limits together and a crossing
  // at one is a crossing at all.
  std::vector<int> rolling_starting_, rolling_turns_;
  std::vector<char> rolling_forced_;
  std::vector<int> jammed_;
  State trial_;
  Data tdata_;
  // The plan solves' path and the sparse path's workspace.
  PlanOptions opt_;
  mutable SparseWorkspaceHandle sparse_;
};

ModeSelector::ModeSelector(const Model& model, const State& state, const ContactTolerances& tol,
                           const ModeHints& hints, LinearSolver solver)
    : model_(model),
      tol_(tol),
      slip_starts_(hints.slip_starts),
      lift_offs_(hints.lift_offs),
      rolling_starts_(hints.rolling_starts),
      np_(model.num_contact_points()),
      data_(MakeData(model)) {
  CalcKinematics(model, state, data_);
  CalcForces(model, state, data_);
  FreeAccelerations(model, state, data_, u_free_);
  if (model.num_constraints() > 0) CalcConstraintRows(model, state, data_);
  geo_.resize(static_cast<size_t>(np_));
  for (int p = 0; p < np_; ++p) {
    geo_[static_cast<size_t>(p)] = internal::CalcContactPointGeometry(model, state, data_, p);
  }
  internal::GetVelocity(model, state, data_, u_);
  c_con_ = model.num_constraints() > 0 ? VectorXd(data_.acceleration_rhs) : VectorXd();
  a_scale_ = std::max(1.0, u_free_.cwiseAbs().maxCoeff());
  double m_max = 0.0;
  for (int b = 0; b < model.num_bodies(); ++b) m_max = std::max(m_max, model.body(b).mass());
  f_scale_ = m_max * a_scale_;
  a_tol_ = tol.relative * a_scale_;
  // The friction-cone test is at round-off level and symmetric: a point within
  // tol.cone (relative) of its cone is "at the limit", and there the motion decides: it is
  // tried as sliding in the direction of impending slip and slides if the slip then grows
  // (slip acceleration along s above tol.cone · a_scale), else it sticks. So a threshold found
  // by bisection on the regime is the exact one to round-off, from either side.
  a_cone_ = tol.cone * a_scale_;
  // The sparse LCP's sign tests at round-off of the force and acceleration scales.
  opt_.solver = solver;
  opt_.workspace = &sparse_;
  opt_.f_tol = 1e-11 * f_scale_;
  opt_.a_tol = 1e-11 * a_scale_;
  starting_.assign(static_cast<size_t>(np_), 0);
  turns_.assign(static_cast<size_t>(np_), 0);
  rolling_starting_.assign(static_cast<size_t>(np_), 0);
  rolling_turns_.assign(static_cast<size_t>(np_), 0);
  rolling_forced_.assign(static_cast<size_t>(np_), 0);
  // Each pass evaluates the active set with the contact stage itself (the forces the
  // integrator will use, friction shared as there), so what is checked is what is integrated.
  trial_ = state;
  tdata_ = MakeData(model);
  // The rolling reference of each round point with rolling resistance, as WriteModes will
  // write it (the rolling direction, or none below stick_speed): the plan and its evaluation
  // then use the moment the integrator will.
  // A round point not rolling faster than stick_speed (as a rim speed |w_r| R) has none: if it
  // sticks, its rolling is held (HoldsRolling).
  for (int p = 0; p < np_; ++p) {
    const ContactPointGeometry& g = geo_[static_cast<size_t>(p)];
    Vec3& ref = trial_.contacts[static_cast<size_t>(p)].rolling_direction_W;
    ref.setZero();
    trial_.contacts[static_cast<size_t>(p)].rolling_held = false;
    if (model.contact(model.contact_of_point(p)).mu_r() > 0.0 && g.num_rolling_axes > 0) {
      const Vec3 wr = g.RollingVelocity();
      if (wr.norm() * g.radius > tol.stick_speed) ref = wr.normalized();
    }
  }
}

bool ModeSelector::HoldsRolling(int p) const {
  return model_.contact(model_.contact_of_point(p)).mu_r() > 0.0 &&
         geo_[static_cast<size_t>(p)].num_rolling_axes > 0 &&
         trial_.contacts[static_cast<size_t>(p)].rolling_direction_W.squaredNorm() == 0.0;
}

void ModeSelector::SetSticking(PointPlan& pp) const {
  pp.mode = ContactMode::kSticking;
  pp.s.setZero();
  pp.held = HoldsRolling(pp.point);
}

void ModeSelector::PlanCandidates() {
  for (int p = 0; p < np_; ++p) {
    const ContactPointGeometry& g = geo_[static_cast<size_t>(p)];
    if (g.gap > tol_.gap || g.v_n > tol_.resting_speed) continue;
    PointPlan pp;
    pp.point = p;
    const double vt = g.v_t.norm();
    const Contact& con = model_.contact(model_.contact_of_point(p));
    if (vt > tol_.stick_speed) {
      pp.mode = ContactMode::kSliding;
      pp.s = g.v_t / vt;
    } else if (con.mu_s() == 0.0) {
      pp.mode = ContactMode::kSliding;  // frictionless: slides without a direction
    }
    pp.target_n = g.AccelerationBias(g.n);
    pp.target_t = Vec3(g.AccelerationBias(g.t1), g.AccelerationBias(g.t2), 0.0);
    pp.target_r = Vec3(g.rolling_bias[0], g.rolling_bias[1], 0.0);
    if (pp.mode == ContactMode::kSticking) pp.held = HoldsRolling(p);
    plan_.push_back(pp);
  }
}

void ModeSelector::SelectModes() {
  for (int pass = 0; pass < 24 * np_ + 8 && !plan_.empty(); ++pass) {
    PlanSolution sol = SolvePlan(model_, data_, geo_, plan_, u_free_, c_con_, true, &trial_, opt_);
    if (!sol.solved) {
      if (!TakeSlidingAsSticking()) break;
      continue;
    }
    // Points whose normal acceleration is positive leave (N = 0 there by complementarity).
    // A point whose normal force just fell through zero sits where N = 0 and a_n = 0 both hold
    // to round-off: it leaves unless it would press in by more than round-off.
    active_.clear();
    for (size_t i = 0; i < plan_.size(); ++i) {
      const double w = sol.w[static_cast<Eigen::Index>(i)];
      const bool stays = Contains(lift_offs_, plan_[i].point) ? w < -a_tol_ : w <= a_tol_;
      if (stays) active_.push_back(plan_[i]);
    }
    if (active_.empty()) break;
    const std::vector<ContactPointOutput>& out = EvaluateActive();
    if (DropPullingPoint(out)) {
      active_.clear();
      continue;
    }
    if (StartSlips(out)) continue;
    if (StartRollings(out)) continue;
    const bool slips_settled = !SettleStartingSlips(out);
    if (!SettleStartingRollings(out) && slips_settled) break;
  }
  plan_ = active_;
}

// No consistent normal forces with the sliding friction (a Painlevé-type inconsistency): the
// sliding points are taken as sticking, and their slip is removed by the impulsive velocity
// projection (ProjectVelocities: an impact without collision; reported in `notes`,
// docs/contact.md). Returns whether a point changed.
bool ModeSelector::TakeSlidingAsSticking() {
  bool changed = false;
  for (PointPlan& pp : plan_) {
    if (pp.mode == ContactMode::kSliding && pp.s.squaredNorm() > 0.0) {
      SetSticking(pp);
      changed = true;
      if (geo_[static_cast<size_t>(pp.point)].v_t.norm() > tol_.stick_speed) {
        jammed_.push_back(pp.point);
      }
    }
  }
  return changed;
}

// The contact stage at the trial state with the active points in their planned modes.
const std::vector<ContactPointOutput>& ModeSelector::EvaluateActive() {
  for (ContactPointState& ps : trial_.contacts) {
    ps.mode = ContactMode::kSeparated;
    ps.slip_direction_W.setZero();
    ps.rolling_held = false;
  }
  for (const PointPlan& pp : active_) {
    ContactPointState& ps = trial_.contacts[static_cast<size_t>(pp.point)];
    ps.mode = pp.mode;
    ps.slip_direction_W = pp.s;
    ps.rolling_held = pp.held;
  }
  CalcAccelerations(model_, trial_, tdata_);
  return tdata_.contact_points;
}

// A least-norm split may pull at a redundant point: that point leaves for good. Returns
// whether a point left.
bool ModeSelector::DropPullingPoint(const std::vector<ContactPointOutput>& out) {
  int drop = -1;
  double most_negative = -tol_.relative * f_scale_;
  for (const PointPlan& pp : active_) {
    const double N = out[static_cast<size_t>(pp.point)].normal_force;
    if (N < most_negative) most_negative = N, drop = pp.point;
  }
  if (drop < 0) return false;
  plan_.erase(std::find_if(plan_.begin(), plan_.end(),
                           [&](const PointPlan& pp) { return pp.point == drop; }));
  return true;
}

// Friction check of the sticking points. Ranks: 3, its friction limit was just crossed
// (slip_starts); 2, over the cone by more than round-off; 1, at the limit (within it).
// The points to switch: every point over the cone is handled one at a time, largest
// excess first; otherwise the crossed and at-limit points start to slip together: points
// that share a load in proportion to their capacity (CalcRedundantRowWeights) reach their
// cones together, and a rigid body held at several points breaks loose at all of them at
// once (one by one would load the rest past their cones in skewed directions). Returns
// whether a point started to slip.
bool ModeSelector::StartSlips(const std::vector<ContactPointOutput>& out) {
  struct Ranked {
    int point, rank;
    double excess;
    Vec3 f;
  };
  std::vector<Ranked> ranked;
  for (const PointPlan& pp : active_) {
    if (pp.mode != ContactMode::kSticking) continue;
    const auto ip = static_cast<size_t>(pp.point);
    if (starting_[ip] == 2) continue;
    const Contact& con = model_.contact(model_.contact_of_point(pp.point));
    const Vec3& f = out[ip].friction_force_W;
    const double cap = con.mu_s() * std::max(0.0, out[ip].normal_force);
    const double excess = f.norm() - cap;
    const double band = tol_.cone * std::max({f.norm(), cap, 1e-6 * f_scale_});
    int rank = 0;
    if (Contains(slip_starts_, pp.point) && f.norm() > band) {
      rank = 3;
    } else if (excess > band) {
      rank = 2;
    } else if (excess >= -band && f.norm() > band) {
      rank = 1;
    }
    if (rank > 0) ranked.push_back({pp.point, rank, excess, f});
  }
  if (ranked.empty()) return false;
  const auto worst =
      std::max_element(ranked.begin(), ranked.end(), [](const Ranked& a, const Ranked& b) {
        return a.rank == 2 && b.rank == 2 ? a.excess < b.excess : (a.rank == 2) < (b.rank == 2);
      });
  for (const Ranked& r : ranked) {
    if (worst->rank == 2 ? r.point != worst->point : r.rank == 2) continue;
    for (PointPlan& pp : plan_) {
      if (pp.point != r.point) continue;
      pp.mode = ContactMode::kSliding;
      pp.held = false;
      pp.s = -r.f.normalized();  // slip starts against the friction it needed
    }
    starting_[static_cast<size_t>(r.point)] = 1;
  }
  return true;
}

// Consistency of the slips that start: the slip acceleration a_t must point along s (a
// slip that starts grows along its own direction, and friction -mu_k N s opposes it:
// maximum dissipation). Where a_t has turned from s (an anisotropic body), s follows it
// (fixed point s = a_t/|a_t|); a point whose slip would not grow sticks after all. Returns
// whether a point reverted or turned (another pass is needed).
bool ModeSelector::SettleStartingSlips(const std::vector<ContactPointOutput>& out) {
  int revert = -1;
  bool turned = false;
  for (PointPlan& pp : plan_) {
    const auto ip = static_cast<size_t>(pp.point);
    if (starting_[ip] != 1 || pp.mode != ContactMode::kSliding) continue;
    const Vec3& a_t = out[ip].slip_acceleration_W;
    const double a_s = a_t.dot(pp.s);
    const bool forced = Contains(slip_starts_, pp.point);
    if (a_s < -a_cone_ || (!forced && a_s <= a_cone_)) {
      revert = pp.point;
      SetSticking(pp);
      starting_[ip] = 2;
      break;
    }
    if (a_t.norm() > a_cone_ && turns_[ip] < 20 && (a_t.normalized() - pp.s).norm() > 1e-12) {
      pp.s = a_t.normalized();
      ++turns_[ip];
      turned = true;
    }
  }
  return revert >= 0 || turned;
}

// Rolling-resistance check of the points whose rolling is held, as StartSlips for friction:
// the holding moment M against the capacity mu_r N R. Ranks: 3, its limit was just crossed
// (rolling_starts); 2, over the capacity by more than round-off; 1, at the limit. Every
// point over its capacity is released one at a time, largest excess first; otherwise the
// crossed and at-limit points are released together. A released point rolls in the
// direction of impending rolling, against the moment that held it (then along its rolling
// acceleration: SettleStartingRollings). Returns whether a point was released.
bool ModeSelector::StartRollings(const std::vector<ContactPointOutput>& out) {
  struct Ranked {
    int point, rank;
    double excess;
    Vec3 M;
    double size;  // max(|M|, mu_r N R)
  };
  std::vector<Ranked> ranked;
  for (const PointPlan& pp : active_) {
    if (pp.mode != ContactMode::kSticking || !pp.held) continue;
    const auto ip = static_cast<size_t>(pp.point);
    if (rolling_starting_[ip] == 2) continue;
    const Vec3& M = out[ip].rolling_moment_W;
    const double cap = out[ip].rolling_moment_capacity;
    const double radius = geo_[ip].radius;
    const double excess = M.norm() - cap;
    const double band = tol_.cone * std::max({M.norm(), cap, 1e-6 * f_scale_ * radius});
    int rank = 0;
    if (Contains(rolling_starts_, pp.point) && M.norm() > band) {
      rank = 3;
    } else if (excess > band) {
      rank = 2;
    } else if (excess >= -band && M.norm() > band) {
      rank = 1;
    }
    if (rank > 0) ranked.push_back({pp.point, rank, excess, M, std::max(M.norm(), cap)});
  }
  if (ranked.empty()) return false;
  // At a crossed limit (an event located to its round-off band, 1e-9 of the moment), the
  // points that share the rolling reached their limits at the same instant: one over by no
  // more than that band is at its limit, not past it.
  const bool crossed =
      std::any_of(ranked.begin(), ranked.end(), [](const Ranked& r) { return r.rank == 3; });
  for (Ranked& r : ranked) {
    if (crossed && r.rank == 2 && r.excess <= 1e-9 * r.size) r.rank = 1;
  }
  const auto worst =
      std::max_element(ranked.begin(), ranked.end(), [](const Ranked& a, const Ranked& b) {
        return a.rank == 2 && b.rank == 2 ? a.excess < b.excess : (a.rank == 2) < (b.rank == 2);
      });
  for (const Ranked& r : ranked) {
    if (worst->rank == 2 ? r.point != worst->point : r.rank == 2) continue;
    for (PointPlan& pp : plan_) {
      if (pp.point == r.point) pp.held = false;
    }
    const auto ip = static_cast<size_t>(r.point);
    trial_.contacts[ip].rolling_direction_W = -r.M.normalized();
    rolling_starting_[ip] = 1;
    rolling_forced_[ip] = worst->rank != 2 && crossed;
  }
  return true;
}

// Consistency of the rollings that start, as SettleStartingSlips: the rolling acceleration
// must point along the rolling direction d (a rolling that starts grows along d, and the
// moment -mu_r N R d opposes it); d follows it where it has turned (fixed point
// d = a_r/|a_r|), and a point whose rolling would not grow is held after all. Returns whether
// a point reverted or turned.
bool ModeSelector::SettleStartingRollings(const std::vector<ContactPointOutput>& out) {
  bool changed = false;
  for (PointPlan& pp : plan_) {
    const auto ip = static_cast<size_t>(pp.point);
    if (rolling_starting_[ip] != 1 || pp.mode != ContactMode::kSticking || pp.held) continue;
    Vec3& d = trial_.contacts[ip].rolling_direction_W;
    const Vec3& a_r = out[ip].rolling_acceleration_W;
    const double a_d = a_r.dot(d);
    const bool forced = rolling_forced_[ip] != 0;
    if (a_d < -a_cone_ || (!forced && a_d <= a_cone_)) {
      d.setZero();
      pp.held = true;
      rolling_starting_[ip] = 2;
      return true;
    }
    if (a_r.norm() > a_cone_ && rolling_turns_[ip] < 20 && (a_r.normalized() - d).norm() > 1e-12) {
      d = a_r.normalized();
      ++rolling_turns_[ip];
      changed = true;
    }
  }
  return changed;
}

void ModeSelector::WriteModes(State& state) const {
  for (int p = 0; p < np_; ++p) {
    ContactPointState& ps = state.contacts[static_cast<size_t>(p)];
    ps.mode = ContactMode::kSeparated;
    ps.slip_direction_W.setZero();
    ps.rolling_direction_W.setZero();
    ps.rolling_held = false;
  }
  for (const PointPlan& pp : plan_) {
    ContactPointState& ps = state.contacts[static_cast<size_t>(pp.point)];
    ps.mode = pp.mode;
    if (pp.mode == ContactMode::kSliding) ps.slip_direction_W = pp.s;
    ps.rolling_held = pp.mode == ContactMode::kSticking && pp.held;
    ps.rolling_direction_W =
        ps.rolling_held ? Vec3::Zero()
                        : trial_.contacts[static_cast<size_t>(pp.point)].rolling_direction_W;
  }
}

// Velocity projection onto the chosen rows: normal velocity zero at pressing points,
// tangential too at sticking ones, constraints J u = b. For the round-off velocities of
// touching points this is a tidy-up; for jammed points (TakeSlidingAsSticking) it is the
// impulse that stops their slip, checked against the friction cone.
void ModeSelector::ProjectVelocities(State& state, ModeSelectionNotes* notes) const {
  if (plan_.empty()) return;
  const double T0 = internal::KineticEnergy(model_, state);
  std::vector<PointPlan> vplan = plan_;
  for (PointPlan& pp : vplan) pp.target_n = 0.0, pp.target_t.setZero(), pp.target_r.setZero();
  // Sliding points keep their slip: only their normal row (no friction in this correction).
  for (PointPlan& pp : vplan) {
    if (pp.mode == ContactMode::kSliding) pp.s.setZero();
  }
  const VectorXd b_con = model_.num_constraints() > 0 ? VectorXd(data_.velocity_rhs) : VectorXd();
  // A jam books the split of its impulses among the points: the dense path's split.
  PlanOptions opt = opt_;
  if (!jammed_.empty()) opt.solver = LinearSolver::kDense;
  const PlanSolution sol = SolvePlan(model_, data_, geo_, vplan, u_, b_con, false, nullptr, opt);
  internal::SetVelocity(model_, data_, sol.u_new, state);
  const double dT = internal::KineticEnergy(model_, state) - T0;
  if (jammed_.empty()) {
    state.contacts[static_cast<size_t>(plan_.front().point)].friction_work += dT;
  } else {
    BookJams(state, vplan, sol, dT, notes);
  }
}

// The jam is an impulse: its energy goes to the impact ledger, shared by the jammed points'
// normal impulses (equally when they carry none).
void ModeSelector::BookJams(State& state, const std::vector<PointPlan>& vplan,
                            const PlanSolution& sol, double dT, ModeSelectionNotes* notes) const {
  Eigen::Index e = model_.num_constraint_rows();
  std::vector<JamImpulse> jams;
  for (size_t i = 0; i < vplan.size(); ++i) {
    const PointPlan& pp = vplan[i];
    const ContactPointGeometry& g = geo_[static_cast<size_t>(pp.point)];
    double Pn = sol.N[static_cast<Eigen::Index>(i)];
    Vec3 Pt = Vec3::Zero();
    if (pp.mode == ContactMode::kSticking) {
      Pt = sol.lambda_E[e] * g.t1 + sol.lambda_E[e + 1] * g.t2;
      e += 2 + (pp.held ? g.num_rolling_axes : 0);
    }
    if (!Contains(jammed_, pp.point)) continue;
    jams.push_back({pp.point, Pn, Pn * g.n + Pt, g.v_t.norm()});
  }
  const double n = static_cast<double>(jams.size());
  double pn_sum = 0.0;
  for (const JamImpulse& j : jams) pn_sum += std::max(0.0, j.normal_impulse);
  for (JamImpulse& j : jams) {
    const double share = pn_sum > 0.0 ? std::max(0.0, j.normal_impulse) / pn_sum : 1.0 / n;
    j.energy_lost = -dT * share;
    state.contacts[static_cast<size_t>(j.point)].impact_work += dT * share;
    const Contact& con = model_.contact(model_.contact_of_point(j.point));
    const ContactPointGeometry& g = geo_[static_cast<size_t>(j.point)];
    const double Pn = j.normal_impulse;
    const double Pt = (j.impulse_W - Pn * g.n).norm();
    if (Pn < 0.0 || Pt > con.mu_s() * Pn * (1.0 + tol_.cone) + tol_.cone * j.impulse_W.norm()) {
      throw InputError(
          fmt::format(
              "contact point '{}' at t = {:.9g} s: sliding at {:.6g} m/s, the contact forces "
              "have no consistent solution (a Painlevé-type paradox of rigid bodies with "
              "friction), and the impulse that would stop the slip ({:.6g} N·s tangential, "
              "{:.6g} N·s normal) lies outside the friction cone mu_s = {}: the rigid model "
              "has no answer here. Lower the friction coefficient or soften the model",
              model_.contact_point_name(j.point), state.t, j.slip_speed, Pt, Pn, con.mu_s()),
          ErrorElement{ErrorElement::Kind::kContactPoint, j.point});
    }
  }
  if (notes != nullptr) notes->jams = std::move(jams);
}

}  // namespace

namespace internal {

const ModeSelectionStats& LastModeSelectionStats() {
  return mode_selection_stats;
}

std::vector<ContactModeChange> SelectContactModes(const Model& model, State& state,
                                                  const ContactTolerances& tol,
                                                  const ModeHints& hints, ModeSelectionNotes* notes,
                                                  LinearSolver solver) {
  mode_selection_stats = ModeSelectionStats{};
  const int np = model.num_contact_points();
  if (state.contacts.size() != static_cast<size_t>(np)) {
    state.contacts.assign(static_cast<size_t>(np), ContactPointState{});
  }
  const std::vector<ContactPointState> before = state.contacts;
  ModeSelector selector(model, state, tol, hints, solver);
  selector.PlanCandidates();
  selector.SelectModes();
  selector.WriteModes(state);
  selector.ProjectVelocities(state, notes);
  mode_selection_stats.dense_jacobian = selector.DenseJacobianSized();
  std::vector<ContactModeChange> changes;
  for (int p = 0; p < np; ++p) {
    const ContactPointState& a = before[static_cast<size_t>(p)];
    const ContactPointState& b = state.contacts[static_cast<size_t>(p)];
    if (a.mode != b.mode || a.rolling_held != b.rolling_held)
      changes.push_back({p, a.mode, b.mode, a.rolling_held, b.rolling_held});
  }
  return changes;
}

}  // namespace internal

std::vector<ContactModeChange> SelectContactModes(const Model& model, State& state,
                                                  const ContactTolerances& tol,
                                                  const ModeHints& hints,
                                                  ModeSelectionNotes* notes) {
  return internal::SelectContactModes(model, state, tol, hints, notes, LinearSolver::kAuto);
}

}  // namespace chasles
