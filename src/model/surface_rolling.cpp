#include "chasles/model/surface_rolling.h"

#include <cmath>

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/math/dual.h"
#include "chasles/model/data.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {
namespace {

using V3d = Eigen::Matrix<Dual, 3, 1>;
using M3d = Eigen::Matrix<Dual, 3, 3>;

/// The derivative part of a dual vector.
Vec3 Rate(const V3d& v) {
  return {v.x().d, v.y().d, v.z().d};
}
Vec3 Val(const V3d& v) {
  return {v.x().v, v.y().v, v.z().v};
}

Mat3 Skew(const Vec3& a) {
  Mat3 S;
  S << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return S;
}

}  // namespace

SurfaceRolling::SurfaceRolling(std::string name, BodyIndex body, SurfaceShape body_shape,
                               const Vec3& p_BoC_B, const Vec3& axis_B, double radius,
                               SurfaceShape surface, const Vec3& centre_W, const Vec3& axis_W,
                               double surface_radius, bool inside)
    : Constraint(std::move(name), kWorld, body),
      body_shape_(body_shape),
      surface_(surface),
      p_BoC_B_(p_BoC_B),
      axis_B_(axis_B),
      radius_(radius),
      centre_W_(centre_W),
      axis_W_(axis_W),
      surface_radius_(surface_radius),
      inside_(inside) {
  if (!(radius > 0.0) || !std::isfinite(radius) || !(surface_radius > 0.0) ||
      !std::isfinite(surface_radius)) {
    throw InputError(fmt::format(
        "constraint '{}': the radii are {:.6g} m (body) and {:.6g} m (surface); both must be "
        "positive lengths",
        this->name(), radius, surface_radius));
  }
  if (inside && !(radius < surface_radius)) {
    throw InputError(fmt::format(
        "constraint '{}': a body of radius {:.6g} m cannot roll inside a surface of radius "
        "{:.6g} m; it must be smaller",
        this->name(), radius, surface_radius));
  }
  if (body_shape == SurfaceShape::kCylinder && surface == SurfaceShape::kSphere) {
    throw InputError(fmt::format(
        "constraint '{}': a cylinder rolls on a cylinder (axes parallel), not on a sphere; "
        "give a sphere or a cylindrical surface",
        this->name()));
  }
  const bool needs_axes = surface == SurfaceShape::kCylinder;
  if (!p_BoC_B.allFinite() || !centre_W.allFinite() ||
      (needs_axes && (!(axis_W.norm() > 0.0) || !axis_W.allFinite())) ||
      (body_shape == SurfaceShape::kCylinder && (!(axis_B.norm() > 0.0) || !axis_B.allFinite()))) {
    throw InputError(fmt::format(
        "constraint '{}': a centre is not finite or an axis is zero; give them all", this->name()));
  }
  if (needs_axes) axis_W_.normalize();
  if (body_shape == SurfaceShape::kCylinder) axis_B_.normalize();
  const Vec3 ref = std::abs(axis_W_.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  b1_ = (ref - axis_W_ * axis_W_.dot(ref)).normalized();
  b2_ = axis_W_.cross(b1_);
}

std::string SurfaceRolling::kind() const {
  return fmt::format(
      "rolling {} {} a {}", body_shape_ == SurfaceShape::kSphere ? "sphere" : "cylinder",
      inside_ ? "inside" : "on", surface_ == SurfaceShape::kSphere ? "sphere" : "cylinder");
}

// The rows are those of the file comment; each row's acceleration term is -(d/dt of the row)·u
// along the motion: for a row d·v_C = d·(v + ω × (C - c)),
//   c_row = -[ḋ·v_C + d·(ω × (Ċ - v))]
// (RelativePointRow in constraints.cpp with a fixed parent), and for an axis row
// (e × b)·ω, c_row = -(ė × b)·ω. The rates Ċ, ḋ, ė are the dual parts of the geometry at
// c + ε v, R + ε [ω]× R.
void SurfaceRolling::Evaluate(const Model& model, const State& state, const Data& data,
                              ConstraintEval& e) const {
  const auto i = static_cast<size_t>(child());
  const BodyState& s = state.bodies[i];
  const Mat3& R = data.R_WB[i];
  const Vec3 w = data.w_WB_W[i];
  const Vec3 c = s.p_WBcm + R * model.body(child()).PointFromCenterOfMass(p_BoC_B_);
  const Vec3 v_c = s.v_WBcm_W + w.cross(c - s.p_WBcm);
  V3d cd;
  for (int k = 0; k < 3; ++k) cd[k] = Dual(c[k], v_c[k]);
  M3d Rd;
  const Mat3 R_dot = Skew(w) * R;
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) Rd(r, k) = Dual(R(r, k), R_dot(r, k));
  }
  const SurfaceContactGeometry<Dual> g = CalcGeometry<Dual>(cd, Rd);
  const Vec3 p_C = Val(g.p_C), p_C_dot = Rate(g.p_C);
  const Vec3 r = p_C - s.p_WBcm;
  const Vec3 v_C = s.v_WBcm_W + w.cross(r);
  e.p_WJ = p_C;
  const V3d dirs[3] = {g.n, g.t1, g.t2};
  for (int k = 0; k < 3; ++k) {
    const Vec3 d = Val(dirs[k]), d_dot = Rate(dirs[k]);
    e.J_child.row(k) << d.transpose(), r.cross(d).transpose();
    e.acceleration_rhs[k] = -(d_dot.dot(v_C) + d.dot(w.cross(p_C_dot - s.v_WBcm_W)));
  }
  const Vec3 u = inside_ ? Vec3(-Val(g.n)) : Val(g.n);
  const double reach = inside_ ? surface_radius_ - radius_ : surface_radius_ + radius_;
  // Row 0 is n·v_C = ±(rate of |c - O|) (- inside, where n = -u): the same sign for g.
  const double dist = (c - (p_C - surface_radius_ * u)).norm();
  e.position_error[0] = inside_ ? reach - dist : dist - reach;
  e.holonomic[0] = true;
  if (body_shape_ == SurfaceShape::kCylinder) {
    const Vec3 ax = Val(g.e), ax_dot = Rate(g.e);
    const Vec3 b[2] = {b1_, b2_};
    for (int k = 0; k < 2; ++k) {
      e.J_child.row(3 + k) << 0.0, 0.0, 0.0, ax.cross(b[k]).transpose();
      e.acceleration_rhs[3 + k] = -ax_dot.cross(b[k]).dot(w);
      e.position_error[3 + k] = ax.dot(b[k]);
      e.holonomic[static_cast<size_t>(3 + k)] = true;
    }
  }
}

}  // namespace chasles
