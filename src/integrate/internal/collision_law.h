#pragma once
/// @file
/// The check of the law for collisions between balls that the model does not list
/// (`collide_all_pairs`), shared by the event-driven spheres and time stepping. Private to the
/// integrate layer.

#include "chasles/integrate/sphere_events.h"

namespace chasles::internal {

/// Checks `law`'s coefficients as a sphere-sphere contact's between balls of `radius` [m] in
/// `model` would be checked (ValidateContactSpec, which names the rule broken): InputError.
void ValidateSphereCollisionLaw(const SphereCollisionLaw& law, const Model& model, double radius);

}  // namespace chasles::internal
