#pragma once
/// @file
/// What every definition of an analysis at a scene's initial state starts from
/// (SolveDefinition, ModesDefinition, RotorBalanceDefinition). Private to the scene layer.

#include <memory>

#include "chasles/error.h"
#include "chasles/scene/scene.h"
#include "chasles/scene/study.h"

namespace chasles::scene_internal {

/// Fills the definition's `model`, `initial` and `settle_initial` from the scene's study
/// (BuildStudy; the end time plays no part in an analysis at an instant) and its
/// `locate_error`, which brings the analysis's errors back at the scene entry they concern
/// (ThrowAtSceneEntry, on a copy of the scene the definition keeps). Returns the study for what
/// else a definition takes from it (its warnings). Errors are SceneErrors at their entry.
template <typename Definition>
Study StartDefinition(const Scene& scene, Definition& definition) {
  Study study = BuildStudy(scene, 1.0);
  definition.model = study.model;
  definition.initial = study.initial;
  definition.settle_initial = study.settling;
  const auto shared = std::make_shared<const Scene>(scene);
  definition.locate_error = [shared](const InputError& e) { ThrowAtSceneEntry(*shared, e); };
  return study;
}

}  // namespace chasles::scene_internal
