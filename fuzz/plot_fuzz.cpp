// Fuzz target: `chasles plot` on a table of the fuzzer's making. The input is split at NUL
// bytes: the first part is the table (a CSV as `chasles simulate` and the sweeps write it), the
// others the columns to draw (X, then Ys) and options: "--log", "--png" (PNG instead of SVG),
// "--json" (the table reached through a run's JSON summary naming it, as `chasles report`
// finds it) and "--by=COLUMN". The command is parsed and run in-process as the program does.
// Promise: exit 0 with the plot complete and free of non-finite coordinates, or exit 2 with no
// plot at all; never exit 1, a crash, a hang or a temporary left in the folder.

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz_support.h"
#include "program.h"

namespace {

namespace fs = std::filesystem;

std::string ReadAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

bool EndsWith(std::string_view s, std::string_view tail) {
  return s.size() >= tail.size() && s.substr(s.size() - tail.size()) == tail;
}

/// True when a quoted attribute value of the SVG holds "nan" or "inf" as a word of its own
/// (PLplot prints a non-finite coordinate so); the texts between tags may say anything.
bool SvgHasNonFiniteNumber(const std::string& svg) {
  const auto letter = [](char c) { return (c | 0x20) >= 'a' && (c | 0x20) <= 'z'; };
  size_t pos = 0;
  while ((pos = svg.find("=\"", pos)) != std::string::npos) {
    const size_t end = svg.find('"', pos + 2);
    if (end == std::string::npos) return false;
    for (size_t i = pos + 2; i + 3 <= end; ++i) {
      const std::string word = {static_cast<char>(svg[i] | 0x20),
                                static_cast<char>(svg[i + 1] | 0x20),
                                static_cast<char>(svg[i + 2] | 0x20)};
      if (word != "nan" && word != "inf") continue;
      if (!letter(svg[i - 1]) && (i + 3 == end || !letter(svg[i + 3]))) return true;
    }
    pos = end + 1;
  }
  return false;
}

/// The plot written on exit 0: a whole SVG (its closing tag last) without a non-finite
/// coordinate, or a whole PNG (its IEND chunk last).
void CheckPlot(const fs::path& path, bool png, std::string_view input) {
  const std::string bytes = ReadAll(path);
  if (png) {
    static const std::string_view kIend("IEND\xae\x42\x60\x82", 8);
    if (bytes.rfind("\x89PNG", 0) != 0 || !EndsWith(bytes, kIend)) {
      chasles::fuzz::Fail("exit 0 but the PNG is not whole", input);
    }
    return;
  }
  if (bytes.rfind("<?xml", 0) != 0 || !EndsWith(bytes, "</svg>\n")) {
    chasles::fuzz::Fail("exit 0 but the SVG is not whole", input);
  }
  if (SvgHasNonFiniteNumber(bytes)) {
    chasles::fuzz::Fail("exit 0 but the SVG has a non-finite coordinate", input);
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  if (std::freopen("/dev/null", "w", stdout) == nullptr) return 1;
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> parts;
  for (size_t start = 0, i = 0; i <= size && parts.size() < 12; ++i) {
    if (i == size || text[i] == '\0') {
      parts.emplace_back(text.substr(start, i - start));
      start = i + 1;
    }
  }
  const fs::path& dir = chasles::fuzz::ScratchDir();
  bool png = false, json = false;
  std::vector<std::string> options, columns;
  for (size_t k = 1; k < parts.size(); ++k) {
    if (parts[k] == "--png") {
      png = true;
    } else if (parts[k] == "--json") {
      json = true;
    } else if (parts[k] == "--log" || parts[k].rfind("--by=", 0) == 0) {
      options.push_back(parts[k]);
    } else {
      columns.push_back(parts[k]);
    }
  }
  if (columns.size() < 2) return 0;  // the parser needs X and a Y
  std::string table = chasles::fuzz::WriteScratchFile("table.csv", parts[0]);
  if (json) table = chasles::fuzz::WriteScratchFile("run.json", R"({"csv": "table.csv"})");
  const fs::path output = dir / (png ? "plot.png" : "plot.svg");
  std::vector<std::string> args = {"chasles",           "plot",   "-o", output.string(),
                                   "--max-input-bytes", "1048576"};
  args.insert(args.end(), options.begin(), options.end());
  args.insert(args.end(), {"--", table});  // the columns may start with '-'
  args.insert(args.end(), columns.begin(), columns.end());
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  auto program = chasles::cli::MakeProgram();
  if (program->plot == nullptr) return 0;  // a build without PLplot
  try {
    program->app.parse(static_cast<int>(args.size()), argv.data());
  } catch (const CLI::ParseError&) {
    return 0;  // e.g. an empty --by=
  }
  const int code = chasles::cli::RunParsed(*program);
  std::fflush(stdout);
  if (code != 0 && code != chasles::cli::kExitBadInput) {
    chasles::fuzz::Fail("chasles plot exited with neither 0 nor 2", text);
  }
  std::error_code ec;
  if (code == 0) {
    CheckPlot(output, png, text);
  } else if (fs::exists(output, ec)) {
    chasles::fuzz::Fail("chasles plot failed but left its plot", text);
  }
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name != "table.csv" && name != "run.json" && e.path() != output) {
      chasles::fuzz::Fail("chasles plot left a file behind", name);
    }
  }
  fs::remove(output, ec);
  fs::remove(dir / "run.json", ec);
  return 0;
}
