#pragma once
/// @file
/// The whole command line of the chasles program: building the parser, parsing, and running
/// the chosen command with the promised exit codes. main() is a two-line wrapper around it;
/// the command-line fuzz target drives the parser through the same object.

#include <memory>

#include <CLI/CLI.hpp>

#include "commands.h"

namespace chasles::cli {

/// Exit codes: 0 success, 2 bad input (scene, options, files, physically impossible values),
/// 3 a failed check of the answer under --strict (simulate, solve: kExitCheckFailed, in
/// certificate_report.h), 1 internal error (docs/reliability.md).
inline constexpr int kExitInternal = 1;
inline constexpr int kExitBadInput = 2;

/// The parser with every command registered and the argument structs it fills.
struct Program {
  CLI::App app;
  MassArgs mass_args;
  CheckArgs check_args;
  SimulateArgs simulate_args;
  SolveArgs solve_args;
  ReportArgs report_args;
  PlotArgs plot_args;
  UpgradeArgs upgrade_args;
  AuditArgs audit_args;
  ModesArgs modes_args;
  BalanceArgs balance_args;
  CLI::App* mass = nullptr;
  CLI::App* audit = nullptr;
  CLI::App* check = nullptr;
  CLI::App* simulate = nullptr;
  CLI::App* solve = nullptr;
  CLI::App* materials = nullptr;
  CLI::App* report = nullptr;
  CLI::App* upgrade = nullptr;
  CLI::App* plot = nullptr;  // null in a build without PLplot
  CLI::App* modes = nullptr;
  CLI::App* balance = nullptr;
};

/// A fresh parser (CLI11 apps are not reusable across parses).
std::unique_ptr<Program> MakeProgram();

/// Runs the command that was parsed (or the built-in demonstration when none was), turning
/// every exception into its exit code and a message on standard error.
int RunParsed(Program& program);

/// Parses argv and runs: the whole program.
int Main(int argc, char** argv);

}  // namespace chasles::cli
