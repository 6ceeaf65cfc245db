#include "chasles/integrate/simulate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>

#include <fmt/format.h>

#include "chasles/dynamics/constraint_solve.h"
#include "chasles/error.h"
#include "integrate/internal/event_root.h"
#include "integrate/internal/free_body_run.h"
#include "integrate/internal/hybrid.h"
#include "integrate/internal/islands.h"

namespace chasles {
namespace {

void Validate(const Model& model, const State& initial, const SimulationOptions& o) {
  ValidateState(model, initial);
  if (!std::isfinite(o.t_end) || !(o.t_end > initial.t)) {
    throw InputError(
        fmt::format("simulation end time {:.9g} s must be after the start time "
                    "{:.9g} s",
                    o.t_end, initial.t));
  }
  if (!(o.output_interval >= 0.0) || !std::isfinite(o.output_interval)) {
    throw InputError(
        fmt::format("output interval {:.6g} s must be >= 0 (0: first and last "
                    "state only)",
                    o.output_interval));
  }
  if (o.integrator != IntegratorKind::kDormandPrince5) {
    if (!(o.fixed_step > 0.0) || !std::isfinite(o.fixed_step)) {
      throw InputError(fmt::format("fixed step {:.6g} s must be positive", o.fixed_step));
    }
    if (!o.events.empty()) {
      throw InputError(
          "events are located on the adaptive integrator's dense output; choose the "
          "Dormand-Prince integrator for a run with events");
    }
  }
  for (size_t i = 0; i < o.events.size(); ++i) {
    const EventSpec& e = o.events[i];
    const ErrorElement element{ErrorElement::Kind::kEvent, static_cast<int>(i)};
    if (!e.g && !e.on_mode_change) {
      throw InputError(fmt::format("event '{}' has no event function", e.name), element);
    }
    if (!e.g && model.num_contacts() == 0) {
      throw InputError(
          fmt::format("event '{}' watches contact modes, but the model has no contacts", e.name),
          element);
    }
  }
  if (!(o.threads >= 1)) {
    throw InputError(fmt::format("threads is {}; it must be >= 1", o.threads));
  }
  if (!(o.contact.yield_changes >= 0) || !(o.contact.yield_window >= 0.0) ||
      !std::isfinite(o.contact.yield_window)) {
    throw InputError(fmt::format(
        "the bound on regime changes ({} changes within {:.6g} s) must be a count >= 0 and a "
        "finite span >= 0 (0 changes: none)",
        o.contact.yield_changes, o.contact.yield_window));
  }
  if (!(o.event_time_tolerance > 0.0)) {
    throw InputError("event time tolerance must be positive (e.g. 1e-12 s)");
  }
}

class Sampler {
 public:
  Sampler(const SimulationOptions& o, SimulationResult& r, double t0) : o_(o), r_(r), t0_(t0) {}
  void Emit(const State& s) {
    if (o_.on_sample) o_.on_sample(s);
    if (o_.store_samples) r_.samples.push_back(s);
  }
  /// Next output time after sample k (k counts from t0).
  double OutputTime(long long k) const { return t0_ + static_cast<double>(k) * o_.output_interval; }

 private:
  const SimulationOptions& o_;
  SimulationResult& r_;
  double t0_;
};

// The events that cross zero in the last step, located on the dense output, earliest first;
// the run stops at the first kStop one (returns its time; +inf when none stops it).
double RecordEvents(const Model& model, const SimulationOptions& o, Integrator& integ,
                    std::vector<double>& g_prev, SimulationResult& r, State& scratch) {
  struct Hit {
    double t;
    size_t e;
  };
  const size_t ne = o.events.size();
  const double t0 = integ.t_previous(), t1 = integ.t();
  std::vector<Hit> hits;
  std::vector<double> g_new(ne);
  for (size_t e = 0; e < ne; ++e) {
    g_new[e] = o.events[e].g(model, integ.state());
    if (!internal::Crosses(o.events[e].direction, g_prev[e], g_new[e])) continue;
    auto g = [&](double t) {
      integ.Interpolate(t, scratch);
      return o.events[e].g(model, scratch);
    };
    hits.push_back(
        {internal::LocateEventTime(g, t0, g_prev[e], t1, g_new[e], o.event_time_tolerance), e});
  }
  g_prev = g_new;
  std::sort(hits.begin(), hits.end(), [](const Hit& a, const Hit& b) { return a.t < b.t; });
  for (const Hit& h : hits) {
    EventRecord rec;
    rec.event = static_cast<int>(h.e);
    rec.name = o.events[h.e].name;
    rec.t = h.t;
    integ.Interpolate(h.t, rec.state);
    r.events.push_back(std::move(rec));
    if (o.events[h.e].action == EventAction::kStop) return h.t;
  }
  return std::numeric_limits<double>::infinity();
}

// A model without contacts: one integrator (MakeIntegrator) stepped to the end or to a
// stopping event. A fixed-step integrator is stepped to each output time in turn (it lands on
// it); a dense one to the end, with the outputs and events taken from its dense output.
SimulationResult RunSmooth(const Model& model, const State& initial, const SimulationOptions& o) {
  SimulationResult r;
  Sampler sampler(o, r, initial.t);
  std::unique_ptr<Integrator> integ = MakeIntegrator(model, o, initial.t);
  integ->Initialize(initial);
  sampler.Emit(integ->state());
  std::vector<double> g_prev(o.events.size());
  for (size_t e = 0; e < o.events.size(); ++e) g_prev[e] = o.events[e].g(model, integ->state());
  long long k = 1;
  State scratch = integ->state();
  while (integ->t() < o.t_end) {
    const bool to_output = !integ->has_dense_output() && o.output_interval > 0.0;
    integ->Step(to_output ? std::min(sampler.OutputTime(k), o.t_end) : o.t_end);
    if (o.on_step) o.on_step(integ->t());
    const double t_stop = RecordEvents(model, o, *integ, g_prev, r, scratch);
    // Output samples up to the end of the step (or the stop).
    const double t_out_end = std::min(integ->t(), t_stop);
    if (o.output_interval > 0.0) {
      while (sampler.OutputTime(k) <= t_out_end && sampler.OutputTime(k) < o.t_end) {
        integ->Interpolate(sampler.OutputTime(k), scratch);
        sampler.Emit(scratch);
        ++k;
      }
    }
    if (std::isfinite(t_stop)) {
      r.final_state = r.events.back().state;
      r.stopped_by_event = true;
      sampler.Emit(r.final_state);
      r.stats = integ->stats();
      return r;
    }
  }
  r.final_state = integ->state();
  sampler.Emit(r.final_state);
  r.stats = integ->stats();
  return r;
}

}  // namespace

const char* ContactEventReasonName(ContactEventReason reason) {
  switch (reason) {
    case ContactEventReason::kInitial:
      return "initial";
    case ContactEventReason::kTouchDown:
      return "touch-down";
    case ContactEventReason::kLiftOff:
      return "lift-off";
    case ContactEventReason::kSlipStopped:
      return "slip stopped";
    case ContactEventReason::kFrictionLimit:
      return "friction limit";
    case ContactEventReason::kRollingStopped:
      return "rolling stopped";
    case ContactEventReason::kRollingLimit:
      return "rolling resistance limit";
    case ContactEventReason::kAccumulation:
      return "bounces accumulated";
    case ContactEventReason::kCollision:
      return "collision";
    case ContactEventReason::kOther:
      return "re-selection";
    case ContactEventReason::kImpulse:
      return "impulse";
    case ContactEventReason::kEngineSwitch:
      return "engine switch";
    case ContactEventReason::kTimeStep:
      return "time step";
  }
  return "unknown";
}

std::vector<ContactModeInterval> CalcModeTimeline(const SimulationResult& result, int point) {
  std::vector<ContactModeInterval> out;
  const double t_first = result.samples.empty() ? result.final_state.t : result.samples.front().t;
  for (const ContactEvent& e : result.contact_events) {
    if (e.point != point) continue;
    if (!out.empty()) {
      if (out.back().mode == e.to) continue;  // a re-selection that kept the mode
      out.back().t_end = e.t;
    }
    out.push_back({out.empty() ? t_first : e.t, result.final_state.t, e.to, e.reason});
  }
  return out;
}

SimulationResult Simulate(const Model& model, const State& initial,
                          const SimulationOptions& options) {
  Validate(model, initial, options);
  RunPathChoice path = ChooseRunPath(model, options);
  SimulationResult r;
  switch (path.path) {
    case RunPath::kIslands:
      r = internal::RunIslands(model, initial, options);
      break;
    case RunPath::kHybrid:
      r = internal::RunHybrid(model, initial, options);
      r.islands.count = path.islands;
      r.islands.reason = path.one_system;
      break;
    case RunPath::kFreeBodyBatch:
      r = internal::RunFreeBodyBatch(model, initial, options);
      break;
    default: {
      // A constrained model starts on its constraints: the initial state is projected
      // (positions, then velocities), so the first sample is the state actually integrated.
      State start = initial;
      if (model.num_constraints() > 0 && options.integrator != IntegratorKind::kEnergyMomentum) {
        Data data = MakeData(model);
        ProjectOntoConstraints(model, start, data);
      }
      r = RunSmooth(model, start, options);
    }
  }
  r.run_path = std::move(path);
  return r;
}

}  // namespace chasles
