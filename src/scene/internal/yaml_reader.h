#pragma once
/// @file
/// Reading YAML nodes with file positions: every failure becomes a SceneError naming the file,
/// line, column and key path. Private to the scene layer.

#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "yaml_tree.h"

#include "chasles/scene/scene_error.h"

namespace chasles::scene_internal {

/// A node with the dotted key path that led to it ("bodies[0].parts[2].radius").
struct At {
  At() = default;
  At(YamlNode node_, std::string path_, YamlMark key_mark_ = {})
      : node(node_), path(std::move(path_)), key_mark(key_mark_) {}
  YamlNode node;
  std::string path;
  /// Where the key of a child with an empty value is ("bodies:" with nothing after it): such a
  /// value has no place of its own (the parser marks it where the next token starts, which may
  /// be lines later or past the end of the file), so errors point at its key.
  YamlMark key_mark;

  At Child(std::string_view key) const;
  At Item(size_t index) const;
  bool Has(std::string_view key) const;
};

/// Where errors point: the file name, and for text that did not come from the file (command-
/// line overrides) a label instead.
class Reporter {
 public:
  explicit Reporter(std::string file) : file_(std::move(file)) {}
  const std::string& file() const { return file_; }

  /// Throws a SceneError at `at`; `offset` is a byte offset inside a scalar (an expression).
  [[noreturn]] void Fail(const At& at, const std::string& message, size_t offset = 0) const;

  /// Requires a mapping whose keys are all in `allowed` (and none repeated). Unknown keys get a
  /// "did you mean" from `allowed`.
  void CheckMap(const At& at, const std::vector<std::string>& allowed, std::string_view what) const;
  /// Requires a key to be present.
  At Require(const At& at, std::string_view key, std::string_view what) const;
  /// Requires a non-empty scalar and returns its text.
  std::string Text(const At& at, std::string_view what) const;
  /// Requires a sequence (of any length; the caller checks the length).
  void CheckSequence(const At& at, std::string_view what) const;

 private:
  std::string file_;
};

/// "a list", "a mapping", "a value", "nothing" for messages about the wrong kind of node.
std::string KindOf(const YamlNode& node);

}  // namespace chasles::scene_internal
