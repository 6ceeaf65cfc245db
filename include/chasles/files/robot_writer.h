#pragma once
/// @file
/// Writing corrected inertials back into a robot file in its own syntax: only the numbers of
/// the inertials being fixed change (URDF attributes, MJCF attributes, SDF element texts); every
/// other byte, comment and attribute order stays; each changed inertial gets an XML comment
/// before it saying what was changed and why. And a unified diff of two texts, to show it.

#include <cstddef>
#include <string>
#include <vector>

#include "chasles/files/robot_model.h"
#include "chasles/math/types.h"

namespace chasles {

/// New values for one link's inertial, in the link frame L.
struct InertialRewrite {
  /// Index into RobotModel::links; the link must have an inertial.
  std::size_t link = 0;
  /// Mass [kg], centre of mass from the link origin in L [m], tensor about it in L [kg·m²].
  double mass = 0.0;
  Vec3 p_LoLcm_L = Vec3::Zero();
  Mat3 I_LcmL_L = Mat3::Zero();
  /// The comment's text (what changed and why); "--" is written "- -".
  std::string comment;
};

/// The text of `model` (model.text) with `fixes` applied. A value is rewritten only where it
/// changes when printed with 6 significant digits; the tensor is written in the inertial's own
/// frame I (URDF rpy, SDF pose: kept), or for an MJCF diaginertia that the new tensor does not
/// fit, as its principal moments with a quat. Throws InputError when a value to change has no
/// text to rewrite (an SDF inertia entry left to its default).
std::string RewriteInertials(const RobotModel& model, const std::vector<InertialRewrite>& fixes);

/// A unified diff (`diff -u`, 3 lines of context) from `before` to `after`, with the two names
/// in its header; empty when the texts are equal.
std::string UnifiedDiff(const std::string& before, const std::string& after,
                        const std::string& before_name, const std::string& after_name);

}  // namespace chasles
