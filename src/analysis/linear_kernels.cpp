#include "analysis/internal/linear_kernels.h"

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/math/dual.h"
#include "chasles/model/bearing.h"
#include "chasles/model/constraints.h"
#include "chasles/model/forces.h"
#include "chasles/model/surface_rolling.h"

namespace chasles::internal {
namespace {

template <class T>
M3<T> Skew(const V3<T>& a) {
  M3<T> S;
  S << T(0.0), -a.z(), a.y(), a.z(), T(0.0), -a.x(), -a.y(), a.x(), T(0.0);
  return S;
}

/// One body (or the world) at the perturbed configuration and velocity.
template <class T>
struct Side {
  V3<T> p = V3<T>::Zero(), v = V3<T>::Zero(), w = V3<T>::Zero();
  M3<T> R = M3<T>::Identity();
  bool world = true;
};

template <class T>
Side<T> GetSide(const LinearBase& base, const VecX<T>& x, BodyIndex b) {
  Side<T> s;
  if (b == kWorld) return s;
  const int n = static_cast<int>(base.p.size());
  const int q = 6 * b, u = 6 * n + 6 * b;
  const auto i = static_cast<size_t>(b);
  s.world = false;
  s.p = base.p[i].cast<T>() + x.template segment<3>(q);
  s.R = (M3<T>::Identity() + Skew<T>(x.template segment<3>(q + 3))) * base.R[i].cast<T>();
  s.v = base.v[i].cast<T>() + x.template segment<3>(u);
  s.w = base.w_W[i].cast<T>() + x.template segment<3>(u + 3);
  return s;
}

/// A point of body b given from Bo in B (a world point for kWorld): position and offset from
/// the centre of mass, in W.
template <class T>
struct Point {
  V3<T> p, r;
};

template <class T>
Point<T> BodyPoint(const Model& model, const Side<T>& s, BodyIndex b, const Vec3& p_BoP_B) {
  if (b == kWorld) return {p_BoP_B.cast<T>(), V3<T>::Zero()};
  const V3<T> r = s.R * model.body(b).PointFromCenterOfMass(p_BoP_B).cast<T>();
  return {s.p + r, r};
}

/// The rows being written: row k on a body's columns (nothing for the world).
template <class T>
struct RowWriter {
  MatX<T>& A;
  void Lin(int k, BodyIndex b, const V3<T>& lin, const V3<T>& ang) {
    if (b == kWorld) return;
    A.template block<1, 3>(k, 6 * b) += lin.transpose();
    A.template block<1, 3>(k, 6 * b + 3) += ang.transpose();
  }
  /// k·(Δv of the material points at p): child linear k, angular r × k; parent the opposite.
  void RelativePoint(int k, BodyIndex parent, const Side<T>& P, BodyIndex child, const Side<T>& C,
                     const V3<T>& p, const V3<T>& dir) {
    Lin(k, child, dir, (p - C.p).cross(dir));
    Lin(k, parent, -dir, -(p - P.p).cross(dir));
  }
  /// c·(w_c - w_p) = 0: the relative angular velocity along c.
  void Angular(int k, BodyIndex parent, BodyIndex child, const V3<T>& c) {
    Lin(k, child, V3<T>::Zero(), c);
    Lin(k, parent, V3<T>::Zero(), -c);
  }
};

// Joint rows (src/model/constraints.cpp): point coincidence, distance along a parent axis
// (the parent's material point at the child's J origin), perpendicularity a·b with
// ġ = (a × b)·(w_p - w_c).
template <class T>
void JointRows(const Model& model, const Joint& j, const LinearBase& base, const VecX<T>& x, int k0,
               RowWriter<T>& w) {
  const BodyIndex pb = j.parent(), cb = j.child();
  const Side<T> P = GetSide(base, x, pb), C = GetSide(base, x, cb);
  const Point<T> Jc = BodyPoint(model, C, cb, j.X_CJ().p_BoJ_B);
  const M3<T> Ra = P.R * j.X_PJ().R_BJ.cast<T>(), Rb = C.R * j.X_CJ().R_BJ.cast<T>();
  const auto point = [&](int k) {
    for (int i = 0; i < 3; ++i) w.RelativePoint(k + i, pb, P, cb, C, Jc.p, V3<T>::Unit(i));
  };
  const auto dist = [&](int k, int axis) {
    w.RelativePoint(k, pb, P, cb, C, Jc.p, V3<T>(Ra.col(axis)));
  };
  const auto perp = [&](int k, int i, int jj) {
    w.Angular(k, pb, cb, V3<T>(-Ra.col(i).cross(Rb.col(jj))));
  };
  switch (j.joint_kind()) {
    case JointKind::kWeld:
      point(k0), perp(k0 + 3, 0, 1), perp(k0 + 4, 1, 2), perp(k0 + 5, 2, 0);
      break;
    case JointKind::kRevolute:
      point(k0), perp(k0 + 3, 0, 2), perp(k0 + 4, 1, 2);
      break;
    case JointKind::kPrismatic:
      dist(k0, 0), dist(k0 + 1, 1), perp(k0 + 2, 0, 1), perp(k0 + 3, 1, 2), perp(k0 + 4, 2, 0);
      break;
    case JointKind::kSpherical:
      point(k0);
      break;
    case JointKind::kCylindrical:
      dist(k0, 0), dist(k0 + 1, 1), perp(k0 + 2, 0, 2), perp(k0 + 3, 1, 2);
      break;
    case JointKind::kPlanar:
      dist(k0, 2), perp(k0 + 1, 0, 2), perp(k0 + 2, 1, 2);
      break;
    case JointKind::kPointOnPlane:
      dist(k0, 2);
      break;
    case JointKind::kPointOnLine:
    case JointKind::kRevoluteInPlane:
      dist(k0, 0), dist(k0 + 1, 1);
      break;
    case JointKind::kPrismaticInPlane:
      dist(k0, 1), perp(k0 + 1, 0, 1);
      break;
    case JointKind::kWeldInPlane:
      dist(k0, 0), dist(k0 + 1, 1), perp(k0 + 2, 0, 1);
      break;
    case JointKind::kPointOnLineInPlane:
      dist(k0, 1);
      break;
  }
}

// Rolling on a plane (src/model/constraints.cpp, RollingContact): the contact point
// C = c - R m, m = n for a sphere or cylinder, m = (n - (n·e) e)/|n - (n·e) e| for a disk;
// rows n, t1, t2 on the relative velocity of the material points at C, and for a cylinder
// (e × n)·(w_c - w_p) = 0.
template <class T>
void RollingRows(const Model& model, const RollingContact& rc, const LinearBase& base,
                 const VecX<T>& x, int k0, RowWriter<T>& w) {
  const BodyIndex pb = rc.parent(), cb = rc.child();
  const Side<T> P = GetSide(base, x, pb), C = GetSide(base, x, cb);
  const M3<T> Tf = P.R * rc.R_PT().cast<T>();
  const V3<T> n = Tf.col(2);
  const V3<T> c = BodyPoint(model, C, cb, rc.p_BoC_B()).p;
  const V3<T> e = C.R * rc.axis_B().cast<T>();
  V3<T> m = n;
  if (rc.shape() == RollingShape::kDisk) {
    const V3<T> u = n - n.dot(e) * e;
    m = u / u.norm();
  }
  const V3<T> pC = c - T(rc.radius()) * m;
  const int rows = rc.shape() == RollingShape::kWheelInPlane ? 2 : 3;
  const V3<T> dirs[3] = {n, Tf.col(0), Tf.col(1)};
  for (int k = 0; k < rows; ++k) w.RelativePoint(k0 + k, pb, P, cb, C, pC, dirs[k]);
  if (rc.shape() == RollingShape::kCylinder) w.Angular(k0 + 3, pb, cb, V3<T>(e.cross(n)));
}

// Rolling on a curved surface (model/surface_rolling.h): its own geometry, written once.
template <class T>
void SurfaceRows(const Model& model, const SurfaceRolling& sr, const LinearBase& base,
                 const VecX<T>& x, int k0, RowWriter<T>& w) {
  const BodyIndex cb = sr.child();
  const Side<T> P = GetSide(base, x, kWorld), C = GetSide(base, x, cb);
  const V3<T> c = BodyPoint(model, C, cb, sr.p_BoC_B()).p;
  const SurfaceContactGeometry<T> g = sr.CalcGeometry<T>(c, C.R);
  const V3<T> dirs[3] = {g.n, g.t1, g.t2};
  for (int k = 0; k < 3; ++k) w.RelativePoint(k0 + k, kWorld, P, cb, C, g.p_C, dirs[k]);
  if (sr.body_shape() == SurfaceShape::kCylinder) {
    w.Angular(k0 + 3, kWorld, cb, V3<T>(g.e.cross(sr.b1().cast<T>())));
    w.Angular(k0 + 4, kWorld, cb, V3<T>(g.e.cross(sr.b2().cast<T>())));
  }
}

template <class T>
void AddForceAtPoint(VecX<T>& f, BodyIndex b, const V3<T>& r, const V3<T>& F) {
  if (b == kWorld) return;
  f.template segment<3>(6 * b) += F;
  f.template segment<3>(6 * b + 3) += r.cross(F);
}

// SpringDamper (model/forces.h): tension k (L - L0) + c L̇ along PQ, pulling P towards Q.
template <class T>
void SpringForces(const Model& model, const SpringDamper& s, const LinearBase& base,
                  const VecX<T>& x, VecX<T>& f) {
  const Side<T> A = GetSide(base, x, s.body_a()), B = GetSide(base, x, s.body_b());
  const Point<T> P = BodyPoint(model, A, s.body_a(), s.p_AoP_A());
  const Point<T> Q = BodyPoint(model, B, s.body_b(), s.p_BoQ_B());
  const V3<T> d = Q.p - P.p;
  const T L = d.norm();
  if (Value(L) == 0.0) return;
  const V3<T> u = d / L;
  const V3<T> vP = A.v + A.w.cross(P.r), vQ = B.v + B.w.cross(Q.r);
  const T tension = T(s.stiffness()) * (L - T(s.rest_length())) + T(s.damping()) * u.dot(vQ - vP);
  AddForceAtPoint<T>(f, s.body_a(), P.r, V3<T>(tension * u));
  AddForceAtPoint<T>(f, s.body_b(), Q.r, V3<T>(-tension * u));
}

// Bearing (model/bearing.h): F = -K x - C ẋ across the axis, at the journal.
template <class T>
void BearingForces(const Model& model, const Bearing& br, const LinearBase& base, const VecX<T>& x,
                   VecX<T>& f) {
  const Side<T> S = GetSide(base, x, br.body());
  const Point<T> P = BodyPoint(model, S, br.body(), br.p_BoP_B());
  const V3<T> d = P.p - br.p_WO().cast<T>(), v = S.v + S.w.cross(P.r);
  const V3<T> e1 = br.R_WA().col(0).cast<T>(), e2 = br.R_WA().col(1).cast<T>();
  const T x1 = e1.dot(d), x2 = e2.dot(d), v1 = e1.dot(v), v2 = e2.dot(v);
  const Eigen::Matrix2d& K = br.K();
  const Eigen::Matrix2d& C = br.C();
  const T F1 = -(T(K(0, 0)) * x1 + T(K(0, 1)) * x2 + T(C(0, 0)) * v1 + T(C(0, 1)) * v2);
  const T F2 = -(T(K(1, 0)) * x1 + T(K(1, 1)) * x2 + T(C(1, 0)) * v1 + T(C(1, 1)) * v2);
  AddForceAtPoint<T>(f, br.body(), P.r, V3<T>(F1 * e1 + F2 * e2));
}

template <class T>
void ForceElementForces(const Model& model, const LinearBase& base, const VecX<T>& x, VecX<T>& f) {
  for (int i = 0; i < model.num_force_elements(); ++i) {
    const ForceElement& e = model.force_element(i);
    if (const auto* g = dynamic_cast<const UniformGravity*>(&e)) {
      for (int b = 0; b < model.num_bodies(); ++b) {
        f.template segment<3>(6 * b) += (model.body(b).mass() * g->g_W()).cast<T>();
      }
    } else if (const auto* s = dynamic_cast<const SpringDamper*>(&e)) {
      SpringForces(model, *s, base, x, f);
    } else if (const auto* br = dynamic_cast<const Bearing*>(&e)) {
      BearingForces(model, *br, base, x, f);
    } else if (const auto* d = dynamic_cast<const LinearDrag*>(&e)) {
      const Side<T> S = GetSide(base, x, d->body());
      f.template segment<3>(6 * d->body()) -= T(d->linear()) * S.v;
      f.template segment<3>(6 * d->body() + 3) -= T(d->angular()) * S.w;
    }
  }
}

}  // namespace

void CheckLinearisable(const Model& model) {
  for (int b = 0; b < model.num_bodies(); ++b) {
    if (model.body(b).num_zero_moments() != 0) {
      throw InputError(
          fmt::format(
              "body '{}': a linearisation needs every body's rotational inertia (it has {} zero "
              "principal moments); give it a shape or an inertia",
              model.body(b).name(), model.body(b).num_zero_moments()),
          ErrorElement{ErrorElement::Kind::kBody, b});
    }
  }
  for (int i = 0; i < model.num_force_elements(); ++i) {
    const ForceElement& e = model.force_element(i);
    if (dynamic_cast<const UniformGravity*>(&e) == nullptr &&
        dynamic_cast<const SpringDamper*>(&e) == nullptr &&
        dynamic_cast<const Bearing*>(&e) == nullptr &&
        dynamic_cast<const LinearDrag*>(&e) == nullptr) {
      throw InputError(
          fmt::format(
              "force '{}': a linearisation handles uniform gravity, springs, dampers, bearings "
              "and drag; this force is a function of time and state whose derivatives are not "
              "known",
              e.name()),
          ErrorElement{ErrorElement::Kind::kForceElement, i});
    }
  }
  for (int c = 0; c < model.num_constraints(); ++c) {
    const Constraint& k = model.constraint(c);
    if (dynamic_cast<const Joint*>(&k) == nullptr &&
        dynamic_cast<const RollingContact*>(&k) == nullptr &&
        dynamic_cast<const SurfaceRolling*>(&k) == nullptr) {
      throw InputError(
          fmt::format(
              "constraint '{}': a linearisation handles joints and rolling; a {} is not linearised",
              k.name(), k.kind()),
          ErrorElement{ErrorElement::Kind::kConstraint, c});
    }
  }
  if (model.num_contacts() > 0) {
    throw InputError(
        fmt::format(
            "contact '{}': a linearisation holds bodies by joints and rolling only; state a "
            "rolling contact instead of a unilateral one",
            model.contact(0).name()),
        ErrorElement{ErrorElement::Kind::kContact, 0});
  }
}

template <class T>
void EvaluateKernels(const Model& model, const LinearBase& base, const VecX<T>& x,
                     KernelOutput<T>& out) {
  const int n = model.num_bodies();
  out.A = MatX<T>::Zero(model.num_constraint_rows(), 6 * n);
  out.f = VecX<T>::Zero(6 * n);
  out.Mud = VecX<T>::Zero(6 * n);
  RowWriter<T> w{out.A};
  for (int c = 0; c < model.num_constraints(); ++c) {
    const Constraint& k = model.constraint(c);
    const int k0 = model.constraint_row_offset(c);
    if (const auto* j = dynamic_cast<const Joint*>(&k)) JointRows(model, *j, base, x, k0, w);
    if (const auto* r = dynamic_cast<const RollingContact*>(&k)) {
      RollingRows(model, *r, base, x, k0, w);
    }
    if (const auto* r = dynamic_cast<const SurfaceRolling*>(&k)) {
      SurfaceRows(model, *r, base, x, k0, w);
    }
  }
  ForceElementForces(model, base, x, out.f);
  for (int b = 0; b < n; ++b) {
    const Side<T> S = GetSide(base, x, b);
    const M3<T> I_W = S.R * model.body(b).I_BBcm_B().cast<T>() * S.R.transpose();
    // Gyroscopic term of Euler's equations in W (dynamics/constraint_solve.h): -w × (I_W w).
    out.f.template segment<3>(6 * b + 3) -= S.w.cross(V3<T>(I_W * S.w));
    const auto i = static_cast<size_t>(b);
    out.Mud.template segment<3>(6 * b) = (model.body(b).mass() * base.a[i]).cast<T>();
    out.Mud.template segment<3>(6 * b + 3) = I_W * base.alpha_W[i].cast<T>();
  }
}

template void EvaluateKernels<double>(const Model&, const LinearBase&, const VecX<double>&,
                                      KernelOutput<double>&);
template void EvaluateKernels<Dual>(const Model&, const LinearBase&, const VecX<Dual>&,
                                    KernelOutput<Dual>&);

}  // namespace chasles::internal
