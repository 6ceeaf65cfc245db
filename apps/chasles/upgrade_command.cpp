#include <cstdio>
#include <filesystem>

#include <fmt/format.h>

#include "certificate_report.h"
#include "chasles/error.h"
#include "chasles/files/atomic_file.h"
#include "chasles/files/output_set.h"
#include "chasles/scene/scene_upgrade.h"
#include "commands.h"
#include "scene_args.h"
#include "unified_diff.h"

namespace chasles::cli {

CLI::App* AddUpgradeCommand(CLI::App& app, UpgradeArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "upgrade",
      fmt::format("Rewrite a scene as format version {}: the version line and each older "
                  "version's spelling are edited where they stand, and 'integrator: adaptive' "
                  "written where a scene with contacts names none (comments and layout kept); "
                  "the unified diff goes to standard output",
                  kSceneFormatVersion));
  cmd->add_option("scene", args.scene, "Scene file (YAML)")->required();
  CLI::Option* out = cmd->add_option("-o,--out", args.output,
                                     "Write the upgraded scene here (complete or not at all)");
  CLI::Option* in_place =
      cmd->add_flag("--in-place", args.in_place,
                    "Replace the scene file by its upgrade (complete or not at all)");
  out->excludes(in_place);
  cmd->add_flag("--check", args.check,
                "Write nothing: exit 3 when the scene needs upgrading (the diff shows how), 0 "
                "when it is current")
      ->excludes(out)
      ->excludes(in_place);
  cmd->add_option("--max-scene-bytes", args.max_scene_bytes,
                  "Largest scene file read, in bytes (default 16777216, 16 MiB)")
      ->check(WholeNumber(kMaxWholeNumber));
  cmd->footer(
      "Without -o or --in-place nothing is written: the diff shows what would change.\n"
      "Examples:\n"
      "  chasles upgrade old.yaml                   # show the diff\n"
      "  chasles upgrade old.yaml -o new.yaml       # write the upgrade beside it\n"
      "  chasles upgrade old.yaml --in-place        # replace the file\n"
      "  chasles upgrade old.yaml --check           # exit 3 if it needs upgrading\n"
      "Changes between versions: docs/scene-format.md.\n"
      "Exit codes: 0 nothing to change, or the upgrade shown or written; 3 with --check, the "
      "scene needs upgrading; 2 bad input (a scene that does not load, an unknown version, a "
      "path that cannot be written); 1 internal error.");
  return cmd;
}

int RunUpgrade(const UpgradeArgs& args) {
  SceneOptions options;
  options.max_scene_bytes = args.max_scene_bytes;
  if (!args.output.empty()) CheckOutputTarget(args.output, "-o");
  const SceneUpgrade u = UpgradeSceneFile(args.scene, options);
  if (!u.changed()) {
    std::fprintf(stderr, "chasles upgrade: %s is format version %d already; nothing to change\n",
                 args.scene.c_str(), kSceneFormatVersion);
    // -o asks for the file: it gets the scene as it is.
    if (!args.output.empty()) WriteFileAtomically(args.output, u.text);
    return 0;
  }
  // Replacing a symbolic link's target, not the link.
  const std::string target = args.in_place && std::filesystem::is_symlink(args.scene)
                                 ? std::filesystem::canonical(args.scene).string()
                                 : (args.in_place ? args.scene : args.output);
  const std::string diff =
      UnifiedDiff(u.before, u.text, args.scene, target.empty() ? args.scene : target);
  std::fwrite(diff.data(), 1, diff.size(), stdout);
  std::fflush(stdout);
  const std::string what =
      fmt::format("{}: format version {} -> {}, {} change{}", args.scene, u.from_version,
                  kSceneFormatVersion, u.changes.size(), u.changes.size() == 1 ? "" : "s");
  if (args.check) {
    std::fprintf(stderr, "chasles upgrade: %s (the diff above); --in-place or -o FILE writes it\n",
                 what.c_str());
    return kExitCheckFailed;
  }
  if (target.empty()) {
    std::fprintf(stderr, "chasles upgrade: %s; nothing written (give -o FILE or --in-place)\n",
                 what.c_str());
    return 0;
  }
  WriteFileAtomically(target, u.text);
  std::fprintf(stderr, "chasles upgrade: %s; wrote %s\n", what.c_str(), target.c_str());
  return 0;
}

}  // namespace chasles::cli
