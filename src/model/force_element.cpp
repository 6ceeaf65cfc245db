#include "chasles/model/force_element.h"

#include "chasles/model/data.h"
#include "chasles/model/state.h"

namespace chasles {

WrenchAccumulator::WrenchAccumulator(const State& state, Data& data) : state_(state), data_(data) {}

void WrenchAccumulator::Begin(ForceElementOutput* output) {
  out_ = output;
  *out_ = ForceElementOutput{};
}

void WrenchAccumulator::AddForceAtCenterOfMass(BodyIndex b, const Vec3& F_W) {
  const auto i = static_cast<size_t>(b);
  const BodyState& bs = state_.bodies[i];
  data_.F_Bcm_W[i] += F_W;
  out_->force_W += F_W;
  out_->moment_Wo_W += bs.p_WBcm.cross(F_W);
  if (records_) records_->push_back({b, bs.p_WBcm, F_W, Vec3::Zero(), false});
  out_->power += F_W.dot(bs.v_WBcm_W);
}

void WrenchAccumulator::AddForceAtPoint(BodyIndex b, const Vec3& p_BcmP_W, const Vec3& F_W) {
  const auto i = static_cast<size_t>(b);
  const BodyState& bs = state_.bodies[i];
  const Vec3 M = p_BcmP_W.cross(F_W);
  data_.F_Bcm_W[i] += F_W;
  data_.M_Bcm_W[i] += M;
  out_->force_W += F_W;
  out_->moment_Wo_W += (bs.p_WBcm + p_BcmP_W).cross(F_W);
  if (records_) records_->push_back({b, bs.p_WBcm + p_BcmP_W, F_W, Vec3::Zero(), false});
  // Power of a force at P: F·v_P with v_P = v_Bcm + w × p_BcmP.
  out_->power += F_W.dot(bs.v_WBcm_W + data_.w_WB_W[i].cross(p_BcmP_W));
}

void WrenchAccumulator::AddMoment(BodyIndex b, const Vec3& M_W) {
  const auto i = static_cast<size_t>(b);
  data_.M_Bcm_W[i] += M_W;
  out_->moment_Wo_W += M_W;
  if (records_) records_->push_back({b, state_.bodies[i].p_WBcm, Vec3::Zero(), M_W, true});
  out_->power += M_W.dot(data_.w_WB_W[i]);
}

double WrenchAccumulator::power() const {
  return out_->power;
}

}  // namespace chasles
