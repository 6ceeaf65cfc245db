// SettleContactsByIsland: impacts and contact modes at one instant, island by island
// (include/chasles/integrate/islands.h).
//
// Why on the islands' Models and not by splitting the dense problems inside the dynamics layer:
// ResolveImpacts and SelectContactModes each build one problem over the whole Model (contact
// rows over every body's 6 columns, one impulse parameter common to all points, one
// complementarity problem per pass, the contact stage of the whole Model to check each pass,
// and tolerances scaled by the largest acceleration and mass of all bodies), so a block split
// there would need Models of the blocks anyway. The islands' Models exist already (IslandSplit),
// and each island's hybrid run selects its own modes on its own Model (RunIslands), so settling
// an island on its Model gives the modes that island's run starts from.
//
// What the split changes against the one problem over the whole Model. Delassus matrix K,
// complementarity matrices and constraint rows are block-diagonal over the islands (no row
// holds bodies of two islands: that is what an island is), so the impulses, velocities and
// modes are the same; the numbers differ at most by round-off and the round-off bands, scaled
// per island here as in the islands' runs. The bookkeeping is per island: an impact record's
// energy is its island's, the frictionless fallback is decided per island, ΔT of an impact is
// shared among its island's points and the projection's among its island's (the totals are the
// same); an island with no approaching point takes no impulse from an impact elsewhere (there
// a resting point's round-off approach is the projection's to remove), and an island without
// contact points is left alone (the whole Model's projection would only tidy its constraints'
// round-off velocities).

#include <algorithm>
#include <utility>

#include "chasles/integrate/islands.h"

namespace chasles {
namespace {

// Sorts records named by a contact point of the whole Model into point order (stable: within a
// point, the order they came in).
template <class Record>
void SortByPoint(std::vector<Record>& records) {
  std::stable_sort(records.begin(), records.end(),
                   [](const Record& a, const Record& b) { return a.point < b.point; });
}

}  // namespace

ContactSettling SettleContactsByIsland(const Model& model, State& state,
                                       const ContactTolerances& tol) {
  ContactSettling out;
  const auto np = static_cast<size_t>(model.num_contact_points());
  if (state.contacts.size() != np) state.contacts.assign(np, ContactPointState{});
  IslandPartition partition = FindIslands(model);
  if (partition.bodies.size() <= 1 || !IslandObstacle(model).empty()) {
    ImpactResult impacts = ResolveImpacts(model, state, tol);
    if (!impacts.impulses.empty()) out.impacts.push_back(std::move(impacts));
    ModeSelectionNotes notes;
    out.changes = SelectContactModes(model, state, tol, {}, &notes);
    out.jams = std::move(notes.jams);
    return out;
  }
  const IslandSplit split(model, std::move(partition));
  out.islands = split.num_islands();
  for (int i = 0; i < split.num_islands(); ++i) {
    if (split.points(i).empty()) continue;
    const IslandModel im = split.Build(i);
    State part = split.Part(im, i, state);
    try {
      ImpactResult impacts = ResolveImpacts(im.model, part, tol);
      ModeSelectionNotes notes;
      std::vector<ContactModeChange> changes = SelectContactModes(im.model, part, tol, {}, &notes);
      const auto global = [&](int local) { return im.points[static_cast<size_t>(local)]; };
      if (!impacts.impulses.empty()) {
        for (ContactImpulse& c : impacts.impulses) c.point = global(c.point);
        out.impacts.push_back(std::move(impacts));
      }
      for (ContactModeChange& c : changes) {
        c.point = global(c.point);
        out.changes.push_back(c);
      }
      for (JamImpulse& j : notes.jams) {
        j.point = global(j.point);
        out.jams.push_back(j);
      }
    } catch (const InputError& e) {
      IslandSplit::RethrowForWholeModel(im, e);
    }
    IslandSplit::ScatterMotion(im, part, state);
  }
  // The islands' points interleave in the whole Model's numbering: its point order, as one
  // problem lists them.
  SortByPoint(out.changes);
  SortByPoint(out.jams);
  return out;
}

}  // namespace chasles
