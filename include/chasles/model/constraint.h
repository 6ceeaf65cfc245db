#pragma once
/// @file
/// Constraints (chapter 8.2-8.3): joints, rolling without slipping and prescribed motions,
/// held by Lagrange multipliers that are the reaction forces. A constraint is a set of scalar
/// rows over the bodies' generalised velocities u_b = [v_WBcm_W; w_WB_W] (angular velocity
/// expressed in W, so that every Jacobian row is built from world vectors):
///   velocity level      J u = b(t, q)            (b = 0 unless a driver moves it)
///   acceleration level  J u̇ = c(t, q, u)         (c holds the velocity-product terms)
/// Holonomic rows also have a position error g(t, q) with ∂g/∂x = J for the displacement
/// x = [δp_WBcm; δθ_W] (a small rotation δθ about W's axes): the projection that removes
/// drift uses these. Constraint forces on the bodies are Jᵀλ (moments about each Bcm, in W).

#include <array>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "chasles/math/types.h"
#include "chasles/model/body.h"

namespace chasles {

class Model;
struct State;
struct Data;

/// Most rows one constraint may have (a weld has 6).
inline constexpr int kMaxConstraintRows = 6;

/// A frame attached to a body (or to the world): origin and axes given in the body's own
/// frame B (from Bo, as the user gives mass properties), or in W when the body is kWorld.
struct AttachmentFrame {
  /// Origin J of the frame from Bo, expressed in B [m] (world position for kWorld).
  Vec3 p_BoJ_B = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  /// Axes of J expressed in B (columns x, y, z); the joint axis is z.
  Mat3 R_BJ = Mat3::Identity();
};

/// What a constraint reports at one configuration: its rows, filled by Constraint::Evaluate.
struct ConstraintEval {
  using Rows = Eigen::Matrix<double, kMaxConstraintRows, 6>;
  using Column = Eigen::Matrix<double, kMaxConstraintRows, 1>;
  /// Jacobian rows on the parent body, per row [∂/∂v_WPcm_W, ∂/∂w_WP_W] (unused for kWorld).
  Rows J_parent = Rows::Zero();
  /// Jacobian rows on the child body, likewise.
  Rows J_child = Rows::Zero();
  /// Velocity right-hand side b (J u = b) [m/s or rad/s].
  Column velocity_rhs = Column::Zero();
  /// Acceleration right-hand side c (J u̇ = c) [m/s² or rad/s²].
  Column acceleration_rhs = Column::Zero();
  /// Position error g of holonomic rows (0 for the others) [m or dimensionless].
  Column position_error = Column::Zero();
  /// Whether each row is holonomic (has a position error the projection removes).
  std::array<bool, kMaxConstraintRows> holonomic{};
  /// The point where the reaction on the child is reported (joint or contact point), in W [m].
  Vec3 p_WJ = Vec3::Zero();
  /// Axes in which a joint's reaction components are named ("its z force": along the joint
  /// axis): the parent's joint frame, in W (W itself for the other constraints).
  Mat3 R_WJ = Mat3::Identity();
  /// Most further bodies one constraint may touch besides its parent and child.
  static constexpr int kMaxExtraBodies = 4;  // J_extra's initialiser lists 4
  /// Rows on further bodies (a string's pulleys carried by bodies that are neither of its
  /// ends): the first `num_extra` entries of `extra_body` and `J_extra`, laid out as J_child.
  int num_extra = 0;
  std::array<BodyIndex, kMaxExtraBodies> extra_body{};
  std::array<Rows, kMaxExtraBodies> J_extra = {Rows::Zero(), Rows::Zero(), Rows::Zero(),
                                               Rows::Zero()};
  /// The rows on body `b` (not kWorld): J_parent, J_child, or an extra slot (made zero when
  /// first asked for; throws InputError past kMaxExtraBodies).
  Rows& RowsOn(BodyIndex b, BodyIndex parent, BodyIndex child);
};

class Constraint {
 public:
  /// `parent` may be kWorld; `child` must be a body.
  Constraint(std::string name, BodyIndex parent, BodyIndex child);
  virtual ~Constraint() = default;
  Constraint(const Constraint&) = delete;
  Constraint& operator=(const Constraint&) = delete;

  /// Name used in reports and messages.
  const std::string& name() const { return name_; }
  /// The parent body, or kWorld.
  BodyIndex parent() const { return parent_; }
  /// The child body: reactions are reported as the force and moment on it.
  BodyIndex child() const { return child_; }
  /// Number of scalar rows (1 to kMaxConstraintRows).
  virtual int num_rows() const = 0;
  /// Kind, for reports ("revolute", "rolling disk", ...).
  virtual std::string kind() const = 0;
  /// Fills `eval` at `state`; reads Data::R_WB and Data::w_WB_W (the kinematics stage).
  virtual void Evaluate(const Model& model, const State& state, const Data& data,
                        ConstraintEval& eval) const = 0;
  /// Whether the constraint is unilateral and can let go (a string going slack): then it has
  /// one holonomic row whose position error g >= 0 is the gap (the slack), whose rate J u is
  /// positive when the gap opens, and whose multiplier (the tension) must be >= 0; its mode is
  /// carried in State::constraint_modes (docs/constraints.md, "Strings that go slack").
  virtual bool can_release() const { return false; }
  /// Newton's restitution coefficient of such a constraint's impact (a string snapping taut):
  /// the gap rate after is -e times the rate before (0: plastic).
  virtual double restitution() const { return 0.0; }
  /// The same constraint on the bodies renumbered by `new_index` (as
  /// ForceElement::Renumbered), or nullptr when it cannot be (the default).
  virtual std::shared_ptr<const Constraint> Renumbered(
      const std::vector<BodyIndex>& /*new_index*/) const {
    return nullptr;
  }

 private:
  std::string name_;
  BodyIndex parent_;
  BodyIndex child_;
};

}  // namespace chasles
