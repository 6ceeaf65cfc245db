#pragma once
/// @file
/// Instantaneous analysis (what `chasles solve` reports): at one state that satisfies the
/// constraints, the acceleration of every body and the reaction of every constraint — "what
/// force does the support exert?" (chapter 8.2-8.3). For rolling contacts also the friction
/// force the rolling needs against the normal force, to compare with μ_s N.

#include <optional>
#include <string>
#include <vector>

#include "chasles/model/data.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {

struct BodyAccelerationReport {
  /// Name of the body.
  std::string name;
  /// Acceleration of the centre of mass, in W [m/s²].
  Vec3 a_WBcm_W = Vec3::Zero();
  /// Angular acceleration, expressed in W [rad/s²].
  Vec3 alpha_WB_W = Vec3::Zero();
  /// Angular acceleration, expressed in B [rad/s²].
  Vec3 alpha_WB_B = Vec3::Zero();
};

struct ReactionReport {
  /// Name and kind of the constraint ("revolute", "rolling disk", ...).
  std::string name;
  std::string kind;
  /// Parent (or kWorld) and child bodies.
  BodyIndex parent = kWorld;
  BodyIndex child = kWorld;
  /// Joint or contact point on the child, in W [m].
  Vec3 p_WJ = Vec3::Zero();
  /// Force and moment (about J) the parent exerts on the child, in W and in the child's B
  /// [N, N·m].
  Vec3 F_Jc_W = Vec3::Zero();
  Vec3 M_Jc_W = Vec3::Zero();
  Vec3 F_Jc_B = Vec3::Zero();
  Vec3 M_Jc_B = Vec3::Zero();
  /// The same in the parent's frame P, R_WPᵀ times the W values (W for a joint to the world):
  /// what a housing feels from the shaft it carries [N, N·m].
  Vec3 F_Jc_P = Vec3::Zero();
  Vec3 M_Jc_P = Vec3::Zero();
  /// Multipliers of its rows [N or N·m]; for a driver the force/moment it supplies.
  std::vector<double> lambda;
  /// Power of its forces on all its bodies [W] (0 for ideal joints and rolling).
  double power = 0.0;
  /// Rolling contacts only: the normal force N (positive pushing the body off the plane) [N],
  /// the friction force in the plane (in W) [N], and |friction| / N, the least static
  /// friction coefficient that rolling needs (infinite when N <= 0: the body would lift off).
  bool is_rolling = false;
  double normal_force = 0.0;
  Vec3 friction_W = Vec3::Zero();
  double friction_needed = 0.0;
  /// Constraints that can let go (strings): taut (kEngaged) or slack (kReleased) (none for the
  /// others), chosen by the complementarity T >= 0, g̈ >= 0, T g̈ = 0 (SelectConstraintModes),
  /// and the gap (the slack L0 - L) [m].
  std::optional<ConstraintMode> mode;
  double gap = 0.0;
};

struct InstantaneousSolution {
  /// Time of the state [s].
  double t = 0.0;
  /// Per body, Model order.
  std::vector<BodyAccelerationReport> bodies;
  /// Per constraint, Model order.
  std::vector<ReactionReport> reactions;
  /// Rank of the constraint rows; below `num_rows` when constraints are redundant.
  int rank = 0;
  int num_rows = 0;
  /// Warnings for the reader (redundant constraints: least-norm reactions reported).
  std::vector<std::string> warnings;
};

struct InstantaneousOptions {
  /// Largest constraint violation accepted in the given state, positions [m] and velocities
  /// [m/s]; project the state first (ProjectOntoConstraints) when it is further off.
  double tolerance = 1e-8;
};

/// Accelerations and reactions at `state`. Throws InputError when the state violates a
/// constraint by more than the tolerance (naming it) or the constraints are inconsistent.
InstantaneousSolution SolveInstantaneous(const Model& model, const State& state,
                                         const InstantaneousOptions& options = {});

/// The report of constraint `c` from the constraint stage of CalcAccelerations in `data`
/// (data.constraints[c]): the one conversion from the solve's ConstraintOutput to the reaction
/// every report shows (SolveInstantaneous, RunStudy).
ReactionReport MakeReactionReport(const Model& model, const Data& data, int c);

}  // namespace chasles
