#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "chasles/files/output_set.h"
#include "chasles/report/json_report.h"
#include "chasles/report/mass_text.h"
#include "chasles/report/report_data.h"
#include "chasles/scene/mass_report.h"
#include "chasles/scene/mesh_file.h"
#include "chasles/scene/robot_file.h"
#include "chasles/scene/scene.h"
#include "chasles/scene/scene_error.h"
#include "chasles/scene/sweep.h"
#include "chasles/scene/units.h"
#include "cluster.h"
#include "commands.h"
#include "html_report.h"
#include "progress.h"
#include "scene_args.h"
#include "sweep_output.h"

namespace chasles::cli {

CLI::App* AddMassCommand(CLI::App& app, MassArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "mass",
      "Mass properties of every body and part: mass, centre of mass, inertia tensor, "
      "principal moments and axes, radii of gyration");
  AddSceneArgs(*cmd, args.scene);
  cmd->get_option("scene")->description(
      "Scene file (YAML), a mesh file (.stl, .obj, .ply, .off) with --unit and a density, or a "
      "robot file (.urdf, .sdf, MJCF .xml: the robot's total about its base). Without one, the "
      "built-in demonstration scene is used.");
  cmd->add_option("--units", args.units,
                  "Units of the report: SI, US (in, lb), or a list such as 'mm,g' or 'ft,slug' "
                  "(default: the scene's own units)");
  cmd->add_option("--format", args.format, "text (for people) or json (for programs)")
      ->check(CLI::IsMember({"text", "json"}));
  cmd->add_option(
         "--about", args.about,
         "Also give the inertia about this point of each body, e.g. --about '[0, 0, 0.5 m]' "
         "(bare numbers in the scene's units; repeatable)")
      ->allow_extra_args(false)
      ->delimiter('\0');  // keep "[x, y, z]" whole: CLI11 would split it into a list
  cmd->add_option("--frame", args.frame,
                  "Also give the central inertia in a frame rotated in the body, e.g. "
                  "--frame '{rotation: {axis: [0, 0, 1], angle: 30 deg}}'");
  cmd->add_option("-o,--output", args.output,
                  "Write the report to this file instead of the terminal");
  cmd->add_flag("--no-parts", args.hide_parts, "Leave out the table of parts");
  cmd->add_option("--html", args.html,
                  "Also write the browser report here: the bodies drawn with their principal "
                  "axes and inertia ellipsoids (one HTML file); with --sweep, the quantities "
                  "plotted against the swept parameters");
  // A help heading (Option::group), not an Option_group: CLI11 2.1's option groups are
  // subcommands inside, and `mass a "" --x` (an empty extra argument, then an unknown option)
  // sent its parser round them forever (found by the command-line fuzz target).
  const std::string mesh = "Mesh file (when SCENE is a .stl, .obj, .ply or .off file)";
  cmd->add_option("--unit", args.mesh_unit,
                  "Length of one unit of the mesh file, e.g. mm or in (mesh files carry no units)")
      ->group(mesh);
  cmd->add_option("--density", args.mesh_density, "Density, e.g. 7850 or '7.85 g/cm^3'")
      ->group(mesh);
  cmd->add_option("--material", args.mesh_material, "A material name instead of a density")
      ->group(mesh);
  cmd->add_option("--mass", args.mesh_mass, "The total mass instead of a density")->group(mesh);
  cmd->add_option("--mode", args.mesh_mode,
                  "solid (default: a closed surface) or shell (a thin sheet)")
      ->group(mesh);
  cmd->add_option("--thickness", args.mesh_thickness, "Shell mode: sheet thickness")->group(mesh);
  cmd->add_option("--areal-density", args.mesh_areal_density, "Shell mode: mass per area")
      ->group(mesh);
  const std::string robot = "Robot file (when SCENE is a .urdf, .sdf or MJCF .xml file)";
  cmd->add_option("--joint", args.robot_joints,
                  "A joint value, NAME=VALUE in rad or m (repeatable; others at zero): the robot's "
                  "total mass, centre of mass and inertia about its base at that configuration")
      ->group(robot);
  cmd->add_option("--package", args.robot_packages,
                  "Where a package:// URI's package is, NAME=DIR (repeatable)")
      ->group(robot);
  AddSweepOptions(*cmd, args.sweep, args.quantity, args.jobs, args.max_runs,
                  fmt::format("NAME for a scene of one body, else BODY.NAME, with NAME one of {} "
                              "(repeatable)",
                              fmt::join(MassSweepQuantityNames(), ", ")));
  cmd->add_option("--precision", args.precision,
                  "With --sweep, digits of the CSV table's numbers: default (12 significant "
                  "digits) or full (every double with %.17g, reads back bitwise)")
      ->check(CLI::IsMember({"default", "full"}));
  cmd->add_flag("--full-precision", args.full_precision, "The same as --precision full");
  cmd->add_flag("--quiet", args.quiet,
                "No progress of a sweep on standard error (otherwise: redrawn on a terminal, one "
                "line every 10 s off it)");
  cmd->add_option("--progress-interval", args.progress_interval,
                  "Seconds between progress lines of a sweep when standard error is not a "
                  "terminal (default 10)");
  cmd->footer(
      "Examples:\n"
      "  chasles mass examples/example-8.1-cylinder.yaml\n"
      "  chasles mass examples/example-8.1-cylinder.yaml --set 'h1=0.25*h' --units mm,g\n"
      "  chasles mass examples/example-8.2-two-rods.yaml --format json -o rods.json\n"
      "  chasles mass part.stl --unit mm --density 7850\n"
      "  chasles mass robot.urdf --joint elbow_joint=1.57\n"
      "  chasles mass examples/example-8.1-cylinder.yaml --sweep 'R=2 cm:8 cm:4' --quantity Izz "
      "--quantity center_of_mass_z\n"
      "Exit codes: 0 success, 2 bad input (the message names file, line, column and key), "
      "1 internal error.");
  return cmd;
}

namespace {
/// The inertia about a point P (parallel-axis theorem, eqs. 8.24-8.29: I_P = I_cm + m (d² 1 -
/// d dᵀ), d from the centre of mass to P) overflows when m d² passes the largest double; say
/// so by name rather than print inf and nan.
void CheckPointInertias(const Scene& scene, const std::vector<MassReportPoint>& extra) {
  for (const SceneBody& body : scene.bodies) {
    const MassProperties& mp = body.mass_properties;
    for (const MassReportPoint& p : MassReportPoints(body, extra)) {
      const Mat3 I = mp.CalcInertiaAbout(p.p_BoP_B).matrix();
      if (I.allFinite()) continue;
      const double d = (p.p_BoP_B - mp.p_BoBcm_B()).stableNorm();
      const std::string what = fmt::format(
          "the inertia of body '{}' about point {} is not a finite number: the point is {:.6g} m "
          "from the centre of mass, and m d² = {:.6g} kg * ({:.6g} m)² overflows the range of a "
          "double (about 1.8e308 kg*m^2); give a point nearer the body",
          body.name, p.name, d, mp.mass(), d);
      // A point of the scene's `points` is refused at its value; one of --about has no place.
      for (const ScenePoint& sp : body.points) {
        if (sp.name == p.name && sp.where.line > 0) {
          throw SceneError(scene.file, sp.where.line, sp.where.column, sp.where.key, what);
        }
      }
      throw InputError(what);
    }
  }
}

Scene LoadMassInput(const MassArgs& args) {
  const bool mesh_options =
      !(args.mesh_unit + args.mesh_mode + args.mesh_density + args.mesh_material + args.mesh_mass +
        args.mesh_areal_density + args.mesh_thickness)
           .empty();
  if (!args.scene.scene.empty() && IsRobotFileName(args.scene.scene) && !mesh_options) {
    RobotReadOptions read;
    read.packages = ParsePackageOptions(args.robot_packages);
    return LoadRobotAsScene(args.scene.scene, read, ParseJointOptions(args.robot_joints));
  }
  if (!args.robot_joints.empty() || !args.robot_packages.empty()) {
    throw InputError("--joint and --package are for a robot file given instead of a scene");
  }
  if (!args.scene.scene.empty() && IsMeshFileName(args.scene.scene)) {
    if (!args.scene.set.empty()) {
      throw SceneError("command line", 0, 0, "--set",
                       "--set is for scene parameters; a mesh file has none");
    }
    return LoadMeshAsScene(
        args.scene.scene,
        MeshCommandOptions{args.mesh_unit, args.mesh_mode, args.mesh_density, args.mesh_material,
                           args.mesh_mass, args.mesh_areal_density, args.mesh_thickness});
  }
  if (mesh_options) {
    throw SceneError("command line", 0, 0, "",
                     "--unit, --density, --material, --mass, --mode, --thickness and "
                     "--areal-density are for a mesh file given instead of a scene; in a scene, "
                     "a mesh part says them itself");
  }
  return LoadScene(args.scene);
}
}  // namespace

namespace {

/// mass --sweep: the quantities at every point of the grid, as a table (docs/sweeps.md).
int RunMassSweep(const MassArgs& args) {
  if (args.scene.scene.empty()) {
    throw InputError("chasles mass --sweep needs a scene file (chasles mass --help)");
  }
  if (!args.about.empty() || !args.frame.empty() || !args.units.empty()) {
    throw InputError(
        "--about, --frame and --units go with one report, not with --sweep (the table is in "
        "SI)");
  }
  // Every target is checked before the first run.
  OutputSet out;
  out.Expect(ReportTarget(args.output), "-o");
  if (!args.html.empty()) {
    RequireHtmlReport("--html");
    out.Expect(args.html, "--html");
  }
  if (!(args.progress_interval > 0) || !std::isfinite(args.progress_interval)) {
    throw InputError(fmt::format("--progress-interval must be a positive time in seconds, got {}",
                                 args.progress_interval));
  }
  const std::vector<SweepSpec> specs = ParseSweeps(args.sweep);
  SweepTable table;
  // Under mpirun: this rank's points; rank 0 gathers the rows and alone writes (cluster.h).
  const Cluster& cluster = Cluster::Get();
  {
    Progress progress("mass --sweep", "", args.quiet || cluster.rank() != 0,
                      args.progress_interval);
    table = MassSweep(
        SceneLoader(args.scene), SceneOptionsFrom(args.scene), specs, args.quantity, args.jobs,
        [&progress](std::int64_t done, std::int64_t total) {
          progress.Update(static_cast<double>(done), static_cast<double>(total));
        },
        args.max_runs > 0 ? args.max_runs : kDefaultMaxRuns, cluster.share());
  }
  SweepWarnings warnings;
  bool check_failed = false;
  if (!GatherSweep(&table, &warnings, &check_failed)) return 0;
  AddSweepTable(out, table, args.format,
                args.full_precision ? CsvPrecision::kFull : ParseCsvPrecision(args.precision),
                ReportTarget(args.output));
  if (!args.html.empty()) {
    out.Add(args.html, HtmlReport(SweepReportData(LoadScene(args.scene), table, "mass")));
  }
  out.Commit();
  SayWroteHtmlReport(args.html);
  return 0;
}

}  // namespace

int RunMass(const MassArgs& args) {
  if (!args.sweep.empty()) return RunMassSweep(args);
  if (!args.quantity.empty() || args.jobs > 0 || args.max_runs > 0) {
    throw InputError(fmt::format("{} goes with --sweep", !args.quantity.empty() ? "--quantity"
                                                         : args.jobs > 0        ? "--jobs"
                                                                                : "--max-runs"));
  }
  // Every target is checked before the scene is read.
  OutputSet out;
  out.Expect(ReportTarget(args.output), "-o");
  if (!args.html.empty()) {
    RequireHtmlReport("--html");
    out.Expect(args.html, "--html");
  }
  const Scene scene = LoadMassInput(args);
  MassTextOptions options;
  options.text.units = args.units;
  TextUnits(scene, options.text);  // a mistyped unit is refused before anything else
  options.parts = !args.hide_parts;
  for (const std::string& a : args.about) {
    options.about.push_back({"'" + a + "'", ReadPointOption(scene, a, "--about")});
  }
  CheckPointInertias(scene, options.about);
  if (!args.frame.empty()) options.R_BF = ReadRotationOption(scene, args.frame, "--frame");
  // Every value of either report is in the JSON form: checked there first, by name (DumpJson,
  // MassText).
  std::string report = args.format == "json"
                           ? DumpJson(MassReportJson(scene, TextUnits(scene, options.text),
                                                     options.about, options.R_BF),
                                      "the mass report")
                           : MassText(scene, options);
  if (!args.html.empty()) out.Add(args.html, HtmlReport(MassReportData(scene)));
  out.Add(ReportTarget(args.output), std::move(report));
  out.Commit();
  SayWroteHtmlReport(args.html);
  return 0;
}

}  // namespace chasles::cli
