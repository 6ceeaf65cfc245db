#include "chasles/model/data.h"

#include "chasles/model/model.h"

namespace chasles {

Data MakeData(const Model& model) {
  const auto nb = static_cast<size_t>(model.num_bodies());
  Data d;
  d.R_WB.assign(nb, Mat3::Identity());
  d.w_WB_W.assign(nb, Vec3::Zero());
  d.F_Bcm_W.assign(nb, Vec3::Zero());
  d.M_Bcm_W.assign(nb, Vec3::Zero());
  d.elements.assign(static_cast<size_t>(model.num_force_elements()), ForceElementOutput{});
  d.a_WBcm_W.assign(nb, Vec3::Zero());
  d.wdot_WB_B.assign(nb, Vec3::Zero());
  return d;
}

}  // namespace chasles
