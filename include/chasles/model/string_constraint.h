#pragma once
/// @file
/// An inextensible, massless string (or cable) held taut: from an end on body A (or the
/// world) over zero or more frictionless pulleys, fixed in the world or carried by bodies, to
/// an end on body B. Each end is a point of its body or a drum (hub, spool) of its body on
/// which the string is wound without slip. The path lies in the plane normal to the string's
/// unit normal n (fixed in W): pulleys and drums are circles in that plane, turning about n;
/// an end point off the plane is allowed only on a string without pulleys and drums
/// (docs/constraints.md, "Strings").
///
/// One row. The path is a chain of circles c_0 (end A), c_1..c_N (pulleys), c_N+1 (end B),
/// each with centre c_i, radius r_i (0 for a point end) and sense s_i = ±1: the string,
/// followed from A to B, goes round circle i counterclockwise about n (s = +1) or clockwise.
/// The straight segment from circle i to circle i+1 is their common tangent: with D the
/// in-plane part of c_i+1 - c_i, h = n·(c_i+1 - c_i) and Δ = s_i+1 r_i+1 - s_i r_i,
///   ℓ_p = sqrt(|D|² - Δ²),  d = (ℓ_p D - Δ n × D) / |D|²   (since c = T + s r n × d),
///   T_i = c_i - s_i r_i n × d,  T_i+1 = c_i+1 - s_i+1 r_i+1 n × d,  ℓ = sqrt(ℓ_p² + h²).
/// The free length L = Σ ℓ + Σ_pulleys r_i φ_i (φ_i the wrap angle of pulley i, in sense s_i).
/// Row (the slack rate, positive when the string slackens):
///   ġ = e_A·w_A + e_B·w_B = 0,
/// e_A the unit vector at A's leaving point T_0 along the string (towards the next point),
/// e_B likewise at B's T_N+1, w the velocity of the body's material point at T (for a drum
/// that is v + ω × r_T: the string is at rest on the drum there; it includes the unwinding).
/// Moving a pulley's tangent point along its circle changes L only to second order, so of a
/// pulley only its centre's motion appears. A pulley k carried by a body, with e_in and e_out
/// the unit vectors (along the string from A to B) of the segments arriving at and leaving
/// it: moving its centre by δc lengthens the arriving segment by e_in·δc and shortens the
/// leaving one by e_out·δc, so ∂L/∂c_k = e_in - e_out and the row gains
///   + (e_out - e_in)·v_c,   v_c = v + ω × r_c   (r_c from the body's Bcm to the centre).
/// (A movable pulley hanging in a loop, e_in down and e_out up: lifting it slackens the string
/// at twice its speed.) The multiplier is the tension T >= 0: the force on each end body is
/// T e at its leaving point (it pulls each end along the string), and on a pulley's body
/// T (e_out - e_in) at the pulley's centre.
/// Acceleration level: J u̇ = c with c = -J̇ u,
///   c = -Σ_ends [ė·w + e·(ω × (ω × r_T))]
///       - Σ_pulleys on bodies [(ė_out - ė_in)·v_c + (e_out - e_in)·(ω × (ω × r_c))],
///   ė = (I - e eᵀ)(u_end - u_start) / ℓ for each segment,
/// u the velocity of a segment's end: w at a string end, v_c at a pulley (0 when fixed). A
/// tangent point slides along its circle's tangent, which is along e, so that motion drops out
/// of (I - e eᵀ). Without drums the row is holonomic, g = L0 - L(q) (the slack; ∂g/∂x = J);
/// with a drum the wound length depends on how far the drum has turned, which the state holds only
/// modulo a turn, so the row is kept at velocity level (no position error).
/// Unilateral (can_release): a string without drums is taut (the row holds, tension T >= 0) or
/// slack (no row, no force), its mode in State::constraint_modes; it goes slack when T falls
/// through 0 and snaps taut (an impact, dynamics/constraint_modes.h) when g falls through 0.
/// A string with a drum is held taut: its slack cannot be tracked (velocity-level row), so a
/// tension that comes out negative is an InputError.

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "chasles/model/constraint.h"

namespace chasles {

/// One end of a string: a point of a body (radius 0) or a drum of the body it is wound on.
struct StringEnd {
  /// The body, or kWorld.
  BodyIndex body = kWorld;
  /// The point, or the drum's centre, from Bo in B (in W for kWorld) [m].
  Vec3 p_BoP_B = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  /// Drum radius [m]; 0 for a point end.
  double radius = 0.0;
  /// For a drum: +1 when the string, followed from end A to end B, goes round it
  /// counterclockwise about the string's normal n, -1 clockwise.
  int sense = 1;
};

/// A frictionless, massless pulley in the string's plane, fixed in the world or carried by a
/// body (a block, a movable pulley's frame): it turns freely on its axle, so only its
/// centre's motion enters. Its axle is taken along the string's normal n whatever the
/// body's attitude: a pulley on a body must turn with it about n only (planar motion); a body
/// that tilts the axle out of n is outside this model.
struct StringPulley {
  /// Centre from Bo in B (in W for kWorld) [m].
  Vec3 p_BoO_B = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  /// Radius [m] (> 0).
  double radius = std::numeric_limits<double>::quiet_NaN();
  /// +1: the string, followed from end A to end B, goes round it counterclockwise about n.
  int sense = 1;
  /// The body carrying the pulley, or kWorld (fixed).
  BodyIndex body = kWorld;
};

/// The path of a string at one configuration (StringConstraint::CalcPath).
struct StringPath {
  /// Leaving points T, in W: 2 per segment (its start and end) [m].
  std::vector<Vec3> points;
  /// Free length L: segments plus the arcs on pulleys [m].
  double length = 0.0;
  /// Unit vectors at the two ends along the string (e_A, e_B).
  Vec3 e_A = Vec3::Zero(), e_B = Vec3::Zero();
  /// Lengths of the first and the last segment [m].
  double first_segment = 0.0, last_segment = 0.0;
};

class StringConstraint final : public Constraint {
 public:
  /// End `a` on its body (the parent), end `b` on its body (the child; not kWorld), over
  /// `pulleys` in order from a to b; `n_W` the normal of the string's plane (normalised);
  /// `length` L0 [m], the free length the string keeps (the holonomic row's g = L0 - L; the
  /// initial free length comes from CalcPath). Throws
  /// InputError for non-positive radii, a sense other than ±1, a zero normal, more than
  /// ConstraintEval::kMaxExtraBodies pulley bodies besides the ends, or a drum or pulley on a
  /// string whose end is a point mass (checked by Model::AddConstraint).
  StringConstraint(std::string name, const StringEnd& a, std::vector<StringPulley> pulleys,
                   const StringEnd& b, const Vec3& n_W, double length);
  int num_rows() const override { return 1; }
  std::string kind() const override { return "string"; }
  void Evaluate(const Model& model, const State& state, const Data& data,
                ConstraintEval& eval) const override;
  std::shared_ptr<const Constraint> Renumbered(
      const std::vector<BodyIndex>& new_index) const override;
  /// The path at the kinematics stage in `data` (positions only). Throws InputError when two
  /// consecutive circles overlap (no common tangent).
  StringPath CalcPath(const Model& model, const State& state, const Data& data) const;
  const StringEnd& end_a() const { return a_; }
  const StringEnd& end_b() const { return b_; }
  const std::vector<StringPulley>& pulleys() const { return pulleys_; }
  /// Whether an end is wound on a drum (then the row is velocity-level only).
  bool has_drum() const { return a_.radius > 0.0 || b_.radius > 0.0; }
  /// The free length L0 the string keeps [m].
  double length() const { return length_; }
  /// Without drums the string can go slack (its row is holonomic: the slack g = L0 - L is known).
  bool can_release() const override { return !has_drum(); }
  /// Newton's restitution when the string snaps taut: the slack rate after is -e times the
  /// rate before (0, the default: plastic, the string's closing rate becomes 0).
  double restitution() const override { return restitution_; }
  /// Sets it; throws InputError unless 0 <= e <= 1.
  void set_restitution(double e);

 private:
  StringEnd a_, b_;
  std::vector<StringPulley> pulleys_;
  Vec3 n_W_;
  double length_;
  double restitution_ = 0.0;
};

}  // namespace chasles
