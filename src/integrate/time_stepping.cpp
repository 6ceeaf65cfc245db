#include "chasles/integrate/time_stepping.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <numeric>

#include <fmt/format.h>

#include "chasles/dynamics/contact_frame.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/error.h"
#include "chasles/integrate/ball_pairs.h"
#include "chasles/integrate/parallel.h"
#include "chasles/math/quaternion.h"
#include "chasles/model/constraints.h"
#include "chasles/model/data.h"
#include "integrate/internal/collision_law.h"

// Moreau–Jean time stepping (J. J. Moreau, "Unilateral contact and dry friction in finite
// freedom dynamics", CISM 302, 1988; M. Jean, Comput. Methods Appl. Mech. Eng. 177, 1999) with
// θ = ½. Velocities u = [v_WBcm; w_WB_W] per body, the rotational part in W at the midpoint
// configuration, where the mass matrix is M_m = diag(m I, R_m I_B R_mᵀ). Over a step of h:
//   q_m = q_k + h/2 u_k (the orientation by the exact rotation exp(h/2 w_W) q_k, so that
//   R_m w_B,k = R_k w_B,k: the world angular velocity at the start is the same in either frame);
//   u_free = u_k + h M_m⁻¹ (f(q_m, u_k) - [0; w × I_W w]);
//   u_k+1 = u_free + M_m⁻¹ Jᵀ P, P from the frictional contact problem U = W P + q with
//   W = J M_m⁻¹ Jᵀ, q = J u_free + e min(J_n u_k, 0) on the normal rows;
//   p_k+1 = p_k + h (v_k + v_k+1)/2, q_k+1 = exp(h (w_k + w_k+1)/2) q_k (world-frame rotation).
// Why this balances: with p_m = p_k + h/2 v_k, p_k+1 × v_k+1 - p_k × v_k = p_m × (v_k+1 - v_k),
// so the angular momentum about Wo changes by exactly the impulses' moments about their
// points of application at q_m (an isotropic body's spin as well); the kinetic energy changes
// by (u_k+1 - u_k)ᵀ M_m ū = h fᵀ ū + Pᵀ J ū (ū the step's mean velocity), so each impulse's
// work is Pᵀ U_mean (normal and friction apart), gravity's h F·v̄ is exactly -ΔV, and what
// remains (the gyroscopic term's and a velocity-dependent force's work at u_k against ū, a
// non-isotropic body's inertia turning between q_m and q_k+1) is the scheme's energy error.

namespace chasles {
namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat63 = Eigen::Matrix<double, 6, 3>;

// One active point at the midpoint configuration: the 3 rows (n, t1, t2) on each body,
// A = [k; r × k] per row (the other body's with a minus sign), and its coefficients. `point`
// is the Model's contact point, or num_contact_points() + k for the step's k-th pair of balls
// (TimeSteppingOptions::collide_all_pairs).
struct ActivePoint {
  int point = -1;
  BodyIndex body = kWorld, other = kWorld;
  Eigen::Matrix<double, 3, 6> A_body, A_other;
  Vec3 n, t1, t2;
  /// Offsets from each body's centre of mass to the point, in W [m].
  Vec3 r = Vec3::Zero(), r_other = Vec3::Zero();
  double mu = 0.0, restitution = 0.0;
  /// Gap at the midpoint [m] and how far the normal turned from the step's start to it.
  double gap = 0.0, turn = 0.0;
};

// The bodies' velocities in the step's frame: v and w in W.
struct Velocities {
  std::vector<Vec6> u;
};

double CalcEnergy(const Model& model, const State& s) {
  double E = 0.0;
  for (int b = 0; b < model.num_bodies(); ++b) {
    const BodyState& bs = s.bodies[static_cast<size_t>(b)];
    const Body& body = model.body(b);
    E += 0.5 * body.mass() * bs.v_WBcm_W.squaredNorm() +
         0.5 * bs.w_WB_B.dot(body.I_BBcm_B() * bs.w_WB_B);
  }
  for (int e = 0; e < model.num_force_elements(); ++e) {
    const ForceElement& fe = model.force_element(e);
    if (fe.has_potential()) E += fe.CalcPotentialEnergy(model, s);
  }
  return E;
}

// Disjoint sets over bodies (union by size, path halving).
class BodySets {
 public:
  explicit BodySets(int n) : parent_(static_cast<size_t>(n)), size_(static_cast<size_t>(n), 1) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  int Find(int x) {
    while (parent_[static_cast<size_t>(x)] != x) {
      const auto i = static_cast<size_t>(x);
      parent_[i] = parent_[static_cast<size_t>(parent_[i])];
      x = parent_[i];
    }
    return x;
  }
  void Link(int a, int b) {
    a = Find(a);
    b = Find(b);
    if (a == b) return;
    if (size_[static_cast<size_t>(a)] < size_[static_cast<size_t>(b)]) std::swap(a, b);
    parent_[static_cast<size_t>(b)] = a;
    size_[static_cast<size_t>(a)] += size_[static_cast<size_t>(b)];
  }

 private:
  std::vector<int> parent_, size_;
};

// A pair of balls held closed (sticking or sliding) at a step's end: its regime then and gap
// (TimeSteppingOptions::collide_all_pairs; a pair not listed is apart).
struct ClosedPair {
  std::pair<int, int> bodies;
  ContactMode mode = ContactMode::kSeparated;
  double gap = 0.0;  // [m]
};

// The gaps and normals of all points at one configuration, and the pairs of balls held closed
// there (in the order of their bodies).
struct Geometry {
  std::vector<double> gaps;  // [m]
  std::vector<Vec3> normals;
  std::vector<ClosedPair> pairs;
};

// An impact in a step (an active point approaching at the step's start): what the run's
// accumulated error estimate takes from it (Run::Propagate).
struct Impact {
  int point = -1;
  BodyIndex body = kWorld, other = kWorld;
  /// How long before the midpoint the point touched, -gap / approach speed, at most h [s].
  double tau = 0.0;
  /// The normal's turn over tau [rad] (its turn from the step's start to the midpoint, scaled).
  double turn = 0.0;
  /// |P| [N·s] and the rate of P_n with the normal's turn, (1 + e) m_eff |U_t| [N·s/rad]
  /// (m_eff = 1/W_nn), times (1 + mu) for the friction impulse that follows it.
  double impulse = 0.0, impulse_rate = 0.0;
  /// The normal's lever for a body-body point, |r| + |r_other| [m] (0 against the world).
  double reach = 0.0;
  /// (1 + e) m_eff / m of each body: how the other body's velocity error passes through.
  double pass_body = 0.0, pass_other = 0.0;
};

// What one step reports before the certificate is assembled.
struct StepOutcome {
  TimeSteppingStep cert;
  std::vector<ContactRegime> regime;  // per point (open for the inactive ones)
  Geometry end;                       // per point at the step's end
  double energy = 0.0;                // T + V at the step's end [J]
  std::vector<Impact> impacts;
  std::vector<char> is_impact;  // per point
  /// Per body: |h F + the impulses of its points that are not impacts| / m [m/s].
  std::vector<double> other_dv;
};

class Stepper {
 public:
  Stepper(const Model& model, const TimeSteppingOptions& o)
      : model_(model),
        o_(o),
        data_(MakeData(model)),
        warm_(static_cast<size_t>(model.num_contact_points()), Eigen::Vector3d::Zero()) {
    if (!o.collide_all_pairs) return;
    radius_ = o.ball_radii.empty() ? BallRadii(model) : o.ball_radii;
    for (int c = 0; c < model.num_contacts(); ++c) {
      const ContactSpec& spec = model.contact(c).spec();
      if (spec.shape != ContactShape::kSphereSphere) continue;
      declared_.push_back(
          {std::min(spec.body, spec.other_body), std::max(spec.body, spec.other_body)});
    }
    std::sort(declared_.begin(), declared_.end());
  }

  // One Moreau–Jean step of length h, in place.
  // `gaps` and `energy` are the start's (the previous outcome's).
  StepOutcome Step(State& s, double h, const Geometry& start, double energy);
  // Gaps and normals of all points at `s`.
  Geometry Measure(const State& s);

 private:
  void Midpoint(const State& s, double h, State& mid) const;
  void FreeVelocities(const State& s, double h, std::vector<Vec6>& u_k, std::vector<Vec6>& u_free);
  // The points touching at the midpoint, into `active` (a buffer kept between steps: a pile's
  // thousand points are some 300 KB, which a fresh vector would fault in every step).
  void FindActive(const State& s, const State& mid, const Geometry& start,
                  std::vector<ActivePoint>& active) const;
  void FindActivePairs(const State& s, const State& mid, std::vector<ActivePoint>& active) const;
  std::vector<std::pair<int, int>> NearPairs(const State& s, double reach) const;
  Eigen::Vector3d& Warm(int point);
  void KeepPairWarmStarts(const std::vector<ActivePoint>& active);
  void CertifyPairs(const State& next, const std::vector<ActivePoint>& active,
                    const Geometry& start, StepOutcome& out) const;
  void SolveIslands(const std::vector<ActivePoint>& active, const std::vector<Vec6>& u_k, double h,
                    std::vector<Vec6>& u, std::vector<Eigen::Vector3d>& P, StepOutcome& out);
  ContactProblemSolution SolveIsland(const std::vector<ActivePoint>& active,
                                     const std::vector<int>& members, const std::vector<Vec6>& u_k,
                                     double h, std::vector<Vec6>& u,
                                     std::vector<Eigen::Vector3d>& P,
                                     std::vector<ContactRegime>& regime,
                                     std::vector<Impact>& impacts);
  Mat63 MinvAt(BodyIndex b, const Eigen::Matrix<double, 3, 6>& A) const;
  void Advance(const State& s, const std::vector<Vec6>& u_k, const std::vector<Vec6>& u, double h,
               State& next) const;
  void BookForces(const State& mid, const std::vector<Vec6>& u_k, const std::vector<Vec6>& u,
                  double h, State& next, StepOutcome& out, Vec3& impulse, Vec3& moment);
  void BookContacts(const State& mid, const std::vector<ActivePoint>& active,
                    const std::vector<Eigen::Vector3d>& P, const std::vector<Vec6>& u_k,
                    const std::vector<Vec6>& u, State& next, StepOutcome& out, Vec3& impulse,
                    Vec3& moment) const;
  void Certify(const State& s, const State& next, const Vec3& impulse, const Vec3& moment,
               const std::vector<double>& gaps, double energy, StepOutcome& out);
  Impact MakeImpact(const ActivePoint& a, const Eigen::Vector3d& U_k, const Eigen::Vector3d& P,
                    double W_nn, double h) const;
  void OtherImpulses(const std::vector<ActivePoint>& active, const std::vector<Eigen::Vector3d>& P,
                     double h, StepOutcome& out) const;

  const Model& model_;
  const TimeSteppingOptions& o_;
  Data data_;
  std::vector<Mat3> R_m_, I_W_inv_;    // per body at the midpoint
  std::vector<Vec3> F_, M_;            // applied force and moment about Bcm, in W
  std::vector<Eigen::Vector3d> warm_;  // last impulse per point, per second of step [N]
  // Pairs of balls (collide_all_pairs): each body's ball radius (0: none), the pairs the model
  // lists (they keep their contacts), and the last impulses of the pairs active in the last
  // step (by bodies) and of this step's pair points (per pair point, as warm_).
  std::vector<double> radius_;
  std::vector<std::pair<int, int>> declared_;
  std::vector<std::pair<std::pair<int, int>, Eigen::Vector3d>> pair_warm_;
  std::vector<Eigen::Vector3d> step_pair_warm_;
  std::vector<ActivePoint> active_;  // the current step's (FindActive)
};

void Stepper::Midpoint(const State& s, double h, State& mid) const {
  mid.t = s.t + 0.5 * h;
  for (size_t b = 0; b < s.bodies.size(); ++b) {
    const BodyState& bs = s.bodies[b];
    BodyState& m = mid.bodies[b];
    m.p_WBcm = bs.p_WBcm + 0.5 * h * bs.v_WBcm_W;
    m.q_WB = IntegrateBodyAngularVelocity(bs.q_WB, bs.w_WB_B, 0.5 * h);
    m.v_WBcm_W = bs.v_WBcm_W;
    m.w_WB_B = bs.w_WB_B;
  }
}

Mat63 Stepper::MinvAt(BodyIndex b, const Eigen::Matrix<double, 3, 6>& A) const {
  const auto i = static_cast<size_t>(b);
  Mat63 G;
  G.topRows<3>() = A.leftCols<3>().transpose() / model_.body(b).mass();
  G.bottomRows<3>() = I_W_inv_[i] * A.rightCols<3>().transpose();
  return G;
}

void Stepper::FreeVelocities(const State& s, double h, std::vector<Vec6>& u_k,
                             std::vector<Vec6>& u_free) {
  const int n = model_.num_bodies();
  R_m_.resize(static_cast<size_t>(n));
  I_W_inv_.resize(static_cast<size_t>(n));
  for (int b = 0; b < n; ++b) {
    const auto i = static_cast<size_t>(b);
    const Body& body = model_.body(b);
    const Mat3& R = data_.R_WB[i];
    R_m_[i] = R;
    I_W_inv_[i] = R * body.I_BBcm_B_inverse() * R.transpose();
    const BodyState& bs = s.bodies[i];
    // R_m w_B,k is the world angular velocity at the start (see the file comment).
    const Vec3 w = R * bs.w_WB_B;
    const Mat3 I_W = R * body.I_BBcm_B() * R.transpose();
    u_k[i] << bs.v_WBcm_W, w;
    u_free[i] << bs.v_WBcm_W + h * data_.F_Bcm_W[i] / body.mass(),
        w + h * I_W_inv_[i] * (data_.M_Bcm_W[i] - w.cross(I_W * w));
  }
}

void Stepper::FindActive(const State& s, const State& mid, const Geometry& start,
                         std::vector<ActivePoint>& active) const {
  active.clear();
  for (int p = 0; p < model_.num_contact_points(); ++p) {
    const ContactFrame g = CalcContactFrame(model_, mid, data_, p);
    if (g.gap > o_.tolerances.gap) continue;
    ActivePoint a;
    a.point = p;
    a.body = g.body;
    a.other = g.other;
    a.n = g.n;
    a.t1 = g.t1;
    a.t2 = g.t2;
    a.r = g.r_BcmC_W;
    a.r_other = g.r_OcmC_W;
    a.gap = g.gap;
    a.turn = (g.n - start.normals[static_cast<size_t>(p)]).norm();
    const Vec3 k[3] = {g.n, g.t1, g.t2};
    for (int r = 0; r < 3; ++r) {
      a.A_body.row(r) << k[r].transpose(), a.r.cross(k[r]).transpose();
      a.A_other.row(r) << -k[r].transpose(), -a.r_other.cross(k[r]).transpose();
    }
    const Contact& c = model_.contact(model_.contact_of_point(p));
    const double slip = g.v_t_W.norm();
    a.mu = slip <= o_.tolerances.stick_speed ? c.mu_s() : c.mu_k();
    a.restitution = c.restitution();
    active.push_back(std::move(a));
  }
  if (o_.collide_all_pairs) FindActivePairs(s, mid, active);
}

// The pairs of balls whose spheres lie within `reach` of touching at `s` [m], the listed pairs
// left out.
std::vector<std::pair<int, int>> Stepper::NearPairs(const State& s, double reach) const {
  std::vector<Vec3> centres(s.bodies.size());
  for (size_t b = 0; b < centres.size(); ++b) centres[b] = s.bodies[b].p_WBcm;
  std::vector<std::pair<int, int>> pairs = FindSpherePairs(centres, radius_, reach);
  if (!declared_.empty()) {
    std::erase_if(pairs, [&](const std::pair<int, int>& p) {
      return std::binary_search(declared_.begin(), declared_.end(), p);
    });
  }
  return pairs;
}

// The pairs of balls touching at the midpoint (gap within the touching tolerance), each as a
// sphere-sphere point of its two balls (body the first, the normal towards it), as the model's
// own sphere-sphere points are built (CalcContactFrame).
void Stepper::FindActivePairs(const State& s, const State& mid,
                              std::vector<ActivePoint>& active) const {
  const int first = model_.num_contact_points();
  int k = 0;
  for (const auto& [i, j] : NearPairs(mid, o_.tolerances.gap)) {
    const auto bi = static_cast<size_t>(i), bj = static_cast<size_t>(j);
    const Vec3 d = mid.bodies[bi].p_WBcm - mid.bodies[bj].p_WBcm;
    const double dn = d.norm();
    if (!(dn > 0.0)) {
      throw InputError(fmt::format("time stepping: the centres of balls '{}' and '{}' coincide "
                                   "at t = {} s; the normal of their contact is undefined",
                                   model_.body(i).name(), model_.body(j).name(), mid.t),
                       ErrorElement{ErrorElement::Kind::kBody, i});
    }
    ActivePoint a;
    a.point = first + k++;
    a.body = i;
    a.other = j;
    a.n = d / dn;
    const Mat3 T = FrameWithZAxis(a.n);
    a.t1 = T.col(0);
    a.t2 = T.col(1);
    a.r = -radius_[bi] * a.n;
    a.r_other = radius_[bj] * a.n;
    a.gap = dn - radius_[bi] - radius_[bj];
    const Vec3 d0 = s.bodies[bi].p_WBcm - s.bodies[bj].p_WBcm;
    a.turn = d0.norm() > 0.0 ? (a.n - d0.normalized()).norm() : 0.0;
    const Vec3 k3[3] = {a.n, a.t1, a.t2};
    for (int r = 0; r < 3; ++r) {
      a.A_body.row(r) << k3[r].transpose(), a.r.cross(k3[r]).transpose();
      a.A_other.row(r) << -k3[r].transpose(), -a.r_other.cross(k3[r]).transpose();
    }
    const Vec3 v_rel = (mid.bodies[bi].v_WBcm_W + data_.w_WB_W[bi].cross(a.r)) -
                       (mid.bodies[bj].v_WBcm_W + data_.w_WB_W[bj].cross(a.r_other));
    const double slip = (v_rel - a.n * a.n.dot(v_rel)).norm();
    a.mu = slip <= o_.tolerances.stick_speed ? o_.pair_law.mu_s : o_.pair_law.mu_k;
    a.restitution = o_.pair_law.restitution;
    active.push_back(std::move(a));
  }
}

// The last impulse per second of step of a point (the model's, or the step's pair point).
Eigen::Vector3d& Stepper::Warm(int point) {
  const auto p = static_cast<size_t>(point);
  return p < warm_.size() ? warm_[p] : step_pair_warm_[p - warm_.size()];
}

// This step's pair points start from the impulses their pairs had in the last step (zero for a
// pair that was not active); after the step, SolveIsland has left theirs in step_pair_warm_.
void Stepper::KeepPairWarmStarts(const std::vector<ActivePoint>& active) {
  std::vector<std::pair<std::pair<int, int>, Eigen::Vector3d>> kept;
  for (const ActivePoint& a : active) {
    if (static_cast<size_t>(a.point) < warm_.size()) continue;
    kept.push_back({{a.body, a.other}, Warm(a.point)});
  }
  pair_warm_ = std::move(kept);
}

// The points that touch couple only the bodies they hold: the islands of bodies linked by
// active points between two bodies each get their own contact problem.
void Stepper::SolveIslands(const std::vector<ActivePoint>& active, const std::vector<Vec6>& u_k,
                           double h, std::vector<Vec6>& u, std::vector<Eigen::Vector3d>& P,
                           StepOutcome& out) {
  BodySets sets(model_.num_bodies());
  for (const ActivePoint& a : active) {
    if (a.other != kWorld) sets.Link(a.body, a.other);
  }
  // Islands in the order of their first point, each point once: deterministic.
  std::vector<int> island_of_root(static_cast<size_t>(model_.num_bodies()), -1);
  std::vector<std::vector<int>> islands;
  for (size_t i = 0; i < active.size(); ++i) {
    int& island = island_of_root[static_cast<size_t>(sets.Find(active[i].body))];
    if (island < 0) {
      island = static_cast<int>(islands.size());
      islands.emplace_back();
    }
    islands[static_cast<size_t>(island)].push_back(static_cast<int>(i));
  }
  out.cert.islands += static_cast<int>(islands.size());
  for (const std::vector<int>& members : islands) {
    out.cert.largest_island = std::max(out.cert.largest_island, static_cast<int>(members.size()));
  }
  // The islands share no body and no point, so each writes only its own entries of u, P, the
  // warm start and the regimes; their certificates are merged in island order afterwards, and
  // the step is bitwise the same for any number of threads.
  std::vector<ContactProblemSolution> solved(islands.size());
  std::vector<std::vector<Impact>> impacts(islands.size());
  std::vector<std::exception_ptr> failed(islands.size());
  std::atomic<size_t> next{0};
  const auto work = [&] {
    for (size_t k; (k = next.fetch_add(1)) < islands.size();) {
      try {
        solved[k] = SolveIsland(active, islands[k], u_k, h, u, P, out.regime, impacts[k]);
      } catch (...) {
        failed[k] = std::current_exception();
      }
    }
  };
  const int threads = std::min<int>(o_.threads, static_cast<int>(islands.size()));
  if (threads > 1) {
    RunOnThreads(threads, work);
  } else {
    work();
  }
  TimeSteppingStep& c = out.cert;
  for (size_t k = 0; k < islands.size(); ++k) {
    if (failed[k]) std::rethrow_exception(failed[k]);
    const ContactProblemSolution& sol = solved[k];
    c.residual_impulse = std::max(c.residual_impulse, sol.residual_impulse);
    c.residual_velocity = std::max(c.residual_velocity, sol.residual_velocity);
    c.impulse_scale = std::max(c.impulse_scale, sol.scale);
    c.newton_iterations += sol.newton_iterations;
    c.sweeps += sol.sweeps;
    c.converged = c.converged && sol.converged;
    for (const Impact& imp : impacts[k]) {
      out.is_impact[static_cast<size_t>(imp.point)] = 1;
      out.impacts.push_back(imp);
    }
  }
}

ContactProblemSolution Stepper::SolveIsland(const std::vector<ActivePoint>& active,
                                            const std::vector<int>& members,
                                            const std::vector<Vec6>& u_k, double h,
                                            std::vector<Vec6>& u, std::vector<Eigen::Vector3d>& P,
                                            std::vector<ContactRegime>& regime,
                                            std::vector<Impact>& impacts) {
  const int m = static_cast<int>(members.size());
  // Each body's points in the island, with M⁻¹ Aᵀ of each: W_ij = Σ_b A_i^b M_b⁻¹ A_j^bᵀ.
  struct Entry {
    int local;
    const Eigen::Matrix<double, 3, 6>* A;
    Mat63 G;
  };
  std::vector<std::pair<BodyIndex, Entry>> by_body;
  FrictionalContactProblem problem;
  problem.q.resize(3 * m);
  problem.mu.resize(static_cast<size_t>(m));
  Eigen::VectorXd warm(3 * m), shift(m);
  std::vector<Eigen::Vector3d> U_start(static_cast<size_t>(m));
  for (int j = 0; j < m; ++j) {
    const ActivePoint& a = active[static_cast<size_t>(members[static_cast<size_t>(j)])];
    Eigen::Vector3d q = a.A_body * u[static_cast<size_t>(a.body)];
    Eigen::Vector3d U_k = a.A_body * u_k[static_cast<size_t>(a.body)];
    by_body.push_back({a.body, Entry{j, &a.A_body, MinvAt(a.body, a.A_body)}});
    if (a.other != kWorld) {
      q += a.A_other * u[static_cast<size_t>(a.other)];
      U_k += a.A_other * u_k[static_cast<size_t>(a.other)];
      by_body.push_back({a.other, Entry{j, &a.A_other, MinvAt(a.other, a.A_other)}});
    }
    // Newton's law at every point at once: U_n + e min(U_n,k, 0) >= 0.
    U_start[static_cast<size_t>(j)] = U_k;
    shift[j] = a.restitution * std::min(U_k[0], 0.0);
    q[0] += shift[j];
    problem.q.segment<3>(3 * j) = q;
    problem.mu[static_cast<size_t>(j)] = a.mu;
    warm.segment<3>(3 * j) = h * Warm(a.point);
  }
  std::stable_sort(by_body.begin(), by_body.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<Eigen::Triplet<double>> t;
  for (size_t lo = 0, hi; lo < by_body.size(); lo = hi) {
    for (hi = lo; hi < by_body.size() && by_body[hi].first == by_body[lo].first; ++hi) {
    }
    for (size_t x = lo; x < hi; ++x) {
      for (size_t y = lo; y < hi; ++y) {
        const Eigen::Matrix3d B = *by_body[x].second.A * by_body[y].second.G;
        for (int r = 0; r < 3; ++r) {
          for (int c = 0; c < 3; ++c) {
            t.emplace_back(3 * by_body[x].second.local + r, 3 * by_body[y].second.local + c,
                           B(r, c));
          }
        }
      }
    }
  }
  problem.W.resize(3 * m, 3 * m);
  problem.W.setFromTriplets(t.begin(), t.end());
  ContactProblemSolution sol = SolveFrictionalContact(problem, warm, o_.solver);
  for (const auto& [b, e] : by_body) {
    u[static_cast<size_t>(b)] += e.G * sol.P.segment<3>(3 * e.local);
  }
  for (int j = 0; j < m; ++j) {
    const ActivePoint& a = active[static_cast<size_t>(members[static_cast<size_t>(j)])];
    const Eigen::Vector3d& U_k = U_start[static_cast<size_t>(j)];
    if (U_k[0] < -o_.tolerances.resting_speed) {
      impacts.push_back(
          MakeImpact(a, U_k, sol.P.segment<3>(3 * j), problem.W.coeff(3 * j, 3 * j), h));
    }
    P[static_cast<size_t>(members[static_cast<size_t>(j)])] = sol.P.segment<3>(3 * j);
    Warm(a.point) = sol.P.segment<3>(3 * j) / h;
    // The regime by the velocities after the step (the impulses of redundant points, and so
    // the solver's regimes, are not unique): apart if separating, else sliding or sticking.
    const double U_n = sol.U[3 * j] - shift[j];
    const double slip = sol.U.segment<2>(3 * j + 1).norm();
    regime[static_cast<size_t>(a.point)] = U_n > o_.tolerances.resting_speed ? ContactRegime::kOpen
                                           : slip > o_.tolerances.stick_speed
                                               ? ContactRegime::kSliding
                                               : ContactRegime::kSticking;
  }
  return sol;
}

// An impact at `a`: approaching at U_k (its frame) at the step's start, met with impulse P;
// W_nn the normal row's diagonal of the contact problem (1 / the effective mass).
Impact Stepper::MakeImpact(const ActivePoint& a, const Eigen::Vector3d& U_k,
                           const Eigen::Vector3d& P, double W_nn, double h) const {
  Impact imp;
  imp.point = a.point;
  imp.body = a.body;
  imp.other = a.other;
  imp.tau = std::min(h, std::max(0.0, -a.gap) / -U_k[0]);
  imp.turn = a.turn * imp.tau / (0.5 * h);
  const double m_eff = 1.0 / W_nn;
  imp.impulse = P.norm();
  imp.impulse_rate = (1.0 + a.restitution) * (1.0 + a.mu) * m_eff * U_k.tail<2>().norm();
  imp.pass_body = (1.0 + a.restitution) * m_eff / model_.body(a.body).mass();
  if (a.other != kWorld) {
    imp.reach = a.r.norm() + a.r_other.norm();
    imp.pass_other = (1.0 + a.restitution) * m_eff / model_.body(a.other).mass();
  }
  return imp;
}

// Per body, the linear impulse of the forces and of the points that are not impacts, over
// the body's mass: what an impact's uncertain instant can shift between its sides [m/s].
void Stepper::OtherImpulses(const std::vector<ActivePoint>& active,
                            const std::vector<Eigen::Vector3d>& P, double h,
                            StepOutcome& out) const {
  std::vector<Vec3> J(data_.F_Bcm_W.size());
  for (size_t b = 0; b < J.size(); ++b) J[b] = h * data_.F_Bcm_W[b];
  for (size_t i = 0; i < active.size(); ++i) {
    const ActivePoint& a = active[i];
    if (out.is_impact[static_cast<size_t>(a.point)]) continue;
    const Vec3 P_W = a.n * P[i][0] + a.t1 * P[i][1] + a.t2 * P[i][2];
    J[static_cast<size_t>(a.body)] += P_W;
    if (a.other != kWorld) J[static_cast<size_t>(a.other)] -= P_W;
  }
  out.other_dv.resize(J.size());
  for (size_t b = 0; b < J.size(); ++b) {
    out.other_dv[b] = J[b].norm() / model_.body(static_cast<BodyIndex>(b)).mass();
  }
}

// Positions from the step's mean velocity; the angular velocity back into B at q_k+1.
void Stepper::Advance(const State& s, const std::vector<Vec6>& u_k, const std::vector<Vec6>& u,
                      double h, State& next) const {
  for (size_t i = 0; i < s.bodies.size(); ++i) {
    const BodyState& bs = s.bodies[i];
    BodyState& nb = next.bodies[i];
    const Vec6 mean = 0.5 * (u_k[i] + u[i]);
    nb.p_WBcm = bs.p_WBcm + h * mean.head<3>();
    const Vec3 w_mean_W = mean.tail<3>();
    nb.q_WB = (QuatExp(h * w_mean_W) * bs.q_WB).normalized();
    nb.v_WBcm_W = u[i].head<3>();
    nb.w_WB_B = nb.q_WB.toRotationMatrix().transpose() * u[i].tail<3>();
    if (!nb.v_WBcm_W.allFinite() || !nb.w_WB_B.allFinite()) {
      throw InputError(fmt::format("time stepping: the velocity of body '{}' became non-finite "
                                   "at t = {} s",
                                   model_.body(static_cast<BodyIndex>(i)).name(), next.t),
                       ErrorElement{ErrorElement::Kind::kBody, static_cast<int>(i)});
    }
  }
}

std::pair<Vec3, Vec3> Momenta(const Model& model, const State& s) {
  Vec3 p = Vec3::Zero(), H = Vec3::Zero();
  for (int b = 0; b < model.num_bodies(); ++b) {
    const BodyState& bs = s.bodies[static_cast<size_t>(b)];
    const Body& body = model.body(b);
    const Vec3 mv = body.mass() * bs.v_WBcm_W;
    p += mv;
    H += bs.p_WBcm.cross(mv) + bs.q_WB.toRotationMatrix() * (body.I_BBcm_B() * bs.w_WB_B);
  }
  return {p, H};
}

// The force elements' integrals over the step, at the midpoint configuration and the step's
// mean velocity (gravity's work is then exactly -ΔV); their impulses add to the balance.
void Stepper::BookForces(const State& mid, const std::vector<Vec6>& u_k, const std::vector<Vec6>& u,
                         double h, State& next, StepOutcome& out, Vec3& impulse, Vec3& moment) {
  State mean = mid;
  for (size_t i = 0; i < mean.bodies.size(); ++i) {
    const Vec6 m = 0.5 * (u_k[i] + u[i]);
    mean.bodies[i].v_WBcm_W = m.head<3>();
    mean.bodies[i].w_WB_B = R_m_[i].transpose() * m.tail<3>();
  }
  CalcKinematics(model_, mean, data_);
  CalcForces(model_, mean, data_);
  for (size_t e = 0; e < next.force_integrals.size(); ++e) {
    const ForceElementOutput& fo = data_.elements[e];
    ForceIntegrals& fi = next.force_integrals[e];
    fi.work += h * fo.power;
    fi.work_nonconservative += h * fo.power_nonconservative;
    fi.linear_impulse_W += h * fo.force_W;
    fi.angular_impulse_Wo_W += h * fo.moment_Wo_W;
    out.cert.work_nonconservative += h * fo.power_nonconservative;
    impulse += h * fo.force_W;
    moment += h * fo.moment_Wo_W;
  }
}

// Each impulse's work on the bodies, Pᵀ U at the step's mean velocity, normal part to the
// point's impact work and tangential part to its friction work; its impulse and moment about
// Wo (at the points of application at q_m) to the balance.
void Stepper::BookContacts(const State& mid, const std::vector<ActivePoint>& active,
                           const std::vector<Eigen::Vector3d>& P, const std::vector<Vec6>& u_k,
                           const std::vector<Vec6>& u, State& next, StepOutcome& out, Vec3& impulse,
                           Vec3& moment) const {
  for (size_t i = 0; i < active.size(); ++i) {
    const ActivePoint& a = active[i];
    const auto b = static_cast<size_t>(a.body);
    Eigen::Vector3d U = a.A_body * (0.5 * (u_k[b] + u[b]));
    const Vec3 P_W = a.n * P[i][0] + a.t1 * P[i][1] + a.t2 * P[i][2];
    const Vec3 at_body = mid.bodies[b].p_WBcm + a.r;
    impulse += P_W;
    moment += at_body.cross(P_W);
    if (a.other != kWorld) {
      const auto o = static_cast<size_t>(a.other);
      U += a.A_other * (0.5 * (u_k[o] + u[o]));
      impulse -= P_W;
      moment -= (mid.bodies[o].p_WBcm + a.r_other).cross(P_W);
    }
    const double w_n = P[i][0] * U[0];
    const double w_t = P[i].tail<2>().dot(U.tail<2>());
    if (static_cast<size_t>(a.point) < next.contacts.size()) {
      ContactPointState& cs = next.contacts[static_cast<size_t>(a.point)];
      cs.impact_work += w_n;
      cs.friction_work += w_t;
    } else {
      next.unlisted_contact_work.impact_work += w_n;
      next.unlisted_contact_work.friction_work += w_t;
    }
    out.cert.work_normal += w_n;
    out.cert.work_friction += w_t;
  }
}

Geometry Stepper::Measure(const State& s) {
  CalcKinematics(model_, s, data_);
  const auto n = static_cast<size_t>(model_.num_contact_points());
  Geometry g{std::vector<double>(n), std::vector<Vec3>(n), {}};
  for (size_t p = 0; p < n; ++p) {
    const ContactFrame f = CalcContactFrame(model_, s, data_, static_cast<int>(p));
    g.gaps[p] = f.gap;
    g.normals[p] = f.n;
  }
  return g;
}

ContactMode ModeOf(ContactRegime r) {
  switch (r) {
    case ContactRegime::kOpen:
      return ContactMode::kSeparated;
    case ContactRegime::kSticking:
      return ContactMode::kSticking;
    case ContactRegime::kSliding:
      return ContactMode::kSliding;
  }
  return ContactMode::kSeparated;
}

void Stepper::Certify(const State& s, const State& next, const Vec3& impulse, const Vec3& moment,
                      const std::vector<double>& gaps, double energy, StepOutcome& out) {
  TimeSteppingStep& c = out.cert;
  c.t = next.t;
  const auto [p0, H0] = Momenta(model_, s);
  const auto [p1, H1] = Momenta(model_, next);
  c.momentum_residual = (p1 - p0 - impulse).norm();
  c.angular_momentum_residual = (H1 - H0 - moment).norm();
  out.energy = CalcEnergy(model_, next);
  c.energy_change = out.energy - energy;
  c.numerical_energy_error =
      c.energy_change - c.work_nonconservative - c.work_normal - c.work_friction;
  out.end = Measure(next);
  const std::vector<double>& end = out.end.gaps;
  for (size_t p = 0; p < end.size(); ++p) {
    c.max_penetration = std::max(c.max_penetration, -end[p]);
    const bool closed = out.regime[p] != ContactRegime::kOpen;
    const bool was_closed = s.contacts[p].mode != ContactMode::kSeparated;
    if (closed && was_closed) {
      c.gap_drift = std::max(c.gap_drift, std::abs(end[p] - gaps[p]));
    }
    if (ModeOf(out.regime[p]) != s.contacts[p].mode) ++c.regime_changes;
  }
}

StepOutcome Stepper::Step(State& s, double h, const Geometry& start, double energy) {
  const auto n = static_cast<size_t>(model_.num_bodies());
  StepOutcome out;
  State mid = s;
  Midpoint(s, h, mid);
  CalcKinematics(model_, mid, data_);
  CalcForces(model_, mid, data_);
  std::vector<Vec6> u_k(n), u(n);
  FreeVelocities(s, h, u_k, u);
  FindActive(s, mid, start, active_);
  const std::vector<ActivePoint>& active = active_;
  // The model's points, then this step's pairs of balls (their points follow the model's), each
  // pair starting from its impulse of the last step.
  std::vector<char> is_active(warm_.size(), 0);
  step_pair_warm_.clear();
  for (const ActivePoint& a : active) {
    if (static_cast<size_t>(a.point) < warm_.size()) {
      is_active[static_cast<size_t>(a.point)] = 1;
      continue;
    }
    const auto it = std::lower_bound(
        pair_warm_.begin(), pair_warm_.end(), std::make_pair(a.body, a.other),
        [](const auto& entry, const std::pair<int, int>& key) { return entry.first < key; });
    const bool had = it != pair_warm_.end() && it->first == std::make_pair(a.body, a.other);
    step_pair_warm_.push_back(had ? it->second : Eigen::Vector3d::Zero());
  }
  for (size_t p = 0; p < warm_.size(); ++p) {
    if (!is_active[p]) warm_[p].setZero();
  }
  out.regime.assign(warm_.size() + step_pair_warm_.size(), ContactRegime::kOpen);
  out.is_impact.assign(out.regime.size(), 0);
  out.cert.active_points = static_cast<int>(active.size());
  std::vector<Eigen::Vector3d> P(active.size(), Eigen::Vector3d::Zero());
  SolveIslands(active, u_k, h, u, P, out);
  if (o_.collide_all_pairs) KeepPairWarmStarts(active);
  OtherImpulses(active, P, h, out);
  State next = s;
  next.t = s.t + h;
  Advance(s, u_k, u, h, next);
  Vec3 impulse = Vec3::Zero(), moment = Vec3::Zero();
  BookForces(mid, u_k, u, h, next, out, impulse, moment);
  BookContacts(mid, active, P, u_k, u, next, out, impulse, moment);
  for (size_t p = 0; p < next.contacts.size(); ++p) {
    ContactPointState& cs = next.contacts[p];
    cs.mode = ModeOf(out.regime[p]);
  }
  Certify(s, next, impulse, moment, start.gaps, energy, out);
  if (o_.collide_all_pairs) CertifyPairs(next, active, start, out);
  s = std::move(next);
  return out;
}

// The pairs of balls in the step's certificate: the deepest penetration at its end (the
// broadphase finds every pair that overlaps, active in the step or not), the gap drift of the
// pairs held closed at both ends, the regime changes (a pair closed at the start and not active
// now opened), and the pairs held closed at the end for the next step (out.end.pairs).
void Stepper::CertifyPairs(const State& next, const std::vector<ActivePoint>& active,
                           const Geometry& start, StepOutcome& out) const {
  TimeSteppingStep& c = out.cert;
  const auto gap_at = [&](int i, int j) {
    const auto bi = static_cast<size_t>(i), bj = static_cast<size_t>(j);
    return (next.bodies[bi].p_WBcm - next.bodies[bj].p_WBcm).norm() - radius_[bi] - radius_[bj];
  };
  for (const auto& [i, j] : NearPairs(next, 0.0)) {
    c.max_penetration = std::max(c.max_penetration, -gap_at(i, j));
  }
  const auto find = [&](const std::pair<int, int>& key) -> const ClosedPair* {
    const auto it = std::lower_bound(
        start.pairs.begin(), start.pairs.end(), key,
        [](const ClosedPair& p, const std::pair<int, int>& k) { return p.bodies < k; });
    return it != start.pairs.end() && it->bodies == key ? &*it : nullptr;
  };
  size_t still_active = 0;
  for (const ActivePoint& a : active) {
    if (static_cast<size_t>(a.point) < warm_.size()) continue;
    const std::pair<int, int> key{a.body, a.other};
    const ClosedPair* before = find(key);
    if (before != nullptr) ++still_active;
    const ContactMode mode = ModeOf(out.regime[static_cast<size_t>(a.point)]);
    if (mode != (before != nullptr ? before->mode : ContactMode::kSeparated)) ++c.regime_changes;
    if (mode == ContactMode::kSeparated) continue;
    const double gap = gap_at(a.body, a.other);
    if (before != nullptr) c.gap_drift = std::max(c.gap_drift, std::abs(gap - before->gap));
    out.end.pairs.push_back({key, mode, gap});
  }
  // Closed at the start and not touching at the midpoint: apart now.
  c.regime_changes += static_cast<int>(start.pairs.size() - still_active);
}

// Two outcomes of consecutive half steps as one step's certificate.
TimeSteppingStep Combine(const TimeSteppingStep& a, const TimeSteppingStep& b) {
  TimeSteppingStep c = b;
  c.active_points = std::max(a.active_points, b.active_points);
  c.islands = std::max(a.islands, b.islands);
  c.largest_island = std::max(a.largest_island, b.largest_island);
  c.residual_impulse = std::max(a.residual_impulse, b.residual_impulse);
  c.residual_velocity = std::max(a.residual_velocity, b.residual_velocity);
  c.impulse_scale = std::max(a.impulse_scale, b.impulse_scale);
  c.newton_iterations += a.newton_iterations;
  c.sweeps += a.sweeps;
  c.momentum_residual = std::max(a.momentum_residual, b.momentum_residual);
  c.angular_momentum_residual = std::max(a.angular_momentum_residual, b.angular_momentum_residual);
  c.energy_change += a.energy_change;
  c.work_nonconservative += a.work_nonconservative;
  c.work_normal += a.work_normal;
  c.work_friction += a.work_friction;
  c.numerical_energy_error += a.numerical_energy_error;
  c.max_penetration = std::max(a.max_penetration, b.max_penetration);
  c.gap_drift = std::max(a.gap_drift, b.gap_drift);
  c.regime_changes += a.regime_changes;
  c.converged = a.converged && b.converged;
  return c;
}

// The largest |(I - c n nᵀ) a + c n nᵀ b| over vectors |a| <= x, |b| <= y and unit n: how an
// impact (v_a' = v_a - c n nᵀ (v_a - v_b)) passes errors x and y of its bodies on to the first.
// With s = |n·a|: x² - s² + (|1 - c| s + c y)², largest at s = |1 - c| c y / (1 - (1 - c)²)
// (within [0, x]) where |1 - c| < 1, else at s = x.
double PassThrough(double x, double y, double c) {
  const double k = std::abs(1.0 - c);
  if (k >= 1.0) return k * x + c * y;
  const double s = std::min(x, k * c * y / (1.0 - k * k));
  return std::sqrt(x * x - s * s + (k * s + c * y) * (k * s + c * y));
}

// One step's certificate as a summary of one step (the energies at the ends left out).
TimeSteppingSummary StepSummary(const TimeSteppingStep& c) {
  TimeSteppingSummary m;
  m.steps = 1;
  m.max_residual_impulse = c.residual_impulse;
  m.max_residual_velocity = c.residual_velocity;
  m.max_momentum_residual = c.momentum_residual;
  m.max_angular_momentum_residual = c.angular_momentum_residual;
  m.max_penetration = c.max_penetration;
  m.max_gap_drift = c.gap_drift;
  m.max_velocity_error = c.velocity_error;
  m.max_angular_velocity_error = c.angular_velocity_error;
  m.accumulated_velocity_error = c.accumulated_velocity_error;
  m.work_nonconservative = c.work_nonconservative;
  m.work_normal = c.work_normal;
  m.work_friction = c.work_friction;
  m.numerical_energy_error = c.numerical_energy_error;
  m.regime_changes = c.regime_changes;
  m.newton_iterations = c.newton_iterations;
  m.sweeps = c.sweeps;
  m.largest_island = c.largest_island;
  return m;
}

class Run {
 public:
  Run(const Model& model, const State& initial, const TimeSteppingOptions& o)
      : model_(model),
        o_(o),
        stepper_(model, o),
        s_(initial),
        error_v_(static_cast<size_t>(model.num_bodies()), 0.0),
        error_x_(static_cast<size_t>(model.num_bodies()), 0.0) {
    if (s_.contacts.empty()) s_.contacts.resize(static_cast<size_t>(model.num_contact_points()));
    s_.force_integrals.resize(static_cast<size_t>(model.num_force_elements()));
    start_ = stepper_.Measure(s_);
    energy_ = CalcEnergy(model, s_);
    result_.summary.initial_energy = energy_;
    result_.regime_changes.assign(s_.contacts.size(), 0);
    result_.last_regime_change = std::isnan(o.quiet_from) ? initial.t : o.quiet_from;
  }

  TimeSteppingResult Go();

 private:
  /// Ends the run at the current state (the end time, or a quiet step).
  TimeSteppingResult Finish();
  void TakeStep(double h);
  void Propagate(const StepOutcome& out, double h);
  void Record(const TimeSteppingStep& c, const std::vector<ContactMode>& before);
  void Sample();

  const Model& model_;
  const TimeSteppingOptions& o_;
  Stepper stepper_;
  State s_;
  Geometry start_;
  double energy_ = 0.0;
  /// The accumulated error estimate per body: of the velocity [m/s] and the position [m].
  std::vector<double> error_v_, error_x_;
  TimeSteppingResult result_;
};

void Run::Sample() {
  result_.sample_energy_error.push_back(result_.summary.numerical_energy_error);
  if (o_.on_sample) o_.on_sample(s_);
  if (o_.store_samples) result_.samples.push_back(s_);
}

// One step of h: two half steps taken, one full step from the same state as their estimate.
void Run::TakeStep(double h) {
  std::vector<ContactMode> before(s_.contacts.size());
  for (size_t p = 0; p < before.size(); ++p) before[p] = s_.contacts[p].mode;
  if (!o_.error_estimate) {
    const StepOutcome out = stepper_.Step(s_, h, start_, energy_);
    start_ = out.end;
    energy_ = out.energy;
    ++result_.stats.function_evaluations;
    Record(out.cert, before);
    return;
  }
  State full = s_;
  const StepOutcome f = stepper_.Step(full, h, start_, energy_);
  const StepOutcome a = stepper_.Step(s_, 0.5 * h, start_, energy_);
  const StepOutcome b = stepper_.Step(s_, 0.5 * h, a.end, a.energy);
  start_ = b.end;
  energy_ = b.energy;
  result_.stats.function_evaluations += 3;
  TimeSteppingStep c = Combine(a.cert, b.cert);
  std::vector<double> local(s_.bodies.size());
  for (size_t i = 0; i < s_.bodies.size(); ++i) {
    const BodyState& x = s_.bodies[i];
    const BodyState& y = full.bodies[i];
    local[i] = (x.v_WBcm_W - y.v_WBcm_W).norm();
    c.velocity_error = std::max(c.velocity_error, local[i]);
    const Vec3 wx = x.q_WB.toRotationMatrix() * x.w_WB_B;
    const Vec3 wy = y.q_WB.toRotationMatrix() * y.w_WB_B;
    c.angular_velocity_error = std::max(c.angular_velocity_error, (wx - wy).norm());
  }
  Propagate(a, 0.5 * h);
  Propagate(b, 0.5 * h);
  // Step doubling measures the smooth part of the error; where any of the three steps met an
  // impact, the difference is the timing of the impact (up to its whole velocity jump), which
  // Propagate has estimated instead.
  const bool smooth = f.impacts.empty() && a.impacts.empty() && b.impacts.empty();
  for (size_t i = 0; i < local.size(); ++i) {
    if (smooth) error_v_[i] += local[i];
    c.accumulated_velocity_error = std::max(c.accumulated_velocity_error, error_v_[i]);
  }
  Record(c, before);
}

// The accumulated error estimate through one step taken (docs/contact.md, "The accumulated
// error estimate"). Each body carries estimates of its velocity error δv and position error δx,
// first order in h. Between impacts δx grows by h δv. An impact is met at the step's midpoint,
// tau after the point touched: the normal used is off by its turn over tau plus what the
// position errors turn it, (δx_a + δx_b) / (|r_a| + |r_b|); a turn dn changes the impulse P n
// by |dn| hypot(|P|, (1 + e) m_eff |U_t|), each body's velocity by that over its mass. The
// bodies' errors pass through the impact, v_a' = v_a - c_a n nᵀ (v_a - v_b) with
// c_a = (1 + e) m_eff / m_a (PassThrough), the position errors alike (an error along n shifts
// the impact's instant: the same reflection); the jump applied tau late moves each body by
// |ΔV| tau; the forces and other points' impulses of the step, split between the impact's two
// sides at an instant known to within the step, add their whole Δv; and impacts that share a
// body within one step, resolved at once where the exact motion may order them, add their
// whole impulses (not small in h, but charged only where impacts fall within one step).
void Run::Propagate(const StepOutcome& out, double h) {
  for (size_t i = 0; i < error_v_.size(); ++i) error_x_[i] += h * error_v_[i];
  std::vector<int> hits(error_v_.size(), 0);
  for (const Impact& imp : out.impacts) {
    ++hits[static_cast<size_t>(imp.body)];
    if (imp.other != kWorld) ++hits[static_cast<size_t>(imp.other)];
  }
  for (const Impact& imp : out.impacts) {
    const auto i = static_cast<size_t>(imp.body);
    const bool pair = imp.other != kWorld;
    const size_t j = pair ? static_cast<size_t>(imp.other) : i;
    const double v_i = error_v_[i], v_j = pair ? error_v_[j] : 0.0;
    const double x_i = error_x_[i], x_j = pair ? error_x_[j] : 0.0;
    const double turn = imp.turn + (pair ? (x_i + x_j) / imp.reach : 0.0);
    // Impacts sharing a body in one step are resolved at once (Moreau's law), where the exact
    // motion may take them one after the other: their whole impulses are in doubt.
    const bool order = hits[i] > 1 || hits[j] > 1;
    // The turn dn changes P n by P_n dn across n and (1 + e) m_eff (U_t·dn) along it.
    const double dP =
        std::hypot(imp.impulse, imp.impulse_rate) * turn + (order ? imp.impulse : 0.0);
    const double m_i = model_.body(imp.body).mass();
    error_v_[i] = PassThrough(v_i, v_j, imp.pass_body) + dP / m_i;
    error_x_[i] = PassThrough(x_i, x_j, imp.pass_body) + imp.impulse / m_i * imp.tau;
    if (pair) {
      const double m_j = model_.body(imp.other).mass();
      error_v_[j] = PassThrough(v_j, v_i, imp.pass_other) + dP / m_j;
      error_x_[j] = PassThrough(x_j, x_i, imp.pass_other) + imp.impulse / m_j * imp.tau;
    }
  }
  for (size_t i = 0; i < hits.size(); ++i) {
    if (hits[i] > 0) error_v_[i] += out.other_dv[i];
  }
}

void Run::Record(const TimeSteppingStep& c0, const std::vector<ContactMode>& before) {
  TimeSteppingStep c = c0;
  c.within_tolerance = c.converged && c.accumulated_velocity_error <= o_.velocity_tolerance;
  TimeSteppingSummary& m = result_.summary;
  const double accumulated = c.accumulated_velocity_error;
  MergeSteppingSummary(m, StepSummary(c));
  m.accumulated_velocity_error = accumulated;
  ++result_.stats.steps;
  for (size_t p = 0; p < before.size(); ++p) {
    if (s_.contacts[p].mode != before[p]) ++result_.regime_changes[p];
  }
  if (!c.within_tolerance && result_.tolerance_met) {
    result_.tolerance_met = false;
    result_.warnings.push_back(
        c.converged
            ? fmt::format("time stepping: the accumulated velocity error is estimated at "
                          "{:.3g} m/s at t = {:.9g} s, above the requested {:.3g} m/s; take a "
                          "smaller step",
                          accumulated, c.t, o_.velocity_tolerance)
            : fmt::format("time stepping: the contact problem of the step ending at t = {:.9g} s "
                          "reached a residual of {:.3g} N·s ({:.3g} m/s), above its tolerance "
                          "{:.3g} of the impulse scale {:.3g} N·s",
                          c.t, c.residual_impulse, c.residual_velocity, o_.solver.tolerance,
                          c.impulse_scale));
  }
  if (o_.store_steps) result_.steps.push_back(c);
  if (o_.on_step) o_.on_step(c.t);
}

TimeSteppingResult Run::Go() {
  const double t0 = s_.t;
  Sample();
  // Stretches between output times, each divided into equal steps no longer than `step`.
  const double interval = o_.output_interval > 0 ? o_.output_interval : o_.t_end - t0;
  for (long k = 0;; ++k) {
    const double a = t0 + static_cast<double>(k) * interval;
    if (a >= o_.t_end) break;
    const double b = std::min(o_.t_end, t0 + static_cast<double>(k + 1) * interval);
    const auto n = static_cast<long>(std::ceil((b - a) / o_.step * (1.0 - 1e-12)));
    const double h = (b - a) / static_cast<double>(std::max(n, 1L));
    for (long j = 0; j < std::max(n, 1L); ++j) {
      const long changes = result_.summary.regime_changes;
      TakeStep(h);
      s_.t = j + 1 == std::max(n, 1L) ? b : a + static_cast<double>(j + 1) * h;
      if (result_.summary.regime_changes != changes) result_.last_regime_change = s_.t;
      if (s_.t - result_.last_regime_change >= o_.quiet_span && s_.t < o_.t_end) {
        result_.quiet = true;
        return Finish();
      }
    }
    if (b < o_.t_end) Sample();
  }
  Sample();
  return Finish();
}

TimeSteppingResult Run::Finish() {
  result_.summary.final_energy = energy_;
  result_.final_state = s_;
  return std::move(result_);
}

}  // namespace

void MergeSteppingSummary(TimeSteppingSummary& into, const TimeSteppingSummary& add) {
  into.steps += add.steps;
  into.max_residual_impulse = std::max(into.max_residual_impulse, add.max_residual_impulse);
  into.max_residual_velocity = std::max(into.max_residual_velocity, add.max_residual_velocity);
  into.max_momentum_residual = std::max(into.max_momentum_residual, add.max_momentum_residual);
  into.max_angular_momentum_residual =
      std::max(into.max_angular_momentum_residual, add.max_angular_momentum_residual);
  into.max_penetration = std::max(into.max_penetration, add.max_penetration);
  into.max_gap_drift = std::max(into.max_gap_drift, add.max_gap_drift);
  into.max_velocity_error = std::max(into.max_velocity_error, add.max_velocity_error);
  into.max_angular_velocity_error =
      std::max(into.max_angular_velocity_error, add.max_angular_velocity_error);
  into.accumulated_velocity_error += add.accumulated_velocity_error;
  into.work_nonconservative += add.work_nonconservative;
  into.work_normal += add.work_normal;
  into.work_friction += add.work_friction;
  into.numerical_energy_error += add.numerical_energy_error;
  into.regime_changes += add.regime_changes;
  into.newton_iterations += add.newton_iterations;
  into.sweeps += add.sweeps;
  into.largest_island = std::max(into.largest_island, add.largest_island);
}

ModelObstacle TimeSteppingObstacle(const Model& model) {
  if (model.num_constraints() > 0) {
    return {fmt::format("constraint '{}': time stepping takes free bodies with contacts only",
                        model.constraint(0).name()),
            ErrorElement{ErrorElement::Kind::kConstraint, 0}};
  }
  for (int c = 0; c < model.num_contacts(); ++c) {
    if (model.contact(c).mu_r() > 0) {
      return {fmt::format("contact '{}': time stepping does not model rolling resistance (mu_r)",
                          model.contact(c).name()),
              ErrorElement{ErrorElement::Kind::kContact, c}};
    }
  }
  return {};
}

std::vector<std::string> TimeSteppingLawWarnings(const Model& model) {
  std::vector<std::string> out;
  for (int c = 0; c < model.num_contacts(); ++c) {
    const Contact& con = model.contact(c);
    if (con.restitution() > 0 && con.restitution_law() != RestitutionLaw::kNewton) {
      out.push_back(fmt::format(
          "contact '{}': time stepping applies Newton's law at all touching points at once; "
          "its restitution_law '{}' is not used (the laws agree for a frictionless collision "
          "of two bodies)",
          con.name(), RestitutionLawName(con.restitution_law())));
    }
  }
  return out;
}

TimeSteppingResult SimulateTimeStepping(const Model& model, const State& initial,
                                        const TimeSteppingOptions& options) {
  if (const ModelObstacle why = TimeSteppingObstacle(model); !why.empty()) {
    throw InputError(why.why, why.element);
  }
  ValidateState(model, initial);
  if (!(options.t_end > initial.t) || !std::isfinite(options.t_end)) {
    throw InputError(
        fmt::format("time stepping: t_end = {} s must be finite and after the "
                    "initial time {} s",
                    options.t_end, initial.t));
  }
  if (!(options.step > 0) || !std::isfinite(options.step)) {
    throw InputError(
        fmt::format("time stepping: step = {} s must be positive and finite", options.step));
  }
  if (!(options.quiet_span > 0)) {
    throw InputError(
        fmt::format("time stepping: quiet_span = {} s must be positive (infinite: never end early)",
                    options.quiet_span));
  }
  if (!(options.output_interval >= 0) || !std::isfinite(options.output_interval)) {
    throw InputError(fmt::format("time stepping: output_interval = {} s must be >= 0 and finite",
                                 options.output_interval));
  }
  if (!(options.threads >= 1)) {
    throw InputError(fmt::format("time stepping: threads is {}; it must be >= 1", options.threads));
  }
  if (options.collide_all_pairs) {
    // The coefficients alone (the radii are checked below).
    internal::ValidateSphereCollisionLaw(options.pair_law, model, 1.0);
    if (!options.ball_radii.empty()) {
      if (options.ball_radii.size() != static_cast<size_t>(model.num_bodies())) {
        throw InputError(fmt::format("time stepping: ball_radii has {} entries for {} bodies",
                                     options.ball_radii.size(), model.num_bodies()));
      }
      for (double r : options.ball_radii) {
        if (!(r >= 0.0) || !std::isfinite(r)) {
          throw InputError(fmt::format(
              "time stepping: a ball radius is {} m; it must be >= 0 (0: not a ball) and finite",
              r));
        }
      }
    }
  }
  Run run(model, initial, options);
  return run.Go();
}

}  // namespace chasles
