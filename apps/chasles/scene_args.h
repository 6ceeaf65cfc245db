#pragma once
/// @file
/// Loading the scene a command names (or the built-in one) with its --set overrides.

#include "chasles/scene/scene.h"
#include "commands.h"

namespace chasles::cli {

void AddSceneArgs(CLI::App& cmd, SceneArgs& args);
Scene LoadScene(const SceneArgs& args);
/// Writes text to the file named (atomically) or to standard output when the name is empty.
void Emit(const std::string& output, const std::string& text);

}  // namespace chasles::cli
