#include "cluster.h"

#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>

#include <fmt/format.h>

#include "chasles/error.h"
#include "mpi/chasles_mpi.h"

namespace chasles::cli {

struct Cluster::Plugin {
  void* handle = nullptr;
  chasles_mpi_gather_fn gather = nullptr;
  chasles_mpi_broadcast_int_fn broadcast_int = nullptr;
  chasles_mpi_finalize_fn finalize = nullptr;
};

namespace {

int EnvInt(const char* name, int fallback) {
  const char* v = std::getenv(name);
  if (!v || !*v) return fallback;
  char* end = nullptr;
  const long n = std::strtol(v, &end, 10);
  return *end == '\0' && n >= 0 && n < 1 << 30 ? static_cast<int>(n) : fallback;
}

/// Where the plugin may be, in order.
std::vector<std::string> PluginCandidates() {
  constexpr const char* kName = "libchasles_mpi.so";
  if (const char* given = std::getenv("CHASLES_MPI_PLUGIN"); given && *given) return {given};
  std::vector<std::string> out;
  std::error_code e;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", e);
  if (!e) {
    const std::filesystem::path dir = exe.parent_path();
    out.push_back((dir.parent_path() / "lib" / kName).string());
    out.push_back((dir.parent_path() / CHASLES_MPI_LIBDIR / kName).string());
    out.push_back((dir / kName).string());
  }
  out.push_back(kName);  // LD_LIBRARY_PATH and the system's folders
  return out;
}

void Check(int e, const char* what) {
  if (e != 0) throw InputError(fmt::format("MPI: {} failed with MPI error code {}", what, e));
}

}  // namespace

Cluster& Cluster::Get() {
  static Cluster cluster;
  return cluster;
}

int Cluster::LaunchedSize() {
  return EnvInt("OMPI_COMM_WORLD_SIZE", EnvInt("PMI_SIZE", 1));
}

int Cluster::LaunchedRank() {
  return EnvInt("OMPI_COMM_WORLD_RANK", EnvInt("PMI_RANK", 0));
}

void Cluster::Start() {
  void* handle = nullptr;
  std::string tried;
  for (const std::string& path : PluginCandidates()) {
    // RTLD_GLOBAL: Open MPI's own components, which it opens in turn, need libmpi's symbols.
    const bool named = path.find('/') != std::string::npos;
    if (named && !std::filesystem::exists(path)) {
      tried += fmt::format("\n  {}: no such file", path);
      continue;
    }
    handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_GLOBAL);
    if (handle) break;
    tried += fmt::format("\n  {}: {}", path, ::dlerror());
  }
  if (!handle) {
    throw InputError(fmt::format(
        "started by mpirun with {} processes, but the MPI plugin libchasles_mpi.so cannot be "
        "loaded, so the sweep cannot be split (and {} full copies would run); build chasles with "
        "MPI (Debian: libopenmpi-dev, CMake option CHASLES_MPI), install Open MPI's run-time "
        "(openmpi-bin), or set CHASLES_MPI_PLUGIN to the plugin's path. Tried:{}",
        LaunchedSize(), LaunchedSize(), tried));
  }
  const auto symbol = [handle](const char* name) {
    void* s = ::dlsym(handle, name);
    if (!s) {
      throw InputError(
          fmt::format("the MPI plugin has no function {}: it is not chasles' plugin "
                      "of this version",
                      name));
    }
    return s;
  };
  const auto abi = reinterpret_cast<chasles_mpi_abi_fn>(symbol("chasles_mpi_abi"));
  if (abi() != CHASLES_MPI_ABI) {
    throw InputError(fmt::format("the MPI plugin has interface version {}, this program needs {}",
                                 abi(), CHASLES_MPI_ABI));
  }
  const auto init = reinterpret_cast<chasles_mpi_init_fn>(symbol("chasles_mpi_init"));
  plugin_ = new Plugin{
      handle, reinterpret_cast<chasles_mpi_gather_fn>(symbol("chasles_mpi_gather")),
      reinterpret_cast<chasles_mpi_broadcast_int_fn>(symbol("chasles_mpi_broadcast_int")),
      reinterpret_cast<chasles_mpi_finalize_fn>(symbol("chasles_mpi_finalize"))};
  Check(init(&rank_, &size_), "MPI_Init");
}

void Cluster::Finish() {
  if (!plugin_) return;
  plugin_->finalize();
  // The library stays open: MPI's atexit handlers may still run from it.
  delete plugin_;
  plugin_ = nullptr;
  rank_ = 0;
  size_ = 1;
}

std::vector<SweepPart> Cluster::Exchange(const SweepPart& mine) {
  exchanged_ = true;
  if (!distributed()) return {mine};
  const std::string bytes = EncodeSweepPart(mine);
  std::vector<std::string> received;
  const chasles_mpi_sink_fn sink = [](void* context, int, const char* data, int64_t size) {
    static_cast<std::vector<std::string>*>(context)->emplace_back(data, static_cast<size_t>(size));
  };
  Check(plugin_->gather(bytes.data(), static_cast<int64_t>(bytes.size()), sink, &received),
        "gathering the sweep's rows");
  std::vector<SweepPart> parts;
  for (const std::string& r : received) parts.push_back(DecodeSweepPart(r));
  return parts;
}

int Cluster::AgreeExitCode(int code) {
  if (!distributed()) return code;
  Check(plugin_->broadcast_int(&code), "broadcasting the exit code");
  return code;
}

bool GatherSweep(SweepTable* table, SweepWarnings* warnings, bool* check_failed) {
  Cluster& cluster = Cluster::Get();
  if (!cluster.distributed()) return true;
  SweepPart mine = TakeSweepPart(*table, cluster.share(), *warnings);
  mine.check_failed = *check_failed;
  const std::vector<SweepPart> parts = cluster.Exchange(mine);
  if (cluster.rank() != 0) return false;
  if (const SweepPart* f = FirstFailure(parts)) throw RankFailure(f->code, f->message);
  MergeSweepParts(parts, table, warnings);
  *check_failed = false;
  for (const SweepPart& p : parts) *check_failed = *check_failed || p.check_failed;
  return true;
}

}  // namespace chasles::cli
