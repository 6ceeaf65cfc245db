#include "whirl_report.h"

namespace chasles::cli {

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

}  // namespace chasles::cli
