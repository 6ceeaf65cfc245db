#include "chasles/integrate/islands.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <typeinfo>
#include <utility>

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/integrate/parallel.h"
#include "chasles/model/string_constraint.h"
#include "integrate/internal/hybrid.h"
#include "integrate/internal/islands.h"

// Islands of the hybrid run. Why they can run apart: the Newton-Euler equations of each body
// (chapter 8.3, m v̇ = F, I ẇ + w × I w = M about Bcm) are coupled to another body's only
// through a force element acting on both, a constraint row J holding both (Jᵀλ) or a contact
// between them; the world plane and a field acting on each body alone (gravity: m g at Bcm)
// couple none. Without such a link the state vector splits into blocks whose derivatives read
// only their own block, and every event function (gap, normal force, slip, friction margin of a
// point; a string's slack or tension) reads only its own island's bodies. Each block is then
// the same ODE with the same events on its own, and its steps (error-controlled on its own
// components only) and restarts need not follow the others'.

namespace chasles {
namespace {

// Disjoint sets of bodies (union by size, path halving).
class UnionFind {
 public:
  explicit UnionFind(int n) : parent_(static_cast<size_t>(n)), size_(static_cast<size_t>(n), 1) {
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
  void Link(BodyIndex a, BodyIndex b) {
    if (a == kWorld || b == kWorld) return;
    int ra = Find(a), rb = Find(b);
    if (ra == rb) return;
    if (size_[static_cast<size_t>(ra)] < size_[static_cast<size_t>(rb)]) std::swap(ra, rb);
    parent_[static_cast<size_t>(rb)] = ra;
    size_[static_cast<size_t>(ra)] += size_[static_cast<size_t>(rb)];
  }

 private:
  std::vector<int> parent_, size_;
};

}  // namespace

IslandPartition FindIslands(const Model& model) {
  const int n = model.num_bodies();
  UnionFind sets(n);
  for (int c = 0; c < model.num_constraints(); ++c) {
    const Constraint& con = model.constraint(c);
    sets.Link(con.parent(), con.child());
    // A string also moves the bodies that carry its pulleys.
    if (const auto* s = dynamic_cast<const StringConstraint*>(&con)) {
      for (const StringPulley& p : s->pulleys()) sets.Link(p.body, con.child());
    }
  }
  for (int k = 0; k < model.num_contacts(); ++k) {
    sets.Link(model.contact(k).body(), model.contact(k).other_body());
  }
  for (int f = 0; f < model.num_force_elements(); ++f) {
    const std::vector<BodyIndex> bodies = model.force_element(f).bodies();
    for (size_t i = 1; i < bodies.size(); ++i) sets.Link(bodies[0], bodies[i]);
  }
  IslandPartition p;
  p.island_of_body.assign(static_cast<size_t>(n), -1);
  std::vector<int> island_of_root(static_cast<size_t>(n), -1);
  for (BodyIndex b = 0; b < n; ++b) {
    int& island = island_of_root[static_cast<size_t>(sets.Find(b))];
    if (island < 0) {
      island = static_cast<int>(p.bodies.size());
      p.bodies.emplace_back();
    }
    p.bodies[static_cast<size_t>(island)].push_back(b);
    p.island_of_body[static_cast<size_t>(b)] = island;
  }
  return p;
}

std::string IslandObstacle(const Model& model) {
  std::vector<BodyIndex> identity(static_cast<size_t>(model.num_bodies()));
  std::iota(identity.begin(), identity.end(), 0);
  for (int f = 0; f < model.num_force_elements(); ++f) {
    if (!model.force_element(f).Renumbered(identity)) {
      return fmt::format(
          "force element '{}' evaluates user functions of the whole state, which may read any "
          "body",
          model.force_element(f).name());
    }
  }
  for (int c = 0; c < model.num_constraints(); ++c) {
    if (!model.constraint(c).Renumbered(identity)) {
      return fmt::format("constraint '{}' ({}) cannot be given to an island",
                         model.constraint(c).name(), model.constraint(c).kind());
    }
  }
  return "";
}

IslandSplit::IslandSplit(const Model& model, IslandPartition partition)
    : model_(model), partition_(std::move(partition)) {
  local_.assign(static_cast<size_t>(model.num_bodies()), kWorld);
  for (const std::vector<BodyIndex>& bodies : partition_.bodies) {
    for (size_t i = 0; i < bodies.size(); ++i) {
      local_[static_cast<size_t>(bodies[i])] = static_cast<BodyIndex>(i);
    }
  }
  contents_.resize(partition_.bodies.size());
  for (int f = 0; f < model.num_force_elements(); ++f) {
    const std::vector<BodyIndex> bodies = model.force_element(f).bodies();
    if (bodies.empty()) {
      for (Contents& c : contents_) c.forces.push_back(f);
    } else {
      contents_[IslandOf(bodies[0])].forces.push_back(f);
    }
  }
  for (int c = 0; c < model.num_constraints(); ++c) {
    contents_[IslandOf(model.constraint(c).child())].constraints.push_back(c);
  }
  for (int k = 0; k < model.num_contacts(); ++k) {
    Contents& c = contents_[IslandOf(model.contact(k).body())];
    c.contacts.push_back(k);
    for (int q = 0; q < model.contact(k).num_points(); ++q) {
      c.points.push_back(model.contact_point_offset(k) + q);
    }
  }
}

IslandModel IslandSplit::Build(int i) const {
  const Contents& contents = contents_[Index(i)];
  IslandModel im;
  Model& m = im.model;
  im.bodies = partition_.bodies[Index(i)];
  for (BodyIndex b : im.bodies) m.AddBody(model_.body(b).name(), model_.body(b).mass_properties());
  for (int f : contents.forces) m.AddForceElement(model_.force_element(f).Renumbered(local_));
  for (int c : contents.constraints) m.AddConstraint(model_.constraint(c).Renumbered(local_));
  for (int k : contents.contacts) {
    ContactSpec spec = model_.contact(k).spec();
    spec.body = local_[static_cast<size_t>(spec.body)];
    if (spec.other_body != kWorld) spec.other_body = local_[static_cast<size_t>(spec.other_body)];
    m.AddContact(spec);
  }
  im.forces = contents.forces;
  im.constraints = contents.constraints;
  im.contacts = contents.contacts;
  im.points = contents.points;
  return im;
}

State IslandSplit::Part(const IslandModel& im, int i, const State& whole) const {
  State s;
  s.t = whole.t;
  for (BodyIndex b : im.bodies) s.bodies.push_back(whole.bodies[static_cast<size_t>(b)]);
  if (!whole.force_integrals.empty()) {
    for (int f : im.forces) {
      const bool shared = model_.force_element(f).bodies().empty();
      s.force_integrals.push_back(shared && i > 0 ? ForceIntegrals{}
                                                  : whole.force_integrals[static_cast<size_t>(f)]);
    }
  }
  for (int c : im.constraints) {
    const auto g = static_cast<size_t>(c);
    if (!whole.constraint_work.empty()) s.constraint_work.push_back(whole.constraint_work[g]);
    if (!whole.constraint_modes.empty()) s.constraint_modes.push_back(whole.constraint_modes[g]);
  }
  if (!whole.contacts.empty()) {
    for (int q : im.points) s.contacts.push_back(whole.contacts[static_cast<size_t>(q)]);
  }
  return s;
}

void IslandSplit::ScatterMotion(const IslandModel& im, const State& part, State& whole) {
  for (size_t j = 0; j < part.bodies.size(); ++j) {
    whole.bodies[static_cast<size_t>(im.bodies[j])] = part.bodies[j];
  }
  for (size_t j = 0; j < part.contacts.size(); ++j) {
    whole.contacts[static_cast<size_t>(im.points[j])] = part.contacts[j];
  }
}

void IslandSplit::RethrowForWholeModel(const IslandModel& im, const InputError& e) {
  if (!e.element() || typeid(e) != typeid(InputError)) throw;
  ErrorElement global = *e.element();
  const auto local = static_cast<size_t>(global.index);
  switch (global.kind) {
    case ErrorElement::Kind::kBody:
    case ErrorElement::Kind::kInitialState:
      global.index = im.bodies[local];
      break;
    case ErrorElement::Kind::kForceElement:
      global.index = im.forces[local];
      break;
    case ErrorElement::Kind::kConstraint:
      global.index = im.constraints[local];
      break;
    case ErrorElement::Kind::kContact:
      global.index = im.contacts[local];
      break;
    case ErrorElement::Kind::kContactPoint:
      global.index = im.points[local];
      break;
    case ErrorElement::Kind::kEvent:  // every island watches all of the run's events
      break;
  }
  throw InputError(e.what(), global);
}

namespace internal {
namespace {

class IslandRun {
 public:
  IslandRun(const Model& model, const State& initial, const SimulationOptions& o,
            IslandPartition partition)
      : model_(model), initial_(initial), o_(o), split_(model, std::move(partition)) {}

  SimulationResult Run() {
    const size_t n = split_.partition().bodies.size();
    results_.resize(n);
    points_.resize(n);
    forces_.resize(n);
    constraints_.resize(n);
    std::vector<std::exception_ptr> errors(n);
    std::atomic<size_t> next{0};
    std::atomic<bool> failed{false};
    const auto work = [&] {
      for (size_t i = next++; i < n && !failed; i = next++) {
        try {
          RunIsland(i);
        } catch (...) {
          errors[i] = std::current_exception();
          failed = true;
        }
      }
    };
    const auto threads = static_cast<size_t>(std::max(1, o_.threads));
    // As many threads as the system starts (parallel.h); `work` catches its own exceptions.
    RunOnThreads(static_cast<int>(std::min(threads, n)), work);
    for (const std::exception_ptr& e : errors) {
      if (e) std::rethrow_exception(e);
    }
    const std::optional<size_t> first = FirstToYield();
    if (first) EndAtYield(*first);
    SimulationResult r = Merge();
    if (first) r.yielded = results_[*first].yielded;
    return r;
  }

 private:
  // The island that yielded first (ContactOptions::yield_changes: integrator auto), the lowest
  // index at equal times; none when no island yielded.
  std::optional<size_t> FirstToYield() const {
    std::optional<size_t> first;
    for (size_t i = 0; i < results_.size(); ++i) {
      if (!results_[i].yielded) continue;
      if (!first || results_[i].final_state.t < results_[*first].final_state.t) first = i;
    }
    return first;
  }

  // Island `first` yielded at t_y: the whole model is handed over there, so every island that
  // ran on past t_y runs again from its start to t_y exactly. Its run up to t_y is the same
  // computation as before (no island sees another), so only the last step changes, cut to end
  // at t_y. Each keeps the samples the yielding island has: the grid times up to t_y (the final
  // state at t_y is a sample only where t_y is itself a grid time, as in one system).
  void EndAtYield(size_t first) {
    const double t_y = results_[first].final_state.t;
    const size_t samples = results_[first].samples.size();
    std::vector<size_t> rerun;
    for (size_t i = 0; i < results_.size(); ++i) {
      if (i != first && results_[i].final_state.t > t_y) rerun.push_back(i);
    }
    std::vector<std::exception_ptr> errors(rerun.size());
    std::atomic<size_t> next{0};
    const auto work = [&] {
      for (size_t k = next++; k < rerun.size(); k = next++) {
        try {
          RunIsland(rerun[k], t_y);
        } catch (...) {
          errors[k] = std::current_exception();
        }
      }
    };
    const auto threads = static_cast<size_t>(std::max(1, o_.threads));
    RunOnThreads(static_cast<int>(std::min(threads, std::max<size_t>(rerun.size(), 1))), work);
    for (const std::exception_ptr& e : errors) {
      if (e) std::rethrow_exception(e);
    }
    for (size_t i = 0; i < results_.size(); ++i) {
      if (i == first) continue;
      std::vector<State>& x = results_[i].samples;
      if (x.size() > samples) x.resize(samples);
      // Handed over with the rest of the model: neither yielded nor ended by itself.
      results_[i].yielded.reset();
    }
  }

  void RunIsland(size_t i, double t_end = std::numeric_limits<double>::quiet_NaN()) {
    const IslandModel im = split_.Build(static_cast<int>(i));
    const State initial = split_.Part(im, static_cast<int>(i), initial_);
    SimulationOptions o = o_;
    if (!std::isnan(t_end)) o.t_end = t_end;
    o.on_sample = nullptr;
    o.store_samples = true;
    o.islands = false;
    // The transition checks in their island form (ChooseRunPath splits a run with on_transition
    // only when it is given), on this island's own states.
    o.island_transition = nullptr;
    o.on_transition = nullptr;
    if (o_.island_transition) {
      o.on_transition =
          o_.island_transition(IslandView{static_cast<int>(i), &im.model, &initial, im.bodies,
                                          im.forces, im.constraints, im.points});
    }
    if (o_.on_step && o_.threads > 1) {
      o.on_step = [this](double t) {
        const std::lock_guard<std::mutex> lock(step_mutex_);
        o_.on_step(t);
      };
    }
    try {
      results_[i] = RunHybrid(im.model, initial, o);
    } catch (const InputError& e) {
      IslandSplit::RethrowForWholeModel(im, e);
    }
    points_[i] = im.points;
    forces_[i] = im.forces;
    constraints_[i] = im.constraints;
  }

  // The whole State from the islands' states `part(i)`.
  template <class Part>
  State Assemble(const Part& part) const {
    const IslandPartition& p = split_.partition();
    const size_t n = p.bodies.size();
    State s;
    s.t = part(0).t;
    s.bodies.resize(static_cast<size_t>(model_.num_bodies()));
    s.force_integrals.assign(static_cast<size_t>(model_.num_force_elements()), ForceIntegrals{});
    s.contacts.resize(static_cast<size_t>(model_.num_contact_points()));
    bool work = false, modes = false;
    for (size_t i = 0; i < n; ++i) {
      work = work || !part(i).constraint_work.empty();
      modes = modes || !part(i).constraint_modes.empty();
    }
    if (work) s.constraint_work.assign(static_cast<size_t>(model_.num_constraints()), 0.0);
    if (modes) s.constraint_modes.resize(static_cast<size_t>(model_.num_constraints()));
    for (size_t i = 0; i < n; ++i) {
      const State& x = part(i);
      if (x.t != s.t) throw std::logic_error("islands: the islands' sample times differ");
      for (size_t j = 0; j < x.bodies.size(); ++j) {
        s.bodies[static_cast<size_t>(p.bodies[i][j])] = x.bodies[j];
      }
      for (size_t j = 0; j < x.force_integrals.size(); ++j) {
        ForceIntegrals& F = s.force_integrals[static_cast<size_t>(forces_[i][j])];
        const ForceIntegrals& f = x.force_integrals[j];
        // Integrals of a sum over bodies: the islands' parts add up (island order).
        F.work += f.work;
        F.work_nonconservative += f.work_nonconservative;
        F.linear_impulse_W += f.linear_impulse_W;
        F.angular_impulse_Wo_W += f.angular_impulse_Wo_W;
      }
      const std::vector<int>& cons = constraints_[i];
      for (size_t j = 0; j < x.constraint_work.size(); ++j) {
        s.constraint_work[static_cast<size_t>(cons[j])] = x.constraint_work[j];
      }
      for (size_t j = 0; j < x.constraint_modes.size(); ++j) {
        s.constraint_modes[static_cast<size_t>(cons[j])] = x.constraint_modes[j];
      }
      for (size_t j = 0; j < x.contacts.size(); ++j) {
        s.contacts[static_cast<size_t>(points_[i][j])] = x.contacts[j];
      }
    }
    s.unlisted_contact_work = initial_.unlisted_contact_work;  // no island changes it
    return s;
  }

  SimulationResult Merge() {
    const IslandPartition& p = split_.partition();
    const size_t n = p.bodies.size();
    SimulationResult r;
    r.islands.split = true;
    r.islands.count = static_cast<int>(n);
    r.islands.bodies = p.bodies;
    const size_t num_samples = results_[0].samples.size();
    for (size_t i = 0; i < n; ++i) {
      if (results_[i].samples.size() != num_samples) {
        throw std::logic_error("islands: the islands' sample counts differ");
      }
    }
    for (size_t k = 0; k < num_samples; ++k) {
      State s = Assemble([&](size_t i) -> const State& { return results_[i].samples[k]; });
      if (o_.on_sample) o_.on_sample(s);
      if (o_.store_samples) r.samples.push_back(std::move(s));
    }
    r.final_state = Assemble([&](size_t i) -> const State& { return results_[i].final_state; });
    // Records in global time order; at equal times in island order, then each island's order
    // (stable sorts). The initial modes come first, by point (constraint), as in one system.
    r.contact_events.resize(static_cast<size_t>(model_.num_contact_points()));
    std::vector<ContactEvent> later;
    std::vector<ConstraintEvent> initial_strings;
    for (size_t i = 0; i < n; ++i) {
      SimulationResult& x = results_[i];
      const std::vector<int>& cons = constraints_[i];
      for (size_t e = 0; e < x.contact_events.size(); ++e) {
        ContactEvent c = x.contact_events[e];
        c.point = points_[i][static_cast<size_t>(c.point)];
        if (e < points_[i].size()) {
          r.contact_events[static_cast<size_t>(c.point)] = c;  // kInitial, one per point
        } else {
          later.push_back(c);
        }
      }
      for (ImpactRecord rec : x.impacts) {
        rec.point = points_[i][static_cast<size_t>(rec.point)];
        r.impacts.push_back(rec);
      }
      for (ConstraintEvent c : x.constraint_events) {
        c.constraint = cons[static_cast<size_t>(c.constraint)];
        (c.reason == ConstraintEventReason::kInitial ? initial_strings : r.constraint_events)
            .push_back(c);
      }
      r.warnings.insert(r.warnings.end(), x.warnings.begin(), x.warnings.end());
      r.stats.steps += x.stats.steps;
      r.stats.rejected_steps += x.stats.rejected_steps;
      r.stats.function_evaluations += x.stats.function_evaluations;
      r.islands.stats.push_back(x.stats);
    }
    const auto by_time = [](const auto& a, const auto& b) { return a.t < b.t; };
    std::stable_sort(later.begin(), later.end(), by_time);
    r.contact_events.insert(r.contact_events.end(), later.begin(), later.end());
    std::stable_sort(r.impacts.begin(), r.impacts.end(), by_time);
    std::stable_sort(r.constraint_events.begin(), r.constraint_events.end(), by_time);
    std::sort(initial_strings.begin(), initial_strings.end(),
              [](const ConstraintEvent& a, const ConstraintEvent& b) {
                return a.constraint < b.constraint;
              });
    r.constraint_events.insert(r.constraint_events.begin(), initial_strings.begin(),
                               initial_strings.end());
    return r;
  }

  const Model& model_;
  const State& initial_;
  const SimulationOptions& o_;
  const IslandSplit split_;
  std::vector<SimulationResult> results_;
  std::vector<std::vector<int>> points_, forces_, constraints_;
  std::mutex step_mutex_;
};

}  // namespace

SimulationResult RunIslands(const Model& model, const State& initial, const SimulationOptions& o) {
  return IslandRun(model, initial, o, FindIslands(model)).Run();
}

}  // namespace internal
}  // namespace chasles
