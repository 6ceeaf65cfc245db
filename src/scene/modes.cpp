#include "chasles/scene/modes.h"

#include <memory>
#include <utility>

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/scene/scene_error.h"
#include "chasles/scene/study.h"
#include "internal/definition_start.h"

namespace chasles {

ModesDefinition MakeModesDefinition(const Scene& scene) {
  ModesDefinition def;
  scene_internal::StartDefinition(scene, def);
  return def;
}

ModesDefinition MakeModesDefinitionAt(const std::function<Scene(const SceneOptions&)>& load,
                                      const SceneOptions& options, const std::string& name,
                                      const std::string& unit, double value) {
  SceneOptions o = options;
  o.parameter_overrides.emplace_back(
      name, unit.empty() ? fmt::format("{:.17g}", value) : fmt::format("{:.17g} {}", value, unit));
  const auto at_value = [name, unit, value](const SceneError& e) {
    return SceneError(e.file(), e.line(), e.column(), e.key(),
                      fmt::format("at {} = {:.12g}{}: {}", name, value,
                                  unit.empty() ? "" : " " + unit, e.message()));
  };
  try {
    ModesDefinition def = MakeModesDefinition(load(o));
    def.locate_error = [locate = std::move(def.locate_error), at_value](const InputError& e) {
      try {
        locate(e);
      } catch (const SceneError& located) {
        throw at_value(located);
      }
    };
    return def;
  } catch (const SceneError& e) {
    throw at_value(e);
  }
}

}  // namespace chasles
