#pragma once
/// @file
/// Where an analysis's errors are placed: a definition (StudyDefinition, SolveDefinition,
/// ModesDefinition) may carry a locator that its entry point (RunStudy, SolveAtState,
/// AnalyseOperatingPointModes) throws every InputError through.

#include <functional>

#include "chasles/error.h"

namespace chasles {

/// Places an error at its source: called with an InputError a computation threw (a
/// LimitError too), it throws the error located (e.g. the scene layer's SceneError at the
/// file:line:col of the entry it concerns) and does not return; should it return, the error
/// is thrown as it was.
using ErrorLocator = std::function<void(const InputError& error)>;

}  // namespace chasles
