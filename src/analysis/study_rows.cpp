// What a study reports at one state: user-body kinematics through the body map, output rows,
// snapshots of bodies, reactions and contact points, the planar angle θ, the rolling watch,
// and the ledger booked at the end of a segment (include/chasles/analysis/study.h).

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string_view>

#include <fmt/format.h>

#include "chasles/analysis/ledger.h"
#include "chasles/analysis/momentum.h"
#include "chasles/analysis/study.h"
#include "chasles/dynamics/contact_solve.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/error.h"
#include "chasles/model/data.h"
#include "internal/study_steps.h"

namespace chasles {

Vec3 BodyMap::PointInModelBody(int b, const Vec3& p_BoP_B) const {
  const BodyPlacement& pl = place[static_cast<size_t>(b)];
  return pl.R_MB * p_BoP_B + pl.p_MoBo_M;
}

MappedBodyMotion CalcMappedBodyMotion(const Model& model, const State& state, const BodyMap& map,
                                      int b) {
  const BodyPlacement& pl = map.place[static_cast<size_t>(b)];
  const BodyState& s = state.bodies[static_cast<size_t>(pl.model_body)];
  const Body& body = model.body(pl.model_body);
  const Mat3 R_WM = s.q_WB.toRotationMatrix();
  MappedBodyMotion m;
  m.R_WB = R_WM * pl.R_MB;
  m.w_WB_W = R_WM * s.w_WB_B;
  const Vec3 p_WMo = s.p_WBcm - R_WM * body.p_BoBcm_B();
  m.p_WBo = p_WMo + R_WM * pl.p_MoBo_M;
  m.p_WBcm = m.p_WBo + m.R_WB * map.p_BoBcm_B[static_cast<size_t>(b)];
  // Rigid-body velocity field: v_P = v_Mcm + w × (p_P - p_Mcm).
  m.v_WBcm_W = s.v_WBcm_W + m.w_WB_W.cross(m.p_WBcm - s.p_WBcm);
  return m;
}

double CalcMechanicalEnergy(const Model& model, const State& state) {
  double V = 0.0;
  for (int i = 0; i < model.num_force_elements(); ++i) {
    V += model.force_element(i).CalcPotentialEnergy(model, state);
  }
  return CalcTranslationalKineticEnergy(model, state) + CalcRotationalKineticEnergy(model, state) +
         V;
}

namespace study_internal {

namespace {

/// Euler ZYX angles (yaw, pitch, roll) of R = Rz(yaw) Ry(pitch) Rx(roll) [rad].
Vec3 CalcYawPitchRoll(const Mat3& R) {
  const double pitch = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  return {std::atan2(R(1, 0), R(0, 0)), pitch, std::atan2(R(2, 1), R(2, 2))};
}

/// The branch of atan2(R(1,0), R(0,0)) + 2πk nearest to `reference` [rad].
double UnwrapTheta(const Mat3& R_WB, double reference) {
  const double wrapped = std::atan2(R_WB(1, 0), R_WB(0, 0));
  const double two_pi = 2.0 * std::numbers::pi;
  return wrapped + two_pi * std::round((reference - wrapped) / two_pi);
}

/// The body quantities a column may ask for, in the order of BodyValue's table.
constexpr std::array<std::string_view, 36> kBodyQuantities = {
    "x",    "y",    "z",  "ox",  "oy",  "oz",    "qw",   "qx",   "qy",   "qz",    "yaw",   "pitch",
    "roll", "tilt", "vx", "vy",  "vz",  "speed", "wx",   "wy",   "wz",   "wbx",   "wby",   "wbz",
    "ax",   "ay",   "az", "alx", "aly", "alz",   "albx", "alby", "albz", "theta", "omega", "alpha"};

int BodyQuantityIndex(std::string_view q) {
  const auto it = std::find(kBodyQuantities.begin(), kBodyQuantities.end(), q);
  return it == kBodyQuantities.end() ? -1 : static_cast<int>(it - kBodyQuantities.begin());
}

/// A body point's velocity and acceleration ("pvx", "pax", ... of StudyColumn::p_BoP_B), the
/// body's own energy and momenta and dH/dt, in the order of BodyKineticsValue's table.
constexpr std::array<std::string_view, 24> kBodyKinetics = {
    "pvx", "pvy", "pvz", "pax", "pay", "paz", "T_trans", "T_rot", "T",   "Px",   "Py",   "Pz",
    "Hx",  "Hy",  "Hz",  "HOx", "HOy", "HOz", "dHx",     "dHy",   "dHz", "dHOx", "dHOy", "dHOz"};

int BodyKineticsIndex(std::string_view q) {
  const auto it = std::find(kBodyKinetics.begin(), kBodyKinetics.end(), q);
  return it == kBodyKinetics.end() ? -1 : static_cast<int>(it - kBodyKinetics.begin());
}

/// Whether a body column needs the accelerations (a, α, a point's a, dH/dt).
bool BodyColumnNeedsAccelerations(std::string_view q) {
  return q[0] == 'a' || q.substr(0, 2) == "pa" || q.substr(0, 2) == "dH";
}

/// The value of a kBodyKinetics quantity of user body `c.body` (exact for a part of a
/// composite: it moves with its model body M).
double BodyKineticsValue(const StudyColumn& c, const Model& model, const BodyMap& map,
                         const State& s, const Data& data) {
  const auto ub = static_cast<size_t>(c.body);
  if (ub >= map.mass.size() || ub >= map.I_BBcm_B.size()) {
    throw InputError(
        fmt::format("output column '{}': the body map carries no mass properties", c.name));
  }
  const MappedBodyMotion m = CalcMappedBodyMotion(model, s, map, c.body);
  const std::string& q = c.quantity;
  const Vec3& w = m.w_WB_W;
  Vec3 al_W = Vec3::Zero(), a_cm = Vec3::Zero();
  if (BodyColumnNeedsAccelerations(q)) {
    // α of M, and a of the user body's centre of mass: a_Mcm + α × r + ω × (ω × r).
    const auto mb = static_cast<size_t>(map.place[ub].model_body);
    al_W = data.R_WB[mb] * data.wdot_WB_B[mb];
    const Vec3 r = m.p_WBcm - s.bodies[mb].p_WBcm;
    a_cm = data.a_WBcm_W[mb] + al_W.cross(r) + w.cross(w.cross(r));
  }
  // The point P: r from the centre of mass, v_P = v + ω × r, a_P = a + α × r + ω × (ω × r).
  Vec3 v_P = Vec3::Zero(), a_P = Vec3::Zero();
  if (q[0] == 'p') {
    const Vec3 r = m.R_WB * (c.p_BoP_B - map.p_BoBcm_B[ub]);
    v_P = m.v_WBcm_W + w.cross(r);
    a_P = a_cm + al_W.cross(r) + w.cross(w.cross(r));
  }
  // The body's own T = ½ m v² + ½ ωᵀ I ω, P = m v, H = I ω about its centre of mass and
  // H_O = H + r_cm × P (eqs. 8.115, 8.116); dH/dt = R (I α + ω × I ω) in body axes (the left
  // sides of Euler's equations, eqs. 8.75-8.81) and dH_O/dt = dH/dt + r_cm × m a_cm.
  const double mass = map.mass[ub];
  const Mat3& I = map.I_BBcm_B[ub];
  const Vec3 w_B = m.R_WB.transpose() * w;
  const Vec3 al_B = m.R_WB.transpose() * al_W;
  const Vec3 P = mass * m.v_WBcm_W;
  const Vec3 H = m.R_WB * Vec3(I * w_B);
  const Vec3 HO = H + m.p_WBcm.cross(P);
  const Vec3 dH = m.R_WB * Vec3(I * al_B + w_B.cross(Vec3(I * w_B)));
  const Vec3 dHO = dH + m.p_WBcm.cross(mass * a_cm);
  const std::array<double, kBodyKinetics.size()> values = {
      v_P.x(),
      v_P.y(),
      v_P.z(),
      a_P.x(),
      a_P.y(),
      a_P.z(),
      0.5 * mass * m.v_WBcm_W.squaredNorm(),
      0.5 * w_B.dot(I * w_B),
      0.5 * mass * m.v_WBcm_W.squaredNorm() + 0.5 * w_B.dot(I * w_B),
      P.x(),
      P.y(),
      P.z(),
      H.x(),
      H.y(),
      H.z(),
      HO.x(),
      HO.y(),
      HO.z(),
      dH.x(),
      dH.y(),
      dH.z(),
      dHO.x(),
      dHO.y(),
      dHO.z()};
  return values[static_cast<size_t>(BodyKineticsIndex(q))];
}

}  // namespace

void CloseSegment(const Model& model, const State& state, LedgerCarry& carry) {
  const LedgerSample L = CalcLedgerSample(model, state, carry.segment_initial);
  carry.work_nc += L.work_nonconservative;
  carry.dissipated += L.dissipated;
  carry.residual += L.energy_residual;
  carry.scale = std::max(carry.scale, L.energy_scale);
  for (const ForceLedger& f : L.forces) carry.work_by_force[f.name] += f.work_nonconservative;
  for (const ConstraintLedger& f : L.constraints) carry.work_by_force[f.name] += f.work;
}

double ThetaTracker::Reference(int b, double omega, double t) const {
  const auto i = static_cast<size_t>(b);
  if (i >= track_.size() || !track_[i].started) return initial_[i];
  const Track& k = track_[i];
  return k.theta + 0.5 * (k.omega + omega) * (t - k.t);
}

double ThetaTracker::Advance(int b, const Mat3& R_WB, double omega, double t) {
  const double theta = UnwrapTheta(R_WB, Reference(b, omega, t));
  track_.resize(initial_.size());
  track_[static_cast<size_t>(b)] = {true, theta, omega, t};
  return theta;
}

double ThetaTracker::At(int b, const Mat3& R_WB, double omega, double t) const {
  return UnwrapTheta(R_WB, Reference(b, omega, t));
}

RowMaker::RowMaker(std::vector<StudyColumn> columns, ThetaTracker& theta)
    : columns_(std::move(columns)), theta_(theta) {
  for (const StudyColumn& c : columns_) {
    if (c.body >= 0 && BodyQuantityIndex(c.quantity) < 0 && BodyKineticsIndex(c.quantity) < 0) {
      throw InputError(
          fmt::format("output column '{}': unknown body quantity '{}'", c.name, c.quantity));
    }
    if ((c.body >= 0 && BodyColumnNeedsAccelerations(c.quantity)) || c.group == "reactions" ||
        c.group == "contacts") {
      needs_accelerations_ = true;
    }
  }
}

std::vector<double> RowMaker::Row(const Model& model, const BodyMap& map, const State& s,
                                  const LedgerCarry& carry, bool advance) {
  const LedgerSample L = CalcLedgerSample(model, s, carry.segment_initial);
  Data data;
  if (needs_accelerations_) {
    data = MakeData(model);
    CalcAccelerations(model, s, data);
  }
  if (theta_.active() && advance) {
    // θ of every body at every sample, so that it stays continuous whatever is printed.
    for (size_t b = 0; b < map.place.size(); ++b) {
      const MappedBodyMotion m = CalcMappedBodyMotion(model, s, map, static_cast<int>(b));
      theta_.Advance(static_cast<int>(b), m.R_WB, m.w_WB_W.z(), s.t);
    }
  }
  std::vector<double> row;
  row.reserve(columns_.size());
  for (const StudyColumn& c : columns_) {
    if (c.body >= 0 && BodyKineticsIndex(c.quantity) >= 0) {
      row.push_back(BodyKineticsValue(c, model, map, s, data));
      continue;
    }
    row.push_back(c.body >= 0 ? BodyValue(c, model, map, s, data)
                              : LedgerValue(c, model, s, L, carry, data));
  }
  return row;
}

double RowMaker::BodyValue(const StudyColumn& c, const Model& model, const BodyMap& map,
                           const State& s, const Data& data) const {
  const MappedBodyMotion m = CalcMappedBodyMotion(model, s, map, c.body);
  const std::string& q = c.quantity;
  const Vec3 w_B = m.R_WB.transpose() * m.w_WB_W;
  Vec3 a_W = Vec3::Zero(), al_W = Vec3::Zero();
  if (q[0] == 'a') {
    // a_P = a_Mcm + α × r + ω × (ω × r) for the user body's centre P of the model body M.
    const auto mb = static_cast<size_t>(map.place[static_cast<size_t>(c.body)].model_body);
    const BodyState& bs = s.bodies[mb];
    al_W = data.R_WB[mb] * data.wdot_WB_B[mb];
    const Vec3 r = m.p_WBcm - bs.p_WBcm;
    a_W = data.a_WBcm_W[mb] + al_W.cross(r) + m.w_WB_W.cross(m.w_WB_W.cross(r));
  }
  const Quat q_WB(m.R_WB);
  const Vec3 ypr = CalcYawPitchRoll(m.R_WB);
  const Vec3 al_B = m.R_WB.transpose() * al_W;
  // Quaternion sign: keep w >= 0 so that the printed components are continuous where they can
  // be and the same rotation always prints the same.
  const double sign = q_WB.w() < 0 ? -1.0 : 1.0;
  const double theta = q == "theta" ? theta_.At(c.body, m.R_WB, m.w_WB_W.z(), s.t) : 0.0;
  const std::array<double, kBodyQuantities.size()> values = {
      m.p_WBcm.x(),    m.p_WBcm.y(),
      m.p_WBcm.z(),    m.p_WBo.x(),
      m.p_WBo.y(),     m.p_WBo.z(),
      sign * q_WB.w(), sign * q_WB.x(),
      sign * q_WB.y(), sign * q_WB.z(),
      ypr.x(),         ypr.y(),
      ypr.z(),         std::acos(std::clamp(m.R_WB(2, 2), -1.0, 1.0)),
      m.v_WBcm_W.x(),  m.v_WBcm_W.y(),
      m.v_WBcm_W.z(),  m.v_WBcm_W.norm(),
      m.w_WB_W.x(),    m.w_WB_W.y(),
      m.w_WB_W.z(),    w_B.x(),
      w_B.y(),         w_B.z(),
      a_W.x(),         a_W.y(),
      a_W.z(),         al_W.x(),
      al_W.y(),        al_W.z(),
      al_B.x(),        al_B.y(),
      al_B.z(),        theta,
      m.w_WB_W.z(),    al_W.z()};
  return values[static_cast<size_t>(BodyQuantityIndex(q))];
}

double RowMaker::LedgerValue(const StudyColumn& c, const Model& model, const State& s,
                             const LedgerSample& L, const LedgerCarry& carry,
                             const Data& data) const {
  const std::string& q = c.quantity;
  if (c.group == "contacts") {
    const ContactPointOutput& o = data.contact_points[static_cast<size_t>(c.point)];
    if (q == "mode") return static_cast<double>(o.mode);
    if (q == "N") return o.normal_force;
    if (q == "f") return o.friction_force_W.norm();
    if (q == "slip") return o.slip_velocity_W.norm();
    return o.gap;
  }
  if (q == "W_friction" || q == "W_rolling" || q == "W_impacts") {
    // Running integrals the State carries since t = 0 (across every segment).
    double w = 0.0;
    for (const ContactPointState& p : s.contacts) {
      w +=
          q == "W_friction" ? p.friction_work : (q == "W_rolling" ? p.rolling_work : p.impact_work);
    }
    return w;
  }
  if (c.group == "reactions") {
    // Force (F) or moment about J (M) the parent exerts on the child, in W ("Fx"), in the
    // child's frame B ("Fx_B") or in the parent's frame P ("Fx_P": R_WPᵀ times W; W for a
    // joint to the world).
    const int ci = model.FindConstraint(c.force);
    const ConstraintOutput& r = data.constraints[static_cast<size_t>(ci)];
    const char frame = q.size() > 3 ? q[3] : 'W';
    const Vec3& v_W = q[0] == 'F' ? r.F_Jc_W : r.M_Jc_W;
    const BodyIndex parent = model.constraint(ci).parent();
    Vec3 v = v_W;
    if (frame == 'B') v = q[0] == 'F' ? r.F_Jc_B : r.M_Jc_B;
    if (frame == 'P' && parent != kWorld) {
      v = data.R_WB[static_cast<size_t>(parent)].transpose() * v_W;
    }
    return v[q[1] - 'x'];
  }
  if (q == "t") return s.t;
  if (q == "T_trans") return L.kinetic_translational;
  if (q == "T_rot") return L.kinetic_rotational;
  if (q == "T") return L.kinetic_translational + L.kinetic_rotational;
  if (q == "V") return L.potential;
  if (q == "E") return L.mechanical_energy;
  if (q == "W_nc") return carry.work_nc + L.work_nonconservative;
  if (q == "W") {
    double v = carry.work_by_force.count(c.force) ? carry.work_by_force.at(c.force) : 0.0;
    for (const ForceLedger& f : L.forces) {
      if (f.name == c.force) v += f.work_nonconservative;
    }
    for (const ConstraintLedger& f : L.constraints) {
      if (f.name == c.force) v += f.work;
    }
    return v;
  }
  if (q == "dissipated") return carry.dissipated + L.dissipated;
  if (q == "jumps") return carry.jumps;
  if (q == "residual") return carry.residual + L.energy_residual;
  if (q[0] == 'P') return L.linear_momentum_W[q[1] - 'x'];
  if (q[0] == 'H' && q[1] == 'O') return L.angular_momentum_Wo_W[q[2] - 'x'];
  if (q[0] == 'H') return L.angular_momentum_Scm_W[q[1] - 'x'];
  throw InputError(fmt::format("output column '{}': unknown quantity '{}'", c.name, q));
}

StudySnapshot MakeSnapshot(const Model& model, const State& state, int num_reported_constraints,
                           const std::vector<std::string>& labels, ThetaTracker& theta,
                           bool advance) {
  StudySnapshot out;
  const int reported = num_reported_constraints < 0
                           ? model.num_constraints()
                           : std::min(num_reported_constraints, model.num_constraints());
  if (model.num_constraints() > 0 || model.num_force_elements() > 0) {
    // The reactions at `state` (the constraint stage of CalcAccelerations), and each force
    // element's forces again, listed this time (into a scratch copy of the resultants).
    Data data = MakeData(model);
    CalcAccelerations(model, state, data);
    for (int i = 0; i < reported; ++i) out.reactions.push_back(MakeReactionReport(model, data, i));
    Data scratch = data;
    WrenchAccumulator acc(state, scratch);
    std::vector<AppliedForceRecord> records;
    acc.Record(&records);
    for (int e = 0; e < model.num_force_elements(); ++e) {
      ForceElementOutput element_out;
      acc.Begin(&element_out);
      records.clear();
      const ForceElement& fe = model.force_element(e);
      fe.AddForces(model, state, scratch, acc);
      for (const AppliedForceRecord& r : records) {
        out.forces.push_back(
            {fe.name(), model.body(r.body).name(), r.p_WP, r.F_W, r.M_W, r.is_moment});
      }
    }
  }
  if (model.num_contacts() > 0) {
    const std::vector<ContactPointOutput> outputs = CalcContactOutputs(model, state);
    for (int p = 0; p < model.num_contact_points(); ++p) {
      const auto i = static_cast<size_t>(p);
      const ContactPointOutput& o = outputs[i];
      const ContactPointState& ps = state.contacts[i];
      out.contacts.push_back({i < labels.size() ? labels[i] : model.contact_point_name(p),
                              StudyContactMode{ps.mode, ps.rolling_held}, o.p_WC, o.n_W,
                              o.normal_force, o.friction_force_W, o.slip_velocity_W, o.gap,
                              ps.friction_work, ps.rolling_work, ps.impact_work,
                              o.rolling_moment_W});
    }
  }
  for (int b = 0; b < model.num_bodies(); ++b) {
    const BodyState& s = state.bodies[static_cast<size_t>(b)];
    StudyBodyState f;
    f.name = model.body(b).name();
    f.mass = model.body(b).mass();
    f.inertia_max = model.body(b).I_BBcm_B().diagonal().maxCoeff();
    f.p_WBcm = s.p_WBcm;
    f.p_WBo = CalcBodyOriginPosition(model, state, b);
    f.q_WB = s.q_WB.w() < 0 ? Quat(-s.q_WB.coeffs()) : s.q_WB;
    f.v_WBcm_W = s.v_WBcm_W;
    f.w_WB_B = s.w_WB_B;
    f.w_WB_W = s.q_WB * s.w_WB_B;
    if (theta.active()) {
      // Planar runs map user bodies one to one onto Model bodies (no embedding).
      const Mat3 R = s.q_WB.toRotationMatrix();
      f.theta = advance ? theta.Advance(b, R, f.w_WB_W.z(), state.t)
                        : theta.At(b, R, f.w_WB_W.z(), state.t);
    }
    out.bodies.push_back(f);
  }
  return out;
}

std::vector<StudyBodyPose> CalcUserBodyPoses(const Model& model, const State& state,
                                             const BodyMap& map) {
  std::vector<StudyBodyPose> poses;
  poses.reserve(map.place.size());
  for (size_t b = 0; b < map.place.size(); ++b) {
    const MappedBodyMotion m = CalcMappedBodyMotion(model, state, map, static_cast<int>(b));
    // The quaternion of R_WB as BodyValue makes it for the columns, so that a row's pose and
    // its origin and quaternion columns are the same doubles.
    const Quat q_WB(m.R_WB);
    poses.push_back({m.p_WBo, q_WB.w() < 0 ? Quat(-q_WB.coeffs()) : q_WB});
  }
  return poses;
}

SlipWatch::SlipWatch(std::vector<RollingWatch> watched) {
  for (RollingWatch& w : watched) entries_.push_back({std::move(w)});
}

void SlipWatch::Sample(const Model& model, const State& s) {
  if (entries_.empty() || model.num_constraints() == 0) return;
  Data data = MakeData(model);
  CalcAccelerations(model, s, data);
  for (Entry& e : entries_) {
    // The multipliers are N (row 0) and the friction components along the plane's tangents
    // t1, t2 (rows 1, 2); the plane may turn with its body.
    const ConstraintEval::Column& lambda =
        data.constraints[static_cast<size_t>(e.watch.constraint)].lambda;
    const double N = lambda[0];
    if (!(N > 0)) {
      if (!e.lifts) e.lifts = true, e.t_lift = s.t;
      continue;
    }
    const double ratio = std::hypot(lambda[1], lambda[2]) / N;
    if (ratio > e.worst) e.worst = ratio, e.t_worst = s.t;
  }
}

void SlipWatch::Report(std::vector<std::string>& notes) const {
  for (const Entry& e : entries_) {
    if (e.lifts) {
      notes.push_back(
          fmt::format("rolling contact '{}': the plane would have to pull (N <= 0) at t = {:.6g} "
                      "s: the body would lift off",
                      e.watch.name, e.t_lift));
    }
    if (e.worst > e.watch.mu_s) {
      notes.push_back(
          fmt::format("rolling contact '{}' needs f/N = {:.6g} at t = {:.6g} s, more than mu_s "
                      "= {:.6g}: the body would slip (the simulation holds it rolling)",
                      e.watch.name, e.worst, e.t_worst, e.watch.mu_s));
    }
  }
}

}  // namespace study_internal

}  // namespace chasles
