#pragma once
/// @file
/// The frame of one contact point at one state, as the contact stage builds it (docs/contact.md):
/// for engines above the dynamics layer that set up their own contact problem (time stepping,
/// integrate/time_stepping.h) from the same geometry.

#include "chasles/math/types.h"
#include "chasles/model/data.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {

/// Point C of contact point `point` with its normal n (towards `body`) and tangents t1, t2
/// (all in W), the gap, the offsets r_BcmC_W and r_OcmC_W from each body's centre of mass to C
/// and the relative velocity of the material points at C, body minus other.
struct ContactFrame {
  BodyIndex body = kWorld;   // the body carrying the feature
  BodyIndex other = kWorld;  // the other body (kWorld for a plane)
  double gap = 0.0;          // [m]; negative in penetration
  Vec3 p_WC = Vec3::Zero();  // [m]
  Vec3 n = Vec3::UnitZ(), t1 = Vec3::UnitX(), t2 = Vec3::UnitY();
  Vec3 r_BcmC_W = Vec3::Zero();  // [m]
  Vec3 r_OcmC_W = Vec3::Zero();  // [m]
  Vec3 v_rel_W = Vec3::Zero();   // [m/s]
  Vec3 v_t_W = Vec3::Zero();     // its tangential part, the slip velocity [m/s]
};

/// Needs the kinematics stage (Data::R_WB, Data::w_WB_W: CalcKinematics).
ContactFrame CalcContactFrame(const Model& model, const State& state, const Data& data, int point);

}  // namespace chasles
