// chasles: the command-line program. Thin by design: parse -> load scene -> compute -> report.
// Exit codes: 0 success, 2 bad input (scene, options, physically impossible values),
// 3 a failed check of the answer under --strict (simulate, solve), 1 internal error.

#include <cstdio>
#include <exception>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "chasles/error.h"
#include "commands.h"

int main(int argc, char** argv) {
  using namespace chasles::cli;
  CLI::App app{
      "chasles: rigid-body kinetics from scene files. Mass properties of bodies and assemblies "
      "(centre of mass, inertia tensor, principal axes, radii of gyration), with units; motion "
      "with an energy/work/momentum ledger."};
  app.set_version_flag("--version", "chasles 0.1.0");
  app.require_subcommand(0, 1);
  app.footer(
      "Run without a command to see the built-in demonstration (the chapter's disk-and-axle "
      "assembly).\n"
      "Examples:\n"
      "  chasles mass examples/example-8.1-cylinder.yaml\n"
      "  chasles mass examples/section-8.3-disk-axle.yaml --units in,lb --format json\n"
      "  chasles check my-scene.yaml\n"
      "  chasles simulate examples/dzhanibekov.yaml --out results\n"
      "  chasles solve examples/example-8.3-cylinder-incline.yaml\n"
      "Scene format: docs/scene-format.md. Exit codes: 0 ok, 2 bad input, 3 a failed check "
      "with --strict (simulate, solve), 1 internal error.");

  MassArgs mass_args;
  CheckArgs check_args;
  SimulateArgs simulate_args;
  SolveArgs solve_args;
  CLI::App* mass = AddMassCommand(app, mass_args);
  CLI::App* check = AddCheckCommand(app, check_args);
  CLI::App* simulate = AddSimulateCommand(app, simulate_args);
  CLI::App* solve = AddSolveCommand(app, solve_args);
  CLI::App* materials = AddMaterialsCommand(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);  // --help, --version
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }

  try {
    if (mass->parsed()) return RunMass(mass_args);
    if (check->parsed()) return RunCheck(check_args);
    if (simulate->parsed()) return RunSimulate(simulate_args);
    if (solve->parsed()) return RunSolve(solve_args);
    if (materials->parsed()) return RunMaterials();
    std::fprintf(stderr,
                 "chasles: no command given, so here is the built-in demonstration scene "
                 "(chasles --help lists the commands).\n\n");
    MassArgs demo;
    return RunMass(demo);
  } catch (const chasles::InputError& e) {
    std::fprintf(stderr, "chasles: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "chasles: internal error: %s\n", e.what());
    return 1;
  }
}
