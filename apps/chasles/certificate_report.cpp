#include "certificate_report.h"

#include <fmt/format.h>

namespace chasles::cli {

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
            {"energy", c.energy_scale}}},
          {"checks", checks}};
}

std::string CertificateText(const Certificate& c) {
  std::string out = fmt::format("\nChecks ({}; worst value against its tolerance, SI)\n",
                                c.passed() ? "all passed" : "SOME FAILED");
  for (const CheckResult& r : c.checks) {
    if (r.count == 0) {
      out += fmt::format("  {:<26} n/a\n", r.name);
      continue;
    }
    out += fmt::format("  {:<26} {}  worst {:.2e} {} (tolerance {:.2e}) at {}, t = {:.9g} s ({})\n",
                       r.name, r.passed() ? "pass" : "FAIL", r.worst, r.unit, r.tolerance, r.where,
                       r.t, CheckPhaseName(r.phase));
  }
  return out;
}

}  // namespace chasles::cli
