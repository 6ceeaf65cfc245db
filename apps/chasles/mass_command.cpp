#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "chasles/files/output_set.h"
#include "chasles/report/json_report.h"
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

namespace {

/// What the report shows, in the units asked for.
struct Presenter {
  UnitSystem units;
  std::string L, M, I, rho;

  explicit Presenter(const UnitSystem& u)
      : units(u),
        L(u.FormatUnit(kLength)),
        M(u.FormatUnit(kMass)),
        I(u.FormatUnit(kInertia)),
        rho(u.FormatUnit(kDensity)) {}

  double Length(double v) const { return units.FromSI(v, kLength); }
  double Mass(double v) const { return units.FromSI(v, kMass); }
  double Inertia(double v) const { return units.FromSI(v, kInertia); }
  Vec3 Lengths(const Vec3& v) const { return Vec3(Length(v.x()), Length(v.y()), Length(v.z())); }
  Mat3 InertiaMatrix(const Mat3& m) const {
    return m.unaryExpr([this](double v) { return Inertia(v); });
  }
};

// Round-off in a result whose scale is `scale` shows as an exact 0 in the text report.
double Clean(double v, double scale) {
  return std::abs(v) <= 1e-13 * scale ? 0.0 : v;
}

std::string Num(double v, double scale) {
  return fmt::format("{:.7g}", Clean(Finite(v, "a value of the mass report"), scale));
}

std::string VecText(const Vec3& v, double scale) {
  return fmt::format("[{}, {}, {}]", Num(v.x(), scale), Num(v.y(), scale), Num(v.z(), scale));
}

void MatrixText(std::string& out, const Mat3& m, const std::string& indent) {
  const double scale = m.cwiseAbs().maxCoeff();
  std::string cells[3][3];
  size_t width = 0;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      cells[i][j] = Num(m(i, j), scale);
      width = std::max(width, cells[i][j].size());
    }
  }
  for (int i = 0; i < 3; ++i) {
    out += fmt::format("{}[ {:>{}}  {:>{}}  {:>{}} ]\n", indent, cells[i][0], width, cells[i][1],
                       width, cells[i][2], width);
  }
}

/// The inertia I_P about a point P of a body of mass `mass`, its principal moments and axes
/// and its radii of gyration about the axes through P.
void PointInertiaText(std::string& out, const Presenter& P, const RotationalInertia& I_P,
                      double mass) {
  // I_P (parallel-axis theorem, eqs. 8.24-8.29), its eigenvalues and eigenvectors, and
  // k = sqrt(I/m) (eq. 8.19) about the axes through P.
  MatrixText(out, P.InertiaMatrix(I_P.matrix()), "    ");
  const PrincipalAxes pp = I_P.CalcPrincipalAxes();
  const double Ps = P.Inertia(I_P.Trace());
  out += fmt::format("    Principal moments   {}, {}, {} {}\n", Num(P.Inertia(pp.moments[0]), Ps),
                     Num(P.Inertia(pp.moments[1]), Ps), Num(P.Inertia(pp.moments[2]), Ps), P.I);
  out += fmt::format("    Principal axes      e1 = {}, e2 = {}, e3 = {}  (body axes)\n",
                     VecText(pp.axes.col(0), 1), VecText(pp.axes.col(1), 1),
                     VecText(pp.axes.col(2), 1));
  const double kp_scale = std::sqrt(std::abs(I_P.Trace() / mass));
  out += fmt::format("    Radii of gyration   about body axes through the point: {} {}\n",
                     VecText(P.Lengths(I_P.CalcRadiiOfGyration(mass)), P.Length(kp_scale)), P.L);
  out +=
      fmt::format("                        about the principal axes through the point: {} {}\n",
                  VecText(P.Lengths(RotationalInertia(pp.moments[0], pp.moments[1], pp.moments[2])
                                        .CalcRadiiOfGyration(mass)),
                          P.Length(kp_scale)),
                  P.L);
}

struct Frame {
  bool given = false;
  std::string text;
  Mat3 R_BF = Mat3::Identity();
};

// Why a body's volume is zero when no part has any (rods, rings, thin disks, points): said so
// that a 0 beside parts with mass does not read as a mistake.
std::string VolumeRemark(const SceneBody& body, double volume) {
  if (volume != 0.0) return "";
  for (const ScenePart& p : body.parts) {
    if (p.volume != 0.0) return "";
  }
  return "  (every part is idealised as a curve, a surface or a point)";
}

std::string TextReport(const Scene& scene, const Presenter& P, const MassArgs& args,
                       const std::vector<MassReportPoint>& extra, const Frame& frame) {
  std::string out;
  out += fmt::format("chasles mass: {}\n", scene.title.empty() ? scene.file : scene.title);
  if (!scene.title.empty()) out += fmt::format("Scene: {}\n", scene.file);
  out += fmt::format("Units: length {}, mass {}, inertia {}.\n{}\n", P.L, P.M, P.I,
                     kInertiaConvention);
  for (const SceneBody& body : scene.bodies) {
    const MassProperties& mp = body.mass_properties;
    const double Lscale =
        // stableNorm: |p| of a part at 1e200 m is 1.7e200, where norm() overflows to inf and
        // would round every coordinate to 0.
        std::max(mp.p_BoBcm_B().stableNorm(), std::sqrt(mp.I_BBcm_B().Trace() / mp.mass()));
    out += fmt::format("\nBody '{}' ({} part{})\n", body.name, body.parts.size(),
                       body.parts.size() == 1 ? "" : "s");
    if (!args.hide_parts) {
      size_t w = 4;
      size_t ws = 5;
      for (const auto& p : body.parts) {
        w = std::max(w, p.name.size());
        ws = std::max(ws, p.shape.size() + (p.subtractive ? 6 : 0));
      }
      out += fmt::format("  {:<{}}  {:<{}}  {:>13}  {}\n", "part", w, "shape", ws,
                         "mass [" + P.M + "]", "centre of mass [" + P.L + "]");
      for (const ScenePart& p : body.parts) {
        const MassProperties& q = p.mass_properties;
        std::string shape = p.shape + (p.subtractive ? " (cut)" : "");
        out += fmt::format("  {:<{}}  {:<{}}  {:>13}  {}\n", p.name, w, shape, ws,
                           Num(P.Mass(q.mass()), 0),
                           VecText(P.Lengths(q.p_BoBcm_B()), P.Length(Lscale)));
        std::string detail;
        if (std::isfinite(p.density)) {
          detail = fmt::format("density {} {}", Num(P.units.FromSI(p.density, kDensity), 0), P.rho);
          if (p.mass_source != "density") detail += fmt::format(" ({})", p.mass_source);
        } else if (p.mass_source != "mass" && p.notes.empty()) {
          detail = p.mass_source;
        }
        for (const auto& n : p.notes) detail += (detail.empty() ? "" : "; ") + n;
        if (p.volume == 0.0 && p.surface_area == 0.0) {
          // A slender rod, a ring or a point: the idealisation has neither.
          detail += std::string(detail.empty() ? "" : "; ") +
                    "no volume or surface area (its mass lies on a curve or at a point)";
        } else if (!std::isnan(p.volume)) {
          detail +=
              fmt::format("{}volume {} {}, surface area {} {}", detail.empty() ? "" : "; ",
                          Num(P.units.FromSI(p.volume, kVolume), 0), P.units.FormatUnit(kVolume),
                          Num(P.units.FromSI(p.surface_area, kArea), 0), P.units.FormatUnit(kArea));
        }
        if (!detail.empty()) out += fmt::format("  {:<{}}  {}\n", "", w, detail);
        // The part's own central inertia, in body axes: the six tensor entries on one line.
        const Mat3 Ip = P.InertiaMatrix(q.I_BBcm_B().matrix());
        const double s = Ip.cwiseAbs().maxCoeff();
        out += fmt::format(
            "  {:<{}}  inertia about its centre of mass [{}]: Ixx {}, Iyy {}, Izz {}, "
            "Ixy {}, Ixz {}, Iyz {}\n",
            "", w, P.I, Num(Ip(0, 0), s), Num(Ip(1, 1), s), Num(Ip(2, 2), s), Num(Ip(0, 1), s),
            Num(Ip(0, 2), s), Num(Ip(1, 2), s));
      }
    }
    const RotationalInertia& Icm = mp.I_BBcm_B();
    out += fmt::format("  Mass                {} {}\n", Num(P.Mass(mp.mass()), 0), P.M);
    out += fmt::format("  Centre of mass      {} {}  (from the body origin, body axes)\n",
                       VecText(P.Lengths(mp.p_BoBcm_B()), P.Length(Lscale)), P.L);
    // Volume (a cut's subtracted) and the surface area where it is exact (one part).
    const BodyMeasures measures = CalcBodyMeasures(body);
    out += fmt::format(
        "  Volume              {}\n",
        std::isnan(measures.volume)
            ? measures.volume_note
            : fmt::format("{} {}{}", Num(P.units.FromSI(measures.volume, kVolume), 0),
                          P.units.FormatUnit(kVolume), VolumeRemark(body, measures.volume)));
    out +=
        fmt::format("  Surface area        {}\n",
                    std::isnan(measures.surface_area)
                        ? measures.surface_area_note
                        : fmt::format("{} {}", Num(P.units.FromSI(measures.surface_area, kArea), 0),
                                      P.units.FormatUnit(kArea)));
    out += fmt::format("  Inertia about the centre of mass, body axes [{}]\n", P.I);
    MatrixText(out, P.InertiaMatrix(Icm.matrix()), "    ");
    const PrincipalAxes pa = Icm.CalcPrincipalAxes();
    const double Iscale = P.Inertia(Icm.Trace());
    out += fmt::format("  Principal moments   {}, {}, {} {}\n",
                       Num(P.Inertia(pa.moments[0]), Iscale), Num(P.Inertia(pa.moments[1]), Iscale),
                       Num(P.Inertia(pa.moments[2]), Iscale), P.I);
    out += fmt::format("  Principal axes      e1 = {}, e2 = {}, e3 = {}  (body axes)\n",
                       VecText(pa.axes.col(0), 1), VecText(pa.axes.col(1), 1),
                       VecText(pa.axes.col(2), 1));
    // The radii describe the spread about the centre of mass, so their round-off scale is
    // their own size, not the body's distance from its origin (a body at 1e200 m still has
    // radii of centimetres).
    const double k_scale = std::sqrt(std::abs(Icm.Trace() / mp.mass()));
    const Vec3 k_body = Icm.CalcRadiiOfGyration(mp.mass());
    const Vec3 k_principal = RotationalInertia(pa.moments[0], pa.moments[1], pa.moments[2])
                                 .CalcRadiiOfGyration(mp.mass());
    out += fmt::format("  Radii of gyration   about body axes through the centre of mass: {} {}\n",
                       VecText(P.Lengths(k_body), P.Length(k_scale)), P.L);
    out += fmt::format("                      about the principal axes: {} {}\n",
                       VecText(P.Lengths(k_principal), P.Length(k_scale)), P.L);
    for (const MassReportPoint& p : MassReportPoints(body, extra)) {
      out += fmt::format("  Inertia about point {} = {} {}, body axes [{}]\n", p.name,
                         VecText(P.Lengths(p.p_BoP_B), P.Length(Lscale)), P.L, P.I);
      PointInertiaText(out, P, mp.CalcInertiaAbout(p.p_BoP_B), mp.mass());
    }
    if (frame.given) {
      out += fmt::format("  Inertia about the centre of mass in frame {} [{}]\n", frame.text, P.I);
      MatrixText(out, P.InertiaMatrix(Icm.ReExpressedIn(frame.R_BF.transpose()).matrix()), "    ");
    }
  }
  for (const auto& w : scene.warnings) out += fmt::format("\nwarning: {}\n", w);
  return out;
}

}  // namespace

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
  const Presenter P(UnitSystem::Parse(args.units.empty() ? scene.units : args.units));
  std::vector<MassReportPoint> extra;
  for (const std::string& a : args.about) {
    extra.push_back({"'" + a + "'", ReadPointOption(scene, a, "--about")});
  }
  CheckPointInertias(scene, extra);
  Frame frame;
  if (!args.frame.empty()) {
    frame.given = true;
    frame.text = "F";
    frame.R_BF = ReadRotationOption(scene, args.frame, "--frame");
  }
  // Every value of either report is in the JSON form: checked there first, by name (and let
  // go before the text is written: for 100 000 bodies each takes some 400 MB).
  std::string report;
  {
    const nlohmann::json j = MassReportJson(
        scene, P.units, extra, frame.given ? std::optional<Mat3>(frame.R_BF) : std::nullopt);
    if (args.format == "json") {
      report = DumpJson(j, "the mass report");
    } else {
      CheckFiniteJson(j, "the mass report");
    }
  }
  if (args.format != "json") report = TextReport(scene, P, args, extra, frame);
  if (!args.html.empty()) out.Add(args.html, HtmlReport(MassReportData(scene)));
  out.Add(ReportTarget(args.output), std::move(report));
  out.Commit();
  SayWroteHtmlReport(args.html);
  return 0;
}

}  // namespace chasles::cli
