#pragma once
/// @file
/// Time stepping for dense contact (docs/contact.md, "Time stepping"): Moreau–Jean's scheme at
/// velocity level with θ = ½, which steps through regime changes instead of locating them and
/// so finishes where the event-driven engines cannot (pressing groups, chatter). Each step of
/// length h, from (q_k, u_k):
///   q_m = q_k + h/2 u_k                         (midpoint configuration; contacts, J, forces)
///   active points: gap(q_m) <= the touching tolerance
///   M (u_k+1 - u_k) = h f(t_k + h/2, q_m, u_k) + Jᵀ P
///   U = J u_k+1, the frictional contact problem (contact_problem.h) with Newton's impact law
///   applied to all active points at once (Moreau's simultaneous law): U_n + e U_n,k >= 0 ⟂
///   P_n >= 0 (U_n,k = J_n u_k), and Coulomb's cone, exact (no regularisation, so no creep);
///   q_k+1 = q_k + h (u_k + u_k+1)/2.
/// The cone's coefficient is mu_s at a point whose slip at the step's start is at most
/// stick_speed and mu_k otherwise. Only the points that touch couple bodies, so each step's
/// contact problem splits into the islands of bodies linked by active sphere-sphere points,
/// solved each on its own (islands merge and split as points open and close).
///
/// Every step is certified (TimeSteppingStep): the contact problem's residual in N·s and m/s,
/// the balance of linear and angular momentum with the impulses applied, the energy ledger
/// with the scheme's own energy error booked as a separate term, the largest penetration, the
/// drift of the gaps of points held closed, each point's regime and the changes, and an
/// a-posteriori estimate of the velocity error: each step's local error by step doubling (two half
/// steps are taken as the step; one full step from the same state estimates their error), and the
/// run's accumulated error of each body's velocity, carried through the impacts (each one's
/// timing and normal, to first order in h) and summed over the smooth steps. A run whose steps do
/// not meet the requested tolerances says so (TimeSteppingResult::tolerance_met, warnings).

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "chasles/dynamics/contact_solve.h"
#include "chasles/integrate/contact_problem.h"
#include "chasles/integrate/obstacle.h"
#include "chasles/integrate/sphere_events.h"
#include "chasles/integrate/stats.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {

struct TimeSteppingOptions {
  /// End time [s].
  double t_end = 0.0;
  /// Step h [s] (> 0); shortened so that it divides the output interval (or the run) evenly.
  double step = 1e-3;
  /// Spacing of output samples [s]; 0: only the initial and final states.
  double output_interval = 0.0;
  /// Tolerances: `gap` is the touching tolerance of the active set, `stick_speed` picks mu_s.
  ContactTolerances tolerances;
  /// The contact problem's settings (its residual tolerance, relative to the impulse scale).
  ContactProblemSettings solver;
  /// Every pair of balls may collide (docs/contact.md, "Every pair of balls"): a ball is a body
  /// with a sphere contact centred at its centre of mass (BallRadii). Each step a broadphase
  /// (FindSpherePairs) finds the pairs of balls that touch at its midpoint, and each becomes an
  /// active point of that step with pair_law's coefficients (restitution by Newton's law at all
  /// points at once, as every point here: pair_law.law is not read), joining the islands and
  /// the certificate like the model's points; their works go to State::unlisted_contact_work.
  /// A pair the model lists as a sphere-sphere contact keeps its own contact. false: only the
  /// model's points.
  bool collide_all_pairs = false;
  SphereCollisionLaw pair_law;
  /// With collide_all_pairs: per body, the radius of its ball [m] (0: not a ball), the sphere
  /// centred at its centre of mass; empty: BallRadii(model).
  std::vector<double> ball_radii;
  /// Estimate the velocity error: each step's by step doubling (three contact solves per step)
  /// and the run's accumulated error (TimeSteppingSummary::accumulated_velocity_error).
  bool error_estimate = true;
  /// Requested bound on the run's accumulated velocity error estimate [m/s] (infinite: none).
  /// The first step that takes the estimate above it is reported (tolerance_met false and a
  /// warning); the run goes on.
  double velocity_tolerance = std::numeric_limits<double>::infinity();
  /// Threads over each step's islands (>= 1; fewer when a step has fewer islands or the system
  /// starts fewer, parallel.h). The result is bitwise the same for any number: the islands share
  /// no body, and their certificates are merged in island order.
  int threads = 1;
  /// Keep every step's certificate in TimeSteppingResult::steps.
  bool store_steps = false;
  /// Keep every sample in TimeSteppingResult::samples.
  bool store_samples = true;
  /// Called with every output sample (optional).
  std::function<void(const State&)> on_sample = nullptr;
  /// Called after every step with its end time (optional); may throw LimitError to stop.
  std::function<void(double t)> on_step = nullptr;
  /// End the run early, after the first step that ends `quiet_span` [s] or more after the last
  /// regime change (integrator: auto hands the run back to the event-driven engine there;
  /// docs/contact.md, "Choosing the engine"). Infinite: never (the default).
  double quiet_span = std::numeric_limits<double>::infinity();
  /// The time of the last regime change before this run [s] (a run continuing another);
  /// NaN: the initial time.
  double quiet_from = std::numeric_limits<double>::quiet_NaN();
};

/// The certificate of one step.
struct TimeSteppingStep {
  /// End of the step [s].
  double t = 0.0;
  /// Active points, the islands their contact problems formed, and the points of the largest
  /// island (the largest contact problem solved).
  int active_points = 0;
  int islands = 0;
  int largest_island = 0;
  /// The contact problems' residual reached: max |F_i| [N·s] and max |F_i| / ρ_i [m/s], and
  /// the impulse scale the solver's tolerance is relative to [N·s].
  double residual_impulse = 0.0;
  double residual_velocity = 0.0;
  double impulse_scale = 0.0;
  /// Newton iterations and Gauss–Seidel sweeps (all islands, all sub-steps).
  int newton_iterations = 0;
  int sweeps = 0;
  /// |Δ(Σ m v) - Σ h F - Σ P| [N·s] and the same for the angular momentum about Wo [N·m·s]:
  /// zero but for round-off (the impulses are applied exactly).
  double momentum_residual = 0.0;
  double angular_momentum_residual = 0.0;
  /// Energy ledger of the step [J]: the change of T + V, the work of the force elements'
  /// non-conservative parts, of the normal impulses (impacts and resting contact: their
  /// restitution loss) and of friction impulses, and what is left: the scheme's own energy
  /// error, ΔE - W_nc - W_normal - W_friction.
  double energy_change = 0.0;
  double work_nonconservative = 0.0;
  double work_normal = 0.0;
  double work_friction = 0.0;
  double numerical_energy_error = 0.0;
  /// Largest penetration at the step's end (max of -gap over points, 0 if none) [m], and the
  /// largest change of gap over the step of a point that stayed sticking or sliding [m].
  double max_penetration = 0.0;
  double gap_drift = 0.0;
  /// Points whose regime changed in this step.
  int regime_changes = 0;
  /// Step doubling: max over bodies of |v_two halves - v_one step| [m/s] and of the angular
  /// velocities [rad/s] (0 without the estimate).
  double velocity_error = 0.0;
  double angular_velocity_error = 0.0;
  /// The run's accumulated estimate of the bodies' velocity error at the step's end, the
  /// largest over the bodies [m/s] (0 without the estimate).
  double accumulated_velocity_error = 0.0;
  /// Whether the contact problems met their residual tolerance and the estimate its bound.
  bool converged = true;
  bool within_tolerance = true;
};

/// The run's certificate: the worst of the steps and the totals.
struct TimeSteppingSummary {
  int steps = 0;
  double max_residual_impulse = 0.0;
  double max_residual_velocity = 0.0;
  double max_momentum_residual = 0.0;
  double max_angular_momentum_residual = 0.0;
  double max_penetration = 0.0;
  double max_gap_drift = 0.0;
  double max_velocity_error = 0.0;
  double max_angular_velocity_error = 0.0;
  /// The accumulated estimate of the velocity error at the end, the largest over the bodies
  /// [m/s] (docs/contact.md, "The accumulated error estimate"): an upper estimate of
  /// |v - v_exact| of each body's linear velocity, first order in h. Stretches merged
  /// (MergeSteppingSummary) add theirs.
  double accumulated_velocity_error = 0.0;
  /// Energy at the start and the end (T + V) [J], and the totals of the ledger's terms [J].
  double initial_energy = 0.0;
  double final_energy = 0.0;
  double work_nonconservative = 0.0;
  double work_normal = 0.0;
  double work_friction = 0.0;
  double numerical_energy_error = 0.0;
  long regime_changes = 0;
  long newton_iterations = 0;
  long sweeps = 0;
  /// The most points in one island over the run (the largest contact problem solved).
  int largest_island = 0;
};

struct TimeSteppingResult {
  /// Initial state, one per output time, final state. Each point's mode is its regime in the
  /// step that ended there (separated, sticking, sliding).
  std::vector<State> samples;
  State final_state;
  /// The scheme's energy error accumulated up to each sample (one per sample, kept even
  /// without store_samples) [J]: the ledger's residual at that sample is this term.
  std::vector<double> sample_energy_error;
  /// Every step's certificate (with TimeSteppingOptions::store_steps).
  std::vector<TimeSteppingStep> steps;
  TimeSteppingSummary summary;
  /// Per contact point: regime changes over the run.
  std::vector<int> regime_changes;
  /// Steps taken (each of two half steps with the estimate).
  IntegratorStats stats;
  /// Whether every step met the solver's residual tolerance and the velocity tolerance.
  bool tolerance_met = true;
  /// What the run did that the user should know (the first step that missed a tolerance, ...).
  std::vector<std::string> warnings;
  /// True when the run ended early because no regime changed for options.quiet_span:
  /// final_state is the end of that step (not a sample).
  bool quiet = false;
  /// The end of the last step that changed a regime (or options.quiet_from) [s].
  double last_regime_change = 0.0;
};

/// Adds the certificate of a later stretch (or step) `add` to `into`: the steps, the worst of
/// the two, the totals and the accumulated estimates; the energies at the ends are left as they
/// are.
void MergeSteppingSummary(TimeSteppingSummary& into, const TimeSteppingSummary& add);

/// Why `model` cannot be time stepped (constraints are not taken yet, nor rolling
/// resistance): names the first element that does not fit; empty when it can.
ModelObstacle TimeSteppingObstacle(const Model& model);

/// What a run of `model` by time stepping should tell the user about its impact law: for each
/// contact with restitution whose restitution_law is not Newton's, that the scheme applies
/// Newton's law at all touching points at once instead (empty when none).
std::vector<std::string> TimeSteppingLawWarnings(const Model& model);

/// Runs `model` from `initial` to options.t_end by Moreau–Jean time stepping. Throws
/// InputError for a model that does not fit (TimeSteppingObstacle), an invalid state or options,
/// and when a velocity becomes non-finite (naming the body and the time).
TimeSteppingResult SimulateTimeStepping(const Model& model, const State& initial,
                                        const TimeSteppingOptions& options);

}  // namespace chasles
