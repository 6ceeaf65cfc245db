// Reading robot descriptions (chasles/files/robot_reader.h): the dispatch on the root element
// and what the three readers share.

#include "chasles/files/robot_reader.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <limits>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/math/rotation.h"
#include "files/internal/package_path.h"
#include "files/internal/robot_readers.h"

namespace chasles {

const char* RobotFormatName(RobotFormat format) {
  switch (format) {
    case RobotFormat::kUrdf:
      return "URDF";
    case RobotFormat::kMjcf:
      return "MJCF";
    case RobotFormat::kSdf:
      return "SDF";
  }
  return "?";
}

const char* GeometryTypeName(GeometryType type) {
  switch (type) {
    case GeometryType::kBox:
      return "box";
    case GeometryType::kCylinder:
      return "cylinder";
    case GeometryType::kSphere:
      return "sphere";
    case GeometryType::kCapsule:
      return "capsule";
    case GeometryType::kEllipsoid:
      return "ellipsoid";
    case GeometryType::kMesh:
      return "mesh";
  }
  return "?";
}

const char* GeometrySetName(GeometrySet set) {
  return set == GeometrySet::kCollision ? "collision" : "visual";
}

namespace internal {

std::size_t LinkIndex::Add(RobotModel& model, RobotLink link, const XmlFile& xml) {
  if (link.name.empty()) xml.Fail(link.line, "a link without a name");
  if (by_name_.count(link.name)) {
    xml.Fail(link.line, fmt::format("a second link named '{}' (the first is on line {})", link.name,
                                    model.links[by_name_.at(link.name)].line));
  }
  if (model.links.size() >= kMaxRobotElements) {
    xml.Fail(link.line, fmt::format("more than {} links", kMaxRobotElements));
  }
  by_name_[link.name] = model.links.size();
  model.links.push_back(std::move(link));
  return model.links.size() - 1;
}

std::size_t LinkIndex::Find(const std::string& name, const XmlFile& xml, int line,
                            const std::string& what) const {
  const auto it = by_name_.find(name);
  if (it == by_name_.end()) xml.Fail(line, fmt::format("{}: no link named '{}'", what, name));
  return it->second;
}

void CheckTree(RobotModel& model, const XmlFile& xml) {
  if (model.links.empty() && model.format == RobotFormat::kSdf) {
    // sdformat drops the massless links of a URDF it converts: a model may be left empty.
    model.warnings.push_back(fmt::format("{}: the model has no link", xml.name()));
    return;
  }
  if (model.links.empty()) xml.Fail(xml.Line(xml.root()), "the robot has no link");
  const std::size_t n = model.links.size();
  std::vector<std::size_t> parent_joint(n, n + model.joints.size());
  const std::size_t none = n + model.joints.size();
  for (std::size_t j = 0; j < model.joints.size(); ++j) {
    const RobotJoint& joint = model.joints[j];
    if (joint.parent == joint.child) {
      xml.Fail(joint.line, fmt::format("joint '{}' joins link '{}' to itself", joint.name,
                                       model.links[joint.child].name));
    }
    if (parent_joint[joint.child] != none) {
      xml.Fail(
          joint.line,
          fmt::format("link '{}' is the child of two joints, '{}' (line {}) and '{}': the "
                      "links must form a tree",
                      model.links[joint.child].name, model.joints[parent_joint[joint.child]].name,
                      model.joints[parent_joint[joint.child]].line, joint.name));
    }
    parent_joint[joint.child] = j;
  }
  // A cycle: following parents from a link comes back to it (at most n steps from any link).
  for (std::size_t start = 0; start < n; ++start) {
    std::size_t at = start;
    for (std::size_t steps = 0; parent_joint[at] != none; ++steps) {
      if (steps > n) {
        const RobotJoint& j = model.joints[parent_joint[start]];
        xml.Fail(j.line, fmt::format("the joints form a cycle through link '{}': the links "
                                     "must form a tree",
                                     model.links[start].name));
      }
      at = model.joints[parent_joint[at]].parent;
    }
  }
  std::vector<std::size_t> roots;
  for (std::size_t i = 0; i < n; ++i) {
    if (parent_joint[i] == none) roots.push_back(i);
  }
  if (roots.size() != 1) {
    xml.Fail(model.links[roots[1]].line,
             fmt::format("links '{}' and '{}' are both roots (no joint has them as its child): "
                         "the links must form one tree",
                         model.links[roots[0]].name, model.links[roots[1]].name));
  }
  model.root = roots[0];
}

void CheckCount(std::size_t count, const XmlFile& xml, pugi::xml_node node, const char* what) {
  if (count > kMaxRobotElements) {
    xml.Fail(node, fmt::format("more than {} {}", kMaxRobotElements, what));
  }
}

void ResolveMesh(RobotGeometry& g, const XmlFile& xml, const std::string& base_dir,
                 const RobotReadOptions& options) {
  const ResolvedPath r = ResolveUri(g.mesh_uri, xml.name(), base_dir, options.packages,
                                    [&](const std::string& why) { xml.Fail(g.line, why); });
  g.mesh_path = r.path;
  g.mesh_problem = r.problem;
}

void CheckGeometrySize(RobotGeometry& g, const XmlFile& xml, pugi::xml_node node) {
  const int used = g.type == GeometryType::kSphere                                         ? 1
                   : g.type == GeometryType::kCylinder || g.type == GeometryType::kCapsule ? 2
                                                                                           : 3;
  static constexpr const char* kNames[4][3] = {{"radius", "", ""},
                                               {"radius", "length", ""},
                                               {"size x", "size y", "size z"},
                                               {"semi-axis x", "semi-axis y", "semi-axis z"}};
  const int row = used == 1 ? 0 : used == 2 ? 1 : g.type == GeometryType::kBox ? 2 : 3;
  for (int k = 0; k < used; ++k) {
    if (!(g.size[k] > 0.0)) {
      xml.Fail(node, fmt::format("{} {}: {} must be positive", GeometryTypeName(g.type),
                                 kNames[row][k], g.size[k]));
    }
  }
  for (int k = used; k < 3; ++k) g.size[k] = std::numeric_limits<double>::quiet_NaN();
}

Mat3 RotationFromRpy(const Vec3& rpy) {
  // Extrinsic x-y-z: R = Rz(yaw) Ry(pitch) Rx(roll), URDF's and SDF's convention.
  return RotationFromEuler("xyz", rpy);
}

}  // namespace internal

bool IsRobotFileName(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".urdf" || ext == ".sdf" || ext == ".xml" || ext == ".mjcf";
}

RobotModel ReadRobotBytes(std::string bytes, const std::string& name,
                          const RobotReadOptions& options) {
  if (bytes.size() > options.max_bytes) {
    throw InputError(fmt::format("robot file '{}': {} bytes, larger than the limit of {} bytes",
                                 name, bytes.size(), options.max_bytes));
  }
  const internal::XmlFile xml(bytes, name);
  const std::string root = xml.root().name();
  RobotModel model;
  if (root == "robot") {
    model = internal::ReadUrdf(xml, options);
  } else if (root == "mujoco") {
    model = internal::ReadMjcf(xml, options);
  } else if (root == "sdf") {
    model = internal::ReadSdf(xml, options);
  } else {
    xml.Fail(xml.root(), fmt::format("root element <{}>: a robot file starts with <robot> "
                                     "(URDF), <mujoco> (MJCF) or <sdf> (SDF)",
                                     root));
  }
  model.file = name;
  model.text = std::move(bytes);
  return model;
}

RobotModel ReadRobotFile(const std::string& path, const RobotReadOptions& options) {
  return ReadRobotBytes(internal::ReadFileBytes(path, "robot file", options.max_bytes), path,
                        options);
}

}  // namespace chasles
