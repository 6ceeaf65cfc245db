#pragma once
/// @file
/// A robot description's kinematics and total mass: every link's pose in the base (root link)
/// frame B at given joint values, and the sum of the links' mass properties there (eqs. 8.4,
/// 8.29: masses add, centres of mass average, tensors shift to the common centre of mass).

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "chasles/files/robot_model.h"
#include "chasles/mass/mass_properties.h"
#include "chasles/math/types.h"

namespace chasles {

/// A link's pose in the base frame B: R_BL and p_BoLo_B [m].
struct LinkPose {
  Mat3 R_BL = Mat3::Identity();
  Vec3 p_BoLo_B = Vec3::Zero();
};

/// The pose of every link (indexed as model.links) at joint values `q` (by joint name, rad or
/// m; joints not named are at zero): X_BC = X_BP · X_PJ · M(q) · X_JC down the tree, M(q) the
/// rotation about the joint's axis through its point (revolute, continuous) or the translation
/// along it (prismatic). Throws InputError for a name that is no joint of the model, or a
/// value for a joint that has no single coordinate (fixed, floating, planar, ball).
std::vector<LinkPose> CalcLinkPoses(const RobotModel& model,
                                    const std::map<std::string, double>& q);

/// The sum of `parts` (one per link, in the link's frame; nullopt: left out) placed at `poses`,
/// expressed in B. Throws InputError when no part has positive mass.
MassProperties CalcRobotMassProperties(const std::vector<LinkPose>& poses,
                                       const std::vector<std::optional<MassProperties>>& parts);

/// A link's inertial as the file gives it: mass, centre of mass in L and the tensor turned
/// from its frame I into L (I_L = R_LI I_I R_LIᵀ). Not validated.
MassProperties GivenMassProperties(const RobotInertial& inertial);

}  // namespace chasles
