#pragma once
/// @file
/// The text reports of `chasles modes` (docs/modes.md): the operating point with its reactions,
/// the linearisation's coordinates and checks, each mode's eigenvalue, frequency, damping or
/// growth and shape, and the verdict; a sweep's modes at each value, its critical speeds and
/// the values where the stability changes. SI throughout.

#include <string>

#include "chasles/scene/modes.h"
#include "chasles/scene/scene.h"

namespace chasles {

/// The small motions about `scene`'s operating point.
std::string ModesText(const Scene& scene, const OperatingPointModes& modes);

/// The modes at each value of a sweep, its critical speeds and its stability changes.
std::string ModesSweepText(const ModesSweep& sweep);

}  // namespace chasles
