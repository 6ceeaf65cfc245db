// Fuzz target: the expression parser (src/scene/expression.cpp) and the unit-suffix parser.
// Promise: malformed text is an ExpressionError (an InputError) with an offset inside the
// text; a constant expression that parses evaluates to a finite number (the parser folds
// constants and reports overflow, 1/0, log(-1) ... itself).

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "chasles/scene/expression.h"
#include "fuzz_support.h"

namespace {

using chasles::Dimension;
using chasles::Expression;
using chasles::ExpressionError;
using chasles::Quantity;
using chasles::Symbol;

// A parameter table like a scene's: a length, a mass, a pure number, and the variables x, y, z
// of a density field.
std::optional<Symbol> Resolve(std::string_view name) {
  const Dimension length{1, 0, 0}, mass{0, 1, 0};
  if (name == "L") return Symbol::Constant(Quantity{2.0, length});
  if (name == "m_wheel") return Symbol::Constant(Quantity{3.5, mass});
  if (name == "k") return Symbol::Constant(Quantity{0.25, Dimension{}});
  if (name == "x") return Symbol::Variable(0, length);
  if (name == "y") return Symbol::Variable(1, length);
  if (name == "z") return Symbol::Variable(2, length);
  return std::nullopt;
}

void CheckOffset(const ExpressionError& e, std::size_t size, std::string_view text) {
  if (e.offset() > size) chasles::fuzz::Fail("error offset beyond the text", text);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const std::vector<std::string> names{"L", "m_wheel", "k", "x", "y", "z"};
  try {
    const Expression e = Expression::Parse(text, Resolve, [&names] { return names; });
    if (e.variable_count() > 3) chasles::fuzz::Fail("variable slot out of range", text);
    if (e.is_constant()) {
      const double v = e.Evaluate();
      if (!std::isfinite(v))
        chasles::fuzz::Fail("a constant expression evaluated non-finite", text);
    } else {
      const double xyz[3] = {0.1, -0.2, 0.3};
      (void)e.Evaluate(xyz);  // values may be NaN (log(x) of a negative x); it must not crash
    }
  } catch (const ExpressionError& e) {
    CheckOffset(e, size, text);
  } catch (const chasles::InputError&) {
  } catch (const std::exception& e) {
    chasles::fuzz::Fail(e.what(), text);
  }
  try {
    const Quantity q = chasles::ParseUnitSuffix(text);
    if (!std::isfinite(q.value)) chasles::fuzz::Fail("a unit evaluated non-finite", text);
  } catch (const ExpressionError& e) {
    CheckOffset(e, size, text);
  } catch (const chasles::InputError&) {
  } catch (const std::exception& e) {
    chasles::fuzz::Fail(e.what(), text);
  }
  return 0;
}
