#pragma once
/// @file
/// Mass properties of a mesh file: the io layer reads it, the mass layer integrates it. Lives
/// here, above both, so that neither depends on the other.

#include <string>

#include "chasles/mass/mesh_mass.h"

namespace chasles {

/// Reads `path` (binary or ASCII STL, OBJ, PLY, ...; see io/mesh_reader.h) and computes its
/// mass properties with ComputeMeshMassProperties. Throws InputError naming the file.
MeshMassResult LoadMeshMassProperties(const std::string& path, const MeshMassOptions& opts);

}  // namespace chasles
