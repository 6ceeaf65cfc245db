// The finite-number guard of every report (chasles/report/json_report.h).

#include "chasles/report/json_report.h"

#include <cmath>

#include <fmt/format.h>

#include "chasles/error.h"

namespace chasles {

namespace {

std::string Why(double v) {
  return fmt::format(
      "is {}, not a finite number: a value in its computation overflowed the range of a double "
      "(about 1.8e308), e.g. a distance of 1e200 m squared in an inertia, or came from one that "
      "did; check the scene for very large positions, sizes, masses or densities (and the units "
      "asked for)",
      v);
}

/// Depth-first: the path of the first non-finite number, or "" when all are finite.
bool FindNonFinite(const nlohmann::json& j, std::string& path, double& value) {
  if (j.is_number_float()) {
    const double v = j.get<double>();
    if (!std::isfinite(v)) {
      value = v;
      return true;
    }
    return false;
  }
  if (j.is_array()) {
    for (size_t i = 0; i < j.size(); ++i) {
      std::string sub;
      if (FindNonFinite(j[i], sub, value)) {
        path = fmt::format("[{}]{}", i, sub);
        return true;
      }
    }
  } else if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) {
      std::string sub;
      if (FindNonFinite(it.value(), sub, value)) {
        path = "." + it.key() + sub;
        return true;
      }
    }
  }
  return false;
}

}  // namespace

void CheckFiniteJson(const nlohmann::json& j, std::string_view report) {
  std::string path;
  double value = 0.0;
  if (FindNonFinite(j, path, value)) {
    if (!path.empty() && path.front() == '.') path.erase(0, 1);
    // The key path reads like a body's name: "bodies[0].points[1].inertia[0][0]" -> the name.
    std::string named = path;
    const auto dot = path.find('.');
    if (path.rfind("bodies[", 0) == 0 && dot != std::string::npos && j.contains("bodies")) {
      const size_t index = std::stoul(path.substr(7));
      const nlohmann::json& b = j["bodies"][index];
      if (b.contains("name") && b["name"].is_string()) {
        named = fmt::format("{} (body '{}')", path, b["name"].get<std::string>());
      }
    }
    throw InputError(fmt::format("{}: {} {}", report, named, Why(value)));
  }
}

std::string DumpJson(const nlohmann::json& j, std::string_view report) {
  CheckFiniteJson(j, report);
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

void CheckFiniteTable(const std::vector<std::string>& columns,
                      const std::vector<std::vector<double>>& rows, std::string_view report) {
  for (size_t r = 0; r < rows.size(); ++r) {
    for (size_t c = 0; c < rows[r].size(); ++c) {
      if (!std::isfinite(rows[r][c])) {
        throw InputError(fmt::format("{}: column '{}' of row {} {}", report,
                                     c < columns.size() ? columns[c] : std::to_string(c), r + 1,
                                     Why(rows[r][c])));
      }
    }
  }
}

double Finite(double v, std::string_view what) {
  if (!std::isfinite(v)) throw InputError(fmt::format("{} {}", what, Why(v)));
  return v;
}

nlohmann::json VecJson(const Vec3& v) {
  return {v.x(), v.y(), v.z()};
}

nlohmann::json MatJson(const Mat3& m) {
  return {{m(0, 0), m(0, 1), m(0, 2)}, {m(1, 0), m(1, 1), m(1, 2)}, {m(2, 0), m(2, 1), m(2, 2)}};
}

}  // namespace chasles
