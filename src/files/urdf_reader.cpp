// The URDF reader (chasles/files/robot_reader.h): <robot> with <link> (<inertial>, <visual>,
// <collision>) and <joint> elements, as urdfdom reads them (wiki.ros.org/urdf/XML).

#include <string>
#include <utility>

#include <fmt/format.h>

#include "files/internal/robot_readers.h"

namespace chasles::internal {

namespace {

/// An <origin xyz rpy> child of `parent`: the pose of the frame it places (identity when
/// absent).
void ReadOrigin(const XmlFile& xml, pugi::xml_node parent, Mat3* R, Vec3* p) {
  const pugi::xml_node o = parent.child("origin");
  *R = Mat3::Identity();
  *p = Vec3::Zero();
  if (!o) return;
  *p = xml.Vector(o, "xyz", Vec3::Zero());
  *R = RotationFromRpy(xml.Vector(o, "rpy", Vec3::Zero()));
}

RobotInertial ReadInertial(const XmlFile& xml, pugi::xml_node e) {
  RobotInertial in;
  in.line = xml.Line(e);
  in.text.element_begin = xml.Begin(e);
  in.text.start_tag_end = xml.StartTagEnd(e);
  ReadOrigin(xml, e, &in.R_LI, &in.p_LoLcm_L);
  if (const pugi::xml_node o = e.child("origin")) {
    in.text.position = xml.Span(o.attribute("xyz"));
    in.text.orientation = xml.Span(o.attribute("rpy"));
  }
  const pugi::xml_node mass = e.child("mass");
  if (!mass) xml.Fail(e, "<inertial> needs a <mass value=...>");
  in.mass = xml.RequiredNumber(mass, "value");
  in.mass_line = xml.Line(mass);
  in.text.mass = xml.Span(mass.attribute("value"));
  const pugi::xml_node I = e.child("inertia");
  if (!I)
    xml.Fail(e, "<inertial> needs an <inertia ixx=... ixy=... ixz=... iyy=... iyz=... izz=...>");
  in.inertia_line = xml.Line(I);
  static constexpr const char* kKeys[6] = {"ixx", "iyy", "izz", "ixy", "ixz", "iyz"};
  double v[6];
  for (int k = 0; k < 6; ++k) {
    v[k] = xml.RequiredNumber(I, kKeys[k]);
    in.text.entries[k] = xml.Span(I.attribute(kKeys[k]));
  }
  in.I_LcmI_I << v[0], v[3], v[4], v[3], v[1], v[5], v[4], v[5], v[2];
  return in;
}

/// The geometry of a <visual> or <collision> element; false for a type chasles does not know
/// (said in the model's warnings).
bool ReadGeometry(const XmlFile& xml, pugi::xml_node e, GeometrySet set, RobotGeometry* g,
                  RobotModel& model, const RobotReadOptions& options) {
  const pugi::xml_node geometry = e.child("geometry");
  if (!geometry) xml.Fail(e, fmt::format("<{}> needs a <geometry>", e.name()));
  const pugi::xml_node shape = geometry.first_child();
  if (!shape || shape.type() != pugi::node_element) {
    xml.Fail(geometry, "<geometry> needs a shape: <box>, <cylinder>, <sphere> or <mesh>");
  }
  g->set = set;
  g->line = xml.Line(shape);
  ReadOrigin(xml, e, &g->R_LG, &g->p_LoGo_L);
  const std::string type = shape.name();
  if (type == "box") {
    g->type = GeometryType::kBox;
    g->size = xml.Vector(shape, "size", Vec3::Constant(-1));
  } else if (type == "cylinder" || type == "capsule") {
    g->type = type == "cylinder" ? GeometryType::kCylinder : GeometryType::kCapsule;
    g->size = Vec3(xml.RequiredNumber(shape, "radius"), xml.RequiredNumber(shape, "length"), 0.0);
  } else if (type == "sphere") {
    g->type = GeometryType::kSphere;
    g->size = Vec3(xml.RequiredNumber(shape, "radius"), 0.0, 0.0);
  } else if (type == "mesh") {
    g->type = GeometryType::kMesh;
    g->mesh_uri = xml.RequiredText(shape, "filename");
    g->mesh_scale = xml.Vector(shape, "scale", Vec3::Ones());
    ResolveMesh(*g, xml, "", options);
    return true;
  } else {
    model.warnings.push_back(
        fmt::format("{}:{}: geometry <{}> is not read (box, cylinder, "
                    "sphere, capsule and mesh are)",
                    xml.name(), g->line, type));
    return false;
  }
  CheckGeometrySize(*g, xml, shape);
  return true;
}

RobotLink ReadLink(const XmlFile& xml, pugi::xml_node e, RobotModel& model,
                   const RobotReadOptions& options) {
  RobotLink link;
  link.name = e.attribute("name").value();
  link.line = xml.Line(e);
  std::size_t inertials = 0;
  for (pugi::xml_node c = e.first_child(); c; c = c.next_sibling()) {
    const std::string tag = c.name();
    if (tag == "inertial") {
      if (++inertials > 1) xml.Fail(c, fmt::format("link '{}' has two <inertial>", link.name));
      link.has_inertial = true;
      link.inertial = ReadInertial(xml, c);
    } else if (tag == "visual" || tag == "collision") {
      CheckCount(link.geometries.size() + 1, xml, c, "geometries in a link");
      RobotGeometry g;
      const GeometrySet set = tag == "visual" ? GeometrySet::kVisual : GeometrySet::kCollision;
      if (ReadGeometry(xml, c, set, &g, model, options)) link.geometries.push_back(std::move(g));
    }
  }
  return link;
}

JointType UrdfJointType(const XmlFile& xml, pugi::xml_node e) {
  const std::string type = e.attribute("type").value();
  if (type == "fixed") return JointType::kFixed;
  if (type == "revolute") return JointType::kRevolute;
  if (type == "continuous") return JointType::kContinuous;
  if (type == "prismatic") return JointType::kPrismatic;
  if (type == "floating") return JointType::kFloating;
  if (type == "planar") return JointType::kPlanar;
  xml.Fail(e, fmt::format("joint type '{}': expected fixed, revolute, continuous, prismatic, "
                          "floating or planar",
                          type));
}

RobotJoint ReadJoint(const XmlFile& xml, pugi::xml_node e, const LinkIndex& links) {
  RobotJoint j;
  j.name = e.attribute("name").value();
  j.line = xml.Line(e);
  if (j.name.empty()) xml.Fail(e, "a joint without a name");
  j.type = UrdfJointType(xml, e);
  const pugi::xml_node parent = e.child("parent"), child = e.child("child");
  if (!parent || !child) {
    xml.Fail(e, fmt::format("joint '{}' needs <parent link=...> and <child link=...>", j.name));
  }
  j.parent = links.Find(parent.attribute("link").value(), xml, xml.Line(parent),
                        fmt::format("joint '{}' parent", j.name));
  j.child = links.Find(child.attribute("link").value(), xml, xml.Line(child),
                       fmt::format("joint '{}' child", j.name));
  ReadOrigin(xml, e, &j.R_PJ, &j.p_PoJo_P);
  if (const pugi::xml_node axis = e.child("axis")) {
    const Vec3 a = xml.Vector(axis, "xyz", Vec3::UnitX());
    if (!(a.norm() > 0.0)) xml.Fail(axis, fmt::format("joint '{}': a zero axis", j.name));
    j.axis = a.normalized();
  }
  if (const pugi::xml_node limit = e.child("limit")) {
    j.lower = xml.Number(limit, "lower", 0.0);
    j.upper = xml.Number(limit, "upper", 0.0);
  }
  return j;
}

}  // namespace

RobotModel ReadUrdf(const XmlFile& xml, const RobotReadOptions& options) {
  RobotModel model;
  model.format = RobotFormat::kUrdf;
  const pugi::xml_node robot = xml.root();
  model.name = robot.attribute("name").value();
  LinkIndex links;
  for (pugi::xml_node e = robot.child("link"); e; e = e.next_sibling("link")) {
    links.Add(model, ReadLink(xml, e, model, options), xml);
  }
  for (pugi::xml_node e = robot.child("joint"); e; e = e.next_sibling("joint")) {
    CheckCount(model.joints.size() + 1, xml, e, "joints");
    model.joints.push_back(ReadJoint(xml, e, links));
  }
  CheckTree(model, xml);
  return model;
}

}  // namespace chasles::internal
