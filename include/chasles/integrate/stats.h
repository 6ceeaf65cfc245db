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
};

}  // namespace chasles
