#include "chasles/model/bearing.h"

#include <cmath>

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/model/data.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {
namespace {

/// The journal's radial displacement x and its rate ẋ in the bearing's axes, and its offset
/// from the centre of mass.
struct Journal {
  Eigen::Vector2d x, x_dot;
  Vec3 r;
};

Journal CalcJournal(const Model& model, const State& state, const Mat3& R_WB, const Vec3& w_W,
                    BodyIndex b, const Vec3& p_BoP_B, const Vec3& p_WO, const Mat3& R_WA) {
  const BodyState& s = state.bodies[static_cast<size_t>(b)];
  Journal j;
  j.r = R_WB * model.body(b).PointFromCenterOfMass(p_BoP_B);
  const Vec3 d = s.p_WBcm + j.r - p_WO;
  const Vec3 v = s.v_WBcm_W + w_W.cross(j.r);
  j.x << R_WA.col(0).dot(d), R_WA.col(1).dot(d);
  j.x_dot << R_WA.col(0).dot(v), R_WA.col(1).dot(v);
  return j;
}

}  // namespace

Bearing::Bearing(std::string name, BodyIndex body, const Vec3& p_BoP_B, const Vec3& p_WO,
                 const Vec3& axis_W, const Eigen::Matrix2d& K, const Eigen::Matrix2d& C)
    : ForceElement(std::move(name)), body_(body), p_BoP_B_(p_BoP_B), p_WO_(p_WO), K_(K), C_(C) {
  if (!(axis_W.norm() > 0.0) || !axis_W.allFinite()) {
    throw InputError(fmt::format(
        "bearing '{}': the axis is zero or not finite; give the shaft's direction", this->name()));
  }
  if (!p_BoP_B.allFinite() || !p_WO.allFinite() || !K.allFinite() || !C.allFinite()) {
    throw InputError(
        fmt::format("bearing '{}': a point, stiffness or damping is not finite", this->name()));
  }
  if (K(0, 0) < 0.0 || K(1, 1) < 0.0 || C(0, 0) < 0.0 || C(1, 1) < 0.0) {
    throw InputError(fmt::format(
        "bearing '{}': the stiffness [{:.6g}, {:.6g}] N/m and damping [{:.6g}, {:.6g}] N*s/m "
        "along its two directions must be >= 0",
        this->name(), K(0, 0), K(1, 1), C(0, 0), C(1, 1)));
  }
  const Vec3 a = axis_W.normalized();
  const Vec3 ref = std::abs(a.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 e1 = (ref - a * a.dot(ref)).normalized();
  R_WA_.col(0) = e1;
  R_WA_.col(1) = a.cross(e1);
  R_WA_.col(2) = a;
}

double Bearing::AddForces(const Model& model, const State& state, const Data& data,
                          WrenchAccumulator& out) const {
  const auto i = static_cast<size_t>(body_);
  const Journal j =
      CalcJournal(model, state, data.R_WB[i], data.w_WB_W[i], body_, p_BoP_B_, p_WO_, R_WA_);
  const Eigen::Vector2d F = -K_ * j.x - C_ * j.x_dot;
  out.AddForceAtPoint(body_, j.r, F[0] * R_WA_.col(0) + F[1] * R_WA_.col(1));
  // Non-conservative power: all but the symmetric stiffness's.
  const Eigen::Matrix2d K_skew = 0.5 * (K_ - K_.transpose());
  return (-K_skew * j.x - C_ * j.x_dot).dot(j.x_dot);
}

double Bearing::CalcPotentialEnergy(const Model& model, const State& state) const {
  const BodyState& s = state.bodies[static_cast<size_t>(body_)];
  const Mat3 R = s.q_WB.normalized().toRotationMatrix();
  const Journal j = CalcJournal(model, state, R, Vec3::Zero(), body_, p_BoP_B_, p_WO_, R_WA_);
  return 0.5 * j.x.dot(0.5 * (K_ + K_.transpose()) * j.x);
}

bool Bearing::is_dissipative() const {
  // Cross-coupled stiffness can feed energy in (oil whip); damping alone only takes it out.
  return K_(0, 1) == K_(1, 0) && C_(0, 1) == C_(1, 0);
}

std::shared_ptr<const ForceElement> Bearing::Renumbered(
    const std::vector<BodyIndex>& new_index) const {
  return std::make_shared<Bearing>(name(), new_index[static_cast<size_t>(body_)], p_BoP_B_, p_WO_,
                                   R_WA_.col(2), K_, C_);
}

}  // namespace chasles
