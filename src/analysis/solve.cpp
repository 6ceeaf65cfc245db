// The instantaneous problem of a Model at a state (chasles/analysis/solve.h).

#include "chasles/analysis/solve.h"

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "chasles/analysis/certificate.h"
#include "chasles/analysis/instantaneous.h"
#include "chasles/analysis/momentum.h"
#include "chasles/dynamics/constraint_solve.h"
#include "chasles/dynamics/contact_solve.h"
#include "chasles/error.h"
#include "chasles/model/data.h"

namespace chasles {

namespace {

std::vector<BodyMotionReport> CalcMotion(const SolveDefinition& def, const Model& model,
                                         const State& state, const InstantaneousSolution& solved,
                                         BodyMotionReport* total) {
  std::vector<BodyMotionReport> out;
  Vec3 M_a = Vec3::Zero();  // Σ m a_cm [N]
  for (int b = 0; b < model.num_bodies(); ++b) {
    const auto i = static_cast<size_t>(b);
    const BodyState& x = state.bodies[i];
    const Body& body = model.body(b);
    const BodyAccelerationReport& acc = solved.bodies[i];
    BodyMotionReport m;
    m.name = body.name();
    m.T_trans = 0.5 * body.mass() * x.v_WBcm_W.squaredNorm();
    m.T_rot = 0.5 * x.w_WB_B.dot(body.I_BBcm_B() * x.w_WB_B);
    m.P = body.mass() * x.v_WBcm_W;
    m.H_cm = x.q_WB * Vec3(body.I_BBcm_B() * x.w_WB_B);
    m.H_O = m.H_cm + x.p_WBcm.cross(m.P);
    m.w_WB_W = x.q_WB * x.w_WB_B;
    m.v_WBcm_W = x.v_WBcm_W;
    // dH_cm/dt = R (I α_B + ω_B × I ω_B): the left side of Euler's equations (eqs. 8.75-8.81),
    // in body axes where I is constant, expressed in W. dH_O/dt = dH_cm/dt + r_cm × m a_cm
    // (H_O = H_cm + r_cm × m v_cm; d/dt of the second term is v_cm × m v_cm + r_cm × m a_cm).
    const Vec3 Hdot_B =
        body.I_BBcm_B() * acc.alpha_WB_B + x.w_WB_B.cross(Vec3(body.I_BBcm_B() * x.w_WB_B));
    m.Hdot_cm = x.q_WB * Hdot_B;
    m.Hdot_O = m.Hdot_cm + x.p_WBcm.cross(body.mass() * acc.a_WBcm_W);
    // The body's named points. r from the centre of mass to P, in W:
    //   v_P = v_cm + ω × r,  a_P = a_cm + α × r + ω × (ω × r).
    if (i < def.points.size()) {
      for (const NamedBodyPoint& p : def.points[i]) {
        const Vec3 r = x.q_WB * body.PointFromCenterOfMass(p.p_BoP_B);
        PointMotionReport pm;
        pm.name = p.name;
        pm.p_WP = x.p_WBcm + r;
        pm.v_WP_W = x.v_WBcm_W + m.w_WB_W.cross(r);
        pm.a_WP_W = acc.a_WBcm_W + acc.alpha_WB_W.cross(r) + m.w_WB_W.cross(m.w_WB_W.cross(r));
        m.points.push_back(pm);
      }
    }
    total->Hdot_O += m.Hdot_O;
    M_a += body.mass() * acc.a_WBcm_W;
    out.push_back(m);
  }
  total->T_trans = CalcTranslationalKineticEnergy(model, state);
  total->T_rot = CalcRotationalKineticEnergy(model, state);
  total->P = CalcLinearMomentum(model, state);
  const Vec3 p_WScm = CalcSystemCenterOfMass(model, state);
  total->H_cm = CalcAngularMomentum(model, state, p_WScm);
  total->H_O = CalcAngularMomentum(model, state, Vec3::Zero());
  // About the system's centre of mass S: H_O = H_S + r_S × P with P = M v_S, so
  // dH_S/dt = dH_O/dt - r_S × Σ m a (the term v_S × M v_S vanishes).
  total->Hdot_cm = total->Hdot_O - p_WScm.cross(M_a);
  return out;
}

std::vector<ContactPointReport> ContactReports(const SolveDefinition& def, const Model& model,
                                               const State& state) {
  std::vector<ContactPointReport> reports;
  const std::vector<ContactPointOutput> outputs = CalcContactOutputs(model, state);
  for (int p = 0; p < model.num_contact_points(); ++p) {
    const int c = model.contact_of_point(p);
    const Contact& con = model.contact(c);
    ContactPointReport r;
    r.point = static_cast<size_t>(p) < def.contact_point_labels.size()
                  ? def.contact_point_labels[static_cast<size_t>(p)]
                  : model.contact_point_name(p);
    r.contact = con.name();
    r.out = outputs[static_cast<size_t>(p)];
    r.mu_s = con.mu_s();
    r.mu_k = con.mu_k();
    r.mu_r = con.mu_r();
    r.round = con.feature(p - model.contact_point_offset(c)).kind != ContactFeatureKind::kPoint;
    reports.push_back(std::move(r));
  }
  return reports;
}

}  // namespace

namespace {
SolveReport SolveUnlocated(const SolveDefinition& definition);
}  // namespace

SolveReport SolveAtState(const SolveDefinition& definition) {
  try {
    return SolveUnlocated(definition);
  } catch (const InputError& e) {
    if (!definition.locate_error) throw;
    definition.locate_error(e);
    throw;  // a locator that returns leaves the error as it is
  }
}

namespace {

SolveReport SolveUnlocated(const SolveDefinition& definition) {
  if (!definition.model) throw InputError("a solve needs its Model (SolveDefinition::model)");
  const Model& model = *definition.model;
  std::vector<std::string> warnings = definition.warnings;
  State state = definition.settle_initial ? SettleInitialState(model, definition.initial,
                                                               *definition.settle_initial, warnings)
                                          : definition.initial;
  Data data = MakeData(model);
  ProjectOntoConstraints(model, state, data);
  if (model.num_contacts() > 0) {
    // The modes at the initial state, chosen as a simulation starts (docs/contact.md, "Mode
    // selection"): the LCP on the normal forces decides which points press, the friction
    // check which of those stick; the accelerations and reactions below are in those modes.
    // Impacts are not applied: a solve reports the state as given.
    state.contacts.assign(static_cast<size_t>(model.num_contact_points()), ContactPointState{});
    SelectContactModes(model, state);
  }
  SolveReport s;
  s.solution = SolveInstantaneous(model, state);
  s.planar = definition.planar;
  s.solution.warnings.insert(s.solution.warnings.begin(), warnings.begin(), warnings.end());
  CertificateBuilder certificate;
  certificate.CheckState(model, state, CheckPhase::kSolve);
  s.certificate = certificate.Finish();
  s.motion = CalcMotion(definition, model, state, s.solution, &s.total);
  // A planar scene's plane constraints follow its own in Model order; their out-of-plane
  // reactions are not physical for a planar body and are not reported.
  s.solution.reactions.resize(definition.mu_s.size());
  s.mu_s = definition.mu_s;
  if (model.num_contacts() > 0) s.contacts = ContactReports(definition, model, state);
  return s;
}

}  // namespace

SweepTable SolveSweep(const std::string& name, const std::string& unit, int count,
                      const std::function<SolveSweepPoint(int k)>& point,
                      const SolveSweepOptions& options) {
  SweepTable table;
  table.parameter = name;
  for (int k = 0; k < count; ++k) {
    if (!options.share.Has(k)) {
      table.rows.emplace_back();
      continue;
    }
    if (options.progress) options.progress(k, count);
    const SolveSweepPoint p = point(k);
    const SolveReport s = SolveAtState(p.definition);
    if (options.on_solution) options.on_solution(k, p.value, s);
    for (const std::string& w : s.certificate.FailureMessages()) {
      table.warnings.push_back(fmt::format("{} = {:.12g}: {}", name, p.value, w));
      table.failed = true;
    }
    std::vector<double> row = {p.value};
    if (k == 0) {
      table.columns.push_back(name);
      table.units.push_back(unit);
      SolutionTableRow(s, &table.columns, &table.units, &row);
    } else {
      SolutionTableRow(s, nullptr, nullptr, &row);
    }
    table.rows.push_back(std::move(row));
  }
  return table;
}

}  // namespace chasles
