#include "integrate/internal/hybrid.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <functional>
#include <limits>
#include <memory>
#include <utility>

#include <fmt/format.h>

#include "chasles/dynamics/constraint_modes.h"
#include "chasles/dynamics/constraint_solve.h"
#include "chasles/dynamics/contact_projection.h"
#include "chasles/dynamics/contact_solve.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/error.h"
#include "integrate/internal/event_root.h"
#include "integrate/internal/ode.h"

namespace chasles::internal {
namespace {

// One scalar event function of one contact point in its current mode; each falls through
// zero at its transition (docs/contact.md, "Events"). kStringGap and kStringTension are those
// of a constraint that can let go (a string): its slack g = L0 - L while slack, its tension
// while taut (docs/constraints.md, "Strings that go slack").
enum class Fn {
  kGap,
  kNormalForce,
  kSlip,
  kFrictionMargin,
  kRolling,
  kRollingMargin,
  kStringGap,
  kStringTension
};

// A gap closes like a contact's: the same location logic (closest approach, short flights).
bool IsGap(Fn f) {
  return f == Fn::kGap || f == Fn::kStringGap;
}
bool IsString(Fn f) {
  return f == Fn::kStringGap || f == Fn::kStringTension;
}

struct ContactFn {
  int point;  // contact point, or constraint for the string functions
  Fn fn;
  ContactEventReason reason;
};

std::vector<ContactFn> EventFunctions(const Model& model, const State& s) {
  std::vector<ContactFn> fns;
  for (int p = 0; p < model.num_contact_points(); ++p) {
    const ContactPointState& ps = s.contacts[static_cast<size_t>(p)];
    switch (ps.mode) {
      case ContactMode::kSeparated:
        fns.push_back({p, Fn::kGap, ContactEventReason::kTouchDown});
        break;
      case ContactMode::kSliding:
        fns.push_back({p, Fn::kNormalForce, ContactEventReason::kLiftOff});
        fns.push_back({p, Fn::kSlip, ContactEventReason::kSlipStopped});
        break;
      case ContactMode::kSticking:
        fns.push_back({p, Fn::kNormalForce, ContactEventReason::kLiftOff});
        fns.push_back({p, Fn::kFrictionMargin, ContactEventReason::kFrictionLimit});
        if (ps.rolling_held) {
          fns.push_back({p, Fn::kRollingMargin, ContactEventReason::kRollingLimit});
        } else if (ps.rolling_direction_W.squaredNorm() > 0.0) {
          fns.push_back({p, Fn::kRolling, ContactEventReason::kRollingStopped});
        }
        break;
    }
  }
  for (int c = 0; c < model.num_constraints(); ++c) {
    if (!model.constraint(c).can_release()) continue;
    if (IsReleased(s, c)) {
      fns.push_back({c, Fn::kStringGap, ContactEventReason::kTouchDown});
    } else {
      fns.push_back({c, Fn::kStringTension, ContactEventReason::kLiftOff});
    }
  }
  return fns;
}

// Gap rate ġ = J u of the string function's constraint (its row, kept in Data::constraint_rows
// in either mode; data filled by CalcAccelerations at `s`); the contact point's normal
// velocity for a contact gap.
double GapRate(const Model& model, const State& s, const Data& data, const ContactFn& f) {
  if (!IsString(f.fn)) return data.contact_points[static_cast<size_t>(f.point)].normal_velocity;
  const Constraint& con = model.constraint(f.point);
  const ConstraintEval& e = data.constraint_rows[static_cast<size_t>(f.point)];
  const auto row = [&](BodyIndex b, const ConstraintEval::Rows& J) {
    const auto i = static_cast<size_t>(b);
    return J.row(0).head<3>().dot(s.bodies[i].v_WBcm_W) + J.row(0).tail<3>().dot(data.w_WB_W[i]);
  };
  double v = row(con.child(), e.J_child);
  if (con.parent() != kWorld) v += row(con.parent(), e.J_parent);
  for (int k = 0; k < e.num_extra; ++k) {  // a pulley carried by a third body
    const auto j = static_cast<size_t>(k);
    v += row(e.extra_body[j], e.J_extra[j]);
  }
  return v;
}

// Values of the event functions at `s` (evaluates the contact forces in s's modes).
void EvalFunctions(const Model& model, const State& s, const std::vector<ContactFn>& fns,
                   Data& data, std::vector<double>& g) {
  CalcAccelerations(model, s, data);
  g.resize(fns.size());
  for (size_t i = 0; i < fns.size(); ++i) {
    const ContactFn& f = fns[i];
    if (f.fn == Fn::kStringGap) {
      g[i] = data.constraint_gap[static_cast<size_t>(f.point)];
      continue;
    }
    if (f.fn == Fn::kStringTension) {
      g[i] = data.constraints[static_cast<size_t>(f.point)].lambda[0];
      continue;
    }
    const ContactPointOutput& out = data.contact_points[static_cast<size_t>(f.point)];
    const ContactPointState& ps = s.contacts[static_cast<size_t>(f.point)];
    const double mu_s = model.contact(model.contact_of_point(f.point)).mu_s();
    switch (f.fn) {
      case Fn::kGap:
        g[i] = out.gap;
        break;
      case Fn::kNormalForce:
        g[i] = out.normal_force;
        break;
      case Fn::kSlip:
        // Slip along the mode's reference direction: falls through zero when the slip stops
        // (or has turned by more than 90°, which re-selection then takes as the new
        // direction).
        g[i] = out.slip_velocity_W.dot(ps.slip_direction_W);
        break;
      case Fn::kFrictionMargin:
        g[i] = mu_s * out.normal_force - out.friction_force_W.norm();
        break;
      case Fn::kStringGap:
      case Fn::kStringTension:
        break;
      case Fn::kRolling:
        // Rolling along the mode's reference direction: falls through zero when it stops.
        g[i] = out.rolling_velocity_W.dot(ps.rolling_direction_W);
        break;
      case Fn::kRollingMargin:
        // The held rolling's margin mu_r N R - |M|: falls through zero when the moment needed
        // to hold it reaches what rolling resistance can give.
        g[i] = out.rolling_moment_capacity - out.rolling_moment_W.norm();
        break;
    }
  }
}

// Round-off band of an event function at the current evaluation (data filled by
// EvalFunctions): relative 1e-9 of the largest contact force, or of the largest slip or
// rolling speed and 1 m/s, so a value inside it is zero for the event logic.
double RoundOffBand(const Model& model, const ContactFn& f, const Data& data) {
  double force = 0.0, speed = 1.0;
  for (const ContactPointOutput& o : data.contact_points) {
    force = std::max({force, std::abs(o.normal_force), o.friction_force_W.norm()});
    speed = std::max(speed, o.slip_velocity_W.norm());
  }
  if (data.lambda.size() > 0) force = std::max(force, data.lambda.cwiseAbs().maxCoeff());
  for (const Vec3& F : data.F_Bcm_W) force = std::max(force, F.norm());
  switch (f.fn) {
    case Fn::kNormalForce:
    case Fn::kFrictionMargin:
    case Fn::kStringTension:
      return 1e-9 * force;
    case Fn::kRollingMargin: {
      // A moment: the force scale at the feature's radius.
      const int ci = model.contact_of_point(f.point);
      return 1e-9 * force *
             model.contact(ci).feature(f.point - model.contact_point_offset(ci)).radius;
    }
    default:
      return 1e-9 * speed;
  }
}

// Bounce history of one point for the accumulation (Zeno) test.
struct BounceHistory {
  double t[2] = {0.0, 0.0};  // times of the last two impacts (t[1] the latest)
  double v[2] = {0.0, 0.0};  // their approach speeds
  int count = 0;             // impacts since the point last rested
};

class HybridRun {
 public:
  HybridRun(const Model& model, const SimulationOptions& o)
      : model_(model),
        o_(o),
        tol_(o.contact.tolerances),
        data_(MakeData(model)),
        bounces_(static_cast<size_t>(model.num_contact_points())) {
    for (int c = 0; c < model.num_constraints(); ++c) {
      strings_ = strings_ || model.constraint(c).can_release();
    }
  }

  SimulationResult Run(const State& initial) {
    State s = Start(initial);
    // Contacts need dense output (Simulate refuses a fixed-step integrator for them).
    const std::unique_ptr<Integrator> integrator = MakeIntegrator(model_, o_, s.t);
    Integrator& integ = *integrator;
    const size_t ne = o_.events.size();
    ug_prev_.assign(ne, 0.0);
    ug_new_.assign(ne, 0.0);
    for (size_t e = 0; e < ne; ++e) {
      if (o_.events[e].g) ug_prev_[e] = o_.events[e].g(model_, s);
    }
    scratch_ = s;
    while (s.t < o_.t_end) {
      integ.Initialize(s);
      Stretch st = BeginStretch(integ, s);
      bool restart = false;
      while (integ.t() < o_.t_end && !restart) {
        integ.Step(o_.t_end);
        if (o_.on_step) o_.on_step(integ.t());
        EvalFunctions(model_, integ.state(), st.fns, data_, st.g1);
        NormalVelocities(integ.state(), st.fns, st.vn1);
        const auto [t_c, which] = FindContactEvent(integ, st);
        const double t_stop = LocateUserEvents(integ, t_c);
        const double t_out_end = std::min({integ.t(), t_c, t_stop});
        EmitUpTo(integ, t_out_end, scratch_);
        if (std::isfinite(t_stop)) {
          StopAtUserEvent(integ, t_stop);
          return std::move(r_);
        }
        if (which >= 0) {
          if (SwitchModes(integ, s, t_c, st.fns[static_cast<size_t>(which)])) return std::move(r_);
          restart = true;
        } else {
          st.g0 = st.g1;
          st.vn0 = st.vn1;
          ug_prev_ = ug_new_;
          s = integ.state();
        }
      }
      AddStats(integ);
    }
    r_.final_state = s;
    Emit(s);
    return std::move(r_);
  }

 private:
  // The contact event functions of one stretch of integration between mode switches, their
  // values and the points' normal velocities at the ends of the current step, and the
  // functions armed at the restart (BeginStretch).
  struct Stretch {
    std::vector<ContactFn> fns;
    std::vector<double> g0, g1;
    // Normal velocities of the points at the step's ends (closest approach, EventTime).
    std::vector<double> vn0, vn1;
    double t_restart = 0.0;
    std::vector<double> band;
    std::vector<char> armed;
  };

  // The first instant: projection onto the constraints, the initial modes (impacts of points
  // that start touching and approaching, then selection) and the first sample.
  State Start(const State& initial) {
    State s = initial;
    if (s.contacts.size() != static_cast<size_t>(model_.num_contact_points())) {
      s.contacts.assign(static_cast<size_t>(model_.num_contact_points()), ContactPointState{});
    }
    // Strings apart (slack beyond the gap tolerance) are slack before the projection, which
    // would otherwise pull them taut.
    EnsureConstraintModes(model_, s);
    std::vector<ConstraintMode> given;
    for (const ConstraintModeState& m : s.constraint_modes) given.push_back(m.mode);
    if (strings_) SelectConstraintModes(model_, s, tol_);
    if (model_.num_constraints() > 0) ProjectOntoConstraints(model_, s, data_);
    const size_t first_string = r_.constraint_events.size();
    Transition(s, -1, ContactEventReason::kInitial);
    // Every string's initial mode is listed (from the mode it was given), and the changes the
    // first transition made are in it.
    std::vector<ConstraintEvent> snaps(
        r_.constraint_events.begin() + static_cast<std::ptrdiff_t>(first_string),
        r_.constraint_events.end());
    r_.constraint_events.resize(first_string);
    for (int c = 0; c < model_.num_constraints(); ++c) {
      if (!model_.constraint(c).can_release()) continue;
      ConstraintEvent ev{s.t, c, given[static_cast<size_t>(c)],
                         s.constraint_modes[static_cast<size_t>(c)].mode,
                         ConstraintEventReason::kInitial};
      for (const ConstraintEvent& x : snaps) {
        if (x.constraint == c && x.impulse != 0.0) {
          ev.reason = x.reason, ev.approach_speed = x.approach_speed, ev.impulse = x.impulse;
          ev.energy_lost = x.energy_lost;
        }
      }
      r_.constraint_events.push_back(ev);
    }
    CheckFiniteState(model_, s);
    for (int p = 0; p < model_.num_contact_points(); ++p) {
      const ContactPointState& ps = s.contacts[static_cast<size_t>(p)];
      r_.contact_events.insert(r_.contact_events.begin() + p,
                               {s.t, p, ContactMode::kSeparated, ps.mode,
                                ContactEventReason::kInitial, false, ps.rolling_held});
    }
    // Keep only the kInitial records for the first instant (the Transition's own are the same
    // changes).
    r_.contact_events.resize(static_cast<size_t>(model_.num_contact_points()));
    // The first sample is the state integrated: on the rows of the chosen modes (the
    // integrator projects again after every step; docs/contact.md, "Drift").
    if (o_.adaptive.project_contacts && HasActiveContactRows(model_, s)) {
      ProjectOntoContactModes(model_, s, data_);
    }
    t0_ = s.t;
    Emit(s);
    return s;
  }

  // Normal velocities of the points of `fns` (data_ filled by EvalFunctions).
  // (The state is integ's at the evaluation: only a string's rate reads it.)
  void NormalVelocities(const State& s, const std::vector<ContactFn>& fns,
                        std::vector<double>& vn) const {
    vn.resize(fns.size());
    for (size_t i = 0; i < fns.size(); ++i) {
      vn[i] = IsGap(fns[i].fn) ? GapRate(model_, s, data_, fns[i]) : 0.0;
    }
  }

  // The event functions of the modes of `s` and their values at the restart (integ initialised
  // at `s`).
  Stretch BeginStretch(const Integrator& integ, const State& s) {
    Stretch st;
    st.fns = EventFunctions(model_, s);
    EvalFunctions(model_, integ.state(), st.fns, data_, st.g0);
    NormalVelocities(integ.state(), st.fns, st.vn0);
    // A function that is zero (or round-off below) where the run restarts has its crossing
    // there, not in a later step: a sticking point left exactly at its friction limit, a
    // slip that started from zero, a normal force that is zero. It is armed: if it then
    // falls below its round-off band before rising out of it, the event is at the restart
    // (without this the crossing would never be seen, since it never was positive).
    st.t_restart = integ.t();
    st.band.resize(st.fns.size());
    st.armed.assign(st.fns.size(), 0);
    for (size_t i = 0; i < st.fns.size(); ++i) {
      st.band[i] = RoundOffBand(model_, st.fns[i], data_);
      st.armed[i] = !IsGap(st.fns[i].fn) && st.g0[i] <= st.band[i];
    }
    return st;
  }

  // Earliest contact event in the step just taken: its time and the index of its function
  // (infinity and -1: none).
  std::pair<double, int> FindContactEvent(Integrator& integ, Stretch& st) {
    double t_c = std::numeric_limits<double>::infinity();
    int which = -1;
    for (size_t i = 0; i < st.fns.size(); ++i) {
      const double t = EventTime(integ, st, i);
      if (t < t_c) t_c = t, which = static_cast<int>(i);
    }
    return {t_c, which};
  }

  // Time of the crossing of event function `i` in the step [ta, tb] just taken (infinity:
  // none).
  double EventTime(Integrator& integ, Stretch& st, size_t i) {
    constexpr double kNone = std::numeric_limits<double>::infinity();
    const std::vector<ContactFn>& fns = st.fns;
    const std::vector<double>&g0 = st.g0, &g1 = st.g1, &vn0 = st.vn0, &vn1 = st.vn1;
    const double ta = integ.t_previous(), tb = integ.t();
    if (st.armed[i]) {
      if (g1[i] < -st.band[i]) return st.t_restart;
      if (g1[i] > st.band[i]) st.armed[i] = 0;
      if (st.armed[i]) return kNone;
    }
    std::vector<double> gv;
    auto g = [&](double t) {
      integ.Interpolate(t, scratch_);
      EvalFunctions(model_, scratch_, {fns[i]}, data_, gv);
      return gv[0];
    };
    double a = ta, ga = g0[i];
    if (IsGap(fns[i].fn) && g0[i] > 0.0 && g1[i] > 0.0) {
      // Apart at both ends, but approaching at the start and separating at the end: the
      // closest approach (the zero of ġ) lies inside the step, and the gap may have
      // dipped below zero there (two spheres passing through each other in one long
      // free-flight step, a turning vertex). Then the touch-down is in [ta, closest].
      if (!(vn0[i] < 0.0 && vn1[i] > 0.0)) return kNone;
      auto gdot = [&](double t) {
        g(t);
        return GapRate(model_, scratch_, data_, fns[i]);
      };
      const double t_min =
          internal::LocateEventTime(gdot, ta, vn0[i], tb, vn1[i], o_.event_time_tolerance);
      const double g_min = g(t_min);
      if (!(g_min < 0.0)) return kNone;
      return internal::LocateEventTime(g, ta, g0[i], t_min, g_min, o_.event_time_tolerance);
    }
    if (!internal::Crosses(EventDirection::kFalling, g0[i], g1[i])) {
      // A point that separated at the step's start (gap at round-off, <= 0) and ends it
      // below the plane made a flight shorter than the step: the gap rose and fell
      // inside it, which the end values do not show. The top of that flight is the zero
      // of the normal velocity ġ; the touch-down is then bracketed by [top, tb]. A
      // flight whose top is not above the plane (a rebound below round-off, a point
      // released at round-off) lands where it sinks below the touching band.
      if (!IsGap(fns[i].fn) || g0[i] > 0.0 || !(g1[i] < 0.0)) return kNone;
      auto gdot = [&](double t) {
        g(t);
        return GapRate(model_, scratch_, data_, fns[i]);
      };
      const double v0 = gdot(ta), v1 = gdot(tb);
      if (v0 > 0.0 && v1 > 0.0) return kNone;  // rising all through the step
      double t_top = ta;
      if (v0 > 0.0 && v1 < 0.0) {
        t_top = internal::LocateEventTime(gdot, ta, v0, tb, v1, o_.event_time_tolerance);
      }
      const double g_top = g(t_top);
      if (!(g_top > 0.0)) {
        // Never above the plane: it is still within the touching band (gap >= -tol.gap,
        // as in SelectContactModes), and lands where it sinks out of it. A point released
        // at round-off (zero normal force and zero relative acceleration, both to
        // round-off) would otherwise land at once and be released again, at one instant.
        const double sink = -tol_.gap;
        if (!(g_top > sink)) return t_top;
        if (!(g1[i] < sink)) return kNone;
        auto below = [&](double t) { return g(t) - sink; };
        return internal::LocateEventTime(below, t_top, g_top - sink, tb, g1[i] - sink,
                                         o_.event_time_tolerance);
      }
      a = t_top, ga = g_top;
    }
    return internal::LocateEventTime(g, a, ga, tb, g1[i], o_.event_time_tolerance);
  }

  // User events in the step just taken, up to the contact event at t_c: records them and
  // returns the time of the earliest that stops the run (infinity: none).
  double LocateUserEvents(Integrator& integ, double t_c) {
    const double ta = integ.t_previous(), tb = integ.t();
    double t_stop = std::numeric_limits<double>::infinity();
    for (size_t e = 0; e < o_.events.size(); ++e) {
      if (!o_.events[e].g) continue;  // a contact-mode event (RecordModeEvents)
      ug_new_[e] = o_.events[e].g(model_, integ.state());
      if (!internal::Crosses(o_.events[e].direction, ug_prev_[e], ug_new_[e])) continue;
      auto g = [&](double t) {
        integ.Interpolate(t, scratch_);
        return o_.events[e].g(model_, scratch_);
      };
      const double t =
          internal::LocateEventTime(g, ta, ug_prev_[e], tb, ug_new_[e], o_.event_time_tolerance);
      if (t > t_c) continue;
      EventRecord rec;
      rec.event = static_cast<int>(e);
      rec.name = o_.events[e].name;
      rec.t = t;
      integ.Interpolate(t, rec.state);
      r_.events.push_back(std::move(rec));
      if (o_.events[e].action == EventAction::kStop) t_stop = std::min(t_stop, t);
    }
    std::sort(r_.events.begin(), r_.events.end(),
              [](const EventRecord& a, const EventRecord& b) { return a.t < b.t; });
    return t_stop;
  }

  // Ends the run at a user event that stops it, at t_stop.
  void StopAtUserEvent(const Integrator& integ, double t_stop) {
    // Drop records after the stop.
    while (!r_.events.empty() && r_.events.back().t > t_stop) r_.events.pop_back();
    r_.final_state = r_.events.back().state;
    r_.stopped_by_event = true;
    Emit(r_.final_state);
    AddStats(integ);
  }

  // The contact event of `fn` at t_c: moves `s` there and makes the transition. True when a
  // contact-mode event stops the run (the result is then complete).
  bool SwitchModes(Integrator& integ, State& s, double t_c, const ContactFn& fn) {
    integ.Interpolate(t_c, s);
    s.t = t_c;
    const State before = o_.on_transition ? s : State{};
    const size_t first_change = r_.contact_events.size();
    if (IsString(fn.fn)) {
      Transition(s, -1, ContactEventReason::kOther, fn.point, fn.fn == Fn::kStringTension);
    } else {
      Transition(s, fn.point, fn.reason);
    }
    CheckFiniteState(model_, s);
    if (o_.on_transition) o_.on_transition(before, s);
    if (RecordModeEvents(first_change, s)) {
      r_.final_state = s;
      r_.stopped_by_event = true;
      Emit(s);
      AddStats(integ);
      return true;
    }
    for (size_t e = 0; e < o_.events.size(); ++e) {
      if (o_.events[e].g) ug_prev_[e] = o_.events[e].g(model_, s);
    }
    if (YieldsAt(s.t, IsString(fn.fn) ? model_.constraint(fn.point).name()
                                      : model_.contact_point_name(fn.point))) {
      r_.final_state = s;
      AddStats(integ);
      return true;
    }
    if (++switches_ > o_.contact.max_mode_switches) {
      throw InputError(
          fmt::format(
              "contacts and strings switched mode more than {} times (at t = {:.9g} s, {} '{}'); "
              "the motion chatters: check the friction coefficients and the tolerances, or raise "
              "max_mode_switches",
              o_.contact.max_mode_switches, s.t, IsString(fn.fn) ? "string" : "point",
              IsString(fn.fn) ? model_.constraint(fn.point).name()
                              : model_.contact_point_name(fn.point)),
          ErrorElement{
              IsString(fn.fn) ? ErrorElement::Kind::kConstraint : ErrorElement::Kind::kContactPoint,
              fn.point});
    }
    return false;
  }

  // Counts the transition just made at t (a touch-down that continues a geometric bounce
  // sequence does not count: the run sums it); true when the last yield_changes counted ones
  // fell within yield_window, and the run yields (RegimeChangeYield, naming `where`).
  bool YieldsAt(double t, const std::string& where) {
    const ContactOptions& c = o_.contact;
    if (c.yield_changes <= 0 || geometric_bounce_) return false;
    recent_.push_back(t);
    if (recent_.size() > static_cast<size_t>(c.yield_changes)) recent_.pop_front();
    if (recent_.size() < static_cast<size_t>(c.yield_changes) ||
        !(t - recent_.front() <= c.yield_window)) {
      return false;
    }
    r_.yielded = RegimeChangeYield{recent_.front(), t, c.yield_changes, where};
    return true;
  }

  void Emit(const State& s) {
    if (o_.on_sample) o_.on_sample(s);
    if (o_.store_samples) r_.samples.push_back(s);
  }

  void EmitUpTo(Integrator& integ, double t_end, State& scratch) {
    if (!(o_.output_interval > 0.0)) return;
    while (true) {
      const double t = t0_ + static_cast<double>(k_) * o_.output_interval;
      if (t > t_end || t >= o_.t_end) break;
      integ.Interpolate(t, scratch);
      Emit(scratch);
      ++k_;
    }
  }

  // Contact-mode events for the changes recorded from `first` on (one transition, at `s`);
  // true when one of them stops the run.
  bool RecordModeEvents(size_t first, const State& s) {
    bool stop = false;
    for (size_t e = 0; e < o_.events.size(); ++e) {
      const EventSpec& spec = o_.events[e];
      if (!spec.on_mode_change) continue;
      const bool fires = std::any_of(r_.contact_events.begin() + static_cast<std::ptrdiff_t>(first),
                                     r_.contact_events.end(),
                                     [&](const ContactEvent& c) { return spec.on_mode_change(c); });
      if (!fires) continue;
      r_.events.push_back({static_cast<int>(e), spec.name, s.t, s});
      stop = stop || spec.action == EventAction::kStop;
    }
    return stop;
  }

  void AddStats(const Integrator& integ) {
    const IntegratorStats& st = integ.stats();
    r_.stats.steps += st.steps - last_.steps;
    r_.stats.rejected_steps += st.rejected_steps - last_.rejected_steps;
    r_.stats.function_evaluations += st.function_evaluations - last_.function_evaluations;
    last_ = st;
  }

  // Impacts, the accumulation test, mode selection and the records, at `s`. `string` is the
  // constraint whose event triggered it (-1: none), `went_slack` true when that was its
  // tension falling through zero. Strings snap taut first (their impact holds every engaged
  // constraint; contacts take no part), then contacts take their impacts and modes, then the
  // strings their modes (an LCP on the tensions) with the contacts' modes fixed.
  void Transition(State& s, int trigger, ContactEventReason reason, int string = -1,
                  bool went_slack = false) {
    if (!strings_) {
      TransitionContacts(s, trigger, reason);
      return;
    }
    std::vector<ConstraintMode> strings_before;
    EnsureConstraintModes(model_, s);
    for (const ConstraintModeState& m : s.constraint_modes) strings_before.push_back(m.mode);
    const std::vector<ConstraintImpulse> snaps = ResolveConstraintImpacts(model_, s, tol_);
    TransitionContacts(s, trigger, reason);
    std::vector<int> release;
    if (went_slack) release.push_back(string);
    SelectConstraintModes(model_, s, tol_, release);
    for (int c = 0; c < model_.num_constraints(); ++c) {
      if (!model_.constraint(c).can_release()) continue;
      const ConstraintMode from = strings_before[static_cast<size_t>(c)];
      const ConstraintMode to = s.constraint_modes[static_cast<size_t>(c)].mode;
      ConstraintEvent ev{s.t, c, from, to,
                         to == ConstraintMode::kReleased ? ConstraintEventReason::kWentSlack
                                                         : ConstraintEventReason::kWentTaut};
      bool snapped = false;
      for (const ConstraintImpulse& ci : snaps) {
        if (ci.constraint != c) continue;
        snapped = true;
        ev.reason = ConstraintEventReason::kSnappedTaut;
        ev.approach_speed = ci.approach_speed;
        ev.impulse = ci.impulse;
        ev.energy_lost = ci.energy_lost;
      }
      if (!snapped && from == to && c != string) continue;
      r_.constraint_events.push_back(ev);
    }
  }

  // A touch-down of `trigger` at time t with approach speed v, against the point's bounce
  // history (which it joins): whether it continues a geometric sequence (successive approach
  // speeds v_i/v_{i-1} = e and flight times τ_i/τ_{i-1} = e, as ballistic flights between
  // bounces give), and whether the rest of it is short enough to sum: the remaining flights
  // end at t + τ_i e/(1-e) (docs/contact.md, "Accumulating bounces").
  struct BounceTest {
    bool geometric = false;
    bool sums = false;
    double accumulation_time = std::numeric_limits<double>::quiet_NaN();
  };
  BounceTest TestBounce(int trigger, double t, double v) {
    BounceTest out;
    const double e = model_.contact(model_.contact_of_point(trigger)).restitution();
    BounceHistory& h = bounces_[static_cast<size_t>(trigger)];
    if (h.count >= 2 && e > 0.0 && e < 1.0 && v > 0.0) {
      const double rtol = o_.contact.accumulation_ratio_tolerance;
      const double r1 = v / h.v[1], r2 = h.v[1] / h.v[0];
      const double tau1 = t - h.t[1], tau0 = h.t[1] - h.t[0];
      // Each touch-down time is known to the event tolerance, so an approach speed v after
      // a flight τ (v ~ a τ / 2) is known to about 2 v tol / τ: the ratios get that slack.
      const double slack1 = 4.0 * o_.event_time_tolerance / (t - h.t[1]);
      const double slack0 = 4.0 * o_.event_time_tolerance / (h.t[1] - h.t[0]);
      out.geometric = std::abs(r1 - e) <= rtol * e + slack1 &&
                      std::abs(r2 - e) <= rtol * e + slack0 &&
                      std::abs(tau1 / tau0 - e) <= rtol * e + 2.0 * o_.event_time_tolerance / tau0;
      if (out.geometric && tau1 * e / (1.0 - e) <= o_.contact.accumulation_remaining_time) {
        out.sums = true;
        out.accumulation_time = t + tau1 * e / (1.0 - e);
      }
    }
    h.t[0] = h.t[1], h.v[0] = h.v[1];
    h.t[1] = t, h.v[1] = v;
    ++h.count;
    return out;
  }

  void TransitionContacts(State& s, int trigger, ContactEventReason reason) {
    std::vector<ContactMode> before(s.contacts.size());
    std::vector<char> held_before(s.contacts.size());
    for (size_t p = 0; p < s.contacts.size(); ++p) {
      before[p] = s.contacts[p].mode;
      held_before[p] = s.contacts[p].rolling_held;
    }
    // Approach speeds before the impulses, for the accumulation test.
    const std::vector<ContactPointOutput> pre = CalcContactOutputs(model_, s);
    int plastic = -1;
    double accumulation_time = std::numeric_limits<double>::quiet_NaN();
    geometric_bounce_ = false;
    if (reason == ContactEventReason::kTouchDown && o_.contact.accumulate_bounces) {
      const BounceTest b =
          TestBounce(trigger, s.t, -pre[static_cast<size_t>(trigger)].normal_velocity);
      geometric_bounce_ = b.geometric;
      if (b.sums) {
        plastic = trigger;
        accumulation_time = b.accumulation_time;
      }
    }
    const ImpactResult ir = plastic >= 0 ? ResolvePlasticImpact(model_, s, plastic, tol_)
                                         : ResolveImpacts(model_, s, tol_);
    const double lost = ir.kinetic_energy_before - ir.kinetic_energy_after;
    double pn_sum = 0.0;
    for (const ContactImpulse& ci : ir.impulses) pn_sum += ci.normal_impulse;
    for (const ContactImpulse& ci : ir.impulses) {
      ImpactRecord rec;
      rec.t = s.t;
      rec.point = ci.point;
      rec.approach_speed = ci.approach_speed;
      rec.normal_impulse = ci.normal_impulse;
      rec.impulse_W = ci.impulse_W;
      rec.energy_lost = pn_sum > 0.0 ? lost * ci.normal_impulse / pn_sum : 0.0;
      rec.accumulation = ci.point == plastic;
      rec.law = ci.law;
      rec.frictionless_fallback = ir.frictionless_fallback;
      if (rec.accumulation) rec.accumulation_time = accumulation_time;
      r_.impacts.push_back(rec);
    }
    // A point whose friction limit was crossed starts to slip, one whose normal force fell
    // through zero leaves (SelectContactModes).
    ModeHints hints;
    if (reason == ContactEventReason::kFrictionLimit && trigger >= 0)
      hints.slip_starts.push_back(trigger);
    if (reason == ContactEventReason::kLiftOff && trigger >= 0) hints.lift_offs.push_back(trigger);
    if (reason == ContactEventReason::kRollingLimit && trigger >= 0)
      hints.rolling_starts.push_back(trigger);
    ModeSelectionNotes notes;
    SelectContactModes(model_, s, tol_, hints, &notes);
    for (const JamImpulse& j : notes.jams) {
      ImpactRecord rec;
      rec.t = s.t;
      rec.point = j.point;
      rec.approach_speed = 0.0;
      rec.normal_impulse = j.normal_impulse;
      rec.impulse_W = j.impulse_W;
      rec.energy_lost = j.energy_lost;
      rec.jam = true;
      r_.impacts.push_back(rec);
      r_.warnings.push_back(fmt::format(
          "contact point '{}' at t = {:.9g} s: sliding at {:.6g} m/s, the contact forces had no "
          "consistent solution (a Painlevé-type paradox); the slip was stopped by an impulsive "
          "jam (an impact without collision) of {:.6g} N·s that took {:.6g} J",
          model_.contact_point_name(j.point), s.t, j.slip_speed, j.impulse_W.norm(),
          j.energy_lost));
    }
    for (size_t p = 0; p < s.contacts.size(); ++p) {
      const ContactMode to = s.contacts[p].mode;
      if (to != ContactMode::kSeparated) bounces_[p].count = 0;  // resting: a new sequence later
      // The triggering point is recorded even when its mode stays (a bounce, rolling that
      // stopped, slip that turned); the others only when their mode (or rolling sub-mode)
      // changes.
      const bool held = s.contacts[p].rolling_held;
      if (to == before[p] && held == (held_before[p] != 0) && static_cast<int>(p) != trigger)
        continue;
      ContactEventReason why = static_cast<int>(p) == trigger ? reason : ContactEventReason::kOther;
      if (static_cast<int>(p) == plastic) why = ContactEventReason::kAccumulation;
      r_.contact_events.push_back(
          {s.t, static_cast<int>(p), before[p], to, why, held_before[p] != 0, held});
    }
  }

  const Model& model_;
  const SimulationOptions& o_;
  const ContactTolerances tol_;
  Data data_;
  std::vector<BounceHistory> bounces_;
  SimulationResult r_;
  IntegratorStats last_;
  double t0_ = 0.0;
  long long k_ = 1;
  int switches_ = 0;
  /// Whether a constraint can let go (a string without drums): then strings have modes.
  bool strings_ = false;
  /// User event functions at the start and end of the current step.
  std::vector<double> ug_prev_, ug_new_;
  /// Dense-output state for event location and samples.
  State scratch_;
  /// Whether the last transition was a touch-down continuing a geometric bounce sequence.
  bool geometric_bounce_ = false;
  /// Times of the last counted transitions (at most ContactOptions::yield_changes).
  std::deque<double> recent_;
};

}  // namespace

SimulationResult RunHybrid(const Model& model, const State& initial, const SimulationOptions& o) {
  HybridRun run(model, o);
  return run.Run(initial);
}

}  // namespace chasles::internal
