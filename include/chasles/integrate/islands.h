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

#include "chasles/dynamics/contact_solve.h"
#include "chasles/error.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

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

/// One island as a Model of its own: its bodies renumbered 0, 1, … in Model order, the force
/// elements acting on them (an element acting on each body alone, gravity, is in every island),
/// its constraints and its contacts, each in Model order, with the whole Model's index of each.
struct IslandModel {
  Model model;
  /// Whole-Model index of each local body, force element, constraint, contact, contact point.
  std::vector<BodyIndex> bodies;
  std::vector<int> forces, constraints, contacts, points;
};

/// The islands of a Model as Models of their own, and States moved between the two numberings.
/// Needs IslandObstacle(model) empty. Making it costs O(bodies + elements); each Build(i) and
/// Part(i) costs the island's size.
class IslandSplit {
 public:
  IslandSplit(const Model& model, IslandPartition partition);
  int num_islands() const { return static_cast<int>(partition_.bodies.size()); }
  const IslandPartition& partition() const { return partition_; }
  /// The contact points of island i (whole-Model indices, in order).
  const std::vector<int>& points(int i) const { return contents_[Index(i)].points; }
  IslandModel Build(int i) const;
  /// Island i's part of `whole` (a State of the whole Model). An element acting on every body
  /// alone (gravity) carries its integrals in island 0 and starts from zero in the others, so
  /// that the islands' integrals add up to the whole's.
  State Part(const IslandModel& island, int i, const State& whole) const;
  /// Writes the island's bodies and contact points of `part` into `whole` (forces' integrals,
  /// constraint work and modes are left as they are).
  static void ScatterMotion(const IslandModel& island, const State& part, State& whole);
  /// Rethrows `e`, thrown by a computation on `island`, naming its element by its index in the
  /// whole Model.
  [[noreturn]] static void RethrowForWholeModel(const IslandModel& island, const InputError& e);

 private:
  // What island i holds, by whole-Model index.
  struct Contents {
    std::vector<int> forces, constraints, contacts, points;
  };
  size_t Index(int i) const { return static_cast<size_t>(i); }
  size_t IslandOf(BodyIndex b) const {
    return static_cast<size_t>(partition_.island_of_body[static_cast<size_t>(b)]);
  }

  const Model& model_;
  IslandPartition partition_;
  /// Each body's index inside its island: the renumbering every island's elements use.
  std::vector<BodyIndex> local_;
  std::vector<Contents> contents_;
};

/// What SettleContactsByIsland did, contact points numbered in the whole Model.
struct ContactSettling {
  /// The impacts: one result per island with an impact, in island order (each result's kinetic
  /// energies and frictionless fallback are its island's); one result when solved whole.
  std::vector<ImpactResult> impacts;
  /// The mode changes and the jams, by point.
  std::vector<ContactModeChange> changes;
  std::vector<JamImpulse> jams;
  /// Islands solved apart; 0 when solved as one problem (one island, or an island obstacle).
  int islands = 0;
};

/// ResolveImpacts, then SelectContactModes, at `state`, on each island with contact points as
/// its own problem: the cost grows with the islands' sizes, not with the whole Model's
/// (docs/contact.md, "Islands"). A model that forms one island, or cannot be split
/// (IslandObstacle), is solved whole. Updates `state` as the two calls do.
ContactSettling SettleContactsByIsland(const Model& model, State& state,
                                       const ContactTolerances& tol = {});

}  // namespace chasles
