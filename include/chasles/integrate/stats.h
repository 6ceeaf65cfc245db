#pragma once
/// @file
/// Work counters shared by the integrators.

#include <cstdint>

namespace chasles {

struct IntegratorStats {
  /// Accepted steps.
  std::int64_t steps = 0;
  /// Rejected step attempts (adaptive integrators only).
  std::int64_t rejected_steps = 0;
  /// Evaluations of the equations of motion (force and acceleration computations).
  std::int64_t function_evaluations = 0;
  /// True when the run was stepped by the free-body batch (FreeBodyBatchRk4Integrator, the
  /// structure-of-arrays fast path for free bodies under uniform gravity) instead of the
  /// general equations of motion.
  bool free_body_batch = false;
};

}  // namespace chasles
