#pragma once
/// @file
/// Error types shared by every layer. Exit codes of the CLI follow them: an InputError (bad
/// scene, bad mesh, impossible physical value) exits with 2; anything else with 1.

#include <stdexcept>
#include <string>

namespace chasles {

/// A physical or geometric input that cannot be right: a negative mass, an inertia that
/// violates the triangle inequality, an open mesh in solid mode. The message names the value,
/// the rule and how to fix it. Layers below `scene` throw it without a file position; the
/// scene layer adds file, line and column (see SceneError).
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace chasles
