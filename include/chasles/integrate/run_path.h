#pragma once
/// @file
/// Which engine runs a simulation: the one place the run path is chosen (docs/contact.md,
/// "Run paths", has the table of what each guarantees). Simulate, the fixed-step integrators
/// (MakeIntegrator), a study's run and a scene's definition all ask ChooseRunPath, and a run's
/// report names the path it took and why.
///
/// The paths:
///  - kSmooth: no contacts and no strings: one integrator (SimulationOptions::integrator) on
///    the whole model, events on the adaptive integrator's dense output.
///  - kFreeBodyBatch: free bodies under uniform gravity alone (FreeBodyBatchObstacle empty)
///    with a fixed-step RK4 or the splitting integrator: the structure-of-arrays batch
///    (free_body_batch.h), tile by tile through the steps between output times.
///  - kHybrid: contacts or strings (modes that switch), one hybrid system: every regime change
///    located on the Dormand–Prince dense output and integrated exactly.
///  - kIslands: the same hybrid run, the bodies split into islands that run separately
///    (islands.h).
///  - kSphereEvents: `integrator: events`: balls on a table in closed form between events
///    (sphere_events.h).
///  - kTimeStepping: `integrator: stepping`: Moreau–Jean time stepping (time_stepping.h).
///  - kAuto: `integrator: auto`: the hybrid run while regime changes come slower than the rule
///    of engine_choice.h, time stepping while they come faster.

#include <string>

#include "chasles/model/model.h"

namespace chasles {

struct SimulationOptions;

enum class RunPath {
  kSmooth,
  kFreeBodyBatch,
  kHybrid,
  kIslands,
  kSphereEvents,
  kTimeStepping,
  kAuto,
};

/// The engine a run asks for: the integrator of its SimulationOptions, or one of the contact
/// engines a scene names (`integrator: events`, `stepping`, `auto`).
enum class EngineRequest { kIntegrator, kEvents, kStepping, kAuto };

/// The path chosen and why.
struct RunPathChoice {
  RunPath path = RunPath::kSmooth;
  /// Why this path, in words for the report ("contacts switch modes; the bodies form one
  /// island", ...).
  std::string reason;
  /// Islands the bodies form (kHybrid and kIslands; 0 where not looked for).
  int islands = 0;
  /// kHybrid: why the bodies run as one system (IslandReport::reason).
  std::string one_system;
};

/// The path's name in reports: "smooth", "free-body batch", "hybrid", "islands",
/// "event-driven spheres", "time stepping", "auto".
const char* RunPathName(RunPath path);

/// The one choice of a run's path for `model` under `options` and `request`:
///  - kEvents: kSphereEvents; InputError when the model is not balls on a table
///    (SphereEventObstacle names what is not).
///  - kStepping: kTimeStepping; InputError when TimeSteppingObstacle names a reason.
///  - kAuto: kAuto (AutoHandoverObstacle says whether it can ever hand over).
///  - kIntegrator: a model with contacts or strings that can let go runs hybrid (InputError
///    unless the integrator is Dormand–Prince), as islands when the bodies form several,
///    islands are on (SimulationOptions::islands), nothing needs the whole State at once
///    (events, on_transition, the engine choice's yield) and IslandObstacle is empty; else
///    kFreeBodyBatch for RK4 or splitting on free bodies under uniform gravity (InputError for
///    splitting on a model that does not qualify); else kSmooth.
RunPathChoice ChooseRunPath(const Model& model, const SimulationOptions& options,
                            EngineRequest request = EngineRequest::kIntegrator);

/// Why a run under `integrator: auto` must stay event-driven on `model` (events, located on
/// the adaptive integrator's dense output, or TimeSteppingObstacle); empty when it can hand
/// over to time stepping.
std::string AutoHandoverObstacle(const Model& model, bool has_events);

}  // namespace chasles
