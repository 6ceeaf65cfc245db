#pragma once
/// @file
/// Where a mesh URI of a robot file points: `package://NAME/PATH` through the package search
/// path (the packages given, then the folders above the robot file: one named NAME, or one
/// holding a folder NAME, as ROS finds a package in its workspace), `file://` and plain paths
/// relative to the robot file's folder (or MJCF's meshdir). A URI that climbs out of its
/// package, or out of the robot's own tree, or that names a device or anything but a regular
/// file, is an InputError; one that names a file that is not there is not (robot descriptions
/// are often shared without their meshes): it comes back with the reason.

#include <string>
#include <utility>
#include <vector>

namespace chasles::internal {

/// A package given on the command line (`--package NAME=DIR`).
using PackageDirs = std::vector<std::pair<std::string, std::string>>;

/// A resolved URI: the file, or an empty path and why.
struct ResolvedPath {
  std::string path;
  std::string problem;
};

/// Resolves `uri`, written in the file `robot_file`, relative paths against `base_dir` (empty:
/// the robot file's folder). `fail` is called with the reason for an URI that escapes or
/// names a device (it throws).
template <typename Fail>
ResolvedPath ResolveUri(const std::string& uri, const std::string& robot_file,
                        const std::string& base_dir, const PackageDirs& packages, Fail fail);

/// The non-template core: returns the reason for a refusal in `refusal` (and an empty
/// result) instead of calling a handler.
ResolvedPath ResolveUriOrRefuse(const std::string& uri, const std::string& robot_file,
                                const std::string& base_dir, const PackageDirs& packages,
                                std::string* refusal);

template <typename Fail>
ResolvedPath ResolveUri(const std::string& uri, const std::string& robot_file,
                        const std::string& base_dir, const PackageDirs& packages, Fail fail) {
  std::string refusal;
  ResolvedPath r = ResolveUriOrRefuse(uri, robot_file, base_dir, packages, &refusal);
  if (!refusal.empty()) fail(refusal);
  return r;
}

}  // namespace chasles::internal
