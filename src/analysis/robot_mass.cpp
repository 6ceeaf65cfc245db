// A robot's kinematics and total mass (chasles/analysis/robot_mass.h).

#include "chasles/analysis/robot_mass.h"

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/math/rotation.h"

namespace chasles {

namespace {

bool HasCoordinate(JointType type) {
  return type == JointType::kRevolute || type == JointType::kContinuous ||
         type == JointType::kPrismatic;
}

}  // namespace

std::vector<LinkPose> CalcLinkPoses(const RobotModel& model,
                                    const std::map<std::string, double>& q) {
  std::map<std::string, std::size_t> by_name;
  for (std::size_t j = 0; j < model.joints.size(); ++j) by_name[model.joints[j].name] = j;
  for (const auto& [name, value] : q) {
    const auto it = by_name.find(name);
    if (it == by_name.end()) {
      throw InputError(
          fmt::format("--joint {}: the robot '{}' has no joint of that name", name, model.name));
    }
    if (!HasCoordinate(model.joints[it->second].type)) {
      throw InputError(
          fmt::format("--joint {}: a joint that has no single coordinate (fixed, "
                      "floating, planar or ball) takes no value",
                      name));
    }
    if (!std::isfinite(value))
      throw InputError(fmt::format("--joint {}: not a finite value", name));
  }
  // The joint whose child each link is; the tree is walked from the root, parents first.
  std::vector<std::vector<std::size_t>> children(model.links.size());
  for (std::size_t j = 0; j < model.joints.size(); ++j) {
    children[model.joints[j].parent].push_back(j);
  }
  std::vector<LinkPose> poses(model.links.size());
  if (poses.empty()) return poses;
  std::vector<std::size_t> stack{model.root};
  while (!stack.empty()) {
    const std::size_t p = stack.back();
    stack.pop_back();
    for (const std::size_t j : children[p]) {
      const RobotJoint& joint = model.joints[j];
      const auto it = q.find(joint.name);
      const double value = it == q.end() ? 0.0 : it->second;
      // M(q): a rotation about the axis through A (p' = A + R (p - A)), or a slide along it.
      Mat3 R_JJq = Mat3::Identity();
      Vec3 p_JJq = Vec3::Zero();
      if (joint.type == JointType::kPrismatic) {
        p_JJq = value * joint.axis;
      } else if (value != 0.0) {
        R_JJq = RotationFromAxisAngle(joint.axis, value);
        p_JJq = joint.p_JoA_J - R_JJq * joint.p_JoA_J;
      }
      const LinkPose& P = poses[p];
      LinkPose& C = poses[joint.child];
      const Mat3 R_BJ = P.R_BL * joint.R_PJ;
      const Vec3 p_BJ = P.p_BoLo_B + P.R_BL * joint.p_PoJo_P;
      const Mat3 R_BJq = R_BJ * R_JJq;
      const Vec3 p_BJq = p_BJ + R_BJ * p_JJq;
      C.R_BL = R_BJq * joint.R_JC;
      C.p_BoLo_B = p_BJq + R_BJq * joint.p_JoCo_J;
      stack.push_back(joint.child);
    }
  }
  return poses;
}

MassProperties CalcRobotMassProperties(const std::vector<LinkPose>& poses,
                                       const std::vector<std::optional<MassProperties>>& parts) {
  std::optional<MassProperties> sum;
  for (std::size_t i = 0; i < parts.size() && i < poses.size(); ++i) {
    if (!parts[i] || !(parts[i]->mass() > 0.0)) continue;
    const MassProperties in_B = parts[i]->ExpressedInParent(poses[i].R_BL, poses[i].p_BoLo_B);
    sum = sum ? *sum + in_B : in_B;
  }
  if (!sum) throw InputError("no link has a positive mass: the robot has no mass properties");
  return *sum;
}

MassProperties GivenMassProperties(const RobotInertial& inertial) {
  const Mat3 I_L = inertial.R_LI * inertial.I_LcmI_I * inertial.R_LI.transpose();
  return MassProperties(inertial.mass, inertial.p_LoLcm_L, RotationalInertia::FromMatrix(I_L));
}

}  // namespace chasles
