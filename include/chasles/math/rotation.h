#pragma once
/// @file
/// Rotation matrices from the ways a person states an orientation. `R_AB` maps vectors
/// expressed in B to the same vectors expressed in A: v_A = R_AB v_B.

#include <string_view>

#include "chasles/math/types.h"

namespace chasles {

/// Skew-symmetric matrix [v]x with [v]x w = v x w.
Mat3 Skew(const Vec3& v);

/// Rotation by `angle` [rad] about `axis` (any non-zero length; normalised here).
/// Throws InputError for a zero or non-finite axis.
Mat3 RotationFromAxisAngle(const Vec3& axis, double angle);

/// Rotation from three Euler angles [rad] applied in `sequence`, e.g. "ZYX" or "zxz".
/// Upper case: intrinsic (about the rotating axes), lower case: extrinsic (about fixed axes).
/// R = R_a(angles[0]) R_b(angles[1]) R_c(angles[2]) for the intrinsic sequence "abc".
/// Throws InputError for a sequence that is not three of x/y/z with no two equal neighbours.
Mat3 RotationFromEuler(std::string_view sequence, const Vec3& angles);

/// Rotation from a quaternion given as (w, x, y, z); it must be within 1e-6 of unit length
/// (it is then normalised) — a clear InputError otherwise.
Mat3 RotationFromQuaternion(double w, double x, double y, double z);

/// The smallest rotation that takes the unit z axis onto `direction` (any non-zero length).
/// Used to point a shape's symmetry axis (its z axis) along a given direction.
Mat3 RotationTakingZTo(const Vec3& direction);

/// True when R is orthonormal with det +1 to within `tolerance`.
bool IsRotation(const Mat3& R, double tolerance = 1e-12);

}  // namespace chasles
