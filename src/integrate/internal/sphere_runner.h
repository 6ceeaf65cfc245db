#pragma once
// The event-driven sphere engine's parts (docs/contact.md, "Event-driven spheres"), shared by
// the files that implement it by concept: a ball's closed-form motion (sphere_motion.cpp), the
// times two balls meet (sphere_pair_times.cpp), the broadphase grid (sphere_broadphase.cpp),
// impacts (sphere_impacts.cpp), pressing groups (sphere_groups.cpp), and the event queue and
// the run (sphere_events.cpp).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <queue>
#include <unordered_map>
#include <utility>
#include <vector>

#include "chasles/dynamics/impact.h"
#include "chasles/integrate/sphere_events.h"
#include "chasles/math/quaternion.h"

namespace chasles::sphere_events_detail {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

enum class Phase { kFlight, kSliding, kRolling, kRest };

/// The contact mode of a ball's plane point in each phase.
ContactMode ModeOfPhase(Phase p);

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
                     const Vec3& om, const Quat& q, bool on_plane, bool force_roll = false);

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
Quat ChainOrient(const Chain& c, double t);
// The chain a ball follows from the segment `first`: its continuations until it rests or lands.
Chain MakeChain(const Ball& b, const World& w, const Segment& first);

// p(σ) = Σ c_k σ^k, degree <= 4.
using Poly = std::array<double, 5>;
// The first σ in [lo, hi] at which f = |d|² - S² enters f <= 0 (the balls touch, approaching):
// f(lo) <= 0 with f falling at lo, or a crossing from f > 0. Infinity if none.
double FirstEntry(const Poly& f, double lo, double hi);

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
inline void Extend(double x0, double v, double a, double ta, double tb, double& lo, double& hi) {
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

inline std::uint64_t PairKey(int a, int b) {
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
  // Rethrows `e` from a run on SubModel(members, ...) naming its element in the whole Model:
  // a member, a gravity element, a member's plane contact or point; no element for a
  // ball-ball contact or a window's own event.
  [[noreturn]] void RethrowForWholeModel(const std::vector<int>& members,
                                         const InputError& e) const;
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

}  // namespace chasles::sphere_events_detail
