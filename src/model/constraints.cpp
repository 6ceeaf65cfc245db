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

// A row on the relative velocity of the two bodies' material points at a point p that moves
// over both (a contact or pitch point): k·Δv = 0, Δv = (v_c + w_c × r) - (v_p + w_p × ρ),
// r = p - p_ccm, ρ = p - p_pcm. Its parts: linear k and angular r × k on the child, the
// opposite on the parent (so Jᵀλ is a force λk on the child at p and -λk on the parent at p).
// Differentiating along the motion, with ṙ = ṗ - v_c and ρ̇ = ṗ - v_p:
//   d/dt(k·Δv) = k̇·Δv + k·(a_c + ẇ_c × r - a_p - ẇ_p × ρ) + k·(w_c × ṙ - w_p × ρ̇),
// so c = -[k̇·Δv + k·(w_c × ṙ - w_p × ρ̇)].
void RelativePointRow(ConstraintEval& e, int row, const Side& P, const Side& C, const Vec3& p,
                      const Vec3& p_dot, const Vec3& k, const Vec3& k_dot) {
  const Vec3 r = p - C.p_cm, rho = p - P.p_cm;
  SetRow(e, row, k, r.cross(k), -k, -rho.cross(k));
  const Vec3 dv = C.v + C.w.cross(r) - P.v - P.w.cross(rho);
  e.acceleration_rhs[row] =
      -(k_dot.dot(dv) + k.dot(C.w.cross(p_dot - C.v) - P.w.cross(p_dot - P.v)));
}

// A material point of body b (or a fixed world point) and its velocity, in W: `p_BoX_B` is
// from Bo in B (a world position for kWorld).
struct MovingPoint {
  Vec3 p, v;
};
MovingPoint BodyPoint(const Model& model, const Side& s, BodyIndex b, const Vec3& p_BoX_B) {
  if (b == kWorld) return {p_BoX_B, Vec3::Zero()};
  const Vec3 r = s.R * model.body(b).PointFromCenterOfMass(p_BoX_B);
  return {s.p_cm + r, s.v + s.w.cross(r)};
}

// The point of a round body's rim (or sphere) nearest a plane of normal n: C = c - R m, with
// m the unit vector from C to the centre c, in W.
//  sphere, cylinder (axis e ⊥ n): m = n (ṁ = ṅ).
//  disk (rim in the plane ⊥ e): the rim's lowest point along n is at m = u/s, u = n - σ e,
//  σ = n·e, s = |u| = √(1 - σ²). With ė, ṅ the rates: σ̇ = ṅ·e + n·ė,
//  u̇ = ṅ - σ̇ e - σ ė, ṡ = m·u̇, ṁ = (u̇ - m ṡ)/s.
// The height of C above the plane through O is h = (c - O)·n - R s; by the envelope theorem
// (C is the lowest point) ḣ = n·Δv_C, the relative velocity of the two material points at C.
struct RimContact {
  Vec3 m = Vec3::Zero(), m_dot = Vec3::Zero();
  double s = 1.0;
};
RimContact CalcRimContact(const std::string& name, bool disk, const Vec3& e, const Vec3& e_dot,
                          const Vec3& n, const Vec3& n_dot) {
  RimContact rc;
  if (!disk) {
    rc.m = n, rc.m_dot = n_dot;
    return rc;
  }
  const double sigma = n.dot(e);
  const Vec3 u = n - sigma * e;
  rc.s = u.norm();
  if (rc.s < 1e-9) {
    throw InputError(fmt::format(
        "constraint '{}': the disk lies flat on the plane (its axis is along the normal); "
        "rolling on the rim is undefined there",
        name));
  }
  rc.m = u / rc.s;
  const double sigma_dot = n_dot.dot(e) + n.dot(e_dot);
  const Vec3 u_dot = n_dot - sigma_dot * e - sigma * e_dot;
  rc.m_dot = (u_dot - rc.m * rc.m.dot(u_dot)) / rc.s;
  return rc;
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
ConstraintEval::Rows& ConstraintEval::RowsOn(BodyIndex b, BodyIndex parent, BodyIndex child) {
  if (b == parent) return J_parent;
  if (b == child) return J_child;
  for (int k = 0; k < num_extra; ++k) {
    if (extra_body[static_cast<size_t>(k)] == b) return J_extra[static_cast<size_t>(k)];
  }
  if (num_extra == kMaxExtraBodies) {
    throw InputError(fmt::format(
        "a constraint touches more than {} bodies besides its two ends; at most {} are supported",
        kMaxExtraBodies, kMaxExtraBodies));
  }
  const auto k = static_cast<size_t>(num_extra++);
  extra_body[k] = b;
  J_extra[k].setZero();
  return J_extra[k];
}

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
        "constraint '{}': parent and child are the same body (index {}); a constraint joins two "
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

std::shared_ptr<const Constraint> Joint::Renumbered(const std::vector<BodyIndex>& new_index) const {
  const auto renumber = [&](BodyIndex b) {
    return b == kWorld ? kWorld : new_index[static_cast<size_t>(b)];
  };
  return std::make_shared<Joint>(name(), kind_, renumber(parent()), X_PJ_, renumber(child()),
                                 X_CJ_);
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
  e.R_WJ = Jp.R_WJ;
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
    : RollingContact(std::move(name), shape, kWorld, p_WO, n_W, body, p_BoC_B, axis_B, radius) {}

RollingContact::RollingContact(std::string name, RollingShape shape, BodyIndex parent,
                               const Vec3& p_PoO_P, const Vec3& n_P, BodyIndex body,
                               const Vec3& p_BoC_B, const Vec3& axis_B, double radius)
    : Constraint(std::move(name), parent, body),
      shape_(shape),
      p_BoC_B_(p_BoC_B),
      radius_(radius),
      p_PoO_P_(p_PoO_P) {
  if (!std::isfinite(radius) || !(radius > 0.0)) {
    throw InputError(
        fmt::format("constraint '{}': rolling radius is {:.6g} m; it must be a positive length",
                    this->name(), radius));
  }
  if (!p_BoC_B.allFinite() || !p_PoO_P.allFinite()) {
    throw InputError(fmt::format(
        "constraint '{}': the body's centre or the plane's point is not finite", this->name()));
  }
  if (!(n_P.norm() > 0.0) || !n_P.allFinite()) {
    throw InputError(fmt::format(
        "constraint '{}': the plane normal is zero or not finite; give the upward normal",
        this->name()));
  }
  R_PT_ = FrameWithZAxis(n_P);
  if (shape == RollingShape::kWheelInPlane) {
    // The plane of motion is the x-y plane (of W, and of a parent that turns about z only):
    // the rolling surface's normal lies in it, and friction acts along the line t1 = z × n.
    const Vec3 n = n_P.normalized();
    if (std::abs(n.z()) > 1e-12) {
      throw InputError(fmt::format(
          "constraint '{}': a wheel moving in the x-y plane rolls on a line of that plane; the "
          "normal [{:.6g}, {:.6g}, {:.6g}] has a z component",
          this->name(), n.x(), n.y(), n.z()));
    }
    const Vec3 n_xy = Vec3(n.x(), n.y(), 0.0).normalized();
    R_PT_.col(0) = Vec3::UnitZ().cross(n_xy);
    R_PT_.col(1) = Vec3::UnitZ();
    R_PT_.col(2) = n_xy;
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

Mat3 RollingContact::CalcPlaneFrame(const Data& data) const {
  if (parent() == kWorld) return R_PT_;
  return data.R_WB[static_cast<size_t>(parent())] * R_PT_;
}

void RollingContact::Evaluate(const Model& model, const State& state, const Data& data,
                              ConstraintEval& e) const {
  const Side P = GetSide(state, data, parent());
  const Side B = GetSide(state, data, child());
  // The plane's axes turn with the parent: k̇ = w_p × k for k = t1, t2, n.
  const Mat3 T = P.R * R_PT_;
  const Vec3 t1 = T.col(0), t2 = T.col(1), n = T.col(2);
  const MovingPoint O = BodyPoint(model, P, parent(), p_PoO_P_);
  const MovingPoint c = BodyPoint(model, B, child(), p_BoC_B_);  // the round body's centre
  const Vec3 ax = B.R * axis_B_;
  const RimContact rc =
      CalcRimContact(name(), shape_ == RollingShape::kDisk, ax, B.w.cross(ax), n, P.w.cross(n));
  // Contact point C = c - R m and its rate (a geometric point, not a material one).
  const Vec3 p_C = c.p - radius_ * rc.m;
  const Vec3 p_C_dot = c.v - radius_ * rc.m_dot;
  e.p_WJ = p_C;
  const Vec3 dirs[3] = {n, t1, t2};
  // A wheel in the plane has no row along t2 = z: the body's planar joint holds that motion.
  const int rows = shape_ == RollingShape::kWheelInPlane ? 2 : 3;
  for (int k = 0; k < rows; ++k) {
    RelativePointRow(e, k, P, B, p_C, p_C_dot, dirs[k], P.w.cross(dirs[k]));
  }
  e.position_error[0] = (c.p - O.p).dot(n) - radius_ * rc.s;
  e.holonomic[0] = true;
  if (shape_ == RollingShape::kCylinder) {
    // Axis parallel to the plane, g = e·n: ġ = (w_c × e)·n + e·(w_p × n) = (e × n)·(w_c - w_p);
    // g̈ = (e × n)·(ẇ_c - ẇ_p) + (ė × n + e × ṅ)·(w_c - w_p).
    const Vec3 exn = ax.cross(n);
    SetRow(e, 3, Vec3::Zero(), exn, Vec3::Zero(), -exn);
    const Vec3 exn_dot = B.w.cross(ax).cross(n) + ax.cross(P.w.cross(n));
    e.acceleration_rhs[3] = -exn_dot.dot(B.w - P.w);
    e.position_error[3] = ax.dot(n);
    e.holonomic[3] = true;
  }
}

// ---------------------------------------------------------------------------------------
const char* GearKindName(GearKind kind) {
  switch (kind) {
    case GearKind::kExternal:
      return "external";
    case GearKind::kInternal:
      return "internal";
    case GearKind::kFace:
      return "face";
  }
  return "gear";
}

GearMesh::GearMesh(std::string name, GearKind kind, BodyIndex parent,
                   const PitchCircle& parent_circle, BodyIndex child,
                   const PitchCircle& child_circle, bool keep_contact)
    : Constraint(std::move(name), parent, child),
      kind_(kind),
      parent_circle_(parent_circle),
      child_circle_(child_circle),
      keep_contact_(keep_contact) {
  const auto check = [&](const PitchCircle& c, const char* which, bool needs_radius) {
    if (!c.p_BoO_B.allFinite()) {
      throw InputError(fmt::format("gear mesh '{}': the {} pitch circle's centre is not finite",
                                   this->name(), which));
    }
    if (!(c.axis_B.norm() > 0.0) || !c.axis_B.allFinite()) {
      throw InputError(fmt::format(
          "gear mesh '{}': the {} gear's axis is zero or not finite; give its direction",
          this->name(), which));
    }
    if (needs_radius && !(std::isfinite(c.radius) && c.radius > 0.0)) {
      throw InputError(fmt::format(
          "gear mesh '{}': the {} pitch radius is {:.6g} m; it must be a positive length",
          this->name(), which, c.radius));
    }
  };
  check(parent_circle, "parent", kind != GearKind::kFace);
  check(child_circle, "child", true);
  parent_circle_.axis_B.normalize();
  child_circle_.axis_B.normalize();
  if (kind == GearKind::kInternal && !(child_circle.radius < parent_circle.radius)) {
    throw InputError(fmt::format(
        "gear mesh '{}': an internal mesh needs the child's pitch radius ({:.6g} m) smaller "
        "than the ring's ({:.6g} m)",
        this->name(), child_circle.radius, parent_circle.radius));
  }
}

std::string GearMesh::kind() const {
  return fmt::format("{} gear mesh", GearKindName(kind_));
}

void GearMesh::Evaluate(const Model& model, const State& state, const Data& data,
                        ConstraintEval& e) const {
  const Side P = GetSide(state, data, parent());
  const Side C = GetSide(state, data, child());
  // Child's pitch circle: centre a (material point), axis e_a (ė_a = w_c × e_a), radius r_a.
  const MovingPoint a = BodyPoint(model, C, child(), child_circle_.p_BoO_B);
  const Vec3 ea = C.R * child_circle_.axis_B, ea_dot = C.w.cross(ea);
  const double ra = child_circle_.radius;
  // Parent's: centre b, axis e_b.
  const MovingPoint b = BodyPoint(model, P, parent(), parent_circle_.p_BoO_B);
  const Vec3 eb = P.R * parent_circle_.axis_B, eb_dot = P.w.cross(eb);
  if (kind_ == GearKind::kFace) {
    // The child's pitch circle on the parent's pitch plane (through b, normal e_b): the
    // rolling disk's geometry, P = a - r_a m; the mesh direction is the circle's tangent there,
    // t = e_a × m (in the plane: n lies in span(m, e_a)), ṫ = ė_a × m + e_a × ṁ.
    const RimContact rc = CalcRimContact(name(), true, ea, ea_dot, eb, eb_dot);
    const Vec3 p = a.p - ra * rc.m, p_dot = a.v - ra * rc.m_dot;
    e.p_WJ = p;
    RelativePointRow(e, 0, P, C, p, p_dot, ea.cross(rc.m), ea_dot.cross(rc.m) + ea.cross(rc.m_dot));
    if (keep_contact_) {
      RelativePointRow(e, 1, P, C, p, p_dot, eb, eb_dot);
      e.position_error[1] = (a.p - b.p).dot(eb) - ra * rc.s;
      e.holonomic[1] = true;
    }
    return;
  }
  // Spur and ring gears: d = b - a, its part in the child's plane d_p = d - (d·e_a) e_a, of
  // length ℓ along d̂ = d_p/ℓ. The pitch point P = a + σ r_a d̂ (σ = +1 external: on the side
  // towards the other centre; σ = -1 internal: away from the ring's centre), the common
  // tangent t = e_a × d̂. Rates: ḋ = ḃ - ȧ, ḋ_p = ḋ - (ḋ·e_a + d·ė_a) e_a - (d·e_a) ė_a,
  // d̂̇ = (ḋ_p - d̂ (d̂·ḋ_p))/ℓ, ṫ = ė_a × d̂ + e_a × d̂̇.
  const double sigma = kind_ == GearKind::kExternal ? 1.0 : -1.0;
  const Vec3 d = b.p - a.p, d_dot = b.v - a.v;
  const double de = d.dot(ea);
  const Vec3 dp = d - de * ea;
  const double ell = dp.norm();
  if (!(ell > 1e-12 * (1.0 + ra))) {
    throw InputError(fmt::format(
        "gear mesh '{}': the two pitch circles are concentric; the pitch point is undefined",
        name()));
  }
  const Vec3 dh = dp / ell;
  const double de_dot = d_dot.dot(ea) + d.dot(ea_dot);
  const Vec3 dp_dot = d_dot - de_dot * ea - de * ea_dot;
  const Vec3 dh_dot = (dp_dot - dh * dh.dot(dp_dot)) / ell;
  const Vec3 p = a.p + sigma * ra * dh, p_dot = a.v + sigma * ra * dh_dot;
  const Vec3 t = ea.cross(dh), t_dot = ea_dot.cross(dh) + ea.cross(dh_dot);
  e.p_WJ = p;
  RelativePointRow(e, 0, P, C, p, p_dot, t, t_dot);
  if (keep_contact_) {
    // g = ℓ - (r_a + r_b) (external), (r_b - r_a) - ℓ (internal): ġ = σ ℓ̇ with
    //   ℓ̇ = d̂·ḋ_p = d̂·ḋ - (d·e_a) w_c·t   (d̂·e_a = 0, d̂·(w × e_a) = w·t)
    //     = -d̂·Δv_P - (d·e_a) t·(w_c - w_p)   (d̂·v_P(child) = d̂·ȧ, d̂·v_P(parent) = d̂·ḃ -
    //                                          (d·e_a) w_p·t, from P - b = (σ r_a - ℓ) d̂ - (d·e_a)
    //                                          e_a)
    // so a relative point row along -σ d̂ plus the angular part -σ (d·e_a) t on the child and
    // +σ (d·e_a) t on the parent, which vanishes when the gears are coplanar. Its rate adds
    //   c += σ [(ḋ·e_a + d·ė_a) t·Δw + (d·e_a) ṫ·Δw],  Δw = w_c - w_p.
    RelativePointRow(e, 1, P, C, p, p_dot, -sigma * dh, -sigma * dh_dot);
    e.J_child.block<1, 3>(1, 3) -= sigma * de * t.transpose();
    e.J_parent.block<1, 3>(1, 3) += sigma * de * t.transpose();
    const Vec3 dw = C.w - P.w;
    e.acceleration_rhs[1] += sigma * (de_dot * t.dot(dw) + de * t_dot.dot(dw));
    const double rb = parent_circle_.radius;
    e.position_error[1] = kind_ == GearKind::kExternal ? ell - (ra + rb) : (rb - ra) - ell;
    e.holonomic[1] = true;
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
