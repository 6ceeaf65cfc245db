#pragma once
/// @file
/// Robot description files (URDF, MJCF, SDF) for the commands: their meshes read by the files
/// layer's readers (Collada among them), and a robot as a one-body scene for
/// `chasles mass` (each link a part placed at its pose for the joint values given).

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "chasles/files/collada_reader.h"
#include "chasles/files/robot_reader.h"
#include "chasles/scene/scene.h"

namespace chasles {

/// The triangles of a mesh file in its own units: Collada (.dae) by ReadColladaFile, the
/// others by ReadMeshFile (files/mesh_reader.h).
TriangleSoup LoadMeshTriangles(const std::string& path);

/// Parses `--package NAME=DIR` and `--joint NAME=VALUE` options (throws InputError naming the
/// option).
std::vector<std::pair<std::string, std::string>> ParsePackageOptions(
    const std::vector<std::string>& options);
std::map<std::string, double> ParseJointOptions(const std::vector<std::string>& options);

/// A scene of one body, the robot, whose parts are its links with their given inertials
/// placed at their poses in the base frame for joint values `joints` (zero otherwise): its
/// mass, centre of mass and inertia are the robot's about the base. A link without an
/// inertial or with zero mass is left out (a note of the body says so); a link whose inertial
/// is not physically valid is an InputError that names it and points to `chasles audit`.
Scene LoadRobotAsScene(const std::string& path, const RobotReadOptions& options,
                       const std::map<std::string, double>& joints);

}  // namespace chasles
