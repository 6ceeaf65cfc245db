#include "scene_args.h"

#include <cstdio>

#include "chasles/io/atomic_file.h"
#include "chasles/scene/scene_error.h"

namespace chasles::cli {

void AddSceneArgs(CLI::App& cmd, SceneArgs& args) {
  cmd.add_option("scene", args.scene,
                 "Scene file (YAML). Without one, the built-in demonstration scene is used.");
  cmd.add_option("--set", args.set,
                 "Override a scene parameter: NAME=EXPRESSION, e.g. --set 'h1=0.25*h' (repeatable)")
      ->allow_extra_args(false)
      ->delimiter('\0');  // an expression may contain commas and brackets: keep it whole
}

Scene LoadScene(const SceneArgs& args) {
  SceneOptions options;
  for (const std::string& s : args.set) {
    const auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw SceneError("command line", 0, 0, "--set",
                       "expected NAME=EXPRESSION, e.g. --set 'h1=0.25*h', got '" + s + "'");
    }
    options.parameter_overrides.emplace_back(s.substr(0, eq), s.substr(eq + 1));
  }
  if (args.scene.empty()) return LoadSceneText(kDemoScene, "<built-in demonstration>", options);
  return LoadSceneFile(args.scene, options);
}

void Emit(const std::string& output, const std::string& text) {
  if (output.empty()) {
    std::fwrite(text.data(), 1, text.size(), stdout);
    std::fflush(stdout);
  } else {
    WriteFileAtomically(output, text);
  }
}

}  // namespace chasles::cli
