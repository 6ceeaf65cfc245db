#pragma once
/// @file
/// Mass properties of a mesh file: the files layer reads it, the mass layer integrates it. Lives
/// here, above both, so that neither depends on the other.

#include <string>

#include "chasles/mass/mesh_mass.h"
#include "chasles/scene/scene.h"

namespace chasles {

/// Reads `path` (binary or ASCII STL, OBJ, PLY, ...; see files/mesh_reader.h) and computes its
/// mass properties with ComputeMeshMassProperties. Throws InputError naming the file.
MeshMassResult LoadMeshMassProperties(const std::string& path, const MeshMassOptions& opts);

/// Options of a mesh file given straight to `chasles mass`, written as in a scene ("mm",
/// "7850 kg/m^3"); empty means not given.
struct MeshCommandOptions {
  std::string unit;           ///< length of one file unit (required)
  std::string mode;           ///< solid (default) or shell
  std::string density;        ///< volume density (solid, or shell with thickness)
  std::string material;       ///< a material name instead of a density
  std::string mass;           ///< total mass instead of a density
  std::string areal_density;  ///< shell mode
  std::string thickness;      ///< shell mode, with density or material
};

/// True for file names chasles reads as meshes (.stl, .obj, .ply, .off, any case).
bool IsMeshFileName(const std::string& path);

/// A one-body scene made of the mesh file `path` with the given options. Errors name the
/// command-line option at fault (SceneError with file "command line").
Scene LoadMeshAsScene(const std::string& path, const MeshCommandOptions& options);

}  // namespace chasles
