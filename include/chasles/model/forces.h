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

 private:
  double mu_;
  Vec3 centre_W_;
};

/// A force at a point P of one body, F = f(t, state), expressed in W or in B. Non-conservative
/// (no potential): its work is integrated along the solution.
class AppliedForce final : public ForceElement {
 public:
  /// `p_BoP_B` is P's position from the body's frame origin, in B [m].
  AppliedForce(std::string name, BodyIndex body, const Vec3& p_BoP_B, VectorFunction force,
               VectorFrame frame);
  /// A constant force [N] expressed in `frame`.
  static std::shared_ptr<AppliedForce> Constant(std::string name, BodyIndex body,
                                                const Vec3& p_BoP_B, const Vec3& force,
                                                VectorFrame frame);
  double AddForces(const Model&, const State&, const Data&, WrenchAccumulator&) const override;
  std::vector<BodyIndex> bodies() const override { return {body_}; }

 private:
  BodyIndex body_;
  Vec3 p_BoP_B_;
  VectorFunction force_;
  VectorFrame frame_;
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

 private:
  BodyIndex body_;
  double linear_, angular_;
};

}  // namespace chasles
