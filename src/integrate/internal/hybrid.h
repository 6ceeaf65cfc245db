#pragma once
/// @file
/// The hybrid run of a model with contacts: Dormand-Prince between contact events, mode
/// selection and impacts at each event, restart. Called by Simulate.

#include "chasles/integrate/simulate.h"

namespace chasles::internal {

/// Runs `model` (with contacts) from `initial` with the adaptive integrator.
SimulationResult RunHybrid(const Model& model, const State& initial, const SimulationOptions& o);

}  // namespace chasles::internal
