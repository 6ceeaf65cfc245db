#pragma once
/// @file
/// Eigen aliases used throughout chasles. All quantities are SI.
/// Quaternions are written (w, x, y, z) everywhere chasles reads or prints them; Eigen's
/// in-memory order differs (x, y, z, w) and never leaks out of the math layer.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace chasles {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

}  // namespace chasles
