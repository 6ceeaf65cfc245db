#pragma once
/// @file
/// The hybrid run of a model with contacts, split into islands where it can be
/// (chasles/integrate/islands.h): each island runs as its own hybrid system (RunHybrid on a
/// Model of its bodies), and the results are merged. Called by Simulate.

#include "chasles/integrate/simulate.h"

namespace chasles::internal {

/// Runs `model` (with contacts or strings) from `initial` as separate islands, each its own
/// hybrid system (the path ChooseRunPath calls kIslands); the result's `islands` lists them.
SimulationResult RunIslands(const Model& model, const State& initial, const SimulationOptions& o);

}  // namespace chasles::internal
