// Mass properties of triangle meshes: integral pass, validation, welding, binary STL reading
// and the end-to-end path, on a torus of 1,000,000 triangles (1000 x 500 quads, 500,000
// vertices).
//   build/bench/mesh_mass_bench --benchmark_min_time=1
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "assimp_reader.h"
#include "chasles/files/mesh_reader.h"
#include "chasles/mass/mesh_mass.h"
#include "chasles/mass/triangle_mesh.h"
#include "chasles/scene/mesh_file.h"
#include "files/internal/mesh_readers.h"

namespace chasles {
namespace {

constexpr int kMajor = 1000, kMinor = 500;  // 2 x 1000 x 500 = 1,000,000 triangles

TriangleMesh MakeTorus() {
  const double R = 0.1, r = 0.03, pi = std::numbers::pi;
  TriangleMesh m;
  for (int i = 0; i < kMajor; ++i) {
    for (int j = 0; j < kMinor; ++j) {
      const double th = 2 * pi * i / kMajor, ph = 2 * pi * j / kMinor;
      m.vertices.emplace_back((R + r * std::cos(ph)) * std::cos(th),
                              (R + r * std::cos(ph)) * std::sin(th), r * std::sin(ph));
    }
  }
  auto id = [](int i, int j) { return std::uint32_t((i % kMajor) * kMinor + (j % kMinor)); };
  for (int i = 0; i < kMajor; ++i) {
    for (int j = 0; j < kMinor; ++j) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return m;
}

const TriangleMesh& Torus() {
  static const TriangleMesh mesh = MakeTorus();
  return mesh;
}

// The torus as a binary STL stores it and ReadMeshFile returns it: three float vertices per
// triangle (widened to double), nothing shared.
const MeshFileData& Soup() {
  static const MeshFileData soup = [] {
    MeshFileData d;
    for (const TriangleIndices& t : Torus().triangles) {
      for (std::uint32_t i : t) {
        for (int k = 0; k < 3; ++k) {
          d.xyz.push_back(static_cast<double>(static_cast<float>(Torus().vertices[i][k])));
        }
      }
    }
    for (std::size_t i = 0; i < d.xyz.size() / 3; ++i) d.indices.push_back(std::uint32_t(i));
    return d;
  }();
  return soup;
}

// The 1,000,000-triangle binary STL (50 MB), written to the temporary directory on first use
// and removed when the program ends.
struct TempStl {
  std::string path;
  TempStl()
      : path((std::filesystem::temp_directory_path() / "chasles_bench_torus_1m.stl").string()) {
    std::ofstream f(path, std::ios::binary);
    char header[80] = "binary STL written by mesh_mass_bench";
    f.write(header, 80);
    const auto n = std::uint32_t(Soup().triangle_count());
    f.write(reinterpret_cast<const char*>(&n), 4);
    const float normal[3] = {0, 0, 0};
    const std::uint16_t attr = 0;
    for (std::size_t t = 0; t < n; ++t) {
      float xyz[9];
      for (int k = 0; k < 9; ++k) xyz[k] = static_cast<float>(Soup().xyz[9 * t + k]);
      f.write(reinterpret_cast<const char*>(normal), 12);
      f.write(reinterpret_cast<const char*>(xyz), 36);
      f.write(reinterpret_cast<const char*>(&attr), 2);
    }
  }
  ~TempStl() {
    std::error_code ec;
    std::filesystem::remove(path, ec);
  }
};

const std::string& StlPath() {
  static const TempStl file;
  return file.path;
}

void BM_IntegrateSolid(benchmark::State& state) {
  const TriangleMesh& mesh = Torus();
  for (auto _ : state) benchmark::DoNotOptimize(CalcSolidIntegrals(mesh));
  state.SetItemsProcessed(state.iterations() * std::int64_t(mesh.triangles.size()));
}
BENCHMARK(BM_IntegrateSolid)->Unit(benchmark::kMillisecond);

void BM_IntegrateShell(benchmark::State& state) {
  const TriangleMesh& mesh = Torus();
  for (auto _ : state) benchmark::DoNotOptimize(CalcShellIntegrals(mesh));
  state.SetItemsProcessed(state.iterations() * std::int64_t(mesh.triangles.size()));
}
BENCHMARK(BM_IntegrateShell)->Unit(benchmark::kMillisecond);

void BM_ValidateSolid(benchmark::State& state) {
  TriangleMesh mesh = Torus();  // already consistent: validation changes nothing
  for (auto _ : state) {
    MeshRepairReport report;
    ValidateSolid(mesh, &report);
    benchmark::DoNotOptimize(report.components);
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(mesh.triangles.size()));
}
BENCHMARK(BM_ValidateSolid)->Unit(benchmark::kMillisecond);

// Welding 3,000,000 STL vertices to 500,000 (exact hash, then the near-duplicate grid).
// Argument 0: exact duplicates only (tolerance 0); 1: the default near-duplicate tolerance.
void BM_Weld(benchmark::State& state) {
  const MeshFileData& soup = Soup();
  const double tolerance = state.range(0) == 0 ? 0.0 : std::nan("");
  for (auto _ : state) {
    MeshRepairReport report;
    TriangleMesh m =
        BuildTriangleMesh(std::span<const double>(soup.xyz),
                          std::span<const std::uint32_t>(soup.indices), 1.0, tolerance, &report);
    benchmark::DoNotOptimize(m.vertices.data());
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(soup.triangle_count()));
}
BENCHMARK(BM_Weld)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// Plain reference for welding, timed in the same run: exact duplicates only, through
// std::unordered_map from the three coordinates' bits to the vertex index (what one writes
// first), into the same triangle array.
struct CornerHash {
  std::size_t operator()(const std::array<std::uint64_t, 3>& k) const noexcept {
    return (std::size_t{k[0]} * 0x9E3779B97F4A7C15ULL) ^
           (std::size_t{k[1]} * 0xC2B2AE3D27D4EB4FULL) ^ k[2];
  }
};
void BM_WeldReferenceUnorderedMap(benchmark::State& state) {
  const MeshFileData& soup = Soup();
  const std::size_t n = soup.xyz.size() / 3;
  for (auto _ : state) {
    std::unordered_map<std::array<std::uint64_t, 3>, std::uint32_t, CornerHash> index;
    std::vector<Vec3> vertices;
    std::vector<TriangleIndices> triangles(n / 3);
    for (std::size_t i = 0; i < n; ++i) {
      const double* p = soup.xyz.data() + 3 * i;
      const std::array<std::uint64_t, 3> key{std::bit_cast<std::uint64_t>(p[0]),
                                             std::bit_cast<std::uint64_t>(p[1]),
                                             std::bit_cast<std::uint64_t>(p[2])};
      const auto [it, added] = index.try_emplace(key, std::uint32_t(vertices.size()));
      if (added) vertices.emplace_back(p[0], p[1], p[2]);
      triangles[i / 3][i % 3] = it->second;
    }
    benchmark::DoNotOptimize(triangles.data());
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(soup.triangle_count()));
}
BENCHMARK(BM_WeldReferenceUnorderedMap)->Unit(benchmark::kMillisecond);

// Plain reference for validation, timed in the same run: the textbook edge match, all
// 3,000,000 half-edges as (lower vertex, upper vertex, half-edge) keys sorted with std::sort
// and checked in pairs (no components, no volume).
void BM_ValidateReferenceSort(benchmark::State& state) {
  const TriangleMesh& mesh = Torus();
  for (auto _ : state) {
    std::vector<std::pair<std::uint64_t, std::uint32_t>> edges;
    edges.reserve(3 * mesh.triangles.size());
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
      for (std::uint32_t k = 0; k < 3; ++k) {
        const std::uint32_t a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
        edges.emplace_back(std::uint64_t{std::min(a, b)} << 32 | std::max(a, b), 3 * t + k);
      }
    }
    std::sort(edges.begin(), edges.end());
    std::size_t unmatched = 0;
    for (std::size_t i = 0; i < edges.size(); i += 2) {
      unmatched += i + 1 >= edges.size() || edges[i].first != edges[i + 1].first;
    }
    benchmark::DoNotOptimize(unmatched);
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(mesh.triangles.size()));
}
BENCHMARK(BM_ValidateReferenceSort)->Unit(benchmark::kMillisecond);

void BM_ReadBinaryStlDirect(benchmark::State& state) {
  const std::string& path = StlPath();
  for (auto _ : state) benchmark::DoNotOptimize(internal::ReadBinaryStl(path).xyz.data());
  state.SetItemsProcessed(state.iterations() * std::int64_t(Soup().triangle_count()));
}
BENCHMARK(BM_ReadBinaryStlDirect)->Unit(benchmark::kMillisecond);

// The same file read as the floats it stores (LoadMeshMassProperties where it cannot map it).
void BM_ReadBinaryStlFloats(benchmark::State& state) {
  const std::string& path = StlPath();
  for (auto _ : state) benchmark::DoNotOptimize(TryReadBinaryStlFloats(path)->data());
  state.SetItemsProcessed(state.iterations() * std::int64_t(Soup().triangle_count()));
}
BENCHMARK(BM_ReadBinaryStlFloats)->Unit(benchmark::kMillisecond);

// The same file mapped, its floats left where they are (TryMapBinaryStl), as
// LoadMeshMassProperties reads it; and welded from there (BuildTriangleSoup of the records).
void BM_MapBinaryStl(benchmark::State& state) {
  const std::string& path = StlPath();
  for (auto _ : state) benchmark::DoNotOptimize(TryMapBinaryStl(path)->coordinates);
  state.SetItemsProcessed(state.iterations() * std::int64_t(Soup().triangle_count()));
}
BENCHMARK(BM_MapBinaryStl)->Unit(benchmark::kMillisecond);

void BM_WeldMappedBinaryStl(benchmark::State& state) {
  const std::optional<MappedBinaryStl> stl = TryMapBinaryStl(StlPath());
  const FloatSoupRecords records{
      stl->coordinates, stl->triangles, MappedBinaryStl::kRecordBytes, {}};
  for (auto _ : state) {
    MeshRepairReport report;
    TriangleMesh m = BuildTriangleSoup(records, 1.0, std::nan(""), &report);
    benchmark::DoNotOptimize(m.vertices.data());
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(stl->triangles));
}
BENCHMARK(BM_WeldMappedBinaryStl)->Unit(benchmark::kMillisecond);

void BM_ReadBinaryStlAssimp(benchmark::State& state) {
  const std::string& path = StlPath();
  for (auto _ : state) benchmark::DoNotOptimize(bench::ReadWithAssimp(path).xyz.data());
  state.SetItemsProcessed(state.iterations() * std::int64_t(Soup().triangle_count()));
}
BENCHMARK(BM_ReadBinaryStlAssimp)->Unit(benchmark::kMillisecond);

// Read + weld + validate + integrate, as the scene loader and the CLI call it.
void BM_EndToEndBinaryStl(benchmark::State& state) {
  const std::string& path = StlPath();
  MeshMassOptions opts;
  opts.density = 7850;
  for (auto _ : state) {
    MeshMassResult res = LoadMeshMassProperties(path, opts);
    benchmark::DoNotOptimize(res.mass_properties.mass());
    state.counters["read_s"] = res.report.read_seconds;
    state.counters["weld_s"] = res.report.weld_seconds;
    state.counters["validate_s"] = res.report.validate_seconds;
    state.counters["integrate_s"] = res.report.integrate_seconds;
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(Soup().triangle_count()));
}
BENCHMARK(BM_EndToEndBinaryStl)->Unit(benchmark::kMillisecond);

// The same path with assimp reading the STL instead of the direct reader, for comparison.
void BM_EndToEndBinaryStlViaAssimp(benchmark::State& state) {
  const std::string& path = StlPath();
  for (auto _ : state) {
    const MeshFileData d = bench::ReadWithAssimp(path);
    MeshRepairReport report;
    TriangleMesh m =
        BuildTriangleMesh(std::span<const double>(d.xyz), std::span<const std::uint32_t>(d.indices),
                          1.0, std::nan(""), &report);
    ValidateSolid(m, &report);
    benchmark::DoNotOptimize(MassPropertiesFromIntegrals(CalcSolidIntegrals(m), 7850).mass());
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(Soup().triangle_count()));
}
BENCHMARK(BM_EndToEndBinaryStlViaAssimp)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace chasles

BENCHMARK_MAIN();
