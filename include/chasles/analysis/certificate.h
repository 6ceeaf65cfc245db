#pragma once
/// @file
/// The certificate: a run (or an instantaneous solve) checks its own answer at every output
/// sample and at every event — the Coulomb cone of sticking points, the kinetic friction of
/// sliding points, N >= 0, gaps, constraint residuals, the work-energy ledger and the
/// Newton–Euler balance of every body with all the forces that act on it — and at every
/// impulse or impact the impulse-momentum balance of every body with all the impulses on it
/// (docs/contact.md, "Certificate"). Each check compares its worst value with a tolerance scaled by
/// the problem's own sizes (force, moment, length, velocity, energy), never a bare number.
///
/// Use: a CertificateBuilder is fed states (CheckState) and ledger residuals (CheckLedger) in
/// any order; Finish() turns what it saw into a Certificate. The scales are those of the whole
/// run (the largest seen), so a check's tolerance does not depend on the order of the samples.

#include <string>
#include <vector>

#include "chasles/model/data.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {

/// Relative tolerances of the checks; each multiplies a scale of the problem.
struct CertificateTolerances {
  /// Force-level checks at one state (friction cone, sliding friction, N >= 0, Newton–Euler
  /// balance): the forces come from one linear solve, exact up to round-off amplified by its
  /// conditioning (gear trains reach 1e-12 of the moment scale), so this is some 45,000
  /// machine epsilons (2.2e-16) of the force scale (the largest force of the run, m |g|
  /// included) or the moment scale.
  double force = 1e-11;
  /// State-level checks (gap, constraint position and velocity residuals): the projection
  /// after every step holds them to round-off, but output samples and events are read from
  /// the integrator's dense output between two projections, so they carry its local error.
  /// The study raises it with a looser integrator tolerance (CertificateTolerancesFor); it
  /// multiplies the length scale (gap, positions) or the velocity scale (velocities).
  double state = 1e-9;
  /// Time stepping (time_stepping.h) detects a touching point at its step's midpoint, so an
  /// approaching point sinks up to half a step times its approach speed before its impulse
  /// stops it: the gap check then allows this time [s] times the velocity scale as well
  /// (half the step; 0 for the other integrators, whose projection holds the gap).
  double gap_time = 0.0;
  /// The ledger residual E - E0 - W_nc - jumps, relative to the energy scale: the global
  /// integration error of the whole run (raised likewise with a looser tolerance).
  double ledger = 1e-7;
  /// Impulse-momentum balance of every body at an impulse or impact (CheckImpulseBalance):
  /// the velocity jumps and the supports' impulses come from one projection (a linear solve)
  /// and the contact impacts' impulses, exact up to round-off as the force-level checks are;
  /// relative to the impulse scale (the largest impulse or momentum change of the run's jumps)
  /// or the angular impulse scale.
  double impulse = 1e-11;
};

/// When a state was checked.
enum class CheckPhase { kSample, kEvent, kBeforeTransition, kAfterTransition, kSolve, kJump };

/// One impulse on a body over an impulsive instant (chapter 8.5): a force impulse J at a point
/// P and a moment impulse about P.
struct BodyImpulse {
  /// Where it comes from: "applied" (an impulse, or a projectile passing through), a
  /// constraint's name (its share on this body), "contact '<point>'" (an impact or a jam).
  std::string source;
  /// P in W [m].
  Vec3 p_WP = Vec3::Zero();
  /// Force impulse, in W [N·s].
  Vec3 J_W = Vec3::Zero();
  /// Moment impulse about P, in W [N·m·s].
  Vec3 M_W = Vec3::Zero();
};

/// One body over an impulsive instant: its velocity jumps and every impulse on it, so that the
/// impulse-momentum principle (eqs. 8.118, 8.119) is checkable from these values alone:
///   m Δv_cm = Σ J,   ΔH_cm = Σ (p_WP - p_WBcm) × J + M,
/// with ΔH_cm = I_W Δω (the positions do not move over the instant). For a body made at the
/// instant (a projectile embedding in a target) "before" is the two bodies' momentum as one
/// body: Δ is then what the supports did.
struct BodyImpulseBalance {
  /// Name of the body.
  std::string body;
  /// Mass [kg] and centre of mass in W [m].
  double mass = 0.0;
  Vec3 p_WBcm = Vec3::Zero();
  /// Velocity of the centre of mass and angular velocity just after, in W [m/s, rad/s].
  Vec3 v_WBcm_W = Vec3::Zero();
  Vec3 w_WB_W = Vec3::Zero();
  /// Their jumps over the instant, in W [m/s, rad/s].
  Vec3 dv_WBcm_W = Vec3::Zero();
  Vec3 dw_WB_W = Vec3::Zero();
  /// Angular momentum about the centre of mass just after, and its jump, in W [kg·m²/s].
  Vec3 H_Bcm_W = Vec3::Zero();
  Vec3 dH_Bcm_W = Vec3::Zero();
  /// Every impulse on the body.
  std::vector<BodyImpulse> impulses;
};

/// "sample", "event", "before a contact transition", ...
const char* CheckPhaseName(CheckPhase phase);

/// One check over the whole run.
struct CheckResult {
  /// Short name ("friction cone", "gap", "linear momentum balance", ...).
  std::string name;
  /// What it compares, for the report.
  std::string description;
  /// SI unit of value and tolerance ("N", "m or rad", ...).
  std::string unit;
  /// Number of values checked (0: the check did not apply, e.g. no sticking point).
  long long count = 0;
  /// The worst value (the one closest to or furthest past its tolerance) and its tolerance.
  double worst = 0.0;
  double tolerance = 0.0;
  /// Where (body, contact point or constraint, with its row) and when the worst value was.
  std::string where;
  double t = 0.0;
  CheckPhase phase = CheckPhase::kSample;
  bool passed() const { return !(worst > tolerance); }
};

struct Certificate {
  std::vector<CheckResult> checks;
  /// The scales the tolerances multiply [N, N·m, m, m/s, J, N·s, N·m·s] (the last two 0 for a
  /// run without impulses or impacts).
  double force_scale = 0.0, moment_scale = 0.0, length_scale = 0.0, velocity_scale = 0.0,
         energy_scale = 0.0, impulse_scale = 0.0, angular_impulse_scale = 0.0;
  bool passed() const;
  /// One sentence per failed check (the warnings of a report).
  std::vector<std::string> FailureMessages() const;
};

class CertificateBuilder {
 public:
  explicit CertificateBuilder(const CertificateTolerances& tolerances = {});

  /// Checks `state` with `data` evaluated at it (CalcAccelerations; a test may then alter it).
  void CheckState(const Model& model, const State& state, const Data& data, CheckPhase phase);
  /// Evaluates Data at `state` (CalcAccelerations in the modes it carries) and checks it.
  void CheckState(const Model& model, const State& state, CheckPhase phase);
  /// Checks the ledger residual [J] against the energy scale [J] at time t; `where` names the
  /// bodies whose ledger it is.
  void CheckLedger(double t, double residual, double energy_scale, CheckPhase phase,
                   const std::string& where = "all bodies");
  /// Checks every body's impulse-momentum balance over the impulsive instant at time t
  /// (BodyImpulseBalance), from the values given.
  void CheckImpulseBalance(double t, const std::vector<BodyImpulseBalance>& bodies);
  /// The gap checks of the states checked from now on allow `seconds` times the velocity
  /// scale (CertificateTolerances::gap_time): a run whose engine changes (integrator: auto)
  /// sets half its step for a time-stepped stretch and 0 for an event-driven one.
  void SetGapTime(double seconds) { gap_time_ = seconds; }
  /// Adds a part of the run checked by a builder of its own, with its own scales (an island at
  /// its contact transitions, docs/contact.md "Islands"): Finish adds its counts and takes its
  /// worst value where it is further past its tolerance than any other (at equal ratios the
  /// builder's own values, then the parts in the order added). The scales Finish reports stay
  /// this builder's.
  void AddPart(const Certificate& part);

  Certificate Finish() const;

 private:
  /// One value of one check and what its tolerance scales with: the run's scale of its kind
  /// times `a` plus `b` (a constraint row mixes a length and an angle, a velocity and a rate:
  /// a L + b, a V + b Ω), or `local_scale` (the size of the value's own terms) if larger.
  enum class Scale { kForce, kMoment, kLength, kVelocity, kEnergy, kImpulse, kAngularImpulse };
  struct Entry {
    int check;
    double value;
    Scale scale;
    double a, b;
    double local_scale;
    std::string where;
    double t;
    CheckPhase phase;
    /// The gap time in force when it was checked [s] (gap checks only).
    double gap_time;
  };
  void Add(int check, double value, Scale scale, double a, double b, double local_scale,
           std::string where, double t, CheckPhase phase);
  /// The moment, velocity, rate and angular impulse scales derived from the run's scales so far.
  struct Scales {
    double moment = 0.0, velocity = 0.0, rate = 0.0, angular_impulse = 0.0;
  };
  Scales CurrentScales() const;
  double Tolerance(const Entry& e, const Scales& k) const;
  double Ratio(const Entry& e, const Scales& k) const;
  /// Drops the entries that can no longer matter (bounded memory on long runs).
  void Compact();

  /// Steps of CheckState. Per body: the sums of all forces on it and of their moments about
  /// its centre of mass, and the sums of their magnitudes (what round-off in the sums is
  /// relative to).
  struct BodyResultants {
    std::vector<Vec3> F, M;
    std::vector<double> F_size, M_size;
  };
  /// Adds force `f` at `p_W` (and moment `m`) on body `b` (nothing for the world).
  void AddForce(const State& state, BodyResultants& r, int b, const Vec3& f, const Vec3& p_W);
  void AddMoment(BodyResultants& r, int b, const Vec3& m);
  /// Starts the resultants with the force stage's and adds the constraint reactions.
  BodyResultants CollectForces(const Model& model, const State& state, const Data& data);
  /// The contact checks (gap, normal force, Coulomb), adding the contact forces to `r`.
  void CheckContacts(const Model& model, const State& state, const Data& data, CheckPhase phase,
                     BodyResultants& r);
  /// Rolling resistance at a sticking point with mu_r > 0 (held: inside mu_r N R; rolling:
  /// mu_r N R against the rolling).
  void CheckRollingResistance(const ContactPointOutput& o, const std::string& where, double t,
                              CheckPhase phase);
  /// Newton–Euler per body against the resultants.
  void CheckBalances(const Model& model, const State& state, const Data& data, CheckPhase phase,
                     const BodyResultants& r);
  /// The constraint residuals, row by row.
  void CheckConstraintRows(const Model& model, const State& state, const Data& data,
                           CheckPhase phase);

  CertificateTolerances tol_;
  /// The gap time of the states checked from now on [s] (tol_.gap_time until SetGapTime).
  double gap_time_ = 0.0;
  std::vector<long long> counts_;
  std::vector<Entry> entries_;
  /// Compact when this many entries are held.
  size_t compact_at_ = size_t{1} << 16;
  /// The run's scales so far: largest force [N], moment [N·m], position or size [m], speed
  /// [m/s], angular speed [rad/s], energy [J], radius of gyration [m].
  double force_ = 0.0, moment_ = 0.0, length_ = 0.0, velocity_ = 0.0, rate_ = 0.0, energy_ = 0.0,
         radius_ = 0.0;
  /// The jumps' scales so far: largest impulse or momentum change [N·s], angular impulse or
  /// angular momentum change [N·m·s].
  double impulse_ = 0.0, angular_impulse_ = 0.0;
  /// Largest total mass of the models checked [kg].
  double mass_ = 0.0;
  /// The parts added (AddPart), merged: per check their summed count and the worst of their
  /// worst values, with its value / tolerance.
  std::vector<CheckResult> parts_;
  std::vector<double> part_ratio_;
};

}  // namespace chasles
