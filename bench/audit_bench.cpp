// The audit of every shared robot (../shared/robots) in URDF and of their MJCF and SDF versions
// (tests/robots): reading the files and their Collada meshes, integrating every link's
// geometry, the checks. docs/audit.md records the figures.

#include <filesystem>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "chasles/analysis/audit.h"
#include "chasles/files/collada_reader.h"
#include "chasles/files/robot_reader.h"
#include "chasles/scene/robot_file.h"

namespace {

namespace fs = std::filesystem;

const fs::path kShared = fs::path(CHASLES_SOURCE_DIR) / ".." / "shared" / "robots";

std::vector<std::string> RobotFiles() {
  std::vector<std::string> files;
  if (!fs::is_directory(kShared)) return files;
  for (const auto& e : fs::recursive_directory_iterator(kShared)) {
    if (e.path().extension() == ".urdf") files.push_back(e.path().string());
  }
  for (const char* dir : {"tests/robots/mjcf", "tests/robots/sdf"}) {
    for (const auto& e : fs::directory_iterator(fs::path(CHASLES_SOURCE_DIR) / dir)) {
      files.push_back(e.path().string());
    }
  }
  return files;
}

// The whole folder as `chasles audit` reads it: every file, every mesh read afresh.
void BM_AuditEveryRobot(benchmark::State& state) {
  const std::vector<std::string> files = RobotFiles();
  if (files.empty()) {
    state.SkipWithError("../shared/robots is absent");
    return;
  }
  chasles::RobotReadOptions read;
  read.packages = {
      {"example-robot-data", (kShared / "example-robot-data").string()},
      {"ur_description", (kShared / "compas_fab/robot_library/ur_description").string()}};
  std::size_t links = 0;
  for (auto _ : state) {
    chasles::AuditOptions options;
    options.cache = chasles::MakeAuditMeshCache(chasles::LoadMeshTriangles);
    links = 0;
    for (const std::string& f : files) {
      const chasles::RobotAudit a = chasles::AuditRobot(chasles::ReadRobotFile(f, read), options);
      links += a.links.size();
    }
    benchmark::DoNotOptimize(links);
  }
  state.counters["files"] = static_cast<double>(files.size());
  state.counters["links"] = static_cast<double>(links);
}
BENCHMARK(BM_AuditEveryRobot)->Unit(benchmark::kMillisecond);

// Reading the largest Collada mesh of the set (the UR5's upper arm, 2 MB, 29 436 triangles).
void BM_ReadCollada(benchmark::State& state) {
  const fs::path file =
      kShared / "example-robot-data/robots/ur_description/meshes/ur5/visual/upperarm.dae";
  if (!fs::exists(file)) {
    state.SkipWithError("../shared/robots is absent");
    return;
  }
  for (auto _ : state) {
    benchmark::DoNotOptimize(chasles::ReadColladaFile(file.string()));
  }
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(fs::file_size(file)));
}
BENCHMARK(BM_ReadCollada)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
