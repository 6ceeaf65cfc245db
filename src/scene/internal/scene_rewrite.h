#pragma once
/// @file
/// An old version's spelling met while reading a scene, as `chasles upgrade` rewrites it: where
/// it stands in the file (0-based line and column, byte offset `pos`) and what
/// replaces it. The reader records one per use (scene_versions.cpp); UpgradeSceneText
/// (scene_upgrade.cpp) turns them into edits of the file's text. Private to the scene layer.

#include <string>

#include "yaml_tree.h"

#include "chasles/scene/scene_constraints.h"

namespace chasles::scene_internal {

/// A scalar as it stands in the file: where it starts, its value and whether it is quoted
/// (then `mark` is the opening quote's).
struct ScalarSource {
  YamlMark mark;
  std::string value;
  bool quoted = false;
};

struct SceneRewrite {
  enum class Kind {
    /// The format version: `scalar` is the `chasles` value; with `insert`, the file has no
    /// `chasles` key and `scalar.mark` is the first key of the root mapping (a `chasles: 3`
    /// line goes before it; `flow`: the root is `{...}` and `chasles: 3, ` goes there).
    kVersion,
    /// A planar world vector [x, y, 0]: the third item (`last`) goes, from the end of the
    /// second (`scalar`); in a block sequence (not `flow`) the third item's line goes.
    kDropZ,
    /// A version-1 name in an expression: `scalar` is the expression, `offset` the byte offset
    /// of the name in its value, `old_text` the name and `new_text` its replacement.
    kRename,
    /// A version-1 or -2 scene with contacts that names no integrator (it runs `adaptive`;
    /// version 3 runs `auto` there): `integrator: adaptive` goes before the first key of
    /// `simulation`, whose mark is `scalar.mark` (`flow`: `simulation: {...}`); with `insert`
    /// the file has no `simulation` key and one goes at its end (`flow`: the root is `{...}`).
    /// A mark with line -1: `simulation` has no keys.
    kKeepAdaptive,
  };
  Kind kind = Kind::kVersion;
  /// Where the spelling is, for messages (1-based line and column, key path).
  SceneSpot spot;
  ScalarSource scalar;
  ScalarSource last;
  bool insert = false;
  bool flow = true;
  size_t offset = 0;
  std::string old_text;
  std::string new_text;
};

/// The source of scalar `node`.
inline ScalarSource SourceOf(const YamlNode& node) {
  return {node.Mark(), std::string(node.Scalar()), node.Quoted()};
}

}  // namespace chasles::scene_internal
