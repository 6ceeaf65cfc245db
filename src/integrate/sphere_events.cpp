// Event-driven spheres on a level plane (docs/contact.md, "Event-driven spheres").
#include "chasles/integrate/sphere_events.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <queue>
#include <unordered_map>
#include <utility>

#include "chasles/dynamics/impact.h"
#include "chasles/error.h"
#include "chasles/math/quaternion.h"
#include "chasles/model/forces.h"

namespace chasles {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

enum class Phase { kFlight, kSliding, kRolling, kRest };

ContactMode ModeOfPhase(Phase p) {
  switch (p) {
    case Phase::kFlight:
      return ContactMode::kSeparated;
    case Phase::kSliding:
      return ContactMode::kSliding;
    default:
      return ContactMode::kSticking;
  }
}

// One ball's constants.
struct Ball {
  BodyIndex body = kWorld;
  int point = -1;  // its plane contact point
  double m = 0.0, R = 0.0, I = 0.0;
  double kappa = 0.0;  // m R² / I
  double mu_s = 0.0, mu_k = 0.0, mu_r = 0.0;
};

// A stretch of closed-form motion from t0 for dur (may be infinite):
//   r = r0 + v0 τ + ½ a τ²,  v = v0 + a τ,  ω = w0 + alpha τ  (τ = t - t0).
struct Segment {
  Phase phase = Phase::kRest;
  double t0 = 0.0, dur = kInf;
  Vec3 r0, v0, w0, a, alpha;
  Quat q0;
  Vec3 s_hat = Vec3::Zero();  // slip direction (sliding)
  double slip0 = 0.0;         // |u0| (sliding)
  double end() const { return t0 + dur; }
  Vec3 Pos(double t) const {
    const double tau = t - t0;
    return r0 + v0 * tau + 0.5 * tau * tau * a;
  }
  Vec3 Vel(double t) const { return v0 + (t - t0) * a; }
  Vec3 Omega(double t) const { return w0 + (t - t0) * alpha; }
};

// Orientation after τ of ω(s) = w0 + alpha s, q' = ½ ω q (ω in W). A fixed axis (alpha ∥ w0)
// is exact: the rotation vector is ∫ω. Otherwise fourth-order Magnus steps (Iserles and
// Nørsett 1999): over a step h from ω_k, Ω = h ω(h/2) + (h³/12) alpha × ω_k (the two terms are
// exact for a linear ω; the rest is about h⁵ |alpha||ω|(|ω| + |alpha| h) / 720), with h chosen
// so that each step's remainder is below 1e-12 rad. The orientation does not enter a ball's
// motion (isotropic inertia, sphere at the centre of mass); it is computed only for the output.
Quat Orient(const Vec3& w0, const Vec3& alpha, const Quat& q0, double tau) {
  if (tau <= 0.0) return q0;
  const Vec3 cross = alpha.cross(w0);
  if (cross.squaredNorm() <= 1e-30 * alpha.squaredNorm() * w0.squaredNorm()) {
    Quat q = QuatExp(w0 * tau + 0.5 * tau * tau * alpha) * q0;
    return q.normalized();
  }
  const double wa = w0.norm() + alpha.norm() * tau;
  const double bound = alpha.norm() * wa * wa;
  const double h_max = std::pow(720e-12 / bound, 0.2);
  const int n = std::max(1, static_cast<int>(std::ceil(tau / h_max)));
  const double h = tau / n;
  Quat q = q0;
  for (int k = 0; k < n; ++k) {
    const Vec3 wk = w0 + (k * h) * alpha;
    const Vec3 omega = h * (wk + 0.5 * h * alpha) + (h * h * h / 12.0) * alpha.cross(wk);
    q = QuatExp(omega) * q;
  }
  return q.normalized();
}

// The problem's shared data.
struct World {
  Vec3 n = Vec3::UnitZ();  // plane normal (towards the balls), -ĝ
  Vec3 p0 = Vec3::Zero();  // a point of the plane
  Vec3 g_W = Vec3::Zero();
  double g = 0.0;  // |g|
  Vec3 e1, e2;     // plane axes
  ContactTolerances tol;
};

// The segment a ball starts at time t with (r, v, ω, q). `on_plane`: touching the plane with
// no normal velocity (n·v is removed); then sliding when the slip exceeds stick_speed,
// rolling (ω's part along the plane set to n × v / R) otherwise, rest when v = 0.
Segment StartSegment(const Ball& b, const World& w, double t, const Vec3& r, const Vec3& v,
                     const Vec3& om, const Quat& q, bool on_plane, bool force_roll = false) {
  Segment s;
  s.t0 = t;
  s.r0 = r;
  s.q0 = q;
  s.a = Vec3::Zero();
  s.alpha = Vec3::Zero();
  if (!on_plane) {
    // Flight: h(τ) = h0 + v_n τ - ½ g τ² reaches 0 at the larger root.
    s.phase = Phase::kFlight;
    s.v0 = v;
    s.w0 = om;
    s.a = w.g_W;
    const double h0 = std::max(w.n.dot(r - w.p0) - b.R, 0.0);
    const double vn = w.n.dot(v);
    s.dur = (vn + std::sqrt(vn * vn + 2.0 * w.g * h0)) / w.g;
    return s;
  }
  const Vec3 vh = v - w.n.dot(v) * w.n;
  const double spin = w.n.dot(om);
  const Vec3 u = vh - b.R * om.cross(w.n);  // slip of the material point at C
  const double slip = u.norm();
  if (!force_roll && slip > w.tol.stick_speed && b.mu_k > 0.0) {
    // Sliding (8.3): u̇ = -mu_k g (1 + m R²/I) ŝ, so ŝ stays and |u| falls linearly.
    s.phase = Phase::kSliding;
    s.v0 = vh;
    s.w0 = om;
    s.s_hat = u / slip;
    s.slip0 = slip;
    s.a = -b.mu_k * w.g * s.s_hat;
    s.alpha = (b.mu_k * b.m * w.g * b.R / b.I) * w.n.cross(s.s_hat);
    s.dur = slip / (b.mu_k * w.g * (1.0 + b.kappa));
    return s;
  }
  if (!force_roll && slip > w.tol.stick_speed) {
    // Frictionless plane: slides for ever with constant v and ω.
    s.phase = Phase::kSliding;
    s.v0 = vh;
    s.w0 = om;
    s.s_hat = u / slip;
    s.slip0 = slip;
    s.dur = kInf;
    return s;
  }
  const double speed = vh.norm();
  s.v0 = vh;
  s.w0 = spin * w.n + w.n.cross(vh) / b.R;
  if (speed == 0.0) {
    s.phase = Phase::kRest;
    s.dur = kInf;
    return s;
  }
  s.phase = Phase::kRolling;
  if (b.mu_r > 0.0) {
    // Rolling resistance mu_r N R against the rolling: v̇ = -mu_r g v̂ / (1 + I/(m R²)).
    s.a = -(b.mu_r * w.g / (1.0 + 1.0 / b.kappa)) * (vh / speed);
    s.alpha = w.n.cross(s.a) / b.R;
    s.dur = speed / s.a.norm();
  }
  return s;
}

// The deterministic continuation of a contact segment at its end (sliding → rolling →
// rest). Flight has none: its end is an impact.
Segment NextSegment(const Ball& b, const World& w, const Segment& s) {
  const double t = s.end();
  const Quat q = Quat::Identity();  // only a chain's first segment carries q (ChainOrient)
  if (s.phase == Phase::kSliding) {
    return StartSegment(b, w, t, s.Pos(t), s.Vel(t), s.Omega(t), q, true, true);
  }
  // Rolling stopped: rest, spinning about n.
  Segment r;
  r.phase = Phase::kRest;
  r.t0 = t;
  r.r0 = s.Pos(t);
  r.v0 = Vec3::Zero();
  r.w0 = w.n.dot(s.w0) * w.n;
  r.a = r.alpha = Vec3::Zero();
  r.q0 = q;
  r.dur = kInf;
  return r;
}

// A ball's known future: up to three segments (sliding, rolling, rest); `known_until` is the
// end of what can be predicted (a landing, or infinity).
struct Chain {
  std::array<Segment, 3> seg;
  int count = 0;
  double known_until = kInf;
  const Segment& At(double t) const {
    for (int k = 0; k + 1 < count; ++k) {
      if (t < seg[static_cast<size_t>(k)].end()) return seg[static_cast<size_t>(k)];
    }
    return seg[static_cast<size_t>(count - 1)];
  }
};

// The orientation at t along a chain, from its first segment's q0.
Quat ChainOrient(const Chain& c, double t) {
  Quat q = c.seg[0].q0;
  for (int k = 0; k < c.count; ++k) {
    const Segment& s = c.seg[static_cast<size_t>(k)];
    const double te = std::min(t, s.end());
    if (te > s.t0) q = Orient(s.w0, s.alpha, q, te - s.t0);
    if (t <= s.end()) break;
  }
  return q;
}

Chain MakeChain(const Ball& b, const World& w, const Segment& first) {
  Chain c;
  c.seg[0] = first;
  c.count = 1;
  if (first.phase == Phase::kFlight) {
    c.known_until = first.end();
    return c;
  }
  while (c.count < 3 && std::isfinite(c.seg[static_cast<size_t>(c.count - 1)].dur)) {
    c.seg[static_cast<size_t>(c.count)] =
        NextSegment(b, w, c.seg[static_cast<size_t>(c.count - 1)]);
    ++c.count;
  }
  return c;
}

// ---- Roots of the contact polynomial -------------------------------------------------------
// p(σ) = Σ c_k σ^k, degree <= 4.
using Poly = std::array<double, 5>;

double Eval(const Poly& c, int deg, double x) {
  double y = c[static_cast<size_t>(deg)];
  for (int k = deg - 1; k >= 0; --k) y = y * x + c[static_cast<size_t>(k)];
  return y;
}

// Sorted real roots of p in (lo, hi): between consecutive roots of p' (recursively) p is
// monotone, and each sign change is bisected to adjacent doubles.
void RootsIn(const Poly& c, int deg, double lo, double hi, std::vector<double>& out) {
  out.clear();
  while (deg > 0 && c[static_cast<size_t>(deg)] == 0.0) --deg;
  if (deg == 0) return;
  std::vector<double> knots{lo};
  if (deg > 1) {
    Poly d{};
    for (int k = 1; k <= deg; ++k) d[static_cast<size_t>(k - 1)] = k * c[static_cast<size_t>(k)];
    std::vector<double> crit;
    RootsIn(d, deg - 1, lo, hi, crit);
    knots.insert(knots.end(), crit.begin(), crit.end());
  }
  knots.push_back(hi);
  for (size_t k = 0; k + 1 < knots.size(); ++k) {
    double a = knots[k], b = knots[k + 1];
    double fa = Eval(c, deg, a), fb = Eval(c, deg, b);
    if (fa == 0.0) {
      if (k > 0 || a > lo) out.push_back(a);
      continue;
    }
    if ((fa > 0.0) == (fb > 0.0) || fb == 0.0) continue;
    for (int it = 0; it < 200; ++it) {
      const double m = 0.5 * (a + b);
      if (m <= a || m >= b) break;
      const double fm = Eval(c, deg, m);
      if ((fm > 0.0) == (fa > 0.0) && fm != 0.0) {
        a = m;
      } else {
        b = m;
      }
    }
    out.push_back(b);
  }
}

// The first σ in [lo, hi] at which f = |d|² - S² enters f <= 0 (the balls touch, approaching):
// f(lo) <= 0 with f falling at lo, or a crossing from f > 0. Infinity if none.
double FirstEntry(const Poly& f, double lo, double hi) {
  Poly d{};
  for (int k = 1; k <= 4; ++k) d[static_cast<size_t>(k - 1)] = k * f[static_cast<size_t>(k)];
  std::vector<double> crit;
  RootsIn(d, 3, lo, hi, crit);
  double a = lo;
  double fa = Eval(f, 4, a);
  crit.push_back(hi);
  for (const double b : crit) {
    const double fb = Eval(f, 4, b);
    const bool falling = fb < fa || (fb == fa && Eval(d, 3, 0.5 * (a + b)) < 0.0);
    if (falling && fa <= 0.0 && b > a) return a;
    if (fa > 0.0 && fb <= 0.0) {
      double x = a, y = b;
      for (int it = 0; it < 200; ++it) {
        const double m = 0.5 * (x + y);
        if (m <= x || m >= y) break;
        if (Eval(f, 4, m) > 0.0) {
          x = m;
        } else {
          y = m;
        }
      }
      return y;
    }
    a = b;
    fa = fb;
  }
  return kInf;
}

// ---- Events --------------------------------------------------------------------------------
enum class Kind : int {
  kSample = 0,
  kPhase = 1,
  kHorizon = 2,
  kPair = 3,
  kLanding = 4,
  kGroup = 5
};

struct Event {
  double t = 0.0;
  Kind kind = Kind::kSample;
  int i = -1, j = -1;
  std::uint32_t ver_i = 0, ver_j = 0;
  std::uint64_t seq = 0;
};

struct Later {
  bool operator()(const Event& x, const Event& y) const {
    if (x.t != y.t) return x.t > y.t;
    if (x.kind != y.kind) return static_cast<int>(x.kind) > static_cast<int>(y.kind);
    return x.seq > y.seq;
  }
};

struct Box {
  double lo1 = 0.0, hi1 = 0.0, lo2 = 0.0, hi2 = 0.0;
  bool Overlaps(const Box& o) const {
    return lo1 <= o.hi1 && o.lo1 <= hi1 && lo2 <= o.hi2 && o.lo2 <= hi2;
  }
};

// Range of x0 + v τ + ½ a τ² over [ta, tb].
void Extend(double x0, double v, double a, double ta, double tb, double& lo, double& hi) {
  const auto at = [&](double t) { return x0 + v * t + 0.5 * a * t * t; };
  const double xa = at(ta), xb = at(tb);
  lo = std::min({lo, xa, xb});
  hi = std::max({hi, xa, xb});
  if (a != 0.0) {
    const double tv = -v / a;
    if (tv > ta && tv < tb) {
      lo = std::min(lo, at(tv));
      hi = std::max(hi, at(tv));
    }
  }
}

std::uint64_t PairKey(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

class Runner {
 public:
  Runner(const Model& model, const SphereEventOptions& options)
      : model_(model), options_(options) {}

  SphereEventResult Run(const State& initial);

 private:
  // Setup.
  void ReadModel();
  void Schedule(Event e) {
    e.seq = seq_++;
    queue_.push(e);
  }
  // The ball's (r, v, ω) at t from its chain.
  const Segment& SegAt(int i, double t) const { return chain_[static_cast<size_t>(i)].At(t); }
  // Broadphase.
  /// The grid column or row of a coordinate: floor(v / cell), clamped to ±2^30 so that it is
  /// an int for any finite coordinate (a ball 1e12 m out is 1e13 cells away). The cells at the
  /// clamp hold every ball beyond it: more pair tests there, never a pair missed, as the pair
  /// tests are exact and neighbouring cells are searched.
  int Cell(double v) const {
    constexpr double kMaxCell = 1 << 30;
    return static_cast<int>(std::clamp(std::floor(v / cell_), -kMaxCell, kMaxCell));
  }
  std::int64_t CellKey(int x, int y) const {
    return (static_cast<std::int64_t>(x) << 32) ^ static_cast<std::uint32_t>(y);
  }
  void RenewBox(int i, double t);
  void TestPair(int i, int j, double t);
  void BeginChain(int i, const Segment& s);
  Segment Restart(int b, double t, const Vec3& r, const Vec3& v, const Vec3& om,
                  const Quat& q) const;
  // Events.
  void Impact(double t, int i, int j);
  Model SubModel(const std::vector<int>& members,
                 const std::vector<std::pair<int, int>>& pairs) const;
  void FindCluster(double t, std::vector<int>& cluster,
                   std::vector<std::pair<int, int>>& pairs) const;
  void RecordImpact(double t, const Model& sub, const ImpactResult& r, const State& after,
                    const std::vector<int>& cluster, int np_plane);
  void BookWorks(const Model& sub, const std::vector<int>& balls, int p,
                 const ContactPointState& c);
  void CheckNoOverlap(const State& initial) const;
  std::vector<Segment> InitialSegments(const State& initial);
  // Pressing groups.
  struct Window {                      // a run of a group by the hybrid engine
    std::shared_ptr<const Model> sub;  // shared by the runs from its checkpoints
    SimulationResult r;
  };
  struct Group {
    std::vector<int> members;
    std::vector<BodyState> states;  // at t_a
    // Mode and rolling sub-mode of the members' plane points at t_a (the hybrid's).
    std::vector<ContactPointState> modes;
    std::vector<Vec3> origin;  // the members' centres at t_o, when the window was planned
    double speed = 0.0;        // the window's speed bound σ
    double span = kInf;        // the longest window to plan (kMinSpan)
    double t_o = 0.0, t_a = 0.0, t_b = 0.0;
    Box box;                      // the window's claim: where its members may be until t_b
    std::unique_ptr<Window> run;  // the window's speculative run, from t_o to t_b
    std::uint32_t ver = 0;
    std::uint64_t tick = 0;  // when the window was planned (tick_)
    bool alive = true;
  };
  void RemoveFromGrid(int i);
  void Join(int g, int i, double t);
  SimulationOptions WindowOptions(double t) const;
  SimulationResult RunGroup(const Model& sub, const State& from, const SimulationOptions& so);
  Window RunWindow(int g, double t, const std::vector<int>* near);
  void Commit(int g, const Window& w, const SimulationResult* head = nullptr);
  void Advance(int g, double t);
  void Merge(int g, int h);
  void Plan(int g, double t);
  Box HereBox(const Group& g) const;
  // Grows `box` to cover the disc of radius pad about r in the plane.
  void Grow(Box& box, const Vec3& r, double pad) const {
    box.lo1 = std::min(box.lo1, w_.e1.dot(r) - pad);
    box.hi1 = std::max(box.hi1, w_.e1.dot(r) + pad);
    box.lo2 = std::min(box.lo2, w_.e2.dot(r) - pad);
    box.hi2 = std::max(box.hi2, w_.e2.dot(r) + pad);
  }
  Box GroupBox(const Group& g, double t) const;
  std::vector<int> BallsIn(const Box& box) const;
  bool MayReach(const Group& g, int o, double t) const;
  // Whether balls a and b may collide (every pair, or the listed ones).
  bool MayCollide(int a, int b) const {
    return options_.collide_all_pairs || listed_pairs_.count(PairKey(a, b)) != 0;
  }
  // Gap between balls a and b with centres r_a and r_b.
  double Gap(int a, const Vec3& r_a, int b, const Vec3& r_b) const {
    return (r_a - r_b).norm() - balls_[static_cast<size_t>(a)].R - balls_[static_cast<size_t>(b)].R;
  }
  void FormGroup(const std::vector<int>& balls, double t);
  void EndWindow(int g, double t);
  void CheckGroups(double t);
  void Handle(const Event& e);
  void CloseSegment(int i, double t);  // books the ledger of i's motion up to t
  State StateAt(double t) const;

  const Model& model_;
  const SphereEventOptions& options_;
  World w_;
  std::vector<Ball> balls_;
  std::vector<int> ball_of_body_;
  std::unordered_map<std::uint64_t, int> listed_pairs_;  // (a, b) -> contact index
  std::vector<int> gravity_elements_;
  double cell_ = 0.0, R_max_ = 0.0;

  std::vector<Chain> chain_;
  std::vector<std::uint32_t> ver_;
  std::vector<Box> box_;
  std::vector<double> horizon_;
  std::vector<std::array<int, 4>> cells_of_;  // x0, x1, y0, y1
  std::unordered_map<std::int64_t, std::vector<int>> grid_;
  std::vector<std::uint64_t> stamp_;
  std::uint64_t stamp_now_ = 0;
  std::priority_queue<Event, std::vector<Event>, Later> queue_;
  std::uint64_t seq_ = 0;

  // Ledger: the state at each ball's last booked time, and the running integrals.
  State ledger_;
  std::vector<double> booked_until_;
  SphereEventResult res_;
  std::vector<Group> groups_;
  std::vector<int> group_of_;              // -1: on its chain
  std::vector<int> renewed_;               // balls whose boxes changed since the last group check
  std::vector<std::uint64_t> renew_tick_;  // when each ball's box was renewed (tick_)
  std::uint64_t tick_ = 0;                 // orders box renewals and group plans
};

}  // namespace

std::string SphereEventObstacle(const Model& model) {
  if (model.num_constraints() > 0) return "the model has constraints";
  Vec3 g = Vec3::Zero();
  for (int e = 0; e < model.num_force_elements(); ++e) {
    const auto* ug = dynamic_cast<const UniformGravity*>(&model.force_element(e));
    if (ug == nullptr) {
      return fmt::format("force element '{}' is not uniform gravity",
                         model.force_element(e).name());
    }
    g += ug->g_W();
  }
  if (!(g.norm() > 0.0)) return "there is no gravity to press the balls on the plane";
  std::vector<int> plane_of(static_cast<size_t>(model.num_bodies()), -1);
  Vec3 n = Vec3::Zero(), p0 = Vec3::Zero();
  bool have_plane = false;
  for (int c = 0; c < model.num_contacts(); ++c) {
    const Contact& con = model.contact(c);
    const ContactSpec& s = con.spec();
    const Body& body = model.body(s.body);
    if (s.shape == ContactShape::kSphereSphere) continue;
    if (s.shape != ContactShape::kSphere) {
      return fmt::format("contact '{}' is a {}, not a sphere on the plane", con.name(),
                         ContactShapeName(s.shape));
    }
    if ((s.p_BoC_B - body.p_BoBcm_B()).norm() > 1e-12 * s.radius) {
      return fmt::format("contact '{}': the sphere is not centred at body '{}''s centre of mass",
                         con.name(), body.name());
    }
    if (plane_of[static_cast<size_t>(s.body)] >= 0) {
      return fmt::format("body '{}' has two plane contacts", body.name());
    }
    plane_of[static_cast<size_t>(s.body)] = c;
    const Vec3 nc = s.plane_normal_W.normalized();
    if (!have_plane) {
      n = nc;
      p0 = s.plane_point_W;
      have_plane = true;
    } else if ((nc - n).norm() > 1e-12 || std::abs(n.dot(s.plane_point_W - p0)) > 1e-12) {
      return fmt::format("contact '{}' is on another plane than the first contact's", con.name());
    }
  }
  if (!have_plane) return "no body has a sphere contact with a plane";
  if ((g / g.norm() + n).norm() > 1e-12) {
    return "gravity is not normal to the plane (a tilted table)";
  }
  for (int b = 0; b < model.num_bodies(); ++b) {
    const Body& body = model.body(b);
    if (plane_of[static_cast<size_t>(b)] < 0) {
      return fmt::format("body '{}' has no sphere contact with the plane", body.name());
    }
    const Mat3& I = body.I_BBcm_B();
    const double i0 = I.trace() / 3.0;
    if (!(i0 > 0.0) || (I - i0 * Mat3::Identity()).norm() > 1e-12 * i0) {
      return fmt::format("body '{}' has no isotropic inertia about its centre of mass (a ball)",
                         body.name());
    }
    const Contact& con = model.contact(plane_of[static_cast<size_t>(b)]);
    const double kappa = body.mass() * con.spec().radius * con.spec().radius / i0;
    if (con.mu_r() / (1.0 + 1.0 / kappa) > con.mu_s()) {
      return fmt::format(
          "contact '{}': rolling resistance mu_r = {} needs more friction than "
          "mu_s = {} holds (it would roll and slip)",
          con.name(), con.mu_r(), con.mu_s());
    }
  }
  for (int c = 0; c < model.num_contacts(); ++c) {
    const ContactSpec& s = model.contact(c).spec();
    if (s.shape != ContactShape::kSphereSphere) continue;
    const auto fits = [&](BodyIndex body, const Vec3& p, double r) {
      const ContactSpec& ps = model.contact(plane_of[static_cast<size_t>(body)]).spec();
      return (p - model.body(body).p_BoBcm_B()).norm() <= 1e-12 * r &&
             std::abs(r - ps.radius) <= 1e-12 * r;
    };
    if (!fits(s.body, s.p_BoC_B, s.radius) || !fits(s.other_body, s.p_OoC_O, s.other_radius)) {
      return fmt::format(
          "contact '{}': its spheres are not the balls' own (same radius, centred "
          "at the centres of mass)",
          model.contact(c).name());
    }
  }
  return {};
}

namespace {

void Runner::ReadModel() {
  const std::string obstacle = SphereEventObstacle(model_);
  if (!obstacle.empty()) {
    throw InputError(
        fmt::format("the event-driven sphere path cannot run this model: {}", obstacle));
  }
  for (int e = 0; e < model_.num_force_elements(); ++e) {
    w_.g_W += static_cast<const UniformGravity&>(model_.force_element(e)).g_W();
    gravity_elements_.push_back(e);
  }
  w_.g = w_.g_W.norm();
  w_.tol = options_.tolerances;
  const int nb = model_.num_bodies();
  balls_.resize(static_cast<size_t>(nb));
  for (int c = 0; c < model_.num_contacts(); ++c) {
    const Contact& con = model_.contact(c);
    const ContactSpec& s = con.spec();
    if (s.shape == ContactShape::kSphereSphere) {
      listed_pairs_[PairKey(s.body, s.other_body)] = c;
      continue;
    }
    Ball& b = balls_[static_cast<size_t>(s.body)];
    const Body& body = model_.body(s.body);
    b.body = s.body;
    b.point = model_.contact_point_offset(c);
    b.m = body.mass();
    b.R = s.radius;
    b.I = body.I_BBcm_B().trace() / 3.0;
    b.kappa = b.m * b.R * b.R / b.I;
    b.mu_s = s.mu_s;
    b.mu_k = s.mu_k;
    b.mu_r = s.mu_r;
    w_.n = s.plane_normal_W.normalized();
    w_.p0 = s.plane_point_W;
    R_max_ = std::max(R_max_, b.R);
  }
  w_.e1 = (std::abs(w_.n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(w_.n).normalized();
  w_.e2 = w_.n.cross(w_.e1);
  cell_ = 4.0 * R_max_;
}

// The segment ball b starts at t from (r, v, ω, q): on the plane when it touches it (gap
// within tol.gap) with a normal velocity within resting_speed (then removed); otherwise in
// flight, which for a ball touching and moving into the plane ends at once in an impact.
Segment Runner::Restart(int b, double t, const Vec3& r, const Vec3& v, const Vec3& om,
                        const Quat& q) const {
  const Ball& ball = balls_[static_cast<size_t>(b)];
  const double gap = w_.n.dot(r - w_.p0) - ball.R;
  const bool on_plane = gap <= w_.tol.gap && std::abs(w_.n.dot(v)) <= w_.tol.resting_speed;
  return StartSegment(ball, w_, t, r, v, om, q, on_plane);
}

void Runner::BeginChain(int i, const Segment& s) {
  chain_[static_cast<size_t>(i)] = MakeChain(balls_[static_cast<size_t>(i)], w_, s);
  ++ver_[static_cast<size_t>(i)];
  const Chain& c = chain_[static_cast<size_t>(i)];
  const std::uint32_t v = ver_[static_cast<size_t>(i)];
  for (int k = 0; k + 1 < c.count; ++k) {
    Schedule({c.seg[static_cast<size_t>(k)].end(), Kind::kPhase, i, -1, v, 0, 0});
  }
  if (std::isfinite(c.known_until)) Schedule({c.known_until, Kind::kLanding, i, -1, v, 0, 0});
  RenewBox(i, s.t0);
}

// The ball's box in the plane over [t, horizon], its cells, and the exact tests against the
// balls whose boxes overlap it. The horizon is where the ball has moved about half a cell.
void Runner::RenewBox(int i, double t) {
  const auto iu = static_cast<size_t>(i);
  const Ball& b = balls_[iu];
  const Chain& c = chain_[iu];
  const Segment& s = c.At(t);
  const Vec3 v = s.Vel(t);
  const double speed = (v - w_.n.dot(v) * w_.n).norm();
  double h = s.phase == Phase::kRest ? kInf : t + 0.5 * cell_ / std::max(speed, 1e-300);
  h = std::min({h, c.known_until, options_.t_end});
  Box box;
  // A ball that is slow now may not stay slow (a backspin ball speeding up): the horizon is
  // shortened until the box covers at most 4 x 4 cells. Any box is correct (the pair tests
  // are exact); its size only sets the work.
  for (;;) {
    box = Box{kInf, -kInf, kInf, -kInf};
    for (int k = 0; k < c.count; ++k) {
      const Segment& sk = c.seg[static_cast<size_t>(k)];
      if (sk.end() < t && k + 1 < c.count) continue;  // over before t
      const double ta = std::max(t, sk.t0), tb = std::min(h, sk.end());
      if (ta > tb) break;
      Extend(w_.e1.dot(sk.r0), w_.e1.dot(sk.v0), w_.e1.dot(sk.a), ta - sk.t0, tb - sk.t0, box.lo1,
             box.hi1);
      Extend(w_.e2.dot(sk.r0), w_.e2.dot(sk.v0), w_.e2.dot(sk.a), ta - sk.t0, tb - sk.t0, box.lo2,
             box.hi2);
    }
    const double pad = b.R * (1.0 + 1e-9) + w_.tol.gap;
    box.lo1 -= pad, box.lo2 -= pad, box.hi1 += pad, box.hi2 += pad;
    const bool small = box.hi1 - box.lo1 <= 3.0 * cell_ && box.hi2 - box.lo2 <= 3.0 * cell_;
    if (small || !(h > t) || (h - t) < 1e-9 * std::max(1.0, std::abs(t))) break;
    h = t + 0.25 * (h - t);
  }
  // Move the ball's cell entries.
  RemoveFromGrid(i);
  std::array<int, 4>& cells = cells_of_[iu];
  cells = {Cell(box.lo1), Cell(box.hi1), Cell(box.lo2), Cell(box.hi2)};
  box_[iu] = box;
  horizon_[iu] = h;
  ++res_.stats.box_renewals;
  ++stamp_now_;
  stamp_[iu] = stamp_now_;
  for (int x = cells[0]; x <= cells[1]; ++x) {
    for (int y = cells[2]; y <= cells[3]; ++y) {
      std::vector<int>& v = grid_[CellKey(x, y)];
      for (const int j : v) {
        const auto ju = static_cast<size_t>(j);
        if (stamp_[ju] == stamp_now_) continue;
        stamp_[ju] = stamp_now_;
        if (box_[ju].Overlaps(box)) TestPair(i, j, t);
      }
      v.push_back(i);
    }
  }
  if (std::isfinite(h) && h < options_.t_end && h < c.known_until) {
    Schedule({h, Kind::kHorizon, i, -1, ver_[iu], 0, 0});
  }
  renewed_.push_back(i);
  renew_tick_[iu] = ++tick_;
}

// The first time in [t, min(horizons)] at which balls i and j touch, approaching: over each
// stretch where both follow one segment, |r_i - r_j|² - (R_i + R_j)² is a quartic in time.
void Runner::TestPair(int i, int j, double t) {
  if (!MayCollide(i, j)) return;
  ++res_.stats.pair_tests;
  const auto iu = static_cast<size_t>(i), ju = static_cast<size_t>(j);
  const Chain &ci = chain_[iu], &cj = chain_[ju];
  const double t_to =
      std::min({horizon_[iu], horizon_[ju], ci.known_until, cj.known_until, options_.t_end});
  if (!(t_to >= t)) return;
  std::array<double, 8> knots{};
  int nk = 0;
  knots[static_cast<size_t>(nk++)] = t;
  for (const Chain* c : {&ci, &cj}) {
    for (int k = 0; k + 1 < c->count; ++k) {
      const double e = c->seg[static_cast<size_t>(k)].end();
      if (e > t && e < t_to) knots[static_cast<size_t>(nk++)] = e;
    }
  }
  for (int a = 2; a < nk; ++a) {  // insertion sort of the (at most four) segment ends
    for (int b = a; b > 1 && knots[static_cast<size_t>(b)] < knots[static_cast<size_t>(b - 1)];
         --b) {
      std::swap(knots[static_cast<size_t>(b)], knots[static_cast<size_t>(b - 1)]);
    }
  }
  knots[static_cast<size_t>(nk++)] = t_to;
  const double S = balls_[iu].R + balls_[ju].R;
  for (int k = 0; k + 1 < nk; ++k) {
    const double s0 = knots[static_cast<size_t>(k)], s1 = knots[static_cast<size_t>(k + 1)];
    if (s1 < s0) continue;
    const Segment &a = ci.At(s0), &b = cj.At(s0);
    const Vec3 d0 = a.Pos(s0) - b.Pos(s0);
    const Vec3 d1 = a.Vel(s0) - b.Vel(s0);
    const Vec3 d2 = 0.5 * (a.a - b.a);
    const Poly f{(d0.norm() - S) * (d0.norm() + S), 2.0 * d0.dot(d1),
                 d1.squaredNorm() + 2.0 * d0.dot(d2), 2.0 * d1.dot(d2), d2.squaredNorm()};
    const double sigma = FirstEntry(f, 0.0, s1 - s0);
    if (std::isfinite(sigma)) {
      Schedule({s0 + sigma, Kind::kPair, i, j, ver_[iu], ver_[ju], 0});
      return;
    }
  }
}

// Books ball i's ledger from its last booked time to t along its chain (closed forms per
// segment): sliding friction's work -mu_k m g ∫|u| = -mu_k m g (|u0| τ - ½ k τ²) with
// k = mu_k g (1 + m R²/I); rolling resistance's -mu_r m g ∫|v|; gravity's work m g·Δr, impulse
// m g τ and moment of impulse about Wo, ∫ r × m g = (r0 τ + v0 τ²/2 + a τ³/6) × m g.
void Runner::CloseSegment(int i, double t) {
  const auto iu = static_cast<size_t>(i);
  const Ball& b = balls_[iu];
  const Chain& c = chain_[iu];
  double from = booked_until_[iu];
  for (int k = 0; k < c.count && from < t; ++k) {
    const Segment& s = c.seg[static_cast<size_t>(k)];
    if (s.end() <= from && k + 1 < c.count) continue;
    const double ta = from - s.t0, tb = std::min(t, s.end()) - s.t0;
    if (tb <= ta) continue;
    ContactPointState& cp = ledger_.contacts[static_cast<size_t>(b.point)];
    if (s.phase == Phase::kSliding && b.mu_k > 0.0) {
      const double kk = b.mu_k * w_.g * (1.0 + b.kappa);
      const auto I = [&](double x) { return s.slip0 * x - 0.5 * kk * x * x; };
      const double work = -b.mu_k * b.m * w_.g * (I(tb) - I(ta));
      cp.friction_work += work;
      res_.energy.friction += work;
    } else if (s.phase == Phase::kRolling && b.mu_r > 0.0) {
      const double v0 = s.v0.norm(), ar = s.a.norm();
      const auto I = [&](double x) { return v0 * x - 0.5 * ar * x * x; };
      const double work = -b.mu_r * b.m * w_.g * (I(tb) - I(ta));
      cp.rolling_work += work;
      res_.energy.rolling += work;
    }
    const auto integral_r = [&](double x) {
      return Vec3(s.r0 * x + s.v0 * (x * x / 2.0) + s.a * (x * x * x / 6.0));
    };
    const Vec3 dr = s.Pos(s.t0 + tb) - s.Pos(s.t0 + ta);
    const Vec3 int_r = integral_r(tb) - integral_r(ta);
    for (const int e : gravity_elements_) {
      const Vec3 ge = static_cast<const UniformGravity&>(model_.force_element(e)).g_W();
      ForceIntegrals& fi = ledger_.force_integrals[static_cast<size_t>(e)];
      fi.work += b.m * ge.dot(dr);
      fi.linear_impulse_W += b.m * ge * (tb - ta);
      fi.angular_impulse_Wo_W += int_r.cross(b.m * ge);
    }
    from = s.t0 + tb;
  }
  booked_until_[iu] = t;
}

State Runner::StateAt(double t) const {
  State s = ledger_;
  s.t = t;
  for (size_t i = 0; i < balls_.size(); ++i) {
    if (group_of_[i] >= 0) {  // brought to t by the caller
      const Group& g = groups_[static_cast<size_t>(group_of_[i])];
      const auto m = static_cast<size_t>(
          std::find(g.members.begin(), g.members.end(), static_cast<int>(i)) - g.members.begin());
      s.bodies[i] = g.states[m];
      ContactPointState& cp = s.contacts[static_cast<size_t>(balls_[i].point)];
      cp.mode = g.modes[m].mode;
      cp.rolling_held = g.modes[m].rolling_held;
      continue;
    }
    const Segment& seg = chain_[i].At(t);
    BodyState& bs = s.bodies[i];
    bs.p_WBcm = seg.Pos(t);
    bs.v_WBcm_W = seg.Vel(t);
    const Vec3 om = seg.Omega(t);
    bs.q_WB = ChainOrient(chain_[i], t);
    bs.w_WB_B = bs.q_WB.conjugate() * om;
    ContactPointState& cp = s.contacts[static_cast<size_t>(balls_[i].point)];
    cp.mode = ModeOfPhase(seg.phase);
    cp.slip_direction_W = seg.phase == Phase::kSliding ? seg.s_hat : Vec3::Zero();
    // The rolling reference, as the hybrid engine writes it (rolling resistance's moment in the
    // contact outputs): the direction of the rolling angular velocity n × v / R.
    const Vec3 v_plane = bs.v_WBcm_W - w_.n.dot(bs.v_WBcm_W) * w_.n;
    cp.rolling_direction_W =
        seg.phase == Phase::kRolling && balls_[i].mu_r > 0.0 && v_plane.norm() > w_.tol.stick_speed
            ? Vec3(w_.n.cross(v_plane).normalized())
            : Vec3::Zero();
    // At rest on the level table, rolling resistance holds the rolling (a moment of zero).
    cp.rolling_held = seg.phase == Phase::kRest && balls_[i].mu_r > 0.0;
  }
  return s;
}

// Grows `cluster` to every ball touching one of it at t (gap <= tol.gap, a pair that may
// collide), listing the touching pairs.
void Runner::FindCluster(double t, std::vector<int>& cluster,
                         std::vector<std::pair<int, int>>& pairs) const {
  std::unordered_map<int, int> local;  // ball -> place in the cluster
  for (size_t k = 0; k < cluster.size(); ++k) local[cluster[k]] = static_cast<int>(k);
  const auto pos = [&](int b) { return SegAt(b, t).Pos(t); };
  for (size_t k = 0; k < cluster.size(); ++k) {
    const int a = cluster[k];
    const Vec3 ra = pos(a);
    const double reach = balls_[static_cast<size_t>(a)].R + R_max_ + w_.tol.gap;
    const int x0 = Cell(w_.e1.dot(ra) - reach);
    const int x1 = Cell(w_.e1.dot(ra) + reach);
    const int y0 = Cell(w_.e2.dot(ra) - reach);
    const int y1 = Cell(w_.e2.dot(ra) + reach);
    for (int x = x0; x <= x1; ++x) {
      for (int y = y0; y <= y1; ++y) {
        const auto it = grid_.find(CellKey(x, y));
        if (it == grid_.end()) continue;
        for (const int c : it->second) {
          if (c == a) continue;
          if (!MayCollide(a, c)) continue;
          const double gap = Gap(a, ra, c, pos(c));
          if (gap > w_.tol.gap) continue;
          if (local.count(c) == 0) {
            local[c] = static_cast<int>(cluster.size());
            cluster.push_back(c);
          }
          const auto p = std::make_pair(std::min(a, c), std::max(a, c));
          if (std::find(pairs.begin(), pairs.end(), p) == pairs.end()) pairs.push_back(p);
        }
      }
    }
  }
}

// Adds the works of point p of `sub` (a Model of `balls`, their plane points first, then one
// sphere-sphere point per touching pair: SubModel) to the ledger: a plane point's and a listed
// pair's to their own points, an unlisted pair's to State::unlisted_contact_work.
void Runner::BookWorks(const Model& sub, const std::vector<int>& balls, int p,
                       const ContactPointState& c) {
  ContactWork* d = &ledger_.unlisted_contact_work;
  ContactPointState* point = nullptr;
  if (p < static_cast<int>(balls.size())) {
    point = &ledger_.contacts[static_cast<size_t>(
        balls_[static_cast<size_t>(balls[static_cast<size_t>(p)])].point)];
  } else {
    const ContactSpec& s = sub.contact(p).spec();
    const auto it = listed_pairs_.find(
        PairKey(balls[static_cast<size_t>(s.body)], balls[static_cast<size_t>(s.other_body)]));
    if (it != listed_pairs_.end()) {
      point = &ledger_.contacts[static_cast<size_t>(model_.contact_point_offset(it->second))];
    }
  }
  if (point != nullptr) {
    point->friction_work += c.friction_work;
    point->rolling_work += c.rolling_work;
    point->impact_work += c.impact_work;
    return;
  }
  d->friction_work += c.friction_work;
  d->rolling_work += c.rolling_work;
  d->impact_work += c.impact_work;
}

// Books an impact: the energy change (shared among the points by normal impulse, as
// ResolveImpacts leaves it in `after`), plane impacts (approaching points only) and ball-ball
// collisions.
void Runner::RecordImpact(double t, const Model& sub, const ImpactResult& r, const State& after,
                          const std::vector<int>& cluster, int np_plane) {
  ++res_.stats.impacts;
  res_.energy.impacts += r.kinetic_energy_after - r.kinetic_energy_before;
  for (int p = 0; p < sub.num_contact_points(); ++p) {
    BookWorks(sub, cluster, p, after.contacts[static_cast<size_t>(p)]);
  }
  for (const ContactImpulse& ci : r.impulses) {
    if (ci.point < np_plane) {
      if (ci.approach_speed <= w_.tol.resting_speed) continue;
      ImpactRecord rec;
      rec.t = t;
      rec.point = balls_[static_cast<size_t>(cluster[static_cast<size_t>(ci.point)])].point;
      rec.approach_speed = ci.approach_speed;
      rec.normal_impulse = ci.normal_impulse;
      rec.impulse_W = ci.impulse_W;
      rec.energy_lost = r.kinetic_energy_before - r.kinetic_energy_after;
      rec.law = ci.law;
      rec.frictionless_fallback = r.frictionless_fallback;
      res_.plane_impacts.push_back(rec);
    } else {
      const ContactSpec& s = sub.contact(ci.point).spec();
      SphereCollision col;
      col.t = t;
      col.body_a = cluster[static_cast<size_t>(s.body)];
      col.body_b = cluster[static_cast<size_t>(s.other_body)];
      col.approach_speed = ci.approach_speed;
      col.normal_impulse = ci.normal_impulse;
      col.impulse_on_a_W = ci.impulse_W;
      col.energy_lost = r.kinetic_energy_before - r.kinetic_energy_after;
      col.law = ci.law;
      col.cluster_size = static_cast<int>(cluster.size());
      res_.collisions.push_back(col);
    }
  }
}

// A Model of `members` (in that order) with their plane contacts (points 0 .. k-1), one
// sphere-sphere contact per pair in `pairs` (points k, k+1, ...: a listed contact's spec, or
// pair_law's) and the model's gravity elements.
Model Runner::SubModel(const std::vector<int>& members,
                       const std::vector<std::pair<int, int>>& pairs) const {
  Model sub;
  std::unordered_map<int, int> local;
  for (size_t k = 0; k < members.size(); ++k) {
    const int b = members[k];
    local[b] = static_cast<int>(k);
    sub.AddBody(model_.body(b).name(), model_.body(b).mass_properties());
  }
  for (size_t k = 0; k < members.size(); ++k) {
    const Ball& b = balls_[static_cast<size_t>(members[k])];
    ContactSpec s = model_.contact(model_.contact_of_point(b.point)).spec();
    s.body = static_cast<BodyIndex>(k);
    sub.AddContact(s);
  }
  for (const auto& [a, c] : pairs) {
    ContactSpec s;
    const auto it = listed_pairs_.find(PairKey(a, c));
    if (it != listed_pairs_.end()) {
      s = model_.contact(it->second).spec();
      const bool swapped = s.body != a;
      s.body = local.at(swapped ? c : a);
      s.other_body = local.at(swapped ? a : c);
    } else {
      s.name = fmt::format("{} | {}", model_.body(a).name(), model_.body(c).name());
      s.shape = ContactShape::kSphereSphere;
      s.body = local.at(a);
      s.other_body = local.at(c);
      s.p_BoC_B = model_.body(a).p_BoBcm_B();
      s.p_OoC_O = model_.body(c).p_BoBcm_B();
      s.radius = balls_[static_cast<size_t>(a)].R;
      s.other_radius = balls_[static_cast<size_t>(c)].R;
      s.restitution = options_.pair_law.restitution;
      s.mu_s = options_.pair_law.mu_s;
      s.mu_k = options_.pair_law.mu_k;
      s.restitution_law = options_.pair_law.law;
    }
    sub.AddContact(s);
  }
  for (const int e : gravity_elements_) {
    const auto& ug = static_cast<const UniformGravity&>(model_.force_element(e));
    sub.AddForceElement(std::make_shared<UniformGravity>(ug.name(), ug.g_W()));
  }
  return sub;
}

// An impact at t started by ball i (a landing, j < 0) or the pair (i, j): every ball touching
// these at t (transitively) and their plane contacts form one small Model, resolved by
// ResolveImpacts; each ball then starts a new chain.
void Runner::Impact(double t, int i, int j) {
  std::vector<int> cluster{i};
  if (j >= 0) cluster.push_back(j);
  std::vector<std::pair<int, int>> pairs;
  FindCluster(t, cluster, pairs);
  // The impact's Model. Orientation does not enter (isotropic balls, spheres at the centres
  // of mass), so each ball is posed with q = 1 and ω in W.
  const Model sub = SubModel(cluster, pairs);
  const int np_plane = static_cast<int>(cluster.size());
  State st = MakeRestState(sub);
  st.t = t;
  for (size_t k = 0; k < cluster.size(); ++k) {
    const Segment& seg = SegAt(cluster[k], t);
    BodyState& bs = st.bodies[k];
    bs.p_WBcm = seg.Pos(t);
    bs.q_WB = Quat::Identity();
    bs.v_WBcm_W = seg.Vel(t);
    bs.w_WB_B = seg.Omega(t);
  }
  ImpactResult r = ResolveImpacts(sub, st, w_.tol);
  if (r.impulses.empty()) {
    if (j < 0) return;  // a landing below resting speed: the caller sets the ball down
    // Approaching slower than resting_speed. If the free motion would press them (the gap's
    // second derivative, (|ḋ|² - (k·ḋ)²)/|d| + k·d̈, negative), a bounce would only start a
    // chase of ever smaller bounces: the touching balls become a group for the hybrid engine.
    // Otherwise they part in second order and the small approach is a small impact, resolved
    // as one (resting_speed is only the threshold of lasting contact).
    const Segment &si = SegAt(i, t), &sj = SegAt(j, t);
    const Vec3 d = si.Pos(t) - sj.Pos(t), dd = si.Vel(t) - sj.Vel(t);
    const Vec3 k = d.normalized();
    const double gap_dd =
        (dd.squaredNorm() - std::pow(k.dot(dd), 2)) / d.norm() + k.dot(si.a - sj.a);
    if (gap_dd < 0.0) {
      FormGroup(cluster, t);
      return;
    }
    ContactTolerances tol = w_.tol;
    tol.resting_speed = 0.0;
    r = ResolveImpacts(sub, st, tol);
    if (r.impulses.empty()) return;  // no approach at all: they part
  }
  RecordImpact(t, sub, r, st, cluster, np_plane);
  // New chains.
  for (size_t k = 0; k < cluster.size(); ++k) {
    const int b = cluster[k];
    const auto bu = static_cast<size_t>(b);
    const Segment& seg = SegAt(b, t);
    CloseSegment(b, t);
    const Quat q = ChainOrient(chain_[bu], t);
    const Segment next = Restart(b, t, seg.Pos(t), st.bodies[k].v_WBcm_W, st.bodies[k].w_WB_B, q);
    const ContactMode before = ModeOfPhase(seg.phase), after = ModeOfPhase(next.phase);
    if (before != after || (j < 0 && b == i)) {
      ContactEvent ev;
      ev.t = t;
      ev.point = balls_[bu].point;
      ev.from = before;
      ev.to = after;
      ev.reason = j < 0 && b == i                    ? ContactEventReason::kTouchDown
                  : after == ContactMode::kSeparated ? ContactEventReason::kLiftOff
                  : j >= 0                           ? ContactEventReason::kCollision
                                                     : ContactEventReason::kOther;
      if (ev.from != ev.to) res_.contact_events.push_back(ev);
    }
    BeginChain(b, next);
  }
}

// Refuses balls that start overlapping (a grid by position).
void Runner::CheckNoOverlap(const State& initial) const {
  const size_t n = balls_.size();
  std::unordered_map<std::int64_t, std::vector<int>> cells;
  for (size_t i = 0; i < n; ++i) {
    const Vec3& r = initial.bodies[i].p_WBcm;
    cells[CellKey(Cell(w_.e1.dot(r)), Cell(w_.e2.dot(r)))].push_back(static_cast<int>(i));
  }
  for (size_t i = 0; i < n; ++i) {
    const Vec3& r = initial.bodies[i].p_WBcm;
    const int cx = Cell(w_.e1.dot(r));
    const int cy = Cell(w_.e2.dot(r));
    for (int x = cx - 1; x <= cx + 1; ++x) {
      for (int y = cy - 1; y <= cy + 1; ++y) {
        const auto it = cells.find(CellKey(x, y));
        if (it == cells.end()) continue;
        for (const int j : it->second) {
          if (static_cast<size_t>(j) <= i) continue;
          const double gap =
              Gap(static_cast<int>(i), r, j, initial.bodies[static_cast<size_t>(j)].p_WBcm);
          if (gap < -w_.tol.gap) {
            throw InputError(fmt::format("bodies '{}' and '{}' start overlapping by {} m",
                                         model_.body(static_cast<int>(i)).name(),
                                         model_.body(j).name(), -gap));
          }
        }
      }
    }
  }
}

// ---- Pressing groups --------------------------------------------------------------------
// Balls that come to press on each other (a chase whose re-collisions shrink to zero approach
// speed, or a rack squeezed) have no closed form: they form a group run by the hybrid engine
// (Simulate on a Model of the group: Dormand-Prince, contact modes, events, impacts) in
// windows [t_o, t_b] in which no outside ball can reach them. A window is planned on a speed
// bound σ (the members' fastest |v| + R |ω|, with a margin) and run at once, speculatively,
// with one stop event: a member leaving its ball of radius σ (τ - t_o) + ε about its place at
// t_o, or coming within kStopGap of an outside ball whose boxes reach the group (on that
// ball's chain). So the window is checked against the members' own motion, not a bound on
// it: a group moving along a rack, balls a tenth of a millimetre from it that it does not
// approach, runs in long windows. The run is kept and taken at the window's end; an outside
// ball whose new chain may reach a member cuts the window (the run is kept to its last
// checkpoint before then and the group run afresh from there). A window is planned at most
// twice as long as the group's last one ran, so little is speculated past where cuts come.
// A ball within kJoinGap of a member joins; groups whose claims (their members' reach over
// the window) meet are cut and each takes half the room between them, or merge when their
// members are within reach. At a window's end the group splits into its touching components,
// and members touching no other member leave on closed-form chains.
constexpr int kMaxGroup = 200;
constexpr double kSpeedMargin = 1.25;  // σ = margin × fastest member + floor
constexpr double kSpeedFloor = 1e-3;   // [m/s]
constexpr double kReach = 1e-8;        // ε: the bound's slack for a run repeated to a cut [m]
constexpr double kMinWindow = 1e-5;    // [s] groups closer than this at σ merge instead
constexpr double kJoinGap = 1e-6;      // [m] a ball this close to a member joins its group
constexpr double kStopGap =
    0.5 * kJoinGap;               // [m] a window stops where an outside ball is this close
constexpr int kCheckpoints = 32;  // samples of a speculative run, from which a cut one resumes
// A window is planned at most twice as long as the last one of its group ran before it was cut
// (or ended), and no shorter than this [s]: speculation past where cuts come is wasted.
constexpr double kMinSpan = 1e-5;

// How far apart two boxes are (positive when they do not overlap).
double Separation(const Box& a, const Box& b) {
  return std::max({b.lo1 - a.hi1, a.lo1 - b.hi1, b.lo2 - a.hi2, a.lo2 - b.hi2});
}

void Runner::RemoveFromGrid(int i) {
  std::array<int, 4>& cells = cells_of_[static_cast<size_t>(i)];
  for (int x = cells[0]; x <= cells[1]; ++x) {
    for (int y = cells[2]; y <= cells[3]; ++y) {
      std::vector<int>& v = grid_[CellKey(x, y)];
      const auto it = std::find(v.begin(), v.end(), i);
      if (it != v.end()) {
        *it = v.back();
        v.pop_back();
      }
    }
  }
  cells = {0, -1, 0, -1};
}

// A group of more than kMaxGroup balls is refused (the hybrid engine's mode selection is dense).
void CheckSize(const std::vector<int>& members, double t) {
  if (static_cast<int>(members.size()) > kMaxGroup) {
    throw InputError(fmt::format(
        "{} balls press on each other at t = {} s: more than the event-driven path hands to "
        "the hybrid engine as one group ({})",
        members.size(), t, kMaxGroup));
  }
}

// Ball i (on its chain) joins group g at t.
void Runner::Join(int g, int i, double t) {
  const auto iu = static_cast<size_t>(i);
  CloseSegment(i, t);
  const Segment& seg = SegAt(i, t);
  BodyState bs;
  bs.p_WBcm = seg.Pos(t);
  bs.v_WBcm_W = seg.Vel(t);
  bs.q_WB = ChainOrient(chain_[iu], t);
  bs.w_WB_B = bs.q_WB.conjugate() * seg.Omega(t);
  RemoveFromGrid(i);
  ++ver_[iu];
  group_of_[iu] = g;
  Group& gr = groups_[static_cast<size_t>(g)];
  gr.members.push_back(i);
  gr.states.push_back(bs);
  ContactPointState cp;
  cp.mode = ModeOfPhase(seg.phase);
  cp.rolling_held = seg.phase == Phase::kRest && balls_[iu].mu_r > 0.0;
  gr.modes.push_back(cp);
  CheckSize(gr.members, t);
}

// Group g's hybrid run from t_a to t, on the pairs that may touch before t (each member stays
// within σ (τ - t_o) + ε of its origin). With `near`, the run is the window's speculative one
// and stops where a member leaves its bound or comes within kStopGap of a ball in `near`.
Runner::Window Runner::RunWindow(int g, double t, const std::vector<int>* near) {
  const Group& gr = groups_[static_cast<size_t>(g)];
  const size_t k = gr.members.size();
  const double reach = gr.speed * (t - gr.t_o) + kReach;
  std::vector<std::pair<int, int>> pairs;
  for (size_t a = 0; a < k; ++a) {
    for (size_t b = a + 1; b < k; ++b) {
      const int ia = gr.members[a], ib = gr.members[b];
      if (!MayCollide(ia, ib)) continue;
      if (Gap(ia, gr.origin[a], ib, gr.origin[b]) <= 2.0 * reach + w_.tol.gap) {
        pairs.emplace_back(std::min(ia, ib), std::max(ia, ib));
      }
    }
  }
  Window w{std::make_shared<const Model>(SubModel(gr.members, pairs)), {}};
  State st = MakeRestState(*w.sub);
  st.t = gr.t_a;
  for (size_t m = 0; m < k; ++m) st.bodies[m] = gr.states[m];
  SimulationOptions so = WindowOptions(t);
  if (near != nullptr) {
    // Checkpoints (the run's samples), from which a cut window is run afresh.
    so.output_interval = (t - gr.t_a) / kCheckpoints;
    EventSpec ev;
    ev.name = "window";
    ev.direction = EventDirection::kFalling;
    ev.action = EventAction::kStop;
    ev.g = [this, &gr, near, k](const Model&, const State& s) {
      double v = kInf;
      for (size_t m = 0; m < k; ++m) {
        const Vec3& r = s.bodies[m].p_WBcm;
        v = std::min(v, gr.speed * (s.t - gr.t_o) + kReach - (r - gr.origin[m]).norm());
        for (const int o : *near) {
          if (!MayCollide(o, gr.members[m])) continue;
          v = std::min(v, Gap(o, SegAt(o, s.t).Pos(s.t), gr.members[m], r) - kStopGap);
        }
      }
      return v;
    };
    so.events.push_back(std::move(ev));
  }
  w.r = RunGroup(*w.sub, st, so);
  return w;
}

// A run of a group's Model by the hybrid engine, counted in the statistics.
SimulationResult Runner::RunGroup(const Model& sub, const State& from,
                                  const SimulationOptions& so) {
  SimulationResult r = Simulate(sub, from, so);
  ++res_.stats.group_windows;
  res_.stats.hybrid.steps += r.stats.steps;
  res_.stats.hybrid.rejected_steps += r.stats.rejected_steps;
  res_.stats.hybrid.function_evaluations += r.stats.function_evaluations;
  return r;
}

// The hybrid engine's options for a group's run to t (no output, no events).
SimulationOptions Runner::WindowOptions(double t) const {
  SimulationOptions so;
  so.t_end = t;
  so.output_interval = 0.0;
  so.adaptive = options_.hybrid;
  so.islands = false;
  so.contact.tolerances = w_.tol;
  so.on_step = options_.on_progress;
  return so;
}

// Books a run of group g (its events, impacts and works) and takes its final states. With
// `head`, w.r was run from a checkpoint of the run `head` (same Model): head's events before
// the checkpoint come first; the works are w.r's, which the checkpoint carried from t_a.
void Runner::Commit(int g, const Window& w, const SimulationResult* head) {
  Group& gr = groups_[static_cast<size_t>(g)];
  const Model& sub = *w.sub;
  const SimulationResult& r = w.r;
  const size_t k = gr.members.size();
  const int np = static_cast<int>(k);
  const double t_from = r.samples.front().t;
  const auto before = [&](double t) { return head == nullptr || t < t_from; };
  for (const SimulationResult* part : {head, &r}) {
    if (part == nullptr) continue;
    for (const ContactEvent& ev : part->contact_events) {
      if (ev.reason == ContactEventReason::kInitial || ev.point >= np) continue;
      if (part == head && !before(ev.t)) continue;
      ContactEvent e = ev;
      e.point = balls_[static_cast<size_t>(gr.members[static_cast<size_t>(ev.point)])].point;
      res_.contact_events.push_back(e);
    }
  }
  std::vector<const ImpactRecord*> impacts;
  if (head != nullptr) {
    for (const ImpactRecord& rec : head->impacts) {
      if (before(rec.t)) impacts.push_back(&rec);
    }
  }
  for (const ImpactRecord& rec : r.impacts) impacts.push_back(&rec);
  for (const ImpactRecord* p : impacts) {
    const ImpactRecord& rec = *p;
    if (rec.approach_speed <= w_.tol.resting_speed) continue;
    if (rec.point < np) {
      ImpactRecord e = rec;
      e.point = balls_[static_cast<size_t>(gr.members[static_cast<size_t>(rec.point)])].point;
      res_.plane_impacts.push_back(e);
    } else {
      const ContactSpec& s = sub.contact(rec.point).spec();
      SphereCollision col;
      col.t = rec.t;
      col.body_a = gr.members[static_cast<size_t>(s.body)];
      col.body_b = gr.members[static_cast<size_t>(s.other_body)];
      col.approach_speed = rec.approach_speed;
      col.normal_impulse = rec.normal_impulse;
      col.impulse_on_a_W = rec.impulse_W;
      col.energy_lost = rec.energy_lost;
      col.law = rec.law;
      col.cluster_size = np;
      res_.collisions.push_back(col);
    }
  }
  // The ledger: works of the contacts and gravity's integrals, from zero at t_a.
  for (int p = 0; p < sub.num_contact_points(); ++p) {
    const ContactPointState& c = r.final_state.contacts[static_cast<size_t>(p)];
    res_.energy.friction += c.friction_work;
    res_.energy.rolling += c.rolling_work;
    res_.energy.impacts += c.impact_work;
    BookWorks(sub, gr.members, p, c);
  }
  for (size_t e = 0; e < gravity_elements_.size(); ++e) {
    const ForceIntegrals& f = r.final_state.force_integrals[e];
    ForceIntegrals& d = ledger_.force_integrals[static_cast<size_t>(gravity_elements_[e])];
    d.work += f.work;
    d.work_nonconservative += f.work_nonconservative;
    d.linear_impulse_W += f.linear_impulse_W;
    d.angular_impulse_Wo_W += f.angular_impulse_Wo_W;
  }
  gr.modes.resize(k);
  for (size_t m = 0; m < k; ++m) {
    gr.states[m] = r.final_state.bodies[m];
    gr.modes[m].mode = r.final_state.contacts[m].mode;
    gr.modes[m].rolling_held = r.final_state.contacts[m].rolling_held;
  }
  gr.t_a = r.final_state.t;
}

// Brings group g to t: the window's speculative run when it ends there; otherwise (a cut) that
// run up to its last checkpoint before t on which no event falls, and a fresh run from there
// to t (which follows the speculative one's path to round-off, within the bound's slack ε);
// without such a checkpoint, a fresh run from t_a.
void Runner::Advance(int g, double t) {
  Group& gr = groups_[static_cast<size_t>(g)];
  if (!(t > gr.t_a)) return;
  std::unique_ptr<Window> run = std::move(gr.run);
  if (run) gr.span = std::max(2.0 * (t - gr.t_o), kMinSpan);
  if (run && run->r.final_state.t == t) {
    Commit(g, *run);
    return;
  }
  if (run && run->r.final_state.t > t) {
    const SimulationResult& r = run->r;
    const auto on_event = [&](double ts) {
      return std::any_of(r.contact_events.begin(), r.contact_events.end(),
                         [&](const ContactEvent& e) { return e.t == ts; }) ||
             std::any_of(r.impacts.begin(), r.impacts.end(),
                         [&](const ImpactRecord& e) { return e.t == ts; });
    };
    for (auto it = r.samples.rbegin(); it != r.samples.rend(); ++it) {
      if (!(it->t < t) || on_event(it->t)) continue;
      if (!(it->t > gr.t_a)) break;
      Window rest{run->sub, RunGroup(*run->sub, *it, WindowOptions(t))};
      Commit(g, rest, &r);
      return;
    }
  }
  Commit(g, RunWindow(g, t, nullptr));
}

// The members' places at t_a ± (R + gap) in the plane.
Box Runner::HereBox(const Group& g) const {
  Box box{kInf, -kInf, kInf, -kInf};
  for (size_t m = 0; m < g.members.size(); ++m) {
    Grow(box, g.states[m].p_WBcm, balls_[static_cast<size_t>(g.members[m])].R + w_.tol.gap);
  }
  return box;
}

// The window's claim until t: the origins ± (σ (t - t_o) + ε + R + gap) in the plane.
Box Runner::GroupBox(const Group& g, double t) const {
  Box box{kInf, -kInf, kInf, -kInf};
  for (size_t m = 0; m < g.members.size(); ++m) {
    Grow(box, g.origin[m],
         g.speed * (t - g.t_o) + kReach + balls_[static_cast<size_t>(g.members[m])].R + w_.tol.gap);
  }
  return box;
}

// The outside balls whose boxes overlap `box`, in index order.
std::vector<int> Runner::BallsIn(const Box& box) const {
  std::vector<int> near;
  for (int x = Cell(box.lo1); x <= Cell(box.hi1); ++x) {
    for (int y = Cell(box.lo2); y <= Cell(box.hi2); ++y) {
      const auto it = grid_.find(CellKey(x, y));
      if (it == grid_.end()) continue;
      for (const int o : it->second) {
        if (box_[static_cast<size_t>(o)].Overlaps(box) &&
            std::find(near.begin(), near.end(), o) == near.end()) {
          near.push_back(o);
        }
      }
    }
  }
  std::sort(near.begin(), near.end());
  return near;
}

// Moves group h's members into group g (both at t_a = t).
void Runner::Merge(int g, int h) {
  Group& other = groups_[static_cast<size_t>(h)];
  Group& mine = groups_[static_cast<size_t>(g)];
  for (size_t m = 0; m < other.members.size(); ++m) {
    group_of_[static_cast<size_t>(other.members[m])] = g;
    mine.members.push_back(other.members[m]);
    mine.states.push_back(other.states[m]);
    mine.modes.push_back(other.modes[m]);
  }
  mine.span = std::min(mine.span, other.span);
  other = Group{};
  other.alive = false;
  CheckSize(mine.members, mine.t_a);
}

// Plans group g's next window from t (its t_a) and runs it: joins the balls within kJoinGap,
// merges or makes room with the groups whose claims meet its own, then runs the window
// speculatively to its planned end (or its stop event). Groups it cut are planned after it.
void Runner::Plan(int g, double t) {
  std::vector<int> replan;
  for (;;) {
    Group& gr = groups_[static_cast<size_t>(g)];
    gr.run.reset();
    const size_t k = gr.members.size();
    double fastest = 0.0;
    for (size_t m = 0; m < k; ++m) {
      const BodyState& bs = gr.states[m];
      fastest =
          std::max(fastest, bs.v_WBcm_W.norm() +
                                balls_[static_cast<size_t>(gr.members[m])].R * bs.w_WB_B.norm());
    }
    gr.speed = kSpeedMargin * fastest + kSpeedFloor;
    gr.t_o = t;
    gr.origin.resize(k);
    for (size_t m = 0; m < k; ++m) gr.origin[m] = gr.states[m].p_WBcm;
    // A claim of at most one radius about each member.
    double t_b = std::min({options_.t_end, t + R_max_ / gr.speed, t + gr.span});
    const std::vector<int> near = BallsIn(GroupBox(gr, t_b));
    bool changed = false;
    for (const int o : near) {
      const Vec3 r_o = SegAt(o, t).Pos(t);
      for (size_t m = 0; m < k && !changed; ++m) {
        if (MayCollide(o, gr.members[m]) && Gap(o, r_o, gr.members[m], gr.origin[m]) <= kJoinGap) {
          Join(g, o, t);
          changed = true;
        }
      }
      if (changed) break;
    }
    if (changed) continue;
    const Box here = HereBox(gr);
    for (size_t h = 0; h < groups_.size() && !changed; ++h) {
      Group& other = groups_[h];
      if (static_cast<int>(h) == g || !other.alive || !other.box.Overlaps(GroupBox(gr, t_b)))
        continue;
      if (other.box.Overlaps(here)) {
        // Its claim reaches this group's members: cut it here.
        Advance(static_cast<int>(h), t);
        ++other.ver;
        other.t_b = t;
        other.box = HereBox(other);
        other.speed = 0.0;
        other.t_o = t;
        other.origin.resize(other.members.size());
        for (size_t m = 0; m < other.members.size(); ++m) other.origin[m] = other.states[m].p_WBcm;
        if (std::find(replan.begin(), replan.end(), h) == replan.end())
          replan.push_back(static_cast<int>(h));
      }
      const double room = 0.5 * Separation(here, other.box) / gr.speed;
      if (room < kMinWindow) {
        Advance(static_cast<int>(h), t);
        Merge(g, static_cast<int>(h));
        changed = true;
      } else {
        t_b = std::min(t_b, t + room);
      }
    }
    if (changed) continue;
    if (!(t_b > t)) {  // the end of the run
      gr.t_b = t_b;
      gr.box = HereBox(gr);
      gr.tick = ++tick_;
      break;
    }
    const std::vector<int> watch = BallsIn(GroupBox(gr, t_b));  // the grid holds no members
    auto run = std::make_unique<Window>(RunWindow(g, t_b, &watch));
    Group& gg = groups_[static_cast<size_t>(g)];
    if (run->r.stopped_by_event) t_b = run->r.final_state.t;
    gg.t_b = t_b;
    gg.box = GroupBox(gg, t_b);
    gg.run = std::move(run);
    gg.tick = ++tick_;
    ++gg.ver;
    Schedule({gg.t_b, Kind::kGroup, g, -1, gg.ver, 0, 0});
    break;
  }
  for (const int h : replan) {
    if (groups_[static_cast<size_t>(h)].alive) Plan(h, t);
  }
}

// Starts a group of `balls` (on their chains) at t.
void Runner::FormGroup(const std::vector<int>& balls, double t) {
  const int g = static_cast<int>(groups_.size());
  groups_.push_back(Group{});
  groups_.back().t_a = t;
  for (const int b : balls) Join(g, b, t);
  ++res_.stats.groups;
  Plan(g, t);
}

// At a window's end the group splits into its touching components (gap within kJoinGap):
// members touching no other leave on chains, the first component goes on as g, the others as
// new groups.
void Runner::EndWindow(int g, double t) {
  Advance(g, t);
  Group gr = std::move(groups_[static_cast<size_t>(g)]);
  const size_t k = gr.members.size();
  std::vector<int> comp(k, -1);
  int nc = 0;
  for (size_t s = 0; s < k; ++s) {
    if (comp[s] >= 0) continue;
    std::vector<size_t> todo{s};
    comp[s] = nc;
    while (!todo.empty()) {
      const size_t a = todo.back();
      todo.pop_back();
      for (size_t b = 0; b < k; ++b) {
        if (comp[b] >= 0 || !MayCollide(gr.members[a], gr.members[b])) continue;
        if (Gap(gr.members[a], gr.states[a].p_WBcm, gr.members[b], gr.states[b].p_WBcm) <=
            kJoinGap) {
          comp[b] = nc;
          todo.push_back(b);
        }
      }
    }
    ++nc;
  }
  std::vector<Group> parts(static_cast<size_t>(nc));
  for (size_t m = 0; m < k; ++m) {
    Group& p = parts[static_cast<size_t>(comp[m])];
    p.members.push_back(gr.members[m]);
    p.states.push_back(gr.states[m]);
    p.modes.push_back(gr.modes[m]);
  }
  std::vector<int> planned;
  int slot = g;
  for (Group& p : parts) {
    if (p.members.size() == 1) {
      const int b = p.members[0];
      const BodyState& bs = p.states[0];
      const auto bu = static_cast<size_t>(b);
      group_of_[bu] = -1;
      booked_until_[bu] = t;
      BeginChain(b, Restart(b, t, bs.p_WBcm, bs.v_WBcm_W, bs.q_WB * bs.w_WB_B, bs.q_WB));
      continue;
    }
    p.t_a = p.t_b = t;
    p.span = gr.span;
    p.ver = gr.ver;
    if (slot < 0) {
      slot = static_cast<int>(groups_.size());
      groups_.emplace_back();
      ++res_.stats.groups;
    }
    for (const int b : p.members) group_of_[static_cast<size_t>(b)] = slot;
    p.box = HereBox(p);
    groups_[static_cast<size_t>(slot)] = std::move(p);
    planned.push_back(slot);
    slot = -1;
  }
  if (planned.empty() || planned[0] != g) {
    groups_[static_cast<size_t>(g)] = Group{};
    groups_[static_cast<size_t>(g)].alive = false;
  }
  for (const int h : planned) {
    if (groups_[static_cast<size_t>(h)].alive && groups_[static_cast<size_t>(h)].t_b <= t)
      Plan(h, t);
  }
}

// Whether ball o's chain comes within rho of the point p during [t, tb]: on each segment
// |r(τ) - p|² - rho² is a quartic in time, as in TestPair.
bool ChainNear(const Chain& c, double t, double tb, const Vec3& p, double rho) {
  tb = std::min(tb, c.known_until);
  for (int k = 0; k < c.count; ++k) {
    const Segment& seg = c.seg[static_cast<size_t>(k)];
    const double s0 = std::max(t, seg.t0), s1 = std::min(tb, seg.end());
    if (s1 < s0) continue;
    const Vec3 d0 = seg.Pos(s0) - p, d1 = seg.Vel(s0), d2 = 0.5 * seg.a;
    const Poly f{(d0.norm() - rho) * (d0.norm() + rho), 2.0 * d0.dot(d1),
                 d1.squaredNorm() + 2.0 * d0.dot(d2), 2.0 * d1.dot(d2), d2.squaredNorm()};
    if (f[0] <= 0.0 || std::isfinite(FirstEntry(f, 0.0, s1 - s0))) return true;
  }
  return false;
}

// Whether outside ball o, on its chain from t, may touch a member of g before g.t_b: member m
// stays within σ (t_b - t_o) + ε of its origin, so o must come within that and both radii
// (and kJoinGap) of the origin.
bool Runner::MayReach(const Group& g, int o, double t) const {
  const Chain& c = chain_[static_cast<size_t>(o)];
  const double reach = g.speed * (g.t_b - g.t_o) + kReach + kJoinGap;
  for (size_t m = 0; m < g.members.size(); ++m) {
    if (!MayCollide(o, g.members[m])) continue;
    const double rho =
        reach + balls_[static_cast<size_t>(o)].R + balls_[static_cast<size_t>(g.members[m])].R;
    if (ChainNear(c, t, g.t_b, g.origin[m], rho)) return true;
  }
  return false;
}

// Outside balls whose new boxes reach a group: the group is brought to now (a cut) and
// re-planned (joining them, or ending its window before they can reach it).
void Runner::CheckGroups(double t) {
  while (!renewed_.empty()) {
    const int i = renewed_.back();
    renewed_.pop_back();
    if (group_of_[static_cast<size_t>(i)] >= 0) continue;
    for (size_t g = 0; g < groups_.size(); ++g) {
      // A group planned after the ball's box was renewed has seen it.
      if (!groups_[g].alive || groups_[g].tick > renew_tick_[static_cast<size_t>(i)] ||
          !groups_[g].box.Overlaps(box_[static_cast<size_t>(i)]))
        continue;
      if (!MayReach(groups_[g], i, t)) continue;
      Advance(static_cast<int>(g), t);
      Plan(static_cast<int>(g), t);
      if (group_of_[static_cast<size_t>(i)] >= 0) break;
    }
  }
}

// One event off the queue (stale ones, whose ball has a new chain, are dropped).
void Runner::Handle(const Event& e) {
  const size_t n = balls_.size();
  const auto iu = static_cast<size_t>(std::max(e.i, 0));
  switch (e.kind) {
    case Kind::kSample: {
      for (size_t g = 0; g < groups_.size(); ++g) {
        if (groups_[g].alive) Advance(static_cast<int>(g), e.t);
      }
      for (size_t i = 0; i < n; ++i) {
        if (group_of_[i] < 0) CloseSegment(static_cast<int>(i), e.t);
      }
      res_.samples.push_back(StateAt(e.t));
      break;
    }
    case Kind::kPhase: {
      if (e.ver_i != ver_[iu]) break;
      const Chain& c = chain_[iu];
      // The segment ending at e.t and the one after it.
      int k = 0;
      while (k + 1 < c.count && c.seg[static_cast<size_t>(k)].end() != e.t) ++k;
      const Segment& s0 = c.seg[static_cast<size_t>(k)];
      const Segment& s1 = c.seg[static_cast<size_t>(std::min(k + 1, c.count - 1))];
      ++res_.stats.phase_events;
      ContactEvent ev;
      ev.t = e.t;
      ev.point = balls_[iu].point;
      ev.from = ModeOfPhase(s0.phase);
      ev.to = ModeOfPhase(s1.phase);
      ev.reason = s0.phase == Phase::kSliding ? ContactEventReason::kSlipStopped
                                              : ContactEventReason::kRollingStopped;
      ev.held_to = s1.phase == Phase::kRest && balls_[iu].mu_r > 0.0;
      res_.contact_events.push_back(ev);
      break;
    }
    case Kind::kHorizon: {
      if (e.ver_i != ver_[iu] || horizon_[iu] != e.t) break;
      RenewBox(e.i, e.t);
      break;
    }
    case Kind::kLanding: {
      if (e.ver_i != ver_[iu]) break;
      const Segment& s = chain_[iu].At(e.t);
      const double vn = w_.n.dot(s.Vel(e.t));
      Impact(e.t, e.i, -1);
      if (-vn <= w_.tol.resting_speed && ver_[iu] == e.ver_i) {
        // Set down without an impact: the ball continues on the plane.
        CloseSegment(e.i, e.t);
        Vec3 v = s.Vel(e.t);
        v -= w_.n.dot(v) * w_.n;
        const Quat q = ChainOrient(chain_[iu], e.t);
        const Segment next =
            StartSegment(balls_[iu], w_, e.t, s.Pos(e.t), v, s.Omega(e.t), q, true);
        res_.contact_events.push_back({e.t, balls_[iu].point, ContactMode::kSeparated,
                                       ModeOfPhase(next.phase), ContactEventReason::kTouchDown});
        BeginChain(e.i, next);
      }
      break;
    }
    case Kind::kGroup: {
      const Group& g = groups_[static_cast<size_t>(e.i)];
      if (g.alive && g.ver == e.ver_i) EndWindow(e.i, e.t);
      break;
    }
    case Kind::kPair: {
      if (e.ver_i != ver_[iu] || e.ver_j != ver_[static_cast<size_t>(e.j)]) break;
      Impact(e.t, e.i, e.j);
      break;
    }
  }
}

// The balls' first segments: a ball below the plane is refused, and what the rules of contact
// adjust in the given state is said (warnings); the initial modes are recorded.
std::vector<Segment> Runner::InitialSegments(const State& initial) {
  const size_t n = balls_.size();
  const double t0 = initial.t;
  std::vector<Segment> first(n);
  for (size_t i = 0; i < n; ++i) {
    const Ball& b = balls_[i];
    const BodyState& bs = initial.bodies[i];
    const std::string& name = model_.body(b.body).name();
    const double gap = w_.n.dot(bs.p_WBcm - w_.p0) - b.R;
    if (gap < -w_.tol.gap) {
      throw InputError(fmt::format("body '{}' starts {} m into the plane", name, -gap));
    }
    const Vec3 om = bs.q_WB * bs.w_WB_B;
    first[i] = Restart(static_cast<int>(i), t0, bs.p_WBcm, bs.v_WBcm_W, om, bs.q_WB);
    if (first[i].phase != Phase::kFlight) {
      const double vn = w_.n.dot(bs.v_WBcm_W);
      if (vn != 0.0) {
        res_.warnings.push_back(fmt::format(
            "body '{}': its normal velocity {:.3g} m/s (within resting_speed) was set to 0: it "
            "starts on the plane",
            name, vn));
      }
      const double moved = (first[i].w0 - om).norm() * b.R;
      if (moved > 1e-14 * (bs.v_WBcm_W.norm() + om.norm() * b.R)) {
        res_.warnings.push_back(fmt::format(
            "body '{}': its slip of {:.3g} m/s (within stick_speed) was taken as rolling: its "
            "angular velocity along the plane was set to n × v / R",
            name, moved));
      }
    }
    res_.contact_events.push_back({t0, b.point, ContactMode::kSeparated,
                                   ModeOfPhase(first[i].phase), ContactEventReason::kInitial});
  }
  return first;
}

SphereEventResult Runner::Run(const State& initial) {
  ReadModel();
  ValidateState(model_, initial);
  if (!(options_.t_end >= initial.t)) {
    throw InputError(
        fmt::format("t_end = {} s is before the initial time {} s", options_.t_end, initial.t));
  }
  if (!std::isfinite(options_.t_end)) {
    throw InputError(fmt::format("t_end = {} s must be finite", options_.t_end));
  }
  if (!(options_.output_interval >= 0.0) || !std::isfinite(options_.output_interval)) {
    throw InputError(
        fmt::format("output_interval = {} s must be >= 0 (0: first and last state only)",
                    options_.output_interval));
  }
  if (options_.collide_all_pairs) {
    // The coefficients as a contact would have them (ValidateContactSpec names the rule).
    ContactSpec law;
    law.name = "pair_law";
    law.shape = ContactShape::kSphereSphere;
    law.radius = law.other_radius = R_max_;
    law.body = 0;
    law.other_body = model_.num_bodies() > 1 ? 1 : 0;
    law.restitution = options_.pair_law.restitution;
    law.mu_s = options_.pair_law.mu_s;
    law.mu_k = options_.pair_law.mu_k;
    law.restitution_law = options_.pair_law.law;
    ValidateContactSpec(law);
  }
  const auto n = balls_.size();
  chain_.resize(n);
  ver_.assign(n, 0);
  box_.assign(n, Box{});
  horizon_.assign(n, 0.0);
  cells_of_.assign(n, {0, -1, 0, -1});
  stamp_.assign(n, 0);
  booked_until_.assign(n, initial.t);
  group_of_.assign(n, -1);
  renew_tick_.assign(n, 0);
  ledger_ = initial;
  ledger_.contacts.assign(static_cast<size_t>(model_.num_contact_points()), ContactPointState{});
  const double t0 = initial.t;
  const std::vector<Segment> first = InitialSegments(initial);
  for (size_t i = 0; i < n; ++i) chain_[i] = MakeChain(balls_[i], w_, first[i]);
  CheckNoOverlap(initial);
  for (size_t i = 0; i < n; ++i) {
    const Chain& c = chain_[i];
    const auto ii = static_cast<int>(i);
    for (int k = 0; k + 1 < c.count; ++k) {
      Schedule({c.seg[static_cast<size_t>(k)].end(), Kind::kPhase, ii, -1, 0, 0, 0});
    }
    if (std::isfinite(c.known_until)) Schedule({c.known_until, Kind::kLanding, ii, -1, 0, 0, 0});
  }
  for (size_t i = 0; i < n; ++i) RenewBox(static_cast<int>(i), t0);
  res_.samples.push_back(StateAt(t0));
  if (options_.output_interval > 0.0) {
    for (long k = 1;; ++k) {
      const double ts = t0 + static_cast<double>(k) * options_.output_interval;
      if (ts >= options_.t_end) break;
      Schedule({ts, Kind::kSample, -1, -1, 0, 0, 0});
    }
  }
  while (!queue_.empty()) {
    const Event e = queue_.top();
    if (e.t > options_.t_end) break;
    queue_.pop();
    Handle(e);
    CheckGroups(e.t);
    if (options_.on_progress) options_.on_progress(e.t);
  }
  for (size_t g = 0; g < groups_.size(); ++g) {
    if (groups_[g].alive) Advance(static_cast<int>(g), options_.t_end);
  }
  for (size_t i = 0; i < n; ++i) {
    if (group_of_[i] < 0) CloseSegment(static_cast<int>(i), options_.t_end);
  }
  res_.final_state = StateAt(options_.t_end);
  if (res_.samples.back().t != options_.t_end) res_.samples.push_back(res_.final_state);
  // The run's own check: the energy balance, each term from its closed form.
  const auto energy = [&](const State& s) {
    double e = 0.0;
    for (size_t i = 0; i < n; ++i) {
      const Ball& b = balls_[i];
      const BodyState& bs = s.bodies[i];
      e += 0.5 * b.m * bs.v_WBcm_W.squaredNorm() + 0.5 * b.I * bs.w_WB_B.squaredNorm() -
           b.m * w_.g_W.dot(bs.p_WBcm);
    }
    return e;
  };
  res_.energy.initial = energy(initial);
  res_.energy.final = energy(res_.final_state);
  res_.energy.residual = res_.energy.final - (res_.energy.initial + res_.energy.friction +
                                              res_.energy.rolling + res_.energy.impacts);
  return res_;
}

}  // namespace

SphereEventResult SimulateSphereEvents(const Model& model, const State& initial,
                                       const SphereEventOptions& options) {
  Runner runner(model, options);
  return runner.Run(initial);
}

}  // namespace chasles
