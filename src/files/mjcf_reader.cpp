// The MJCF reader (chasles/files/robot_reader.h): <mujoco> with <compiler>, <default> classes,
// <asset> meshes and the <worldbody> tree of <body> elements with their <inertial>, <joint>
// and <geom> (mujoco.readthedocs.io, "XML Reference"; MuJoCo 2.2's defaults).

#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "chasles/math/rotation.h"
#include "files/internal/robot_readers.h"

namespace chasles::internal {

namespace {

/// What <compiler> says, and the default classes.
struct MjcfContext {
  MjcfContext(const XmlFile& x, const RobotReadOptions& o) : xml(x), options(o) {}
  const XmlFile& xml;
  const RobotReadOptions& options;
  bool degrees = true;           // angle="degree" (MuJoCo's default)
  std::string eulerseq = "xyz";  // MuJoCo: lower case rotates with the frame
  std::string meshdir;           // meshdir, or assetdir, relative to the file's folder
  /// Per class: its parent class ("" for main) and its element defaults by tag.
  std::map<std::string, std::pair<std::string, std::map<std::string, pugi::xml_node>>> classes;
  /// Mesh assets by name: the <mesh> element.
  std::map<std::string, pugi::xml_node> meshes;
};

/// The attribute `key` of `e` (a <tag> of class `cls`), from `e` itself or its class chain.
pugi::xml_attribute Lookup(const MjcfContext& c, pugi::xml_node e, const std::string& cls,
                           const char* key) {
  if (pugi::xml_attribute a = e.attribute(key)) return a;
  std::string at = cls;
  for (std::size_t guard = 0; guard <= c.classes.size(); ++guard) {
    const auto it = c.classes.find(at);
    if (it == c.classes.end()) break;
    const auto& elements = it->second.second;
    const auto d = elements.find(e.name());
    if (d != elements.end()) {
      if (pugi::xml_attribute a = d->second.attribute(key)) return a;
    }
    if (at.empty()) break;
    at = it->second.first;
  }
  return {};
}

void ReadDefaults(MjcfContext& c, pugi::xml_node d, const std::string& parent, int depth) {
  // The top <default> is class "main" (key ""); nested ones name their class.
  const std::string name = d.attribute("class") ? d.attribute("class").value() : "main";
  const std::string key = depth == 0 && name == "main" ? "" : name;
  if (!key.empty() && c.classes.count(key)) {
    c.xml.Fail(d, fmt::format("a second default class '{}'", name));
  }
  auto& entry = c.classes[key];
  entry.first = parent;
  for (pugi::xml_node e = d.first_child(); e; e = e.next_sibling()) {
    if (e.type() != pugi::node_element) continue;
    if (std::string(e.name()) == "default") {
      if (!e.attribute("class")) c.xml.Fail(e, "a nested <default> needs a class");
      ReadDefaults(c, e, key, depth + 1);
    } else {
      entry.second[e.name()] = e;
    }
  }
}

/// An orientation given by quat, axisangle, euler, xyaxes or zaxis (at most one).
Mat3 Orientation(const MjcfContext& c, pugi::xml_node e, std::string* key = nullptr) {
  const XmlFile& xml = c.xml;
  int given = 0;
  Mat3 R = Mat3::Identity();
  const double unit = c.degrees ? M_PI / 180.0 : 1.0;
  if (e.attribute("quat")) {
    ++given;
    const std::vector<double> q = xml.Numbers(e, "quat", 4);
    const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!(n > 0.0)) xml.Fail(e, "quat: a zero quaternion");
    R = Quat(q[0] / n, q[1] / n, q[2] / n, q[3] / n).toRotationMatrix();
    if (key) *key = "quat";
  }
  if (e.attribute("axisangle")) {
    ++given;
    const std::vector<double> a = xml.Numbers(e, "axisangle", 4);
    if (!(Vec3(a[0], a[1], a[2]).norm() > 0.0)) xml.Fail(e, "axisangle: a zero axis");
    R = RotationFromAxisAngle(Vec3(a[0], a[1], a[2]), a[3] * unit);
    if (key) *key = "axisangle";
  }
  if (e.attribute("euler")) {
    ++given;
    // MuJoCo's lower case turns with the frame (intrinsic), chasles' upper case does.
    std::string seq = c.eulerseq;
    for (char& ch : seq) ch = std::islower(ch) ? std::toupper(ch) : std::tolower(ch);
    R = RotationFromEuler(seq, xml.Vector(e, "euler", Vec3::Zero()) * unit);
    if (key) *key = "euler";
  }
  if (e.attribute("xyaxes")) {
    ++given;
    const std::vector<double> v = xml.Numbers(e, "xyaxes", 6);
    const Vec3 x = Vec3(v[0], v[1], v[2]);
    Vec3 y = Vec3(v[3], v[4], v[5]);
    y -= x.dot(y) / x.squaredNorm() * x;
    if (!(x.norm() > 0.0) || !(y.norm() > 1e-12 * x.norm())) xml.Fail(e, "xyaxes: degenerate axes");
    R.col(0) = x.normalized();
    R.col(1) = y.normalized();
    R.col(2) = R.col(0).cross(R.col(1));
    if (key) *key = "xyaxes";
  }
  if (e.attribute("zaxis")) {
    ++given;
    const Vec3 z = xml.Vector(e, "zaxis", Vec3::UnitZ());
    if (!(z.norm() > 0.0)) xml.Fail(e, "zaxis: a zero axis");
    R = RotationTakingZTo(z);
    if (key) *key = "zaxis";
  }
  if (given > 1) {
    xml.Fail(e, "more than one of quat, axisangle, euler, xyaxes and zaxis: give one orientation");
  }
  return R;
}

RobotInertial ReadInertial(const MjcfContext& c, pugi::xml_node e) {
  const XmlFile& xml = c.xml;
  RobotInertial in;
  in.line = in.mass_line = in.inertia_line = xml.Line(e);
  in.text.element_begin = xml.Begin(e);
  in.text.start_tag_end = xml.StartTagEnd(e);
  if (!e.attribute("pos")) xml.Fail(e, "<inertial> needs pos");
  in.p_LoLcm_L = xml.Vector(e, "pos", Vec3::Zero());
  in.text.position = xml.Span(e.attribute("pos"));
  in.R_LI = Orientation(c, e, &in.text.orientation_key);
  if (!in.text.orientation_key.empty()) {
    in.text.orientation = xml.Span(e.attribute(in.text.orientation_key.c_str()));
  }
  in.mass = xml.RequiredNumber(e, "mass");
  in.text.mass = xml.Span(e.attribute("mass"));
  if (e.attribute("fullinertia")) {
    if (e.attribute("diaginertia")) xml.Fail(e, "both diaginertia and fullinertia: give one");
    if (!in.text.orientation_key.empty()) {
      xml.Fail(e, "fullinertia with an orientation: MuJoCo refuses both (give one)");
    }
    const std::vector<double> v = xml.Numbers(e, "fullinertia", 6);
    in.I_LcmI_I << v[0], v[3], v[4], v[3], v[1], v[5], v[4], v[5], v[2];
    in.text.mjcf_inertia = xml.Span(e.attribute("fullinertia"));
    in.text.mjcf_full = true;
  } else if (e.attribute("diaginertia")) {
    in.I_LcmI_I = xml.Vector(e, "diaginertia", Vec3::Zero()).asDiagonal();
    in.text.mjcf_inertia = xml.Span(e.attribute("diaginertia"));
  } else {
    xml.Fail(e, "<inertial> needs diaginertia or fullinertia");
  }
  return in;
}

/// A geom's type, size and placement; false for one without volume (plane, height field).
bool ReadGeom(const MjcfContext& c, pugi::xml_node e, const std::string& cls, RobotGeometry* g,
              RobotModel& model) {
  const XmlFile& xml = c.xml;
  g->line = xml.Line(e);
  const std::string type = Lookup(c, e, cls, "type") ? Lookup(c, e, cls, "type").value() : "sphere";
  const pugi::xml_attribute contype = Lookup(c, e, cls, "contype");
  const pugi::xml_attribute conaffinity = Lookup(c, e, cls, "conaffinity");
  const bool visual_only =
      contype && conaffinity && contype.as_int() == 0 && conaffinity.as_int() == 0;
  g->set = visual_only ? GeometrySet::kVisual : GeometrySet::kCollision;
  std::vector<double> size;
  if (const pugi::xml_attribute a = Lookup(c, e, cls, "size")) {
    size = xml.ParseNumbers(a.value(), xml.Line(a) > 0 ? xml.Line(a) : g->line, "<geom size>", 0);
  }
  size.resize(3, 0.0);
  g->p_LoGo_L = xml.Vector(e, "pos", Vec3::Zero());
  g->R_LG = Orientation(c, e);
  double half = size[1];
  if (e.attribute("fromto") && type != "mesh") {
    const std::vector<double> f = xml.Numbers(e, "fromto", 6);
    const Vec3 a(f[0], f[1], f[2]), b(f[3], f[4], f[5]);
    if (!((b - a).norm() > 0.0)) xml.Fail(e, "fromto: the two ends coincide");
    g->p_LoGo_L = (a + b) / 2;
    g->R_LG = RotationTakingZTo(b - a);
    half = (b - a).norm() / 2;
  }
  if (type == "sphere") {
    g->type = GeometryType::kSphere;
    g->size = Vec3(size[0], 0, 0);
  } else if (type == "capsule" || type == "cylinder") {
    g->type = type == "capsule" ? GeometryType::kCapsule : GeometryType::kCylinder;
    g->size = Vec3(size[0], 2 * half, 0);
  } else if (type == "box") {
    g->type = GeometryType::kBox;
    g->size = 2 * Vec3(size[0], size[1], size[2]);
  } else if (type == "ellipsoid") {
    g->type = GeometryType::kEllipsoid;
    g->size = Vec3(size[0], size[1], size[2]);
  } else if (type == "mesh") {
    g->type = GeometryType::kMesh;
    const std::string name = Lookup(c, e, cls, "mesh").value();
    const auto it = c.meshes.find(name);
    if (it == c.meshes.end()) xml.Fail(e, fmt::format("geom mesh '{}': no such mesh asset", name));
    g->mesh_uri = it->second.attribute("file").value();
    g->mesh_scale = xml.Vector(it->second, "scale", Vec3::Ones());
    ResolveMesh(*g, xml, c.meshdir, c.options);
    return true;
  } else if (type == "plane" || type == "hfield" || type == "sdf") {
    if (type != "plane") {
      model.warnings.push_back(fmt::format("{}:{}: geom type '{}' has no volume chasles reads",
                                           xml.name(), g->line, type));
    }
    return false;
  } else {
    xml.Fail(e, fmt::format("geom type '{}' is not one of MuJoCo's", type));
  }
  CheckGeometrySize(*g, xml, e);
  return true;
}

/// The joint between `body`'s parent and `body`: the body's first <joint> or <freejoint>.
RobotJoint ReadBodyJoint(const MjcfContext& c, pugi::xml_node body, const std::string& cls,
                         RobotModel& model) {
  const XmlFile& xml = c.xml;
  RobotJoint j;
  j.p_PoJo_P = xml.Vector(body, "pos", Vec3::Zero());
  j.R_PJ = Orientation(c, body);
  j.line = xml.Line(body);
  j.type = JointType::kFixed;
  j.name = std::string(body.attribute("name").value()) + " (fixed)";
  std::size_t joints = 0;
  for (pugi::xml_node e = body.first_child(); e; e = e.next_sibling()) {
    const std::string tag = e.name();
    if (tag != "joint" && tag != "freejoint") continue;
    if (++joints > 1) {
      model.warnings.push_back(
          fmt::format("{}:{}: body '{}' has more than one joint; only the "
                      "first moves with --joint",
                      xml.name(), xml.Line(e), body.attribute("name").value()));
      break;
    }
    j.line = xml.Line(e);
    j.name = e.attribute("name").value();
    if (j.name.empty()) j.name = fmt::format("joint of body '{}'", body.attribute("name").value());
    const std::string jcls = e.attribute("class") ? e.attribute("class").value() : cls;
    const std::string type =
        tag == "freejoint"
            ? "free"
            : (Lookup(c, e, jcls, "type") ? Lookup(c, e, jcls, "type").value() : "hinge");
    j.type = type == "hinge"   ? JointType::kRevolute
             : type == "slide" ? JointType::kPrismatic
             : type == "ball"  ? JointType::kBall
                               : JointType::kFloating;
    if (type != "hinge" && type != "slide" && type != "ball" && type != "free") {
      xml.Fail(e, fmt::format("joint type '{}': expected hinge, slide, ball or free", type));
    }
    j.p_JoA_J = xml.Vector(e, "pos", Vec3::Zero());
    Vec3 a = Vec3::UnitZ();
    if (const pugi::xml_attribute axis = Lookup(c, e, jcls, "axis")) {
      const std::vector<double> v = xml.ParseNumbers(axis.value(), j.line, "<joint axis>", 3);
      a = Vec3(v[0], v[1], v[2]);
    }
    if (!(a.norm() > 0.0)) xml.Fail(e, "joint axis: a zero vector");
    j.axis = a.normalized();
    if (const pugi::xml_attribute range = Lookup(c, e, jcls, "range")) {
      const std::vector<double> r = xml.ParseNumbers(range.value(), j.line, "<joint range>", 2);
      const double unit = (type == "hinge" && c.degrees) ? M_PI / 180.0 : 1.0;
      j.lower = r[0] * unit;
      j.upper = r[1] * unit;
    }
  }
  return j;
}

void ReadBody(MjcfContext& c, pugi::xml_node body, std::size_t parent, const std::string& cls,
              RobotModel& model, LinkIndex& links) {
  const XmlFile& xml = c.xml;
  RobotLink link;
  link.name = body.attribute("name").value();
  link.line = xml.Line(body);
  if (link.name.empty()) link.name = fmt::format("body on line {}", link.line);
  const std::string childclass =
      body.attribute("childclass") ? body.attribute("childclass").value() : cls;
  RobotJoint joint = ReadBodyJoint(c, body, childclass, model);
  for (pugi::xml_node e = body.first_child(); e; e = e.next_sibling()) {
    const std::string tag = e.name();
    if (tag == "inertial") {
      if (link.has_inertial) xml.Fail(e, "a second <inertial> in one body");
      link.has_inertial = true;
      link.inertial = ReadInertial(c, e);
    } else if (tag == "geom") {
      CheckCount(link.geometries.size() + 1, xml, e, "geoms in a body");
      const std::string gcls = e.attribute("class") ? e.attribute("class").value() : childclass;
      if (!gcls.empty() && !c.classes.count(gcls)) {
        xml.Fail(e, fmt::format("class '{}': no such default class", gcls));
      }
      RobotGeometry g;
      if (ReadGeom(c, e, gcls, &g, model)) link.geometries.push_back(std::move(g));
    }
  }
  const std::size_t index = links.Add(model, std::move(link), xml);
  joint.parent = parent;
  joint.child = index;
  CheckCount(model.joints.size() + 1, xml, body, "joints");
  model.joints.push_back(std::move(joint));
  for (pugi::xml_node e = body.child("body"); e; e = e.next_sibling("body")) {
    ReadBody(c, e, index, childclass, model, links);
  }
}

void ReadCompiler(MjcfContext& c, pugi::xml_node compiler, RobotModel& model) {
  const XmlFile& xml = c.xml;
  const std::string angle = compiler.attribute("angle").value();
  if (!angle.empty() && angle != "degree" && angle != "radian") {
    xml.Fail(compiler, fmt::format("angle '{}': expected degree or radian", angle));
  }
  if (!angle.empty()) c.degrees = angle == "degree";
  if (compiler.attribute("eulerseq")) c.eulerseq = compiler.attribute("eulerseq").value();
  const std::string folder = std::filesystem::path(xml.name()).parent_path().string();
  for (const char* key : {"assetdir", "meshdir"}) {
    if (compiler.attribute(key)) {
      const std::filesystem::path dir = compiler.attribute(key).value();
      c.meshdir = (dir.is_absolute() ? dir : std::filesystem::path(folder) / dir).string();
    }
  }
  if (std::string(compiler.attribute("inertiafromgeom").value()) == "true") {
    model.warnings.push_back(fmt::format(
        "{}:{}: inertiafromgeom=\"true\": MuJoCo replaces every body's inertial by one computed "
        "from its geoms, so the inertials written here are not used",
        xml.name(), xml.Line(compiler)));
  }
}

}  // namespace

RobotModel ReadMjcf(const XmlFile& xml, const RobotReadOptions& options) {
  RobotModel model;
  model.format = RobotFormat::kMjcf;
  const pugi::xml_node mujoco = xml.root();
  model.name = mujoco.attribute("model").value();
  MjcfContext c(xml, options);
  c.classes[""];
  if (const pugi::xml_node inc =
          mujoco.find_node([](pugi::xml_node n) { return std::string(n.name()) == "include"; })) {
    xml.Fail(inc, "<include> is not read: give the file with its included parts merged");
  }
  for (pugi::xml_node e = mujoco.child("compiler"); e; e = e.next_sibling("compiler")) {
    ReadCompiler(c, e, model);
  }
  for (pugi::xml_node e = mujoco.child("default"); e; e = e.next_sibling("default")) {
    ReadDefaults(c, e, "", 0);
  }
  for (pugi::xml_node a = mujoco.child("asset"); a; a = a.next_sibling("asset")) {
    for (pugi::xml_node m = a.child("mesh"); m; m = m.next_sibling("mesh")) {
      const std::string file = xml.RequiredText(m, "file");
      std::string name = m.attribute("name").value();
      if (name.empty()) name = std::filesystem::path(file).stem().string();
      if (!c.meshes.emplace(name, m).second) {
        xml.Fail(m, fmt::format("a second mesh asset named '{}'", name));
      }
    }
  }
  const pugi::xml_node world = mujoco.child("worldbody");
  if (!world) xml.Fail(mujoco, "no <worldbody>");
  LinkIndex links;
  RobotLink world_link;
  world_link.name = "world";
  world_link.line = xml.Line(world);
  const std::size_t root = links.Add(model, std::move(world_link), xml);
  for (pugi::xml_node e = world.child("body"); e; e = e.next_sibling("body")) {
    ReadBody(c, e, root, "", model, links);
  }
  CheckTree(model, xml);
  return model;
}

}  // namespace chasles::internal
