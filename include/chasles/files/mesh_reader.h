#pragma once
/// @file
/// Reading triangle meshes from files: binary and ASCII STL, OBJ, PLY (ASCII and binary) and
/// OFF, each by a strict reader of chasles' own (docs/reliability-mesh.md). Mesh files carry no
/// units: coordinates come back exactly as stored (in double precision), and the caller applies
/// the scale (unit) and pose.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "chasles/files/mapped_file.h"

namespace chasles {

/// The largest magnitude of a mesh coordinate, in the file's own unit: 3.4028234663852886e38,
/// the largest float, so every format (binary STL stores floats) accepts the same range, and the
/// mass integrals, which take fifth powers of coordinate differences, stay finite in double.
inline constexpr double kMaxMeshCoordinate = 3.4028234663852886e38;

/// A triangle mesh as stored in a file, before any welding or validation.
struct MeshFileData {
  /// Vertex coordinates x0, y0, z0, x1, ... in the file's own length unit, each exactly the
  /// number the file stores: the double nearest to the decimal text (ASCII STL, OBJ, OFF, ASCII
  /// PLY of any declared type), a binary PLY `double` as is, a float (binary STL, binary PLY
  /// `float`) widened to double; all finite and within ±kMaxMeshCoordinate.
  std::vector<double> xyz;
  /// Vertex indices, three per triangle, into the vertices of `xyz`. A binary STL gives every
  /// triangle its own three vertices (0, 1, 2, 3, 4, 5, ...): it shares none.
  std::vector<std::uint32_t> indices;
  /// What was read: "binary STL", "ASCII STL", "OBJ", "PLY" or "OFF".
  std::string format;
  /// True when the file stores a coordinate as a float (binary STL; a binary PLY whose x, y or
  /// z is `float`): its vertices are resolved only to float32's spacing at their magnitude,
  /// 2^-23 to 2^-24 of it.
  bool single_precision = false;

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

/// When `path` is a regular file named .stl (any case) whose size is exactly that of a binary
/// STL of the triangle count in its header (84 + 50 n bytes), its vertex coordinates as the
/// floats the file stores: nine a triangle, triangle t the vertices 3 t, 3 t + 1, 3 t + 2, no
/// vertex shared (ReadMeshFile returns the same numbers widened to double, with indices 0, 1,
/// 2, ...). Otherwise nothing: ReadMeshFile reads the file, or says what is wrong with it.
/// Throws InputError as ReadMeshFile does on an unreadable file or a non-finite coordinate.
/// For the mass of a large binary STL: 36 bytes of coordinates a triangle instead of 84.
std::optional<std::vector<float>> TryReadBinaryStlFloats(const std::string& path);

/// A binary STL read in place (TryMapBinaryStl): the open file and where its floats lie.
struct MappedBinaryStl {
  /// The file, mapped into memory (or read into a buffer where it cannot be mapped).
  MappedFile file;
  /// Triangle t's nine vertex coordinates x0, y0, z0, x1, ..., z2, as floats in the machine's
  /// byte order (not aligned), start at coordinates + t * kRecordBytes.
  const unsigned char* coordinates = nullptr;
  /// The number of triangles.
  std::uint32_t triangles = 0;
  /// The size of a binary STL record: normal, three vertices, attribute word.
  static constexpr std::size_t kRecordBytes = 50;

  /// Throws the InputError ReadMeshFile gives for the first non-finite coordinate of triangle
  /// `t` (from 0), without the "mesh file 'PATH': " that starts it; returns when all nine are
  /// finite.
  void ThrowIfNonFinite(std::size_t t) const;
};

/// TryReadBinaryStlFloats without copying the floats: for the same files, the same floats,
/// read where they lie in the file mapped into memory (MappedFile, with its caveat on a file
/// truncated while it is read), with the same errors except that the coordinates are not
/// checked for finiteness here: the caller, who reads them anyway, checks them and calls
/// ThrowIfNonFinite for the first bad triangle. Nothing where TryReadBinaryStlFloats gives
/// nothing, and on a machine whose floats are not little-endian (use TryReadBinaryStlFloats
/// there). For the mass of a large binary STL: no memory of its own for the coordinates, and no
/// copy.
std::optional<MappedBinaryStl> TryMapBinaryStl(const std::string& path);

}  // namespace chasles
