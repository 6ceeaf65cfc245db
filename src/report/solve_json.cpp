// What `chasles solve` prints (chasles/report/solve_json.h).

#include "chasles/report/solve_json.h"

#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "chasles/model/contact.h"
#include "chasles/report/certificate_json.h"
#include "chasles/report/json_report.h"
#include "chasles/report/result_names.h"

namespace chasles {

nlohmann::json SolveJson(const SolveReport& s) {
  nlohmann::json j;
  j["t"] = s.solution.t;
  j["bodies"] = nlohmann::json::array();
  for (const auto& b : s.solution.bodies) {
    j["bodies"].push_back({{"name", b.name},
                           {"acceleration", VecJson(b.a_WBcm_W)},
                           {"angular_acceleration", VecJson(b.alpha_WB_W)},
                           {"angular_acceleration_body", VecJson(b.alpha_WB_B)}});
    if (s.planar) {
      // Chapter eqs. 8.41-8.43: a_x, a_y of the centre of mass and alpha about z.
      j["bodies"].back()["planar"] = {
          {"a_x", b.a_WBcm_W.x()}, {"a_y", b.a_WBcm_W.y()}, {"alpha", b.alpha_WB_W.z()}};
    }
  }
  j["reactions"] = nlohmann::json::array();
  for (size_t i = 0; i < s.solution.reactions.size(); ++i) {
    const ReactionReport& r = s.solution.reactions[i];
    nlohmann::json x = {{"name", r.name},
                        {"kind", r.kind},
                        {"point", VecJson(r.p_WJ)},
                        {"force", VecJson(r.F_Jc_W)},
                        {"moment", VecJson(r.M_Jc_W)},
                        {"force_body", VecJson(r.F_Jc_B)},
                        {"moment_body", VecJson(r.M_Jc_B)},
                        {"force_parent", VecJson(r.F_Jc_P)},
                        {"moment_parent", VecJson(r.M_Jc_P)},
                        {"multipliers", r.lambda},
                        {"power", r.power}};
    if (s.planar) {
      x["planar"] = {{"Fx", r.F_Jc_W.x()}, {"Fy", r.F_Jc_W.y()}, {"Mz", r.M_Jc_W.z()}};
    }
    if (r.mode) {
      x["mode"] = StringModeName(*r.mode);
      x["tension"] = r.lambda[0];
      x["slack"] = r.gap;
    }
    if (r.is_rolling) {
      x["normal_force"] = r.normal_force;
      x["friction"] = VecJson(r.friction_W);
      x["friction_magnitude"] = r.friction_W.norm();
      x["friction_needed"] = r.friction_needed;
      if (!std::isnan(s.mu_s[i])) {
        x["mu_s"] = s.mu_s[i];
        x["rolls"] = r.friction_needed <= s.mu_s[i];
      }
    }
    j["reactions"].push_back(x);
  }
  const auto motion = [](const BodyMotionReport& m) {
    return nlohmann::json{
        {"kinetic_energy", m.T_trans + m.T_rot},  {"kinetic_translational", m.T_trans},
        {"kinetic_rotational", m.T_rot},          {"linear_momentum", VecJson(m.P)},
        {"angular_momentum_cm", VecJson(m.H_cm)}, {"angular_momentum_origin", VecJson(m.H_O)}};
  };
  j["energy_momentum"] = {{"bodies", nlohmann::json::array()}, {"total", motion(s.total)}};
  j["energy_momentum"]["total"]["angular_momentum_rate_cm"] = VecJson(s.total.Hdot_cm);
  j["energy_momentum"]["total"]["angular_momentum_rate_origin"] = VecJson(s.total.Hdot_O);
  for (const BodyMotionReport& m : s.motion) {
    nlohmann::json b = motion(m);
    b["name"] = m.name;
    b["angular_momentum_rate_cm"] = VecJson(m.Hdot_cm);
    b["angular_momentum_rate_origin"] = VecJson(m.Hdot_O);
    j["energy_momentum"]["bodies"].push_back(b);
  }
  // Per body: ω and v_cm at the solved state, each named point's position, velocity and
  // acceleration, and dH/dt about the centre of mass and about O (SolveReport's motion).
  j["kinematics"] = nlohmann::json::array();
  for (size_t i = 0; i < s.motion.size(); ++i) {
    const BodyMotionReport& m = s.motion[i];
    nlohmann::json b = {{"name", m.name},
                        {"angular_velocity", VecJson(m.w_WB_W)},
                        {"velocity", VecJson(m.v_WBcm_W)},
                        {"angular_momentum_rate_cm", VecJson(m.Hdot_cm)},
                        {"angular_momentum_rate_origin", VecJson(m.Hdot_O)},
                        {"points", nlohmann::json::array()}};
    if (i < s.solution.bodies.size()) {
      b["acceleration"] = VecJson(s.solution.bodies[i].a_WBcm_W);
      b["angular_acceleration"] = VecJson(s.solution.bodies[i].alpha_WB_W);
    }
    for (const PointMotionReport& p : m.points) {
      b["points"].push_back({{"name", p.name},
                             {"position", VecJson(p.p_WP)},
                             {"velocity", VecJson(p.v_WP_W)},
                             {"acceleration", VecJson(p.a_WP_W)}});
    }
    j["kinematics"].push_back(b);
  }
  j["contacts"] = nlohmann::json::array();
  for (const ContactPointReport& c : s.contacts) {
    j["contacts"].push_back({{"point", c.point},
                             {"contact", c.contact},
                             {"mode", ContactModeName(c.out.mode)},
                             {"regime", c.Regime()},
                             {"normal_force", c.out.normal_force},
                             {"friction", VecJson(c.out.friction_force_W)},
                             {"friction_magnitude", c.out.friction_force_W.norm()},
                             {"friction_needed", c.FrictionRatio()},
                             {"mu_s", c.mu_s},
                             {"mu_k", c.mu_k},
                             {"mu_r", c.mu_r},
                             {"rolling_held", c.out.rolling_held},
                             {"rolling_moment", VecJson(c.out.rolling_moment_W)},
                             {"rolling_moment_capacity", c.out.rolling_moment_capacity},
                             {"slip_velocity", VecJson(c.out.slip_velocity_W)},
                             {"gap", c.out.gap},
                             {"point_W", VecJson(c.out.p_WC)},
                             {"normal_W", VecJson(c.out.n_W)}});
  }
  j["planar"] = s.planar;
  j["rank"] = s.solution.rank;
  j["rows"] = s.solution.num_rows;
  j["warnings"] = s.solution.warnings;
  for (const std::string& w : s.certificate.FailureMessages()) j["warnings"].push_back(w);
  j["checks"] = CertificateJson(s.certificate);
  return j;
}

nlohmann::json SweepJson(const SweepTable& table) {
  nlohmann::json j = {{"parameter", table.parameter},
                      {"units", "SI"},
                      {"columns", table.columns},
                      {"column_units", table.units}};
  if (!table.parameters.empty()) j["parameters"] = table.parameters;
  if (table.errors.empty()) {
    j["rows"] = table.rows;
    return j;
  }
  // A failed run's values are null, never a silent NaN; "errors" says why (null when it ran).
  j["rows"] = nlohmann::json::array();
  j["errors"] = nlohmann::json::array();
  for (size_t r = 0; r < table.rows.size(); ++r) {
    nlohmann::json row = nlohmann::json::array();
    for (const double v : table.rows[r]) {
      row.push_back(std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr));
    }
    j["rows"].push_back(std::move(row));
    const std::string& e = r < table.errors.size() ? table.errors[r] : std::string();
    j["errors"].push_back(e.empty() ? nlohmann::json(nullptr) : nlohmann::json(e));
  }
  return j;
}

std::string SweepCsv(const SweepTable& table, CsvPrecision precision) {
  return CsvText({table.columns, table.units, table.rows, table.errors},
                 precision == CsvPrecision::kFull ? 17 : 12, "the sweep table");
}

std::string SolveCsv(const SolveReport& report, CsvPrecision precision) {
  CsvTable t;
  t.rows.emplace_back();
  SolutionTableRow(report, &t.columns, &t.units, &t.rows.back());
  return CsvText(t, precision == CsvPrecision::kFull ? 17 : 12, "the solve table");
}

}  // namespace chasles
