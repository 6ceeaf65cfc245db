#pragma once
/// @file
/// Loading the scene a command names (or the built-in one) with its --set overrides.

#include <cstdint>
#include <functional>

#include "chasles/scene/scene.h"
#include "commands.h"

namespace chasles::cli {

void AddSceneArgs(CLI::App& cmd, SceneArgs& args);
/// Accepts a number that is positive and finite (so "nan", "inf", "-1" and "0" are refused
/// with exit 2 while the command line is parsed); `rule` says what is expected, e.g. "--until
/// must be a positive time in seconds".
CLI::Validator PositiveFiniteNumber(const std::string& rule);
/// Accepts a whole number from 1 to `max` written in decimal digits: "0", "-1", "1.5", "1e3"
/// and a number past `max` (e.g. 99999999999999999999, past the range of the option's integer
/// type) are refused while the command line is parsed.
CLI::Validator WholeNumber(std::int64_t max);
/// The largest count an option takes (the range of std::int64_t).
inline constexpr std::int64_t kMaxWholeNumber = INT64_MAX;
/// The most threads --jobs asks for.
inline constexpr std::int64_t kMaxJobs = 65536;
/// The scene options the arguments give (--set overrides, --max-scene-bytes).
SceneOptions SceneOptionsFrom(const SceneArgs& args);
/// Reads the scene the arguments name (or the built-in one) with the options it is given.
std::function<Scene(const SceneOptions&)> SceneLoader(const SceneArgs& args);
Scene LoadScene(const SceneArgs& args);
/// The target of a command's report: standard output ("-") when `output` is empty or "-".
std::string ReportTarget(const std::string& output);
/// A file a run's JSON summary at `json_path` names (its CSV, its scene): `path` as written
/// when it exists (relative to the current folder, as the run wrote it), else the file of that
/// name beside the JSON, else `path` (for the error that follows).
std::string ResolveBesideJson(const std::string& path, const std::string& json_path);

}  // namespace chasles::cli
