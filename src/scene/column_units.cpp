// Units of a run's columns (chasles/scene/column_units.h). The names follow AllColumns
// (src/scene/study_columns.cpp): per body "<body>_<suffix>", ledger columns, "W_<element>",
// per constraint "<name>_<component>", per contact point "<label>_<quantity>".

#include "chasles/scene/column_units.h"

#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "chasles/error.h"

namespace chasles {

namespace {

/// Every column name of the scene's run with its unit.
std::map<std::string, std::string> ColumnUnitTable(const Scene& scene) {
  static const std::map<std::string, std::string> body_suffix = {
      {"x", "m"},          {"y", "m"},          {"z", "m"},          {"ox", "m"},
      {"oy", "m"},         {"oz", "m"},         {"qw", ""},          {"qx", ""},
      {"qy", ""},          {"qz", ""},          {"yaw", "rad"},      {"pitch", "rad"},
      {"roll", "rad"},     {"tilt", "rad"},     {"theta", "rad"},    {"vx", "m/s"},
      {"vy", "m/s"},       {"vz", "m/s"},       {"speed", "m/s"},    {"wx", "rad/s"},
      {"wy", "rad/s"},     {"wz", "rad/s"},     {"wbx", "rad/s"},    {"wby", "rad/s"},
      {"wbz", "rad/s"},    {"omega", "rad/s"},  {"ax", "m/s^2"},     {"ay", "m/s^2"},
      {"az", "m/s^2"},     {"alx", "rad/s^2"},  {"aly", "rad/s^2"},  {"alz", "rad/s^2"},
      {"albx", "rad/s^2"}, {"alby", "rad/s^2"}, {"albz", "rad/s^2"}, {"alpha", "rad/s^2"}};
  std::map<std::string, std::string> units = {{"t", "s"}};
  for (const SceneBody& b : scene.bodies) {
    for (const auto& [suffix, unit] : body_suffix) units[b.name + "_" + suffix] = unit;
    for (const char* s : {"T_trans", "T_rot", "T"}) units[b.name + "_" + s] = "J";
    for (const char* s : {"Px", "Py", "Pz"}) units[b.name + "_" + s] = "kg*m/s";
    for (const char* s : {"Hx", "Hy", "Hz", "HOx", "HOy", "HOz"}) {
      units[b.name + "_" + s] = "kg*m^2/s";
    }
    for (const char* s : {"dHx", "dHy", "dHz", "dHOx", "dHOy", "dHOz"}) {
      units[b.name + "_" + s] = "N*m";
    }
    for (const ScenePoint& p : b.points) {
      for (const char* s : {"vx", "vy", "vz"}) units[b.name + "_" + p.name + "_" + s] = "m/s";
      for (const char* s : {"ax", "ay", "az"}) units[b.name + "_" + p.name + "_" + s] = "m/s^2";
    }
  }
  for (const char* s : {"T_trans", "T_rot", "T", "V", "E", "W_nc", "W_friction", "W_rolling",
                        "W_impacts", "dissipated", "jumps", "residual"}) {
    units[s] = "J";
  }
  for (const SceneForce& f : scene.dynamics.forces) units["W_" + f.name] = "J";
  for (const char* s : {"Px", "Py", "Pz"}) units[s] = "kg*m/s";
  for (const char* s : {"Hx", "Hy", "Hz", "HOx", "HOy", "HOz"}) units[s] = "kg*m^2/s";
  for (const std::string& n : scene.dynamics.constraints.names()) {
    units["W_" + n] = "J";
    for (const char* frame : {"", "_B", "_P"}) {
      for (const char* s : {"Fx", "Fy", "Fz"}) units[n + "_" + s + frame] = "N";
      for (const char* s : {"Mx", "My", "Mz"}) units[n + "_" + s + frame] = "N*m";
    }
  }
  for (const std::string& p : scene.dynamics.contacts.point_labels()) {
    units[p + "_mode"] = "";
    units[p + "_N"] = "N";
    units[p + "_f"] = "N";
    units[p + "_slip"] = "m/s";
    units[p + "_gap"] = "m";
  }
  return units;
}

}  // namespace

std::string StudyColumnUnit(const Scene& scene, const std::string& column) {
  return StudyColumnUnits(scene, {column}).front();
}

std::vector<std::string> StudyColumnUnits(const Scene& scene,
                                          const std::vector<std::string>& columns) {
  const std::map<std::string, std::string> table = ColumnUnitTable(scene);
  std::vector<std::string> out;
  for (const std::string& c : columns) {
    const auto it = table.find(c);
    if (it == table.end()) {
      throw InputError(fmt::format("'{}' is not a column of the run of scene '{}'", c, scene.file));
    }
    out.push_back(it->second);
  }
  return out;
}

}  // namespace chasles
