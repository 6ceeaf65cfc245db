#include "chasles/mass/materials.h"

#include "chasles/suggest.h"

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
  // Canonical names first, so that a tie prefers the material's own name over an alias.
  std::vector<std::string> names;
  for (const Material& m : kTable) names.emplace_back(m.name);
  for (const Material& m : kTable) {
    for (std::string_view a : m.aliases) names.emplace_back(a);
  }
  const std::vector<std::string> best = SuggestNames(key, names, 1);
  return best.empty() ? std::string() : best.front();
}

}  // namespace chasles
