#pragma once
/// @file
/// Loading the scene a command names (or the built-in one) with its --set overrides.

#include <functional>

#include "chasles/scene/scene.h"
#include "commands.h"

namespace chasles::cli {

void AddSceneArgs(CLI::App& cmd, SceneArgs& args);
/// Accepts a number that is positive and finite (so "nan", "inf", "-1" and "0" are refused
/// with exit 2 while the command line is parsed); `rule` says what is expected, e.g. "--until
/// must be a positive time in seconds".
CLI::Validator PositiveFiniteNumber(const std::string& rule);
/// The scene options the arguments give (--set overrides, --max-scene-bytes).
SceneOptions SceneOptionsFrom(const SceneArgs& args);
/// Reads the scene the arguments name (or the built-in one) with the options it is given.
std::function<Scene(const SceneOptions&)> SceneLoader(const SceneArgs& args);
Scene LoadScene(const SceneArgs& args);
/// Writes text to the file named (atomically) or to standard output when the name is empty.
void Emit(const std::string& output, const std::string& text);
/// The whole file at `path`; InputError "PATH: cannot open WHAT" when it cannot be read.
std::string ReadTextFile(const std::string& path, const std::string& what);
/// A file a run's JSON summary at `json_path` names (its CSV, its scene): `path` as written
/// when it exists (relative to the current folder, as the run wrote it), else the file of that
/// name beside the JSON, else `path` (for the error that follows).
std::string ResolveBesideJson(const std::string& path, const std::string& json_path);

}  // namespace chasles::cli
