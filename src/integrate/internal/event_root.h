#pragma once
/// @file
/// Event location on the dense output, shared by Simulate and the hybrid (contact) loop.

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "chasles/integrate/simulate.h"

namespace chasles::internal {

/// The first time at or after the sign change of g in [a, b] (g(a) = ga, g(b) = gb of
/// opposite signs), to within `tol` [s]: the Illinois variant of regula falsi (Dowell &
/// Jarratt, BIT 11, 1971). It keeps a bracket, so the answer is never before the crossing,
/// and it is superlinear, so a tight tolerance costs only a few more evaluations of the dense
/// output. The bracket cannot shrink below a few ulps of t: the effective tolerance is at
/// least 8 ε |b|, so late events (t ~ 1e5 s) still terminate.
/// Whether g going from g0 to g1 over a step is a zero crossing in direction `d`: from < 0 to
/// >= 0 (rising), from > 0 to <= 0 (falling).
inline bool Crosses(EventDirection d, double g0, double g1) {
  const bool rising = g0 < 0.0 && g1 >= 0.0;
  const bool falling = g0 > 0.0 && g1 <= 0.0;
  switch (d) {
    case EventDirection::kRising:
      return rising;
    case EventDirection::kFalling:
      return falling;
    default:
      return rising || falling;
  }
}

inline double LocateEventTime(const std::function<double(double)>& g, double a, double ga, double b,
                              double gb, double tol) {
  tol = std::max(tol, 8.0 * std::numeric_limits<double>::epsilon() * std::abs(b));
  int side = 0;
  for (int iter = 0; iter < 200 && b - a > tol; ++iter) {
    double c = (a * gb - b * ga) / (gb - ga);
    // Keep c strictly inside and at least tol/2 from the ends so the bracket always shrinks.
    c = std::clamp(c, a + 0.5 * tol, b - 0.5 * tol);
    const double gc = g(c);
    if (gc == 0.0) return c;
    if ((gc > 0.0) == (gb > 0.0)) {
      b = c, gb = gc;
      if (side == -1) ga *= 0.5;
      side = -1;
    } else {
      a = c, ga = gc;
      if (side == 1) gb *= 0.5;
      side = 1;
    }
  }
  return b;
}

}  // namespace chasles::internal
