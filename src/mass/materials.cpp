#include "chasles/mass/materials.h"

#include <algorithm>
#include <array>
#include <cctype>

#include <fmt/format.h>

#include "chasles/error.h"

namespace chasles {
namespace {

using Names = std::span<const std::string_view>;

// Aliases (normalised form). Spelling variants first, then abbreviations.
constexpr std::string_view kSteel[] = {"carbon_steel", "mild_steel"};
constexpr std::string_view kStainless[] = {"stainless", "inox"};
constexpr std::string_view kAluminium[] = {"aluminum", "al"};
constexpr std::string_view kAcrylic[] = {"pmma", "plexiglass", "perspex"};
constexpr std::string_view kPolyethylene[] = {"hdpe"};
constexpr std::string_view kPolypropylene[] = {"pp"};
constexpr std::string_view kPtfe[] = {"teflon"};
constexpr std::string_view kPvc[] = {"polyvinyl_chloride"};
constexpr std::string_view kCarbon[] = {"carbon_fiber", "cfrp"};
constexpr std::string_view kRubber[] = {"natural_rubber"};

// Typical room-temperature handbook densities [kg/m³] (CRC Handbook, MatWeb typical values).
constexpr Material kTable[] = {
    {"steel", 7850, kSteel},
    {"stainless_steel", 8000, kStainless},
    {"cast_iron", 7200, {}},
    {"iron", 7874, {}},
    {"aluminium", 2700, kAluminium},
    {"lead", 11340, {}},
    {"copper", 8960, {}},
    {"brass", 8500, {}},
    {"bronze", 8800, {}},
    {"titanium", 4506, {}},
    {"gold", 19300, {}},
    {"silver", 10490, {}},
    {"platinum", 21450, {}},
    {"zinc", 7140, {}},
    {"tin", 7287, {}},
    {"nickel", 8908, {}},
    {"tungsten", 19250, {}},
    {"magnesium", 1738, {}},
    {"concrete", 2400, {}},
    {"granite", 2700, {}},
    {"glass", 2500, {}},
    {"water", 1000, {}},
    {"ice", 917, {}},
    {"oak", 750, {}},
    {"pine", 500, {}},
    {"balsa", 160, {}},
    {"rubber", 1100, kRubber},
    {"nylon", 1150, {}},
    {"abs", 1050, {}},
    {"pla", 1240, {}},
    {"acrylic", 1180, kAcrylic},
    {"polycarbonate", 1200, {}},
    {"polyethylene", 950, kPolyethylene},
    {"polypropylene", 905, kPolypropylene},
    {"polystyrene", 1050, {}},
    {"pvc", 1380, kPvc},
    {"ptfe", 2200, kPtfe},
    {"carbon_fibre", 1600, kCarbon},
};

const Material* Find(const std::string& normalized) {
  for (const Material& m : kTable) {
    if (m.name == normalized) return &m;
    for (std::string_view a : m.aliases) {
      if (a == normalized) return &m;
    }
  }
  return nullptr;
}

// Optimal-string-alignment distance: Levenshtein plus transposition of neighbours ("stele").
int EditDistance(std::string_view a, std::string_view b) {
  const size_t n = a.size(), m = b.size();
  std::vector<std::vector<int>> d(n + 1, std::vector<int>(m + 1, 0));
  for (size_t i = 0; i <= n; ++i) d[i][0] = static_cast<int>(i);
  for (size_t j = 0; j <= m; ++j) d[0][j] = static_cast<int>(j);
  for (size_t i = 1; i <= n; ++i) {
    for (size_t j = 1; j <= m; ++j) {
      const int cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    }
  }
  return d[n][m];
}

}  // namespace

std::span<const Material> Materials() {
  return kTable;
}

std::string NormalizeMaterialName(std::string_view name) {
  std::string out;
  bool pending_separator = false;
  for (char ch : name) {
    if (ch == ' ' || ch == '-' || ch == '_' || ch == '\t') {
      pending_separator = !out.empty();
      continue;
    }
    if (pending_separator) out += '_';
    pending_separator = false;
    out += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  }
  return out;
}

std::optional<double> FindMaterialDensity(std::string_view name) {
  const Material* m = Find(NormalizeMaterialName(name));
  if (m == nullptr) return std::nullopt;
  return m->density;
}

double LookUpMaterialDensity(std::string_view name) {
  if (const std::optional<double> rho = FindMaterialDensity(name)) return *rho;
  const std::string suggestion = SuggestMaterialName(name);
  std::string names;
  for (const Material& m : kTable) {
    if (!names.empty()) names += ", ";
    names += m.name;
  }
  if (!suggestion.empty()) {
    throw InputError(fmt::format(
        "unknown material '{}'; did you mean '{}'? Known materials: {}; or give a density "
        "in kg/m^3 instead",
        name, suggestion, names));
  }
  throw InputError(
      fmt::format("unknown material '{}'. Known materials: {}; or give a density in kg/m^3 instead",
                  name, names));
}

std::vector<std::string> MaterialNames() {
  std::vector<std::string> out;
  for (const Material& m : kTable) {
    out.emplace_back(m.name);
    for (std::string_view a : m.aliases) out.emplace_back(a);
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string SuggestMaterialName(std::string_view unknown) {
  const std::string key = NormalizeMaterialName(unknown);
  if (key.empty()) return {};
  // A typo changes about one letter in four; short names allow one edit only, so that "ab"
  // does not suggest "al".
  const int allowed = key.size() <= 4 ? 1 : (key.size() <= 8 ? 2 : 3);
  std::string best;
  int best_distance = allowed + 1;
  // Canonical names first, so that a tie prefers the material's own name over an alias.
  for (const Material& m : kTable) {
    const int d = EditDistance(key, m.name);
    if (d < best_distance) best_distance = d, best = m.name;
  }
  for (const Material& m : kTable) {
    for (std::string_view a : m.aliases) {
      const int d = EditDistance(key, a);
      if (d < best_distance) best_distance = d, best = a;
    }
  }
  return best;
}

}  // namespace chasles
