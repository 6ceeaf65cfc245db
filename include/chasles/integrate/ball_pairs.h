#pragma once
/// @file
/// Balls that may all collide with one another (`ball_collisions`; docs/contact.md, "Every pair
/// of balls"): which bodies are balls, and a broadphase that finds the pairs near each other in
/// O(n + pairs near) instead of testing all n (n - 1) / 2.

#include <utility>
#include <vector>

#include "chasles/math/types.h"
#include "chasles/model/model.h"

namespace chasles {

/// Per body, the radius of its ball, or 0 when it is not one. A ball is a body with a sphere
/// contact centred at its centre of mass (on a plane, or either side of a sphere-sphere
/// contact), the ball's radius that sphere's; the event-driven path's balls (sphere_events.h)
/// are such bodies. Throws InputError for a body with two such spheres of different radii (which
/// one is the ball is not clear).
std::vector<double> BallRadii(const Model& model);

/// The pairs (i, j), i < j, of spheres with |c_i - c_j| <= r_i + r_j + reach, in increasing
/// order of (i, j). A uniform grid of cell 2 max r + reach over the centres (cells sorted, not
/// allocated over the extent, so far-flung spheres cost nothing): each sphere is tested against
/// those of its own cell and the 26 neighbours, O(n log n + pairs near) in all. Spheres of
/// radius 0 (not balls) take no part. reach >= 0; the centres must be finite.
std::vector<std::pair<int, int>> FindSpherePairs(const std::vector<Vec3>& centres,
                                                 const std::vector<double>& radii, double reach);

}  // namespace chasles
