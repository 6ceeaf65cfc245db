#include "program.h"

#include <cstdio>
#include <exception>
#include <filesystem>
#include <new>

#include <nlohmann/json.hpp>

#include "chasles/error.h"

namespace chasles::cli {

std::unique_ptr<Program> MakeProgram() {
  auto p = std::make_unique<Program>();
  CLI::App& app = p->app;
  app.description(
      "chasles: rigid-body kinetics from scene files. Mass properties of bodies and assemblies "
      "(centre of mass, inertia tensor, principal axes, radii of gyration), with units; motion "
      "with an energy/work/momentum ledger.");
  app.name("chasles");
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
      "  chasles simulate examples/dzhanibekov.yaml --html dzhanibekov.html\n"
      "Scene format: docs/scene-format.md. Exit codes: 0 ok, 2 bad input, 3 a failed check "
      "with --strict (simulate, solve), 1 internal error.");
  p->mass = AddMassCommand(app, p->mass_args);
  p->check = AddCheckCommand(app, p->check_args);
  p->simulate = AddSimulateCommand(app, p->simulate_args);
  p->solve = AddSolveCommand(app, p->solve_args);
  p->materials = AddMaterialsCommand(app);
  p->report = AddReportCommand(app, p->report_args);
#ifdef CHASLES_HAVE_PLOT
  p->plot = AddPlotCommand(app, p->plot_args);
#endif
  return p;
}

int RunParsed(Program& p) {
  try {
    if (p.mass->parsed()) return RunMass(p.mass_args);
    if (p.check->parsed()) return RunCheck(p.check_args);
    if (p.simulate->parsed()) return RunSimulate(p.simulate_args);
    if (p.solve->parsed()) return RunSolve(p.solve_args);
    if (p.materials->parsed()) return RunMaterials();
    if (p.report->parsed()) return RunReport(p.report_args);
    if (p.plot && p.plot->parsed()) return RunPlot(p.plot_args);
    std::fprintf(stderr,
                 "chasles: no command given, so here is the built-in demonstration scene "
                 "(chasles --help lists the commands).\n\n");
    MassArgs demo;
    return RunMass(demo);
  } catch (const chasles::InputError& e) {
    std::fprintf(stderr, "chasles: error: %s\n", e.what());
    return kExitBadInput;
  } catch (const std::filesystem::filesystem_error& e) {
    // A file-system problem is the user's to fix (a path, a permission): exit 2 with the path.
    std::fprintf(stderr, "chasles: error: %s\n", e.what());
    return kExitBadInput;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr,
                 "chasles: error: out of memory: the input asks for more memory than this "
                 "machine gives (see docs/reliability-io.md for the size limits)\n");
    return kExitBadInput;
  } catch (const nlohmann::json::exception& e) {
    // Scene text is checked to be UTF-8 at load and reports dump with replacement characters,
    // so this is text from elsewhere that JSON cannot hold.
    std::fprintf(stderr, "chasles: error: the report cannot be written as JSON: %s\n", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "chasles: internal error: %s\n", e.what());
    return kExitInternal;
  }
}

int Main(int argc, char** argv) {
  std::unique_ptr<Program> p = MakeProgram();
  try {
    p->app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return p->app.exit(e);  // --help, --version
  } catch (const CLI::ParseError& e) {
    p->app.exit(e);
    return kExitBadInput;
  }
  return RunParsed(*p);
}

}  // namespace chasles::cli
