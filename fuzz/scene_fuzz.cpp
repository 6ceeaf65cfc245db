// Fuzz target: the scene loader and everything `chasles solve` does with a scene (units,
// expressions, shapes, model building, the instantaneous solve and its report).
// Promise: the program's exit code is 0, 2 (bad input) or 3 (a failed check) — never 1 (an
// internal error), never a crash or a hang.

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz_support.h"
#include "program.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // Reports are not what is tested; keep them out of the fuzzer's output.
  if (std::freopen("/dev/null", "w", stdout) == nullptr) return 1;
  // Scenes name meshes relative to their own folder (examples/meshes/...): offer the same
  // folder next to the scratch scene, so the seeds from examples/ load their meshes.
  std::error_code ec;
  std::filesystem::create_directory_symlink(
      std::filesystem::path(CHASLES_SOURCE_DIR) / "examples" / "meshes",
      chasles::fuzz::ScratchDir() / "meshes", ec);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const std::string path = chasles::fuzz::WriteScratchFile("scene.yaml", text);
  std::vector<std::string> args{"chasles", "solve", path, "--format", "json"};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const int code = chasles::cli::Main(static_cast<int>(args.size()), argv.data());
  std::fflush(stdout);
  if (code == chasles::cli::kExitInternal) {
    chasles::fuzz::Fail("chasles solve exited with 1 (internal error)", text);
  }
  return 0;
}
