#pragma once
/// @file
/// Reading triangle meshes from files: binary and ASCII STL, OBJ, PLY (and whatever else
/// assimp reads). Mesh files carry no units: coordinates come back exactly as stored, and the
/// caller applies the scale (unit) and pose.

#include <cstdint>
#include <string>
#include <vector>

namespace chasles {

/// A triangle mesh as stored in a file, before any welding or validation.
struct MeshFileData {
  /// Vertex coordinates x0, y0, z0, x1, ... in the file's own length unit (single precision,
  /// which is what STL stores and what assimp returns).
  std::vector<float> xyz;
  /// Vertex indices, three per triangle, into the vertices of `xyz`. A binary STL gives every
  /// triangle its own three vertices (0, 1, 2, 3, 4, 5, ...): it shares none.
  std::vector<std::uint32_t> indices;
  /// What was read: "binary STL", "ASCII STL", "OBJ", "PLY", ... (from the reader used).
  std::string format;

  /// Number of vertices.
  std::size_t vertex_count() const { return xyz.size() / 3; }
  /// Number of triangles.
  std::size_t triangle_count() const { return indices.size() / 3; }
};

/// Reads the triangles of a mesh file. Binary STL is read directly (fast path); everything
/// else goes through assimp, with polygons triangulated and node transforms applied. Lines and
/// points are ignored. Throws InputError naming the file when it is missing, unreadable or
/// garbled, when a binary STL's size does not match its triangle count, or when it holds no
/// triangles.
MeshFileData ReadMeshFile(const std::string& path);

}  // namespace chasles
