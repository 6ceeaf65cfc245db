// Object File Format (OFF), as written by Geomview and used by the Princeton Shape Benchmark:
//   [C][N][ST]OFF            (the prefixes add colour, normal, texture values per vertex)
//   nv nf ne
//   x y z [extra values]     nv lines
//   k i0 ... ik-1 [colour]   nf lines, 0-based indices
// '#' starts a comment. The prefixes only append values after the three coordinates, so one
// rule reads them all: the first three numbers of a vertex line and the k + 1 first of a face
// line count, the rest of the line is ignored.

#include <fmt/format.h>

#include "files/internal/mesh_readers.h"
#include "files/internal/mesh_text.h"

namespace chasles::internal {
namespace {

// Fewest bytes a vertex line "0 0 0\n" and a face line "3 0 1 2\n" can take: the counts
// declared in the header must fit in what follows it before anything is allocated.
constexpr std::uint64_t kMinVertexLineBytes = 6;
constexpr std::uint64_t kMinFaceLineBytes = 8;

bool IsOffKeyword(std::string_view tok) {
  if (tok.size() < 3 || tok.substr(tok.size() - 3) != "OFF") return false;
  for (const char c : tok.substr(0, tok.size() - 3)) {
    if (c != 'C' && c != 'N' && c != 'S' && c != 'T') return false;
  }
  return true;
}

}  // namespace

MeshFileData ReadOff(std::string_view text, const std::string& name) {
  TextScanner s(text, name, '#');
  s.SkipSpace();
  if (s.AtEnd()) MeshFail(name, "empty file (an OFF starts with the keyword 'OFF')");
  const std::size_t keyword_at = s.pos();
  const std::string_view keyword = s.Token();
  if (!IsOffKeyword(keyword)) {
    const bool dimension = keyword.find("OFF") != std::string_view::npos;
    s.FailAt(keyword_at,
             dimension ? fmt::format("'{}': only 3-D OFF (OFF, COFF, NOFF, CNOFF, STOFF, ...) is "
                                     "supported",
                                     TextScanner::Short(keyword))
                       : fmt::format("'{}' where the keyword 'OFF' was expected",
                                     TextScanner::Short(keyword)));
  }
  if (!s.AtLineEnd()) {  // the counts may share the keyword's line, unless it says BINARY
    s.SkipBlanks();
    const std::size_t at = s.pos();
    if (s.TokenOnLine() == "BINARY") s.FailAt(at, "binary OFF is not supported; write it as text");
    s.Seek(at);
  }
  const std::size_t counts_at = (s.SkipSpace(), s.pos());
  const std::int64_t nv = s.Integer("the vertex count", false);
  const std::int64_t nf = s.Integer("the face count", true);
  if (!s.AtLineEnd()) s.Integer("the edge count", true);  // ignored, as by every reader
  if (nv < 0 || nf < 0) s.FailAt(counts_at, fmt::format("negative count ({} {})", nv, nf));
  s.SkipLine();
  // The declared counts against what is left: at least 6 bytes a vertex, 8 a face (the last
  // line may lack its line feed).
  const std::uint64_t left = s.Remaining() + 1;
  const auto unv = static_cast<std::uint64_t>(nv), unf = static_cast<std::uint64_t>(nf);
  if (unv > left / kMinVertexLineBytes || unf > left / kMinFaceLineBytes ||
      unv * kMinVertexLineBytes + unf * kMinFaceLineBytes > left) {
    s.FailAt(counts_at,
             fmt::format("the header declares {} vertices and {} faces, which take at least {} "
                         "bytes, but only {} bytes follow it: the file is truncated or the "
                         "counts are wrong",
                         nv, nf,
                         static_cast<long double>(unv) * kMinVertexLineBytes +
                             static_cast<long double>(unf) * kMinFaceLineBytes - 1,
                         s.Remaining()));
  }
  if (unv > UINT32_MAX) s.FailAt(counts_at, "more than 2^32 - 1 vertices");

  MeshFileData data;
  data.format = "OFF";
  data.xyz.reserve(3 * unv);
  for (std::uint64_t v = 0; v < unv; ++v) {
    s.SkipSpace();
    if (s.AtEnd()) {
      s.Fail(fmt::format("truncated: the file ends after {} of {} vertices", v, nv));
    }
    for (const char* what : {"vertex x", "vertex y", "vertex z"}) {
      data.xyz.push_back(s.CoordinateOnLine(what));
    }
    s.SkipLine();
  }
  FanBuilder fan(data.indices);
  for (std::uint64_t f = 0; f < unf; ++f) {
    s.SkipSpace();
    if (s.AtEnd()) s.Fail(fmt::format("truncated: the file ends after {} of {} faces", f, nf));
    const std::size_t at = s.pos();
    const std::int64_t k = s.Integer("the face's vertex count", true);
    if (k < 3) {
      s.FailAt(at, fmt::format("face {} has {} vertices; a face needs at least 3", f + 1, k));
    }
    fan.Start();
    for (std::int64_t c = 0; c < k; ++c) {
      s.SkipBlanks();
      const std::size_t i_at = s.pos();
      if (s.AtLineEnd()) {
        s.FailAt(i_at,
                 fmt::format("face {} declares {} vertices but its line holds {}", f + 1, k, c));
      }
      const std::int64_t i = s.Integer("a vertex index", true);
      if (i < 0 || i >= nv) {
        s.FailAt(i_at, fmt::format("face {}: vertex index {} is out of range (0 to {})", f + 1, i,
                                   nv - 1));
      }
      fan.Add(static_cast<std::uint32_t>(i));
    }
    s.SkipLine();  // a colour may follow
  }
  s.SkipSpace();
  if (!s.AtEnd()) {
    s.Fail(fmt::format("unexpected data after the {} vertices and {} faces the header declares", nv,
                       nf));
  }
  if (data.indices.empty()) MeshFail(name, "empty mesh (the OFF holds no face)");
  return data;
}

}  // namespace chasles::internal
