#pragma once
/// @file
/// The scene's initial state against its constraints (docs/scene-format.md, "Initial state and
/// constraints"). Private to the scene layer.

#include <string>
#include <vector>

#include "chasles/model/model.h"
#include "chasles/model/state.h"
#include "chasles/scene/scene.h"

namespace chasles::scene_internal {

/// `given` (the scene's initial state on `model`, one Model body per scene body) on the
/// constraints. Residuals within kRoundOffResidual of the state's scales are corrected without
/// a word; larger ones are a SceneError at the body's `initial` entry listing each violated
/// constraint (residual with units, body, what to give) and the nearest consistent values,
/// unless the scene has `project_initial: true`: then the projected state is returned and every
/// changed value (body, quantity, given -> used, with units) is appended to `warnings`.
State SettleInitialState(const Scene& scene, const Model& model, const State& given,
                         std::vector<std::string>& warnings);

}  // namespace chasles::scene_internal
