#pragma once
/// @file
/// The instantaneous problem of a scene (what `chasles solve` reports, chapter 8.2-8.3): at the
/// scene's initial state, every body's acceleration, every constraint's reaction, the friction
/// rolling needs against mu_s, each contact point's mode and forces, the kinetic energy and
/// momenta, and the solve's checks of its own answer. A sweep repeats it over a range of one
/// scene parameter and returns a table.

#include <functional>
#include <string>
#include <vector>

#include "chasles/analysis/certificate.h"
#include "chasles/analysis/instantaneous.h"
#include "chasles/dynamics/contact_solve.h"
#include "chasles/model/contact.h"
#include "chasles/scene/scene.h"

namespace chasles {

/// Kinetic energy and momenta of one body (or, for the total, of all of them) at the solved
/// state (eqs. 8.115, 8.116): T = ½ m v² + ½ ωᵀ I ω, p = m v, H about the centre of mass
/// I ω and about the world origin H_O = H + p_cm × m v.
struct SceneMotion {
  /// Body name ("" for the total).
  std::string name;
  /// Translational and rotational kinetic energy [J].
  double T_trans = 0.0, T_rot = 0.0;
  /// Linear momentum in W [kg·m/s].
  Vec3 P = Vec3::Zero();
  /// Angular momentum about the body's own centre of mass (for the total, about the system's
  /// centre of mass), in W [kg·m²/s].
  Vec3 H_cm = Vec3::Zero();
  /// Angular momentum about the world origin, in W [kg·m²/s].
  Vec3 H_O = Vec3::Zero();
};

/// One contact point at the solved state, in the mode SelectContactModes chose.
struct SceneContactReport {
  /// The scene's name of the point ("floor", "incline_0", "rear") and its contact's name.
  std::string point, contact;
  /// Mode, normal and friction force, slip velocity, gap, point and normal in W.
  ContactPointOutput out;
  /// The contact's coefficients of static and kinetic friction.
  double mu_s = 0.0, mu_k = 0.0;
  /// A round feature (sphere, rim): a sticking one rolls without slipping.
  bool round = false;
  /// "rolls" or "sticks" (sticking), "slides", "separated".
  std::string Regime() const;
  /// |f| / N: the friction a sticking point needs (compare with mu_s), mu_k when sliding, 0
  /// when separated.
  double FrictionRatio() const;
};

/// Everything `chasles solve` reports for one scene.
struct SceneSolution {
  /// Accelerations, reactions (a planar scene's plane constraints left out), rank, warnings
  /// (initial values changed by `project_initial: true` first).
  InstantaneousSolution solution;
  /// mu_s of each reaction (NaN when not a rolling contact with `mu_s`), in reaction order.
  std::vector<double> mu_s;
  /// Per body (Model order).
  std::vector<SceneMotion> motion;
  /// All bodies together.
  SceneMotion total;
  /// A planar scene: reports in x, y and about z (a_x, a_y, alpha; Fx, Fy, Mz).
  bool planar = false;
  /// Contact points (scene order), in their chosen modes.
  std::vector<SceneContactReport> contacts;
  /// The solve's checks of its own answer (friction, N, gaps, residuals, Newton–Euler).
  Certificate certificate;
};

/// Solves the scene's instantaneous problem at its initial state (projected onto the
/// constraints; contact modes chosen as a simulation starts, impacts not applied). Errors are
/// SceneErrors at the scene entry they concern (ThrowAtSceneEntry).
SceneSolution SolveScene(const Scene& scene);

/// One row of a sweep table: the solution's values in table order, with their names and SI
/// units ("m/s^2", "N", ...) when the pointers are given. Per body a and alpha (planar: a_x,
/// a_y, alpha), the kinetic energy and momenta per body and in total (named as the
/// simulation's ledger columns), per constraint F and M (planar: Fx, Fy, Mz) and for rolling
/// N, |f| and f/N, per contact point mode (0 separated, 1 sliding, 2 sticking), N, |f|, f/N.
void SolutionTableRow(const SceneSolution& s, std::vector<std::string>* names,
                      std::vector<std::string>* units, std::vector<double>* values);

/// A sweep of one scene parameter: COUNT values from START to STOP, both expressions with
/// units as in a scene file ("0 deg", "60 deg").
struct SweepSpec {
  std::string name, start, stop;
  int count = 0;
  /// Where the sweep was given, for errors (SceneError file and key), e.g. "command line" and
  /// "--sweep".
  std::string source = "sweep";
  std::string key = "sweep";
};

/// Reads NAME=START:STOP:COUNT (e.g. "theta=0 deg:60 deg:7"). Throws SceneError at
/// (`source`, `key`) for a malformed text or COUNT < 2.
SweepSpec ParseSweep(const std::string& text, const std::string& source = "sweep",
                     const std::string& key = "sweep");

/// The sweep's result: one row per value, the swept parameter first (SI).
struct SweepTable {
  std::string parameter;
  std::vector<std::string> columns;
  /// SI unit of each column ("" for pure numbers and angles in rad).
  std::vector<std::string> units;
  std::vector<std::vector<double>> rows;
  /// Failed checks, one per failed check of one value: "theta = 0.5: ...".
  std::vector<std::string> warnings;
  /// True when a check failed at some value.
  bool failed = false;
};

struct SweepOptions {
  /// Called before value k of count is solved (e.g. for a progress display).
  std::function<void(int k, int count)> progress;
  /// Called after each value is solved, with the parameter's SI value and the solution.
  std::function<void(double value, const SceneSolution& solution)> on_solution;
};

/// Loads the scene once per value with `options` plus the override NAME = START + (STOP -
/// START) k / (COUNT - 1) (so START and STOP keep their units) and solves it. `load` reads the
/// scene with the options it is given (from a file or from text). Throws SceneError at the
/// spec's source and key when the scene has no such parameter or COUNT < 2.
SweepTable SolveSweep(const std::function<Scene(const SceneOptions&)>& load,
                      const SceneOptions& options, const SweepSpec& spec,
                      const SweepOptions& sweep_options = {});

}  // namespace chasles
