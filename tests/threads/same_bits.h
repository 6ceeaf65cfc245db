#pragma once
/// @file
/// Bitwise comparison of States for the threads tests: a run on several threads must give the
/// one-thread run's bits, not merely close numbers.

#include <cstring>

#include "chasles/model/state.h"

namespace chasles::test {

/// Whether a and b have the same time and the same bits in every body's motion.
inline bool SameBits(const State& a, const State& b) {
  if (a.t != b.t || a.bodies.size() != b.bodies.size()) return false;
  for (size_t i = 0; i < a.bodies.size(); ++i) {
    const BodyState &x = a.bodies[i], &y = b.bodies[i];
    if (std::memcmp(x.p_WBcm.data(), y.p_WBcm.data(), sizeof(double) * 3) != 0 ||
        std::memcmp(x.v_WBcm_W.data(), y.v_WBcm_W.data(), sizeof(double) * 3) != 0 ||
        std::memcmp(x.w_WB_B.data(), y.w_WB_B.data(), sizeof(double) * 3) != 0 ||
        std::memcmp(x.q_WB.coeffs().data(), y.q_WB.coeffs().data(), sizeof(double) * 4) != 0) {
      return false;
    }
  }
  return true;
}

}  // namespace chasles::test
