// The certificate's transition checks per island (src/analysis/internal/island_checks.h).
//
// Why per island is the same certificate: an island shares no force element, constraint or
// contact with another (islands.cpp), so its bodies' Newton-Euler balances, its contact points'
// complementarity and gaps and its constraints' residuals read its own states only, and
// CheckState on the island's Model at a transition checks exactly the rows the whole model's
// CheckState would check there for those bodies. The work-energy ledger is a sum over bodies and
// elements: T and V of the whole model are the islands' sums (gravity, acting on each body alone,
// is in every island, with its potential of that island's bodies), and the non-conservative work
// of an element, constraint or contact point is its island's; so the whole residual
// E - E0 - W_nc is the sum of the islands' residuals, and each island's is checked against its
// own energy scale, which is at most the whole model's.

#include "internal/island_checks.h"

#include <algorithm>
#include <string>

#include <fmt/format.h>

#include "chasles/analysis/ledger.h"

namespace chasles::study_internal {
namespace {

// "island of body 'ball 3'", "island of bodies 'a', 'b' and 4 more": the bodies whose ledger it
// is, by their names in the whole model (an island's Model keeps them).
std::string IslandName(const Model& model) {
  constexpr int kNamed = 2;
  const int n = model.num_bodies();
  std::string names = fmt::format("'{}'", model.body(0).name());
  for (int b = 1; b < std::min(n, kNamed); ++b)
    names += fmt::format(", '{}'", model.body(b).name());
  if (n > kNamed) names += fmt::format(" and {} more", n - kNamed);
  return fmt::format("island of bod{} {}", n == 1 ? "y" : "ies", names);
}

}  // namespace

std::function<TransitionCheck(const IslandView&)> IslandChecks::Hook() {
  return [this](const IslandView& view) -> TransitionCheck {
    auto island = std::make_shared<Island>(Island{view.island, CertificateBuilder(tolerances_)});
    // The island's checks start from its initial state, as the run's from the run's: the scales
    // they are judged by (a slip speed below the velocity scale's round-off has no direction)
    // are the island's own from its start on.
    island->builder.CheckState(*view.model, *view.initial, CheckPhase::kSample);
    {
      // An island run again (to the instant another island yielded: integrator auto) replaces
      // its first run, whose checks went past the state the run goes on from.
      const std::lock_guard<std::mutex> lock(mutex_);
      std::erase_if(islands_, [&](const auto& x) { return x->index == view.island; });
      islands_.push_back(island);
    }
    // Copies: the view lives only for this call; the Model outlives the island's run.
    const Model* model = view.model;
    return [island, model, initial = *view.initial, where = IslandName(*view.model)](
               const State& before, const State& after) {
      const auto check = [&](const State& s, CheckPhase phase) {
        island->builder.CheckState(*model, s, phase);
        const LedgerSample L = CalcLedgerSample(*model, s, initial);
        island->builder.CheckLedger(s.t, L.energy_residual, L.energy_scale, phase, where);
      };
      check(before, CheckPhase::kBeforeTransition);
      check(after, CheckPhase::kAfterTransition);
    };
  };
}

void IslandChecks::AddTo(CertificateBuilder& into) {
  std::stable_sort(islands_.begin(), islands_.end(),
                   [](const auto& a, const auto& b) { return a->index < b->index; });
  for (const std::shared_ptr<Island>& island : islands_) into.AddPart(island->builder.Finish());
  islands_.clear();
}

}  // namespace chasles::study_internal
