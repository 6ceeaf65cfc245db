#include "scene_args.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/scene/scene_error.h"

namespace chasles::cli {

void AddSceneArgs(CLI::App& cmd, SceneArgs& args) {
  cmd.add_option("scene", args.scene,
                 "Scene file (YAML). Without one, the built-in demonstration scene is used.");
  cmd.add_option("--set", args.set,
                 "Override a scene parameter: NAME=EXPRESSION, e.g. --set 'h1=0.25*h'; one "
                 "parameter per --set (repeat --set for each: --set a=1 --set b=2)")
      ->type_name("NAME=EXPR")
      ->allow_extra_args(false)
      ->delimiter('\0');  // an expression may contain commas and brackets: keep it whole
  cmd.add_option("--max-scene-bytes", args.max_scene_bytes,
                 "Largest scene file read, in bytes (default 16777216, 16 MiB); a larger file, "
                 "or a pipe or device that gives more, is refused before it is parsed")
      ->check(WholeNumber(kMaxWholeNumber));
}

CLI::Validator PositiveFiniteNumber(const std::string& rule) {
  return CLI::Validator(
      [rule](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0' || !std::isfinite(v) || !(v > 0)) {
          return rule + " (a positive, finite number), got '" + text + "'";
        }
        return "";
      },
      "POSITIVE");
}

CLI::Validator WholeNumber(std::int64_t max) {
  return CLI::Validator(
      [max](std::string& text) -> std::string {
        std::int64_t v = 0;
        const char* end = text.data() + text.size();
        const auto [ptr, ec] = std::from_chars(text.data(), end, v);
        if (text.empty() || ptr != end || ec != std::errc() || v < 1 || v > max) {
          return fmt::format("expected a whole number from 1 to {}, got '{}'", max, text);
        }
        return "";
      },
      "N");
}

SceneOptions SceneOptionsFrom(const SceneArgs& args) {
  SceneOptions options;
  options.max_scene_bytes = args.max_scene_bytes;
  for (const std::string& s : args.set) {
    const auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw SceneError("command line", 0, 0, "--set",
                       "expected NAME=EXPRESSION, e.g. --set 'h1=0.25*h', got '" + s + "'");
    }
    options.parameter_overrides.emplace_back(s.substr(0, eq), s.substr(eq + 1));
  }
  return options;
}

std::function<Scene(const SceneOptions&)> SceneLoader(const SceneArgs& args) {
  const std::string path = args.scene;
  return [path](const SceneOptions& options) {
    if (path.empty()) return LoadSceneText(kDemoScene, "<built-in demonstration>", options);
    return LoadSceneFile(path, options);
  };
}

Scene LoadScene(const SceneArgs& args) {
  return SceneLoader(args)(SceneOptionsFrom(args));
}

std::string ResolveBesideJson(const std::string& path, const std::string& json_path) {
  if (path.empty() || std::filesystem::exists(path)) return path;
  const std::filesystem::path beside =
      std::filesystem::path(json_path).parent_path() / std::filesystem::path(path).filename();
  return std::filesystem::exists(beside) ? beside.string() : path;
}

std::string ReportTarget(const std::string& output) {
  return output.empty() ? std::string("-") : output;
}

}  // namespace chasles::cli
