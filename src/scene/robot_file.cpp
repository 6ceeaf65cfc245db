// Robot description files for the commands (chasles/scene/robot_file.h).

#include "chasles/scene/robot_file.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <filesystem>

#include <fmt/format.h>

#include "chasles/analysis/robot_mass.h"
#include "chasles/error.h"
#include "chasles/files/mesh_reader.h"

namespace chasles {

TriangleSoup LoadMeshTriangles(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".dae") return ReadColladaFile(path);
  MeshFileData data = ReadMeshFile(path);
  TriangleSoup soup;
  soup.xyz.assign(data.xyz.begin(), data.xyz.end());
  soup.indices = std::move(data.indices);
  soup.format = data.format;
  return soup;
}

std::vector<std::pair<std::string, std::string>> ParsePackageOptions(
    const std::vector<std::string>& options) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const std::string& o : options) {
    const std::size_t eq = o.find('=');
    if (eq == 0 || eq == std::string::npos || eq + 1 == o.size()) {
      throw InputError(fmt::format("--package '{}': expected NAME=DIR", o));
    }
    if (!std::filesystem::is_directory(o.substr(eq + 1))) {
      throw InputError(fmt::format("--package '{}': '{}' is not a folder", o, o.substr(eq + 1)));
    }
    out.emplace_back(o.substr(0, eq), o.substr(eq + 1));
  }
  return out;
}

std::map<std::string, double> ParseJointOptions(const std::vector<std::string>& options) {
  std::map<std::string, double> out;
  for (const std::string& o : options) {
    const std::size_t eq = o.find('=');
    double v = 0.0;
    const char* end = o.data() + o.size();
    const auto r = eq == std::string::npos
                       ? std::from_chars_result{end, std::errc::invalid_argument}
                       : std::from_chars(o.data() + eq + 1, end, v);
    if (eq == 0 || r.ec != std::errc() || r.ptr != end || !std::isfinite(v)) {
      throw InputError(
          fmt::format("--joint '{}': expected NAME=VALUE, the value in rad (or m "
                      "for a prismatic joint)",
                      o));
    }
    if (!out.emplace(o.substr(0, eq), v).second) {
      throw InputError(fmt::format("--joint '{}': that joint is given twice", o.substr(0, eq)));
    }
  }
  return out;
}

Scene LoadRobotAsScene(const std::string& path, const RobotReadOptions& options,
                       const std::map<std::string, double>& joints) {
  const RobotModel model = ReadRobotFile(path, options);
  const std::vector<LinkPose> poses = CalcLinkPoses(model, joints);
  Scene scene;
  scene.file = path;
  scene.title = fmt::format("{} ({}, {} links)", model.name, RobotFormatName(model.format),
                            model.links.size());
  SceneBody body;
  body.name = model.name.empty() ? "robot" : model.name;
  std::vector<std::optional<MassProperties>> parts;
  for (std::size_t i = 0; i < model.links.size(); ++i) {
    const RobotLink& link = model.links[i];
    parts.emplace_back(std::nullopt);
    if (!link.has_inertial || !(link.inertial.mass > 0.0)) {
      scene.warnings.push_back(fmt::format("link '{}' (line {}) has {}: left out", link.name,
                                           link.line,
                                           link.has_inertial ? "no mass" : "no inertial"));
      continue;
    }
    const MassProperties given = GivenMassProperties(link.inertial);
    const std::string invalid = given.I_BBcm_B().CheckPhysicallyValid();
    if (!invalid.empty()) {
      throw InputError(
          fmt::format("{}:{}: link '{}': {} (chasles audit {} says more and writes "
                      "a fix)",
                      path, link.inertial.line, link.name, invalid, path));
    }
    parts.back() = given;
    ScenePart part;
    part.name = link.name;
    part.shape = "link";
    part.mass_source = "mass";
    part.mass_properties = given.ExpressedInParent(poses[i].R_BL, poses[i].p_BoLo_B);
    part.line = link.inertial.line;
    part.geometry.p_BoPo_B = poses[i].p_BoLo_B;
    part.geometry.R_BP = poses[i].R_BL;
    body.parts.push_back(std::move(part));
  }
  body.mass_properties = CalcRobotMassProperties(poses, parts);
  body.mass_properties.Validate(fmt::format("robot '{}'", body.name));
  body.line = 1;
  scene.bodies.push_back(std::move(body));
  return scene;
}

}  // namespace chasles
