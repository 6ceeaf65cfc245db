// Binary and ASCII STL. The binary layout: 80-byte header, uint32 little-endian triangle count
// n, then n records of 50 bytes (normal, three vertices as 12 little-endian floats, a uint16
// attribute word), so a binary STL is exactly 84 + 50 n bytes.

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <system_error>

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/files/mapped_file.h"
#include "files/internal/mesh_readers.h"
#include "files/internal/mesh_text.h"

namespace chasles::internal {
namespace {

constexpr std::uintmax_t kStlHeaderBytes = 84;  // 80-byte header + uint32 triangle count
constexpr std::uintmax_t kStlRecordBytes = 50;  // normal, 3 vertices (12 floats), uint16
// Indices are uint32 and a binary STL shares no vertex: 3 n must stay below 2^32.
constexpr std::uint32_t kStlMaxTriangles = UINT32_MAX / 3;

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

File OpenOrThrow(const std::string& path) {
  File f(std::fopen(path.c_str(), "rb"));
  if (!f) {
    throw InputError(fmt::format("mesh file '{}': cannot be opened for reading ({})", path,
                                 std::strerror(errno)));
  }
  return f;
}

std::uint32_t ReadU32LE(const unsigned char* p) {
  return std::uint32_t{p[0]} | std::uint32_t{p[1]} << 8 | std::uint32_t{p[2]} << 16 |
         std::uint32_t{p[3]} << 24;
}

// The checks on the announced count shared by the file and memory readers.
void CheckStlCount(const std::string& name, std::uint32_t n, std::uintmax_t size) {
  const std::uintmax_t expected = kStlHeaderBytes + kStlRecordBytes * std::uintmax_t{n};
  if (size != expected) {
    throw InputError(fmt::format(
        "mesh file '{}': binary STL size mismatch: the header announces {} triangles, i.e. "
        "84 + 50 x {} = {} bytes, but the file has {} bytes; it is truncated or not a binary "
        "STL",
        name, n, n, expected, size));
  }
  if (n == 0) {
    throw InputError(
        fmt::format("mesh file '{}': empty mesh (the binary STL holds 0 triangles)", name));
  }
  if (n > kStlMaxTriangles) {
    throw InputError(fmt::format(
        "mesh file '{}': {} triangles is more than the {} a mesh can hold (3 vertices each, "
        "32-bit indices)",
        name, n, kStlMaxTriangles));
  }
}

// What is wrong with coordinate k (0 to 8) of triangle t (from 0), when it is not finite.
std::string NonFinite(std::size_t t, int k, float value) {
  return fmt::format("triangle {} has a non-finite vertex coordinate ({}) (byte offset {})", t + 1,
                     value, kStlHeaderBytes + kStlRecordBytes * t + 12 + 4 * k);
}

// Copies the 9 vertex coordinates of `count` records into `out` (T: float as stored, or double,
// each float widened exactly) and checks them: the first record is `first` (for messages).
template <typename T>
void DecodeStlRecords(const unsigned char* records, std::size_t count, std::size_t first, T* out,
                      const std::string& name) {
  for (std::size_t r = 0; r < count; ++r) {
    // Skip the 12-byte normal; read the 36 bytes of vertices; skip the attribute word.
    const unsigned char* rec = records + r * kStlRecordBytes + 12;
    float f[9];
    if constexpr (std::endian::native == std::endian::little) {
      std::memcpy(f, rec, 36);
    } else {
      for (int k = 0; k < 9; ++k) f[k] = std::bit_cast<float>(ReadU32LE(rec + 4 * k));
    }
    for (int k = 0; k < 9; ++k) out[k] = static_cast<T>(f[k]);
    for (int k = 0; k < 9; ++k) {
      if (!std::isfinite(f[k])) {
        throw InputError(fmt::format("mesh file '{}': {}", name, NonFinite(first + r, k, f[k])));
      }
    }
    out += 9;
  }
}

MeshFileData NewStlData(std::uint32_t n) {
  MeshFileData data;
  data.format = "binary STL";
  data.single_precision = true;  // a record holds its vertices as 9 floats
  data.xyz.resize(std::size_t{n} * 9);
  data.indices.resize(std::size_t{n} * 3);
  for (std::size_t i = 0; i < data.indices.size(); ++i) {
    data.indices[i] = static_cast<std::uint32_t>(i);
  }
  return data;
}

// Case-insensitive comparison with a lower-case keyword.
bool IsKeyword(std::string_view tok, std::string_view keyword) {
  if (tok.size() != keyword.size()) return false;
  for (std::size_t i = 0; i < tok.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(tok[i])) != keyword[i]) return false;
  }
  return true;
}

// Reads the binary STL `path` in chunks, decoding the coordinates into the array that
// `allocate(n)` returns for its n triangles (9 n values, float or double).
template <typename Allocate>
void ReadBinaryStlRecords(const std::string& path, Allocate allocate) {
  std::error_code ec;
  const std::uintmax_t file_size = std::filesystem::file_size(path, ec);
  if (ec) {
    throw InputError(fmt::format("mesh file '{}': cannot read its size ({})", path, ec.message()));
  }
  File f = OpenOrThrow(path);
  std::array<unsigned char, kStlHeaderBytes> header{};
  if (std::fread(header.data(), 1, header.size(), f.get()) != header.size()) {
    throw InputError(
        fmt::format("mesh file '{}': too short for a binary STL ({} bytes; the header alone is 84)",
                    path, file_size));
  }
  const std::uint32_t n = ReadU32LE(header.data() + 80);
  CheckStlCount(path, n, file_size);
  auto* out = allocate(n);
  // Records are read in chunks so the raw file never sits in memory next to the result.
  constexpr std::size_t kChunk = 16384;
  std::vector<unsigned char> buf(kChunk * kStlRecordBytes);
  for (std::size_t done = 0; done < n;) {
    const std::size_t count = std::min<std::size_t>(kChunk, n - done);
    if (std::fread(buf.data(), kStlRecordBytes, count, f.get()) != count) {
      throw InputError(
          fmt::format("mesh file '{}': read error after {} of {} triangles", path, done, n));
    }
    DecodeStlRecords(buf.data(), count, done, out + 9 * done, path);
    done += count;
  }
}

}  // namespace

bool LooksLikeBinaryStl(const std::string& path, std::uintmax_t file_size) {
  if (file_size < kStlHeaderBytes) return false;
  File f = OpenOrThrow(path);
  std::array<unsigned char, kStlHeaderBytes> header{};
  if (std::fread(header.data(), 1, header.size(), f.get()) != header.size()) return false;
  const std::uint32_t n = ReadU32LE(header.data() + 80);
  return file_size == kStlHeaderBytes + kStlRecordBytes * std::uintmax_t{n};
}

// Why a reader of our own: measured on a 1,000,000-triangle binary STL (50 MB, page cache
// warm; bench/mesh_mass_bench.cpp), assimp 5.2's STL importer takes about 0.18 s, this reader
// 0.013-0.027 s. Through assimp, read + weld + validate + integrate took 0.38 s, too close to
// the 0.5 s budget on a busy machine; with this reader it takes 0.15 s. It also reports a
// size that does not match the announced triangle count as such.
MeshFileData ReadBinaryStl(const std::string& path) {
  MeshFileData data;
  ReadBinaryStlRecords(path, [&data](std::uint32_t n) {
    data = NewStlData(n);
    return data.xyz.data();
  });
  return data;
}

std::vector<float> ReadBinaryStlFloats(const std::string& path) {
  std::vector<float> xyz;
  ReadBinaryStlRecords(path, [&xyz](std::uint32_t n) {
    xyz.resize(std::size_t{n} * 9);
    return xyz.data();
  });
  return xyz;
}

std::optional<MappedBinaryStl> MapBinaryStl(const std::string& path) {
  if constexpr (std::endian::native != std::endian::little) return std::nullopt;
  std::optional<MappedFile> file;
  try {
    file.emplace(path);
  } catch (const std::system_error& e) {
    throw InputError(fmt::format("mesh file '{}': cannot be opened for reading ({})", path,
                                 std::strerror(e.code().value())));
  }
  // Not a regular file at least 84 bytes long whose header can be read: ReadMeshFile says what
  // it is (as LooksLikeBinaryStl does).
  std::array<unsigned char, kStlHeaderBytes> header{};
  if (!file->regular() || file->size() < kStlHeaderBytes) return std::nullopt;
  try {
    if (file->ReadAt(0, header.data(), header.size()) != header.size()) return std::nullopt;
  } catch (const std::system_error&) {
    return std::nullopt;
  }
  const std::uint32_t n = ReadU32LE(header.data() + 80);
  if (file->size() != kStlHeaderBytes + kStlRecordBytes * std::uintmax_t{n}) return std::nullopt;
  CheckStlCount(path, n, file->size());
  // Mapped only now that the size is known to hold the n records; see MappedFile on a file
  // truncated while mapped.
  std::span<const unsigned char> bytes;
  try {
    bytes = file->Bytes();
  } catch (const std::system_error&) {
    throw InputError(
        fmt::format("mesh file '{}': read error after {} of {} triangles", path, 0, n));
  }
  if (bytes.size() != file->size()) {
    const std::size_t done =
        bytes.size() < kStlHeaderBytes ? 0 : (bytes.size() - kStlHeaderBytes) / kStlRecordBytes;
    throw InputError(
        fmt::format("mesh file '{}': read error after {} of {} triangles", path, done, n));
  }
  MappedBinaryStl stl{std::move(*file), bytes.data() + kStlHeaderBytes + 12, n};
  return stl;
}

MeshFileData ReadBinaryStlBytes(std::string_view bytes, const std::string& name) {
  if (bytes.size() < kStlHeaderBytes) {
    throw InputError(
        fmt::format("mesh file '{}': too short for a binary STL ({} bytes; the header alone is 84)",
                    name, bytes.size()));
  }
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
  const std::uint32_t n = ReadU32LE(p + 80);
  CheckStlCount(name, n, bytes.size());
  MeshFileData data = NewStlData(n);
  DecodeStlRecords(p + kStlHeaderBytes, n, 0, data.xyz.data(), name);
  return data;
}

bool LooksLikeAsciiStl(std::string_view bytes) {
  const std::string_view head = bytes.substr(0, 512);
  if (head.find('\0') != std::string_view::npos) return false;
  std::size_t i = 0;
  while (i < head.size() && std::isspace(static_cast<unsigned char>(head[i]))) ++i;
  return IsKeyword(head.substr(i, 5), "solid");
}

MeshFileData ReadStl(std::string_view bytes, const std::string& name) {
  if (bytes.size() >= kStlHeaderBytes) {
    const std::uint32_t n = ReadU32LE(reinterpret_cast<const unsigned char*>(bytes.data()) + 80);
    if (bytes.size() == kStlHeaderBytes + kStlRecordBytes * std::uintmax_t{n}) {
      return ReadBinaryStlBytes(bytes, name);
    }
  }
  if (LooksLikeAsciiStl(bytes)) return ReadAsciiStl(bytes, name);
  return ReadBinaryStlBytes(bytes, name);  // fails, saying what the size should be
}

// The grammar, one token at a time (white space and line ends are interchangeable):
//   file   := solid+
//   solid  := "solid" [name...] facet* "endsolid" [name]
//   facet  := "facet" "normal" n n n "outer" "loop" ("vertex" x y z){3} "endloop" "endfacet"
// The names after "solid" and "endsolid" run to the end of their lines.
MeshFileData ReadAsciiStl(std::string_view text, const std::string& name) {
  TextScanner s(text, name);
  MeshFileData data;
  data.format = "ASCII STL";
  std::size_t facet = 0;  // facets read so far (for messages)
  auto expect = [&](std::string_view keyword, std::string_view where) {
    const std::string_view tok = s.Token();
    if (IsKeyword(tok, keyword)) return;
    if (tok.empty()) {
      s.Fail(fmt::format("truncated ASCII STL: the file ends {} where '{}' was expected", where,
                         keyword));
    }
    s.FailAt(
        static_cast<std::size_t>(tok.data() - text.data()),
        fmt::format("'{}' where '{}' was expected {}", TextScanner::Short(tok), keyword, where));
  };
  auto coordinate = [&](std::string_view what) {
    s.SkipSpace();
    const std::size_t at = s.pos();
    const std::string_view tok = s.Token();
    if (tok.empty()) {
      s.Fail(
          fmt::format("truncated ASCII STL: the file ends inside facet {} where {} was "
                      "expected",
                      facet + 1, what));
    }
    double v = 0;
    if (!ParseDouble(tok, v)) {
      s.FailAt(at, fmt::format("facet {}: {} '{}' is not a number", facet + 1, what,
                               TextScanner::Short(tok)));
    }
    return std::pair<double, std::size_t>(v, at);
  };

  std::size_t solids = 0;
  for (;;) {
    s.SkipSpace();
    if (s.AtEnd()) {
      if (solids == 0) MeshFail(name, "empty ASCII STL (no 'solid' line)");
      break;
    }
    expect("solid", solids == 0 ? "at the start of the file" : "after 'endsolid'");
    ++solids;
    s.SkipLine();  // the solid's name, if any
    for (;;) {
      s.SkipSpace();
      const std::size_t at = s.pos();
      const std::string_view tok = s.Token();
      if (IsKeyword(tok, "endsolid")) {
        s.SkipLine();  // its name, if any
        break;
      }
      if (tok.empty()) {
        s.Fail(
            fmt::format("truncated ASCII STL: the file ends after {} facets without "
                        "'endsolid'",
                        facet));
      }
      if (!IsKeyword(tok, "facet")) {
        s.FailAt(at, fmt::format("'{}' where 'facet' or 'endsolid' was expected",
                                 TextScanner::Short(tok)));
      }
      const std::string where = fmt::format("in facet {}", facet + 1);
      expect("normal", where);
      for (int k = 0; k < 3; ++k) coordinate("a normal component");  // checked, then ignored
      expect("outer", where);
      expect("loop", where);
      if (data.xyz.size() / 3 + 3 > std::size_t{UINT32_MAX}) {
        MeshFail(name, "more than 2^32 vertices");
      }
      for (int v = 0; v < 3; ++v) {
        expect("vertex", where);
        for (int k = 0; k < 3; ++k) {
          const auto [x, x_at] = coordinate("a vertex coordinate");
          if (!IsMeshCoordinate(x)) {
            s.FailAt(x_at, fmt::format("facet {}: vertex coordinate {} is {}", facet + 1, x,
                                       kCoordinateRule));
          }
          data.xyz.push_back(x);
        }
      }
      expect("endloop", where);
      expect("endfacet", where);
      ++facet;
    }
  }
  if (facet == 0) MeshFail(name, "empty mesh (the ASCII STL holds no facet)");
  data.indices.resize(data.xyz.size() / 3);
  for (std::size_t i = 0; i < data.indices.size(); ++i) {
    data.indices[i] = static_cast<std::uint32_t>(i);
  }
  return data;
}

}  // namespace chasles::internal

namespace chasles {

void MappedBinaryStl::ThrowIfNonFinite(std::size_t t) const {
  float f[9];
  std::memcpy(f, coordinates + t * kRecordBytes, sizeof f);
  for (int k = 0; k < 9; ++k) {
    if (!std::isfinite(f[k])) throw InputError(internal::NonFinite(t, k, f[k]));
  }
}

}  // namespace chasles
