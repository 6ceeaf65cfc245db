#pragma once
/// @file
/// Reading robot descriptions: URDF, MJCF (MuJoCo) and SDF (SDFormat), told apart by their
/// root element (<robot>, <mujoco>, <sdf>), by readers as strict as the mesh readers
/// (docs/audit.md, "Reading robot files"): every number finite and within ±1e18, every
/// reference resolved (a joint's links, an MJCF class or mesh asset), the links a tree
/// (no cycle, one parent each, one root), mesh URIs confined to their package, sizes and
/// depths capped. Every error is an InputError "FILE:LINE: WHAT".

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "chasles/files/robot_model.h"

namespace chasles {

/// Options of the robot readers.
struct RobotReadOptions {
  /// Packages by name (`--package NAME=DIR`), searched before the folders above the file.
  std::vector<std::pair<std::string, std::string>> packages;
  /// Largest file read [bytes].
  std::size_t max_bytes = std::size_t{64} << 20;
};

/// Most links, joints or geometries a robot file may hold.
inline constexpr std::size_t kMaxRobotElements = 100000;

/// Reads the robot description in `path`.
RobotModel ReadRobotFile(const std::string& path, const RobotReadOptions& options = {});

/// The same from bytes in memory: `name` is the file's name in errors and the place relative
/// mesh paths are resolved from (no other file is read: meshes are resolved, not opened).
RobotModel ReadRobotBytes(std::string bytes, const std::string& name,
                          const RobotReadOptions& options = {});

/// True for names chasles reads as robot files (.urdf, .sdf, .xml, .mjcf; any case).
bool IsRobotFileName(const std::string& path);

}  // namespace chasles
