#pragma once
/// @file
/// Rolling without slipping of a round body on a fixed curved surface of the world: a ball in a
/// bowl or on a dome (a sphere on the inside or outside of a sphere), a ball in a pipe, a
/// cylinder in a trough or on a drum (a cylinder on the inside or outside of a circular
/// cylinder, their axes parallel). docs/constraints.md, "Rolling on curved surfaces".
///
/// With c the body's centre, O the surface's centre (a sphere) or the foot of c on its axis
/// a (a cylinder), u = (c - O)/|c - O| and R the surface's radius, the contact point is
/// C = O + R u, at the body's radius r from c, and the normal towards the body is n = -u on
/// the inside, +u on the outside. Rows on the velocity of the body's material point at C:
///   n·v_C = 0 (holonomic: |c - O| = R - r inside, R + r outside), t1·v_C = t2·v_C = 0,
/// with t1 = a × u, t2 = a on a cylinder (circumferential, axial) and on a sphere
/// t1 = (u × f)/|u × f|, t2 = u × t1 for the fixed world axis f least aligned with u. A
/// cylinder's axis e is kept parallel to a by (e × b_k)·ω = 0 for two fixed b_k normal to a
/// (holonomic: e·b_k = 0). The rows are written once over the scalar type (SurfaceContact):
/// the velocity-product terms are the exact derivative of the rows along the motion, taken
/// with a dual number (math/dual.h).

#include <memory>
#include <string>
#include <vector>

#include "chasles/math/dual.h"
#include "chasles/math/types.h"
#include "chasles/model/constraint.h"

namespace chasles {

enum class SurfaceShape {
  kSphere,    ///< a sphere: centre and radius
  kCylinder,  ///< a circular cylinder: a point of its axis, the axis and the radius
};

/// The contact geometry at a configuration: the body's centre c and rotation R (scalar T).
template <class T>
struct SurfaceContactGeometry {
  Eigen::Matrix<T, 3, 1> p_C, n, t1, t2, e;
};

class SurfaceRolling final : public Constraint {
 public:
  /// `body_shape` kSphere or kCylinder (a cylinder rolls on a cylinder only); `p_BoC_B` the
  /// body's centre from Bo in B [m], `axis_B` its axis in B (a cylinder), `radius` r > 0 [m];
  /// the surface: `centre_W` [m], `axis_W` (a cylinder), `surface_radius` R > 0 [m], and
  /// whether the body rolls on its `inside` (then r < R). Throws InputError otherwise.
  SurfaceRolling(std::string name, BodyIndex body, SurfaceShape body_shape, const Vec3& p_BoC_B,
                 const Vec3& axis_B, double radius, SurfaceShape surface, const Vec3& centre_W,
                 const Vec3& axis_W, double surface_radius, bool inside);
  int num_rows() const override { return body_shape_ == SurfaceShape::kCylinder ? 5 : 3; }
  std::string kind() const override;
  void Evaluate(const Model& model, const State& state, const Data& data,
                ConstraintEval& eval) const override;

  /// The contact geometry for the body's centre `c` and rotation `R` (see the file comment).
  template <class T>
  SurfaceContactGeometry<T> CalcGeometry(const Eigen::Matrix<T, 3, 1>& c,
                                         const Eigen::Matrix<T, 3, 3>& R) const;

  SurfaceShape body_shape() const { return body_shape_; }
  const Vec3& p_BoC_B() const { return p_BoC_B_; }
  /// The fixed directions b_1, b_2 normal to a cylinder's axis.
  const Vec3& b1() const { return b1_; }
  const Vec3& b2() const { return b2_; }

 private:
  SurfaceShape body_shape_, surface_;
  Vec3 p_BoC_B_, axis_B_;
  double radius_;
  Vec3 centre_W_, axis_W_;
  double surface_radius_;
  bool inside_;
  Vec3 b1_, b2_;
};

template <class T>
SurfaceContactGeometry<T> SurfaceRolling::CalcGeometry(const Eigen::Matrix<T, 3, 1>& c,
                                                       const Eigen::Matrix<T, 3, 3>& R) const {
  using V = Eigen::Matrix<T, 3, 1>;
  const V O = centre_W_.cast<T>(), a = axis_W_.cast<T>();
  V d = c - O;
  V foot = O;
  if (surface_ == SurfaceShape::kCylinder) {
    foot = O + a * a.dot(d);
    d = c - foot;
  }
  using std::sqrt;
  const V u = d / sqrt(d.dot(d));
  SurfaceContactGeometry<T> g;
  g.p_C = foot + T(surface_radius_) * u;
  g.n = inside_ ? V(-u) : u;
  if (surface_ == SurfaceShape::kCylinder) {
    g.t1 = a.cross(u);
    g.t2 = a;
  } else {
    // The fixed world axis least aligned with u, so that u × f is far from zero.
    const Vec3 uv(Value(u.x()), Value(u.y()), Value(u.z()));
    Eigen::Index k = 0;
    uv.cwiseAbs().minCoeff(&k);
    const V f = Vec3::Unit(k).cast<T>();
    const V g1 = u.cross(f);
    g.t1 = g1 / sqrt(g1.dot(g1));
    g.t2 = u.cross(g.t1);
  }
  g.e = R * axis_B_.cast<T>();
  return g;
}

}  // namespace chasles
