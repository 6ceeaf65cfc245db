#pragma once
/// @file
/// The output columns of a simulation (key `output.columns`): per-body kinematic columns
/// "<body>_<quantity>" and ledger columns, and the groups that name several at once. Private
/// to the scene layer.

#include <cstddef>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "chasles/analysis/study.h"
#include "chasles/scene/scene.h"

namespace chasles::scene_internal {

/// A column: name, group, body, quantity, force, contact point (see StudyColumn).
using ColumnInfo = StudyColumn;

/// The columns a scene offers, in a stable order: t; a planar scene's per-body columns; the
/// per-body groups, each body by body; the named points' groups; then the ledger, each force's
/// and constraint's work, the momenta, the reactions and the contact points' columns. A scene
/// of 100 000 bodies offers some 6 million, so they are never all listed: a body's column is
/// found from its body's name and its suffix, a group expanded on its own, the scene's other
/// columns kept in a table. Built once per use (in time linear in the scene's size), then each
/// lookup costs the length of the name. The scene must outlive the index.
class ColumnIndex {
 public:
  explicit ColumnIndex(const Scene& scene);
  /// The column called `name` (the first in the order above when several have that name, e.g.
  /// a planar body's x, which is also its "position" x), or nullopt.
  std::optional<ColumnInfo> Find(const std::string& name) const;
  /// The names of a group's columns, or of the one column called `name`; empty when unknown.
  std::vector<std::string> Expand(const std::string& name) const;
  /// Expand, appended to `out` (one array for many groups: a scene may have millions).
  void ExpandInto(const std::string& name, std::vector<std::string>& out) const;
  /// Why `name` is neither (with suggestions), for the error.
  std::string Unknown(const std::string& name) const;

 private:
  static bool IsGroup(const std::string& name);
  void AddGroup(const std::string& name, std::vector<std::string>& out) const;
  ColumnInfo BodyColumn(size_t body, const char* group, const char* suffix) const;
  ColumnInfo PointColumn(size_t body, size_t point, size_t group, size_t k) const;
  const Scene& scene_;
  std::vector<ColumnInfo> others_;  // t's successors that are no body's, in order
  std::unordered_map<std::string, size_t> body_, other_;
  std::unordered_map<std::string, std::pair<size_t, size_t>> point_;  // "<body>_<point>"
};

/// Column names for a group or a single column name; empty with `why` set when unknown.
std::vector<std::string> ExpandColumn(const Scene& scene, const std::string& name,
                                      std::string* why);
/// The columns written when the scene has no `output`.
std::vector<std::string> DefaultColumns(const Scene& scene);
/// Names of the groups, for help and messages.
std::vector<std::string> ColumnGroups();

}  // namespace chasles::scene_internal
