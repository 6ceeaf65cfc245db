// RunStudy: segments between impulses and impacts, contact settling at the start and after
// each jump, output rows on one global grid, the ledger carried across segments, limits on the
// work, and the certificate (include/chasles/analysis/study.h).

#include "chasles/analysis/study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <unordered_set>
#include <utility>

#include <fmt/format.h>

#include "chasles/analysis/ledger.h"
#include "chasles/dynamics/constraint_modes.h"
#include "chasles/dynamics/constraint_solve.h"
#include "chasles/dynamics/contact_solve.h"
#include "chasles/dynamics/impact.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/dynamics/redundancy.h"
#include "chasles/error.h"
#include "chasles/integrate/islands.h"
#include "chasles/integrate/run_path.h"
#include "chasles/integrate/sphere_events.h"
#include "chasles/model/data.h"
#include "internal/island_checks.h"
#include "internal/study_steps.h"

namespace chasles {

namespace {

using study_internal::LedgerCarry;
using study_internal::RowMaker;
using study_internal::Segment;
using study_internal::SlipWatch;
using study_internal::ThetaTracker;

/// Largest magnitude of a motion in SI (position, speed) a run accepts: beyond it the energies
/// (½ m v²) and moments (r × F) of ordinary bodies leave double precision, so such a motion is
/// a blown-up or mistyped input.
constexpr double kMotionScale = 1e150;

/// Why integrator: auto time steps a run with every pair of balls able to collide.
constexpr const char* kPairsNeedStepping =
    "every pair of balls may collide (ball_collisions), and only time stepping finds the pairs";

/// Throws when a body's motion is not finite or has run away beyond kMotionScale.
void CheckFinite(const Model& model, const State& state) {
  for (int b = 0; b < model.num_bodies(); ++b) {
    const BodyState& s = state.bodies[static_cast<size_t>(b)];
    const bool ok = s.p_WBcm.allFinite() && s.v_WBcm_W.allFinite() && s.w_WB_B.allFinite() &&
                    s.q_WB.coeffs().allFinite() && s.p_WBcm.norm() < kMotionScale &&
                    s.v_WBcm_W.norm() < kMotionScale && s.w_WB_B.norm() < kMotionScale;
    if (!ok) {
      throw InputError(
          fmt::format(
              "the motion of body '{}' diverged (non-finite or beyond 1e150 in SI) near "
              "t = {:.9g} s; the run is stopped. Check the force expressions for a singularity, "
              "or use a smaller 'step' or the adaptive integrator",
              model.body(b).name(), state.t),
          ErrorElement{ErrorElement::Kind::kBody, b});
    }
  }
}

/// An impulse or an impact, in time order.
struct Jump {
  double t;
  const StudyImpulseSpec* impulse;
  const StudyImpactSpec* impact;
};

/// One impulse of a settling and the impact problem (an island's) it came from.
struct ImpactAt {
  const ContactImpulse* impulse;
  const ImpactResult* result;
};

/// The impulses of `results` in point order (one problem lists its points in order already;
/// the islands' points interleave).
std::vector<ImpactAt> ImpulsesByPoint(const std::vector<ImpactResult>& results) {
  std::vector<ImpactAt> all;
  for (const ImpactResult& r : results) {
    for (const ContactImpulse& i : r.impulses) all.push_back({&i, &r});
  }
  std::stable_sort(all.begin(), all.end(), [](const ImpactAt& a, const ImpactAt& b) {
    return a.impulse->point < b.impulse->point;
  });
  return all;
}

/// One run of a study: the state, the current segment and everything recorded so far.
class StudyRun {
 public:
  explicit StudyRun(const StudyDefinition& def)
      : def_(def),
        theta_(def.initial_theta),
        rows_(def.columns, theta_),
        certificate_(def.certificate),
        slip_(def.rolling_watch),
        started_(std::chrono::steady_clock::now()) {}

  /// The run; an InputError that names a body names a user body (an index into def.bodies).
  StudyResult Run();

 private:
  StudyResult RunUnmapped();
  /// Rethrows `e`, naming the first user body placed in the current segment's model body it
  /// names (after an embedding a model body carries several).
  [[noreturn]] void RethrowForUserBody(const InputError& e) const;
  const std::string& Label(int p) const { return labels_[static_cast<size_t>(p)]; }
  void Start();
  /// The impacts of the settled islands, by point (each with its island's energy change).
  void RecordImpacts(const std::vector<ImpactResult>& results, double t);
  void RecordChanges(const std::vector<ContactModeChange>& changes, double t,
                     ContactEventReason reason);
  /// Impacts of the contacts driven into their planes, then every point's mode; appends each
  /// impact's and jam's impulse on its body (contact point, impulse in W) to `impulses` when
  /// given.
  void SettleContacts(ContactEventReason reason,
                      std::vector<std::pair<int, Vec3>>* impulses = nullptr);
  void Certify(const State& s, CheckPhase phase);
  void OnStep(double t);
  void RunTo(double t_b);
  /// Where the next run of an engine ends and its output interval (0: none before its end).
  struct Stretch {
    double t_end;
    double output_interval;
  };
  Stretch NextStretch(double t_b) const;
  void RunAdaptiveStretch(double t_b);
  void RunSteppingStretch(double t_b);
  void SwitchToStepping(const RegimeChangeYield& why);
  /// The run goes on time stepped (integrator: auto): the certificate's gap time, the impact
  /// law's warnings (once), the quiet span's start.
  void EnterStepping();
  void SwitchToEvents();
  void RunEvents(double t_b);
  void RecordSphereEvents(const SphereEventResult& r);
  void RunStepping(double t_b);
  void RecordSteppingSamples(const TimeSteppingResult& r);
  void RecordStepping(const TimeSteppingResult& r);
  void RecordSimulation(const SimulationResult& r, const std::vector<ContactPointState>& carried,
                        const std::vector<EventSpec>& events);
  void ApplyJump(const Jump& j);
  double AnswerJump(const State& before, std::vector<study_internal::JumpImpulse> impulses,
                    StudyJump& rec);
  void Finish();
  /// Appends the output row of `s` (and its snapshot when the definition asks for them).
  void AddRow(const Model& model, const State& s);

  const StudyDefinition& def_;
  ThetaTracker theta_;
  RowMaker rows_;
  CertificateBuilder certificate_;
  SlipWatch slip_;
  std::chrono::steady_clock::time_point started_;
  std::int64_t steps_taken_ = 0;
  Segment seg_;
  State state_;
  LedgerCarry carry_;
  double energy_initial_ = 0.0;
  std::vector<std::string> labels_;
  bool stopped_ = false;
  /// Time of the last output row [s] (the run's errors say how far it got).
  double t_last_row_ = 0.0;
  StudyResult result_;
  /// integrator: auto: the engine the run is on, the time-stepped segments' own energy error so
  /// far (and the projections at their handovers) [J], the last regime change of the current
  /// time-stepped segment [s], and whether the impact-law warnings were given.
  StudyEngine engine_ = StudyEngine::kAdaptive;
  /// The run's path (ChooseRunPath at the start).
  RunPath path_ = RunPath::kSmooth;
  double scheme_error_ = 0.0;
  double quiet_from_ = 0.0;
  bool law_warned_ = false;
  /// integrator: auto with every pair of balls able to collide: only time stepping finds the
  /// pairs, so the run is time stepped from start to end.
  bool stepped_throughout_ = false;
  /// The strings named in result_.string_events so far.
  std::unordered_set<std::string> strings_listed_;
};

StudyResult StudyRun::Run() {
  try {
    return RunUnmapped();
  } catch (const InputError& e) {
    RethrowForUserBody(e);
  }
}

void StudyRun::RethrowForUserBody(const InputError& e) const {
  if (!e.element() || e.element()->kind != ErrorElement::Kind::kBody ||
      typeid(e) != typeid(InputError)) {
    throw;
  }
  for (size_t b = 0; b < seg_.map.place.size(); ++b) {
    if (seg_.map.place[b].model_body == e.element()->index) {
      ErrorElement element = *e.element();
      element.index = static_cast<int>(b);
      throw InputError(e.what(), element);
    }
  }
  throw;
}

StudyResult StudyRun::RunUnmapped() {
  Start();
  // Impulses and impacts in time order (stable: the definition's order at equal times).
  std::vector<Jump> jumps;
  for (const auto& i : def_.impulses) jumps.push_back({i.t, &i, nullptr});
  for (const auto& i : def_.impacts) jumps.push_back({i.t, nullptr, &i});
  std::stable_sort(jumps.begin(), jumps.end(),
                   [](const Jump& a, const Jump& b) { return a.t < b.t; });
  const double t_end = def_.options.t_end;
  for (const Jump& j : jumps) {
    if (j.t > t_end) {
      result_.notes.push_back(fmt::format(
          "an impulse or impact at t = {:.6g} s is after the end time {:.6g} s and was not "
          "applied",
          j.t, t_end));
      continue;
    }
    RunTo(j.t);
    if (stopped_) break;
    ApplyJump(j);
  }
  if (!stopped_) RunTo(t_end);
  Finish();
  return std::move(result_);
}

void StudyRun::Start() {
  if (!(def_.options.output_interval > 0)) {
    throw InputError("a study needs a positive output interval (options.output_interval)");
  }
  result_.engine = def_.sphere_events   ? EngineRequest::kEvents
                   : def_.time_stepping ? EngineRequest::kStepping
                   : def_.auto_engine   ? EngineRequest::kAuto
                                        : EngineRequest::kIntegrator;
  result_.integrator = def_.options.integrator;
  if (def_.auto_engine) {
    if (def_.sphere_events || def_.time_stepping) {
      throw InputError("a run chooses its engine (auto_engine) or names one, not both");
    }
    const EngineChoiceRule& rule = def_.auto_engine->rule;
    if (!(rule.step > 0) || !std::isfinite(rule.step) || !(rule.changes >= 1) ||
        !(rule.window >= 0) || !std::isfinite(rule.window) || !(rule.quiet_span > 0)) {
      throw InputError(fmt::format(
          "the engine choice's rule (step {:.6g} s, {} changes within {:.6g} s, quiet span "
          "{:.6g} s) needs a positive step, at least one change, a finite window >= 0 and a "
          "positive quiet span (MakeEngineChoiceRule makes one)",
          rule.step, rule.changes, rule.window, rule.quiet_span));
    }
    result_.engine_rule = def_.auto_engine->rule;
    result_.engine_by_default = def_.auto_engine->by_default;
    stepped_throughout_ = def_.auto_engine->stepping.collide_all_pairs;
    StudyEngineSegment first;
    first.t_begin = def_.initial.t;
    if (stepped_throughout_) {
      first.engine = StudyEngine::kStepping;
      first.stays = kPairsNeedStepping;
    }
    result_.segments.push_back(std::move(first));
  }
  result_.warnings = def_.warnings;
  for (const StudyColumn& c : def_.columns) result_.columns.push_back(c.name);
  seg_ = study_internal::FirstSegment(def_);
  // The path (ChooseRunPath): a hybrid run's own Simulate says again whether it split.
  SimulationOptions chosen = def_.options;
  if (def_.events) chosen.events = def_.events(seg_.map);
  result_.run_path = ChooseRunPath(*seg_.model, chosen,
                                   def_.sphere_events   ? EngineRequest::kEvents
                                   : def_.time_stepping ? EngineRequest::kStepping
                                   : def_.auto_engine   ? EngineRequest::kAuto
                                                        : EngineRequest::kIntegrator);
  path_ = result_.run_path.path;
  if (stepped_throughout_) {
    if (const ModelObstacle o = TimeSteppingObstacle(*seg_.model); !o.empty()) {
      throw InputError(
          fmt::format("integrator auto: {}, which cannot run this scene: {} (balls on a table "
                      "may name 'integrator: events', which finds the pairs between events)",
                      kPairsNeedStepping, o.why),
          o.element);
    }
    result_.run_path.reason = std::string("time stepping throughout: ") + kPairsNeedStepping;
  }
  if ((path_ == RunPath::kSphereEvents || path_ == RunPath::kTimeStepping) &&
      (!chosen.events.empty() || !def_.impulses.empty() || !def_.impacts.empty())) {
    throw InputError(
        "an event-driven (sphere_events) or time-stepped run takes no events, impulses or "
        "impacts");
  }
  state_ = def_.initial;
  CheckFinite(*seg_.model, state_);
  const Model& model = *seg_.model;
  labels_ = def_.contact_point_labels;
  for (int p = static_cast<int>(labels_.size()); p < model.num_contact_points(); ++p) {
    labels_.push_back(model.contact_point_name(p));
  }
  // The ledger starts from the state as given: an impact or a jam at t = 0 is part of it.
  if (model.num_contacts() > 0) {
    state_.contacts.assign(static_cast<size_t>(model.num_contact_points()), ContactPointState{});
  }
  const State as_given = state_;
  // The event-driven path settles its balls itself (a ball moving into the table lands at
  // once) and lists every point's initial mode (RecordSphereEvents).
  if (model.num_contacts() > 0 && (path_ == RunPath::kTimeStepping || stepped_throughout_)) {
    // Time stepping chooses the regimes in its first step; the timeline starts separated.
    for (int p = 0; p < model.num_contact_points(); ++p) {
      result_.contact_events.push_back({state_.t,
                                        Label(p),
                                        model.contact(model.contact_of_point(p)).name(),
                                        {},
                                        {},
                                        ContactEventReason::kInitial});
    }
  } else if (model.num_contacts() > 0 && path_ != RunPath::kSphereEvents) {
    SettleContacts(ContactEventReason::kInitial);
    // Every point's initial mode is part of the timeline, changed or not: the labels the
    // settling listed, gathered in one pass over its records (not one pass per point).
    std::unordered_set<std::string> listed;
    for (const StudyContactEvent& e : result_.contact_events) listed.insert(e.point);
    for (int p = 0; p < model.num_contact_points(); ++p) {
      if (listed.count(Label(p)) > 0) continue;
      const ContactPointState& ps = state_.contacts[static_cast<size_t>(p)];
      const StudyContactMode regime{ps.mode, ps.rolling_held};
      result_.contact_events.push_back({state_.t, Label(p),
                                        model.contact(model.contact_of_point(p)).name(), regime,
                                        regime, ContactEventReason::kInitial});
    }
  }
  carry_.segment_initial = as_given;
  energy_initial_ = CalcMechanicalEnergy(model, as_given);
  AddRow(model, state_);
  Certify(state_, CheckPhase::kSample);
  slip_.Sample(model, state_);
  if (stepped_throughout_) EnterStepping();
}

void StudyRun::RecordImpacts(const std::vector<ImpactResult>& results, double t) {
  for (const ImpactAt& i : ImpulsesByPoint(results)) {
    const ImpactResult& r = *i.result;
    result_.impacts.push_back(
        {t, Label(i.impulse->point), i.impulse->approach_speed, i.impulse->normal_impulse,
         r.kinetic_energy_before - r.kinetic_energy_after, false,
         std::numeric_limits<double>::quiet_NaN(), false, i.impulse->law, r.frictionless_fallback});
  }
}

void StudyRun::RecordChanges(const std::vector<ContactModeChange>& changes, double t,
                             ContactEventReason reason) {
  const Model& m = *seg_.model;
  for (const ContactModeChange& c : changes) {
    result_.contact_events.push_back({t,
                                      Label(c.point),
                                      m.contact(m.contact_of_point(c.point)).name(),
                                      {c.from, c.held_from},
                                      {c.to, c.held_to},
                                      reason});
  }
}

// Contacts that approach take their impact first; then every contact point gets a consistent
// mode, so that the next output row already shows it. Each island is settled as its own problem
// (SettleContactsByIsland): the dense impact and mode problems cost the cube of their points, and
// one problem over 1,000 independent balls took 7 s of an 8 s run (docs/benchmarks.md).
void StudyRun::SettleContacts(ContactEventReason reason,
                              std::vector<std::pair<int, Vec3>>* impulses) {
  if (seg_.model->num_contacts() == 0) return;
  const ContactTolerances tol;
  const ContactSettling settled = SettleContactsByIsland(*seg_.model, state_, tol);
  RecordImpacts(settled.impacts, state_.t);
  RecordChanges(settled.changes, state_.t, reason);
  if (impulses != nullptr) {
    for (const ImpactAt& i : ImpulsesByPoint(settled.impacts)) {
      impulses->emplace_back(i.impulse->point, i.impulse->impulse_W);
    }
    for (const JamImpulse& j : settled.jams) impulses->emplace_back(j.point, j.impulse_W);
  }
  for (const JamImpulse& j : settled.jams) {
    result_.impacts.push_back({state_.t, Label(j.point), 0.0, j.normal_impulse, j.energy_lost,
                               false, std::numeric_limits<double>::quiet_NaN(), true, std::nullopt,
                               false});
    result_.warnings.push_back(fmt::format(
        "contact point '{}' at t = {:.9g} s: sliding at {:.6g} m/s, the contact forces had no "
        "consistent solution (a Painlevé-type paradox); the slip was stopped by an impulsive "
        "jam (an impact without collision) that took {:.6g} J",
        Label(j.point), state_.t, j.slip_speed, j.energy_lost));
  }
}

// The certificate: every sample, event and contact transition is checked (the ledger with the
// residual carried across the segments).
void StudyRun::Certify(const State& s, CheckPhase phase) {
  certificate_.CheckState(*seg_.model, s, phase);
  const LedgerSample L = CalcLedgerSample(*seg_.model, s, carry_.segment_initial);
  certificate_.CheckLedger(s.t, carry_.residual + L.energy_residual - scheme_error_,
                           std::max(carry_.scale, L.energy_scale), phase);
}

// Every accepted step of every segment counts against the step limit and the wall time.
void StudyRun::OnStep(double t) {
  if (def_.progress) def_.progress(t);
  const StudyLimits& limits = def_.limits;
  if (++steps_taken_ > limits.max_steps) {
    throw LimitError(LimitError::Limit::kSteps,
                     fmt::format("the run reached the limit of {} {} at t = {:.9g} s (of {:.9g} s)",
                                 limits.max_steps,
                                 path_ == RunPath::kSphereEvents
                                     ? "steps (events, and the pressing groups' integration "
                                       "steps)"
                                     : "integration steps",
                                 t, def_.options.t_end));
  }
  if (limits.timeout > 0) {
    const std::chrono::duration<double> used = std::chrono::steady_clock::now() - started_;
    if (used.count() > limits.timeout) {
      throw LimitError(LimitError::Limit::kTime,
                       fmt::format("the run reached its wall-time limit of {:g} s at t = {:.9g} s "
                                   "(of {:.9g} s) after {} steps (a limit of 0 s turns it off)",
                                   limits.timeout, t, def_.options.t_end, steps_taken_));
    }
  }
}

// Integrates from state.t to t_b, sampling on the global grid k * dt_out: on the engine the
// definition names, or (integrator: auto) on the one the run is on, each stretch handing over
// to the other when its rule says so.
void StudyRun::RunTo(double t_b) {
  if (path_ == RunPath::kSphereEvents) {
    RunEvents(t_b);
    return;
  }
  if (path_ == RunPath::kTimeStepping) {
    RunStepping(t_b);
    return;
  }
  while (state_.t < t_b && !stopped_) {
    if (engine_ == StudyEngine::kStepping) {
      RunSteppingStretch(t_b);
    } else {
      RunAdaptiveStretch(t_b);
    }
  }
}

// A run from state.t towards t_b: to t_b with the output grid when state.t is on it, else to
// the next grid time with no output between (its final state is that grid time's row).
StudyRun::Stretch StudyRun::NextStretch(double t_b) const {
  const double dt_out = def_.options.output_interval;
  const double k = std::ceil(state_.t / dt_out - 1e-9);
  const double next_grid = k * dt_out;
  const bool on_grid = std::abs(next_grid - state_.t) <= 1e-9 * dt_out;
  return {on_grid ? t_b : std::min(next_grid, t_b), on_grid ? dt_out : 0.0};
}

// One run of the hybrid event-driven engine (Simulate) over the next stretch. Under
// integrator: auto it yields where its regime changes come faster than the rule allows, and the
// run goes on time stepped from the state reached.
void StudyRun::RunAdaptiveStretch(double t_b) {
  const Stretch stretch = NextStretch(t_b);
  SimulationOptions o = def_.options;
  o.t_end = stretch.t_end;
  o.output_interval = stretch.output_interval;
  o.events = def_.events ? def_.events(seg_.map) : std::vector<EventSpec>{};
  o.store_samples = false;
  o.on_step = [this](double t) { OnStep(t); };
  bool first = true;
  o.on_sample = [&](const State& s) {
    if (first) {
      first = false;
      return;
    }
    if (static_cast<std::int64_t>(result_.rows.size()) >= def_.limits.max_rows) {
      throw LimitError(LimitError::Limit::kRows,
                       fmt::format("the run reached the limit of {} output rows at t = {:.9g} s",
                                   def_.limits.max_rows, s.t));
    }
    CheckFinite(*seg_.model, s);
    AddRow(*seg_.model, s);
    Certify(s, CheckPhase::kSample);
    slip_.Sample(*seg_.model, s);
    if (def_.progress) def_.progress(s.t);
  };
  o.on_transition = [&](const State& before, const State& after) {
    Certify(before, CheckPhase::kBeforeTransition);
    Certify(after, CheckPhase::kAfterTransition);
  };
  // Split into islands, each island checks its own transitions (docs/contact.md, "Islands").
  study_internal::IslandChecks island_checks(def_.certificate);
  o.island_transition = island_checks.Hook();
  std::string stays;
  if (def_.auto_engine) {
    stays = AutoHandoverObstacle(*seg_.model, !o.events.empty());
    if (stays.empty()) {
      o.contact.yield_changes = def_.auto_engine->rule.changes;
      o.contact.yield_window = def_.auto_engine->rule.window;
    }
    result_.segments.back().stays = stays;
  }
  // Modes carried into this run: its "initial" records that only restate them are dropped.
  const std::vector<ContactPointState> carried = state_.contacts;
  SimulationResult r;
  try {
    r = Simulate(*seg_.model, state_, o);
  } catch (const LimitError&) {
    throw;
  } catch (const InputError& e) {
    std::string why = fmt::format("the run stopped after t = {:.9g} s: {}", t_last_row_, e.what());
    if (!stays.empty()) {
      why += "; integrator auto cannot hand this run over to time stepping: " + stays;
    }
    throw InputError(why, e.element());
  }
  island_checks.AddTo(certificate_);
  RecordSimulation(r, carried, o.events);
  if (!def_.auto_engine) result_.run_path = r.run_path;
  state_ = r.final_state;
  if (r.stopped_by_event) stopped_ = true;
  if (def_.auto_engine) {
    StudyEngineSegment& seg = result_.segments.back();
    if (r.islands.split) seg.islands = std::max(seg.islands, r.islands.count);
    IntegratorStats& st = seg.stats;
    st.steps += r.stats.steps;
    st.rejected_steps += r.stats.rejected_steps;
    st.function_evaluations += r.stats.function_evaluations;
  }
  if (r.yielded) SwitchToStepping(*r.yielded);
}

// One run of time stepping (integrator: auto) over the next stretch, ended early where no
// regime has changed for the rule's quiet span: the run then goes on event-driven.
void StudyRun::RunSteppingStretch(double t_b) {
  const EngineChoiceRule& rule = def_.auto_engine->rule;
  const Stretch stretch = NextStretch(t_b);
  TimeSteppingOptions o = def_.auto_engine->stepping;
  o.step = rule.step;
  o.t_end = stretch.t_end;
  o.output_interval = stretch.output_interval;
  o.quiet_span = stepped_throughout_ ? std::numeric_limits<double>::infinity() : rule.quiet_span;
  o.quiet_from = quiet_from_;
  o.threads = def_.options.threads;
  o.on_step = [this](double t) { OnStep(t); };
  TimeSteppingResult r;
  try {
    r = SimulateTimeStepping(*seg_.model, state_, o);
  } catch (const LimitError&) {
    throw;
  } catch (const InputError& e) {
    throw InputError(fmt::format("the run stopped after t = {:.9g} s: {}", t_last_row_, e.what()),
                     e.element());
  }
  RecordSteppingSamples(r);
  CheckFinite(*seg_.model, r.final_state);
  StudyEngineSegment& seg = result_.segments.back();
  study_internal::AddSteppingSummary(seg.stepping, r.summary);
  seg.tolerance_met = seg.tolerance_met && r.tolerance_met;
  seg.stats.steps += r.stats.steps;
  seg.stats.function_evaluations += r.stats.function_evaluations;
  result_.stats.steps += r.stats.steps;
  result_.stats.function_evaluations += r.stats.function_evaluations;
  result_.warnings.insert(result_.warnings.end(), r.warnings.begin(), r.warnings.end());
  scheme_error_ += r.summary.numerical_energy_error;
  quiet_from_ = r.last_regime_change;
  state_ = r.final_state;
  if (r.quiet) SwitchToEvents();
}

// The event-driven engine's regime changes came faster than the rule allows (`why`): the run
// goes on time stepped from the state just after the last of them.
void StudyRun::SwitchToStepping(const RegimeChangeYield& why) {
  result_.segments.back().t_end = state_.t;
  StudyEngineSegment seg;
  seg.t_begin = state_.t;
  seg.engine = StudyEngine::kStepping;
  seg.reason = EngineSwitch::kRegimeChanges;
  seg.changes = why.changes;
  seg.span = why.t_last - why.t_first;
  seg.where = why.where;
  result_.segments.push_back(std::move(seg));
  EnterStepping();
}

void StudyRun::EnterStepping() {
  // Moreau–Jean sees an approaching point at its step's midpoint (time_stepping.h).
  certificate_.SetGapTime(0.5 * def_.auto_engine->rule.step);
  if (!law_warned_) {
    law_warned_ = true;
    for (std::string& w : TimeSteppingLawWarnings(*seg_.model)) {
      result_.warnings.push_back(std::move(w));
    }
  }
  quiet_from_ = state_.t;
  engine_ = StudyEngine::kStepping;
}

// No regime has changed for the quiet span: the event-driven engine takes over. Its start
// chooses the modes and projects the touching points onto their planes; that is done here, so
// that what the projection changed (the scheme's penetration, its energy) is said and booked
// with the scheme's own energy error.
void StudyRun::SwitchToEvents() {
  const Model& model = *seg_.model;
  result_.segments.back().t_end = state_.t;
  StudyEngineSegment seg;
  seg.t_begin = state_.t;
  seg.engine = StudyEngine::kAdaptive;
  seg.reason = EngineSwitch::kQuiet;
  seg.quiet = state_.t - quiet_from_;
  SettleContacts(ContactEventReason::kEngineSwitch);
  const study_internal::EventsHandover handover = study_internal::ProjectForEvents(model, state_);
  CheckFinite(model, state_);
  seg.projection_depth = handover.depth;
  seg.projection_energy = handover.energy;
  scheme_error_ += handover.energy;
  result_.segments.push_back(std::move(seg));
  certificate_.SetGapTime(def_.certificate.gap_time);
  Certify(state_, CheckPhase::kAfterTransition);
  engine_ = StudyEngine::kAdaptive;
}

// The balls event-driven from state.t to t_b (the only segment: no jumps), sampled on the
// global grid k * dt_out (SimulateSphereEvents samples t0 + k dt_out, and t0 = 0 here or a grid
// time); every event handled and every step of a pressing group counts against the limits.
void StudyRun::RunEvents(double t_b) {
  SphereEventOptions o = *def_.sphere_events;
  o.t_end = t_b;
  o.output_interval = def_.options.output_interval;
  o.on_progress = [this](double t) { OnStep(t); };
  const SphereEventResult r = SimulateSphereEvents(*seg_.model, state_, o);
  RecordSphereEvents(r);
  state_ = r.final_state;
}

// Time stepping from state.t to t_b (the only segment), sampled on the global grid; every step
// counts against the limits. The ledger's residual at a sample is the scheme's own energy
// error, booked as its own term: the certificate checks what is left.
void StudyRun::RunStepping(double t_b) {
  TimeSteppingOptions o = *def_.time_stepping;
  o.t_end = t_b;
  o.output_interval = def_.options.output_interval;
  o.threads = def_.options.threads;
  o.on_step = [this](double t) { OnStep(t); };
  const TimeSteppingResult r = SimulateTimeStepping(*seg_.model, state_, o);
  RecordStepping(r);
  state_ = r.final_state;
}

// A time-stepped run's samples as rows, each checked (its ledger with the scheme's own energy
// error taken out: it is booked as its own term), and the regime changes at the output
// resolution (every step's count is in the summary); a run that ended early (quiet) adds the
// changes up to its final state.
void StudyRun::RecordSteppingSamples(const TimeSteppingResult& r) {
  const Model& m = *seg_.model;
  const auto changes = [&](const State& before, const State& after) {
    for (int p = 0; p < m.num_contact_points(); ++p) {
      const ContactMode a = before.contacts[static_cast<size_t>(p)].mode;
      const ContactMode b = after.contacts[static_cast<size_t>(p)].mode;
      if (a == b) continue;
      result_.contact_events.push_back({after.t,
                                        Label(p),
                                        m.contact(m.contact_of_point(p)).name(),
                                        {a, false},
                                        {b, false},
                                        ContactEventReason::kTimeStep});
    }
  };
  for (size_t k = 1; k < r.samples.size(); ++k) {  // the first is the start, already a row
    const State& s = r.samples[k];
    if (static_cast<std::int64_t>(result_.rows.size()) >= def_.limits.max_rows) {
      throw LimitError(LimitError::Limit::kRows,
                       fmt::format("the run reached the limit of {} output rows at t = {:.9g} s",
                                   def_.limits.max_rows, s.t));
    }
    CheckFinite(m, s);
    AddRow(m, s);
    certificate_.CheckState(m, s, CheckPhase::kSample);
    const LedgerSample L = CalcLedgerSample(m, s, carry_.segment_initial);
    certificate_.CheckLedger(
        s.t, carry_.residual + L.energy_residual - (scheme_error_ + r.sample_energy_error[k]),
        std::max(carry_.scale, L.energy_scale), CheckPhase::kSample);
    slip_.Sample(m, s);
    changes(r.samples[k - 1], s);
  }
  if (r.quiet && !r.samples.empty()) changes(r.samples.back(), r.final_state);
}

void StudyRun::RecordStepping(const TimeSteppingResult& r) {
  const Model& m = *seg_.model;
  RecordSteppingSamples(r);
  CheckFinite(m, r.final_state);
  result_.warnings.insert(result_.warnings.end(), r.warnings.begin(), r.warnings.end());
  result_.stats = r.stats;
  // Assigned, not emplaced: clang 14 takes a nested struct with member initialisers for not
  // default-constructible inside std::optional's constraints.
  result_.time_stepping = StudyResult::TimeStepped();
  StudyResult::TimeStepped& ts = *result_.time_stepping;
  ts.step = def_.time_stepping->step;
  ts.summary = r.summary;
  ts.tolerance_met = r.tolerance_met;
  for (int p = 0; p < m.num_contact_points(); ++p) {
    ts.regime_changes.emplace_back(Label(p), r.regime_changes[static_cast<size_t>(p)]);
  }
}

void StudyRun::RecordSphereEvents(const SphereEventResult& r) {
  const Model& m = *seg_.model;
  for (size_t k = 1; k < r.samples.size(); ++k) {  // the first is the start, already a row
    const State& s = r.samples[k];
    if (static_cast<std::int64_t>(result_.rows.size()) >= def_.limits.max_rows) {
      throw LimitError(LimitError::Limit::kRows,
                       fmt::format("the run reached the limit of {} output rows at t = {:.9g} s",
                                   def_.limits.max_rows, s.t));
    }
    CheckFinite(m, s);
    AddRow(m, s);
    Certify(s, CheckPhase::kSample);
    slip_.Sample(m, s);
  }
  CheckFinite(m, r.final_state);
  // The timeline: every point's initial mode (a pair point's is separated: the balls meet in
  // impacts, and a pressing group's pair forces are the hybrid engine's), then the changes.
  std::vector<bool> listed(static_cast<size_t>(m.num_contact_points()), false);
  for (const ContactEvent& e : r.contact_events) {
    const std::string& contact = m.contact(m.contact_of_point(e.point)).name();
    if (e.reason == ContactEventReason::kInitial) listed[static_cast<size_t>(e.point)] = true;
    result_.contact_events.push_back(
        {e.t, Label(e.point), contact, {e.from, e.held_from}, {e.to, e.held_to}, e.reason});
  }
  for (int p = 0; p < m.num_contact_points(); ++p) {
    if (listed[static_cast<size_t>(p)]) continue;
    result_.contact_events.push_back({state_.t,
                                      Label(p),
                                      m.contact(m.contact_of_point(p)).name(),
                                      {},
                                      {},
                                      ContactEventReason::kInitial});
  }
  std::stable_sort(
      result_.contact_events.begin(), result_.contact_events.end(),
      [](const StudyContactEvent& a, const StudyContactEvent& b) { return a.t < b.t; });
  // Impacts with the table and between balls, in time order; a collision of a listed pair is
  // at its contact point, of any other pair at "A | B".
  // The listed pairs' points, by their bodies (a later listing of a pair wins, as before).
  std::map<std::pair<BodyIndex, BodyIndex>, int> pair_point;
  for (int k = 0; k < m.num_contacts(); ++k) {
    const ContactSpec& s = m.contact(k).spec();
    if (s.shape != ContactShape::kSphereSphere) continue;
    pair_point[std::minmax(s.body, s.other_body)] = m.contact_point_offset(k);
  }
  std::vector<StudyImpact> impacts;
  for (const ImpactRecord& imp : r.plane_impacts) {
    impacts.push_back({imp.t, Label(imp.point), imp.approach_speed, imp.normal_impulse,
                       imp.energy_lost, imp.accumulation, imp.accumulation_time, imp.jam, imp.law,
                       imp.frictionless_fallback});
  }
  for (const SphereCollision& c : r.collisions) {
    std::string point = fmt::format("{} | {}", m.body(c.body_a).name(), m.body(c.body_b).name());
    const auto listed = pair_point.find(std::minmax(c.body_a, c.body_b));
    if (listed != pair_point.end()) point = Label(listed->second);
    impacts.push_back({c.t, point, c.approach_speed, c.normal_impulse, c.energy_lost, false,
                       std::numeric_limits<double>::quiet_NaN(), false, c.law, false});
  }
  std::stable_sort(impacts.begin(), impacts.end(),
                   [](const StudyImpact& a, const StudyImpact& b) { return a.t < b.t; });
  result_.impacts.insert(result_.impacts.end(), impacts.begin(), impacts.end());
  result_.warnings.insert(result_.warnings.end(), r.warnings.begin(), r.warnings.end());
  result_.stats = r.stats.hybrid;
  result_.event_driven =
      StudyEventDriven{r.stats, static_cast<long>(r.collisions.size()), r.energy};
}

void StudyRun::RecordSimulation(const SimulationResult& r,
                                const std::vector<ContactPointState>& carried,
                                const std::vector<EventSpec>& events) {
  const Model& m = *seg_.model;
  CheckFinite(m, r.final_state);
  result_.stats.steps += r.stats.steps;
  result_.stats.rejected_steps += r.stats.rejected_steps;
  result_.stats.function_evaluations += r.stats.function_evaluations;
  result_.stats.free_body_batch = result_.stats.free_body_batch || r.stats.free_body_batch;
  result_.islands = r.islands;
  for (const EventRecord& e : r.events) {
    const bool stop = events[static_cast<size_t>(e.event)].action == EventAction::kStop;
    Certify(e.state, CheckPhase::kEvent);
    result_.events.push_back(
        {e.name, e.t, stop,
         study_internal::MakeSnapshot(m, e.state, def_.num_reported_constraints, labels_, theta_,
                                      false),
         rows_.Row(m, seg_.map, e.state, carry_, false)});
  }
  for (const ContactEvent& e : r.contact_events) {
    // The modes carried into this run are already in the timeline: Simulate lists every
    // point's starting mode (as a change from separated); only a mode it chose differently
    // from the one carried in is news.
    ContactMode from = e.from;
    bool held_from = e.held_from;
    if (e.reason == ContactEventReason::kInitial) {
      const auto p = static_cast<size_t>(e.point);
      from = p < carried.size() ? carried[p].mode : ContactMode::kSeparated;
      held_from = p < carried.size() && carried[p].rolling_held;
      if (from == e.to && held_from == e.held_to) continue;
    }
    result_.contact_events.push_back({e.t,
                                      Label(e.point),
                                      m.contact(m.contact_of_point(e.point)).name(),
                                      {from, held_from},
                                      {e.to, e.held_to},
                                      e.reason});
  }
  for (const ConstraintEvent& e : r.constraint_events) {
    const std::string& name = m.constraint(e.constraint).name();
    // A later segment lists its strings' modes again as "initial": only news is kept.
    const bool known = strings_listed_.count(name) > 0;
    if (e.reason == ConstraintEventReason::kInitial && known && e.from == e.to &&
        e.impulse == 0.0) {
      continue;
    }
    strings_listed_.insert(name);
    result_.string_events.push_back(
        {e.t, name, e.from, e.to, e.reason, e.approach_speed, e.impulse, e.energy_lost});
  }
  for (const ImpactRecord& imp : r.impacts) {
    result_.impacts.push_back({imp.t, Label(imp.point), imp.approach_speed, imp.normal_impulse,
                               imp.energy_lost, imp.accumulation, imp.accumulation_time, imp.jam,
                               imp.law, imp.frictionless_fallback});
  }
  result_.warnings.insert(result_.warnings.end(), r.warnings.begin(), r.warnings.end());
}

// The supports' and contacts' answer to a jump whose applied impulses `impulses` are in
// state_ already: the supports' impulsive reaction, then the contacts driven into their planes,
// recorded in `rec` (reactions, every body's jumps from `before`, the impacts) and checked.
// Returns the energy between the two.
double StudyRun::AnswerJump(const State& before, std::vector<study_internal::JumpImpulse> impulses,
                            StudyJump& rec) {
  const Model& model = *seg_.model;
  Eigen::VectorXd mu = Eigen::VectorXd::Zero(model.num_constraint_rows());
  if (model.num_constraints() > 0) {
    // The supports' impulsive reaction: projecting the velocities onto the constraints with the
    // mass metric, du = M⁻¹ Jᵀ μ, is exactly the response of ideal constraints to the impulse
    // (impulse-momentum with the constraint impulse Jᵀ μ; docs/constraints.md).
    Data data = MakeData(model);
    ProjectOntoConstraints(model, state_, data, {}, &mu);
  }
  // A contact the jump drives into its plane takes an impact; then the modes are chosen again
  // for the new velocities (a sticking point may now slip). The impacts take the constraints'
  // share with them: SupportImpulseOf recovers it.
  const State projected = state_;
  const size_t first_impact = result_.impacts.size();
  std::vector<std::pair<int, Vec3>> contact_impulses;
  SettleContacts(ContactEventReason::kImpulse, &contact_impulses);
  CheckFinite(model, state_);
  for (size_t i = first_impact; i < result_.impacts.size(); ++i) {
    rec.impacts.push_back(static_cast<int>(i));
  }
  const std::vector<study_internal::JumpImpulse> contacts =
      study_internal::ContactJumpImpulses(model, state_, contact_impulses, labels_);
  mu += study_internal::SupportImpulseOf(model, projected, contacts);
  impulses.insert(impulses.end(), contacts.begin(), contacts.end());
  study_internal::RecordJumpImpulses(model, before, state_, mu, impulses,
                                     def_.num_reported_constraints, rec);
  certificate_.CheckImpulseBalance(rec.t, rec.bodies);
  return CalcMechanicalEnergy(model, projected);
}

void StudyRun::ApplyJump(const Jump& j) {
  study_internal::CloseSegment(*seg_.model, state_, carry_);
  StudyJump rec;
  rec.t = state_.t;
  rec.energy_before = CalcMechanicalEnergy(*seg_.model, state_);
  const std::shared_ptr<const Model> model_before = seg_.model;
  const State state_before = state_;
  std::vector<study_internal::JumpImpulse> impulses;
  int shown = 0;
  if (j.impulse) {
    shown = study_internal::ApplyStudyImpulse(*j.impulse, seg_, state_, &impulses);
    rec.kind = StudyJumpKind::kImpulse;
    rec.description =
        fmt::format("impulse on {}", def_.bodies[static_cast<size_t>(j.impulse->body)].name);
  } else {
    const std::string& target = def_.bodies[static_cast<size_t>(j.impact->target)].name;
    const std::string& projectile = def_.bodies[static_cast<size_t>(j.impact->projectile)].name;
    const auto model_body = [&](int b) {
      return seg_.map.place[static_cast<size_t>(b)].model_body;
    };
    if (model_body(j.impact->target) == model_body(j.impact->projectile)) {
      throw InputError(
          fmt::format(
              "impact at t = {:.6g} s: '{}' and '{}' are already one body (an earlier impact "
              "embedded one in the other)",
              j.impact->t, projectile, target),
          ErrorElement{ErrorElement::Kind::kBody, model_body(j.impact->projectile)});
    }
    shown = study_internal::ApplyStudyImpact(*j.impact, def_.build_model, seg_, state_, &impulses);
    rec.kind =
        j.impact->exit_fraction > 0 ? StudyJumpKind::kPassThrough : StudyJumpKind::kEmbedding;
    rec.description = j.impact->exit_fraction > 0
                          ? fmt::format("{} passes through {} keeping {:.4g} of its velocity",
                                        projectile, target, j.impact->exit_fraction)
                          : fmt::format("{} embeds in {}", projectile, target);
  }
  // The velocity jumps are counted from the state before; after an embedding (a new Model) from
  // the composite moving with the two bodies' momentum, so that they are the supports' doing.
  const State before = seg_.model == model_before ? state_before : state_;
  const double energy_between = AnswerJump(before, std::move(impulses), rec);
  const Model& model = *seg_.model;
  rec.energy_after = CalcMechanicalEnergy(model, state_);
  const BodyState& s = state_.bodies[static_cast<size_t>(shown)];
  rec.v_after_W = s.v_WBcm_W;
  rec.w_after_W = s.q_WB * s.w_WB_B;
  carry_.jumps += rec.energy_after - rec.energy_before;
  // The energy between the supports' answer and the contacts' is on the ledger's scale too: a
  // contact impact may take all the impulse gave (a rod struck onto the floor it rests on).
  carry_.scale = std::max({carry_.scale, std::abs(rec.energy_before), std::abs(rec.energy_after),
                           std::abs(energy_between)});
  carry_.segment_initial = state_;
  result_.jumps.push_back(std::move(rec));
  AddRow(model, state_);
  Certify(state_, CheckPhase::kSample);
}

void StudyRun::AddRow(const Model& model, const State& s) {
  t_last_row_ = s.t;
  result_.rows.push_back(rows_.Row(model, seg_.map, s, carry_));
  if (def_.record_row_poses) {
    result_.row_poses.push_back(study_internal::CalcUserBodyPoses(model, s, seg_.map));
  }
  if (!def_.record_row_snapshots) return;
  StudySnapshot snap =
      study_internal::MakeSnapshot(model, s, def_.num_reported_constraints, labels_, theta_, false);
  snap.bodies.clear();
  result_.row_snapshots.push_back(std::move(snap));
}

void StudyRun::Finish() {
  const Model& model = *seg_.model;
  result_.ledger = study_internal::FinalLedger(def_, model, state_, carry_, energy_initial_);
  result_.ledger.time_stepping_error = scheme_error_;
  if (model.num_constraints() > 0) {
    Data data = MakeData(model);
    CalcAccelerations(model, state_, data);
    if (data.constraint_rank < model.num_constraint_rows()) {
      Data scratch = MakeData(model);
      for (std::string& w : DescribeRedundancy(model, AnalyseRedundancy(model, state_, scratch))) {
        result_.warnings.push_back(std::move(w));
      }
    }
  }
  StudySnapshot final_snapshot = study_internal::MakeSnapshot(
      model, state_, def_.num_reported_constraints, labels_, theta_, true);
  result_.final_reactions = std::move(final_snapshot.reactions);
  result_.final_contacts = std::move(final_snapshot.contacts);
  result_.final_bodies = std::move(final_snapshot.bodies);
  slip_.Report(result_.notes);
  if (result_.stats.free_body_batch && def_.options.integrator == IntegratorKind::kRk4) {
    result_.notes.push_back(
        "free bodies with at most uniform gravity on them: stepped by the free-body batch (the "
        "same RK4 on a structure of arrays)");
  }
  if (!result_.segments.empty()) result_.segments.back().t_end = state_.t;
  result_.certificate = certificate_.Finish();
  result_.t_end = state_.t;
  result_.stopped_by_event = stopped_;
}

}  // namespace

namespace {

/// The definition with its initial state settled onto the constraints (settle_initial).
StudyDefinition Settled(const StudyDefinition& definition) {
  if (!definition.model) {
    throw InputError("settling the initial state needs the first Model (StudyDefinition::model)");
  }
  StudyDefinition settled = definition;
  settled.initial = SettleInitialState(*definition.model, definition.initial,
                                       *definition.settle_initial, settled.warnings);
  settled.settle_initial.reset();
  return settled;
}

}  // namespace

StudyResult RunStudy(const StudyDefinition& definition) {
  try {
    StudyResult r = definition.settle_initial ? StudyRun(Settled(definition)).Run()
                                              : StudyRun(definition).Run();
    if (definition.column_units) r.units = definition.column_units(r.columns);
    return r;
  } catch (const InputError& e) {
    if (!definition.locate_error) throw;
    definition.locate_error(e);
    throw;  // a locator that returns leaves the error as it is
  }
}

}  // namespace chasles
