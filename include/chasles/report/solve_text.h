#pragma once
/// @file
/// The text report of a scene's instantaneous solve, as `chasles solve` prints it: every body's
/// acceleration, every constraint's reaction (for rolling the friction it needs against mu_s),
/// each contact point's mode and forces, the kinetic energy and momenta, the velocities and
/// dH/dt, warnings and checks.

#include <string>

#include "chasles/report/text_format.h"
#include "chasles/scene/scene.h"
#include "chasles/scene/solve.h"

namespace chasles {

/// The report of `solution` of `scene` in the units `options` asks for. Throws InputError
/// naming a value that is not finite or a bad unit.
std::string SolveText(const Scene& scene, const SolveReport& solution,
                      const TextOptions& options = {});

}  // namespace chasles
