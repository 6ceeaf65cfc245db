// Fuzz target: every mesh reader (src/files/) and the mesh mass pipeline behind it (weld, repair,
// integrate). Each input is read as every supported format, in memory, so one corpus of mesh
// files serves all readers.
// Promise: a malformed mesh is an InputError — never a crash, a hang, another exception, an
// index out of range, a coordinate that is not finite or beyond ±kMaxMeshCoordinate, or an
// allocation far beyond the input's size (libFuzzer's -rss_limit_mb and -malloc_limit_mb catch
// those) — and a mesh that is accepted has finite mass properties in solid and in shell mode.

#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

#include "chasles/error.h"
#include "chasles/mass/mesh_mass.h"
#include "files/internal/mesh_readers.h"
#include "fuzz_support.h"

namespace {

void CheckMesh(const chasles::MeshFileData& data, const char* ext) {
  if (data.xyz.size() % 3 != 0 || data.indices.size() % 3 != 0) {
    chasles::fuzz::Fail("a reader returned a partial vertex or triangle", ext);
  }
  for (double c : data.xyz) {
    if (!(std::abs(c) <= chasles::kMaxMeshCoordinate)) {
      chasles::fuzz::Fail("a reader returned a coordinate beyond the mesh range", ext);
    }
  }
  for (std::uint32_t i : data.indices) {
    if (i >= data.vertex_count()) chasles::fuzz::Fail("a reader returned a bad index", ext);
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  for (const char* ext : {"stl", "ply", "off", "obj"}) {
    chasles::MeshFileData mesh;
    try {
      mesh = chasles::internal::ReadMeshBytes(bytes, std::string("fuzz.") + ext);
    } catch (const chasles::InputError&) {
      continue;
    } catch (const std::exception& e) {
      chasles::fuzz::Fail(e.what(), ext);
    }
    CheckMesh(mesh, ext);
    for (const bool shell : {false, true}) {
      chasles::MeshMassOptions opts;
      opts.scale = 1e-3;
      if (shell) {
        opts.mode = chasles::MeshMassMode::kShell;
        opts.areal_density = 2.0;
      } else {
        opts.density = 7850.0;
      }
      try {
        std::vector<double> xyz = mesh.xyz;
        std::vector<std::uint32_t> indices = mesh.indices;
        const chasles::MeshMassResult r = chasles::ComputeMeshMassProperties(
            std::move(xyz), std::move(indices), opts, std::string("fuzz.") + ext);
        const chasles::MassProperties& p = r.mass_properties;
        if (!std::isfinite(p.mass()) || !p.p_BoBcm_B().allFinite() ||
            !p.I_BBcm_B().matrix().allFinite()) {
          chasles::fuzz::Fail("an accepted mesh has non-finite mass properties", ext);
        }
      } catch (const chasles::InputError&) {
      } catch (const std::exception& e) {
        chasles::fuzz::Fail(e.what(), ext);
      }
    }
  }
  return 0;
}
