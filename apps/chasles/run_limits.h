#pragma once
/// @file
/// The command-line limits on a run's work and its progress display (simulate):
/// --max-steps, --max-rows, --timeout, --min-step, --quiet, --progress-interval
/// (docs/reliability-limits.md).

#include <CLI/CLI.hpp>

#include "chasles/scene/study.h"
#include "commands.h"

namespace chasles::cli {

/// Registers the options on `cmd`, storing into `args`.
void AddRunLimitOptions(CLI::App& cmd, SimulateArgs& args);
/// The limits given on the command line into `options` (0 / NaN keep the scene's), checked.
void ApplyRunLimitOptions(const SimulateArgs& args, StudyOptions& options);

}  // namespace chasles::cli
