#pragma once
/// @file
/// A scene's small motions (`chasles modes`, docs/modes.md) as a ModesDefinition for the
/// analysis layer's AnalyseOperatingPointModes and SweepModes (chasles/analysis/modes.h: the
/// operating point, the linearisation, the modes, and sweeps of a parameter with the values
/// where the stability changes): the scene's Model and initial state, and the locator that
/// brings the analysis's errors back at the scene entry they concern.

#include <functional>
#include <string>

#include "chasles/analysis/modes.h"
#include "chasles/scene/scene.h"

namespace chasles {

/// The scene's Model, initial state and its settling (BuildStudy), and the locator of the
/// analysis's errors (ThrowAtSceneEntry). Errors, here or in the analysis of it, are SceneErrors at
/// the entry they concern.
ModesDefinition MakeModesDefinition(const Scene& scene);

/// The definition of the scene `load` reads with `options` and the parameter `name` set to
/// `value` [SI; `unit` its SI unit, "" for a number], for a point of SweepModes. Its errors,
/// here or in the analysis, are SceneErrors at the scene entry that name the parameter's value
/// ("at NAME = VALUE UNIT: ...").
ModesDefinition MakeModesDefinitionAt(const std::function<Scene(const SceneOptions&)>& load,
                                      const SceneOptions& options, const std::string& name,
                                      const std::string& unit, double value);

}  // namespace chasles
