#pragma once
/// @file
/// How far a state is from its constraints, constraint by constraint and in units, judged
/// against the state's own length and velocity scales: what tells a user's inconsistent initial
/// state (an error, or a projection that is reported) from the round-off of a consistent one
/// (corrected without a word). docs/constraints.md, "Initial state".

#include <vector>

#include "chasles/model/constraint.h"
#include "chasles/model/data.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {

/// A residual below this fraction of the state's scales (ConstraintScales) is round-off: a
/// value typed or computed consistently (`v = omega*r`) leaves residuals of a few ulps, while a
/// value missing or inconsistent leaves one of the order of the scale itself.
inline constexpr double kRoundOffResidual = 1e-9;

/// Whether row `k` of a constraint's evaluated rows carries a moment: no linear-velocity part
/// on either body (an axis row a·b = 0, a rotation driver). Its multiplier is a moment [N·m],
/// its position error an angle [rad] and its velocity residual an angular velocity [rad/s];
/// every other row's multiplier is a force [N], its errors a length [m] and a speed [m/s].
bool IsMomentRow(const ConstraintEval& eval, int k);

/// The scales a state's constraint residuals are judged against.
struct ConstraintScales {
  /// Largest of the bodies' radii of gyration sqrt(tr I / m), their centre-of-mass distances
  /// from the origin and the constraint points' [m].
  double length = 0.0;
  /// Largest of the bodies' |v_WBcm|, |w| times `length`, and the drivers' prescribed rates
  /// (angular ones times `length`) [m/s].
  double velocity = 0.0;
};

/// The scales of `state` (fills the kinematics stage and the rows).
ConstraintScales CalcConstraintScales(const Model& model, const State& state, Data& data);

/// The residual of one constraint at a state, split by unit.
struct ConstraintResidual {
  /// The constraint (Model order).
  int constraint = -1;
  /// Largest |g| of its holonomic length rows [m] and of its axis rows [rad].
  double position_length = 0.0;
  double position_angle = 0.0;
  /// Largest |J u - b| of its force rows [m/s] and of its moment rows [rad/s].
  double velocity_linear = 0.0;
  double velocity_angular = 0.0;
  /// True when a position (velocity) residual exceeds the tolerance.
  bool position_violated = false;
  bool velocity_violated = false;
};

/// The constraints whose residual at `state` exceeds `relative_tolerance` times the scales
/// (lengths against `scales.length`, angles against 1 rad, speeds against `scales.velocity`,
/// angular velocities against `scales.velocity / scales.length`), in Model order. Fills the
/// kinematics stage and the rows.
std::vector<ConstraintResidual> FindConstraintViolations(
    const Model& model, const State& state, Data& data, const ConstraintScales& scales,
    double relative_tolerance = kRoundOffResidual);

}  // namespace chasles
