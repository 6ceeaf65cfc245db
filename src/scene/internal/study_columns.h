#pragma once
/// @file
/// The output columns of a simulation (key `output.columns`): per-body kinematic columns
/// "<body>_<quantity>" and ledger columns, and the groups that name several at once. Private
/// to the scene layer.

#include <string>
#include <vector>

#include "chasles/scene/scene.h"

namespace chasles::scene_internal {

struct ColumnInfo {
  /// Column name in the CSV header.
  std::string name;
  /// Group it belongs to ("position", "energy", ...).
  std::string group;
  /// Scene body index for per-body columns; -1 for t and ledger columns.
  int body = -1;
  /// What it is: a body quantity suffix ("x", "qw", "ax", ...), or the ledger name ("T_trans",
  /// "W_nc", ...), or "W" with `force` set for a force element's work.
  std::string quantity;
  /// Force element name for per-force work columns.
  std::string force;
  /// Contact point index (Model order) for the "contacts" group's columns; -1 otherwise.
  int point = -1;
};

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
