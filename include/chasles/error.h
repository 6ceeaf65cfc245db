#pragma once
/// @file
/// Error types shared by every layer. Exit codes of the CLI follow them: an InputError (bad
/// scene, bad mesh, impossible physical value) exits with 2; anything else with 1.
///
/// Policy: InputError and its kinds are for what a user can get wrong (the scene, the mesh,
/// the limits they set). A misuse of the library's API that no input can cause, a bug in the
/// calling code, is a UsageError (a std::logic_error), not an InputError.

#include <optional>
#include <stdexcept>
#include <string>
#include <typeinfo>

namespace chasles {

/// The element of a Model an error concerns: its kind and its index among the Model's elements
/// of that kind. The layer that built the Model maps it back to where the element is defined
/// (the scene: its file, line and column), without reading the message.
struct ErrorElement {
  enum class Kind {
    kBody,          ///< Model::body(index)
    kForceElement,  ///< Model::force_element(index)
    kConstraint,    ///< Model::constraint(index) (joints, rolling, drivers, gears, strings)
    kContact,       ///< Model::contact(index)
    kContactPoint,  ///< the Model's contact point `index` (Model::contact_point_name)
    kEvent,         ///< SimulationOptions::events[index]
    kInitialState,  ///< the initial state given for body `index` (a study's user body)
  };
  Kind kind = Kind::kBody;
  int index = -1;
  /// The element's output (its force and moment, its reaction) evaluated to NaN or an
  /// infinity while its inputs were finite: the fault is in how it computes them (a force's
  /// expression), not in the state.
  bool non_finite_output = false;
};

/// A physical or geometric input that cannot be right: a negative mass, an inertia that
/// violates the triangle inequality, an open mesh in solid mode. The message names the value,
/// the rule and how to fix it, and the error carries the Model element it concerns when there
/// is one. Layers below `scene` throw it without a file position; the scene layer adds file,
/// line and column (see SceneError).
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
  InputError(const std::string& message, std::optional<ErrorElement> element)
      : std::runtime_error(message), element_(element) {}
  /// The element the error concerns; none when it is about the run or the input as a whole.
  const std::optional<ErrorElement>& element() const { return element_; }

 private:
  std::optional<ErrorElement> element_;
};

/// Rethrows the InputError being handled, tagged with `element` when it names none: a check
/// inside an element (its constructor, its force law) knows the element by its name only, its
/// caller knows its index. Call it only inside a handler. Located and other derived errors
/// (a scene's SceneError, a LimitError) pass unchanged.
[[noreturn]] inline void RethrowForElement(const InputError& e, const ErrorElement& element) {
  if (e.element() || typeid(e) != typeid(InputError)) throw;
  throw InputError(e.what(), element);
}

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
