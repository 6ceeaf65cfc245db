#pragma once
/// @file
/// Simulate's free-body batch path (RunPath::kFreeBodyBatch) and the fixed-step grid it shares
/// with MakeIntegrator.

#include "chasles/integrate/simulate.h"

namespace chasles::internal {

/// The step a fixed-step run takes: `options.fixed_step` (> 0, finite; InputError otherwise)
/// shortened to divide the output interval (the whole run from `t_start` when it is 0) evenly,
/// so that every output time is a step end.
double FixedGridStep(const SimulationOptions& options, double t_start);

/// Runs free bodies under uniform gravity alone (FreeBodyBatchObstacle empty) with the RK4 or
/// the splitting stepper of FreeBodyBatch: the bodies stay in the batch's arrays from the start
/// to the end, each stretch between output times advanced tile by tile through its steps, and
/// are written back into a State only at the output times. The bodies come out bit for bit as
/// the batch's own Advance makes them (and as MakeIntegrator's step-by-step wrapper of the
/// batch does); the gravity elements' force integrals are added per step in closed form.
SimulationResult RunFreeBodyBatch(const Model& model, const State& initial,
                                  const SimulationOptions& o);

}  // namespace chasles::internal
