#pragma once
/// @file
/// Islands of a Model: the groups of bodies that act on one another. Two bodies are in one
/// island when a constraint holds both (a joint, a string with its ends and the bodies carrying
/// its pulleys), a contact is between them (sphere-sphere), or a force element acts between
/// them (a spring-damper). Contacts with the world plane and elements acting on each body
/// alone (gravity) do not link. Simulate runs each island of a model with contacts as its own
/// hybrid system (docs/contact.md, "Islands").

#include <string>
#include <vector>

#include "chasles/model/model.h"

namespace chasles {

struct IslandPartition {
  /// Each island's bodies in Model order; islands ordered by their smallest body index.
  std::vector<std::vector<BodyIndex>> bodies;
  /// Island of each body.
  std::vector<int> island_of_body;
};

/// The islands of `model` by the links that can ever act (the static partition: a sphere-sphere
/// contact links its bodies even while they are apart). O(bodies + elements).
IslandPartition FindIslands(const Model& model);

/// Why `model` cannot run as separate islands: names the first force element or constraint
/// that cannot be renumbered onto an island (ForceElement::Renumbered, Constraint::Renumbered);
/// empty when it can.
std::string IslandObstacle(const Model& model);

}  // namespace chasles
