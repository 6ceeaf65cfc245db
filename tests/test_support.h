#pragma once
/// @file
/// Helpers shared by the tests: named, scaled tolerances and matrix comparisons.

#include <algorithm>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "chasles/math/types.h"

namespace chasles::test {

/// Machine epsilon for double.
inline constexpr double kEps = std::numeric_limits<double>::epsilon();
/// Tolerance for results that are exact up to a handful of floating-point operations.
inline constexpr double kExact = 64 * kEps;

/// 1 in a build with AddressSanitizer (GCC says so with __SANITIZE_ADDRESS__, clang with
/// __has_feature), else 0; a macro for tests that must leave code out under it.
#if defined(__SANITIZE_ADDRESS__)
#define CHASLES_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CHASLES_TEST_ASAN 1
#endif
#endif
#ifndef CHASLES_TEST_ASAN
#define CHASLES_TEST_ASAN 0
#endif

/// True in a build with AddressSanitizer (the sanitizer build, CHASLES_SANITIZE, or fuzzing).
inline constexpr bool kAddressSanitizer = CHASLES_TEST_ASAN == 1;

/// How many times a long test repeats its work (steps of one long run, random cases of a
/// property): `n` in an ordinary build, n / 10 under the sanitizers. The sanitizers look for
/// memory errors and undefined behaviour on the test's paths, which the first tenth walks as
/// the rest do; the numbers over all `n` are checked by the ordinary build, which CI runs too.
inline constexpr long Repeats(long n) {
  return kAddressSanitizer ? std::max(n / 10, 1L) : n;
}

/// Whether the `i`-th of a list of like cases (every example through the program, each in its
/// own run) is run: all of them in an ordinary build, every fourth under the sanitizers, which
/// walk the same readers, engines and writers in that quarter (see Repeats). A loop still counts
/// every case, so its "at least N" check holds in both builds.
inline constexpr bool Sampled(long i) {
  return !kAddressSanitizer || i % 4 == 0;
}

/// |a - b| <= rel * max(|b|, scale): a relative test whose floor is `scale` (the problem's
/// magnitude), so that expected zeros compare against the problem, not against zero.
inline ::testing::AssertionResult Near(double a, double b, double rel, double scale = 0.0) {
  const double tol = rel * std::max(std::abs(b), scale);
  if (std::abs(a - b) <= tol && std::isfinite(a)) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << a << " vs expected " << b << " (difference " << a - b << ", tolerance " << tol << ")";
}

template <typename A, typename B>
::testing::AssertionResult MatNear(const A& a, const B& b, double rel, double scale = 0.0) {
  const double s = std::max(b.cwiseAbs().maxCoeff(), scale);
  const double diff = (a - b).cwiseAbs().maxCoeff();
  if (diff <= rel * s && a.allFinite()) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "\n"
         << a << "\nvs expected\n"
         << b << "\n(max difference " << diff << ", tolerance " << rel * s << ")";
}

}  // namespace chasles::test
