#pragma once
/// @file
/// Forward-mode dual numbers a + b ε (ε² = 0) for the exact first derivatives of the
/// linearisation (analysis/linearize.h) and of the velocity-product terms of rows written once over
/// the scalar type (model/surface_rolling.h): a function f evaluated at x + ε d returns f(x) + ε
/// f'(x) d, to round-off and with no step size. One direction per evaluation; Eigen matrices of
/// Dual work through the NumTraits below (no mixing with double inside expressions: constants are
/// cast with .cast<Dual>()).

#include <cmath>

#include <Eigen/Core>

namespace chasles {

struct Dual {
  double v = 0.0;  ///< value
  double d = 0.0;  ///< derivative along the chosen direction
  Dual() = default;
  Dual(double value) : v(value) {}  // NOLINT: constants convert implicitly, as in Eigen
  Dual(double value, double derivative) : v(value), d(derivative) {}
  Dual& operator+=(const Dual& o) {
    v += o.v, d += o.d;
    return *this;
  }
  Dual& operator-=(const Dual& o) {
    v -= o.v, d -= o.d;
    return *this;
  }
  Dual& operator*=(const Dual& o) {
    d = d * o.v + v * o.d, v *= o.v;
    return *this;
  }
  Dual& operator/=(const Dual& o) {
    d = (d * o.v - v * o.d) / (o.v * o.v), v /= o.v;
    return *this;
  }
};

inline Dual operator+(Dual a, const Dual& b) {
  return a += b;
}
inline Dual operator-(Dual a, const Dual& b) {
  return a -= b;
}
inline Dual operator*(Dual a, const Dual& b) {
  return a *= b;
}
inline Dual operator/(Dual a, const Dual& b) {
  return a /= b;
}
inline Dual operator-(const Dual& a) {
  return {-a.v, -a.d};
}
inline Dual operator+(const Dual& a) {
  return a;
}
inline bool operator<(const Dual& a, const Dual& b) {
  return a.v < b.v;
}
inline bool operator>(const Dual& a, const Dual& b) {
  return a.v > b.v;
}
inline bool operator<=(const Dual& a, const Dual& b) {
  return a.v <= b.v;
}
inline bool operator>=(const Dual& a, const Dual& b) {
  return a.v >= b.v;
}
inline bool operator==(const Dual& a, const Dual& b) {
  return a.v == b.v && a.d == b.d;
}
inline bool operator!=(const Dual& a, const Dual& b) {
  return !(a == b);
}
inline Dual sqrt(const Dual& a) {
  const double s = std::sqrt(a.v);
  return {s, a.d / (2.0 * s)};
}
inline Dual abs(const Dual& a) {
  return a.v < 0.0 ? -a : a;
}
inline Dual conj(const Dual& a) {
  return a;
}
inline Dual real(const Dual& a) {
  return a;
}
inline Dual imag(const Dual&) {
  return 0.0;
}
inline Dual abs2(const Dual& a) {
  return a * a;
}

/// The value of a double or a Dual.
inline double Value(double x) {
  return x;
}
inline double Value(const Dual& x) {
  return x.v;
}

}  // namespace chasles

namespace Eigen {
template <>
struct NumTraits<chasles::Dual> : NumTraits<double> {
  using Real = chasles::Dual;
  using NonInteger = chasles::Dual;
  using Nested = chasles::Dual;
  using Literal = chasles::Dual;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 1,
    ReadCost = 2,
    AddCost = 2,
    MulCost = 4
  };
};
}  // namespace Eigen
