#include "chasles/model/constraints.h"

#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/model/data.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {
namespace {

// Motion of one side of a constraint. The world has zero velocity and identity orientation.
struct Side {
  Vec3 p_cm = Vec3::Zero();
  Vec3 v = Vec3::Zero();
  Vec3 w = Vec3::Zero();  // angular velocity, in W
  Mat3 R = Mat3::Identity();
};

Side GetSide(const State& state, const Data& data, BodyIndex b) {
  Side s;
  if (b == kWorld) return s;
  const auto i = static_cast<size_t>(b);
  s.p_cm = state.bodies[i].p_WBcm;
  s.v = state.bodies[i].v_WBcm_W;
  s.w = data.w_WB_W[i];
  s.R = data.R_WB[i];
  return s;
}

// An attachment frame at the current configuration.
struct Attached {
  Vec3 p;     // origin J, in W
  Mat3 R_WJ;  // axes, in W
  Vec3 r;     // p - p_cm (offset from the body's centre of mass), in W
  Vec3 v_P;   // velocity of the body's material point at J, in W
};

Attached Attach(const Model& model, const Side& s, BodyIndex b, const AttachmentFrame& X) {
  if (b == kWorld) return {X.p_BoJ_B, X.R_BJ, Vec3::Zero(), Vec3::Zero()};
  const Vec3 r = s.R * model.body(b).PointFromCenterOfMass(X.p_BoJ_B);
  return {s.p_cm + r, s.R * X.R_BJ, r, s.v + s.w.cross(r)};
}

// Writes one row. The velocity of a body point P along a fixed direction k is
// k·(v + w × r) = k·v + w·(r × k): linear part k, angular part r × k.
void SetRow(ConstraintEval& e, int k, const Vec3& lin_c, const Vec3& ang_c, const Vec3& lin_p,
            const Vec3& ang_p) {
  e.J_child.row(k) << lin_c.transpose(), ang_c.transpose();
  e.J_parent.row(k) << lin_p.transpose(), ang_p.transpose();
}

// Point coincidence, g = d = p_Jc - p_Jp (3 rows).
//   ġ = v_c + w_c × r_c - v_p - w_p × r_p
//   g̈ = [a_c + ẇ_c × r_c - a_p - ẇ_p × r_p] + w_c × (w_c × r_c) - w_p × (w_p × r_p)
// so c = -(w_c × (w_c × r_c) - w_p × (w_p × r_p)) (the centripetal terms).
void PointRows(ConstraintEval& e, int k0, const Side& P, const Attached& Jp, const Side& C,
               const Attached& Jc) {
  const Vec3 d = Jc.p - Jp.p;
  const Vec3 bias = -(C.w.cross(C.w.cross(Jc.r)) - P.w.cross(P.w.cross(Jp.r)));
  for (int i = 0; i < 3; ++i) {
    const Vec3 k = Vec3::Unit(i);
    SetRow(e, k0 + i, k, Jc.r.cross(k), -k, -Jp.r.cross(k));
    e.position_error[k0 + i] = d[i];
    e.acceleration_rhs[k0 + i] = bias[i];
    e.holonomic[static_cast<size_t>(k0 + i)] = true;
  }
}

// Distance along a parent axis a (turning with the parent), g = d·a.
//   ġ = ḋ·a + d·(w_p × a); the angular part on the parent is -(ρ × a) with ρ = p_Jc - p_pcm,
//   the parent's point that coincides with the child's J origin.
//   g̈ = d̈·a + 2 ḋ·(w_p × a) + d·(ẇ_p × a + w_p × (w_p × a)); the terms without u̇:
//   c = -[a·(w_c × (w_c × r_c) - w_p × (w_p × r_p)) + 2 ḋ·(w_p × a) + d·(w_p × (w_p × a))].
void DistanceRow(ConstraintEval& e, int k, const Side& P, const Attached& Jp, const Side& C,
                 const Attached& Jc, const Vec3& a) {
  const Vec3 d = Jc.p - Jp.p;
  const Vec3 d_dot = Jc.v_P - Jp.v_P;
  const Vec3 rho = Jc.p - P.p_cm;
  SetRow(e, k, a, Jc.r.cross(a), -a, -rho.cross(a));
  e.position_error[k] = d.dot(a);
  const Vec3 wpa = P.w.cross(a);
  e.acceleration_rhs[k] = -(a.dot(C.w.cross(C.w.cross(Jc.r)) - P.w.cross(P.w.cross(Jp.r))) +
                            2.0 * d_dot.dot(wpa) + d.dot(P.w.cross(wpa)));
  e.holonomic[static_cast<size_t>(k)] = true;
}

// Perpendicularity of a parent axis a and a child axis b, g = a·b.
//   ġ = (w_p × a)·b + a·(w_c × b) = (a × b)·(w_p - w_c)
//   g̈ = (a × b)·(ẇ_p - ẇ_c) + ċ·(w_p - w_c), ċ = (w_p × a) × b + a × (w_c × b)
void PerpendicularRow(ConstraintEval& e, int k, const Side& P, const Side& C, const Vec3& a,
                      const Vec3& b) {
  const Vec3 c = a.cross(b);
  SetRow(e, k, Vec3::Zero(), -c, Vec3::Zero(), c);
  e.position_error[k] = a.dot(b);
  const Vec3 c_dot = P.w.cross(a).cross(b) + a.cross(C.w.cross(b));
  e.acceleration_rhs[k] = -c_dot.dot(P.w - C.w);
  e.holonomic[static_cast<size_t>(k)] = true;
}

void RequireFrame(const std::string& name, const char* which, const AttachmentFrame& X) {
  if (!X.p_BoJ_B.allFinite() || !X.R_BJ.allFinite()) {
    throw InputError(fmt::format(
        "constraint '{}': the {} frame has a non-finite origin or axes; give every component", name,
        which));
  }
  const double orth = (X.R_BJ.transpose() * X.R_BJ - Mat3::Identity()).cwiseAbs().maxCoeff();
  if (orth > 1e-9 || X.R_BJ.determinant() < 0.0) {
    throw InputError(
        fmt::format("constraint '{}': the {} frame's axes are not a right-handed orthonormal set "
                    "(|RᵀR - E| = {:.3g}); use FrameWithZAxis(axis) to build them",
                    name, which, orth));
  }
}

}  // namespace

// ---------------------------------------------------------------------------------------
Constraint::Constraint(std::string name, BodyIndex parent, BodyIndex child)
    : name_(std::move(name)), parent_(parent), child_(child) {
  if (name_.empty()) throw InputError("a constraint needs a non-empty name");
  if (child == kWorld) {
    throw InputError(fmt::format(
        "constraint '{}': the child is the world; put the world as the parent and the moving "
        "body as the child",
        name_));
  }
  if (parent == child) {
    throw InputError(fmt::format(
        "constraint '{}': parent and child are the same body ({}); a constraint joins two "
        "different bodies or a body and the world",
        name_, child));
  }
}

Mat3 FrameWithZAxis(const Vec3& axis) {
  const double n = axis.norm();
  if (!std::isfinite(n) || n == 0.0) {
    throw InputError("an axis direction is zero or not finite; give a non-zero vector");
  }
  const Vec3 z = axis / n;
  int least = 0;
  for (int i = 1; i < 3; ++i) {
    if (std::abs(z[i]) < std::abs(z[least])) least = i;
  }
  const Vec3 h = Vec3::Unit(least);
  const Vec3 x = (h - h.dot(z) * z).normalized();
  Mat3 R;
  R << x, z.cross(x), z;
  return R;
}

AttachmentFrame AttachmentFrameAtWorldPose(const Model& model, const State& state, BodyIndex b,
                                           const Vec3& p_WJ, const Mat3& R_WJ) {
  if (b == kWorld) return {p_WJ, R_WJ};
  const Mat3 R_WB = state.bodies[static_cast<size_t>(b)].q_WB.normalized().toRotationMatrix();
  const Vec3 p_WBo = CalcBodyOriginPosition(model, state, b);
  return {R_WB.transpose() * (p_WJ - p_WBo), R_WB.transpose() * R_WJ};
}

// ---------------------------------------------------------------------------------------
const char* JointKindName(JointKind kind) {
  switch (kind) {
    case JointKind::kWeld:
      return "weld";
    case JointKind::kRevolute:
      return "revolute";
    case JointKind::kPrismatic:
      return "prismatic";
    case JointKind::kSpherical:
      return "spherical";
    case JointKind::kCylindrical:
      return "cylindrical";
    case JointKind::kPlanar:
      return "planar";
    case JointKind::kPointOnPlane:
      return "point-on-plane";
    case JointKind::kPointOnLine:
      return "point-on-line";
    case JointKind::kRevoluteInPlane:
      return "planar revolute";
    case JointKind::kPrismaticInPlane:
      return "planar prismatic";
    case JointKind::kWeldInPlane:
      return "planar weld";
    case JointKind::kPointOnLineInPlane:
      return "planar point-on-line";
  }
  return "joint";
}

Joint::Joint(std::string name, JointKind kind, BodyIndex parent, const AttachmentFrame& X_PJ,
             BodyIndex child, const AttachmentFrame& X_CJ)
    : Constraint(std::move(name), parent, child), kind_(kind), X_PJ_(X_PJ), X_CJ_(X_CJ) {
  RequireFrame(this->name(), "parent", X_PJ);
  RequireFrame(this->name(), "child", X_CJ);
}

int Joint::num_rows() const {
  switch (kind_) {
    case JointKind::kWeld:
      return 6;
    case JointKind::kRevolute:
    case JointKind::kPrismatic:
      return 5;
    case JointKind::kCylindrical:
      return 4;
    case JointKind::kSpherical:
    case JointKind::kPlanar:
      return 3;
    case JointKind::kPointOnLine:
    case JointKind::kRevoluteInPlane:
    case JointKind::kPrismaticInPlane:
      return 2;
    case JointKind::kPointOnPlane:
    case JointKind::kPointOnLineInPlane:
      return 1;
    case JointKind::kWeldInPlane:
      return 3;
  }
  return 0;
}

void Joint::Evaluate(const Model& model, const State& state, const Data& data,
                     ConstraintEval& e) const {
  const Side P = GetSide(state, data, parent());
  const Side C = GetSide(state, data, child());
  const Attached Jp = Attach(model, P, parent(), X_PJ_);
  const Attached Jc = Attach(model, C, child(), X_CJ_);
  const Vec3 ax = Jp.R_WJ.col(0), ay = Jp.R_WJ.col(1), az = Jp.R_WJ.col(2);
  const Vec3 bx = Jc.R_WJ.col(0), by = Jc.R_WJ.col(1), bz = Jc.R_WJ.col(2);
  e.p_WJ = Jc.p;
  // Rotation rows: a_x·b_z = a_y·b_z = 0 keep b_z along a_z (free spin about z); adding
  // a_x·b_y = 0 stops that spin too (near alignment the three are independent: their
  // gradients are a_z, a_x, a_y).
  switch (kind_) {
    case JointKind::kWeld:
      PointRows(e, 0, P, Jp, C, Jc);
      PerpendicularRow(e, 3, P, C, ax, by);
      PerpendicularRow(e, 4, P, C, ay, bz);
      PerpendicularRow(e, 5, P, C, az, bx);
      break;
    case JointKind::kRevolute:
      PointRows(e, 0, P, Jp, C, Jc);
      PerpendicularRow(e, 3, P, C, ax, bz);
      PerpendicularRow(e, 4, P, C, ay, bz);
      break;
    case JointKind::kPrismatic:
      DistanceRow(e, 0, P, Jp, C, Jc, ax);
      DistanceRow(e, 1, P, Jp, C, Jc, ay);
      PerpendicularRow(e, 2, P, C, ax, by);
      PerpendicularRow(e, 3, P, C, ay, bz);
      PerpendicularRow(e, 4, P, C, az, bx);
      break;
    case JointKind::kSpherical:
      PointRows(e, 0, P, Jp, C, Jc);
      break;
    case JointKind::kCylindrical:
      DistanceRow(e, 0, P, Jp, C, Jc, ax);
      DistanceRow(e, 1, P, Jp, C, Jc, ay);
      PerpendicularRow(e, 2, P, C, ax, bz);
      PerpendicularRow(e, 3, P, C, ay, bz);
      break;
    case JointKind::kPlanar:
      DistanceRow(e, 0, P, Jp, C, Jc, az);
      PerpendicularRow(e, 1, P, C, ax, bz);
      PerpendicularRow(e, 2, P, C, ay, bz);
      break;
    case JointKind::kPointOnPlane:
      DistanceRow(e, 0, P, Jp, C, Jc, az);
      break;
    case JointKind::kPointOnLine:
      DistanceRow(e, 0, P, Jp, C, Jc, ax);
      DistanceRow(e, 1, P, Jp, C, Jc, ay);
      break;
    // In-plane rows (a_z the plane's normal): their gradients span the in-plane motions
    // (v_x, v_y, w_z) of the two bodies; the out-of-plane ones (v_z, w_x, w_y) belong to each
    // body's kPlanar joint with the world, so no row repeats another.
    case JointKind::kRevoluteInPlane:
      DistanceRow(e, 0, P, Jp, C, Jc, ax);
      DistanceRow(e, 1, P, Jp, C, Jc, ay);
      break;
    case JointKind::kPrismaticInPlane:
      DistanceRow(e, 0, P, Jp, C, Jc, ay);
      PerpendicularRow(e, 1, P, C, ax, by);
      break;
    case JointKind::kWeldInPlane:
      DistanceRow(e, 0, P, Jp, C, Jc, ax);
      DistanceRow(e, 1, P, Jp, C, Jc, ay);
      PerpendicularRow(e, 2, P, C, ax, by);
      break;
    case JointKind::kPointOnLineInPlane:
      DistanceRow(e, 0, P, Jp, C, Jc, ay);
      break;
  }
}

// ---------------------------------------------------------------------------------------
RollingContact::RollingContact(std::string name, RollingShape shape, BodyIndex body,
                               const Vec3& p_BoC_B, const Vec3& axis_B, double radius,
                               const Vec3& p_WO, const Vec3& n_W)
    : Constraint(std::move(name), kWorld, body),
      shape_(shape),
      p_BoC_B_(p_BoC_B),
      radius_(radius),
      p_WO_(p_WO) {
  if (!std::isfinite(radius) || !(radius > 0.0)) {
    throw InputError(
        fmt::format("constraint '{}': rolling radius is {:.6g} m; it must be a positive length",
                    this->name(), radius));
  }
  if (!p_BoC_B.allFinite() || !p_WO.allFinite()) {
    throw InputError(fmt::format(
        "constraint '{}': the body's centre or the plane's point is not finite", this->name()));
  }
  if (!(n_W.norm() > 0.0) || !n_W.allFinite()) {
    throw InputError(fmt::format(
        "constraint '{}': the plane normal is zero or not finite; give the upward normal",
        this->name()));
  }
  const Mat3 T = FrameWithZAxis(n_W);
  t1_W_ = T.col(0), t2_W_ = T.col(1), n_W_ = T.col(2);
  if (shape == RollingShape::kWheelInPlane) {
    // The plane of motion is W's x-y plane: the rolling surface's normal lies in it, and
    // friction acts along the line t1 = z × n.
    if (std::abs(n_W_.z()) > 1e-12) {
      throw InputError(fmt::format(
          "constraint '{}': a wheel moving in the x-y plane rolls on a line of that plane; the "
          "normal [{:.6g}, {:.6g}, {:.6g}] has a z component",
          this->name(), n_W_.x(), n_W_.y(), n_W_.z()));
    }
    n_W_.z() = 0.0;
    n_W_.normalize();
    t1_W_ = Vec3::UnitZ().cross(n_W_);
    t2_W_ = Vec3::UnitZ();
  }
  if (shape != RollingShape::kSphere) {
    if (!(axis_B.norm() > 0.0) || !axis_B.allFinite()) {
      throw InputError(fmt::format(
          "constraint '{}': the symmetry axis is zero or not finite; give the wheel's axle "
          "direction in the body frame",
          this->name()));
    }
    axis_B_ = axis_B.normalized();
  } else {
    axis_B_ = Vec3::UnitZ();
  }
}

std::string RollingContact::kind() const {
  switch (shape_) {
    case RollingShape::kSphere:
      return "rolling sphere";
    case RollingShape::kCylinder:
      return "rolling cylinder";
    case RollingShape::kDisk:
      return "rolling disk";
    case RollingShape::kWheelInPlane:
      return "rolling wheel (planar)";
  }
  return "rolling";
}

void RollingContact::Evaluate(const Model& model, const State& state, const Data& data,
                              ConstraintEval& e) const {
  const Side B = GetSide(state, data, child());
  const Vec3 r_c = B.R * model.body(child()).PointFromCenterOfMass(p_BoC_B_);  // Bcm to centre
  const Vec3& n = n_W_;
  // Unit vector m from the contact point C to the centre: C = centre - R m.
  //  sphere, cylinder (axis e ⊥ n): m = n, constant.
  //  disk (rim in the plane ⊥ e): the rim's lowest point along n is at m = u/|u|,
  //  u = n - (n·e) e. With σ = n·e, ė = w × e, σ̇ = n·ė:
  //  u̇ = -σ̇ e - σ ė, s = |u| = √(1 - σ²), ṡ = -σ σ̇ / s, ṁ = u̇/s - u ṡ/s².
  Vec3 m = n, m_dot = Vec3::Zero();
  double s = 1.0;
  if (shape_ == RollingShape::kDisk) {
    const Vec3 ax = B.R * axis_B_;
    const double sigma = n.dot(ax);
    const Vec3 u = n - sigma * ax;
    s = u.norm();
    if (s < 1e-9) {
      throw InputError(fmt::format(
          "constraint '{}': the disk lies flat on the plane (its axis is along the normal); "
          "rolling on the rim is undefined there",
          name()));
    }
    m = u / s;
    const Vec3 e_dot = B.w.cross(ax);
    const double sigma_dot = n.dot(e_dot);
    const Vec3 u_dot = -sigma_dot * ax - sigma * e_dot;
    const double s_dot = -sigma * sigma_dot / s;
    m_dot = u_dot / s - u * (s_dot / (s * s));
  }
  const Vec3 r = r_c - radius_ * m;  // Bcm to the contact point C, in W
  e.p_WJ = B.p_cm + r;
  // Rows k·v_C = k·(v + w × r) = 0 for k = n, t1, t2 (k fixed in W). Differentiating along
  // the motion, r moves over the body: ṙ = w × r_c - R ṁ (r_c is a material vector), so
  //   k·(a + ẇ × r) + k·(w × ṙ) = 0,  c = -k·(w × ṙ).
  // The normal row is the derivative of the holonomic height of the lowest point,
  //   h = (centre - p_O)·n - R s  (envelope theorem: ḣ = n·v_C).
  const Vec3 r_dot = B.w.cross(r_c) - radius_ * m_dot;
  const Vec3 w_x_rdot = B.w.cross(r_dot);
  const Vec3 dirs[3] = {n, t1_W_, t2_W_};
  // A wheel in the plane has no row along t2 = z: the body's planar joint holds that motion.
  const int tangent_rows = shape_ == RollingShape::kWheelInPlane ? 2 : 3;
  for (int k = 0; k < tangent_rows; ++k) {
    SetRow(e, k, dirs[k], r.cross(dirs[k]), Vec3::Zero(), Vec3::Zero());
    e.acceleration_rhs[k] = -dirs[k].dot(w_x_rdot);
  }
  e.position_error[0] = (B.p_cm + r_c - p_WO_).dot(n) - radius_ * s;
  e.holonomic[0] = true;
  if (shape_ == RollingShape::kCylinder) {
    // Axis parallel to the plane, g = e·n: ġ = (w × e)·n = w·(e × n);
    // g̈ = ẇ·(e × n) + w·((w × e) × n).
    const Vec3 ax = B.R * axis_B_;
    SetRow(e, 3, Vec3::Zero(), ax.cross(n), Vec3::Zero(), Vec3::Zero());
    e.acceleration_rhs[3] = -B.w.dot(B.w.cross(ax).cross(n));
    e.position_error[3] = ax.dot(n);
    e.holonomic[3] = true;
  }
}

// ---------------------------------------------------------------------------------------
TimeFunction TimeFunction::Quadratic(double f0, double f1, double f2) {
  return {[=](double t) { return f0 + t * (f1 + 0.5 * f2 * t); },
          [=](double t) { return f1 + f2 * t; }, [=](double) { return f2; }};
}

PrescribedMotion::PrescribedMotion(std::string name, DriverKind kind, BodyIndex parent,
                                   const AttachmentFrame& X_PJ, BodyIndex child,
                                   const AttachmentFrame& X_CJ, TimeFunction f)
    : Constraint(std::move(name), parent, child),
      kind_(kind),
      X_PJ_(X_PJ),
      X_CJ_(X_CJ),
      f_(std::move(f)) {
  RequireFrame(this->name(), "parent", X_PJ);
  RequireFrame(this->name(), "child", X_CJ);
  if (!f_.value || !f_.rate || !f_.acceleration) {
    throw InputError(fmt::format(
        "constraint '{}': a prescribed motion needs f(t), its rate and its acceleration",
        this->name()));
  }
}

std::string PrescribedMotion::kind() const {
  return kind_ == DriverKind::kTranslation ? "prescribed translation" : "prescribed rotation";
}

void PrescribedMotion::Evaluate(const Model& model, const State& state, const Data& data,
                                ConstraintEval& e) const {
  const Side P = GetSide(state, data, parent());
  const Side C = GetSide(state, data, child());
  const Attached Jp = Attach(model, P, parent(), X_PJ_);
  const Attached Jc = Attach(model, C, child(), X_CJ_);
  const Vec3 az = Jp.R_WJ.col(2);
  const double t = state.t;
  e.p_WJ = Jc.p;
  if (kind_ == DriverKind::kTranslation) {
    // g = d·a_z - f(t): the distance row with ḟ and f̈ on the right-hand sides.
    DistanceRow(e, 0, P, Jp, C, Jc, az);
    e.position_error[0] -= f_.value(t);
  } else {
    // θ = atan2(b_x·a_y, b_x·a_x) about a_z (b_z ∥ a_z held by a revolute joint):
    //   θ̇ = a_z·(w_c - w_p);  θ̈ = a_z·(ẇ_c - ẇ_p) + (w_p × a_z)·(w_c - w_p).
    const Vec3 bx = Jc.R_WJ.col(0);
    SetRow(e, 0, Vec3::Zero(), az, Vec3::Zero(), -az);
    e.acceleration_rhs[0] = -P.w.cross(az).dot(C.w - P.w);
    const double theta = std::atan2(bx.dot(Jp.R_WJ.col(1)), bx.dot(Jp.R_WJ.col(0)));
    e.position_error[0] = std::remainder(theta - f_.value(t), 2.0 * std::numbers::pi);
    e.holonomic[0] = true;
  }
  e.velocity_rhs[0] = f_.rate(t);
  e.acceleration_rhs[0] += f_.acceleration(t);
}

}  // namespace chasles
