// When two balls meet: the first root of their contact polynomial over each stretch where
// both follow one segment (docs/contact.md, "Event-driven spheres").
#include "integrate/internal/sphere_runner.h"

namespace chasles::sphere_events_detail {

// ---- Roots of the contact polynomial -------------------------------------------------------

double Eval(const Poly& c, int deg, double x) {
  double y = c[static_cast<size_t>(deg)];
  for (int k = deg - 1; k >= 0; --k) y = y * x + c[static_cast<size_t>(k)];
  return y;
}

// Sorted real roots of p in (lo, hi): between consecutive roots of p' (recursively) p is
// monotone, and each sign change is bisected to adjacent doubles.
void RootsIn(const Poly& c, int deg, double lo, double hi, std::vector<double>& out) {
  out.clear();
  while (deg > 0 && c[static_cast<size_t>(deg)] == 0.0) --deg;
  if (deg == 0) return;
  std::vector<double> knots{lo};
  if (deg > 1) {
    Poly d{};
    for (int k = 1; k <= deg; ++k) d[static_cast<size_t>(k - 1)] = k * c[static_cast<size_t>(k)];
    std::vector<double> crit;
    RootsIn(d, deg - 1, lo, hi, crit);
    knots.insert(knots.end(), crit.begin(), crit.end());
  }
  knots.push_back(hi);
  for (size_t k = 0; k + 1 < knots.size(); ++k) {
    double a = knots[k], b = knots[k + 1];
    double fa = Eval(c, deg, a), fb = Eval(c, deg, b);
    if (fa == 0.0) {
      if (k > 0 || a > lo) out.push_back(a);
      continue;
    }
    if ((fa > 0.0) == (fb > 0.0) || fb == 0.0) continue;
    for (int it = 0; it < 200; ++it) {
      const double m = 0.5 * (a + b);
      if (m <= a || m >= b) break;
      const double fm = Eval(c, deg, m);
      if ((fm > 0.0) == (fa > 0.0) && fm != 0.0) {
        a = m;
      } else {
        b = m;
      }
    }
    out.push_back(b);
  }
}

// The first σ in [lo, hi] at which f = |d|² - S² enters f <= 0 (the balls touch, approaching):
// f(lo) <= 0 with f falling at lo, or a crossing from f > 0. Infinity if none.
double FirstEntry(const Poly& f, double lo, double hi) {
  Poly d{};
  for (int k = 1; k <= 4; ++k) d[static_cast<size_t>(k - 1)] = k * f[static_cast<size_t>(k)];
  std::vector<double> crit;
  RootsIn(d, 3, lo, hi, crit);
  double a = lo;
  double fa = Eval(f, 4, a);
  crit.push_back(hi);
  for (const double b : crit) {
    const double fb = Eval(f, 4, b);
    const bool falling = fb < fa || (fb == fa && Eval(d, 3, 0.5 * (a + b)) < 0.0);
    if (falling && fa <= 0.0 && b > a) return a;
    if (fa > 0.0 && fb <= 0.0) {
      double x = a, y = b;
      for (int it = 0; it < 200; ++it) {
        const double m = 0.5 * (x + y);
        if (m <= x || m >= y) break;
        if (Eval(f, 4, m) > 0.0) {
          x = m;
        } else {
          y = m;
        }
      }
      return y;
    }
    a = b;
    fa = fb;
  }
  return kInf;
}

// The first time in [t, min(horizons)] at which balls i and j touch, approaching: over each
// stretch where both follow one segment, |r_i - r_j|² - (R_i + R_j)² is a quartic in time.
void Runner::TestPair(int i, int j, double t) {
  if (!MayCollide(i, j)) return;
  ++res_.stats.pair_tests;
  const auto iu = static_cast<size_t>(i), ju = static_cast<size_t>(j);
  const Chain &ci = chain_[iu], &cj = chain_[ju];
  const double t_to =
      std::min({horizon_[iu], horizon_[ju], ci.known_until, cj.known_until, options_.t_end});
  if (!(t_to >= t)) return;
  std::array<double, 8> knots{};
  int nk = 0;
  knots[static_cast<size_t>(nk++)] = t;
  for (const Chain* c : {&ci, &cj}) {
    for (int k = 0; k + 1 < c->count; ++k) {
      const double e = c->seg[static_cast<size_t>(k)].end();
      if (e > t && e < t_to) knots[static_cast<size_t>(nk++)] = e;
    }
  }
  for (int a = 2; a < nk; ++a) {  // insertion sort of the (at most four) segment ends
    for (int b = a; b > 1 && knots[static_cast<size_t>(b)] < knots[static_cast<size_t>(b - 1)];
         --b) {
      std::swap(knots[static_cast<size_t>(b)], knots[static_cast<size_t>(b - 1)]);
    }
  }
  knots[static_cast<size_t>(nk++)] = t_to;
  const double S = balls_[iu].R + balls_[ju].R;
  for (int k = 0; k + 1 < nk; ++k) {
    const double s0 = knots[static_cast<size_t>(k)], s1 = knots[static_cast<size_t>(k + 1)];
    if (s1 < s0) continue;
    const Segment &a = ci.At(s0), &b = cj.At(s0);
    const Vec3 d0 = a.Pos(s0) - b.Pos(s0);
    const Vec3 d1 = a.Vel(s0) - b.Vel(s0);
    const Vec3 d2 = 0.5 * (a.a - b.a);
    const Poly f{(d0.norm() - S) * (d0.norm() + S), 2.0 * d0.dot(d1),
                 d1.squaredNorm() + 2.0 * d0.dot(d2), 2.0 * d1.dot(d2), d2.squaredNorm()};
    const double sigma = FirstEntry(f, 0.0, s1 - s0);
    if (std::isfinite(sigma)) {
      Schedule({s0 + sigma, Kind::kPair, i, j, ver_[iu], ver_[ju], 0});
      return;
    }
  }
}

}  // namespace chasles::sphere_events_detail
