#pragma once
/// @file
/// A table of common engineering materials and their densities [kg/m³].
///
/// The values are typical room-temperature handbook values (alloys and woods vary by grade
/// and moisture by several per cent); a scene can always state its own density, and should
/// when the answer depends on it (the chapter's Example 8.1 uses 2712 kg/m³ for aluminium
/// where this table holds 2700 kg/m³).
///
/// Names are matched case-insensitively, with spaces, hyphens and underscores equivalent
/// ("Stainless Steel" = "stainless-steel" = "stainless_steel"); British and American
/// spellings and common abbreviations are aliases ("aluminum", "hdpe", "pmma").

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace chasles {

/// One entry of the material table.
struct Material {
  /// Canonical name, lower case with underscores, e.g. "stainless_steel".
  std::string_view name;
  /// Typical density at room temperature [kg/m³].
  double density;
  /// Other names that mean this material, e.g. {"aluminum"}.
  std::span<const std::string_view> aliases;
};

/// Every material in the table, in a stable order (metals, then stone and glass, then water
/// and ice, woods, polymers).
std::span<const Material> Materials();

/// The name as the table compares it: lower case, runs of spaces, hyphens and underscores
/// turned into one underscore, leading and trailing ones dropped.
std::string NormalizeMaterialName(std::string_view name);

/// Density [kg/m³] of the material called `name` (canonical name or alias), or nothing.
std::optional<double> FindMaterialDensity(std::string_view name);

/// Density [kg/m³] of the material called `name`; throws InputError for an unknown name,
/// suggesting the closest known one ("unknown material 'stell'; did you mean 'steel'? ...").
double LookUpMaterialDensity(std::string_view name);

/// Every name the table accepts (canonical names and aliases), sorted.
std::vector<std::string> MaterialNames();

/// The accepted name closest to `unknown` by edit distance (insertions, deletions,
/// substitutions and swaps of neighbours), or an empty string when nothing is close enough
/// to be a plausible typo.
std::string SuggestMaterialName(std::string_view unknown);

}  // namespace chasles
