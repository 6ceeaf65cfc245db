#pragma once
/// @file
/// The certificate's checks at contact transitions, island by island (docs/contact.md,
/// "Islands"): a run split into islands checks each island's states, with its own Model, at its
/// own transitions, into a CertificateBuilder of its own; the islands' certificates join the
/// run's in island order after the run.

#include <memory>
#include <mutex>
#include <vector>

#include "chasles/analysis/certificate.h"
#include "chasles/integrate/simulate.h"

namespace chasles::study_internal {

class IslandChecks {
 public:
  explicit IslandChecks(const CertificateTolerances& tolerances) : tolerances_(tolerances) {}
  /// The island form of the transition hook (SimulationOptions::island_transition): each
  /// island's builder checks the island's initial state (its scales from its start on), then at
  /// each transition the states before and after (CheckState, and the island's ledger since its
  /// initial state). Safe to call from several threads at once.
  std::function<TransitionCheck(const IslandView&)> Hook();
  /// Adds every island's certificate to `into` in island order (the same for any number of
  /// threads), and forgets them.
  void AddTo(CertificateBuilder& into);

 private:
  struct Island {
    int index;
    CertificateBuilder builder;
  };
  CertificateTolerances tolerances_;
  std::mutex mutex_;
  std::vector<std::shared_ptr<Island>> islands_;
};

}  // namespace chasles::study_internal
