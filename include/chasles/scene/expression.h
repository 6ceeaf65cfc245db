#pragma once
/// @file
/// Unit-bearing arithmetic expressions of the scene format: "9/8 in", "7850 kg/m^3",
/// "100 rpm", "2 m + 3 cm", "m_wheel * r^2 / 2", "rho0 * (1 + z / (2 m))".
///
/// The parser is our own small recursive-descent parser rather than muparser or exprtk:
/// those evaluate plain doubles, while we need a dimension carried through every operation
/// (checked once, when the expression is parsed) and errors located at an exact byte offset.
///
/// Grammar (precedence low to high):
///   expr    := term (('+' | '-') term)*
///   term    := product [unit] (('*' | '/') product [unit])*
///   product := unary (('*' | '/') unary)*
///   unary   := ('-' | '+') unary | power
///   power   := primary ['^' unary]                 (right-associative: 2^3^2 = 2^9)
///   primary := number | name | name '(' expr (',' expr)* ')' | '(' expr ')'
///   unit    := uname ['^' ['-'] integer] (('*' | '/') uname ['^' ['-'] integer])*
/// Numbers: 12, 1.5, .5, 1e-3, 2.5E+6.
///
/// Rules for names:
///  - Units by juxtaposition: a product followed directly (no operator) by a name starts a
///    unit suffix that multiplies that product: "9/8 in" is (9/8)*in, "7850 kg/m^3" is
///    7850*(kg/m^3), "-9.81 m/s^2" is (-9.81)*(m/s^2), "2 m + 3 cm" is 2*m + 3*cm. Inside a
///    unit suffix every name that is a unit is read as the unit, even when a parameter has
///    the same name ("7850 kg/m^3" with a parameter m still means metres). '*' or '/'
///    continue the unit only when a name follows ("2 m / 4 s" is (2 m)/(4 s)), and a name
///    that is not a unit but a parameter or variable, a function or pi ends it
///    ("100 kg/m^4 * x" is (100 kg/m^4)*x, "1000 kg/m^3 * exp(z/R)" is
///    (1000 kg/m^3)*exp(z/R): the same value by left associativity). Beware: "2 m * L" with a
///    parameter L multiplies by the litre; write "(2 m)*L" or "L*2 m" (an error in such an
///    expression says so: Expression::unit_note). A name directly after a value that is not
///    a unit is an error ("2 x": write 2*x), and so is a name after a unit and '*' that is
///    none of these (the message shows the unit as read and how to end it).
///  - Elsewhere a name is resolved, in order, as: a function if '(' follows (sqrt cbrt abs
///    sin cos tan asin acos atan atan2 exp log log10 min max hypot pow); a symbol of the
///    caller's resolver (named parameters, variables x, y, z); the constant pi; a unit.
///    So a parameter named m shadows the metre in "9/16*m", while "2*in" is 2 inches.
///  - Powers: the exponent must be dimensionless. A base with a dimension needs a constant
///    integer exponent (r^2, t^-1); a dimensionless base takes any exponent. sqrt needs even
///    exponents (sqrt(m^2) is a length; sqrt of a length is an error), cbrt multiples of 3.
///  - sin cos tan exp log log10 asin acos atan take dimensionless arguments (angles are
///    dimensionless: "sin(30 deg)"); atan2, min, max, hypot take two arguments of the same
///    dimension; pow(a, n) is a^n.
///
/// Constant sub-expressions are folded while parsing, so literal errors ("1/0", "log(-1)",
/// "sqrt(-2 m^2)", overflow) are reported with their offset: a constant expression never
/// evaluates to NaN or infinity. Expressions that depend on variables are checked only for
/// dimensions; their callers check the values they produce.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "chasles/error.h"
#include "chasles/scene/units.h"

namespace chasles {

/// A malformed or dimensionally wrong expression. what() is the message without location
/// ("cannot add length and mass"); the scene layer adds file:line:col from offset().
class ExpressionError : public InputError {
 public:
  ExpressionError(std::string message, size_t offset)
      : InputError(message), message_(std::move(message)), offset_(offset) {}
  /// 0-based byte offset into the expression text where the problem is (text size = at end).
  size_t offset() const { return offset_; }
  /// The message, without location (same as what()).
  const std::string& message() const { return message_; }

 private:
  std::string message_;
  size_t offset_;
};

/// What a name in an expression stands for: a constant (a named parameter, already
/// evaluated) or a variable slot filled at evaluation time (x, y, z of a density field).
struct Symbol {
  enum class Kind { kConstant, kVariable };
  /// Which of the two this is.
  Kind kind = Kind::kConstant;
  /// For kConstant: the value (SI) and dimension; for kVariable: only `dim` is used.
  Quantity quantity;
  /// For kVariable: index into the span given to Expression::Evaluate.
  int index = -1;

  /// A named constant, value in SI.
  static Symbol Constant(const Quantity& q) { return {Kind::kConstant, q, -1}; }
  /// A variable read from `variables[index]` at evaluation time, in SI units of `dim`.
  static Symbol Variable(int index, const Dimension& dim) {
    return {Kind::kVariable, Quantity{0.0, dim}, index};
  }
};

/// Resolves a name to a Symbol, or nullopt when the name is not a symbol (it may then be a
/// constant or a unit). It may throw (e.g. InputError for a parameter cycle); the exception
/// propagates out of Expression::Parse unchanged.
using SymbolResolver = std::function<std::optional<Symbol>(std::string_view)>;

/// Lists the resolver's names, for "did you mean" hints: called only when a message needs them
/// (a scene of 100 000 bodies has 1.8 million state-variable names).
using SymbolNames = std::function<std::vector<std::string>()>;

/// A parsed, dimension-checked, compiled expression. Evaluation runs a flat postfix program
/// on a fixed-size stack: no allocation and no indirect call per node.
class Expression {
 public:
  /// Parses `text`. `resolver` may be empty (then only units, pi and functions are known).
  /// `symbol_names` lists the resolver's names, used only for "did you mean" hints.
  /// Throws ExpressionError.
  static Expression Parse(std::string_view text, const SymbolResolver& resolver,
                          const SymbolNames& symbol_names = {});

  /// Dimension of the result.
  const Dimension& dimension() const { return dim_; }
  /// True when the expression uses no variable (its value is known after parsing).
  bool is_constant() const { return variable_count_ == 0; }
  /// 1 + the highest variable index used; Evaluate needs at least this many values.
  int variable_count() const { return variable_count_; }
  /// The source text.
  const std::string& text() const { return text_; }
  /// Set when a unit suffix read a name that is also a parameter or variable as the unit
  /// ("2 N * t": t the tonne): what happened and how to write the other reading, for a caller
  /// whose dimension check then fails ("" otherwise).
  const std::string& unit_note() const { return unit_note_; }

  /// Value in SI units of dimension(), with the variables (SI) at their slot indices.
  /// Throws std::invalid_argument if fewer than variable_count() values are given.
  double Evaluate(std::span<const double> variables = {}) const;

  /// Largest evaluation stack an expression may need; deeper ones are rejected by Parse.
  static constexpr int kMaxStack = 64;

 private:
  struct Instruction {
    std::uint8_t op;
    int index;     // variable slot or integer exponent
    double value;  // constant
  };
  std::string text_;
  std::string unit_note_;
  Dimension dim_;
  int variable_count_ = 0;
  std::vector<Instruction> program_;

  friend class ExpressionCompiler;
};

/// Parses and evaluates a constant expression ("3600 lb", "9/8 in"). Throws ExpressionError,
/// also when the expression depends on a variable.
Quantity EvaluateQuantity(std::string_view text, const SymbolResolver& resolver,
                          const SymbolNames& symbol_names = {});

/// Parses a pure unit expression: unit names joined by '*' or '/', each with an optional
/// integer power, parentheses allowed ("m", "kg/m^3", "N*m", "kg/(m*s^2)", "1/s"). For a trailing
/// unit after a sequence, e.g. "[0, 0, 2] m". Returns the SI value of one such unit.
/// Throws ExpressionError.
Quantity ParseUnitSuffix(std::string_view text);

}  // namespace chasles
