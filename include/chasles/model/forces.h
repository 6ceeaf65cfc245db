#pragma once
/// @file
/// The force elements of a free-body model (chapter 8.3): uniform and inverse-square gravity,
/// forces and moments given as functions of time and state, linear spring-dampers and viscous
/// drag. Every constructor validates its physical input (InputError naming the element).

#include <memory>
#include <string>
#include <vector>

#include "chasles/model/force_element.h"

namespace chasles {

/// Uniform gravity g_W [m/s²] on every body, at its centre of mass.
/// Potential V = -Σ m g·p_WBcm.
class UniformGravity final : public ForceElement {
 public:
  UniformGravity(std::string name, const Vec3& g_W);
  /// Gravitational acceleration, in W [m/s²].
  const Vec3& g_W() const { return g_W_; }
  double AddForces(const Model&, const State&, const Data&, WrenchAccumulator&) const override;
  bool has_potential() const override { return true; }
  double CalcPotentialEnergy(const Model& model, const State& state) const override;
  std::vector<BodyIndex> bodies() const override { return {}; }
  std::shared_ptr<const ForceElement> Renumbered(
      const std::vector<BodyIndex>& new_index) const override;

 private:
  Vec3 g_W_;
};

/// Inverse-square central gravity towards a fixed point: F = -mu m r/|r|³ at each body's
/// centre of mass, r from `centre_W` to Bcm. Potential V = -mu m/|r|. The gravity-gradient
/// moment on a body of finite size is not included (it is smaller by (size/r)²).
class CentralGravity final : public ForceElement {
 public:
  /// `mu` = G M [m³/s²] > 0.
  CentralGravity(std::string name, double mu, const Vec3& centre_W);
  double AddForces(const Model&, const State&, const Data&, WrenchAccumulator&) const override;
  bool has_potential() const override { return true; }
  double CalcPotentialEnergy(const Model& model, const State& state) const override;
  std::vector<BodyIndex> bodies() const override { return {}; }
  std::shared_ptr<const ForceElement> Renumbered(
      const std::vector<BodyIndex>& new_index) const override;

 private:
  double mu_;
  Vec3 centre_W_;
};

/// A force at a point P of one body, F = f(t, state), expressed in W or in B. Non-conservative
/// (no potential): its work is integrated along the solution.
///
/// The point P is fixed in the body (a thruster, a rope tied to it), or fixed in the world
/// (`point_frame` kWorld: a pusher held still, a fixed guide the body slides past): then the
/// force acts at whichever material point of the body is at P at that instant, its moment
/// about Bcm is (p_WP - p_WBcm) × F and its power F·v_P with v_P = v_Bcm + w × (p_WP - p_WBcm)
/// the velocity of that material point (Greenwood, Principles of Dynamics, 2nd ed., sec. 4.2:
/// the power of a force is F dotted with the velocity of the material point it acts on).
class AppliedForce final : public ForceElement {
 public:
  /// `p_BoP_B` is P's position from the body's frame origin, in B [m].
  AppliedForce(std::string name, BodyIndex body, const Vec3& p_BoP_B, VectorFunction force,
               VectorFrame frame);
  /// `p_P` is P: from the body's frame origin in B (`point_frame` kBody), or P's world
  /// position (`point_frame` kWorld) [m]; `frame` the frame the force is expressed in.
  AppliedForce(std::string name, BodyIndex body, const Vec3& p_P, VectorFrame point_frame,
               VectorFunction force, VectorFrame frame);
  /// A constant force [N] expressed in `frame`.
  static std::shared_ptr<AppliedForce> Constant(std::string name, BodyIndex body,
                                                const Vec3& p_BoP_B, const Vec3& force,
                                                VectorFrame frame);
  double AddForces(const Model&, const State&, const Data&, WrenchAccumulator&) const override;
  std::vector<BodyIndex> bodies() const override { return {body_}; }

 private:
  BodyIndex body_;
  Vec3 p_P_;
  VectorFrame point_frame_;
  VectorFunction force_;
  VectorFrame frame_;
};

/// A cable from a point P of one body to a fixed point Q of the world (a winch, a pulley
/// whose axle is fixed): tension T = f(t, state) >= 0 pulls P towards Q, F = T (p_WQ - p_WP) /
/// |p_WQ - p_WP|, so the line of action turns with the body as P moves. The tension is given,
/// not the length (a winch that holds a length is a constraint); a negative T (a cable cannot
/// push) is an error when evaluated. Non-conservative: its work is integrated.
class CableForce final : public ForceElement {
 public:
  /// `p_BoP_B` is P from the body's frame origin, in B [m]; `p_WQ` the world point [m].
  CableForce(std::string name, BodyIndex body, const Vec3& p_BoP_B, const Vec3& p_WQ,
             ScalarFunction tension);
  double AddForces(const Model&, const State&, const Data&, WrenchAccumulator&) const override;
  std::vector<BodyIndex> bodies() const override { return {body_}; }

 private:
  BodyIndex body_;
  Vec3 p_BoP_B_, p_WQ_;
  ScalarFunction tension_;
};

/// A string wound on a drum (hub, spool) of a body and pulled by hand with tension P = f(t,
/// state) >= 0 along a direction d fixed in the world, its far end at infinity (the string
/// stays parallel to d). The drum is a circle of radius r about the axis a (fixed in the body)
/// through its centre c; the string leaves it in the drum's plane at the tangent point
///   T = c - s r a × d̂,   d̂ the unit in-plane part of d,
/// the end-A tangent formula of StringConstraint (model/string_constraint.h) with the other
/// circle at infinity: there the segment's direction is d̂ and the centre lies at T + s r a ×
/// d̂. `sense` s = +1 when the string, followed from the drum to the hand, leaves the drum going
/// counterclockwise about a, -1 clockwise. The force P d (d unit) acts on the body's material
/// point at T; its power is P d·v_T. A negative P (a string cannot push) is an error when
/// evaluated; so is a direction along the drum's axis.
class StringPull final : public ForceElement {
 public:
  /// `p_BoC_B` the drum's centre from Bo in B [m], `axis_B` its axis in B (any non-zero
  /// length), `radius` > 0 [m], `sense` ±1, `direction_W` the pull's direction in W (any
  /// non-zero length; its part along the axis, if any, is kept in the force).
  StringPull(std::string name, BodyIndex body, const Vec3& p_BoC_B, const Vec3& axis_B,
             double radius, int sense, const Vec3& direction_W, ScalarFunction tension);
  double AddForces(const Model&, const State&, const Data&, WrenchAccumulator&) const override;
  std::vector<BodyIndex> bodies() const override { return {body_}; }
  /// The tangent point T in W at the kinematics stage in `data` [m].
  Vec3 CalcTangentPoint(const Model& model, const State& state, const Data& data) const;

 private:
  BodyIndex body_;
  Vec3 p_BoC_B_, axis_B_;
  double radius_;
  int sense_;
  Vec3 d_W_;
  ScalarFunction tension_;
};

/// A torque across a joint (a motor, a drive shaft, a brake): tau = f(t, state) [N·m] about
/// the joint's axis a, +tau a on the child and -tau a on the parent (Newton's third law for a
/// couple: the pair exerts no net moment on the two bodies together). The axis is fixed in
/// the parent (along the revolute joint it acts across). Its power is
/// tau a·(w_child - w_parent), the rate of work across the joint.
class JointTorque final : public ForceElement {
 public:
  /// `axis_P` the joint axis in the parent's frame (in W when `parent` is kWorld), any
  /// non-zero length; positive tau turns the child about it relative to the parent.
  JointTorque(std::string name, BodyIndex parent, BodyIndex child, const Vec3& axis_P,
              ScalarFunction torque);
  double AddForces(const Model&, const State&, const Data&, WrenchAccumulator&) const override;
  std::vector<BodyIndex> bodies() const override;

 private:
  BodyIndex parent_, child_;
  Vec3 axis_P_;
  ScalarFunction torque_;
};

/// A pure moment (couple) on one body, M = f(t, state) [N·m], expressed in W or in B.
class AppliedMoment final : public ForceElement {
 public:
  AppliedMoment(std::string name, BodyIndex body, VectorFunction moment, VectorFrame frame);
  /// A constant moment [N·m] expressed in `frame`.
  static std::shared_ptr<AppliedMoment> Constant(std::string name, BodyIndex body,
                                                 const Vec3& moment, VectorFrame frame);
  double AddForces(const Model&, const State&, const Data&, WrenchAccumulator&) const override;
  std::vector<BodyIndex> bodies() const override { return {body_}; }

 private:
  BodyIndex body_;
  VectorFunction moment_;
  VectorFrame frame_;
};

/// Linear spring-damper between point P of body A and point Q of body B (or a world point when
/// B is kWorld). Tension f = k (L - L0) + c dL/dt along the line PQ; P is pulled towards Q.
/// Potential ½ k (L - L0)²; the damper's power -c (dL/dt)² is its non-conservative part.
class SpringDamper final : public ForceElement {
 public:
  /// `p_AoP_A` from A's frame origin in A [m]; `p_BoQ_B` likewise, or Q's world position when
  /// `body_b` is kWorld. `rest_length` L0 >= 0 [m], `stiffness` k >= 0 [N/m],
  /// `damping` c >= 0 [N·s/m].
  SpringDamper(std::string name, BodyIndex body_a, const Vec3& p_AoP_A, BodyIndex body_b,
               const Vec3& p_BoQ_B, double rest_length, double stiffness, double damping);
  double AddForces(const Model&, const State&, const Data&, WrenchAccumulator&) const override;
  bool has_potential() const override { return stiffness_ != 0.0; }
  double CalcPotentialEnergy(const Model& model, const State& state) const override;
  bool is_dissipative() const override { return true; }
  std::vector<BodyIndex> bodies() const override;
  std::shared_ptr<const ForceElement> Renumbered(
      const std::vector<BodyIndex>& new_index) const override;
  /// The two ends: body A (never kWorld) and body B (or kWorld), and their points as given.
  BodyIndex body_a() const { return a_; }
  BodyIndex body_b() const { return b_; }
  const Vec3& p_AoP_A() const { return p_AoP_A_; }
  const Vec3& p_BoQ_B() const { return p_BoQ_B_; }
  /// L0 [m], k [N/m], c [N·s/m].
  double rest_length() const { return rest_length_; }
  double stiffness() const { return stiffness_; }
  double damping() const { return damping_; }

 private:
  BodyIndex a_, b_;
  Vec3 p_AoP_A_, p_BoQ_B_;
  double rest_length_, stiffness_, damping_;
};

/// Viscous drag on one body: F = -c v_WBcm at the centre of mass and M = -c_w w_WB.
class LinearDrag final : public ForceElement {
 public:
  /// `linear` c >= 0 [N·s/m], `angular` c_w >= 0 [N·m·s].
  LinearDrag(std::string name, BodyIndex body, double linear, double angular);
  double AddForces(const Model&, const State&, const Data&, WrenchAccumulator&) const override;
  bool is_dissipative() const override { return true; }
  std::vector<BodyIndex> bodies() const override { return {body_}; }
  std::shared_ptr<const ForceElement> Renumbered(
      const std::vector<BodyIndex>& new_index) const override;
  /// The body, c [N·s/m] and c_w [N·m·s].
  BodyIndex body() const { return body_; }
  double linear() const { return linear_; }
  double angular() const { return angular_; }

 private:
  BodyIndex body_;
  double linear_, angular_;
};

}  // namespace chasles
