// Units and groups of a run's columns (chasles/scene/column_units.h), from the columns' groups
// and quantities (scene/internal/study_columns.h). Units: per body "<body>_<suffix>", ledger
// columns, "W_<element>", per constraint "<name>_<component>", per contact point
// "<label>_<quantity>".

#include "chasles/scene/column_units.h"

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "chasles/error.h"
#include "scene/internal/study_columns.h"

namespace chasles {

namespace {

/// The unit of a column from its group and quantity.
std::string UnitOf(const scene_internal::ColumnInfo& c) {
  static const std::map<std::string, std::string> body_quantity = {
      {"x", "m"},          {"y", "m"},          {"z", "m"},          {"ox", "m"},
      {"oy", "m"},         {"oz", "m"},         {"qw", ""},          {"qx", ""},
      {"qy", ""},          {"qz", ""},          {"yaw", "rad"},      {"pitch", "rad"},
      {"roll", "rad"},     {"tilt", "rad"},     {"theta", "rad"},    {"vx", "m/s"},
      {"vy", "m/s"},       {"vz", "m/s"},       {"speed", "m/s"},    {"wx", "rad/s"},
      {"wy", "rad/s"},     {"wz", "rad/s"},     {"wbx", "rad/s"},    {"wby", "rad/s"},
      {"wbz", "rad/s"},    {"omega", "rad/s"},  {"ax", "m/s^2"},     {"ay", "m/s^2"},
      {"az", "m/s^2"},     {"alx", "rad/s^2"},  {"aly", "rad/s^2"},  {"alz", "rad/s^2"},
      {"albx", "rad/s^2"}, {"alby", "rad/s^2"}, {"albz", "rad/s^2"}, {"alpha", "rad/s^2"},
      {"T_trans", "J"},    {"T_rot", "J"},      {"T", "J"},          {"Px", "kg*m/s"},
      {"Py", "kg*m/s"},    {"Pz", "kg*m/s"},    {"Hx", "kg*m^2/s"},  {"Hy", "kg*m^2/s"},
      {"Hz", "kg*m^2/s"},  {"HOx", "kg*m^2/s"}, {"HOy", "kg*m^2/s"}, {"HOz", "kg*m^2/s"},
      {"dHx", "N*m"},      {"dHy", "N*m"},      {"dHz", "N*m"},      {"dHOx", "N*m"},
      {"dHOy", "N*m"},     {"dHOz", "N*m"},     {"pvx", "m/s"},      {"pvy", "m/s"},
      {"pvz", "m/s"},      {"pax", "m/s^2"},    {"pay", "m/s^2"},    {"paz", "m/s^2"}};
  static const std::map<std::string, std::string> contact_quantity = {
      {"mode", ""}, {"N", "N"}, {"f", "N"}, {"slip", "m/s"}, {"gap", "m"}};
  if (c.name == "t") return "s";
  if (c.body >= 0) return body_quantity.at(c.quantity);
  const std::string& g = c.group;
  if (g == "energy" || g == "work" || g == "residual") return "J";
  if (g == "contacts") return contact_quantity.at(c.quantity);
  if (g == "reactions" || g == "reactions_3d") return c.quantity[0] == 'F' ? "N" : "N*m";
  return c.quantity[0] == 'P' ? "kg*m/s" : "kg*m^2/s";  // the momenta
}

}  // namespace

std::string StudyColumnUnit(const Scene& scene, const std::string& column) {
  return StudyColumnUnits(scene, {column}).front();
}

std::vector<std::string> StudyColumnUnits(const Scene& scene,
                                          const std::vector<std::string>& columns) {
  const scene_internal::ColumnIndex index(scene);
  std::vector<std::string> out;
  for (const std::string& c : columns) {
    const std::optional<scene_internal::ColumnInfo> info = index.Find(c);
    if (!info) {
      throw InputError(fmt::format("'{}' is not a column of the run of scene '{}'", c, scene.file));
    }
    out.push_back(UnitOf(*info));
  }
  return out;
}

std::vector<std::string> StudyColumnGroups(const Scene& scene,
                                           const std::vector<std::string>& columns) {
  const scene_internal::ColumnIndex index(scene);
  std::vector<std::string> out;
  for (const std::string& c : columns) {
    const std::optional<scene_internal::ColumnInfo> info = index.Find(c);
    out.push_back(info ? info->group : std::string());
  }
  return out;
}

std::vector<std::string> ExpandStudyColumns(const Scene& scene,
                                            const std::vector<std::string>& names) {
  const scene_internal::ColumnIndex index(scene);
  std::vector<std::string> out;
  for (const std::string& name : names) index.ExpandInto(name, out);
  return out;
}

}  // namespace chasles
