#include <fmt/format.h>

#include "chasles/scene/scene.h"
#include "commands.h"
#include "scene_args.h"

namespace chasles::cli {

CLI::App* AddCheckCommand(CLI::App& app, CheckArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "check", "Read and validate a scene without computing a report; exit 0 when it is good");
  AddSceneArgs(*cmd, args.scene);
  cmd->footer("Example:\n  chasles check examples/example-8.2-two-rods.yaml");
  return cmd;
}

int RunCheck(const CheckArgs& args) {
  const Scene scene = LoadScene(args.scene);
  size_t parts = 0;
  for (const auto& b : scene.bodies) parts += b.parts.size();
  fmt::print("{}: ok ({} bod{}, {} part{}, {} parameter{})\n", scene.file, scene.bodies.size(),
             scene.bodies.size() == 1 ? "y" : "ies", parts, parts == 1 ? "" : "s",
             scene.parameters.size(), scene.parameters.size() == 1 ? "" : "s");
  for (const auto& w : scene.warnings) fmt::print("warning: {}\n", w);
  return 0;
}

}  // namespace chasles::cli
