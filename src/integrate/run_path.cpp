#include "chasles/integrate/run_path.h"

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/integrate/free_body_batch.h"
#include "chasles/integrate/islands.h"
#include "chasles/integrate/simulate.h"
#include "chasles/integrate/sphere_events.h"
#include "chasles/integrate/time_stepping.h"

namespace chasles {
namespace {

// Why a hybrid run is one system although its bodies may form several islands; empty when the
// islands can run separately.
std::string OneSystemReason(const Model& model, const SimulationOptions& o, int count) {
  if (!o.islands) return "islands turned off";
  if (count <= 1) return "the bodies form one island";
  if (o.on_transition && !o.island_transition) {
    return "the checks at each contact change (on_transition: energy, contact forces) need the "
           "whole system's state at that instant";
  }
  if (!o.events.empty()) return "user events are functions of the whole state";
  return IslandObstacle(model);
}

RunPathChoice ChooseHybrid(const Model& model, const SimulationOptions& o) {
  if (o.integrator != IntegratorKind::kDormandPrince5) {
    throw InputError(
        "contacts and strings switch modes at events located on the adaptive integrator's "
        "dense output; choose the Dormand-Prince integrator for a model with contacts or "
        "strings");
  }
  RunPathChoice c;
  c.islands = static_cast<int>(FindIslands(model).bodies.size());
  c.one_system = OneSystemReason(model, o, c.islands);
  if (c.one_system.empty()) {
    c.path = RunPath::kIslands;
    c.reason = fmt::format(
        "contacts or strings switch modes; the bodies form {} islands, each run as its own "
        "hybrid system",
        c.islands);
  } else {
    c.path = RunPath::kHybrid;
    c.reason = "contacts or strings switch modes; one hybrid system: " + c.one_system;
  }
  return c;
}

RunPathChoice ChooseWithoutContacts(const Model& model, const SimulationOptions& o) {
  RunPathChoice c;
  const bool batch_kind =
      o.integrator == IntegratorKind::kRk4 || o.integrator == IntegratorKind::kSplitting;
  const ModelObstacle obstacle = batch_kind ? FreeBodyBatchObstacle(model) : ModelObstacle{};
  if (batch_kind && obstacle.empty()) {
    c.path = RunPath::kFreeBodyBatch;
    c.reason = fmt::format(
        "free bodies under uniform gravity alone, stepped by {} on the structure-of-arrays batch",
        o.integrator == IntegratorKind::kRk4 ? "RK4" : "the symplectic splitting");
    return c;
  }
  if (o.integrator == IntegratorKind::kSplitting) {
    throw InputError(fmt::format("the splitting integrator steps free bodies under uniform "
                                 "gravity only, and {}; choose rk4 or the adaptive integrator",
                                 obstacle.why),
                     obstacle.element);
  }
  c.path = RunPath::kSmooth;
  c.reason = fmt::format("no contacts or strings: the {} integrator on the whole model",
                         IntegratorName(o.integrator));
  if (batch_kind) c.reason += fmt::format(" (not the free-body batch: {})", obstacle.why);
  return c;
}

}  // namespace

const char* RunPathName(RunPath path) {
  switch (path) {
    case RunPath::kSmooth:
      return "smooth";
    case RunPath::kFreeBodyBatch:
      return "free-body batch";
    case RunPath::kHybrid:
      return "hybrid";
    case RunPath::kIslands:
      return "islands";
    case RunPath::kSphereEvents:
      return "event-driven spheres";
    case RunPath::kTimeStepping:
      return "time stepping";
    case RunPath::kAuto:
      return "auto";
  }
  return "unknown";
}

std::string AutoHandoverObstacle(const Model& model, bool has_events) {
  if (has_events) {
    return "the run's events are located on the adaptive integrator's dense output";
  }
  return TimeSteppingObstacle(model).why;
}

RunPathChoice ChooseRunPath(const Model& model, const SimulationOptions& options,
                            EngineRequest request) {
  RunPathChoice c;
  switch (request) {
    case EngineRequest::kEvents:
      if (const ModelObstacle o = SphereEventObstacle(model); !o.empty()) {
        throw InputError(fmt::format("'integrator: events' runs balls on a table only: {}", o.why),
                         o.element);
      }
      c.path = RunPath::kSphereEvents;
      c.reason = "balls on a table, in closed form between events, as requested";
      return c;
    case EngineRequest::kStepping:
      if (const ModelObstacle o = TimeSteppingObstacle(model); !o.empty()) {
        throw InputError(fmt::format("'integrator: stepping' cannot run this scene: {}", o.why),
                         o.element);
      }
      c.path = RunPath::kTimeStepping;
      c.reason = "Moreau-Jean at a fixed step, as requested";
      return c;
    case EngineRequest::kAuto: {
      c.path = RunPath::kAuto;
      const std::string stays = AutoHandoverObstacle(model, !options.events.empty());
      c.reason = stays.empty()
                     ? "the hybrid run while regime changes come slower than the rule allows, "
                       "time stepping while they come faster"
                     : "the hybrid run throughout: " + stays;
      return c;
    }
    case EngineRequest::kIntegrator:
      break;
  }
  bool switching = false;  // a constraint that can let go (a string without drums)
  for (int k = 0; k < model.num_constraints(); ++k) {
    switching = switching || model.constraint(k).can_release();
  }
  if (model.num_contacts() > 0 || switching) return ChooseHybrid(model, options);
  return ChooseWithoutContacts(model, options);
}

}  // namespace chasles
