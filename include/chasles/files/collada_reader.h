#pragma once
/// @file
/// Reading the triangles of a Collada (.dae) file: the meshes of <library_geometries> placed by
/// the nodes of its visual scene (matrix, translate, rotate, scale; nodes instanced from
/// <library_nodes>), in metres (<unit meter>) with z up (<up_axis>: Y_UP turned +90° about x,
/// X_UP turned so that x becomes z). As strict as the other mesh readers
/// (docs/reliability-mesh.md): every count checked against the numbers present, every index
/// against its array, every number finite; instancing cycles and depth refused; the output
/// capped at kMaxColladaTriangles. Errors are InputError "FILE:LINE: WHAT".

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace chasles {

/// A triangle soup as a mesh reader returns it (the same fields as io's MeshFileData, in
/// double precision: Collada meshes are often in millimetres far from their origin).
struct TriangleSoup {
  /// Vertex coordinates x0, y0, z0, x1, ... [m]; all finite.
  std::vector<double> xyz;
  /// Three vertex indices per triangle.
  std::vector<std::uint32_t> indices;
  /// What was read: "Collada".
  std::string format;

  std::size_t vertex_count() const { return xyz.size() / 3; }
  std::size_t triangle_count() const { return indices.size() / 3; }
};

/// Most triangles a Collada file may place (after instancing).
inline constexpr std::size_t kMaxColladaTriangles = std::size_t{1} << 25;

/// Reads the triangles of the Collada file `path`.
TriangleSoup ReadColladaFile(const std::string& path);

/// The same from memory; `name` is what errors call the file.
TriangleSoup ReadColladaBytes(std::string bytes, const std::string& name);

}  // namespace chasles
