#pragma once
/// @file
/// SelectContactModes with the linear solver of its plan solves chosen (the public function
/// uses LinearSolver::kAuto). The plan solves are the LCP on the normal forces of the candidate
/// points with the bilateral rows (constraints, sticking tangents, held rolling) eliminated,
/// and the velocity projection onto the chosen rows. kDense: the dense Schur complement and
/// Lemke's method for every size; kSparse: the rows by body blocks through the sparse
/// factorisation (sparse_solve.h) and a principal pivoting on the set of pressing points, the
/// dense path answering where the sparse one cannot (docs/design.md, "Sparse mode selection");
/// kAuto: sparse from kSparseMinRows plan rows on. The evaluations of the chosen modes (the
/// contact stage) keep Data's default (kAuto) either way.

#include <vector>

#include "chasles/dynamics/contact_solve.h"
#include "chasles/model/data.h"

namespace chasles::internal {

std::vector<ContactModeChange> SelectContactModes(const Model& model, State& state,
                                                  const ContactTolerances& tol,
                                                  const ModeHints& hints, ModeSelectionNotes* notes,
                                                  LinearSolver solver);

/// What the plan solves of the last SelectContactModes on this thread did: the number of
/// plan solves that took the sparse path, the number that fell back to the dense one, and the
/// pivots (changes of the pressing set) of the sparse LCP, and whether either Data of the
/// selection (its working Data and the one its evaluations use) ended with its dense Data::J
/// sized (made so by MakeData below kSparseMinRows rows, else by a dense solve that needed it).
/// For tests and benchmarks.
struct ModeSelectionStats {
  int sparse_solves = 0;
  int dense_solves = 0;
  int sparse_pivots = 0;
  bool dense_jacobian = false;
};
const ModeSelectionStats& LastModeSelectionStats();

}  // namespace chasles::internal
