#pragma once
/// @file
/// Reads a mesh file through assimp (triangulating polygons, applying node transforms), for the
/// benchmark's comparison with chasles' own binary STL reader only. The library does not use
/// assimp: assimp 5.2 aborts, hangs or allocates without bound on small malformed files
/// (docs/reliability-mesh.md).

#include <string>

#include "chasles/files/mesh_reader.h"

namespace chasles::bench {

MeshFileData ReadWithAssimp(const std::string& path);

}  // namespace chasles::bench
