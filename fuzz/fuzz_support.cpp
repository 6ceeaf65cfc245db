#include "fuzz_support.h"

#include <fstream>

#include <unistd.h>

namespace chasles::fuzz {

const std::filesystem::path& ScratchDir() {
  static const std::filesystem::path dir = [] {
    std::filesystem::path d =
        std::filesystem::temp_directory_path() / ("chasles-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    // Removed at exit; a crashed process leaves it in the system temporary folder.
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(ScratchDir(), ec);
    });
    return d;
  }();
  return dir;
}

std::string WriteScratchFile(const std::string& name, std::string_view bytes) {
  const std::filesystem::path path = ScratchDir() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) Fail("cannot write the scratch file", path.string());
  return path.string();
}

void Fail(const char* what, std::string_view detail) {
  std::fprintf(stderr, "fuzz: broken promise: %s: %.*s\n", what, static_cast<int>(detail.size()),
               detail.data());
  std::abort();
}

}  // namespace chasles::fuzz
