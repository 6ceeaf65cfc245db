// The instantaneous problem of a scene and its sweep (chasles/scene/solve.h).

#include "chasles/scene/solve.h"

#include <algorithm>
#include <cctype>
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

std::vector<BodyMotionReport> CalcMotion(const Scene& scene, const Model& model, const State& state,
                                         const InstantaneousSolution& solved,
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
    // The body's named points (a scene body is Model body b, frames alike: BuildStudy starts
    // from the identity map). r from the centre of mass to P, in W:
    //   v_P = v_cm + ω × r,  a_P = a_cm + α × r + ω × (ω × r).
    if (i < scene.bodies.size()) {
      for (const ScenePoint& p : scene.bodies[i].points) {
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
    r.mu_r = con.mu_r();
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
    // The scene's own warnings (version-1 spellings, mesh repairs) come first, then the
    // initial values the projection changed (`project_initial: true`).
    s.solution.warnings.insert(s.solution.warnings.begin(), study.warnings.begin(),
                               study.warnings.end());
    s.solution.warnings.insert(s.solution.warnings.begin(), scene.warnings.begin(),
                               scene.warnings.end());
    CertificateBuilder certificate;
    certificate.CheckState(model, state, CheckPhase::kSolve);
    s.certificate = certificate.Finish();
    s.motion = CalcMotion(scene, model, state, s.solution, &s.total);
    FillMuS(scene, s);
    if (model.num_contacts() > 0) s.contacts = ContactReports(scene, model, state);
    return s;
  } catch (const InputError& e) {
    ThrowAtSceneEntry(scene, e);
  }
}

std::string SweepParameterUnit(const SweepSpec& spec, const Dimension& dim) {
  // An identifier of START or STOP that names an angle unit marks the parameter as an angle
  // (the Dimension alone cannot: an angle is a pure number).
  bool angle = false;
  for (const std::string* text : {&spec.start, &spec.stop}) {
    std::string word;
    for (size_t i = 0; i <= text->size(); ++i) {
      const char c = i < text->size() ? (*text)[i] : ' ';
      if (std::isalnum(static_cast<unsigned char>(c)) || c == '_') {
        word += c;
        continue;
      }
      angle = angle || word == "rad" || word == "deg" || word == "rev" || word == "rpm" ||
              word == "cps";
      word.clear();
    }
  }
  return UnitSystem().FormatUnit(dim, angle ? Angular::kYes : Angular::kNo);
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
      if (n == spec.name) parameter_unit = SweepParameterUnit(spec, q.dim);
    }
    if (std::find(known.begin(), known.end(), spec.name) == known.end()) {
      throw SceneError(spec.source, 0, 0, spec.key,
                       fmt::format("the scene has no parameter '{}'{}; parameters: {}", spec.name,
                                   DidYouMean(spec.name, known), fmt::join(known, ", ")));
    }
  }
  for (int k = 0; k < spec.count; ++k) {
    if (!sweep_options.share.Has(k)) {
      table.rows.emplace_back();
      continue;
    }
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
    if (sweep_options.on_solution) sweep_options.on_solution(k, value, s);
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
