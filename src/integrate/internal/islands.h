#pragma once
/// @file
/// The hybrid run of a model with contacts, split into islands where it can be
/// (chasles/integrate/islands.h): each island runs as its own hybrid system (RunHybrid on a
/// Model of its bodies), and the results are merged. Called by Simulate.

#include "chasles/integrate/simulate.h"

namespace chasles::internal {

/// Runs `model` (with contacts or strings) from `initial`: as islands when it has several and
/// nothing needs the whole State at once, else as one system (RunHybrid). The result's
/// `islands` says which and why.
SimulationResult RunHybridIslands(const Model& model, const State& initial,
                                  const SimulationOptions& o);

}  // namespace chasles::internal
