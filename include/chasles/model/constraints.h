#pragma once
/// @file
/// The constraint kinds: ideal joints between two bodies (or a body and the world), rolling
/// without slipping of a round body on a plane of the world or of another body, gears in mesh
/// (pitch circles rolling on each other), and prescribed-motion drivers. Every
/// constructor validates its input (InputError naming the constraint). The joint frame J is
/// given on both bodies; its z axis is the joint axis (or the plane's normal, or the line).

#include <functional>
#include <memory>
#include <string>

#include "chasles/model/constraint.h"

namespace chasles {

enum class JointKind {
  kWeld,          ///< no relative motion (6 rows)
  kRevolute,      ///< rotation about z only (5 rows)
  kPrismatic,     ///< translation along z only (5 rows)
  kSpherical,     ///< rotation about the common point (3 rows)
  kCylindrical,   ///< rotation about and translation along z (4 rows)
  kPlanar,        ///< child's x-y plane slides on parent's x-y plane (3 rows)
  kPointOnPlane,  ///< child's J origin stays on parent's x-y plane (1 row, frictionless)
  kPointOnLine,   ///< child's J origin stays on parent's z line (2 rows, frictionless)
  // The in-plane rows of a joint whose J z axis is the normal of the plane of motion, for
  // planar mechanisms: each body's out-of-plane motion is held once, by a kPlanar joint with
  // the world, so these leave out the rows that would repeat it (docs/constraints.md).
  kRevoluteInPlane,     ///< J origins coincide in the x-y plane (2 rows: a pin)
  kPrismaticInPlane,    ///< slides along x in the x-y plane, no turn about z (2 rows)
  kWeldInPlane,         ///< no relative motion in the x-y plane (3 rows)
  kPointOnLineInPlane,  ///< child's J origin on parent's x line, in the x-y plane (1 row)
};

/// Name of a joint kind ("revolute", ...).
const char* JointKindName(JointKind kind);

/// An ideal (frictionless, workless) joint. Rows, with a_i the parent frame's axes, b_i the
/// child's, d = p_WJc - p_WJp the offset of the child's J origin from the parent's:
///   point coincidence d = 0; axis-aligned distance d·a_k = 0; perpendicularity a_i·b_j = 0.
class Joint final : public Constraint {
 public:
  /// `X_PJ` the joint frame on the parent (a world pose when the parent is kWorld), `X_CJ` on
  /// the child; assembled, the held parts of the two frames coincide (AttachmentFrameAtWorldPose
  /// makes both from one world pose). Throws InputError for non-orthonormal axes.
  Joint(std::string name, JointKind kind, BodyIndex parent, const AttachmentFrame& X_PJ,
        BodyIndex child, const AttachmentFrame& X_CJ);
  /// Which joint this is.
  JointKind joint_kind() const { return kind_; }
  /// The joint frame on the parent and on the child.
  const AttachmentFrame& X_PJ() const { return X_PJ_; }
  const AttachmentFrame& X_CJ() const { return X_CJ_; }
  int num_rows() const override;
  std::string kind() const override { return JointKindName(kind_); }
  void Evaluate(const Model& model, const State& state, const Data& data,
                ConstraintEval& eval) const override;
  std::shared_ptr<const Constraint> Renumbered(
      const std::vector<BodyIndex>& new_index) const override;

 private:
  JointKind kind_;
  AttachmentFrame X_PJ_, X_CJ_;
};

enum class RollingShape {
  kSphere,    ///< touches at centre - R n
  kCylinder,  ///< axis stays parallel to the plane; touches along a line (its mid point used)
  kDisk,      ///< thin disk or wheel rim, may tilt: touches at the rim's lowest point
  /// A wheel (or cylinder) moving in W's x-y plane on the line where the plane (normal in
  /// x-y) cuts it: the normal and the in-plane friction rows only (2 rows); its axis is kept
  /// along z by the body's kPlanar joint with the world (planar scenes).
  kWheelInPlane,
};

/// Rolling without slipping of a round body (the child) on a plane: a fixed world plane, or a
/// plane attached to another body (the parent, e.g. a turntable or a conveyor), which may
/// move. Rows on the RELATIVE velocity Δv_C = v_C(child) - v_C(parent) of the two bodies'
/// material points at the contact C: normal n·Δv_C = 0 (holonomic: the height of the lowest
/// point above the plane), tangential t1·Δv_C = t2·Δv_C = 0 (nonholonomic), with n, t1, t2
/// turning with the parent; for a cylinder its axis e stays parallel to the plane, e·n = 0.
/// Multipliers: the normal force N (row 0) and the friction force components along t1, t2
/// (rows 1, 2), on the child at C; the parent receives the opposite force at C.
class RollingContact final : public Constraint {
 public:
  /// On a fixed world plane: `p_BoC_B` the centre of the sphere / cylinder / disk from Bo in
  /// B [m]; `axis_B` its symmetry axis in B (ignored for a sphere); `radius` R > 0 [m]; the
  /// plane passes through `p_WO` [m] with upward unit normal `n_W` (normalised here).
  RollingContact(std::string name, RollingShape shape, BodyIndex body, const Vec3& p_BoC_B,
                 const Vec3& axis_B, double radius, const Vec3& p_WO, const Vec3& n_W);
  /// On a plane of body `parent` (kWorld: the constructor above): the plane passes through
  /// `p_PoO_P` (from the parent's Po, in P) [m] with upward normal `n_P` (in P).
  RollingContact(std::string name, RollingShape shape, BodyIndex parent, const Vec3& p_PoO_P,
                 const Vec3& n_P, BodyIndex body, const Vec3& p_BoC_B, const Vec3& axis_B,
                 double radius);
  int num_rows() const override {
    return shape_ == RollingShape::kCylinder ? 4 : shape_ == RollingShape::kWheelInPlane ? 2 : 3;
  }
  std::string kind() const override;
  void Evaluate(const Model& model, const State& state, const Data& data,
                ConstraintEval& eval) const override;
  /// The plane's axes [t1 t2 n] in W at the kinematics stage in `data` (t1 × t2 = n, n the
  /// upward normal; constant for a world plane, turning with the parent otherwise). For
  /// kWheelInPlane t1 = z × n (the rolling direction) and t2 = z.
  Mat3 CalcPlaneFrame(const Data& data) const;
  /// The round body's shape, centre from Bo in B [m], unit axis in B and radius [m].
  RollingShape shape() const { return shape_; }
  const Vec3& p_BoC_B() const { return p_BoC_B_; }
  const Vec3& axis_B() const { return axis_B_; }
  double radius() const { return radius_; }
  /// The plane's point (from Po, in P; in W for the world) [m] and axes [t1 t2 n] in P.
  const Vec3& p_PoO_P() const { return p_PoO_P_; }
  const Mat3& R_PT() const { return R_PT_; }

 private:
  RollingShape shape_;
  Vec3 p_BoC_B_, axis_B_;
  double radius_;
  /// The plane's point (from Po, in P; in W for the world) and axes [t1 t2 n] in P.
  Vec3 p_PoO_P_;
  Mat3 R_PT_;
};

/// How two pitch circles mesh (GearMesh).
enum class GearKind {
  kExternal,  ///< spur gears side by side: the circles touch from outside
  kInternal,  ///< the child inside the parent's ring gear: touching from inside
  kFace,      ///< the child's pitch circle on the parent's pitch plane (a crown or face gear)
};

/// Name of a gear kind ("external", ...).
const char* GearKindName(GearKind kind);

/// A pitch circle on a body: centre, axis and radius (the parent's of a face gear has no
/// radius: its pitch surface is the plane through the centre normal to the axis).
struct PitchCircle {
  /// Centre from Bo, in B (in W for kWorld) [m].
  Vec3 p_BoO_B = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  /// Unit axis in B (in W for kWorld).
  Vec3 axis_B = Vec3::UnitZ();
  /// Pitch radius [m] (unused for the parent of a face gear).
  double radius = std::numeric_limits<double>::quiet_NaN();
};

/// Two gears in mesh, modelled by their pitch circles rolling on each other without slipping
/// at the pitch point P (the point of the child's pitch circle that touches the parent's).
/// Frictionless teeth carry only the force along the common tangent t of the pitch circles at
/// P (the mesh force: what transmits torque) and, when the pitch surfaces are pressed
/// together, a separating (normal) force; sliding along the third direction (across the tooth
/// face) is free. Rows, with Δv_P = v_P(child) - v_P(parent) of the material points at P:
///   row 0 (mesh):   t·Δv_P = 0, nonholonomic in general (the angles of two gears on fixed
///                   axles obey it integrated, r_A θ_A ± r_B θ_B = const, but with moving
///                   axles not).
///   row 1 (only with `keep_contact`): the pitch surfaces stay touching (holonomic):
///     external: centre distance ℓ = r_A + r_B,  internal: ℓ = r_B - r_A (ℓ measured in the
///     child's plane), face: the lowest point of the child's pitch circle on the parent's
///     plane. Leave it out when bearings already fix the centre distance (two gears on
///     axles): it would be redundant; keep it when nothing else does (a gear on a clevis).
/// The multipliers: the mesh force along t (row 0) and the separating force (row 1) [N].
class GearMesh final : public Constraint {
 public:
  /// `parent_circle` on `parent` (may be kWorld), `child_circle` on `child`. Throws
  /// InputError for non-positive radii, zero axes, or an internal mesh whose child is not
  /// smaller than the ring.
  GearMesh(std::string name, GearKind kind, BodyIndex parent, const PitchCircle& parent_circle,
           BodyIndex child, const PitchCircle& child_circle, bool keep_contact);
  int num_rows() const override { return keep_contact_ ? 2 : 1; }
  std::string kind() const override;
  void Evaluate(const Model& model, const State& state, const Data& data,
                ConstraintEval& eval) const override;
  /// Which mesh this is.
  GearKind gear_kind() const { return kind_; }

 private:
  GearKind kind_;
  PitchCircle parent_circle_, child_circle_;
  bool keep_contact_;
};

/// A prescribed function of time f(t) with its first two derivatives (for drivers).
struct TimeFunction {
  /// f(t) [m or rad].
  std::function<double(double)> value;
  /// ḟ(t) [m/s or rad/s].
  std::function<double(double)> rate;
  /// f̈(t) [m/s² or rad/s²].
  std::function<double(double)> acceleration;
  /// f = f0 + f1 t + ½ f2 t² (constant acceleration f2; f2 = 0 gives a constant rate).
  static TimeFunction Quadratic(double f0, double f1, double f2);
};

enum class DriverKind {
  kTranslation,  ///< d·a_z = f(t): the child's J origin along the parent's z axis
  kRotation,     ///< angle from a_x to b_x about a_z = f(t) (with a revolute joint on z)
};

/// A prescribed motion (one row, rheonomic): J u = ḟ, J u̇ = f̈ - (velocity products). Its
/// multiplier is the force [N] (translation) or moment [N·m] (rotation) the driver supplies
/// along/about the parent's z axis. A body's world position component is a translation
/// driver with the world as parent (frame at the origin, z along the component).
class PrescribedMotion final : public Constraint {
 public:
  /// Frames as for Joint; the driven coordinate is zero when the two J origins coincide
  /// (translation) or their x axes do (rotation). `f` must have all three functions.
  PrescribedMotion(std::string name, DriverKind kind, BodyIndex parent, const AttachmentFrame& X_PJ,
                   BodyIndex child, const AttachmentFrame& X_CJ, TimeFunction f);
  int num_rows() const override { return 1; }
  std::string kind() const override;
  void Evaluate(const Model& model, const State& state, const Data& data,
                ConstraintEval& eval) const override;

 private:
  DriverKind kind_;
  AttachmentFrame X_PJ_, X_CJ_;
  TimeFunction f_;
};

/// The attachment frame on body `b` (or kWorld) that coincides with the world pose
/// (p_WJ, R_WJ) at `state`: what a scene gives as "joint at this world point, axis z".
AttachmentFrame AttachmentFrameAtWorldPose(const Model& model, const State& state, BodyIndex b,
                                           const Vec3& p_WJ, const Mat3& R_WJ);

/// A rotation whose z column is the unit vector along `axis` (x, y completed arbitrarily but
/// deterministically). Throws InputError for a zero axis.
Mat3 FrameWithZAxis(const Vec3& axis);

}  // namespace chasles
