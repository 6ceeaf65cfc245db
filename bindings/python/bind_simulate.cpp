// The model-level analyses: the instantaneous solve and Simulate.

#include <cmath>
#include <string>

#include "bindings.h"
#include "chasles/analysis/instantaneous.h"
#include "chasles/error.h"
#include "chasles/integrate/simulate.h"
#include "chasles/integrate/time_stepping.h"
#include "chasles/model/model.h"

namespace chasles::python {

namespace {

void BindInstantaneous(py::module_& m) {
  py::class_<BodyAccelerationReport>(m, "BodyAcceleration", "Accelerations of one body.")
      .def_readonly("name", &BodyAccelerationReport::name)
      .def_readonly("acceleration", &BodyAccelerationReport::a_WBcm_W,
                    "Of the centre of mass, in W [m/s^2]")
      .def_readonly("angular_acceleration", &BodyAccelerationReport::alpha_WB_W, "In W [rad/s^2]")
      .def_readonly("angular_acceleration_body", &BodyAccelerationReport::alpha_WB_B,
                    "In B [rad/s^2]")
      .def("__repr__", [](const BodyAccelerationReport& b) {
        return py::str("BodyAcceleration('{}', acceleration={}, angular_acceleration={})")
            .format(b.name, py::cast(b.a_WBcm_W), py::cast(b.alpha_WB_W));
      });
  py::class_<ReactionReport>(m, "Reaction",
                             "The force and moment a constraint's parent (or the world) exerts "
                             "on its child at the joint or contact point.")
      .def_readonly("name", &ReactionReport::name)
      .def_readonly("kind", &ReactionReport::kind)
      .def_readonly("parent", &ReactionReport::parent)
      .def_readonly("child", &ReactionReport::child)
      .def_readonly("point", &ReactionReport::p_WJ, "Joint or contact point in W [m]")
      .def_readonly("force", &ReactionReport::F_Jc_W, "In W [N]")
      .def_readonly("moment", &ReactionReport::M_Jc_W, "About the point, in W [N*m]")
      .def_readonly("force_body", &ReactionReport::F_Jc_B, "In the child's frame [N]")
      .def_readonly("moment_body", &ReactionReport::M_Jc_B, "In the child's frame [N*m]")
      .def_readonly("force_parent", &ReactionReport::F_Jc_P,
                    "In the parent's frame (W for a joint to the world) [N]")
      .def_readonly("moment_parent", &ReactionReport::M_Jc_P,
                    "In the parent's frame (W for a joint to the world) [N*m]")
      .def_readonly("multipliers", &ReactionReport::lambda, "Of its rows [N or N*m]")
      .def_readonly("power", &ReactionReport::power, "[W]")
      .def_readonly("is_rolling", &ReactionReport::is_rolling)
      .def_readonly("normal_force", &ReactionReport::normal_force, "Rolling: N [N]")
      .def_readonly("friction", &ReactionReport::friction_W, "Rolling: friction in W [N]")
      .def_readonly("friction_needed", &ReactionReport::friction_needed,
                    "Rolling: |f|/N, the least mu_s rolling needs")
      .def("__repr__", [](const ReactionReport& r) {
        return py::str("Reaction('{}', {}, force={}, moment={})")
            .format(r.name, r.kind, py::cast(r.F_Jc_W), py::cast(r.M_Jc_W));
      });
  py::class_<InstantaneousSolution>(m, "InstantaneousSolution",
                                    "Accelerations and reactions at one state.")
      .def_readonly("t", &InstantaneousSolution::t)
      .def_readonly("bodies", &InstantaneousSolution::bodies)
      .def_readonly("reactions", &InstantaneousSolution::reactions)
      .def_readonly("rank", &InstantaneousSolution::rank)
      .def_readonly("num_rows", &InstantaneousSolution::num_rows)
      .def_readonly("warnings", &InstantaneousSolution::warnings);
  m.def(
      "solve_instantaneous",
      [](const Model& model, const State& state, double tolerance) {
        py::gil_scoped_release release;
        return SolveInstantaneous(model, state, InstantaneousOptions{tolerance});
      },
      py::arg("model"), py::arg("state"), py::arg("tolerance") = 1e-8,
      "Accelerations of every body and reactions of every constraint at `state` (which must "
      "satisfy the constraints to `tolerance`).");
}

void BindOptions(py::module_& m) {
  py::enum_<IntegratorKind>(m, "Integrator", "Integrators of simulate().")
      .value("DORMAND_PRINCE", IntegratorKind::kDormandPrince5)
      .value("RK4", IntegratorKind::kRk4)
      .value("ENERGY_MOMENTUM", IntegratorKind::kEnergyMomentum)
      .value("SPLITTING", IntegratorKind::kSplitting);
  py::enum_<EventDirection>(m, "EventDirection", "Which zero crossings of g count.")
      .value("RISING", EventDirection::kRising)
      .value("FALLING", EventDirection::kFalling)
      .value("EITHER", EventDirection::kEither);
  py::enum_<EventAction>(m, "EventAction", "What happens at an event.")
      .value("STOP", EventAction::kStop)
      .value("RECORD", EventAction::kRecord);
  py::class_<EventSpec>(m, "EventSpec",
                        "An event: a zero crossing of g(t, state) located on the dense output "
                        "(Dormand-Prince only) to SimulationOptions.event_time_tolerance.")
      .def(py::init(
               [](std::string name, py::function g, EventDirection direction, EventAction action) {
                 EventSpec e;
                 e.name = std::move(name);
                 // A NaN or an infinity cannot be located as a zero crossing: refused at once,
                 // as the scene's events refuse one.
                 e.g = GilSafe<double, const Model&, const State&>(
                     std::move(g), [name = e.name](const py::function& f, const Model& /*model*/,
                                                   const State& state) {
                       const double v = CallbackResult<double>(f, f(state.t, state), "a number");
                       if (!std::isfinite(v)) {
                         throw InputError("event '" + name + "': g(t, state) returned " +
                                          std::string(py::str(py::float_(v))) +
                                          " at t = " + std::string(py::str(py::float_(state.t))) +
                                          " s; an event function must return a finite number");
                       }
                       return v;
                     });
                 e.direction = direction;
                 e.action = action;
                 return e;
               }),
           py::arg("name"), py::arg("g"), py::arg("direction") = EventDirection::kEither,
           py::arg("action") = EventAction::kStop)
      .def_readonly("name", &EventSpec::name)
      .def_readonly("direction", &EventSpec::direction)
      .def_readonly("action", &EventSpec::action);
  py::class_<SimulationOptions>(m, "SimulationOptions", "Settings of simulate().")
      .def(py::init([](double t_end, double output_interval, IntegratorKind integrator, double rtol,
                       double atol, double fixed_step) {
             SimulationOptions o;
             o.t_end = t_end;
             o.output_interval = output_interval;
             o.integrator = integrator;
             o.adaptive.rtol = rtol;
             o.adaptive.atol = atol;
             o.fixed_step = fixed_step;
             return o;
           }),
           py::arg("t_end"), py::arg("output_interval") = 0.0,
           py::arg("integrator") = IntegratorKind::kDormandPrince5, py::arg("rtol") = 1e-9,
           py::arg("atol") = 1e-12, py::arg("fixed_step") = 1e-3)
      .def_readwrite("t_end", &SimulationOptions::t_end, "End time [s]")
      .def_readwrite("output_interval", &SimulationOptions::output_interval,
                     "Spacing of samples [s]; 0: initial and final only")
      .def_readwrite("integrator", &SimulationOptions::integrator)
      .def_readwrite("fixed_step", &SimulationOptions::fixed_step, "[s] (RK4, energy-momentum)")
      .def_property(
          "rtol", [](const SimulationOptions& o) { return o.adaptive.rtol; },
          [](SimulationOptions& o, double v) { o.adaptive.rtol = v; }, "Relative tolerance")
      .def_property(
          "atol", [](const SimulationOptions& o) { return o.adaptive.atol; },
          [](SimulationOptions& o, double v) { o.adaptive.atol = v; }, "Absolute tolerance")
      .def_property(
          "max_step", [](const SimulationOptions& o) { return o.adaptive.max_step; },
          [](SimulationOptions& o, double v) { o.adaptive.max_step = v; },
          "Largest step [s] (inf: no limit)")
      .def_readwrite("events", &SimulationOptions::events,
                     "Events to locate (a list of EventSpec; Dormand-Prince only)")
      .def_readwrite("event_time_tolerance", &SimulationOptions::event_time_tolerance,
                     "Width of the final bracket around an event time [s]")
      .def_readwrite("islands", &SimulationOptions::islands,
                     "Run independent groups of bodies of a model with contacts separately")
      .def_readwrite("threads", &SimulationOptions::threads,
                     "Threads over the islands (>= 1; the result is the same for any number)");
}

/// Samples as a table: t, then per body its centre of mass, quaternion, velocity and angular
/// velocity in B (the names of a scene run's columns).
py::tuple SamplesTable(const std::vector<State>& samples, const Model& model) {
  std::vector<std::string> names = {"t"};
  std::vector<std::string> units = {"s"};
  const char* suffix[] = {"x",  "y",  "z",  "qw",  "qx",  "qy", "qz",
                          "vx", "vy", "vz", "wbx", "wby", "wbz"};
  const char* unit[] = {"m",   "m",   "m",   "",      "",      "",     "",
                        "m/s", "m/s", "m/s", "rad/s", "rad/s", "rad/s"};
  for (int b = 0; b < model.num_bodies(); ++b) {
    for (int k = 0; k < 13; ++k) {
      names.push_back(model.body(b).name() + "_" + suffix[k]);
      units.push_back(unit[k]);
    }
  }
  std::vector<std::vector<double>> rows;
  for (const State& s : samples) {
    std::vector<double> row = {s.t};
    for (const BodyState& b : s.bodies) {
      row.insert(row.end(), {b.p_WBcm.x(), b.p_WBcm.y(), b.p_WBcm.z(), b.q_WB.w(), b.q_WB.x(),
                             b.q_WB.y(), b.q_WB.z(), b.v_WBcm_W.x(), b.v_WBcm_W.y(), b.v_WBcm_W.z(),
                             b.w_WB_B.x(), b.w_WB_B.y(), b.w_WB_B.z()});
    }
    rows.push_back(std::move(row));
  }
  return py::make_tuple(names, units, TableArray(rows, names.size()));
}

void BindResult(py::module_& m) {
  py::class_<IntegratorStats>(m, "IntegratorStats", "Work counters of a run.")
      .def_readonly("steps", &IntegratorStats::steps)
      .def_readonly("rejected_steps", &IntegratorStats::rejected_steps)
      .def_readonly("function_evaluations", &IntegratorStats::function_evaluations)
      .def_readonly("free_body_batch", &IntegratorStats::free_body_batch,
                    "True when the free-body batch (structure of arrays) stepped the run");
  py::class_<EventRecord>(m, "EventRecord", "A located event.")
      .def_readonly("name", &EventRecord::name)
      .def_readonly("t", &EventRecord::t)
      .def_readonly("event", &EventRecord::event, "Index into SimulationOptions.events")
      .def_readonly("state", &EventRecord::state);
  py::class_<ContactEvent>(m, "ContactEvent", "A mode change of one contact point.")
      .def_readonly("t", &ContactEvent::t)
      .def_readonly("point", &ContactEvent::point)
      .def_readonly("from_mode", &ContactEvent::from)
      .def_readonly("to_mode", &ContactEvent::to)
      .def_readonly("held_from", &ContactEvent::held_from,
                    "Rolling held by rolling resistance before the change")
      .def_readonly("held_to", &ContactEvent::held_to,
                    "Rolling held by rolling resistance after the change")
      .def_property_readonly("reason", [](const ContactEvent& e) {
        return std::string(ContactEventReasonName(e.reason));
      });
  py::class_<ImpactRecord>(m, "ImpactRecord", "One impact at a contact point.")
      .def_readonly("t", &ImpactRecord::t)
      .def_readonly("point", &ImpactRecord::point)
      .def_readonly("approach_speed", &ImpactRecord::approach_speed)
      .def_readonly("normal_impulse", &ImpactRecord::normal_impulse)
      .def_readonly("energy_lost", &ImpactRecord::energy_lost);
  py::class_<IslandReport>(m, "IslandReport", "How a run with contacts was split into islands.")
      .def_readonly("split", &IslandReport::split, "True: the islands ran separately")
      .def_readonly("count", &IslandReport::count, "Number of islands (0: not looked for)")
      .def_readonly("reason", &IslandReport::reason, "Why the run was one system")
      .def_readonly("bodies", &IslandReport::bodies, "Each island's bodies (when split)")
      .def_readonly("stats", &IslandReport::stats, "Each island's work (when split)");
  py::class_<SimulationResult>(m, "SimulationResult", "Samples, events and counters of a run.")
      .def_readonly("samples", &SimulationResult::samples, "States at the output times")
      .def_readonly("final_state", &SimulationResult::final_state)
      .def_readonly("events", &SimulationResult::events)
      .def_readonly("stopped_by_event", &SimulationResult::stopped_by_event)
      .def_readonly("stats", &SimulationResult::stats)
      .def_readonly("contact_events", &SimulationResult::contact_events)
      .def_readonly("impacts", &SimulationResult::impacts)
      .def_readonly("warnings", &SimulationResult::warnings)
      .def_readonly("islands", &SimulationResult::islands)
      .def(
          "_table",
          [](const SimulationResult& r, const Model& model) {
            return SamplesTable(r.samples, model);
          },
          py::arg("model"));
  m.def(
      "_simulate",
      [](const Model& model, const State& initial, const SimulationOptions& options) {
        py::gil_scoped_release release;
        return Simulate(model, initial, options);
      },
      py::arg("model"), py::arg("initial"), py::arg("options"));
}

/// The settings time stepping shares with the event-driven engines: the law of the ball pairs
/// no contact lists, the tolerances of the active set and the contact problem's solver.
void BindSteppingSettings(py::module_& m) {
  py::class_<SphereCollisionLaw>(m, "SphereCollisionLaw",
                                 "Coefficients of the collisions between balls that the model "
                                 "does not list as sphere-sphere contacts.")
      .def(py::init([](double restitution, double mu_s, double mu_k, RestitutionLaw law) {
             return SphereCollisionLaw{restitution, mu_s, mu_k, law};
           }),
           py::arg("restitution") = 0.0, py::arg("mu_s") = 0.0, py::arg("mu_k") = 0.0,
           py::arg("law") = RestitutionLaw::kEnergetic)
      .def_readwrite("restitution", &SphereCollisionLaw::restitution, "Coefficient (0 to 1)")
      .def_readwrite("mu_s", &SphereCollisionLaw::mu_s, "Static friction coefficient")
      .def_readwrite("mu_k", &SphereCollisionLaw::mu_k, "Kinetic friction coefficient")
      .def_readwrite("law", &SphereCollisionLaw::law,
                     "Restitution law of the event-driven engine (time stepping applies "
                     "Newton's law at all touching points at once and does not read it)");
  py::class_<ContactTolerances>(m, "ContactTolerances", "Tolerances of contact modes and impacts.")
      .def(py::init([](double gap, double resting_speed, double stick_speed, double relative,
                       double cone) {
             return ContactTolerances{gap, resting_speed, stick_speed, relative, cone};
           }),
           py::arg("gap") = ContactTolerances{}.gap,
           py::arg("resting_speed") = ContactTolerances{}.resting_speed,
           py::arg("stick_speed") = ContactTolerances{}.stick_speed,
           py::arg("relative") = ContactTolerances{}.relative,
           py::arg("cone") = ContactTolerances{}.cone)
      .def_readwrite("gap", &ContactTolerances::gap,
                     "A point with gap at or below this is touching [m]")
      .def_readwrite("resting_speed", &ContactTolerances::resting_speed,
                     "Approach speed at or below this is resting contact, not an impact [m/s]")
      .def_readwrite("stick_speed", &ContactTolerances::stick_speed,
                     "Slip speed at or below this may stick (time stepping: mu_s) [m/s]")
      .def_readwrite("relative", &ContactTolerances::relative,
                     "Relative tolerance of the sign tests")
      .def_readwrite("cone", &ContactTolerances::cone,
                     "Relative tolerance of the friction-cone test");
  py::class_<ContactProblemSettings>(m, "ContactProblemSettings",
                                     "Settings of the frictional contact problem's solver.")
      .def(py::init([](double tolerance, int max_newton_iterations, int max_sweeps) {
             return ContactProblemSettings{tolerance, max_newton_iterations, max_sweeps};
           }),
           py::arg("tolerance") = ContactProblemSettings{}.tolerance,
           py::arg("max_newton_iterations") = ContactProblemSettings{}.max_newton_iterations,
           py::arg("max_sweeps") = ContactProblemSettings{}.max_sweeps)
      .def_readwrite("tolerance", &ContactProblemSettings::tolerance,
                     "Residual tolerance, relative to the impulse scale")
      .def_readwrite("max_newton_iterations", &ContactProblemSettings::max_newton_iterations,
                     "Newton iterations before the Gauss-Seidel sweeps take over")
      .def_readwrite("max_sweeps", &ContactProblemSettings::max_sweeps,
                     "Gauss-Seidel sweeps at most");
}

void BindSteppingOptions(py::module_& m) {
  const TimeSteppingOptions d;
  py::class_<TimeSteppingOptions>(m, "TimeSteppingOptions",
                                  "Settings of simulate_time_stepping() (Moreau-Jean time "
                                  "stepping, docs/contact.md, \"Time stepping\").")
      .def(py::init([](double t_end, double step, double output_interval,
                       const ContactTolerances& tolerances, const ContactProblemSettings& solver,
                       bool collide_all_pairs, const SphereCollisionLaw& pair_law,
                       std::vector<double> ball_radii, bool error_estimate,
                       double velocity_tolerance, int threads, bool store_steps, bool store_samples,
                       double quiet_span, double quiet_from) {
             TimeSteppingOptions o;
             o.t_end = t_end;
             o.step = step;
             o.output_interval = output_interval;
             o.tolerances = tolerances;
             o.solver = solver;
             o.collide_all_pairs = collide_all_pairs;
             o.pair_law = pair_law;
             o.ball_radii = std::move(ball_radii);
             o.error_estimate = error_estimate;
             o.velocity_tolerance = velocity_tolerance;
             o.threads = threads;
             o.store_steps = store_steps;
             o.store_samples = store_samples;
             o.quiet_span = quiet_span;
             o.quiet_from = quiet_from;
             return o;
           }),
           py::arg("t_end"), py::arg("step") = d.step, py::arg("output_interval") = 0.0,
           py::arg("tolerances") = d.tolerances, py::arg("solver") = d.solver,
           py::arg("collide_all_pairs") = false, py::arg("pair_law") = d.pair_law,
           py::arg("ball_radii") = std::vector<double>{}, py::arg("error_estimate") = true,
           py::arg("velocity_tolerance") = d.velocity_tolerance, py::arg("threads") = 1,
           py::arg("store_steps") = false, py::arg("store_samples") = true,
           py::arg("quiet_span") = d.quiet_span, py::arg("quiet_from") = d.quiet_from)
      .def_readwrite("t_end", &TimeSteppingOptions::t_end, "End time [s]")
      .def_readwrite("step", &TimeSteppingOptions::step,
                     "Step h [s] (> 0); shortened to divide the output interval (or the run)")
      .def_readwrite("output_interval", &TimeSteppingOptions::output_interval,
                     "Spacing of samples [s]; 0: initial and final only")
      .def_readwrite("tolerances", &TimeSteppingOptions::tolerances,
                     "ContactTolerances: gap is the touching tolerance [m], stick_speed picks "
                     "mu_s [m/s]")
      .def_readwrite("solver", &TimeSteppingOptions::solver,
                     "ContactProblemSettings: the contact problem's residual tolerance")
      .def_readwrite("collide_all_pairs", &TimeSteppingOptions::collide_all_pairs,
                     "Every pair of balls may collide, with pair_law (a listed sphere-sphere "
                     "contact keeps its own)")
      .def_readwrite("pair_law", &TimeSteppingOptions::pair_law,
                     "SphereCollisionLaw of the pairs no contact lists")
      .def_readwrite("ball_radii", &TimeSteppingOptions::ball_radii,
                     "Per body the radius of its ball [m] (0: not a ball); empty: the bodies' "
                     "sphere contacts centred at their centres of mass")
      .def_readwrite("error_estimate", &TimeSteppingOptions::error_estimate,
                     "Estimate the velocity error by step doubling (three solves per step)")
      .def_readwrite("velocity_tolerance", &TimeSteppingOptions::velocity_tolerance,
                     "Bound on the run's accumulated velocity error estimate [m/s] (inf: none)")
      .def_readwrite("threads", &TimeSteppingOptions::threads,
                     "Threads over each step's islands (>= 1; the result is the same for any)")
      .def_readwrite("store_steps", &TimeSteppingOptions::store_steps,
                     "Keep every step's certificate in result.steps")
      .def_readwrite("store_samples", &TimeSteppingOptions::store_samples,
                     "Keep every sample in result.samples")
      .def_readwrite("quiet_span", &TimeSteppingOptions::quiet_span,
                     "End after the first step quiet_span [s] after the last regime change "
                     "(inf: never)")
      .def_readwrite("quiet_from", &TimeSteppingOptions::quiet_from,
                     "Time of the last regime change before this run [s] (NaN: the initial "
                     "time)");
}

void BindSteppingStep(py::module_& m) {
  using S = TimeSteppingStep;
  py::class_<S>(m, "TimeSteppingStep", "The certificate of one time step.")
      .def_readonly("t", &S::t, "End of the step [s]")
      .def_readonly("active_points", &S::active_points)
      .def_readonly("islands", &S::islands)
      .def_readonly("largest_island", &S::largest_island,
                    "The points of the step's largest island (its largest contact problem)")
      .def_readonly("residual_impulse", &S::residual_impulse, "max |F_i| [N*s]")
      .def_readonly("residual_velocity", &S::residual_velocity, "max |F_i| / rho_i [m/s]")
      .def_readonly("impulse_scale", &S::impulse_scale, "The solver tolerance's scale [N*s]")
      .def_readonly("newton_iterations", &S::newton_iterations)
      .def_readonly("sweeps", &S::sweeps)
      .def_readonly("momentum_residual", &S::momentum_residual, "[N*s]")
      .def_readonly("angular_momentum_residual", &S::angular_momentum_residual, "[N*m*s]")
      .def_readonly("energy_change", &S::energy_change, "Change of T + V [J]")
      .def_readonly("work_nonconservative", &S::work_nonconservative, "[J]")
      .def_readonly("work_normal", &S::work_normal, "Of the normal impulses [J]")
      .def_readonly("work_friction", &S::work_friction, "Of the friction impulses [J]")
      .def_readonly("numerical_energy_error", &S::numerical_energy_error,
                    "The scheme's own energy error [J]")
      .def_readonly("max_penetration", &S::max_penetration, "At the step's end [m]")
      .def_readonly("gap_drift", &S::gap_drift, "Of points held closed [m]")
      .def_readonly("regime_changes", &S::regime_changes)
      .def_readonly("velocity_error", &S::velocity_error, "Step doubling [m/s]")
      .def_readonly("angular_velocity_error", &S::angular_velocity_error, "[rad/s]")
      .def_readonly("accumulated_velocity_error", &S::accumulated_velocity_error,
                    "The run's estimate at the step's end, largest over the bodies [m/s]")
      .def_readonly("converged", &S::converged, "The contact problems met their tolerance")
      .def_readonly("within_tolerance", &S::within_tolerance,
                    "The estimate met velocity_tolerance");
}

void BindSteppingSummary(py::module_& m) {
  using S = TimeSteppingSummary;
  py::class_<S>(m, "TimeSteppingSummary", "The run's certificate: the worst steps and the totals.")
      .def_readonly("steps", &S::steps)
      .def_readonly("max_residual_impulse", &S::max_residual_impulse, "[N*s]")
      .def_readonly("max_residual_velocity", &S::max_residual_velocity, "[m/s]")
      .def_readonly("max_momentum_residual", &S::max_momentum_residual, "[N*s]")
      .def_readonly("max_angular_momentum_residual", &S::max_angular_momentum_residual, "[N*m*s]")
      .def_readonly("max_penetration", &S::max_penetration, "[m]")
      .def_readonly("max_gap_drift", &S::max_gap_drift, "[m]")
      .def_readonly("max_velocity_error", &S::max_velocity_error, "[m/s]")
      .def_readonly("max_angular_velocity_error", &S::max_angular_velocity_error, "[rad/s]")
      .def_readonly("accumulated_velocity_error", &S::accumulated_velocity_error,
                    "Estimate of |v - v_exact| at the end, largest over the bodies [m/s]")
      .def_readonly("initial_energy", &S::initial_energy, "T + V [J]")
      .def_readonly("final_energy", &S::final_energy, "T + V [J]")
      .def_readonly("work_nonconservative", &S::work_nonconservative, "[J]")
      .def_readonly("work_normal", &S::work_normal, "[J]")
      .def_readonly("work_friction", &S::work_friction, "[J]")
      .def_readonly("numerical_energy_error", &S::numerical_energy_error, "[J]")
      .def_readonly("regime_changes", &S::regime_changes)
      .def_readonly("newton_iterations", &S::newton_iterations)
      .def_readonly("sweeps", &S::sweeps)
      .def_readonly("largest_island", &S::largest_island,
                    "The most points in one island over the run (the report's largest contact "
                    "problem)");
}

void BindSteppingResult(py::module_& m) {
  BindSteppingStep(m);
  BindSteppingSummary(m);
  using R = TimeSteppingResult;
  py::class_<R>(m, "TimeSteppingResult", "Samples and certificate of a time-stepping run.")
      .def_readonly("samples", &R::samples,
                    "Initial state, one per output time, final state (each point's mode its "
                    "regime in the step that ended there)")
      .def_readonly("final_state", &R::final_state)
      .def_readonly("sample_energy_error", &R::sample_energy_error,
                    "The scheme's energy error accumulated up to each sample [J]")
      .def_readonly("steps", &R::steps, "Every step's certificate (with store_steps)")
      .def_readonly("summary", &R::summary)
      .def_readonly("regime_changes", &R::regime_changes, "Per contact point, over the run")
      .def_readonly("stats", &R::stats)
      .def_readonly("tolerance_met", &R::tolerance_met,
                    "Every step met the solver's residual tolerance and velocity_tolerance")
      .def_readonly("warnings", &R::warnings)
      .def_readonly("quiet", &R::quiet,
                    "The run ended early, quiet_span after the last regime change")
      .def_readonly("last_regime_change", &R::last_regime_change, "[s]")
      .def(
          "_table", [](const R& r, const Model& model) { return SamplesTable(r.samples, model); },
          py::arg("model"));
  m.def(
      "_simulate_time_stepping",
      [](const Model& model, const State& initial, const TimeSteppingOptions& options) {
        py::gil_scoped_release release;
        return SimulateTimeStepping(model, initial, options);
      },
      py::arg("model"), py::arg("initial"), py::arg("options"));
}

}  // namespace

void BindSimulate(py::module_& m) {
  BindInstantaneous(m);
  BindOptions(m);
  BindResult(m);
  BindSteppingSettings(m);
  BindSteppingOptions(m);
  BindSteppingResult(m);
}

}  // namespace chasles::python
