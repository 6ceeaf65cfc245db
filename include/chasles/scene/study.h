#pragma once
/// @file
/// A scene's dynamics as a study: a StudyDefinition for the library's RunStudy
/// (include/chasles/analysis/study.h, where the run and its result types live), or a Model, an
/// initial State and SimulationOptions for Simulate (docs/scene-format.md, "Dynamics"). This
/// layer only translates: the scene's bodies, forces (expressions), joints, contacts, events,
/// impulses, impacts, columns and limits; the definition locates its run's errors, which come
/// back at their file:line:col.

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "chasles/analysis/initial_state.h"
#include "chasles/analysis/study.h"
#include "chasles/error.h"
#include "chasles/integrate/simulate.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"
#include "chasles/scene/scene.h"

namespace chasles {

/// The first segment of a scene's run, ready for Simulate.
struct Study {
  /// Held by pointer: the force and event functions read it, so its address must not change.
  std::shared_ptr<const Model> model;
  /// The initial state as the scene gives it: on the constraints once settled with
  /// `settling` (the analysis layer's SettleInitialState; `project_initial: true` projects it).
  State initial;
  InitialSettling settling;
  /// Integrator, end time, output interval, tolerances and events from the scene.
  SimulationOptions options;
  /// What the scene models otherwise than it reads (a string given from a body to the world).
  std::vector<std::string> warnings;
};

/// Builds the Model (one body per scene body, gravity, the scene's force elements, and its
/// joints, rolling contacts and drivers with attachment frames taken from their world poses at
/// the initial State), the initial State and how to settle it, and the options. `until` [s]
/// overrides the scene's end time when finite. Throws SceneError at the entry concerned when
/// there is no end time or a value is invalid.
Study BuildStudy(const Scene& scene, double until = std::numeric_limits<double>::quiet_NaN());

struct StudyOptions {
  /// End time [s], overriding the scene's when finite.
  double until = std::numeric_limits<double>::quiet_NaN();
  /// Called with the time of every output sample and every accepted step (e.g. for a
  /// progress display).
  std::function<void(double t)> progress;
  /// Limits on the run's work replacing the scene's `simulation:` keys (command-line flags;
  /// docs/reliability-limits.md): accepted integration steps and output rows (< 1: the
  /// scene's), wall time [s] (0: none; NaN: the scene's) and the smallest step [s] (NaN: the
  /// scene's, or 1e-12 of the span).
  std::int64_t max_steps = 0;
  std::int64_t max_rows = 0;
  double timeout = std::numeric_limits<double>::quiet_NaN();
  double min_step = std::numeric_limits<double>::quiet_NaN();
  /// Record the reactions and contact points at every output row (the browser report).
  bool record_row_snapshots = false;
  /// Record every body's pose at every output row (StudyResult::row_poses; the browser
  /// report's replay).
  bool record_row_poses = false;
};

/// The scene's study for the library's RunStudy: bodies, a ModelBuilder and an EventBuilder
/// (holding their own copy of the scene), the initial state as given and how the run settles
/// it on the constraints (projected when `project_initial: true`, each change a warning; an
/// error at the body's `initial` entry otherwise), options, columns, impulses, impacts,
/// limits (the command line's `options`, else the scene's), the certificate's tolerances, the
/// columns' units (StudyColumnUnits) and the locator of the run's errors. Every error, here or
/// in the analysis layer's RunStudy of it, is a SceneError with the scene file's line and
/// column (ThrowAtSceneEntry): bad settings; inputs no run can integrate; limits the run would
/// exceed for sure (rows from the span and the output interval, fixed steps, a spring too stiff
/// for the step budget), refused here; a force, reaction, acceleration or state that becomes
/// non-finite during the run (the element and the time are named; nothing non-finite is ever
/// returned); a limit on the work reached (steps, rows, wall time, smallest step: the message
/// names the limit and the flag and scene key that raise it).
StudyDefinition MakeStudyDefinition(const Scene& scene, const StudyOptions& options = {});

/// Rethrows an InputError found after the scene was read (building the Model, assembling or
/// solving the constraints, during the run) as a SceneError at the entry of the Model element
/// it carries (InputError::element: a body, force element, constraint, contact, contact point
/// or event, mapped to the scene entry it was built from), at a force's expression when that
/// evaluated to a non-finite value; at the `simulation` key when it carries none. A SceneError
/// is rethrown as it is.
[[noreturn]] void ThrowAtSceneEntry(const Scene& scene, const InputError& error);

/// The CSV columns named on the command line (groups or single columns, as in the scene's
/// `output.columns`), with `t` first. Throws SceneError naming --columns for an unknown name.
std::vector<std::string> SelectColumns(const Scene& scene, const std::vector<std::string>& names);

}  // namespace chasles
