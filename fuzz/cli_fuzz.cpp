// Fuzz target: the command-line parser and the checks each command makes of its options.
// The input is split at NUL bytes into arguments. Commands that only read (mass, check,
// solve, upgrade without --in-place) are then run, provided every file they would read is
// inside the source tree and no output file is asked for; simulate is only parsed (it writes
// files and may run long).
// Promise: parse errors are reported (exit 2), and a run's exit code is never 1.

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz_support.h"
#include "program.h"

namespace {

// True for "" (the built-in scene) or a regular file under the source tree: the fuzzer must
// not make the program read /dev/stdin or write outside its scratch folder.
bool SafeToRead(const std::string& path) {
  if (path.empty()) return true;
  std::error_code ec;
  const std::filesystem::path p = std::filesystem::weakly_canonical(path, ec);
  if (ec || !std::filesystem::is_regular_file(p, ec)) return false;
  const std::string root = std::filesystem::weakly_canonical(CHASLES_SOURCE_DIR, ec).string();
  return p.string().rfind(root + "/", 0) == 0;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  if (std::freopen("/dev/null", "w", stdout) == nullptr) return 1;
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> args{"chasles"};
  std::size_t start = 0;
  for (std::size_t i = 0; i <= size && args.size() < 33; ++i) {
    if (i == size || text[i] == '\0') {
      args.emplace_back(text.substr(start, i - start));
      start = i + 1;
    }
  }
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  auto program = chasles::cli::MakeProgram();
  try {
    program->app.parse(static_cast<int>(args.size()), argv.data());
  } catch (const CLI::ParseError&) {
    return 0;  // --help, --version and every parse error: reported by CLI11, exit 0 or 2
  } catch (const std::exception& e) {
    chasles::fuzz::Fail(e.what(), text);
  }
  const chasles::cli::Program& p = *program;
  bool run = false;
  if (p.mass->parsed()) {
    run = SafeToRead(p.mass_args.scene.scene) && p.mass_args.output.empty();
  } else if (p.check->parsed()) {
    run = SafeToRead(p.check_args.scene.scene);
  } else if (p.solve->parsed()) {
    run = SafeToRead(p.solve_args.scene.scene);
  } else if (p.upgrade->parsed()) {
    run = SafeToRead(p.upgrade_args.scene) && p.upgrade_args.output.empty() &&
          !p.upgrade_args.in_place;
  } else if (p.materials->parsed()) {
    run = true;
  }
  if (!run) return 0;
  const int code = chasles::cli::RunParsed(*program);
  std::fflush(stdout);
  if (code == chasles::cli::kExitInternal) {
    chasles::fuzz::Fail("a command exited with 1 (internal error)", text);
  }
  return 0;
}
