#pragma once
/// @file
/// The three robot readers behind ReadRobotFile, and what they share: the kinematic tree's
/// checks and the limits on counts.

#include <cstddef>
#include <map>
#include <string>

#include "chasles/files/robot_model.h"
#include "chasles/files/robot_reader.h"
#include "files/internal/xml_file.h"

namespace chasles::internal {

RobotModel ReadUrdf(const XmlFile& xml, const RobotReadOptions& options);
RobotModel ReadMjcf(const XmlFile& xml, const RobotReadOptions& options);
RobotModel ReadSdf(const XmlFile& xml, const RobotReadOptions& options);

/// Links by name, refusing duplicates and more than kMaxRobotElements.
class LinkIndex {
 public:
  /// Adds `link` to `model`; throws at `line` when its name is empty or taken.
  std::size_t Add(RobotModel& model, RobotLink link, const XmlFile& xml);
  /// The link called `name`; throws at `line` naming `what` ("joint 'j' parent") otherwise.
  std::size_t Find(const std::string& name, const XmlFile& xml, int line,
                   const std::string& what) const;

 private:
  std::map<std::string, std::size_t> by_name_;
};

/// Checks that the joints make the links a tree (each link the child of at most one joint, no
/// cycle, exactly one link that is no joint's child) and sets model.root. Errors name the
/// joint's line.
void CheckTree(RobotModel& model, const XmlFile& xml);

/// Refuses a count beyond kMaxRobotElements at `node`.
void CheckCount(std::size_t count, const XmlFile& xml, pugi::xml_node node, const char* what);

/// The mesh URI of a geometry resolved against `base_dir` (empty: the file's folder) and the
/// options' packages: sets mesh_path or mesh_problem; refuses URIs that escape or name a
/// device (at the geometry's line).
void ResolveMesh(RobotGeometry& g, const XmlFile& xml, const std::string& base_dir,
                 const RobotReadOptions& options);

/// Refuses a primitive whose used dimensions (GeometryType's) are not all positive, at `node`;
/// sets the unused ones to NaN.
void CheckGeometrySize(RobotGeometry& g, const XmlFile& xml, pugi::xml_node node);

/// A rotation from URDF's and SDF's roll, pitch, yaw: R = Rz(y) Ry(p) Rx(r).
Mat3 RotationFromRpy(const Vec3& rpy);

}  // namespace chasles::internal
