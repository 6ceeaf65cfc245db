#pragma once
/// @file
/// The instantaneous problem of a Model at a state, as `chasles solve` reports it (chapter
/// 8.2-8.3): every body's acceleration, every constraint's reaction, the friction rolling needs
/// against mu_s, each contact point's mode and forces, the kinetic energy and momenta, and the
/// solve's checks of its own answer. A SolveDefinition says what to solve and how to name it;
/// the scene layer makes one from a scene (MakeSolveDefinition), a program in code.

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "chasles/analysis/error_locator.h"
#include "chasles/analysis/initial_state.h"
#include "chasles/analysis/solve_report.h"
#include "chasles/analysis/sweep.h"
#include "chasles/math/types.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {

/// A named point fixed in a body (its velocity and acceleration are reported).
struct NamedBodyPoint {
  std::string name;
  /// From the body origin, in B [m].
  Vec3 p_BoP_B = Vec3::Zero();
};

struct SolveDefinition {
  std::shared_ptr<const Model> model;
  /// The state to solve at (on the constraints up to round-off: the solve projects it).
  State initial;
  /// Settle `initial` onto the constraints first (SettleInitialState: an error, or the nearest
  /// consistent state with each change a warning after `warnings`); none: as it is.
  std::optional<InitialSettling> settle_initial;
  /// A planar problem: reports in x, y and about z.
  bool planar = false;
  /// Warnings to list first (e.g. the scene's, then initial values changed by a projection).
  std::vector<std::string> warnings;
  /// Named points of each body (Model order; shorter: the rest have none).
  std::vector<std::vector<NamedBodyPoint>> points;
  /// mu_s of each reported constraint (NaN when it has none); its size is the number of the
  /// Model's constraints (the first ones) reported.
  std::vector<double> mu_s;
  /// Contact point labels in Model order (empty: Model::contact_point_name).
  std::vector<std::string> contact_point_labels;
  /// Places the solve's errors at their source (the scene layer's file:line:col); null: they
  /// are thrown as they are.
  ErrorLocator locate_error;
};

/// Solves the instantaneous problem at the definition's state, projected onto the constraints,
/// in the contact modes chosen as a simulation starts (impacts not applied). Throws InputError
/// for a state or Model it cannot solve, through the definition's `locate_error` when it has
/// one.
SolveReport SolveAtState(const SolveDefinition& definition);

/// One value of a solve sweep: the parameter's SI value and the definition to solve there.
struct SolveSweepPoint {
  double value = 0.0;
  SolveDefinition definition;
};

struct SolveSweepOptions {
  /// Called before value k of count is solved (e.g. for a progress display).
  std::function<void(int k, int count)> progress;
  /// Called after each value is solved, with its index, the parameter's SI value and the
  /// solution.
  std::function<void(int k, double value, const SolveReport& solution)> on_solution;
  /// The values solved here; the rows of the others are left empty (no values) and no
  /// warnings are made for them. Row 0, with the columns' names, is always rank 0's.
  SweepShare share;
};

/// Solves `count` values of one parameter (`name`, SI unit `unit`: "" for a number), value k
/// at `point(k)`'s definition, in order, into a table: the parameter's value then the solution
/// (SolutionTableRow) per row, each failed check of a solve a warning naming the value (and
/// the table failed). The errors are the points' (a point's definition locates its own).
SweepTable SolveSweep(const std::string& name, const std::string& unit, int count,
                      const std::function<SolveSweepPoint(int k)>& point,
                      const SolveSweepOptions& options = {});

}  // namespace chasles
