// The instantaneous problem of a scene and its sweep (chasles/scene/solve.h).

#include "chasles/scene/solve.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "chasles/analysis/momentum.h"
#include "chasles/dynamics/constraint_solve.h"
#include "chasles/dynamics/contact_solve.h"
#include "chasles/error.h"
#include "chasles/model/data.h"
#include "chasles/model/model.h"
#include "chasles/scene/scene_error.h"
#include "chasles/scene/study.h"
#include "chasles/suggest.h"

namespace chasles {

namespace {

void FillMuS(const Scene& scene, SolveReport& s) {
  const SceneConstraints& c = scene.dynamics.constraints;
  // A planar scene's plane constraints follow its own in Model order; their out-of-plane
  // reactions are not physical for a planar body and are not reported.
  s.solution.reactions.resize(c.names().size());
  s.mu_s.assign(s.solution.reactions.size(), std::numeric_limits<double>::quiet_NaN());
  for (size_t i = 0; i < c.rolling.size(); ++i) s.mu_s[c.joints.size() + i] = c.rolling[i].mu_s;
}

std::vector<BodyMotionReport> CalcMotion(const Model& model, const State& state,
                                         BodyMotionReport* total) {
  std::vector<BodyMotionReport> out;
  for (int b = 0; b < model.num_bodies(); ++b) {
    const BodyState& x = state.bodies[static_cast<size_t>(b)];
    const Body& body = model.body(b);
    BodyMotionReport m;
    m.name = body.name();
    m.T_trans = 0.5 * body.mass() * x.v_WBcm_W.squaredNorm();
    m.T_rot = 0.5 * x.w_WB_B.dot(body.I_BBcm_B() * x.w_WB_B);
    m.P = body.mass() * x.v_WBcm_W;
    m.H_cm = x.q_WB * Vec3(body.I_BBcm_B() * x.w_WB_B);
    m.H_O = m.H_cm + x.p_WBcm.cross(m.P);
    out.push_back(m);
  }
  total->T_trans = CalcTranslationalKineticEnergy(model, state);
  total->T_rot = CalcRotationalKineticEnergy(model, state);
  total->P = CalcLinearMomentum(model, state);
  total->H_cm = CalcAngularMomentum(model, state, CalcSystemCenterOfMass(model, state));
  total->H_O = CalcAngularMomentum(model, state, Vec3::Zero());
  return out;
}

std::vector<ContactPointReport> ContactReports(const Scene& scene, const Model& model,
                                               const State& state) {
  std::vector<ContactPointReport> reports;
  const std::vector<ContactPointOutput> outputs = CalcContactOutputs(model, state);
  const std::vector<std::string> labels = scene.dynamics.contacts.point_labels();
  for (int p = 0; p < model.num_contact_points(); ++p) {
    const int c = model.contact_of_point(p);
    const Contact& con = model.contact(c);
    ContactPointReport r;
    r.point = labels[static_cast<size_t>(p)];
    r.contact = con.name();
    r.out = outputs[static_cast<size_t>(p)];
    r.mu_s = con.mu_s();
    r.mu_k = con.mu_k();
    r.round = con.feature(p - model.contact_point_offset(c)).kind != ContactFeatureKind::kPoint;
    reports.push_back(std::move(r));
  }
  return reports;
}

}  // namespace

SolveReport SolveScene(const Scene& scene) {
  try {
    // The end time plays no part in an instantaneous solve.
    Study study = BuildStudy(scene, 1.0);
    State state = study.initial;
    const Model& model = *study.model;
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
    s.planar = scene.planar;
    // Initial values the projection changed (`project_initial: true`) come first.
    s.solution.warnings.insert(s.solution.warnings.begin(), study.warnings.begin(),
                               study.warnings.end());
    CertificateBuilder certificate;
    certificate.CheckState(model, state, CheckPhase::kSolve);
    s.certificate = certificate.Finish();
    s.motion = CalcMotion(model, state, &s.total);
    FillMuS(scene, s);
    if (model.num_contacts() > 0) s.contacts = ContactReports(scene, model, state);
    return s;
  } catch (const InputError& e) {
    ThrowAtSceneEntry(scene, e);
  }
}

SweepSpec ParseSweep(const std::string& text, const std::string& source, const std::string& key) {
  const auto fail = [&](const std::string& why) { throw SceneError(source, 0, 0, key, why); };
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) {
    fail("expected NAME=START:STOP:COUNT, e.g. --sweep 'theta=0 deg:60 deg:7', got '" + text + "'");
  }
  SweepSpec s;
  s.source = source;
  s.key = key;
  s.name = text.substr(0, eq);
  const std::string rest = text.substr(eq + 1);
  const auto c1 = rest.find(':');
  const auto c2 = c1 == std::string::npos ? c1 : rest.find(':', c1 + 1);
  if (c2 == std::string::npos || rest.find(':', c2 + 1) != std::string::npos) {
    fail("expected NAME=START:STOP:COUNT (three fields after '='), got '" + text + "'");
  }
  s.start = rest.substr(0, c1);
  s.stop = rest.substr(c1 + 1, c2 - c1 - 1);
  const std::string count = rest.substr(c2 + 1);
  try {
    size_t used = 0;
    s.count = std::stoi(count, &used);
    if (used != count.size()) s.count = 0;
  } catch (const std::exception&) {
    s.count = 0;
  }
  if (s.count < 2) fail("COUNT must be a whole number >= 2, got '" + count + "'");
  return s;
}

SweepTable SolveSweep(const std::function<Scene(const SceneOptions&)>& load,
                      const SceneOptions& options, const SweepSpec& spec,
                      const SweepOptions& sweep_options) {
  if (spec.count < 2) {
    throw SceneError(spec.source, 0, 0, spec.key,
                     fmt::format("COUNT must be a whole number >= 2, got {}", spec.count));
  }
  SweepTable table;
  table.parameter = spec.name;
  std::string parameter_unit;
  {
    const Scene scene = load(options);
    std::vector<std::string> known;
    for (const auto& [n, q] : scene.parameters) {
      known.push_back(n);
      if (n == spec.name) parameter_unit = UnitSystem::Parse("SI").FormatUnit(q.dim);
    }
    if (std::find(known.begin(), known.end(), spec.name) == known.end()) {
      throw SceneError(spec.source, 0, 0, spec.key,
                       fmt::format("the scene has no parameter '{}'{}; parameters: {}", spec.name,
                                   DidYouMean(spec.name, known), fmt::join(known, ", ")));
    }
  }
  for (int k = 0; k < spec.count; ++k) {
    if (sweep_options.progress) sweep_options.progress(k, spec.count);
    // The k-th value as an expression, so START and STOP keep their units.
    SceneOptions o = options;
    o.parameter_overrides.emplace_back(
        spec.name, fmt::format("({}) + (({}) - ({})) * {} / {}", spec.start, spec.stop, spec.start,
                               k, spec.count - 1));
    const Scene scene = load(o);
    double value = std::numeric_limits<double>::quiet_NaN();
    for (const auto& [n, q] : scene.parameters) {
      if (n == spec.name) value = q.value;
    }
    const SolveReport s = SolveScene(scene);
    if (sweep_options.on_solution) sweep_options.on_solution(value, s);
    for (const std::string& w : s.certificate.FailureMessages()) {
      table.warnings.push_back(fmt::format("{} = {:.12g}: {}", spec.name, value, w));
      table.failed = true;
    }
    std::vector<double> row = {value};
    if (k == 0) {
      table.columns.push_back(spec.name);
      table.units.push_back(parameter_unit);
      SolutionTableRow(s, &table.columns, &table.units, &row);
    } else {
      SolutionTableRow(s, nullptr, nullptr, &row);
    }
    table.rows.push_back(std::move(row));
  }
  return table;
}

}  // namespace chasles
