// Pressing groups: balls that press on each other, run by the hybrid engine in windows no
// outside ball can reach (docs/contact.md, "Event-driven spheres").
#include "integrate/internal/sphere_runner.h"

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/model/forces.h"

namespace chasles::sphere_events_detail {

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
  try {
    w.r = RunGroup(*w.sub, st, so);
  } catch (const InputError& e) {
    RethrowForWholeModel(gr.members, e);
  }
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

}  // namespace chasles::sphere_events_detail
