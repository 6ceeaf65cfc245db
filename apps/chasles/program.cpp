#include "program.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <new>
#include <string>
#include <utility>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "chasles/error.h"
#include "chasles/files/output_set.h"
#include "cluster.h"

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
      "  chasles upgrade old-scene.yaml --in-place\n"
      "  chasles simulate examples/dzhanibekov.yaml --out results\n"
      "  chasles solve examples/example-8.3-cylinder-incline.yaml\n"
      "  chasles modes examples/whipple-bicycle.yaml\n"
      "  chasles simulate examples/dzhanibekov.yaml --html dzhanibekov.html\n"
      "  chasles audit robot.urdf --fix --out fixed\n"
      "Scene format: docs/scene-format.md. Exit codes: 0 ok, 2 bad input, 3 a failed check "
      "with --strict (simulate, solve), a scene to upgrade with upgrade --check or an error "
      "found by audit, 1 internal error.");
  p->mass = AddMassCommand(app, p->mass_args);
  p->check = AddCheckCommand(app, p->check_args);
  p->simulate = AddSimulateCommand(app, p->simulate_args);
  p->solve = AddSolveCommand(app, p->solve_args);
  p->modes = AddModesCommand(app, p->modes_args);
  p->balance = AddBalanceCommand(app, p->balance_args);
  p->materials = AddMaterialsCommand(app);
  p->report = AddReportCommand(app, p->report_args);
  p->upgrade = AddUpgradeCommand(app, p->upgrade_args);
  p->audit = AddAuditCommand(app, p->audit_args);
#ifdef CHASLES_HAVE_PLOT
  p->plot = AddPlotCommand(app, p->plot_args);
#endif
  return p;
}

namespace {

/// The exit code and the message line of the exception being handled.
std::pair<int, std::string> Describe(std::exception_ptr failure) {
  try {
    std::rethrow_exception(failure);
  } catch (const RankFailure& e) {
    return {e.code(), e.what()};  // printed by its rank's own handler, below
  } catch (const chasles::InputError& e) {
    return {kExitBadInput, fmt::format("chasles: error: {}", e.what())};
  } catch (const std::filesystem::filesystem_error& e) {
    // A file-system problem is the user's to fix (a path, a permission): exit 2 with the path.
    return {kExitBadInput, fmt::format("chasles: error: {}", e.what())};
  } catch (const std::bad_alloc&) {
    return {kExitBadInput,
            "chasles: error: out of memory: the input asks for more memory than this machine "
            "gives (see docs/reliability-io.md for the size limits)"};
  } catch (const nlohmann::json::exception& e) {
    // Scene text is checked to be UTF-8 at load and reports dump with replacement characters,
    // so this is text from elsewhere that JSON cannot hold.
    return {kExitBadInput,
            fmt::format("chasles: error: the report cannot be written as JSON: {}", e.what())};
  } catch (const std::exception& e) {
    return {kExitInternal, fmt::format("chasles: internal error: {}", e.what())};
  }
}

/// A sweep, which every rank of mpirun runs its share of (other commands run on rank 0).
bool IsSweep(const Program& p) {
  return (p.mass->parsed() && !p.mass_args.sweep.empty()) ||
         (p.simulate->parsed() && !p.simulate_args.sweep.empty()) ||
         (p.solve->parsed() && !p.solve_args.sweep.empty());
}

int RunCommand(Program& p) {
  if (p.mass->parsed()) return RunMass(p.mass_args);
  if (p.check->parsed()) return RunCheck(p.check_args);
  if (p.simulate->parsed()) return RunSimulate(p.simulate_args);
  if (p.solve->parsed()) return RunSolve(p.solve_args);
  if (p.modes->parsed()) return RunModes(p.modes_args);
  if (p.balance->parsed()) return RunBalance(p.balance_args);
  if (p.materials->parsed()) return RunMaterials();
  if (p.report->parsed()) return RunReport(p.report_args);
  if (p.upgrade->parsed()) return RunUpgrade(p.upgrade_args);
  if (p.audit->parsed()) return RunAudit(p.audit_args);
  if (p.plot && p.plot->parsed()) return RunPlot(p.plot_args);
  std::fprintf(stderr,
               "chasles: no command given, so here is the built-in demonstration scene "
               "(chasles --help lists the commands).\n\n");
  MassArgs demo;
  return RunMass(demo);
}

}  // namespace

int RunParsed(Program& p) {
  Cluster& cluster = Cluster::Get();
  const bool shared = cluster.distributed() && IsSweep(p);
  // Under mpirun a command other than a sweep runs once, on rank 0.
  if (cluster.distributed() && !shared && cluster.rank() != 0) return 0;
  try {
    const int code = RunCommand(p);
    // Every rank of a sweep sends rank 0 its part once (GatherSweep in the command).
    if (shared && !cluster.exchanged()) cluster.Exchange(SweepPart{});
    return code;
  } catch (...) {
    auto [code, line] = Describe(std::current_exception());
    if (shared && !cluster.exchanged()) {
      // The others wait for this rank's part: send the failure instead, and rank 0 prints the
      // one the serial sweep would have stopped at (ranks that failed alike print nothing).
      SweepPart failed;
      failed.code = code;
      failed.message = line;
      failed.failed_at = cluster.point();
      const std::vector<SweepPart> parts = cluster.Exchange(failed);
      if (cluster.rank() != 0) return code;
      const SweepPart* first = FirstFailure(parts);
      code = first->code;
      line = first->message;
    }
    std::fprintf(stderr, "%s\n", line.c_str());
    return code;
  }
}

int Main(int argc, char** argv) {
  // Before any thread starts: SIGINT, SIGTERM and SIGHUP remove the outputs' temporaries.
  GuardOutputsAgainstSignals();
  Cluster& cluster = Cluster::Get();
  if (Cluster::LaunchedSize() > 1) {
    try {
      cluster.Start();
    } catch (const chasles::InputError& e) {
      // Without MPI the ranks cannot agree who speaks: the one mpirun numbered 0 does.
      if (Cluster::LaunchedRank() == 0) std::fprintf(stderr, "chasles: error: %s\n", e.what());
      return kExitBadInput;
    }
  }
  std::unique_ptr<Program> p = MakeProgram();
  int code = 0;
  try {
    p->app.parse(argc, argv);
    code = RunParsed(*p);
  } catch (const CLI::Success& e) {
    code = cluster.rank() == 0 ? p->app.exit(e) : 0;  // --help, --version
  } catch (const CLI::ParseError& e) {
    if (cluster.rank() == 0) p->app.exit(e);
    code = kExitBadInput;
  }
  // Whatever was printed must have reached standard output (a full disk, a closed pipe).
  if ((std::fflush(stdout) != 0 || std::ferror(stdout)) && code == 0) {
    std::fprintf(stderr, "chasles: error: cannot write to standard output: %s\n",
                 std::strerror(errno));
    code = kExitBadInput;
  }
  code = cluster.AgreeExitCode(code);
  cluster.Finish();
  return code;
}

}  // namespace chasles::cli
