#include "chasles/scene/mesh_file.h"

#include <chrono>
#include <optional>
#include <vector>

#include <fmt/format.h>

#include "chasles/files/mesh_reader.h"

namespace chasles {

MeshMassResult LoadMeshMassProperties(const std::string& path, const MeshMassOptions& opts) {
  MeshMassReport report;
  report.path = path;
  const auto t0 = std::chrono::steady_clock::now();
  // A binary STL is read in place, its floats where the file holds them (no memory to fill,
  // the same numbers once widened).
  if (std::optional<MappedBinaryStl> stl = TryMapBinaryStl(path)) {
    report.read_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    report.format = "binary STL";
    report.single_precision = true;
    // The weld checks the floats, naming a non-finite one as the reader would.
    const FloatSoupRecords soup{stl->coordinates, stl->triangles, MappedBinaryStl::kRecordBytes,
                                [&stl](std::size_t t) { stl->ThrowIfNonFinite(t); }};
    return ComputeMeshMassProperties(soup, opts, fmt::format("mesh file '{}'", path),
                                     std::move(report));
  }
  // Elsewhere a binary STL keeps its floats (half the memory to fill).
  if (std::optional<std::vector<float>> soup = TryReadBinaryStlFloats(path)) {
    report.read_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    report.format = "binary STL";
    report.single_precision = true;
    return ComputeMeshMassProperties(std::move(*soup), opts, fmt::format("mesh file '{}'", path),
                                     std::move(report));
  }
  MeshFileData data = ReadMeshFile(path);
  report.read_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  report.format = data.format;
  report.single_precision = data.single_precision;
  return ComputeMeshMassProperties(std::move(data.xyz), std::move(data.indices), opts,
                                   fmt::format("mesh file '{}'", path), std::move(report));
}

}  // namespace chasles
