#pragma once
/// @file
/// Error types shared by every layer. Exit codes of the CLI follow them: an InputError (bad
/// scene, bad mesh, impossible physical value) exits with 2; anything else with 1.
///
/// Policy: InputError and its kinds are for what a user can get wrong (the scene, the mesh,
/// the limits they set). A misuse of the library's API that no input can cause, a bug in the
/// calling code, is a UsageError (a std::logic_error), not an InputError.

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

/// A run reached one of its limits on work: the number of integration steps, of output rows,
/// the wall time, or the smallest step the adaptive integrator may take. Bad input too (the
/// problem as posed needs more than the limit allows): the scene layer adds where the limit is
/// set and how to raise it.
class LimitError : public InputError {
 public:
  enum class Limit { kSteps, kRows, kTime, kMinStep };
  LimitError(Limit limit, const std::string& message) : InputError(message), limit_(limit) {}
  Limit limit() const { return limit_; }

 private:
  Limit limit_;
};

/// A call the API does not allow whatever the input: a Data used with a Model other than the
/// one MakeData made it for (see model/data.h). A bug in the calling code; the message says
/// how to call it instead.
class UsageError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

}  // namespace chasles
