#pragma once
/// @file
/// Reading triangle meshes from files: binary and ASCII STL, OBJ, PLY (ASCII and binary) and
/// OFF, each by a strict reader of chasles' own (docs/reliability-mesh.md). Mesh files carry no
/// units: coordinates come back exactly as stored, and the caller applies the scale (unit) and
/// pose.

#include <cstdint>
#include <string>
#include <vector>

namespace chasles {

/// A triangle mesh as stored in a file, before any welding or validation.
struct MeshFileData {
  /// Vertex coordinates x0, y0, z0, x1, ... in the file's own length unit (single precision,
  /// which is what STL stores); all finite.
  std::vector<float> xyz;
  /// Vertex indices, three per triangle, into the vertices of `xyz`. A binary STL gives every
  /// triangle its own three vertices (0, 1, 2, 3, 4, 5, ...): it shares none.
  std::vector<std::uint32_t> indices;
  /// What was read: "binary STL", "ASCII STL", "OBJ", "PLY" or "OFF".
  std::string format;

  /// Number of vertices.
  std::size_t vertex_count() const { return xyz.size() / 3; }
  /// Number of triangles.
  std::size_t triangle_count() const { return indices.size() / 3; }
};

/// Reads the triangles of a mesh file, chosen by its extension (case-insensitive): .stl
/// (binary when its size is 84 + 50 n bytes, else ASCII when it starts with "solid"), .obj,
/// .ply, .off. Polygons are fan-triangulated; OBJ lines and points are ignored. Throws
/// InputError "mesh file 'PATH': WHAT (line N)" or "(byte offset N)" when the file is missing,
/// has another extension, is malformed in any way (truncated, a count its size cannot hold, an
/// index out of range, a non-finite coordinate, a missing or unknown header line), or holds no
/// triangles. Memory stays within a small multiple of the file's size, and time linear in it.
MeshFileData ReadMeshFile(const std::string& path);

}  // namespace chasles
