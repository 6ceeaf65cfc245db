#pragma once
/// @file
/// Redundant constraints: more rows than the motions they stop (two coaxial hinges on one
/// door, a rolling disk on a fixed pivot). The accelerations are still unique, but the
/// reactions are not: any λ with Jᵀλ = 0 (a self-equilibrated set of reactions) can be added.
/// Rigid-body statics cannot say how the supports share those loads; the solve reports the
/// least-norm reactions with moments weighted by the mechanism's length ℓ,
///   min Σ_force rows λ² + Σ_moment rows (λ / ℓ)²,
/// so newtons are never traded against newton-metres and the answer does not depend on the
/// unit of length. This file finds ℓ, which reaction components the null space of Jᵀ leaves
/// undetermined, and a determinate set of supports (docs/constraints.md, "Redundant
/// constraints").

#include <array>
#include <limits>
#include <string>
#include <vector>

#include "chasles/model/data.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {

/// The mechanism's characteristic length ℓ [m]: the RMS distance of the constraint points
/// (Data::constraint_rows' p_WJ) from their centroid, the lever arm over which a pair of
/// support forces can stand in for a moment; when the points coincide (a spread within 1e-9 of
/// their distance from the origin or the radius of gyration: round-off), the bodies' RMS radius
/// of gyration sqrt(tr I / 2m) (1 m for particles only). Reads the rows in `data`
/// (CalcConstraintRows).
double CalcMechanismLength(const Model& model, const Data& data);

/// One weight per constraint row: 1 for force rows, ℓ for moment rows (IsMomentRow), so that
/// λ_k / d_k is a force for every row. Reads the rows in `data`.
Eigen::VectorXd CalcReactionWeights(const Model& model, const Data& data);

/// A reaction component of one constraint: its force along, or moment about, one axis of its
/// frame (ConstraintEval::R_WJ: a joint's frame, whose z is the joint axis; W otherwise), on
/// the child at the constraint point.
struct ReactionComponent {
  int constraint = -1;
  /// 0, 1, 2 for x, y, z.
  int axis = 0;
  bool moment = false;
  /// For a moment: the body (child or parent) whose spin about this axis is not a degree of
  /// freedom (a slender rod about its own axis, or a particle), so no moment about it is
  /// needed or transmitted; kWorld when there is none.
  BodyIndex frozen_spin_body = kWorld;
};

/// Components that equilibrium leaves partly undetermined: only `components.size() -
/// dimension` independent combinations of them are fixed by the equations of motion.
struct IndeterminateGroup {
  std::vector<ReactionComponent> components;
  /// Number of independent self-equilibrated combinations (dimension of the null space part).
  int dimension = 0;
  /// For a group of one combination: its coefficients on `components` (moments divided by
  /// ℓ); the determined combination of two components X1, X2 is c2 X1 - c1 X2.
  std::vector<double> null_combination;
};

/// What a determinate model keeps of one constraint.
struct SupportChange {
  int constraint = -1;
  /// Joints: the components it keeps, [Fx, Fy, Fz, Mx, My, Mz] in its frame.
  std::array<bool, 6> kept{};
  /// Joints: the components it carries now (the same for an unchanged joint).
  std::array<bool, 6> carried{};
  /// Other constraints: the rows it keeps, and its row count.
  std::vector<int> kept_rows;
  int num_rows = 0;
  /// True for a Joint (`kept` and `carried` apply).
  bool is_joint = false;
};

struct Redundancy {
  /// Rows and rank of J (rank < rows: redundant).
  int rows = 0;
  int rank = 0;
  /// ℓ [m] (CalcMechanismLength).
  double length = std::numeric_limits<double>::quiet_NaN();
  std::vector<IndeterminateGroup> groups;
  /// A determinate set of supports: the constraints that change (forces are kept before
  /// moments, constraints in Model order, so two coaxial hinges become a ball joint and a
  /// point-on-line, the textbook's hinge model).
  std::vector<SupportChange> changes;
};

/// Analyses the constraint rows at `state` (fills the kinematics stage and the rows).
Redundancy AnalyseRedundancy(const Model& model, const State& state, Data& data);

/// The analysis in words, one sentence per indeterminate group and one for the determinate
/// alternative (empty when the constraints are not redundant).
std::vector<std::string> DescribeRedundancy(const Model& model, const Redundancy& r);

}  // namespace chasles
