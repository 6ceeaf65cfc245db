// The certificate as JSON (chasles/report/certificate_json.h).

#include "chasles/report/certificate_json.h"

#include <utility>

namespace chasles {

nlohmann::json CertificateJson(const Certificate& c) {
  nlohmann::json checks = nlohmann::json::array();
  for (const CheckResult& r : c.checks) {
    nlohmann::json j = {{"name", r.name},         {"description", r.description},
                        {"applies", r.count > 0}, {"count", r.count},
                        {"passed", r.passed()},   {"unit", r.unit},
                        {"worst", r.worst},       {"tolerance", r.tolerance}};
    if (r.count > 0) {
      j["where"] = r.where;
      j["t"] = r.t;
      j["phase"] = CheckPhaseName(r.phase);
    }
    checks.push_back(std::move(j));
  }
  return {{"passed", c.passed()},
          {"scales",
           {{"force", c.force_scale},
            {"moment", c.moment_scale},
            {"length", c.length_scale},
            {"velocity", c.velocity_scale},
            {"energy", c.energy_scale},
            {"impulse", c.impulse_scale},
            {"angular_impulse", c.angular_impulse_scale}}},
          {"checks", checks}};
}

}  // namespace chasles
