#include "chasles/model/string_constraint.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/model/data.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {
namespace {

// One circle of the path (an end has radius 0 when it is a point), with the motion of the
// body that carries it (zero for the world and the fixed pulleys).
struct Circle {
  Vec3 c = Vec3::Zero();  // centre, in W
  double r = 0.0;
  int s = 1;
  Vec3 p_cm = Vec3::Zero();  // the body's centre of mass (unused for the world)
  Vec3 v = Vec3::Zero();     // the body's centre-of-mass velocity
  Vec3 w = Vec3::Zero();     // the body's angular velocity, in W
};

// A circle of centre p_BoC_B on `body` (in W for kWorld).
Circle BodyCircle(const Model& model, const State& state, const Data& data, BodyIndex body,
                  const Vec3& p_BoC_B, double r, int s) {
  Circle k;
  k.r = r;
  k.s = s;
  if (body == kWorld) {
    k.c = p_BoC_B;
    return k;
  }
  const auto i = static_cast<size_t>(body);
  k.p_cm = state.bodies[i].p_WBcm;
  k.v = state.bodies[i].v_WBcm_W;
  k.w = data.w_WB_W[i];
  k.c = k.p_cm + data.R_WB[i] * model.body(body).PointFromCenterOfMass(p_BoC_B);
  return k;
}

Circle EndCircle(const Model& model, const State& state, const Data& data, const StringEnd& e) {
  return BodyCircle(model, state, data, e.body, e.p_BoP_B, e.radius, e.sense);
}

void CheckEnd(const std::string& name, const char* which, const StringEnd& e) {
  if (!e.p_BoP_B.allFinite()) {
    throw InputError(fmt::format("string '{}': end {} has no finite point", name, which));
  }
  if (!(e.radius >= 0.0) || !std::isfinite(e.radius)) {
    throw InputError(fmt::format(
        "string '{}': end {}'s drum radius is {}; give a radius > 0 for a drum, 0 for a point",
        name, which, e.radius));
  }
  if (e.sense != 1 && e.sense != -1) {
    throw InputError(
        fmt::format("string '{}': end {}'s sense is {}; expected +1 or -1", name, which, e.sense));
  }
}

}  // namespace

StringConstraint::StringConstraint(std::string name, const StringEnd& a,
                                   std::vector<StringPulley> pulleys, const StringEnd& b,
                                   const Vec3& n_W, double length)
    : Constraint(std::move(name), a.body, b.body),
      a_(a),
      b_(b),
      pulleys_(std::move(pulleys)),
      n_W_(n_W),
      length_(length) {
  CheckEnd(this->name(), "A", a_);
  CheckEnd(this->name(), "B", b_);
  for (size_t k = 0; k < pulleys_.size(); ++k) {
    const StringPulley& p = pulleys_[k];
    if (!p.p_BoO_B.allFinite() || !(p.radius > 0.0) || !std::isfinite(p.radius) ||
        (p.sense != 1 && p.sense != -1)) {
      throw InputError(fmt::format(
          "string '{}': pulley {} needs a finite centre, a radius > 0 and a sense of +1 or -1",
          this->name(), k + 1));
    }
  }
  std::vector<BodyIndex> carriers;  // pulley bodies other than the ends
  for (const StringPulley& p : pulleys_) {
    if (p.body == kWorld || p.body == a_.body || p.body == b_.body) continue;
    if (std::find(carriers.begin(), carriers.end(), p.body) == carriers.end()) {
      carriers.push_back(p.body);
    }
  }
  if (carriers.size() > static_cast<size_t>(ConstraintEval::kMaxExtraBodies)) {
    throw InputError(fmt::format(
        "string '{}': its pulleys are carried by {} bodies besides its ends; at most {} are "
        "supported (split it into several strings)",
        this->name(), carriers.size(), ConstraintEval::kMaxExtraBodies));
  }
  if (!(n_W_.norm() > 0.0) || !n_W_.allFinite()) {
    throw InputError(
        fmt::format("string '{}': the normal of the string's plane has zero length", this->name()));
  }
  n_W_.normalize();
  if (!(length_ > 0.0) || !std::isfinite(length_)) {
    throw InputError(
        fmt::format("string '{}': its length is {}; it must be > 0", this->name(), length_));
  }
}

std::shared_ptr<const Constraint> StringConstraint::Renumbered(
    const std::vector<BodyIndex>& new_index) const {
  const auto renumber = [&](BodyIndex b) {
    return b == kWorld ? kWorld : new_index[static_cast<size_t>(b)];
  };
  StringEnd a = a_, b = b_;
  a.body = renumber(a.body);
  b.body = renumber(b.body);
  std::vector<StringPulley> pulleys = pulleys_;
  for (StringPulley& p : pulleys) p.body = renumber(p.body);
  auto copy = std::make_shared<StringConstraint>(name(), a, std::move(pulleys), b, n_W_, length_);
  copy->set_restitution(restitution_);
  return copy;
}

void StringConstraint::set_restitution(double e) {
  if (!(e >= 0.0 && e <= 1.0)) {
    throw InputError(fmt::format(
        "string '{}': its restitution is {}; it must lie in [0, 1] (0: plastic)", name(), e));
  }
  restitution_ = e;
}

// The path (header comment): common tangents of consecutive circles, and the wrap of each
// pulley from the in-plane direction d_in of the segment arriving to d_out of the one leaving,
// φ = atan2(s n·(d_in × d_out), d_in·d_out) taken in [-π/2, 3π/2).
StringPath StringConstraint::CalcPath(const Model& model, const State& state,
                                      const Data& data) const {
  std::vector<Circle> circles;
  circles.push_back(EndCircle(model, state, data, a_));
  for (const StringPulley& p : pulleys_) {
    circles.push_back(BodyCircle(model, state, data, p.body, p.p_BoO_B, p.radius, p.sense));
  }
  circles.push_back(EndCircle(model, state, data, b_));
  StringPath path;
  const Vec3& n = n_W_;
  std::vector<Vec3> d_plane;
  for (size_t i = 0; i + 1 < circles.size(); ++i) {
    const Circle& c0 = circles[i];
    const Circle& c1 = circles[i + 1];
    const Vec3 D_full = c1.c - c0.c;
    Vec3 T0 = c0.c, T1 = c1.c, seg = D_full, d = Vec3::Zero();
    if (c0.r > 0.0 || c1.r > 0.0) {
      const double h = n.dot(D_full);
      const Vec3 D = D_full - h * n;
      const double delta = c1.s * c1.r - c0.s * c0.r;
      const double q = D.squaredNorm() - delta * delta;
      if (!(q > 0.0)) {
        throw InputError(fmt::format(
            "string '{}': circles {} and {} of its path overlap (centre distance {:.6g} m); no "
            "straight segment joins them",
            name(), i + 1, i + 2, D.norm()));
      }
      const double lp = std::sqrt(q);
      d = (lp * D - delta * n.cross(D)) / D.squaredNorm();
      T0 = c0.c - c0.s * c0.r * n.cross(d);
      T1 = c1.c - c1.s * c1.r * n.cross(d);
      seg = lp * d + h * n;
    }
    const double ell = seg.norm();
    if (!(ell > 0.0)) {
      throw InputError(fmt::format(
          "string '{}': segment {} of its path has zero length; its direction is undefined", name(),
          i + 1));
    }
    path.points.push_back(T0);
    path.points.push_back(T1);
    path.length += ell;
    d_plane.push_back(d);
    if (i == 0) path.e_A = seg / ell, path.first_segment = ell;
    if (i + 2 == circles.size()) path.e_B = -seg / ell, path.last_segment = ell;
  }
  for (size_t k = 1; k + 1 < circles.size(); ++k) {
    const Vec3& d_in = d_plane[k - 1];
    const Vec3& d_out = d_plane[k];
    double phi = std::atan2(circles[k].s * n.dot(d_in.cross(d_out)), d_in.dot(d_out));
    if (phi < -0.5 * std::numbers::pi) phi += 2.0 * std::numbers::pi;
    path.length += circles[k].r * phi;
  }
  return path;
}

void StringConstraint::Evaluate(const Model& model, const State& state, const Data& data,
                                ConstraintEval& eval) const {
  const StringPath path = CalcPath(model, state, data);
  const Circle A = EndCircle(model, state, data, a_);
  const Circle B = EndCircle(model, state, data, b_);
  const Vec3& TA = path.points.front();
  const Vec3& TB = path.points.back();
  // Offsets of the leaving points from each body's centre of mass, and the material
  // velocities there (w = v + ω × r; zero for the world).
  Vec3 rA = Vec3::Zero();
  if (a_.body != kWorld) rA = TA - A.p_cm;
  const Vec3 rB = TB - B.p_cm;
  const Vec3 wA = A.v + A.w.cross(rA);
  const Vec3 wB = B.v + B.w.cross(rB);
  const Vec3& eA = path.e_A;
  const Vec3& eB = path.e_B;
  // Row: ġ = e_A·w_A + e_B·w_B; a body point's velocity along e is e·v + ω·(r × e).
  eval.J_parent.row(0) << eA.transpose(), rA.cross(eA).transpose();
  eval.J_child.row(0) << eB.transpose(), rB.cross(eB).transpose();
  // Each segment's direction e_i (from circle i towards circle i+1; T_i+1 - T_i, header),
  // its length ℓ_i, and the velocities u_i of the circles: w at the ends, the centre's
  // velocity v_c at a pulley (0 when fixed). ė_i = (I - e_i e_iᵀ)(u_i+1 - u_i)/ℓ_i.
  const size_t nc = pulleys_.size() + 2;
  std::vector<Vec3> u(nc, Vec3::Zero()), r_c(nc, Vec3::Zero());
  u.front() = wA;
  u.back() = wB;
  for (size_t k = 0; k < pulleys_.size(); ++k) {
    const StringPulley& p = pulleys_[k];
    const Circle C = BodyCircle(model, state, data, p.body, p.p_BoO_B, p.radius, p.sense);
    if (p.body == kWorld) continue;
    r_c[k + 1] = C.c - C.p_cm;
    u[k + 1] = C.v + C.w.cross(r_c[k + 1]);
  }
  std::vector<Vec3> e(nc - 1), e_dot(nc - 1);
  for (size_t i = 0; i + 1 < nc; ++i) {
    const Vec3 seg = path.points[2 * i + 1] - path.points[2 * i];
    const double ell = seg.norm();
    e[i] = seg / ell;
    const Vec3 du = u[i + 1] - u[i];
    e_dot[i] = (du - e[i] * e[i].dot(du)) / ell;
  }
  // Ends: e_A = e_0, e_B = -e_N (so ė_B = -ė_N).
  double Jdot_u = e_dot.front().dot(wA) + eA.dot(A.w.cross(A.w.cross(rA))) - e_dot.back().dot(wB) +
                  eB.dot(B.w.cross(B.w.cross(rB)));
  // Pulleys on bodies: the row (e_out - e_in)·(v + ω × r_c) on the carrying body (added to an
  // end's row when the pulley rides on that end's body), and its J̇u term.
  for (size_t k = 0; k < pulleys_.size(); ++k) {
    const StringPulley& p = pulleys_[k];
    if (p.body == kWorld) continue;
    const Vec3 f = e[k + 1] - e[k];  // e_out - e_in
    const Vec3& r = r_c[k + 1];
    const Vec3 w = data.w_WB_W[static_cast<size_t>(p.body)];
    ConstraintEval::Rows& J = eval.RowsOn(p.body, parent(), child());
    J.block<1, 3>(0, 0) += f.transpose();
    J.block<1, 3>(0, 3) += r.cross(f).transpose();
    Jdot_u += (e_dot[k + 1] - e_dot[k]).dot(u[k + 1]) + f.dot(w.cross(w.cross(r)));
  }
  eval.acceleration_rhs[0] = -Jdot_u;
  eval.holonomic[0] = !has_drum();
  eval.position_error[0] = has_drum() ? 0.0 : length_ - path.length;
  eval.p_WJ = TB;
}

}  // namespace chasles
