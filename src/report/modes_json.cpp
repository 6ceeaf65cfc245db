// A mode as JSON (chasles/report/modes_json.h).

#include "chasles/report/modes_json.h"

#include <complex>

namespace chasles {

nlohmann::json ModeJson(const Mode& m) {
  const auto complex = [](std::complex<double> z) { return nlohmann::json{z.real(), z.imag()}; };
  nlohmann::json shape = nlohmann::json::array();
  for (Eigen::Index i = 0; i < m.shape.size(); ++i) shape.push_back(complex(m.shape[i]));
  nlohmann::json j = {{"eigenvalue", complex(m.eigenvalue)},
                      {"frequency_hz", m.frequency_hz},
                      {"damping_ratio", m.damping_ratio},
                      {"growth_rate", m.growth_rate},
                      {"stable", m.stable},
                      {"neutral", m.neutral},
                      {"rigid", m.rigid},
                      {"shape", shape}};
  if (m.rigid) j["frees"] = m.rigid_coordinate;
  return j;
}

}  // namespace chasles
