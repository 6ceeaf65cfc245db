// The browser report's data of chasles audit (audit_text.h).

#include "audit_text.h"

#include <cmath>
#include <cstdint>
#include <optional>

#include <fmt/format.h>

#include "chasles/analysis/robot_mass.h"
#include "chasles/error.h"
#include "chasles/math/quaternion.h"
#include "chasles/report/audit_text.h"
#include "chasles/report/json_report.h"
#include "chasles/report/report_data.h"
#include "chasles/scene/robot_file.h"
#include "chasles/scene/scene.h"

namespace chasles::cli {

namespace {

/// The rotation R as the page's quaternion [w, x, y, z] (w ≥ 0).
nlohmann::json QuatJson(const Mat3& R) {
  const Quat q(R);
  const Eigen::Vector4d w = QuatToWxyz(q.w() < 0 ? Quat(-q.coeffs()) : q);
  return {w[0], w[1], w[2], w[3]};
}

/// A primitive of a link as a part, placed in B by the link's pose (the page's shapes have
/// their axis of symmetry along z, as the robot formats do; a capsule is drawn as its
/// cylinder). Meshes are not parts of the scene: MeshPartJson draws them.
ScenePart PrimitivePart(const RobotGeometry& g, const LinkPose& pose) {
  ScenePart p;
  p.name = fmt::format("{} {} (line {})", GeometrySetName(g.set), GeometryTypeName(g.type), g.line);
  p.mass_source = "mass";
  p.geometry.R_BP = pose.R_BL * g.R_LG;
  p.geometry.p_BoPo_B = pose.p_BoLo_B + pose.R_BL * g.p_LoGo_L;
  switch (g.type) {
    case GeometryType::kBox:
      p.shape = "box";
      p.geometry.dimensions = {{"size", {g.size[0], g.size[1], g.size[2]}}};
      break;
    case GeometryType::kSphere:
      p.shape = "sphere";
      p.geometry.dimensions = {{"radius", {g.size[0]}}};
      break;
    case GeometryType::kEllipsoid:
      p.shape = "ellipsoid";
      p.geometry.dimensions = {{"semi_axes", {g.size[0], g.size[1], g.size[2]}}};
      break;
    case GeometryType::kCylinder:
    case GeometryType::kCapsule:
      p.shape = "cylinder";
      p.geometry.dimensions = {{"radius", {g.size[0]}}, {"length", {g.size[1]}}};
      break;
    case GeometryType::kMesh:
      break;
  }
  return p;
}

/// A mesh of a link as the page's part (docs/report.md, "The data"): its vertices scaled to
/// metres in its frame G (f4) and its triangles, G placed in B by the link's pose; the shape
/// "missing mesh" (drawn as a marker) when the file was not resolved or cannot be read (the
/// audit's notes say why). The page's own reader takes no Collada, so the mesh is read here.
nlohmann::json MeshPartJson(const RobotGeometry& g, const LinkPose& pose) {
  nlohmann::json part = {{"name", fmt::format("{} mesh (line {})", GeometrySetName(g.set), g.line)},
                         {"shape", "missing mesh"},
                         {"subtract", false},
                         {"position", VecJson(pose.p_BoLo_B + pose.R_BL * g.p_LoGo_L)},
                         {"quaternion", QuatJson(pose.R_BL * g.R_LG)},
                         {"dimensions", nlohmann::json::object()}};
  if (g.mesh_path.empty()) return part;
  TriangleSoup soup;
  try {
    soup = LoadMeshTriangles(g.mesh_path);
  } catch (const InputError&) {
    return part;
  }
  std::vector<float> xyz(soup.xyz.size());
  for (std::size_t i = 0; i < xyz.size(); ++i) {
    xyz[i] = static_cast<float>(soup.xyz[i] * g.mesh_scale[static_cast<int>(i % 3)]);
  }
  part["shape"] = "mesh";
  part["mesh"] = {
      {"vertices", Base64(xyz.data(), xyz.size() * sizeof(float))},
      {"triangles", Base64(soup.indices.data(), soup.indices.size() * sizeof(std::uint32_t))}};
  return part;
}

/// A link drawn: its given inertial (the body's mass properties, so the page's violet
/// ellipsoid and table are the given ones), its primitives, and the uniform ellipsoid of its
/// geometry's inertia at the given mass as a part "computed" (AuditReportData moves it out).
SceneBody LinkBody(const std::string& name, const RobotLink& link, const LinkAudit& l,
                   const LinkPose& pose) {
  SceneBody body;
  body.name = name;
  body.mass_properties = l.given.ExpressedInParent(pose.R_BL, pose.p_BoLo_B);
  const GeometryEstimate* e = l.computed ? &l.estimates[*l.computed] : nullptr;
  if (e && std::isfinite(e->volume) && e->volume > 0.0) {
    ScenePart c;
    c.name = "computed";
    c.shape = "custom";
    c.mass_source = "mass";
    c.mass_properties = e->AtMass(l.given.mass()).ExpressedInParent(pose.R_BL, pose.p_BoLo_B);
    body.parts.push_back(c);
  }
  for (const RobotGeometry& g : link.geometries) {
    if (g.type != GeometryType::kMesh) body.parts.push_back(PrimitivePart(g, pose));
  }
  return body;
}

/// A link's entry in the page's list: name, line, its findings, and the index of its body in
/// "bodies" (null when it is not drawn).
nlohmann::json LinkEntry(const LinkAudit& l, std::optional<std::size_t> body) {
  nlohmann::json findings = nlohmann::json::array();
  for (const Finding& f : l.findings) {
    findings.push_back({{"severity", SeverityName(f.severity)},
                        {"code", FindingCodeName(f.code)},
                        {"line", f.line},
                        {"message", f.message}});
  }
  return {{"name", l.name},
          {"line", l.line},
          {"body", body ? nlohmann::json(*body) : nlohmann::json(nullptr)},
          {"findings", findings}};
}

}  // namespace

nlohmann::json AuditReportData(const std::vector<RobotModel>& models,
                               const std::vector<RobotAudit>& audits,
                               const std::map<std::string, double>& joints) {
  // Each link with a valid given inertial is a body at its pose in its robot's base frame (at
  // `joints`); the page draws all of them in one view.
  Scene scene;
  scene.file = models.empty() ? "" : models.front().file;
  scene.title = "chasles audit";
  nlohmann::json files = nlohmann::json::array();
  std::vector<nlohmann::json> extra;  // per body: its geometry's source and method, meshes
  for (std::size_t k = 0; k < audits.size(); ++k) {
    const RobotAudit& a = audits[k];
    const std::vector<LinkPose> poses = CalcLinkPoses(models[k], joints);
    nlohmann::json links = nlohmann::json::array();
    for (std::size_t i = 0; i < a.links.size(); ++i) {
      const LinkAudit& l = a.links[i];
      const bool drawn = l.has_inertial && l.given.mass() > 0.0 &&
                         l.given.I_BBcm_B().CheckPhysicallyValid().empty();
      links.push_back(LinkEntry(l, drawn ? std::optional(scene.bodies.size()) : std::nullopt));
      if (!drawn) continue;
      const std::string name = audits.size() > 1 ? fmt::format("{}: {}", a.file, l.name) : l.name;
      scene.bodies.push_back(LinkBody(name, models[k].links[i], l, poses[i]));
      nlohmann::json x = {{"meshes", nlohmann::json::array()}};
      if (l.computed) {
        const GeometryEstimate& e = l.estimates[*l.computed];
        x["computed"] = {{"source", GeometrySetName(e.set)},
                         {"method", GeometryMethodName(e.method)}};
      }
      for (const RobotGeometry& g : models[k].links[i].geometries) {
        if (g.type == GeometryType::kMesh) x["meshes"].push_back(MeshPartJson(g, poses[i]));
      }
      extra.push_back(x);
    }
    files.push_back({{"path", a.file},
                     {"format", RobotFormatName(a.format)},
                     {"robot", a.robot_name},
                     {"errors", a.Count(Severity::kError)},
                     {"warnings", a.Count(Severity::kWarning)},
                     {"notes", a.Count(Severity::kNote)},
                     {"links", links}});
  }
  nlohmann::json data = MassReportData(scene);
  data["audit"] = files;
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    nlohmann::json& body = data["bodies"][b];
    nlohmann::json& parts = body["parts"];
    if (!parts.empty() && parts[0]["name"] == "computed") {
      body["computed"] = extra[b]["computed"];
      body["computed"]["ellipsoid"] = parts[0]["ellipsoid"];
      parts.erase(0);
    }
    for (nlohmann::json& m : extra[b]["meshes"]) parts.push_back(std::move(m));
  }
  return data;
}

}  // namespace chasles::cli
