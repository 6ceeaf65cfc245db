#include "integrate/internal/ode.h"

#include <cmath>

#include <fmt/format.h>

#include "chasles/dynamics/constraint_solve.h"
#include "chasles/dynamics/contact_projection.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/error.h"
#include "chasles/math/quaternion.h"
#include "integrate/internal/compensated.h"

namespace chasles::internal {

namespace {

std::string Show(const Vec3& v) {
  return fmt::format("[{:.6g}, {:.6g}, {:.6g}]", v.x(), v.y(), v.z());
}

// "infinite" when a component is infinite (a NaN next to it usually comes from it, e.g.
// 0 * inf in a rotation), else "NaN".
const char* Kind(std::initializer_list<Vec3> vectors, std::initializer_list<double> values = {}) {
  for (const Vec3& v : vectors) {
    for (int i = 0; i < 3; ++i) {
      if (std::isinf(v[i])) return "infinite";
    }
  }
  for (double v : values) {
    if (std::isinf(v)) return "infinite";
  }
  return "NaN";
}

}  // namespace

void CheckFiniteState(const Model& model, const State& state) {
  for (int b = 0; b < model.num_bodies() && b < static_cast<int>(state.bodies.size()); ++b) {
    const BodyState& s = state.bodies[static_cast<size_t>(b)];
    const char* quantity = !s.p_WBcm.allFinite()          ? "position"
                           : !s.q_WB.coeffs().allFinite() ? "orientation"
                           : !s.v_WBcm_W.allFinite()      ? "velocity"
                           : !s.w_WB_B.allFinite()        ? "angular velocity"
                                                          : nullptr;
    if (quantity == nullptr) continue;
    throw InputError(
        fmt::format(
            "the {} of body '{}' became {} at t = {:.9g} s (position {}, velocity {}, angular "
            "velocity {})",
            quantity, model.body(b).name(),
            Kind({s.p_WBcm, s.v_WBcm_W, s.w_WB_B, Vec3(s.q_WB.coeffs().head<3>())}, {s.q_WB.w()}),
            state.t, Show(s.p_WBcm), Show(s.v_WBcm_W), Show(s.w_WB_B)),
        ErrorElement{ErrorElement::Kind::kBody, b});
  }
}

void CheckFiniteEvaluation(const Model& model, const State& state, const Data& data,
                           bool accelerations) {
  const double t = state.t;
  // Inputs before outputs: a body whose state is already not finite makes every force on it so.
  CheckFiniteState(model, state);
  for (int e = 0; e < model.num_force_elements() && e < static_cast<int>(data.elements.size());
       ++e) {
    const ForceElementOutput& o = data.elements[static_cast<size_t>(e)];
    if (o.force_W.allFinite() && o.moment_Wo_W.allFinite() && std::isfinite(o.power)) continue;
    throw InputError(
        fmt::format(
            "force element '{}' evaluated to {} at t = {:.9g} s (force {} N, moment about the "
            "origin {} N*m): check its expression or the bodies' positions "
            "(a body at a force centre, a logarithm or a division by zero)",
            model.force_element(e).name(), Kind({o.force_W, o.moment_Wo_W}, {o.power}), t,
            Show(o.force_W), Show(o.moment_Wo_W)),
        ErrorElement{ErrorElement::Kind::kForceElement, e, true});
  }
  for (int c = 0; c < model.num_constraints() && c < static_cast<int>(data.constraints.size());
       ++c) {
    const ConstraintOutput& o = data.constraints[static_cast<size_t>(c)];
    if (o.F_Jc_W.allFinite() && o.M_Jc_W.allFinite() && std::isfinite(o.power)) continue;
    throw InputError(
        fmt::format(
            "constraint '{}': its reaction evaluated to {} at t = {:.9g} s (force {} N, moment {} "
            "N*m): check the masses and inertias it joins and its driver",
            model.constraint(c).name(), Kind({o.F_Jc_W, o.M_Jc_W}, {o.power}), t, Show(o.F_Jc_W),
            Show(o.M_Jc_W)),
        ErrorElement{ErrorElement::Kind::kConstraint, c, true});
  }
  for (int p = 0;
       p < model.num_contact_points() && p < static_cast<int>(data.contact_points.size()); ++p) {
    const ContactPointOutput& o = data.contact_points[static_cast<size_t>(p)];
    if (std::isfinite(o.normal_force) && o.friction_force_W.allFinite() &&
        std::isfinite(o.friction_power) && std::isfinite(o.rolling_power)) {
      continue;
    }
    throw InputError(
        fmt::format(
            "contact point '{}': its force evaluated to {} at t = {:.9g} s (normal {:.6g} N, "
            "friction {} N)",
            model.contact_point_name(p),
            Kind({o.friction_force_W}, {o.normal_force, o.friction_power, o.rolling_power}), t,
            o.normal_force, Show(o.friction_force_W)),
        ErrorElement{ErrorElement::Kind::kContactPoint, p, true});
  }
  for (int b = 0; b < model.num_bodies(); ++b) {
    const auto i = static_cast<size_t>(b);
    const bool forces =
        i >= data.F_Bcm_W.size() || (data.F_Bcm_W[i].allFinite() && data.M_Bcm_W[i].allFinite());
    const bool acc = !accelerations || i >= data.a_WBcm_W.size() ||
                     (data.a_WBcm_W[i].allFinite() && data.wdot_WB_B[i].allFinite());
    if (forces && acc) continue;
    throw InputError(
        fmt::format("the {} of body '{}' became non-finite at t = {:.9g} s (mass {:.6g} kg): check "
                    "its mass and inertia against the forces on it",
                    forces ? "acceleration" : "resultant force", model.body(b).name(), t,
                    model.body(b).mass()),
        ErrorElement{ErrorElement::Kind::kBody, b});
  }
}

OdeSystem::OdeSystem(const Model& model)
    : model_(model),
      size_(kBodySize * model.num_bodies() + kForceSize * model.num_force_elements() +
            model.num_constraints() + 2 * model.num_contact_points()),
      body_offset_end_(kBodySize * model.num_bodies()),
      contact_offset_(kBodySize * model.num_bodies() + kForceSize * model.num_force_elements() +
                      model.num_constraints()),
      state_(MakeRestState(model)),
      data_(MakeData(model)) {}

void OdeSystem::Pack(const State& s, Vector& y) const {
  y.resize(size_);
  for (int b = 0; b < model_.num_bodies(); ++b) {
    const BodyState& bs = s.bodies[static_cast<size_t>(b)];
    double* o = y.data() + kBodySize * b;
    o[0] = bs.p_WBcm.x(), o[1] = bs.p_WBcm.y(), o[2] = bs.p_WBcm.z();
    o[3] = bs.q_WB.w(), o[4] = bs.q_WB.x(), o[5] = bs.q_WB.y(), o[6] = bs.q_WB.z();
    o[7] = bs.v_WBcm_W.x(), o[8] = bs.v_WBcm_W.y(), o[9] = bs.v_WBcm_W.z();
    o[10] = bs.w_WB_B.x(), o[11] = bs.w_WB_B.y(), o[12] = bs.w_WB_B.z();
  }
  for (int e = 0; e < model_.num_force_elements(); ++e) {
    const ForceIntegrals& fi = s.force_integrals[static_cast<size_t>(e)];
    double* o = y.data() + body_offset_end_ + kForceSize * e;
    o[0] = fi.work, o[1] = fi.work_nonconservative;
    o[2] = fi.linear_impulse_W.x(), o[3] = fi.linear_impulse_W.y(), o[4] = fi.linear_impulse_W.z();
    o[5] = fi.angular_impulse_Wo_W.x(), o[6] = fi.angular_impulse_Wo_W.y();
    o[7] = fi.angular_impulse_Wo_W.z();
  }
  const int c0 = body_offset_end_ + kForceSize * model_.num_force_elements();
  for (int c = 0; c < model_.num_constraints(); ++c) {
    const auto i = static_cast<size_t>(c);
    y[c0 + c] = i < s.constraint_work.size() ? s.constraint_work[i] : 0.0;
  }
  for (int p = 0; p < model_.num_contact_points(); ++p) {
    const auto i = static_cast<size_t>(p);
    const bool has = i < s.contacts.size();
    y[contact_offset_ + 2 * p] = has ? s.contacts[i].friction_work : 0.0;
    y[contact_offset_ + 2 * p + 1] = has ? s.contacts[i].rolling_work : 0.0;
  }
}

void OdeSystem::SetDiscreteState(const State& state) {
  state_.contacts = state.contacts;
  state_.contacts.resize(static_cast<size_t>(model_.num_contact_points()));
  state_.constraint_modes = state.constraint_modes;
}

void OdeSystem::Unpack(double t, const Vector& y, State& s) const {
  s.t = t;
  for (int b = 0; b < model_.num_bodies(); ++b) {
    BodyState& bs = s.bodies[static_cast<size_t>(b)];
    const double* o = y.data() + kBodySize * b;
    bs.p_WBcm = Vec3(o[0], o[1], o[2]);
    bs.q_WB = Quat(o[3], o[4], o[5], o[6]);
    bs.v_WBcm_W = Vec3(o[7], o[8], o[9]);
    bs.w_WB_B = Vec3(o[10], o[11], o[12]);
  }
  for (int e = 0; e < model_.num_force_elements(); ++e) {
    ForceIntegrals& fi = s.force_integrals[static_cast<size_t>(e)];
    const double* o = y.data() + body_offset_end_ + kForceSize * e;
    fi.work = o[0];
    fi.work_nonconservative = o[1];
    fi.linear_impulse_W = Vec3(o[2], o[3], o[4]);
    fi.angular_impulse_Wo_W = Vec3(o[5], o[6], o[7]);
  }
  const int c0 = body_offset_end_ + kForceSize * model_.num_force_elements();
  s.constraint_work.resize(static_cast<size_t>(model_.num_constraints()));
  for (int c = 0; c < model_.num_constraints(); ++c) {
    s.constraint_work[static_cast<size_t>(c)] = y[c0 + c];
  }
  if (&s != &state_) s.constraint_modes = state_.constraint_modes;
  if (model_.num_contact_points() > 0) {
    if (&s != &state_) s.contacts = state_.contacts;
    for (int p = 0; p < model_.num_contact_points(); ++p) {
      ContactPointState& cs = s.contacts[static_cast<size_t>(p)];
      cs.friction_work = y[contact_offset_ + 2 * p];
      cs.rolling_work = y[contact_offset_ + 2 * p + 1];
    }
  }
}

void OdeSystem::Derivative(double t, const Vector& y, Vector& ydot) {
  ++evaluations_;
  Unpack(t, y, state_);
  CalcAccelerations(model_, state_, data_);
  ydot.resize(size_);
  for (int b = 0; b < model_.num_bodies(); ++b) {
    const auto i = static_cast<size_t>(b);
    const double* o = y.data() + kBodySize * b;
    double* d = ydot.data() + kBodySize * b;
    d[0] = o[7], d[1] = o[8], d[2] = o[9];
    const Eigen::Vector4d qd =
        QuatDerivativeWxyz(Eigen::Vector4d(o[3], o[4], o[5], o[6]), state_.bodies[i].w_WB_B);
    d[3] = qd[0], d[4] = qd[1], d[5] = qd[2], d[6] = qd[3];
    const Vec3& a = data_.a_WBcm_W[i];
    const Vec3& wd = data_.wdot_WB_B[i];
    d[7] = a.x(), d[8] = a.y(), d[9] = a.z();
    d[10] = wd.x(), d[11] = wd.y(), d[12] = wd.z();
  }
  for (int e = 0; e < model_.num_force_elements(); ++e) {
    const ForceElementOutput& out = data_.elements[static_cast<size_t>(e)];
    double* d = ydot.data() + body_offset_end_ + kForceSize * e;
    d[0] = out.power, d[1] = out.power_nonconservative;
    d[2] = out.force_W.x(), d[3] = out.force_W.y(), d[4] = out.force_W.z();
    d[5] = out.moment_Wo_W.x(), d[6] = out.moment_Wo_W.y(), d[7] = out.moment_Wo_W.z();
  }
  const int c0 = body_offset_end_ + kForceSize * model_.num_force_elements();
  for (int c = 0; c < model_.num_constraints(); ++c) {
    ydot[c0 + c] = data_.constraints[static_cast<size_t>(c)].power;
  }
  for (int p = 0; p < model_.num_contact_points(); ++p) {
    const ContactPointOutput& out = data_.contact_points[static_cast<size_t>(p)];
    ydot[contact_offset_ + 2 * p] = out.friction_power;
    ydot[contact_offset_ + 2 * p + 1] = out.rolling_power;
  }
  // A non-finite derivative: name what made it (a rejected step could never recover from it).
  if (!ydot.allFinite()) {
    CheckFiniteEvaluation(model_, state_, data_, true);
    throw InputError(fmt::format("the equations of motion became non-finite at t = {:.9g} s", t));
  }
}

bool OdeSystem::projects(bool contacts) const {
  return has_constraints() || (contacts && HasActiveContactRows(model_, state_));
}

void OdeSystem::Project(State& state, bool contacts) {
  if (contacts) {
    ProjectOntoContactModes(model_, state, data_);  // the constraints alone when none touch
  } else {
    ProjectOntoConstraints(model_, state, data_);
  }
}

void OdeSystem::NormalizeQuaternions(Vector& y, Vector* ydot, Vector* compensation) const {
  for (int b = 0; b < model_.num_bodies(); ++b) {
    auto q = y.segment<4>(kBodySize * b + 3);
    const double s = 1.0 / q.norm();
    if (compensation) {
      auto c = compensation->segment<4>(kBodySize * b + 3);
      NormalizeCompensated(q, c);
    } else {
      q *= s;
    }
    if (ydot) ydot->segment<4>(kBodySize * b + 3) *= s;
  }
}

}  // namespace chasles::internal
