#pragma once
/// @file
/// The named steps of RunStudy (include/chasles/analysis/study.h), each with its own unit
/// tests (tests/unit/analysis/study_steps_test.cpp). Private to the analysis layer.

#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "chasles/analysis/ledger.h"
#include "chasles/analysis/study.h"

namespace chasles::study_internal {

/// The ledger across segments: totals of the finished segments plus the running one.
struct LedgerCarry {
  /// State the running segment started from (its ledger is relative to it).
  State segment_initial;
  double work_nc = 0.0, dissipated = 0.0, jumps = 0.0, residual = 0.0, scale = 0.0;
  /// Work of each force element and constraint in the finished segments [J].
  std::map<std::string, double> work_by_force;
};

/// Books the running segment's ledger at `state` into the carry (before a jump starts a new
/// segment from there).
void CloseSegment(const Model& model, const State& state, LedgerCarry& carry);

/// The angle θ of each body about z in a planar run, continuous however many turns it makes.
class ThetaTracker {
 public:
  /// `initial`: each body's initial θ [rad]; empty for a spatial run.
  explicit ThetaTracker(std::vector<double> initial) : initial_(std::move(initial)) {}
  bool active() const { return !initial_.empty(); }
  /// θ of body b at time t, continuous with the previous call (calls in time order): the
  /// branch of atan2(R(1,0), R(0,0)) + 2πk nearest to the previous θ advanced by the
  /// trapezoidal ω Δt (or the initial θ).
  double Advance(int b, const Mat3& R_WB, double omega, double t);
  /// The same without advancing the track (for an event's state, which may lie before the
  /// last sample).
  double At(int b, const Mat3& R_WB, double omega, double t) const;

 private:
  struct Track {
    bool started = false;
    double theta = 0.0, omega = 0.0, t = 0.0;
  };
  double Reference(int b, double omega, double t) const;
  std::vector<double> initial_;
  std::vector<Track> track_;
};

/// Makes the output rows of a study's columns.
class RowMaker {
 public:
  RowMaker(std::vector<StudyColumn> columns, ThetaTracker& theta);
  /// The row at `s` (ledger relative to the carry). `advance`: move the θ track on to `s`
  /// (false for an event's state, which may lie before the last sample).
  std::vector<double> Row(const Model& model, const BodyMap& map, const State& s,
                          const LedgerCarry& carry, bool advance = true);

 private:
  double BodyValue(const StudyColumn& c, const Model& model, const BodyMap& map, const State& s,
                   const Data& data) const;
  double LedgerValue(const StudyColumn& c, const Model& model, const State& s,
                     const LedgerSample& L, const LedgerCarry& carry, const Data& data) const;
  std::vector<StudyColumn> columns_;
  ThetaTracker& theta_;
  bool needs_accelerations_ = false;
};

/// Bodies, reactions (the first `num_reported_constraints`, -1: all) and contact points
/// (labelled by `labels`) of `model` at `state`. Planar runs take θ from `theta`, advancing it
/// when `advance`.
StudySnapshot MakeSnapshot(const Model& model, const State& state, int num_reported_constraints,
                           const std::vector<std::string>& labels, ThetaTracker& theta,
                           bool advance);

/// Every user body's pose at `state` (StudyResult::row_poses): origin and orientation of its
/// frame through the map, the quaternion with w >= 0 as the quaternion columns print it.
std::vector<StudyBodyPose> CalcUserBodyPoses(const Model& model, const State& state,
                                             const BodyMap& map);

/// Watches the friction each watched rolling contact needs over the output samples.
class SlipWatch {
 public:
  explicit SlipWatch(std::vector<RollingWatch> watched);
  void Sample(const Model& model, const State& s);
  /// Notes for the contacts that lifted off or needed more than μ_s N.
  void Report(std::vector<std::string>& notes) const;

 private:
  struct Entry {
    RollingWatch watch;
    double worst = 0.0, t_worst = 0.0;
    bool lifts = false;
    double t_lift = 0.0;
  };
  std::vector<Entry> entries_;
};

/// Everything that changes at an embedding: the bodies, the map and the Model built on them.
struct Segment {
  std::vector<NamedBody> bodies;
  BodyMap map;
  std::shared_ptr<const Model> model;
};

/// The first segment: one Model body per user body, the identity map.
Segment FirstSegment(const StudyDefinition& definition);

/// An impulse on a Model body at a jump (applied, or a contact's), its point and values in W.
struct JumpImpulse {
  int body = 0;
  BodyImpulse impulse;
};

/// Applies an impulse to `state`; returns the Model body to show in the jump's record. Appends
/// the impulse to `applied` when given.
int ApplyStudyImpulse(const StudyImpulseSpec& impulse, const Segment& seg, State& state,
                      std::vector<JumpImpulse>* applied = nullptr);

/// Applies an impact: a pass-through changes `state`; an embedding replaces `seg` (the
/// composite body, the new map and Model built by `build`) and `state`. Returns the Model body
/// to show. Throws InputError when the two are already one body. A pass-through appends its
/// impulses to `applied` when given (J on the target at the projectile's centre, -J on the
/// projectile); an embedding none (the composite's momentum is the two bodies').
int ApplyStudyImpact(const StudyImpactSpec& impact, const ModelBuilder& build, Segment& seg,
                     State& state, std::vector<JumpImpulse>* applied = nullptr);

/// The impulses of contact impacts and jams at `state` (after them: the positions are those of
/// the instant), each given as (contact point, impulse on the contact's body in W): on the
/// body at the contact point, and the opposite on the other body (a sphere-sphere contact) at
/// its own surface point, C - gap n. Labelled "contact '<label>'".
std::vector<JumpImpulse> ContactJumpImpulses(const Model& model, const State& state,
                                             const std::vector<std::pair<int, Vec3>>& impulses,
                                             const std::vector<std::string>& labels);

/// The supports' impulse (multipliers per constraint row, du = M⁻¹ Jᵀ μ) that goes with
/// impulses given on the bodies of a constrained Model at `state` (on the constraints): that
/// of the ideal supports' response, found by applying them to a copy and projecting it
/// (ProjectOntoConstraints). Contact impacts take the constraints' share with them this way
/// (impact.h: the inverse mass restricted to the constraints), so this recovers it.
Eigen::VectorXd SupportImpulseOf(const Model& model, const State& state,
                                 const std::vector<JumpImpulse>& impulses);

/// Fills jump.reactions (the first `num_reported_constraints`, -1: all) and jump.bodies: the
/// constraints' impulsive reactions from the multipliers `mu` at `after`, and every body's
/// velocity jumps from `before` to `after` (same Model) with the impulses on it: `impulses`
/// (applied and contacts) and every constraint's share of Jᵀμ at its joint point.
void RecordJumpImpulses(const Model& model, const State& before, const State& after,
                        const Eigen::VectorXd& mu, const std::vector<JumpImpulse>& impulses,
                        int num_reported_constraints, StudyJump& jump);

/// The ledger at the end of the run.
StudyLedger FinalLedger(const StudyDefinition& definition, const Model& model, const State& state,
                        const LedgerCarry& carry, double energy_initial);

/// Adds the certificate of a later stretch of time stepping to `into` (the worst of the two and
/// the totals; the initial energy stays `into`'s, the final is `add`'s). `into` with no steps
/// takes `add` as it is.
void AddSteppingSummary(TimeSteppingSummary& into, const TimeSteppingSummary& add);

/// What handing a time-stepped state over to the event-driven engine changed.
struct EventsHandover {
  /// The largest |gap| of a touching point before the projection (its penetration) [m].
  double depth = 0.0;
  /// The mechanical energy after the projection minus before [J].
  double energy = 0.0;
};

/// Projects the touching points of `state` (in the modes it carries) onto their planes and its
/// velocities onto the active rows (ProjectOntoContactModes), as the event-driven engine's start
/// does, and says what that changed.
EventsHandover ProjectForEvents(const Model& model, State& state);

}  // namespace chasles::study_internal
