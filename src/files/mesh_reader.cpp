#include "chasles/files/mesh_reader.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <system_error>

#include <fmt/format.h>

#include "chasles/error.h"
#include "files/internal/mesh_readers.h"

namespace chasles {
namespace internal {
namespace {

// The extension of `path`, lower case, with its dot.
std::string Extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

[[noreturn]] void UnsupportedFormat(const std::string& name, const std::string& ext) {
  throw InputError(fmt::format("mesh file '{}': unsupported format '{}'; supported: {}", name,
                               ext.empty() ? std::string("(no extension)") : ext,
                               kSupportedMeshFormats));
}

using File = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;

File OpenOrThrow(const std::string& path) {
  File f(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!f) {
    throw InputError(fmt::format("mesh file '{}': cannot be opened for reading ({})", path,
                                 std::strerror(errno)));
  }
  return f;
}

// The whole file in memory (the text readers and PLY work on it). `size` was just measured;
// a file that shrinks meanwhile is read as far as it goes, one that grows is cut at `size`.
std::string ReadWholeFile(const std::string& path, std::uintmax_t size) {
  File f = OpenOrThrow(path);
  std::string bytes(static_cast<std::size_t>(size), '\0');
  const std::size_t n = std::fread(bytes.data(), 1, bytes.size(), f.get());
  if (std::ferror(f.get())) {
    throw InputError(fmt::format("mesh file '{}': read error ({})", path, std::strerror(errno)));
  }
  bytes.resize(n);
  return bytes;
}

// The first bytes of a file, to tell ASCII from binary STL.
std::string ReadHead(const std::string& path, std::size_t n) {
  File f = OpenOrThrow(path);
  std::string bytes(n, '\0');
  bytes.resize(std::fread(bytes.data(), 1, n, f.get()));
  return bytes;
}

}  // namespace

MeshFileData ReadMeshBytes(std::string_view bytes, const std::string& name) {
  const std::string ext = Extension(name);
  if (ext == ".stl") return ReadStl(bytes, name);
  if (ext == ".obj") return ReadObj(bytes, name);
  if (ext == ".ply") return ReadPly(bytes, name);
  if (ext == ".off") return ReadOff(bytes, name);
  UnsupportedFormat(name, ext);
}

}  // namespace internal

MeshFileData ReadMeshFile(const std::string& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) {
    throw InputError(
        fmt::format("mesh file '{}': not found; check the path (relative paths are "
                    "resolved from the current directory)",
                    path));
  }
  if (!std::filesystem::is_regular_file(status)) {
    throw InputError(fmt::format("mesh file '{}': not a regular file", path));
  }
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec || size == 0) {
    throw InputError(fmt::format("mesh file '{}': empty mesh (the file is empty)", path));
  }
  const std::string ext = internal::Extension(path);
  if (ext == ".stl") {
    // The fast path: a consistent binary STL is streamed without holding the file.
    if (internal::LooksLikeBinaryStl(path, size)) return internal::ReadBinaryStl(path);
    // Not a consistent binary STL: an ASCII one starts with "solid"; anything else is a
    // binary STL whose size does not match its count (ReadBinaryStl says so).
    if (!internal::LooksLikeAsciiStl(internal::ReadHead(path, 512))) {
      return internal::ReadBinaryStl(path);
    }
  } else if (ext != ".obj" && ext != ".ply" && ext != ".off") {
    internal::UnsupportedFormat(path, ext);
  }
  return internal::ReadMeshBytes(internal::ReadWholeFile(path, size), path);
}

std::optional<std::vector<float>> TryReadBinaryStlFloats(const std::string& path) {
  std::error_code ec;
  if (internal::Extension(path) != ".stl" ||
      !std::filesystem::is_regular_file(std::filesystem::status(path, ec))) {
    return std::nullopt;
  }
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec || !internal::LooksLikeBinaryStl(path, size)) return std::nullopt;
  return internal::ReadBinaryStlFloats(path);
}

std::optional<MappedBinaryStl> TryMapBinaryStl(const std::string& path) {
  std::error_code ec;
  if (internal::Extension(path) != ".stl" ||
      !std::filesystem::is_regular_file(std::filesystem::status(path, ec))) {
    return std::nullopt;
  }
  return internal::MapBinaryStl(path);
}

}  // namespace chasles
