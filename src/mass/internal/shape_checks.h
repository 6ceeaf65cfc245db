#pragma once
/// @file
/// Dimension checks shared by the shape factories: each throws InputError naming the shape,
/// the dimension, its value and the rule.

#include <cmath>
#include <string_view>

#include <fmt/format.h>

#include "chasles/error.h"

namespace chasles::internal {

/// `kind`: "<label> <value> m must be positive and finite" unless 0 < value < inf.
inline void RequirePositiveLength(std::string_view kind, std::string_view label, double value) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw InputError(
        fmt::format("{}: {} {:.6g} m must be positive and finite", kind, label, value));
  }
}

/// `kind`: "<small_label> <small> m must be smaller than <big_label> <big> m" unless small < big.
inline void RequireSmaller(std::string_view kind, std::string_view small_label, double small,
                           std::string_view big_label, double big) {
  if (!(small < big)) {
    throw InputError(fmt::format("{}: {} {:.6g} m must be smaller than {} {:.6g} m", kind,
                                 small_label, small, big_label, big));
  }
}

}  // namespace chasles::internal
