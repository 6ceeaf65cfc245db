#include "chasles/math/rotation.h"

#include <cctype>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "chasles/error.h"

namespace chasles {

Mat3 Skew(const Vec3& v) {
  Mat3 S;
  S << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return S;
}

Mat3 RotationFromAxisAngle(const Vec3& axis, double angle) {
  const double n = axis.norm();
  if (!std::isfinite(n) || n == 0.0) {
    throw InputError(
        fmt::format("rotation axis [{}, {}, {}] has no direction; give a non-zero axis", axis.x(),
                    axis.y(), axis.z()));
  }
  if (!std::isfinite(angle)) throw InputError("rotation angle is not a finite number");
  return Eigen::AngleAxisd(angle, axis / n).toRotationMatrix();
}

namespace {
Vec3 UnitAxis(char c) {
  switch (std::tolower(static_cast<unsigned char>(c))) {
    case 'x':
      return Vec3::UnitX();
    case 'y':
      return Vec3::UnitY();
    default:
      return Vec3::UnitZ();
  }
}
}  // namespace

Mat3 RotationFromEuler(std::string_view sequence, const Vec3& angles) {
  auto bad = [&] {
    return InputError(fmt::format(
        "Euler sequence '{}' is not valid: use three of x, y, z with no two equal neighbours, "
        "upper case for intrinsic (e.g. ZYX) or lower case for extrinsic (e.g. zyx)",
        sequence));
  };
  if (sequence.size() != 3) throw bad();
  const bool intrinsic = std::isupper(static_cast<unsigned char>(sequence[0]));
  for (char c : sequence) {
    const char l = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (l != 'x' && l != 'y' && l != 'z') throw bad();
    if (static_cast<bool>(std::isupper(static_cast<unsigned char>(c))) != intrinsic) throw bad();
  }
  if (std::tolower(sequence[0]) == std::tolower(sequence[1]) ||
      std::tolower(sequence[1]) == std::tolower(sequence[2])) {
    throw bad();
  }
  if (!angles.allFinite()) throw InputError("Euler angles are not finite numbers");
  Mat3 R = Mat3::Identity();
  for (int i = 0; i < 3; ++i) {
    const Mat3 Ri = Eigen::AngleAxisd(angles[i], UnitAxis(sequence[i])).toRotationMatrix();
    // Intrinsic a-b-c composes left to right; extrinsic a-b-c is the reverse product.
    R = intrinsic ? Mat3(R * Ri) : Mat3(Ri * R);
  }
  return R;
}

Mat3 RotationFromQuaternion(double w, double x, double y, double z) {
  const double n = std::sqrt(w * w + x * x + y * y + z * z);
  if (!std::isfinite(n) || std::abs(n - 1.0) > 1e-6) {
    throw InputError(fmt::format(
        "quaternion [{}, {}, {}, {}] (w, x, y, z) has length {}; a rotation needs length 1", w, x,
        y, z, n));
  }
  return Quat(w / n, x / n, y / n, z / n).toRotationMatrix();
}

Mat3 RotationTakingZTo(const Vec3& direction) {
  const double n = direction.norm();
  if (!std::isfinite(n) || n == 0.0) {
    throw InputError(
        fmt::format("axis direction [{}, {}, {}] has no direction; give a non-zero vector",
                    direction.x(), direction.y(), direction.z()));
  }
  return Quat::FromTwoVectors(Vec3::UnitZ(), direction / n).toRotationMatrix();
}

bool IsRotation(const Mat3& R, double tolerance) {
  return R.allFinite() && (R.transpose() * R - Mat3::Identity()).norm() <= tolerance &&
         std::abs(R.determinant() - 1.0) <= tolerance;
}

}  // namespace chasles
