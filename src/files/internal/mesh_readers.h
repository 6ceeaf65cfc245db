#pragma once
/// @file
/// The individual readers behind ReadMeshFile, exposed for the tests, the benchmarks and the
/// fuzz targets. Every reader that takes bytes works in memory only (no file system): `name`
/// is what its errors call the file. All of them throw InputError
/// "mesh file 'NAME': WHAT (line N)" or "(byte offset N)" on malformed input, never read past
/// the bytes given, check every count a header declares against the bytes that follow before
/// allocating anything for it, range-check every index, and refuse non-finite coordinates.
/// See docs/reliability-mesh.md.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "chasles/files/mesh_reader.h"

namespace chasles::internal {

/// True when the file's size is exactly 84 + 50 n bytes for the triangle count n in its
/// header. (An ASCII STL also starts with "solid", and so do many binary ones: the size is
/// the reliable test.)
bool LooksLikeBinaryStl(const std::string& path, std::uintmax_t file_size);

/// Reads a binary STL file directly, in chunks: 80-byte header, uint32 count, 50-byte records
/// (normal, three vertices, attribute word). The stored normals are ignored: the vertex order
/// defines the orientation. Throws InputError on a size mismatch, a read error or a
/// non-finite vertex coordinate.
MeshFileData ReadBinaryStl(const std::string& path);

/// The same, keeping the coordinates as the floats the file stores (9 a triangle, triangle t
/// the vertices 3 t, 3 t + 1, 3 t + 2): half the memory of ReadBinaryStl's doubles.
std::vector<float> ReadBinaryStlFloats(const std::string& path);

/// The binary STL `path` in place, for TryMapBinaryStl: nothing when it is not a regular file
/// of exactly 84 + 50 n bytes for the count n in its header, or on a machine whose floats are
/// not little-endian; else the errors of ReadBinaryStlFloats but for non-finite coordinates.
std::optional<MappedBinaryStl> MapBinaryStl(const std::string& path);

/// The same from memory.
MeshFileData ReadBinaryStlBytes(std::string_view bytes, const std::string& name);

/// True when `bytes` should be read as an ASCII STL: it starts (after white space) with
/// "solid" and its first 512 bytes hold no NUL byte (binary headers that say "solid" are
/// followed by binary counts and floats, which nearly always do).
bool LooksLikeAsciiStl(std::string_view bytes);

/// Reads an ASCII STL strictly: `solid`, then facets of exactly `facet normal x y z`,
/// `outer loop`, three `vertex x y z`, `endloop`, `endfacet`, then `endsolid` (further
/// `solid ... endsolid` blocks may follow). Keywords are case-insensitive. A file cut short
/// is an error naming the line, never a mesh of the facets that survived.
MeshFileData ReadAsciiStl(std::string_view text, const std::string& name);

/// Binary or ASCII STL from memory: the size test first (as ReadMeshFile), then
/// LooksLikeAsciiStl; anything else is read as binary (and then fails on its size).
MeshFileData ReadStl(std::string_view bytes, const std::string& name);

/// Reads a Wavefront OBJ: `v x y z [w | r g b]` and `f` with 1-based or negative (relative)
/// indices in the forms i, i/t, i//n, i/t/n; polygons are fan-triangulated. Every other
/// statement (vt, vn, g, o, s, usemtl, mtllib, l, p, comments) is ignored.
MeshFileData ReadObj(std::string_view text, const std::string& name);

/// Reads a PLY (ascii, binary_little_endian, binary_big_endian): the `vertex` element's
/// scalar x, y, z of any numeric type, and the `face` element's list property
/// `vertex_indices` (or `vertex_index`) with integer count and index types; polygons are
/// fan-triangulated. Other elements and properties are read over and ignored.
MeshFileData ReadPly(std::string_view bytes, const std::string& name);

/// Reads an OFF (Object File Format): an `OFF` keyword (or COFF, NOFF, CNOFF, STOFF, ...:
/// anything after the three coordinates of a vertex line, or after the indices of a face line,
/// such as colours or normals, is ignored), the counts `nv nf [ne]`, nv vertex lines, nf face
/// lines `k i0 ... ik-1` with 0-based indices. '#' starts a comment. Binary OFF is refused.
MeshFileData ReadOff(std::string_view text, const std::string& name);

/// Dispatches on the extension of `name` (case-insensitive): .stl, .obj, .ply, .off. Any
/// other extension is an InputError listing the supported ones.
MeshFileData ReadMeshBytes(std::string_view bytes, const std::string& name);

/// The extensions ReadMeshBytes and ReadMeshFile accept, for messages and docs.
inline constexpr std::string_view kSupportedMeshFormats =
    ".stl (binary or ASCII), .obj, .ply (ASCII or binary), .off";

}  // namespace chasles::internal
