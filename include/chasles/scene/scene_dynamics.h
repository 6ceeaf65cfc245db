#pragma once
/// @file
/// The dynamics part of a scene (docs/scene-format.md, "Dynamics"): gravity, initial motion of
/// each body, force elements, events, impulses, impacts, simulation and output settings. All
/// values are SI; force and event expressions are kept compiled, with the state variables of
/// StateVariableLayout as their variable slots.

#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "chasles/integrate/simulate.h"
#include "chasles/integrate/sphere_events.h"
#include "chasles/math/types.h"
#include "chasles/model/force_element.h"
#include "chasles/scene/expression.h"
#include "chasles/scene/scene_constraints.h"
#include "chasles/scene/scene_contacts.h"

namespace chasles {

/// Slots of the state variables an expression may read: slot 0 is `t`, then one block of
/// kPerBody values for each body in scene order (names "<body>_<suffix>").
struct StateVariableLayout {
  /// Suffixes in slot order within a body's block: Bcm position (W) [m], Bcm velocity (W)
  /// [m/s], angular velocity in W and in B [rad/s], tilt (angle of B's z axis from W's z)
  /// [rad], Euler ZYX yaw, pitch, roll of R_WB [rad], speed |v| [m/s], angular speed |w|
  /// [rad/s]; then the planar angle θ about z [rad] and angular acceleration α_z [rad/s²]
  /// (planar scenes only). A 3-D scene names every slot but the last two by its suffix; a
  /// planar scene names x, y, vx, vy, speed, theta, alpha and calls the wz slot `omega` (signed
  /// ω about z): kPlanarNames.
  static constexpr std::array<const char*, 20> kSuffixes = {
      "x",   "y",   "z",    "vx",  "vy",    "vz",   "wx",    "wy",    "wz",    "wbx",
      "wby", "wbz", "tilt", "yaw", "pitch", "roll", "speed", "omega", "theta", "alpha"};
  static constexpr int kPerBody = static_cast<int>(kSuffixes.size());
  /// Index in kSuffixes of ω_z, of the tilt, of the yaw (pitch and roll follow), of |ω| (3-D
  /// `omega`), of θ and of α_z.
  static constexpr int kWz = 8, kTilt = 12, kYaw = 13, kAngularSpeed = 17, kTheta = 18, kAlpha = 19;
  /// A planar scene's body variables: its name suffix and the kSuffixes slot it reads (one
  /// name per quantity, the names of the `planar` output columns).
  static constexpr std::array<std::pair<const char*, int>, 8> kPlanarNames = {{{"x", 0},
                                                                               {"y", 1},
                                                                               {"theta", kTheta},
                                                                               {"vx", 3},
                                                                               {"vy", 4},
                                                                               {"omega", kWz},
                                                                               {"alpha", kAlpha},
                                                                               {"speed", 16}}};
  /// Slot of variable `suffix_index` of body `body` (scene order).
  static constexpr int Slot(int body, int suffix_index) {
    return 1 + body * kPerBody + suffix_index;
  }
  /// Slots after the bodies' blocks (events only): six reaction values per scene constraint
  /// ("<name>_Fx" ... "<name>_Mz", in W [N, N·m]), then kContactSuffixes for each contact
  /// point ("<point>_mode" ...), in SceneContacts::point_labels() order.
  static constexpr int kPerConstraint = 6;
  /// Per contact point: mode (0 separated, 1 sliding, 2 sticking), normal force N [N],
  /// friction force |f| [N], slip speed [m/s], gap [m] (the output columns of group contacts).
  static constexpr std::array<const char*, 5> kContactSuffixes = {"mode", "N", "f", "slip", "gap"};
  static constexpr int kPerContactPoint = static_cast<int>(kContactSuffixes.size());
};

/// Initial motion of one body (key `initial`), resolved to the world frame.
struct SceneInitialState {
  /// Position of the body frame origin Bo in W [m].
  Vec3 p_WBo = Vec3::Zero();
  /// Orientation of B in W.
  Quat q_WB = Quat::Identity();
  /// Velocity of the point P below, in W [m/s].
  Vec3 v_WP_W = Vec3::Zero();
  /// The point whose velocity is given, from Bo in B [m] (the centre of mass by default).
  Vec3 p_BoP_B = Vec3::Zero();
  /// Angular velocity of B in W, expressed in W [rad/s].
  Vec3 w_WB_W = Vec3::Zero();
  /// Planar scenes: the angle θ of B about z as given (the reported θ continues from it) [rad].
  double theta = 0.0;
  /// The body's `initial` entry (its entry in `bodies` when it has none), for errors about
  /// an initial state that violates the constraints.
  SceneSpot where;
};

/// A vector of three expressions of t and the state (a force [N] or a moment [N·m]).
struct SceneVectorExpression {
  std::array<Expression, 3> components;
  /// True when no component reads t or the state.
  bool is_constant() const;
  /// The vector for the given state variables (at least the largest slot used + 1 values).
  Vec3 Evaluate(std::span<const double> variables) const;
  /// 1 + the highest slot any component reads.
  int variable_count() const;
};

/// Largest magnitude of a motion in SI (a position [m], a speed [m/s] or [rad/s]) that a
/// scene may start a run with: beyond it the energies (½ m v²) and moments (r × F) of ordinary
/// bodies leave double precision, so such a value is mistyped (docs/reliability-limits.md).
inline constexpr double kMotionScale = 1e150;

/// One entry of `forces`.
struct SceneForce {
  enum class Type {
    kForce,
    kMoment,
    kSpring,
    kDrag,
    kCentralGravity,
    kCable,
    kJointTorque,
    kStringPull,
    kBearing
  };
  Type type = Type::kForce;
  /// Unique name (reports, ledger columns "W_<name>").
  std::string name;
  /// The entry, for errors found when the motion is built or run.
  SceneSpot where;
  /// The `value` of a force, moment or joint torque (whose force or torque is that expression
  /// and nothing else), for an expression that evaluates to NaN or an infinity during a run or
  /// a solve; line 0 for the other elements.
  SceneSpot expression_where;
  /// Body acted on (scene index), or for a spring its first end.
  int body = -1;
  /// Point of application from Bo in B [m] (force; spring's first end; cable's body end;
  /// string pull's drum centre), or a world point [m] when `point_frame` is kWorld (force
  /// only).
  Vec3 p_BoP_B = Vec3::Zero();
  /// kWorld: the force acts at the material point currently at the world point p_BoP_B.
  VectorFrame point_frame = VectorFrame::kBody;
  /// Cable's or string pull's tension [N], or joint torque [N·m], as an expression.
  Expression scalar;
  /// Cable: the fixed world point it runs to [m].
  Vec3 p_WQ = Vec3::Zero();
  /// String pull: the drum's axis in B (unit), radius [m] and sense (+1 counterclockwise
  /// about the axis), and the pull's unit direction in W.
  Vec3 drum_axis_B = Vec3::UnitZ();
  double drum_radius = 0.0;
  int drum_sense = 1;
  Vec3 direction_W = Vec3::UnitX();
  /// Joint torque: the joint it acts across (index into SceneConstraints::joints).
  int joint = -1;
  /// Force [N] or moment [N·m] as expressions.
  SceneVectorExpression value;
  /// Frame the value is expressed in (force, moment).
  VectorFrame frame = VectorFrame::kWorld;
  /// Spring: second end's body (scene index) or kWorld, and its point (from that body's Bo in
  /// its frame, or the world point) [m].
  int body_b = kWorld;
  Vec3 p_BoQ_B = Vec3::Zero();
  /// Spring rest length [m], stiffness [N/m], damping [N·s/m].
  double rest_length = 0.0, stiffness = 0.0, damping = 0.0;
  /// Drag coefficients: linear [N·s/m] and angular [N·m·s].
  double linear = 0.0, angular = 0.0;
  /// Central gravity: mu = G M [m³/s²] and the attracting point in W [m].
  double mu = 0.0;
  Vec3 centre_W = Vec3::Zero();
  /// Bearing (model/bearing.h): its centre in W at the initial configuration (`at`, also the
  /// journal's place on the body then) [m], its axis in W, stiffness [N/m] and damping
  /// [N·s/m] matrices in its axes e1, e2.
  Vec3 bearing_at_W = Vec3::Zero();
  Vec3 bearing_axis_W = Vec3::UnitZ();
  Eigen::Matrix2d bearing_K = Eigen::Matrix2d::Zero(), bearing_C = Eigen::Matrix2d::Zero();
};

/// The contact-mode change a contact-mode event watches (docs/scene-format.md, `events`).
enum class SceneModeChange {
  kNone,           ///< not a contact-mode event: a crossing of `when`
  kStartsSliding,  ///< a point begins to slide (from sticking, or touching down sliding)
  kStopsSliding,   ///< a sliding point sticks (a round body then rolls)
  kSeparates,      ///< a point in contact separates
  kTouches,        ///< a separated point touches down (a bounce included)
  kAny,            ///< any of these, or any other change of mode
};

/// One entry of `events`: a crossing of `when` through `crosses`, or a contact-mode change.
struct SceneEvent {
  std::string name;
  /// The entry, for errors found when the motion is built or run.
  SceneSpot where;
  /// A contact-mode event: the change watched, the contact (or point label) as written and
  /// its points (indices in SceneContacts::point_labels() order).
  SceneModeChange change = SceneModeChange::kNone;
  std::string contact;
  std::vector<int> points;
  /// Expression of t and the state.
  Expression when;
  /// Level crossed, in SI units of when's dimension.
  double crosses = 0.0;
  EventDirection direction = EventDirection::kEither;
  EventAction action = EventAction::kStop;
};

/// One entry of `impulses`: J applied at a point of a body at an instant.
struct SceneImpulse {
  /// Time [s].
  double t = 0.0;
  int body = -1;
  /// Point from Bo in B [m].
  Vec3 p_BoP_B = Vec3::Zero();
  /// Impulse [N·s] expressed in `frame`.
  Vec3 J = Vec3::Zero();
  VectorFrame frame = VectorFrame::kWorld;
};

/// One entry of `impacts`: the projectile body hits the target at its current position.
struct SceneImpact {
  /// Time [s].
  double t = 0.0;
  int target = -1;
  int projectile = -1;
  /// Fraction of its velocity the projectile keeps (0: it embeds and the two become one body).
  double exit_fraction = 0.0;
};

/// Default limits on a run's work (docs/reliability-limits.md); the scene's `simulation:` keys
/// and the command line's flags replace them.
inline constexpr std::int64_t kDefaultMaxSteps = 10'000'000;
inline constexpr std::int64_t kDefaultMaxRows = 1'000'000;
/// The smallest step, as a fraction of the span simulated, when `min_step` is not given.
inline constexpr double kDefaultMinStepFraction = 1e-12;
/// The accepted range of the adaptive integrator's relative tolerance: below 1e-14 double
/// precision cannot deliver it (round-off of a step is ~1e-16 per component), above 1e-2 the
/// answer has no digits worth reporting.
inline constexpr double kMinTolerance = 1e-14;
inline constexpr double kMaxTolerance = 1e-2;

/// Key `simulation`.
struct SceneSimulation {
  /// True when the scene has the key (the scene can be simulated).
  bool present = false;
  /// End time [s]; NaN when not given (the command line must give it).
  double until = std::numeric_limits<double>::quiet_NaN();
  IntegratorKind integrator = IntegratorKind::kDormandPrince5;
  /// `integrator: events`: balls on a table run event-driven (SimulateSphereEvents); the
  /// tolerances below are then those of its pressing groups' hybrid runs.
  bool event_driven = false;
  /// `integrator: stepping`: Moreau–Jean time stepping (SimulateTimeStepping) with `step`.
  bool time_stepping = false;
  /// `integrator: auto`: the run chooses between the adaptive (event-driven) engine and time
  /// stepping with `step` (or DefaultEngineStep) as its regime changes come (EngineChoiceRule).
  bool auto_engine = false;
  /// `auto_engine` because the scene names no integrator: format version 3's default for a
  /// scene with contacts (versions 1 and 2 ran `adaptive` there). The report says so.
  bool auto_by_default = false;
  /// `ball_collisions`: every pair of balls the scene does not list as a sphere-sphere contact
  /// collides, with these coefficients (event-driven only).
  bool collide_all_pairs = false;
  SphereCollisionLaw ball_collisions;
  /// Relative and absolute tolerance of the adaptive integrator.
  double rtol = 1e-10;
  double atol = 1e-12;
  /// Step of the fixed-step integrators and of time stepping (also auto's) [s] (NaN when not
  /// given).
  double step = std::numeric_limits<double>::quiet_NaN();
  /// Output spacing [s]; NaN: 200 intervals over the run.
  double output_interval = std::numeric_limits<double>::quiet_NaN();
  /// Limits on the run's work: accepted integration steps, output rows, wall time [s] (0:
  /// none), and the smallest step [s] (NaN: kDefaultMinStepFraction of the span).
  std::int64_t max_steps = kDefaultMaxSteps;
  std::int64_t max_rows = kDefaultMaxRows;
  double timeout = 0.0;
  double min_step = std::numeric_limits<double>::quiet_NaN();
  /// Where the `simulation` key stands (line 1 of the file when the scene has none), and each
  /// of its keys given ("until", "tolerance", "step", "max_steps", ...), for errors found when
  /// the run is built or during it.
  SceneSpot where{1, 1, ""};
  std::map<std::string, SceneSpot, std::less<>> keys;
  /// The spot of `key` when the scene gives it, else that of `simulation`.
  const SceneSpot& Spot(std::string_view key) const;
};

struct SceneDynamics {
  /// Uniform gravity, when the scene has `gravity` [m/s²].
  bool has_gravity = false;
  Vec3 g_W = Vec3::Zero();
  /// One per body, in scene order (at rest at the origin unless `initial` says otherwise).
  std::vector<SceneInitialState> initial;
  std::vector<SceneForce> forces;
  std::vector<SceneEvent> events;
  std::vector<SceneImpulse> impulses;
  std::vector<SceneImpact> impacts;
  SceneSimulation simulation;
  /// Root key `project_initial: true`: an initial state that violates the constraints is
  /// projected onto them (each changed value a warning) instead of being an error.
  bool project_initial = false;
  /// Joints, rolling contacts and drivers (keys `joints`, `rolling`, `drivers`).
  SceneConstraints constraints;
  /// Unilateral contacts with friction and the material-pair table (keys `contacts`,
  /// `material_pairs`).
  SceneContacts contacts;
  /// Output column names (after expanding groups), in order.
  std::vector<std::string> columns;
};

}  // namespace chasles
