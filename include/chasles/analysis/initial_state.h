#pragma once
/// @file
/// An initial state as given against the Model's constraints (docs/scene-format.md, "Initial
/// state and constraints"): within round-off it is corrected without a word; beyond, it is an
/// error listing each violated constraint and what to give, unless the caller asks for the
/// nearest consistent state (`project_initial: true`), each changed value a warning. RunStudy,
/// SolveAtState and AnalyseOperatingPointModes settle their definition's state with this first.

#include <string>
#include <vector>

#include "chasles/math/types.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {

/// How an initial state is settled and how its values are named (as the user gave them).
struct InitialSettling {
  /// Start from the nearest consistent state (mass-weighted), each change a warning; false: a
  /// violation beyond round-off is an error.
  bool project = false;
  /// A planar problem: positions and velocities as [x, y], the orientation as θ about z.
  bool planar = false;
  /// Each body's initial angle θ about z as given [rad] (planar only).
  std::vector<double> theta;
  /// Each body's point whose initial velocity was given, from its origin in B [m] (empty, or
  /// shorter: the origin).
  std::vector<Vec3> p_BoP_B;
};

/// `given` (one Model body per body the caller named, the Model's names) on the constraints,
/// string modes chosen first (a string longer than its path starts slack). Residuals within
/// kRoundOffResidual of the state's scales are corrected without a word; larger ones are an
/// InputError at the initial state of the first violated constraint's body
/// (ErrorElement::Kind::kInitialState) listing each violated constraint (residual with units,
/// body, what to give) and the nearest consistent values, unless `settling.project`: then the
/// projected state is returned and every changed value (body, quantity, given -> used, with
/// units) is appended to `warnings`. Throws InputError when the positions cannot be assembled.
State SettleInitialState(const Model& model, const State& given, const InitialSettling& settling,
                         std::vector<std::string>& warnings);

}  // namespace chasles
