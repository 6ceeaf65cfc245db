#pragma once
/// @file
/// Rotational inertia: the chapter's inertia tensor [I] (eq. 8.16).
///
/// Sign convention (stated once, used everywhere in chasles, input and output): the tensor
/// holds the moments of inertia on its diagonal and the *negated* product integrals off it,
///   Ixx = ∫(y²+z²) dm,   Ixy = -∫xy dm,   ...
/// so that the angular momentum is H = [I] ω (eq. 8.15). A report that shows "Ixy" shows this
/// tensor entry. Units: kg·m².

#include <limits>
#include <string>
#include <string_view>

#include "chasles/math/types.h"

namespace chasles {

/// Principal moments (ascending) and axes of a rotational inertia.
struct PrincipalAxes {
  /// Principal moments I1 <= I2 <= I3 [kg·m²].
  Vec3 moments = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  /// Columns are the unit principal axes, expressed in the tensor's frame; det = +1.
  /// For repeated moments the axes are chosen as close to the frame's own axes as possible,
  /// so a sphere or a cube reports the identity.
  Mat3 axes = Mat3::Constant(std::numeric_limits<double>::quiet_NaN());
};

class RotationalInertia {
 public:
  /// NaN everywhere, so that a value never set shows.
  RotationalInertia();

  /// From the tensor entries (chapter convention: products entered as they stand in [I],
  /// i.e. Ixy = -∫xy dm). Not validated: call Validate() at an API boundary.
  RotationalInertia(double Ixx, double Iyy, double Izz, double Ixy = 0, double Ixz = 0,
                    double Iyz = 0);

  /// From a full matrix; it must be symmetric to round-off (checked by Validate()). The
  /// stored tensor is the symmetric part.
  static RotationalInertia FromMatrix(const Mat3& I);
  static RotationalInertia Zero() { return RotationalInertia(0, 0, 0); }

  /// The tensor [kg·m²].
  const Mat3& matrix() const { return I_; }
  double Ixx() const { return I_(0, 0); }
  double Iyy() const { return I_(1, 1); }
  double Izz() const { return I_(2, 2); }
  /// Tensor entries (= -∫xy dm etc.).
  double Ixy() const { return I_(0, 1); }
  double Ixz() const { return I_(0, 2); }
  double Iyz() const { return I_(1, 2); }
  double Trace() const { return I_.trace(); }

  /// Empty when the tensor could belong to a real body (or a thin limit of one): finite,
  /// symmetric, principal moments >= 0 and obeying the triangle inequality I1 + I2 >= I3, with
  /// a tolerance scaled by the trace (equality is a flat plate; a zero moment a slender rod).
  /// Otherwise a sentence naming the violated rule with the numbers.
  std::string CheckPhysicallyValid() const;
  /// Throws InputError with "<what>: <CheckPhysicallyValid()>" when not valid.
  void Validate(std::string_view what) const;

  /// The same tensor expressed in frame A, given R_AB: I_A = R_AB I_B R_ABᵀ.
  RotationalInertia ReExpressedIn(const Mat3& R_AB) const;

  /// Parallel-axis theorem (eq. 8.29): this tensor is about the centre of mass; returns the
  /// tensor about point P, where `p_PCm` is the centre of mass's position from P (same frame):
  ///   I_P = I_Cm + m (|d|² E - d dᵀ).
  RotationalInertia ShiftFromCenterOfMass(double mass, const Vec3& p_PCm) const;
  /// The inverse of ShiftFromCenterOfMass: this tensor is about P; returns it about Cm.
  RotationalInertia ShiftToCenterOfMass(double mass, const Vec3& p_PCm) const;

  /// Principal moments (sorted ascending) and right-handed axes; see PrincipalAxes.
  PrincipalAxes CalcPrincipalAxes() const;

  /// Radii of gyration about the frame's x, y, z axes (eq. 8.19): R = sqrt(I/m) [m].
  Vec3 CalcRadiiOfGyration(double mass) const;

  RotationalInertia operator+(const RotationalInertia& other) const;
  RotationalInertia operator-(const RotationalInertia& other) const;
  RotationalInertia operator*(double s) const;

 private:
  explicit RotationalInertia(const Mat3& I) : I_(I) {}
  Mat3 I_;
};

/// Tensor of a point mass `mass` at `d` about the origin: m (|d|² E - d dᵀ).
Mat3 PointMassInertia(double mass, const Vec3& d);

}  // namespace chasles
