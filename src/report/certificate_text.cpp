#include "chasles/report/certificate_text.h"

#include <fmt/format.h>

namespace chasles {
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

}  // namespace chasles
