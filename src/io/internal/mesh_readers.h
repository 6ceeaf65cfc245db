#pragma once
/// @file
/// The individual readers behind ReadMeshFile, exposed for the tests and benchmarks.

#include <cstdint>
#include <string>

#include "chasles/io/mesh_reader.h"

namespace chasles::internal {

/// True when the file's size is exactly 84 + 50 n bytes for the triangle count n in its
/// header. (An ASCII STL also starts with "solid", and so do many binary ones: the size is
/// the reliable test.)
bool LooksLikeBinaryStl(const std::string& path, std::uintmax_t file_size);

/// Reads a binary STL directly: 80-byte header, uint32 count, 50-byte records (normal,
/// three vertices, attribute word). The stored normals are ignored: the vertex order defines
/// the orientation. Throws InputError on a size mismatch or a read error.
MeshFileData ReadBinaryStl(const std::string& path);

/// Reads any format assimp knows (triangulating polygons, applying node transforms).
/// Throws InputError when assimp cannot read it or finds no triangles.
MeshFileData ReadWithAssimp(const std::string& path);

}  // namespace chasles::internal
