#include "chasles/integrate/ball_pairs.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include <fmt/format.h>

#include "chasles/error.h"

namespace chasles {

std::vector<double> BallRadii(const Model& model) {
  std::vector<double> radius(static_cast<size_t>(model.num_bodies()), 0.0);
  const auto take = [&](BodyIndex b, const Vec3& p_BoC_B, double r, int contact) {
    const Body& body = model.body(b);
    if ((p_BoC_B - body.p_BoBcm_B()).norm() > 1e-12 * r) return;  // not centred: not the ball
    double& R = radius[static_cast<size_t>(b)];
    if (R > 0.0 && std::abs(R - r) > 1e-12 * r) {
      throw InputError(
          fmt::format("body '{}' has sphere contacts of radius {} m and {} m centred at its "
                      "centre of mass: which is the ball that collides with the others is not "
                      "clear (give it one radius)",
                      body.name(), R, r),
          ErrorElement{ErrorElement::Kind::kContact, contact});
    }
    R = r;
  };
  for (int c = 0; c < model.num_contacts(); ++c) {
    const ContactSpec& s = model.contact(c).spec();
    if (s.shape == ContactShape::kSphere) take(s.body, s.p_BoC_B, s.radius, c);
    if (s.shape == ContactShape::kSphereSphere) {
      take(s.body, s.p_BoC_B, s.radius, c);
      take(s.other_body, s.p_OoC_O, s.other_radius, c);
    }
  }
  return radius;
}

namespace {

using Cell = std::array<std::int64_t, 3>;

// The cell of a coordinate, clamped far inside the integer range (centres that far apart share
// a cell: more distance tests, never a missed pair).
std::int64_t CellOf(double x, double cell) {
  constexpr double kMax = 4.0e18;
  return static_cast<std::int64_t>(std::clamp(std::floor(x / cell), -kMax, kMax));
}

}  // namespace

std::vector<std::pair<int, int>> FindSpherePairs(const std::vector<Vec3>& centres,
                                                 const std::vector<double>& radii, double reach) {
  double r_max = 0.0;
  for (double r : radii) r_max = std::max(r_max, r);
  std::vector<std::pair<int, int>> pairs;
  if (!(r_max > 0.0)) return pairs;
  // Two spheres that touch within reach are at most 2 r_max + reach apart: in neighbouring cells.
  const double cell = 2.0 * r_max + reach;
  std::vector<std::pair<Cell, int>> sorted;
  sorted.reserve(centres.size());
  for (size_t i = 0; i < centres.size(); ++i) {
    if (!(radii[i] > 0.0)) continue;
    const Vec3& c = centres[i];
    sorted.push_back(
        {{CellOf(c.x(), cell), CellOf(c.y(), cell), CellOf(c.z(), cell)}, static_cast<int>(i)});
  }
  std::sort(sorted.begin(), sorted.end());
  const auto test = [&](int i, int j) {
    const double d = radii[static_cast<size_t>(i)] + radii[static_cast<size_t>(j)] + reach;
    if ((centres[static_cast<size_t>(i)] - centres[static_cast<size_t>(j)]).squaredNorm() <=
        d * d) {
      pairs.push_back({std::min(i, j), std::max(i, j)});
    }
  };
  // Each cell against itself and the 13 neighbours that come after it (the other 13 see it).
  for (size_t lo = 0, hi; lo < sorted.size(); lo = hi) {
    const Cell& k = sorted[lo].first;
    for (hi = lo; hi < sorted.size() && sorted[hi].first == k; ++hi) {
    }
    for (size_t a = lo; a < hi; ++a) {
      for (size_t b = a + 1; b < hi; ++b) test(sorted[a].second, sorted[b].second);
    }
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dz = -1; dz <= 1; ++dz) {
          const Cell o{k[0] + dx, k[1] + dy, k[2] + dz};
          if (!(k < o)) continue;  // itself, or a cell that comes before (it tests this one)
          auto it = std::lower_bound(sorted.begin() + static_cast<std::ptrdiff_t>(hi), sorted.end(),
                                     std::make_pair(o, -1));
          for (; it != sorted.end() && it->first == o; ++it) {
            for (size_t a = lo; a < hi; ++a) test(sorted[a].second, it->second);
          }
        }
      }
    }
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace chasles
