// Fuzz target: `chasles report` on a run of the fuzzer's making. The input is split at NUL
// bytes into the run's JSON summary, its CSV and its scene, written as run.json, run.csv and
// scene.yaml in a folder of their own (the summary names the other two, found beside it as
// the command finds them). The command is parsed and run in-process as the program does. A
// summary naming a file outside that folder and the source tree is not run: the fuzzer must
// not make the program read /dev/stdin.
// Promise: exit 0 with the page complete (its embedded data whole JSON), or exit 2 with no page
// at all; never exit 1, a crash, a hang or a temporary left in the folder.

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "chasles/error.h"
#include "chasles/files/input_file.h"
#include "chasles/report/json_input.h"
#include "fuzz_support.h"
#include "program.h"
#include "scene_args.h"

namespace {

namespace fs = std::filesystem;

/// True for a regular file under the scratch folder or the source tree.
bool SafeToRead(const std::string& path) {
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(path, ec);
  if (ec || !fs::is_regular_file(p, ec)) return false;
  for (const fs::path& root : {fs::path(CHASLES_SOURCE_DIR), chasles::fuzz::ScratchDir()}) {
    if (p.string().rfind(fs::weakly_canonical(root, ec).string() + "/", 0) == 0) return true;
  }
  return false;
}

/// Whether every file the summary names (its "scene" and "csv", resolved as the command
/// resolves them) is safe to read. A summary that is not JSON, or names them with another
/// type, is refused by the command before it reads anything more.
bool NamesOnlySafeFiles(const std::string& json_path) {
  nlohmann::json j;
  try {
    j = chasles::ParseJsonText(chasles::ReadInputFile(json_path, "the summary", 1 << 20, ""),
                               json_path);
  } catch (const chasles::InputError&) {
    return true;
  }
  if (!j.is_object()) return true;
  for (const char* key : {"scene", "csv"}) {
    if (!j.contains(key) || !j.at(key).is_string()) continue;
    const std::string path =
        chasles::cli::ResolveBesideJson(j.at(key).get<std::string>(), json_path);
    if (!path.empty() && !SafeToRead(path)) return false;
  }
  return true;
}

/// The page written on exit 0: whole (its closing tag last), its data a whole JSON document.
void CheckPage(const fs::path& path, std::string_view input) {
  std::ifstream in(path, std::ios::binary);
  const std::string page((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (page.size() < 8 || page.substr(page.size() - 8) != "</html>\n") {
    chasles::fuzz::Fail("exit 0 but the page is not whole", input);
  }
  const std::string open = "<script type=\"application/json\" id=\"chasles-data\">";
  const size_t start = page.find(open);
  const size_t end = page.find("</script>", start);
  if (start == std::string::npos || end == std::string::npos) {
    chasles::fuzz::Fail("exit 0 but the page has no data", input);
  }
  const std::string data = page.substr(start + open.size(), end - start - open.size());
  if (!nlohmann::json::accept(data)) {
    chasles::fuzz::Fail("exit 0 but the page's data is not JSON (a NaN written?)", input);
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  if (std::freopen("/dev/null", "w", stdout) == nullptr) return 1;
  // Scenes name meshes relative to their own folder, as in the scene target.
  std::error_code ec;
  fs::create_directory_symlink(fs::path(CHASLES_SOURCE_DIR) / "examples" / "meshes",
                               chasles::fuzz::ScratchDir() / "meshes", ec);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string_view> parts;
  for (size_t start = 0, i = 0; i <= size && parts.size() < 3; ++i) {
    if (i == size || text[i] == '\0') {
      // The scene is the rest of the input, NUL bytes and all (the loader refuses them).
      parts.push_back(parts.size() == 2 ? text.substr(start) : text.substr(start, i - start));
      start = i + 1;
    }
  }
  const fs::path& dir = chasles::fuzz::ScratchDir();
  const std::vector<std::string> names = {"run.json", "run.csv", "scene.yaml"};
  std::error_code ec;
  for (size_t k = 0; k < names.size(); ++k) {
    if (k < parts.size()) {
      chasles::fuzz::WriteScratchFile(names[k], parts[k]);
    } else {
      fs::remove(dir / names[k], ec);
    }
  }
  const std::string json = (dir / "run.json").string();
  if (!NamesOnlySafeFiles(json)) return 0;
  const fs::path output = dir / "report.html";
  std::vector<std::string> args = {"chasles",           "report", json, "-o", output.string(),
                                   "--max-input-bytes", "1048576"};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  auto program = chasles::cli::MakeProgram();
  program->app.parse(static_cast<int>(args.size()), argv.data());
  const int code = chasles::cli::RunParsed(*program);
  std::fflush(stdout);
  if (code != 0 && code != chasles::cli::kExitBadInput) {
    chasles::fuzz::Fail("chasles report exited with neither 0 nor 2", text);
  }
  if (code == 0) {
    CheckPage(output, text);
  } else if (fs::exists(output, ec)) {
    chasles::fuzz::Fail("chasles report failed but left its page", text);
  }
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name != "meshes" && name != "report.html" &&
        std::find(names.begin(), names.end(), name) == names.end()) {
      chasles::fuzz::Fail("chasles report left a file behind", name);
    }
  }
  fs::remove(output, ec);
  return 0;
}
