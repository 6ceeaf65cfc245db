#pragma once
/// @file
/// A scene file rewritten to the current format version (`chasles upgrade`; docs/scene-format.md,
/// "Changes between versions"). The file is read as it says (a file without `chasles` is
/// version 1) and each version-1 spelling the reader meets is replaced in the text where it
/// stands, at the YAML node's place: the version line, a planar world vector's third value, a
/// renamed body variable. Nothing else changes: comments, layout, quoting and key order stay;
/// the YAML is never emitted anew.

#include <string>
#include <string_view>
#include <vector>

#include "chasles/scene/scene.h"

namespace chasles {

struct SceneUpgrade {
  /// The version the file was read as (1 when it has no `chasles` key).
  int from_version = kSceneFormatVersion;
  /// The file as read.
  std::string before;
  /// The file as version kSceneFormatVersion; the file's own text when it is already that.
  std::string text;
  /// One line per edit, in the file's order: "FILE:LINE:COL: KEY: OLD -> NEW".
  std::vector<std::string> changes;
  /// True when `text` differs from the file.
  bool changed() const { return !changes.empty(); }
};

/// Rewrites the scene `text` (named `name` in messages; mesh files are found beside it) as the
/// current format version. Throws SceneError (an InputError) for a scene that does not load
/// as it stands, or whose old spelling sits where a text edit cannot reach it safely (an
/// escaped or multi-line value: the message says what to write there by hand). The result is
/// read back before it is returned; a result that does not load is a std::logic_error.
SceneUpgrade UpgradeSceneText(std::string_view text, const std::string& name,
                              const SceneOptions& options = {});

/// The same for the file at `path` (read with options.max_scene_bytes as its limit).
SceneUpgrade UpgradeSceneFile(const std::string& path, const SceneOptions& options = {});

}  // namespace chasles
