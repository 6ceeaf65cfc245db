// What an instantaneous solve reports, and a sweep table's row (chasles/analysis/solve_report.h).

#include "chasles/analysis/solve_report.h"

#include <string>
#include <vector>

namespace chasles {

std::string ContactPointReport::Regime() const {
  switch (out.mode) {
    case ContactMode::kSticking:
      if (out.rolling_held) return "rolling held";
      return round ? "rolls" : "sticks";
    case ContactMode::kSliding:
      return "slides";
    case ContactMode::kSeparated:
      break;
  }
  return "separated";
}

double ContactPointReport::FrictionRatio() const {
  if (out.mode == ContactMode::kSticking) return out.friction_needed;
  if (out.mode == ContactMode::kSliding && out.normal_force > 0) {
    return out.friction_force_W.norm() / out.normal_force;
  }
  return 0.0;
}

void SolutionTableRow(const SolveReport& s, std::vector<std::string>* names,
                      std::vector<std::string>* units, std::vector<double>* values) {
  auto add = [&](const std::string& name, const char* unit, double v) {
    if (names) names->push_back(name);
    if (units) units->push_back(unit);
    if (values) values->push_back(v);
  };
  const char* xyz[] = {"x", "y", "z"};
  if (s.planar) {
    for (const auto& b : s.solution.bodies) {
      add(b.name + "_ax", "m/s^2", b.a_WBcm_W.x());
      add(b.name + "_ay", "m/s^2", b.a_WBcm_W.y());
      add(b.name + "_alpha", "rad/s^2", b.alpha_WB_W.z());
    }
  }
  for (const auto& b : s.solution.bodies) {
    if (s.planar) break;
    for (int k = 0; k < 3; ++k) add(b.name + "_a" + xyz[k], "m/s^2", b.a_WBcm_W[k]);
    for (int k = 0; k < 3; ++k) add(b.name + "_al" + xyz[k], "rad/s^2", b.alpha_WB_W[k]);
  }
  // Velocities, the named points' velocities and accelerations, and dH/dt (about the centre of
  // mass "dH", about O "dHO"); planar: x and y of vectors in the plane, z of ω and dH/dt.
  const std::vector<int> in_plane = s.planar ? std::vector<int>{0, 1} : std::vector<int>{0, 1, 2};
  const std::vector<int> normal = s.planar ? std::vector<int>{2} : std::vector<int>{0, 1, 2};
  for (const BodyMotionReport& m : s.motion) {
    for (int k : in_plane) add(m.name + "_v" + xyz[k], "m/s", m.v_WBcm_W[k]);
    for (int k : normal)
      add(m.name + (s.planar ? "_omega" : std::string("_w") + xyz[k]), "rad/s", m.w_WB_W[k]);
    for (const PointMotionReport& p : m.points) {
      for (int k : in_plane) add(m.name + "_" + p.name + "_v" + xyz[k], "m/s", p.v_WP_W[k]);
      for (int k : in_plane) add(m.name + "_" + p.name + "_a" + xyz[k], "m/s^2", p.a_WP_W[k]);
    }
    for (int k : normal) add(m.name + "_dH" + xyz[k], "N*m", m.Hdot_cm[k]);
    for (int k : normal) add(m.name + "_dHO" + xyz[k], "N*m", m.Hdot_O[k]);
  }
  // Energy and momenta as the simulation's ledger columns names them: per body with the body's
  // name first, H about its centre of mass, HO about the origin; then the totals (H about the
  // system's centre of mass).
  const auto motion = [&](const std::string& prefix, const BodyMotionReport& m) {
    add(prefix + "T_trans", "J", m.T_trans);
    add(prefix + "T_rot", "J", m.T_rot);
    add(prefix + "T", "J", m.T_trans + m.T_rot);
    // Planar: P in the plane, H about z (eqs. 8.34-8.38); the rest is zero by construction.
    for (int k : in_plane) add(prefix + "P" + xyz[k], "kg*m/s", m.P[k]);
    for (int k : normal) add(prefix + "H" + xyz[k], "kg*m^2/s", m.H_cm[k]);
    for (int k : normal) add(prefix + "HO" + xyz[k], "kg*m^2/s", m.H_O[k]);
  };
  for (const BodyMotionReport& m : s.motion) motion(m.name + "_", m);
  motion("", s.total);
  for (int k : normal) add(std::string("dH") + xyz[k], "N*m", s.total.Hdot_cm[k]);
  for (int k : normal) add(std::string("dHO") + xyz[k], "N*m", s.total.Hdot_O[k]);
  for (const auto& r : s.solution.reactions) {
    if (s.planar) {
      add(r.name + "_Fx", "N", r.F_Jc_W.x());
      add(r.name + "_Fy", "N", r.F_Jc_W.y());
      add(r.name + "_Mz", "N*m", r.M_Jc_W.z());
    }
    for (int k = 0; k < 3 && !s.planar; ++k) add(r.name + "_F" + xyz[k], "N", r.F_Jc_W[k]);
    for (int k = 0; k < 3 && !s.planar; ++k) add(r.name + "_M" + xyz[k], "N*m", r.M_Jc_W[k]);
    if (r.is_rolling) {
      add(r.name + "_N", "N", r.normal_force);
      add(r.name + "_f", "N", r.friction_W.norm());
      add(r.name + "_f_over_N", "", r.friction_needed);
    }
  }
  // Contact points as the simulation's contact columns name them; mode 0 separated, 1 sliding,
  // 2 sticking.
  for (const ContactPointReport& c : s.contacts) {
    add(c.point + "_mode", "", static_cast<double>(c.out.mode));
    add(c.point + "_N", "N", c.out.normal_force);
    add(c.point + "_f", "N", c.out.friction_force_W.norm());
    add(c.point + "_f_over_N", "", c.FrictionRatio());
  }
}

}  // namespace chasles
