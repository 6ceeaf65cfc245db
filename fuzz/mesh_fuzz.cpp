// Fuzz target: every mesh reader and the mesh mass pipeline behind it (weld, repair,
// integrate). Each input is tried as every supported format, by file extension, so one corpus
// of mesh files serves all readers.
// Promise: a malformed mesh is an InputError — never a crash, a hang, another exception, or an
// allocation far beyond the file's size (libFuzzer's -rss_limit_mb and -malloc_limit_mb catch
// those) — and a mesh that is accepted has finite mass properties.

#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

#include "chasles/error.h"
#include "chasles/scene/mesh_file.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  for (const char* ext : {"stl", "ply", "off", "obj"}) {
    const std::string path = chasles::fuzz::WriteScratchFile(std::string("mesh.") + ext, bytes);
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
        const chasles::MeshMassResult r = chasles::LoadMeshMassProperties(path, opts);
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
