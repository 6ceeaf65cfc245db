#pragma once
/// @file
/// The output columns of a simulation (key `output.columns`): per-body kinematic columns
/// "<body>_<quantity>" and ledger columns, and the groups that name several at once. Private
/// to the scene layer.

#include <string>
#include <vector>

#include "chasles/analysis/study.h"
#include "chasles/scene/scene.h"

namespace chasles::scene_internal {

/// A column: name, group, body, quantity, force, contact point (see StudyColumn).
using ColumnInfo = StudyColumn;

/// Every column the scene offers, in a stable order.
std::vector<ColumnInfo> AllColumns(const Scene& scene);
/// Column names for a group or a single column name; empty with `why` set when unknown.
std::vector<std::string> ExpandColumn(const Scene& scene, const std::string& name,
                                      std::string* why);
/// The columns written when the scene has no `output`.
std::vector<std::string> DefaultColumns(const Scene& scene);
/// Names of the groups, for help and messages.
std::vector<std::string> ColumnGroups();

}  // namespace chasles::scene_internal
