// Impacts of the event-driven spheres: the touching cluster, the hybrid engine's impact
// law on it, and the ledger of the works (docs/contact.md, "Event-driven spheres").
#include "integrate/internal/sphere_runner.h"

#include <optional>
#include <typeinfo>

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/model/forces.h"

namespace chasles::sphere_events_detail {

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

void Runner::RethrowForWholeModel(const std::vector<int>& members, const InputError& e) const {
  if (!e.element() || typeid(e) != typeid(InputError)) throw;
  const ErrorElement& local = *e.element();
  const auto k = static_cast<size_t>(local.index);
  std::optional<ErrorElement> whole;
  switch (local.kind) {
    case ErrorElement::Kind::kBody:
    case ErrorElement::Kind::kInitialState:
      whole = ErrorElement{local.kind, members[k], local.non_finite_output};
      break;
    case ErrorElement::Kind::kForceElement:
      whole = ErrorElement{local.kind, gravity_elements_[k], local.non_finite_output};
      break;
    case ErrorElement::Kind::kContact:
    case ErrorElement::Kind::kContactPoint:
      if (k < members.size()) {
        const int point = balls_[static_cast<size_t>(members[k])].point;
        whole = ErrorElement{
            local.kind,
            local.kind == ErrorElement::Kind::kContact ? model_.contact_of_point(point) : point,
            local.non_finite_output};
      }
      break;
    case ErrorElement::Kind::kConstraint:
    case ErrorElement::Kind::kEvent:
      break;
  }
  throw InputError(e.what(), whole);
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
  ImpactResult r;
  try {
    r = ResolveImpacts(sub, st, w_.tol);
  } catch (const InputError& e) {
    RethrowForWholeModel(cluster, e);
  }
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
    try {
      r = ResolveImpacts(sub, st, tol);
    } catch (const InputError& e) {
      RethrowForWholeModel(cluster, e);
    }
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
            throw InputError(
                fmt::format("bodies '{}' and '{}' start overlapping by {} m",
                            model_.body(static_cast<int>(i)).name(), model_.body(j).name(), -gap),
                ErrorElement{ErrorElement::Kind::kBody, static_cast<int>(i)});
          }
        }
      }
    }
  }
}

}  // namespace chasles::sphere_events_detail
