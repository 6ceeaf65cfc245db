#pragma once
/// @file
/// A radial bearing on a shaft (docs/modes.md, "Rotors"): the journal, a point P of a body,
/// is held near a fixed world point O by springs and dampers across the bearing's axis a. With
/// the radial displacement δ = (E - a aᵀ)(p_P - p_O) in the bearing's axes e1, e2 (normal to
/// a, e2 = a × e1), x = [e1·δ, e2·δ] and its rate ẋ from the journal's material velocity,
///   F = -K x - C ẋ   (K = [[k11, k12], [k21, k22]], C likewise; k12, k21 the cross-coupling
///                     of an oil-film bearing),
/// the force F1 e1 + F2 e2 acting on the body at P; nothing along the axis. The symmetric part
/// of K has the potential ½ xᵀ K_s x; the rest of K and C do non-conservative work.

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "chasles/model/force_element.h"

namespace chasles {

class Bearing final : public ForceElement {
 public:
  /// `p_BoP_B` the journal from Bo in B [m]; `p_WO` the bearing's centre in W [m]; `axis_W`
  /// its axis (any non-zero length); `K` [N/m] and `C` [N·s/m] in the axes e1 (W's x projected
  /// normal to the axis, or y when x is along it), e2. Throws InputError for a zero axis,
  /// non-finite values, or a negative direct stiffness or damping.
  Bearing(std::string name, BodyIndex body, const Vec3& p_BoP_B, const Vec3& p_WO,
          const Vec3& axis_W, const Eigen::Matrix2d& K, const Eigen::Matrix2d& C);
  double AddForces(const Model& model, const State& state, const Data& data,
                   WrenchAccumulator& out) const override;
  bool has_potential() const override { return true; }
  double CalcPotentialEnergy(const Model& model, const State& state) const override;
  bool is_dissipative() const override;
  std::vector<BodyIndex> bodies() const override { return {body_}; }
  std::shared_ptr<const ForceElement> Renumbered(
      const std::vector<BodyIndex>& new_index) const override;

  BodyIndex body() const { return body_; }
  const Vec3& p_BoP_B() const { return p_BoP_B_; }
  const Vec3& p_WO() const { return p_WO_; }
  /// The bearing's axes [e1 e2 a] in W.
  const Mat3& R_WA() const { return R_WA_; }
  const Eigen::Matrix2d& K() const { return K_; }
  const Eigen::Matrix2d& C() const { return C_; }

 private:
  BodyIndex body_;
  Vec3 p_BoP_B_, p_WO_;
  Mat3 R_WA_;
  Eigen::Matrix2d K_, C_;
};

}  // namespace chasles
