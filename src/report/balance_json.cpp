// The JSON report of `chasles balance` (docs/modes.md, "Rotors"; analysis/balance.h and
// analysis/whirl.h have the equations).

#include "chasles/report/balance_json.h"

#include <cmath>

namespace chasles {
namespace {

nlohmann::json Vec(const Vec3& v) {
  return {v.x(), v.y(), v.z()};
}

}  // namespace

nlohmann::json BalanceJson(const std::string& body, const BalanceReport& r, const RotorAxis& axis) {
  nlohmann::json corrections = nlohmann::json::array();
  const char* names[2] = {"A", "B"};
  const double z[2] = {axis.z_A, axis.z_B};
  for (int k = 0; k < 2; ++k) {
    const BalanceCorrection& c = r.corrections[static_cast<size_t>(k)];
    corrections.push_back({{"plane", names[k]},
                           {"position", z[k]},
                           {"mass", c.mass},
                           {"radius", c.radius},
                           {"angle", c.angle},
                           {"point", Vec(c.p_W)}});
  }
  nlohmann::json j = {
      {"body", body},
      {"mass", r.mass},
      {"static_unbalance", r.static_unbalance_W.norm()},
      {"static_unbalance_vector", Vec(r.static_unbalance_W)},
      {"couple_unbalance", r.couple_unbalance_W.norm()},
      {"couple_unbalance_vector", Vec(r.couple_unbalance_W)},
      {"reference_directions", {Vec(r.e1_W), Vec(r.e2_W)}},
      {"corrections", corrections},
      {"residual_after", {{"static", r.residual_static}, {"couple", r.residual_couple}}},
      {"permissible", nullptr},
      {"bearing_reactions", nullptr}};
  if (std::isfinite(r.speed)) {
    j["speed"] = r.speed;
    j["bearing_reactions"] = {
        {"before", {{"A", Vec(r.bearing_forces_W[0])}, {"B", Vec(r.bearing_forces_W[1])}}},
        {"after",
         {{"A", Vec(r.bearing_forces_after_W[0])}, {"B", Vec(r.bearing_forces_after_W[1])}}}};
  }
  if (std::isfinite(r.permissible)) {
    j["permissible"] = {{"grade", r.grade},
                        {"total", r.permissible},
                        {"A", r.permissible_per_plane[0]},
                        {"B", r.permissible_per_plane[1]},
                        {"met", r.static_unbalance_W.norm() <= r.permissible}};
  }
  return j;
}

nlohmann::json WhirlJson(const WhirlMap& w) {
  nlohmann::json speeds = nlohmann::json::array(), points = nlohmann::json::array();
  for (const WhirlPoint& p : w.points) {
    speeds.push_back(p.speed);
    nlohmann::json modes = nlohmann::json::array();
    for (const WhirlMode& m : p.modes) {
      modes.push_back({{"eigenvalue", {m.eigenvalue.real(), m.eigenvalue.imag()}},
                       {"frequency_hz", m.frequency_hz},
                       {"damping_ratio", m.damping_ratio},
                       {"direction", WhirlDirectionName(m.direction)}});
    }
    points.push_back({{"speed", p.speed}, {"modes", modes}});
  }
  nlohmann::json critical = nlohmann::json::array();
  for (const WhirlCriticalSpeed& c : w.critical_speeds) {
    nlohmann::json dirs = nlohmann::json::array();
    for (const WhirlDirection d : c.directions) dirs.push_back(WhirlDirectionName(d));
    critical.push_back({{"speed", c.speed}, {"directions", dirs}});
  }
  return {{"speeds", speeds}, {"points", points}, {"critical_speeds", critical}};
}

nlohmann::json RotorBalanceJson(const RotorBalance& b) {
  nlohmann::json j = BalanceJson(b.body, b.balance, b.axis);
  j["whirl"] = b.whirl ? WhirlJson(*b.whirl) : nlohmann::json(nullptr);
  return j;
}

}  // namespace chasles
