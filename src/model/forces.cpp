#include "chasles/model/forces.h"

#include <cmath>

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/model/data.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {
namespace {

// Body b's index under `new_index` (kWorld stays kWorld).
BodyIndex Renumber(const std::vector<BodyIndex>& new_index, BodyIndex b) {
  return b == kWorld ? kWorld : new_index[static_cast<size_t>(b)];
}

void RequireFinite(const std::string& name, const char* what, const Vec3& v) {
  if (!v.allFinite()) {
    throw InputError(fmt::format("force element '{}': {} is not a finite vector", name, what));
  }
}

void RequireNonNegative(const std::string& name, const char* what, double x, const char* unit) {
  if (!std::isfinite(x) || x < 0.0) {
    throw InputError(
        fmt::format("force element '{}': {} is {:.6g} {}; it must be a finite number >= 0", name,
                    what, x, unit));
  }
}

void RequireFunction(const std::string& name, const VectorFunction& f) {
  if (!f) throw InputError(fmt::format("force element '{}': no function given", name));
}

}  // namespace

// ---------------------------------------------------------------------------------------
UniformGravity::UniformGravity(std::string name, const Vec3& g_W)
    : ForceElement(std::move(name)), g_W_(g_W) {
  RequireFinite(this->name(), "gravitational acceleration", g_W);
}

std::shared_ptr<const ForceElement> UniformGravity::Renumbered(
    const std::vector<BodyIndex>& /*new_index*/) const {
  return std::make_shared<UniformGravity>(name(), g_W_);
}

double UniformGravity::AddForces(const Model& model, const State&, const Data&,
                                 WrenchAccumulator& out) const {
  for (int b = 0; b < model.num_bodies(); ++b) {
    out.AddForceAtCenterOfMass(b, model.body(b).mass() * g_W_);
  }
  return 0.0;
}

double UniformGravity::CalcPotentialEnergy(const Model& model, const State& state) const {
  double V = 0.0;
  for (int b = 0; b < model.num_bodies(); ++b) {
    V -= model.body(b).mass() * g_W_.dot(state.bodies[static_cast<size_t>(b)].p_WBcm);
  }
  return V;
}

// ---------------------------------------------------------------------------------------
CentralGravity::CentralGravity(std::string name, double mu, const Vec3& centre_W)
    : ForceElement(std::move(name)), mu_(mu), centre_W_(centre_W) {
  if (!std::isfinite(mu) || !(mu > 0.0)) {
    throw InputError(fmt::format(
        "force element '{}': gravitational parameter mu is {:.6g} m³/s²; it must be positive "
        "(mu = G M, 3.986e14 for the Earth)",
        this->name(), mu));
  }
  RequireFinite(this->name(), "centre", centre_W);
}

std::shared_ptr<const ForceElement> CentralGravity::Renumbered(
    const std::vector<BodyIndex>& /*new_index*/) const {
  return std::make_shared<CentralGravity>(name(), mu_, centre_W_);
}

double CentralGravity::AddForces(const Model& model, const State& state, const Data&,
                                 WrenchAccumulator& out) const {
  for (int b = 0; b < model.num_bodies(); ++b) {
    const Vec3 r = state.bodies[static_cast<size_t>(b)].p_WBcm - centre_W_;
    const double r2 = r.squaredNorm();
    // F = -mu m r / |r|³ (Newton's law of gravitation).
    out.AddForceAtCenterOfMass(b, (-mu_ * model.body(b).mass() / (r2 * std::sqrt(r2))) * r);
  }
  return 0.0;
}

double CentralGravity::CalcPotentialEnergy(const Model& model, const State& state) const {
  double V = 0.0;
  for (int b = 0; b < model.num_bodies(); ++b) {
    V -= mu_ * model.body(b).mass() /
         (state.bodies[static_cast<size_t>(b)].p_WBcm - centre_W_).norm();
  }
  return V;
}

// ---------------------------------------------------------------------------------------
AppliedForce::AppliedForce(std::string name, BodyIndex body, const Vec3& p_BoP_B,
                           VectorFunction force, VectorFrame frame)
    : AppliedForce(std::move(name), body, p_BoP_B, VectorFrame::kBody, std::move(force), frame) {}

AppliedForce::AppliedForce(std::string name, BodyIndex body, const Vec3& p_P,
                           VectorFrame point_frame, VectorFunction force, VectorFrame frame)
    : ForceElement(std::move(name)),
      body_(body),
      p_P_(p_P),
      point_frame_(point_frame),
      force_(std::move(force)),
      frame_(frame) {
  RequireFinite(this->name(), "point of application", p_P);
  RequireFunction(this->name(), force_);
}

std::shared_ptr<AppliedForce> AppliedForce::Constant(std::string name, BodyIndex body,
                                                     const Vec3& p_BoP_B, const Vec3& force,
                                                     VectorFrame frame) {
  RequireFinite(name, "force", force);
  return std::make_shared<AppliedForce>(
      std::move(name), body, p_BoP_B, [force](const Model&, const State&) { return force; }, frame);
}

double AppliedForce::AddForces(const Model& model, const State& state, const Data& data,
                               WrenchAccumulator& out) const {
  const auto i = static_cast<size_t>(body_);
  const Mat3& R = data.R_WB[i];
  const Vec3 f = force_(model, state);
  const Vec3 F_W = frame_ == VectorFrame::kWorld ? f : Vec3(R * f);
  // A world point: the material point of the body at p_WP now, p_BcmP = p_WP - p_WBcm.
  const Vec3 p_BcmP_W = point_frame_ == VectorFrame::kWorld
                            ? Vec3(p_P_ - state.bodies[i].p_WBcm)
                            : Vec3(R * model.body(body_).PointFromCenterOfMass(p_P_));
  out.AddForceAtPoint(body_, p_BcmP_W, F_W);
  return out.power();
}

// ---------------------------------------------------------------------------------------
CableForce::CableForce(std::string name, BodyIndex body, const Vec3& p_BoP_B, const Vec3& p_WQ,
                       ScalarFunction tension)
    : ForceElement(std::move(name)),
      body_(body),
      p_BoP_B_(p_BoP_B),
      p_WQ_(p_WQ),
      tension_(std::move(tension)) {
  RequireFinite(this->name(), "body point", p_BoP_B);
  RequireFinite(this->name(), "world point", p_WQ);
  if (!tension_)
    throw InputError(fmt::format("force element '{}': no tension given", this->name()));
}

double CableForce::AddForces(const Model& model, const State& state, const Data& data,
                             WrenchAccumulator& out) const {
  const auto i = static_cast<size_t>(body_);
  const Vec3 p_BcmP_W = data.R_WB[i] * model.body(body_).PointFromCenterOfMass(p_BoP_B_);
  const Vec3 d = p_WQ_ - (state.bodies[i].p_WBcm + p_BcmP_W);
  const double L = d.norm();
  const double T = tension_(model, state);
  if (!(T >= 0.0)) {
    throw InputError(fmt::format(
        "force element '{}': the cable's tension is {:.6g} N at t = {:.6g} s; a cable can only "
        "pull (tension >= 0)",
        name(), T, state.t));
  }
  // At P = Q the direction is undefined: the cable has no length left to pull along.
  if (L == 0.0) return 0.0;
  out.AddForceAtPoint(body_, p_BcmP_W, (T / L) * d);
  return out.power();
}

// ---------------------------------------------------------------------------------------
StringPull::StringPull(std::string name, BodyIndex body, const Vec3& p_BoC_B, const Vec3& axis_B,
                       double radius, int sense, const Vec3& direction_W, ScalarFunction tension)
    : ForceElement(std::move(name)),
      body_(body),
      p_BoC_B_(p_BoC_B),
      axis_B_(axis_B),
      radius_(radius),
      sense_(sense),
      d_W_(direction_W),
      tension_(std::move(tension)) {
  RequireFinite(this->name(), "drum centre", p_BoC_B);
  RequireFinite(this->name(), "drum axis", axis_B);
  RequireFinite(this->name(), "direction", direction_W);
  if (!(axis_B.norm() > 0.0)) {
    throw InputError(fmt::format("force element '{}': the drum's axis is zero", this->name()));
  }
  if (!(direction_W.norm() > 0.0)) {
    throw InputError(fmt::format("force element '{}': the pull's direction is zero", this->name()));
  }
  if (!(radius > 0.0) || !std::isfinite(radius)) {
    throw InputError(fmt::format("force element '{}': the drum's radius is {}; it must be > 0",
                                 this->name(), radius));
  }
  if (sense != 1 && sense != -1) {
    throw InputError(
        fmt::format("force element '{}': the sense is {}; expected +1 or -1", this->name(), sense));
  }
  if (!tension_)
    throw InputError(fmt::format("force element '{}': no tension given", this->name()));
  axis_B_.normalize();
  d_W_.normalize();
}

// T = c - s r a × d̂ (header): the point where a string leaving in direction d̂ leaves the
// circle, the centre on its left (s = +1) or right of the string seen along a.
Vec3 StringPull::CalcTangentPoint(const Model& model, const State& state, const Data& data) const {
  const auto i = static_cast<size_t>(body_);
  const Vec3 a = data.R_WB[i] * axis_B_;
  const Vec3 c =
      state.bodies[i].p_WBcm + data.R_WB[i] * model.body(body_).PointFromCenterOfMass(p_BoC_B_);
  const Vec3 d_plane = d_W_ - a * a.dot(d_W_);
  const double len = d_plane.norm();
  if (!(len > 1e-12)) {
    throw InputError(fmt::format(
        "force element '{}': the pull's direction is along the drum's axis at t = {:.6g} s; the "
        "string has no side of the drum to leave from",
        name(), state.t));
  }
  return c - sense_ * radius_ * a.cross(d_plane / len);
}

double StringPull::AddForces(const Model& model, const State& state, const Data& data,
                             WrenchAccumulator& out) const {
  const double P = tension_(model, state);
  if (!(P >= 0.0)) {
    throw InputError(fmt::format(
        "force element '{}': the string's tension is {:.6g} N at t = {:.6g} s; a string can only "
        "pull (tension >= 0)",
        name(), P, state.t));
  }
  const Vec3 T = CalcTangentPoint(model, state, data);
  out.AddForceAtPoint(body_, T - state.bodies[static_cast<size_t>(body_)].p_WBcm, P * d_W_);
  return out.power();
}

// ---------------------------------------------------------------------------------------
JointTorque::JointTorque(std::string name, BodyIndex parent, BodyIndex child, const Vec3& axis_P,
                         ScalarFunction torque)
    : ForceElement(std::move(name)),
      parent_(parent),
      child_(child),
      axis_P_(axis_P),
      torque_(std::move(torque)) {
  RequireFinite(this->name(), "axis", axis_P);
  if (axis_P.norm() == 0.0) {
    throw InputError(fmt::format("force element '{}': the joint axis is zero", this->name()));
  }
  axis_P_.normalize();
  if (!torque_) throw InputError(fmt::format("force element '{}': no torque given", this->name()));
  if (child == kWorld || child == parent) {
    throw InputError(
        fmt::format("force element '{}': a joint torque needs a child body other than its parent",
                    this->name()));
  }
}

std::vector<BodyIndex> JointTorque::bodies() const {
  if (parent_ == kWorld) return {child_};
  return {parent_, child_};
}

double JointTorque::AddForces(const Model& model, const State& state, const Data& data,
                              WrenchAccumulator& out) const {
  const Vec3 a_W =
      parent_ == kWorld ? axis_P_ : Vec3(data.R_WB[static_cast<size_t>(parent_)] * axis_P_);
  const Vec3 M_W = torque_(model, state) * a_W;
  out.AddMoment(child_, M_W);
  if (parent_ != kWorld) out.AddMoment(parent_, -M_W);
  // Power tau a·(w_child - w_parent): the accumulator sums M·w over both bodies.
  return out.power();
}

AppliedMoment::AppliedMoment(std::string name, BodyIndex body, VectorFunction moment,
                             VectorFrame frame)
    : ForceElement(std::move(name)), body_(body), moment_(std::move(moment)), frame_(frame) {
  RequireFunction(this->name(), moment_);
}

std::shared_ptr<AppliedMoment> AppliedMoment::Constant(std::string name, BodyIndex body,
                                                       const Vec3& moment, VectorFrame frame) {
  RequireFinite(name, "moment", moment);
  return std::make_shared<AppliedMoment>(
      std::move(name), body, [moment](const Model&, const State&) { return moment; }, frame);
}

double AppliedMoment::AddForces(const Model& model, const State& state, const Data& data,
                                WrenchAccumulator& out) const {
  const Vec3 m = moment_(model, state);
  out.AddMoment(
      body_, frame_ == VectorFrame::kWorld ? m : Vec3(data.R_WB[static_cast<size_t>(body_)] * m));
  return out.power();
}

// ---------------------------------------------------------------------------------------
SpringDamper::SpringDamper(std::string name, BodyIndex body_a, const Vec3& p_AoP_A,
                           BodyIndex body_b, const Vec3& p_BoQ_B, double rest_length,
                           double stiffness, double damping)
    : ForceElement(std::move(name)),
      a_(body_a),
      b_(body_b),
      p_AoP_A_(p_AoP_A),
      p_BoQ_B_(p_BoQ_B),
      rest_length_(rest_length),
      stiffness_(stiffness),
      damping_(damping) {
  RequireFinite(this->name(), "first attachment point", p_AoP_A);
  RequireFinite(this->name(), "second attachment point", p_BoQ_B);
  RequireNonNegative(this->name(), "rest length", rest_length, "m");
  RequireNonNegative(this->name(), "stiffness", stiffness, "N/m");
  RequireNonNegative(this->name(), "damping", damping, "N·s/m");
  if (body_a == kWorld) {
    throw InputError(
        fmt::format("force element '{}': the first end must be on a body; put the world end second",
                    this->name()));
  }
  if (body_a == body_b) {
    throw InputError(fmt::format(
        "force element '{}': both ends are on body index {}; a spring inside one rigid body does "
        "nothing",
        this->name(), body_a));
  }
}

std::vector<BodyIndex> SpringDamper::bodies() const {
  if (b_ == kWorld) return {a_};
  return {a_, b_};
}

std::shared_ptr<const ForceElement> SpringDamper::Renumbered(
    const std::vector<BodyIndex>& new_index) const {
  return std::make_shared<SpringDamper>(name(), Renumber(new_index, a_), p_AoP_A_,
                                        Renumber(new_index, b_), p_BoQ_B_, rest_length_, stiffness_,
                                        damping_);
}

namespace {
struct EndPoint {
  Vec3 p_BcmP_W;  // offset from the body's centre of mass, in W
  Vec3 p_WP;      // world position
  Vec3 v_WP;      // world velocity
};

EndPoint CalcEndPoint(const Model& model, const State& state, const Data* data, BodyIndex b,
                      const Vec3& p_BoP_B) {
  if (b == kWorld) return {Vec3::Zero(), p_BoP_B, Vec3::Zero()};
  const auto i = static_cast<size_t>(b);
  const BodyState& bs = state.bodies[i];
  const Vec3 p_BcmP_B = model.body(b).PointFromCenterOfMass(p_BoP_B);
  if (data == nullptr) {
    const Vec3 r = bs.q_WB.normalized() * p_BcmP_B;
    return {r, bs.p_WBcm + r, Vec3::Zero()};
  }
  const Vec3 r = data->R_WB[i] * p_BcmP_B;
  return {r, bs.p_WBcm + r, bs.v_WBcm_W + data->w_WB_W[i].cross(r)};
}
}  // namespace

double SpringDamper::AddForces(const Model& model, const State& state, const Data& data,
                               WrenchAccumulator& out) const {
  const EndPoint P = CalcEndPoint(model, state, &data, a_, p_AoP_A_);
  const EndPoint Q = CalcEndPoint(model, state, &data, b_, p_BoQ_B_);
  const Vec3 d = Q.p_WP - P.p_WP;
  const double L = d.norm();
  // At zero length the line of action is undefined; with L0 = 0 the force k d vanishes there
  // anyway, and a finite rest length with coincident ends is a singular configuration.
  if (L == 0.0) return 0.0;
  const Vec3 u = d / L;
  const double L_dot = u.dot(Q.v_WP - P.v_WP);
  const double tension = stiffness_ * (L - rest_length_) + damping_ * L_dot;
  const Vec3 F_on_P = tension * u;
  out.AddForceAtPoint(a_, P.p_BcmP_W, F_on_P);
  if (b_ != kWorld) out.AddForceAtPoint(b_, Q.p_BcmP_W, -F_on_P);
  // Power of the pair: -tension · dL/dt; the damper's share is -c (dL/dt)².
  return -damping_ * L_dot * L_dot;
}

double SpringDamper::CalcPotentialEnergy(const Model& model, const State& state) const {
  const Vec3 d = CalcEndPoint(model, state, nullptr, b_, p_BoQ_B_).p_WP -
                 CalcEndPoint(model, state, nullptr, a_, p_AoP_A_).p_WP;
  const double stretch = d.norm() - rest_length_;
  return 0.5 * stiffness_ * stretch * stretch;
}

// ---------------------------------------------------------------------------------------
LinearDrag::LinearDrag(std::string name, BodyIndex body, double linear, double angular)
    : ForceElement(std::move(name)), body_(body), linear_(linear), angular_(angular) {
  RequireNonNegative(this->name(), "linear drag coefficient", linear, "N·s/m");
  RequireNonNegative(this->name(), "angular drag coefficient", angular, "N·m·s");
}

std::shared_ptr<const ForceElement> LinearDrag::Renumbered(
    const std::vector<BodyIndex>& new_index) const {
  return std::make_shared<LinearDrag>(name(), Renumber(new_index, body_), linear_, angular_);
}

double LinearDrag::AddForces(const Model&, const State& state, const Data& data,
                             WrenchAccumulator& out) const {
  const auto i = static_cast<size_t>(body_);
  out.AddForceAtCenterOfMass(body_, -linear_ * state.bodies[i].v_WBcm_W);
  out.AddMoment(body_, -angular_ * data.w_WB_W[i]);
  return out.power();
}

}  // namespace chasles
