#pragma once
/// @file
/// The subcommands of the chasles program, one file each. Each Add...Command registers its
/// options on the app and returns the subcommand; Run... does the work once parsed.

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "chasles/files/input_file.h"
#include "chasles/scene/scene.h"

namespace chasles::cli {

/// Options shared by commands that read a scene.
struct SceneArgs {
  std::string scene;                               // path, or "" for the built-in demonstration
  std::vector<std::string> set;                    // NAME=EXPRESSION parameter overrides
  size_t max_scene_bytes = kDefaultMaxSceneBytes;  // --max-scene-bytes
};

struct MassArgs {
  SceneArgs scene;
  std::string units;               // "" = the scene's own units
  std::string format = "text";     // text | json
  std::vector<std::string> about;  // extra points for the inertia
  std::string frame;               // orientation of a report frame in the body
  std::string output;              // file, or "" for standard output
  bool hide_parts = false;
  std::string html;  // --html: also write the browser report here
  // --sweep NAME=START:STOP:COUNT (repeatable: a grid) with --quantity (docs/sweeps.md).
  std::vector<std::string> sweep, quantity;
  int jobs = 0;                       // threads of a sweep; 0: the hardware's concurrency
  std::int64_t max_runs = 0;          // most points of a sweep; 0: the default limit
  bool quiet = false;                 // no progress of a sweep on stderr
  double progress_interval = 10.0;    // [s] between progress lines off a terminal
  std::string precision = "default";  // a sweep table's numbers: default | full (%.17g)
  bool full_precision = false;        // --full-precision: precision "full"
  // A mesh file given instead of a scene (chasles mass part.stl --unit mm --density 7850):
  // these say what the scene's mesh part would.
  std::string mesh_unit, mesh_mode, mesh_density, mesh_material, mesh_mass, mesh_areal_density,
      mesh_thickness;
  // A robot file given instead of a scene (chasles mass robot.urdf --joint elbow=0.5).
  std::vector<std::string> robot_packages, robot_joints;
};

CLI::App* AddMassCommand(CLI::App& app, MassArgs& args);
int RunMass(const MassArgs& args);

struct CheckArgs {
  SceneArgs scene;
};
CLI::App* AddCheckCommand(CLI::App& app, CheckArgs& args);
int RunCheck(const CheckArgs& args);

struct SimulateArgs {
  SceneArgs scene;
  double until = std::numeric_limits<double>::quiet_NaN();  // [s]; NaN: the scene's
  std::string out_dir;                                      // "" = current directory
  std::string format = "text";                              // text | json
  std::vector<std::string> columns;  // CSV columns or groups, replacing the scene's output
  std::string units;                 // text report units; "" = the scene's
  bool strict = false;               // a failed check exits with kExitCheckFailed
  // Limits on the run's work, replacing the scene's simulation keys (0 / NaN: the scene's).
  std::int64_t max_steps = 0;
  std::int64_t max_rows = 0;
  double timeout = std::numeric_limits<double>::quiet_NaN();   // [s]; 0: none
  double min_step = std::numeric_limits<double>::quiet_NaN();  // [s]
  bool quiet = false;                                          // no progress on stderr
  double progress_interval = 10.0;  // [s] between progress lines off a terminal
  std::string html;                 // --html: also write the browser report here
  // --sweep NAME=START:STOP:COUNT (repeatable: a grid) with --quantity (docs/sweeps.md).
  std::vector<std::string> sweep, quantity;
  int jobs = 0;                       // threads of a sweep; 0: the hardware's concurrency
  std::string keep_runs;              // write each run's CSV and JSON here
  std::int64_t max_runs = 0;          // most points of a sweep; 0: the default limit
  std::string precision = "default";  // CSV numbers: default | full (%.17g)
  bool full_precision = false;        // --full-precision: precision "full"
};
CLI::App* AddSimulateCommand(CLI::App& app, SimulateArgs& args);
int RunSimulate(const SimulateArgs& args);

struct SolveArgs {
  SceneArgs scene;
  std::string sweep;                  // NAME=START:STOP:COUNT, or "" for one solve
  std::string format = "text";        // text | json
  bool strict = false;                // a failed check exits with kExitCheckFailed
  std::int64_t max_rows = 0;          // most sweep values; 0: the default limit
  bool quiet = false;                 // no progress on stderr
  double progress_interval = 10.0;    // [s] between progress lines off a terminal
  std::string html;                   // --html: also write the browser report here (one solve)
  std::string units;                  // text report units; "" = the scene's
  std::string output;                 // -o/--out: write the report here, "" = standard output
  std::string precision = "default";  // CSV numbers: default | full (%.17g)
  bool full_precision = false;        // --full-precision: precision "full"
};
CLI::App* AddSolveCommand(CLI::App& app, SolveArgs& args);
int RunSolve(const SolveArgs& args);

/// `chasles report RUN.json -o report.html`: the browser report of a finished simulate run,
/// from its JSON summary, the CSV it names and the scene it names.
struct ReportArgs {
  std::string run_json;
  std::string output;
  std::vector<std::string> set;                    // the run's --set overrides, if any
  size_t max_scene_bytes = kDefaultMaxSceneBytes;  // --max-scene-bytes
  size_t max_input_bytes = kDefaultMaxInputBytes;  // --max-input-bytes (the JSON and the CSV)
};
CLI::App* AddReportCommand(CLI::App& app, ReportArgs& args);
int RunReport(const ReportArgs& args);

/// `chasles upgrade FILE`: the scene rewritten as the current format version, shown as a
/// unified diff and written with -o or --in-place (docs/scene-format.md, "Changes between
/// versions").
struct UpgradeArgs {
  std::string scene;
  std::string output;  // -o: write the upgraded scene here
  bool in_place = false;
  bool check = false;  // only say whether the file needs upgrading (exit 3 when it does)
  size_t max_scene_bytes = kDefaultMaxSceneBytes;
};
CLI::App* AddUpgradeCommand(CLI::App& app, UpgradeArgs& args);
int RunUpgrade(const UpgradeArgs& args);

/// `chasles audit FILE...`: robot descriptions (URDF, MJCF, SDF) checked against their own
/// geometry (docs/audit.md).
struct AuditArgs {
  std::vector<std::string> files;
  std::string format = "text";        // text | json
  std::string output;                 // -o: the report to this file
  std::string html;                   // --html: the browser report
  bool fix = false;                   // --fix: write corrected files
  std::string out_dir;                // --out: where --fix writes
  std::vector<std::string> packages;  // --package NAME=DIR
  std::vector<std::string> joints;    // --joint NAME=VALUE (the robot's total)
};
CLI::App* AddAuditCommand(CLI::App& app, AuditArgs& args);
int RunAudit(const AuditArgs& args);

CLI::App* AddMaterialsCommand(CLI::App& app);
int RunMaterials();

struct PlotArgs {
  std::string input;                 // a run's JSON, a run's CSV or a sweep's CSV
  std::vector<std::string> columns;  // X, then the Y columns
  std::string output;                // .svg or .png
  std::string title;
  std::string by;    // one line per value of this column (a grid sweep's other parameter)
  bool log = false;  // both axes logarithmic (base 10)
  size_t max_input_bytes = kDefaultMaxInputBytes;  // --max-input-bytes
};
/// Built only with PLplot (CHASLES_HAVE_PLOT).
CLI::App* AddPlotCommand(CLI::App& app, PlotArgs& args);
int RunPlot(const PlotArgs& args);

/// `chasles modes SCENE`: small motions about the operating point (docs/modes.md).
struct ModesArgs {
  SceneArgs scene;
  std::string sweep;            // NAME=START:STOP:COUNT, or "" for one operating point
  std::string format = "text";  // text | json | csv (a sweep's table)
  std::string output;           // -o/--out, "" = standard output
  std::string html;             // --html: also write the browser report here (the modes animated)
};
CLI::App* AddModesCommand(CLI::App& app, ModesArgs& args);
int RunModes(const ModesArgs& args);

/// `chasles balance SCENE --body NAME ...`: a rotor's unbalance and its two-plane correction
/// (docs/modes.md, "Rotors").
struct BalanceArgs {
  SceneArgs scene;
  std::string body;                   // the rotor (a body of the scene)
  std::string axis = "[0, 0, 1]";     // spin axis in W, as in a scene
  std::string through = "[0, 0, 0]";  // a point of the axis in W
  std::string planes;                 // 'A, B': the two correction planes' positions along the axis
  std::string radius;                 // the correction radius (a length with its unit)
  std::string speed;            // the spin for the bearing reactions and the grade (rad/s, rpm)
  double grade = 0.0;           // ISO 21940-11 balance grade G [mm/s]; 0: none
  std::string whirl;            // 'A:B:N': the spins of the whirl rows (with elastic bearings)
  std::string format = "text";  // text | json
  std::string output;           // -o/--out
};
CLI::App* AddBalanceCommand(CLI::App& app, BalanceArgs& args);
int RunBalance(const BalanceArgs& args);

/// The built-in demonstration scene (the chapter's disk-and-axle assembly, Section 8.3).
extern const char* const kDemoScene;

}  // namespace chasles::cli
