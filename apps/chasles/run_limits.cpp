#include "run_limits.h"

#include <cmath>
#include <string>

#include <fmt/format.h>

#include "chasles/error.h"
#include "scene_args.h"

namespace chasles::cli {

namespace {

/// A time in seconds that is finite and >= 0 (`positive`: > 0); "nan" and "inf" are refused.
CLI::Validator Seconds(bool positive) {
  return CLI::Validator(
      [positive](std::string& text) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(text, v) || !std::isfinite(v) || v < 0 ||
            (positive && v == 0)) {
          return fmt::format("expected a finite time in seconds {} 0, got '{}'",
                             positive ? ">" : ">=", text);
        }
        return "";
      },
      "SECONDS");
}

}  // namespace

/// --max-steps, --max-rows, --timeout, --min-step and --quiet (docs/reliability-limits.md).
void AddRunLimitOptions(CLI::App& cmd, SimulateArgs& args) {
  cmd.add_option("--max-steps", args.max_steps,
                 "Most integration steps before the run stops with exit 2 (default: the scene's "
                 "simulation.max_steps, else 10000000)")
      ->check(WholeNumber(kMaxWholeNumber));
  cmd.add_option("--max-rows", args.max_rows,
                 "Most CSV rows; a run that would write more is refused before it starts "
                 "(default: the scene's simulation.max_rows, else 1000000)")
      ->check(WholeNumber(kMaxWholeNumber));
  cmd.add_option("--timeout", args.timeout,
                 "Wall-time limit [s] after which the run stops with exit 2; 0: none (default: "
                 "the scene's simulation.timeout, else none)")
      ->check(Seconds(false));
  cmd.add_option("--min-step", args.min_step,
                 "Smallest step [s]: an adaptive step below it, or a fixed step below it, stops "
                 "the run with exit 2 (default: the scene's simulation.min_step, else 1e-12 of "
                 "the span)")
      ->check(Seconds(true));
  cmd.add_flag("--quiet", args.quiet, "No progress on standard error");
  cmd.add_option("--progress-interval", args.progress_interval,
                 "Seconds between progress lines when standard error is not a terminal "
                 "(default 10)")
      ->check(Seconds(true));
}

/// The limits given on the command line into `options`, checked.
void ApplyRunLimitOptions(const SimulateArgs& args, StudyOptions& options) {
  if (args.max_steps < 0 || args.max_rows < 0) {
    throw InputError(fmt::format("--max-steps and --max-rows must be whole numbers >= 1, got {}",
                                 args.max_steps < 0 ? args.max_steps : args.max_rows));
  }
  if (!std::isnan(args.timeout) && !(args.timeout >= 0 && std::isfinite(args.timeout))) {
    throw InputError(fmt::format("--timeout must be a time in seconds >= 0 (0: no limit), got {}",
                                 args.timeout));
  }
  if (!std::isnan(args.min_step) && !(args.min_step > 0 && std::isfinite(args.min_step))) {
    throw InputError(
        fmt::format("--min-step must be a positive time in seconds, got {}", args.min_step));
  }
  if (!(args.progress_interval > 0) || !std::isfinite(args.progress_interval)) {
    throw InputError(fmt::format("--progress-interval must be a positive time in seconds, got {}",
                                 args.progress_interval));
  }
  options.max_steps = args.max_steps;
  options.max_rows = args.max_rows;
  options.timeout = args.timeout;
  options.min_step = args.min_step;
}

}  // namespace chasles::cli
