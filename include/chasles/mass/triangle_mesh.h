#pragma once
/// @file
/// Indexed triangle meshes and the clean-up that makes them fit for mass properties:
/// welding duplicate vertices, dropping degenerate triangles, and (for solids) checking that
/// the surface is closed and manifold and orienting it outwards.

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "chasles/math/types.h"

namespace chasles {

/// Three vertex indices; counter-clockwise seen from outside for an oriented solid.
using TriangleIndices = std::array<std::uint32_t, 3>;

/// An indexed triangle mesh.
struct TriangleMesh {
  /// Vertex positions [m once scaled; the file's unit before].
  std::vector<Vec3> vertices;
  /// Triangles as indices into `vertices`.
  std::vector<TriangleIndices> triangles;
};

/// What the clean-up did to a mesh; every count is zero on a clean input.
struct MeshRepairReport {
  /// Vertices before welding.
  std::size_t vertices_in = 0;
  /// Vertices after welding (exact and near duplicates merged).
  std::size_t vertices_out = 0;
  /// Triangles before dropping degenerate ones.
  std::size_t triangles_in = 0;
  /// Triangles with a repeated vertex index (after welding) or exactly zero area, dropped.
  std::size_t degenerate_dropped = 0;
  /// Welding tolerance used [same unit as the vertices].
  double weld_tolerance = 0.0;
  /// Connected components (by shared edges) of the validated solid.
  std::size_t components = 0;
  /// Triangles reversed to make the orientation consistent within their component.
  std::size_t triangles_flipped = 0;
  /// True when the whole mesh was inside out (negative enclosed volume) and was reversed.
  bool inside_out_flipped = false;
  /// Human-readable warnings (repairs made, suspicious input); never printed by the library.
  std::vector<std::string> warnings;
};

/// Relative weld tolerance used when none is given: a fraction of the bounding-box diagonal.
inline constexpr double kDefaultWeldRelativeTolerance = 1e-9;

/// The least bounding-box diagonal a mesh may have (in the unit of its vertices, after
/// scaling), unless all its vertices coincide: a mesh's second moments are fifth powers of its
/// size, which stay above 1e-150 for this size, far from double's underflow near 1e-308, and
/// so do the products of the exact zero-area and orientation tests.
inline constexpr double kMinMeshExtent = 1e-30;

/// Builds an indexed mesh from coordinates `xyz` (x0, y0, z0, x1, ...) multiplied by `scale`
/// and triangle indices (three per triangle). Vertices with bit-identical coordinates are
/// merged by hashing, then vertices closer than `tolerance` (after scaling; a NaN tolerance
/// means kDefaultWeldRelativeTolerance times the bounding-box diagonal) by a grid search; each
/// vertex goes to the first earlier kept vertex within the tolerance. Then degenerate
/// triangles are dropped (see MeshRepairReport). Throws InputError on an index out of range, a
/// non-finite coordinate, a mesh smaller than kMinMeshExtent, or no triangle left. Exact: the
/// vertices are `xyz` times `scale` (exactly `xyz` for a scale of 1, the coordinates of a
/// single-precision input widened to double).
TriangleMesh BuildTriangleMesh(std::span<const float> xyz, std::span<const std::uint32_t> indices,
                               double scale, double tolerance, MeshRepairReport* report);
/// The same for double-precision coordinates.
TriangleMesh BuildTriangleMesh(std::span<const double> xyz, std::span<const std::uint32_t> indices,
                               double scale, double tolerance, MeshRepairReport* report);
/// The same for a triangle soup (a binary STL): triangle t is the vertices 3 t, 3 t + 1,
/// 3 t + 2, i.e. BuildTriangleMesh with the indices 0, 1, 2, ..., without storing them. The
/// number of coordinates must be a multiple of 9.
TriangleMesh BuildTriangleSoup(std::span<const float> xyz, double scale, double tolerance,
                               MeshRepairReport* report);

/// A triangle soup of floats laid out in fixed-size records, read in place: triangle t's nine
/// coordinates x0, y0, z0, x1, ..., z2 (floats in the machine's byte order, at any alignment)
/// start at `data + t * stride`. A binary STL in memory is one: its records are 50 bytes, the
/// coordinates 12 bytes into each, after the normal.
struct FloatSoupRecords {
  const unsigned char* data = nullptr;
  std::size_t triangles = 0;
  std::size_t stride = 36;
  /// When set, called with the triangle (from 0) of the first non-finite coordinate, to throw
  /// an InputError that names it in the caller's terms (a file's byte offset); otherwise, or
  /// when it returns, BuildTriangleSoup's own error names the vertex.
  std::function<void(std::size_t triangle)> non_finite;
};

/// BuildTriangleSoup for the floats of `records`, read where they lie (no copy).
TriangleMesh BuildTriangleSoup(const FloatSoupRecords& records, double scale, double tolerance,
                               MeshRepairReport* report);

/// Makes `mesh` a valid solid boundary or throws InputError. Rules: every undirected edge is
/// shared by exactly two triangles (closed, manifold); within each connected component the
/// two triangles at an edge traverse it in opposite directions (consistent orientation,
/// repaired by flood fill from the first triangle of the component, keeping the majority
/// orientation; a non-orientable component is an error); the enclosed volume is positive
/// (an inside-out mesh is reversed as a whole). Repairs are counted and described in
/// `report`. The error for an open or non-manifold mesh gives the counts of boundary and
/// non-manifold edges and the coordinates of the first offending edge.
void ValidateSolid(TriangleMesh& mesh, MeshRepairReport* report);

}  // namespace chasles
