// The SDF reader (chasles/files/robot_reader.h): <sdf> with one <model> (directly or in a
// <world>), its <link>, <joint>, <frame> and nested <model> elements, and the poses between
// them (sdformat.org, "Pose frame semantics", SDFormat 1.7-1.9: a pose is relative to the
// frame named by relative_to, else to the element's default: the model for links, frames and
// nested models, the child link for joints).

#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "chasles/math/rotation.h"
#include "files/internal/robot_readers.h"

namespace chasles::internal {

namespace {

/// A frame of the model: a link, a joint, a <frame>, a model.
struct SdfFrame {
  int line = 0;
  /// The frame its pose is relative to (scoped name).
  std::string relative_to;
  /// The pose as written, in `relative_to`.
  Mat3 R = Mat3::Identity();
  Vec3 p = Vec3::Zero();
  /// The pose in the top model's frame, once resolved.
  bool resolved = false, visiting = false;
  Mat3 R_M = Mat3::Identity();
  Vec3 p_M = Vec3::Zero();
};

struct SdfContext {
  SdfContext(const XmlFile& x, const RobotReadOptions& o, RobotModel& m)
      : xml(x), options(o), model(m) {}
  const XmlFile& xml;
  const RobotReadOptions& options;
  RobotModel& model;
  LinkIndex links;
  std::map<std::string, SdfFrame> frames;
  /// Joints with their scope, read after every link of every scope.
  std::vector<std::pair<pugi::xml_node, std::string>> joints;
};

/// `name` written in the scope `prefix` ("" or "outer::inner::").
std::string Scoped(const std::string& prefix, const std::string& name) {
  return prefix + name;
}

/// A <pose> child: its rotation and translation, and its relative_to (empty if none).
void ReadPose(const XmlFile& xml, pugi::xml_node parent, Mat3* R, Vec3* p,
              std::string* relative_to) {
  *R = Mat3::Identity();
  *p = Vec3::Zero();
  const pugi::xml_node pose = parent.child("pose");
  if (!pose) return;
  if (relative_to) *relative_to = pose.attribute("relative_to").value();
  const std::string format = pose.attribute("rotation_format").value();
  const bool degrees = std::string(pose.attribute("degrees").value()) == "true";
  if (format == "quat_xyzw") {
    const std::vector<double> v = xml.TextNumbers(pose, 7);
    const double n = std::sqrt(v[3] * v[3] + v[4] * v[4] + v[5] * v[5] + v[6] * v[6]);
    if (!(n > 0.0)) xml.Fail(pose, "<pose>: a zero quaternion");
    *p = Vec3(v[0], v[1], v[2]);
    *R = Quat(v[6] / n, v[3] / n, v[4] / n, v[5] / n).toRotationMatrix();
    return;
  }
  if (!format.empty() && format != "euler_rpy") {
    xml.Fail(pose, fmt::format("rotation_format '{}': expected euler_rpy or quat_xyzw", format));
  }
  const std::vector<double> v = xml.TextNumbers(pose, 6);
  *p = Vec3(v[0], v[1], v[2]);
  *R = RotationFromRpy(Vec3(v[3], v[4], v[5]) * (degrees ? M_PI / 180.0 : 1.0));
}

/// Adds the frame `name` of `element` with its pose, relative to `fallback` unless it names
/// its own frame.
void AddFrame(SdfContext& c, const std::string& name, pugi::xml_node element,
              const std::string& prefix, const std::string& fallback) {
  SdfFrame f;
  f.line = c.xml.Line(element);
  std::string rel;
  ReadPose(c.xml, element, &f.R, &f.p, &rel);
  f.relative_to =
      rel.empty() ? fallback : (rel == "__model__" ? prefix + "__model__" : prefix + rel);
  if (!c.frames.emplace(name, f).second) {
    c.xml.Fail(element, fmt::format("a second frame named '{}'", name));
  }
}

/// The pose of frame `name` in the top model's frame, following relative_to.
const SdfFrame& Resolve(SdfContext& c, const std::string& name, int line) {
  const auto it = c.frames.find(name);
  if (it == c.frames.end()) c.xml.Fail(line, fmt::format("no frame named '{}'", name));
  SdfFrame& f = it->second;
  if (f.resolved) return f;
  if (f.visiting) c.xml.Fail(f.line, fmt::format("the poses of frame '{}' form a cycle", name));
  f.visiting = true;
  if (f.relative_to.empty()) {
    f.R_M = f.R;
    f.p_M = f.p;
  } else {
    const SdfFrame& base = Resolve(c, f.relative_to, f.line);
    f.R_M = base.R_M * f.R;
    f.p_M = base.p_M + base.R_M * f.p;
  }
  f.visiting = false;
  f.resolved = true;
  return f;
}

RobotInertial ReadInertial(const XmlFile& xml, pugi::xml_node e) {
  RobotInertial in;
  in.line = xml.Line(e);
  in.text.element_begin = xml.Begin(e);
  in.text.start_tag_end = xml.StartTagEnd(e);
  std::string rel;
  ReadPose(xml, e, &in.R_LI, &in.p_LoLcm_L, &rel);
  if (!rel.empty())
    xml.Fail(e.child("pose"), "an inertial's pose relative_to another frame is not read");
  in.text.position = xml.TextSpanOf(e.child("pose"));
  // SDF's defaults: mass 1, diagonal moments 1, products 0.
  in.mass = 1.0;
  if (const pugi::xml_node m = e.child("mass")) {
    in.mass = xml.TextNumbers(m, 1)[0];
    in.mass_line = xml.Line(m);
    in.text.mass = xml.TextSpanOf(m);
  }
  static constexpr const char* kKeys[6] = {"ixx", "iyy", "izz", "ixy", "ixz", "iyz"};
  double v[6] = {1, 1, 1, 0, 0, 0};
  if (const pugi::xml_node I = e.child("inertia")) {
    in.inertia_line = xml.Line(I);
    for (int k = 0; k < 6; ++k) {
      if (const pugi::xml_node n = I.child(kKeys[k])) {
        v[k] = xml.TextNumbers(n, 1)[0];
        in.text.entries[k] = xml.TextSpanOf(n);
      }
    }
  }
  in.I_LcmI_I << v[0], v[3], v[4], v[3], v[1], v[5], v[4], v[5], v[2];
  return in;
}

/// The <geometry> of a <collision> or <visual>; false for one without volume.
bool ReadGeometry(SdfContext& c, pugi::xml_node e, GeometrySet set, RobotGeometry* g) {
  const XmlFile& xml = c.xml;
  g->set = set;
  g->line = xml.Line(e);
  std::string rel;
  ReadPose(xml, e, &g->R_LG, &g->p_LoGo_L, &rel);
  if (!rel.empty())
    xml.Fail(e.child("pose"), "a geometry's pose relative_to another frame is not read");
  const pugi::xml_node geometry = e.child("geometry");
  if (!geometry) xml.Fail(e, fmt::format("<{}> needs a <geometry>", e.name()));
  const pugi::xml_node shape = geometry.first_child();
  if (!shape || shape.type() != pugi::node_element) xml.Fail(geometry, "<geometry> needs a shape");
  const std::string type = shape.name();
  auto number = [&](const char* key) {
    const pugi::xml_node n = shape.child(key);
    if (!n) xml.Fail(shape, fmt::format("<{}> needs <{}>", type, key));
    return xml.TextNumbers(n, 1)[0];
  };
  if (type == "box") {
    g->type = GeometryType::kBox;
    if (!shape.child("size")) xml.Fail(shape, "<box> needs <size>");
    const std::vector<double> s = xml.TextNumbers(shape.child("size"), 3);
    g->size = Vec3(s[0], s[1], s[2]);
  } else if (type == "cylinder" || type == "capsule") {
    g->type = type == "cylinder" ? GeometryType::kCylinder : GeometryType::kCapsule;
    g->size = Vec3(number("radius"), number("length"), 1.0);
  } else if (type == "sphere") {
    g->type = GeometryType::kSphere;
    g->size = Vec3(number("radius"), 1.0, 1.0);
  } else if (type == "ellipsoid") {
    g->type = GeometryType::kEllipsoid;
    if (!shape.child("radii")) xml.Fail(shape, "<ellipsoid> needs <radii>");
    const std::vector<double> s = xml.TextNumbers(shape.child("radii"), 3);
    g->size = Vec3(s[0], s[1], s[2]);
  } else if (type == "mesh") {
    g->type = GeometryType::kMesh;
    g->mesh_uri = shape.child("uri").text().get();
    if (g->mesh_uri.empty()) xml.Fail(shape, "<mesh> needs a <uri>");
    // model://NAME/PATH is found as ROS finds package://NAME/PATH.
    if (g->mesh_uri.starts_with("model://")) g->mesh_uri = "package://" + g->mesh_uri.substr(8);
    if (const pugi::xml_node s = shape.child("scale")) {
      const std::vector<double> v = xml.TextNumbers(s, 3);
      g->mesh_scale = Vec3(v[0], v[1], v[2]);
    }
    ResolveMesh(*g, xml, "", c.options);
    return true;
  } else {
    if (type != "plane" && type != "empty") {
      c.model.warnings.push_back(
          fmt::format("{}:{}: geometry <{}> is not read", xml.name(), xml.Line(shape), type));
    }
    return false;
  }
  CheckGeometrySize(*g, xml, shape);
  return true;
}

void ReadLink(SdfContext& c, pugi::xml_node e, const std::string& prefix) {
  const XmlFile& xml = c.xml;
  RobotLink link;
  link.name = Scoped(prefix, e.attribute("name").value());
  link.line = xml.Line(e);
  for (pugi::xml_node k = e.first_child(); k; k = k.next_sibling()) {
    const std::string tag = k.name();
    if (tag == "inertial") {
      if (link.has_inertial) xml.Fail(k, "a second <inertial> in one link");
      link.has_inertial = true;
      link.inertial = ReadInertial(xml, k);
    } else if (tag == "collision" || tag == "visual") {
      CheckCount(link.geometries.size() + 1, xml, k, "geometries in a link");
      RobotGeometry g;
      const GeometrySet set = tag == "visual" ? GeometrySet::kVisual : GeometrySet::kCollision;
      if (ReadGeometry(c, k, set, &g)) link.geometries.push_back(std::move(g));
    }
  }
  AddFrame(c, link.name, e, prefix, prefix + "__model__");
  c.links.Add(c.model, std::move(link), xml);
}

void ReadModel(SdfContext& c, pugi::xml_node model, const std::string& prefix) {
  const XmlFile& xml = c.xml;
  for (pugi::xml_node e = model.first_child(); e; e = e.next_sibling()) {
    const std::string tag = e.name();
    if (tag == "include") xml.Fail(e, "<include> is not read: give the model with it merged");
    if (tag == "link") {
      ReadLink(c, e, prefix);
    } else if (tag == "joint") {
      CheckCount(c.joints.size() + 1, xml, e, "joints");
      c.joints.emplace_back(e, prefix);
    } else if (tag == "frame") {
      const std::string attached = e.attribute("attached_to").value();
      AddFrame(c, Scoped(prefix, e.attribute("name").value()), e, prefix,
               attached.empty() ? prefix + "__model__" : Scoped(prefix, attached));
    } else if (tag == "model") {
      const std::string inner = prefix + e.attribute("name").value() + "::";
      AddFrame(c, inner + "__model__", e, prefix, prefix + "__model__");
      ReadModel(c, e, inner);
    }
  }
}

/// A joint of scope `prefix`; false for a joint to the world (which only places the model).
bool ReadJoint(SdfContext& c, pugi::xml_node e, const std::string& prefix, RobotJoint* j) {
  const XmlFile& xml = c.xml;
  j->name = Scoped(prefix, e.attribute("name").value());
  j->line = xml.Line(e);
  const std::string type = e.attribute("type").value();
  const std::map<std::string, JointType> types = {{"fixed", JointType::kFixed},
                                                  {"revolute", JointType::kRevolute},
                                                  {"continuous", JointType::kContinuous},
                                                  {"prismatic", JointType::kPrismatic},
                                                  {"ball", JointType::kBall},
                                                  {"universal", JointType::kBall},
                                                  {"revolute2", JointType::kBall},
                                                  {"screw", JointType::kRevolute}};
  if (!types.count(type)) xml.Fail(e, fmt::format("joint type '{}' is not one of SDF's", type));
  j->type = types.at(type);
  const std::string parent = e.child("parent").text().get();
  const std::string child = e.child("child").text().get();
  if (parent.empty() || child.empty()) xml.Fail(e, "a joint needs <parent> and <child>");
  const std::string child_name = Scoped(prefix, child);
  AddFrame(c, j->name, e, prefix, child_name);
  if (parent == "world") return false;
  j->parent = c.links.Find(Scoped(prefix, parent), xml, j->line, "joint '" + j->name + "' parent");
  j->child = c.links.Find(child_name, xml, j->line, "joint '" + j->name + "' child");
  if (const pugi::xml_node axis = e.child("axis")) {
    const pugi::xml_node xyz = axis.child("xyz");
    Vec3 a = Vec3::UnitZ();
    if (xyz) {
      const std::vector<double> v = xml.TextNumbers(xyz, 3);
      a = Vec3(v[0], v[1], v[2]);
      if (!(a.norm() > 0.0)) xml.Fail(xyz, "a zero axis");
      const std::string in = xyz.attribute("expressed_in").value();
      if (!in.empty()) {
        const std::string frame = in == "__model__" ? prefix + "__model__" : Scoped(prefix, in);
        const SdfFrame& f = Resolve(c, frame, j->line);
        a = Resolve(c, j->name, j->line).R_M.transpose() * f.R_M * a;
      }
    }
    j->axis = a.normalized();
    if (const pugi::xml_node limit = axis.child("limit")) {
      if (limit.child("lower")) j->lower = xml.TextNumbers(limit.child("lower"), 1)[0];
      if (limit.child("upper")) j->upper = xml.TextNumbers(limit.child("upper"), 1)[0];
    }
  }
  return true;
}

}  // namespace

RobotModel ReadSdf(const XmlFile& xml, const RobotReadOptions& options) {
  RobotModel model;
  model.format = RobotFormat::kSdf;
  pugi::xml_node top = xml.root().child("model");
  if (!top) {
    const pugi::xml_node world = xml.root().child("world");
    if (world) top = world.child("model");
    if (top && top.next_sibling("model")) {
      xml.Fail(top.next_sibling("model"), "a world of several models: give one model");
    }
  }
  if (!top) xml.Fail(xml.root(), "no <model>");
  model.name = top.attribute("name").value();
  SdfContext c(xml, options, model);
  SdfFrame model_frame;
  model_frame.line = xml.Line(top);
  c.frames["__model__"] = model_frame;
  ReadModel(c, top, "");
  for (const auto& [e, prefix] : c.joints) {
    RobotJoint j;
    if (!ReadJoint(c, e, prefix, &j)) continue;
    // X_PJ = X_MP⁻¹ X_MJ and X_JC = X_MJ⁻¹ X_MC, from the poses in the model frame M.
    const SdfFrame& P = Resolve(c, model.links[j.parent].name, j.line);
    const SdfFrame& J = Resolve(c, j.name, j.line);
    const SdfFrame& C = Resolve(c, model.links[j.child].name, j.line);
    j.R_PJ = P.R_M.transpose() * J.R_M;
    j.p_PoJo_P = P.R_M.transpose() * (J.p_M - P.p_M);
    j.R_JC = J.R_M.transpose() * C.R_M;
    j.p_JoCo_J = J.R_M.transpose() * (C.p_M - J.p_M);
    model.joints.push_back(std::move(j));
  }
  // Every frame resolves (a cycle of relative_to is an error even where nothing uses it).
  for (const auto& [name, frame] : c.frames) Resolve(c, name, frame.line);
  CheckTree(model, xml);
  return model;
}

}  // namespace chasles::internal
