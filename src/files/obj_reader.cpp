// Wavefront OBJ, the geometry subset: vertices and polygonal faces. Statement reference:
// the Wavefront "Object Files (.obj)" appendix of the Advanced Visualizer manual: `v x y z [w]`
// (some writers append r g b), `f v1[/vt1[/vn1]] v2... ` with indices counted from 1, or
// negative to count back from the latest vertex (-1 is the last one defined).

#include <fmt/format.h>

#include "files/internal/mesh_readers.h"
#include "files/internal/mesh_text.h"

namespace chasles::internal {

MeshFileData ReadObj(std::string_view text, const std::string& name) {
  TextScanner s(text, name, '#');
  MeshFileData data;
  data.format = "OBJ";
  FanBuilder fan(data.indices);
  std::size_t faces = 0;
  while (!s.AtEnd()) {
    const std::string_view statement = s.TokenOnLine();
    if (statement == "v") {
      if (data.vertex_count() >= std::size_t{UINT32_MAX}) {
        s.Fail("more than 2^32 - 1 vertices");
      }
      for (const char* what : {"vertex x", "vertex y", "vertex z"}) {
        data.xyz.push_back(s.CoordinateOnLine(what));
      }
    } else if (statement == "f") {
      ++faces;
      const std::size_t defined = data.vertex_count();
      std::size_t corners = 0;
      const std::size_t line_start = s.pos();
      fan.Start();
      for (;;) {
        s.SkipBlanks();
        const std::size_t at = s.pos();
        std::string_view tok = s.TokenOnLine();
        if (tok.empty()) break;
        // The vertex index is the part before the first '/'; texture and normal indices
        // after it are not needed.
        const std::size_t slash = tok.find('/');
        const std::string_view index_text = tok.substr(0, slash);
        std::int64_t i = 0;
        if (!ParseInt(index_text, i)) {
          s.FailAt(at, fmt::format("face {}: '{}' is not a vertex index (i, i/t, i//n or i/t/n)",
                                   faces, TextScanner::Short(tok)));
        }
        // 1-based, or negative relative to the vertices defined so far.
        const std::int64_t resolved = i > 0 ? i - 1 : static_cast<std::int64_t>(defined) + i;
        if (i == 0 || resolved < 0 || resolved >= static_cast<std::int64_t>(defined)) {
          s.FailAt(at, fmt::format("face {}: vertex index {} is out of range ({} vertices "
                                   "defined before this face; indices count from 1, or back "
                                   "from -1)",
                                   faces, i, defined));
        }
        fan.Add(static_cast<std::uint32_t>(resolved));
        ++corners;
      }
      if (corners < 3) {
        s.FailAt(line_start,
                 fmt::format("face {} has {} vertices; a face needs at least 3", faces, corners));
      }
    }
    // Anything else (vt, vn, g, o, s, usemtl, mtllib, l, p, blank or comment) is ignored.
    s.SkipLine();
  }
  if (data.indices.empty()) {
    MeshFail(name, fmt::format("empty mesh (the OBJ holds {} vertices and no face)",
                               data.vertex_count()));
  }
  return data;
}

}  // namespace chasles::internal
