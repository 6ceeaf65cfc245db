#include "chasles/scene/expression.h"

#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/error.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::kExact;
using test::Near;
using ::testing::HasSubstr;

constexpr double kPi = std::numbers::pi;
constexpr double kIn = 0.0254;      // m, exact
constexpr double kFt = 0.3048;      // m, exact
constexpr double kLb = 0.45359237;  // kg, exact
constexpr double kGn = 9.80665;     // m/s^2, exact

constexpr Dimension kDensity{-3, 1, 0};
constexpr Dimension kAcceleration{1, 0, -2};
constexpr Dimension kForce{1, 1, -2};

// A resolver over a fixed table of symbols, as the scene layer would build.
struct Table {
  std::map<std::string, Symbol, std::less<>> symbols;
  SymbolResolver resolver() const {
    return [this](std::string_view name) -> std::optional<Symbol> {
      const auto it = symbols.find(name);
      if (it == symbols.end()) return std::nullopt;
      return it->second;
    };
  }
  /// Lists the names when a message asks (Expression::Parse calls it only then).
  SymbolNames names() const {
    return [this] {
      std::vector<std::string> out;
      for (const auto& [name, s] : symbols) out.push_back(name);
      return out;
    };
  }
};

Quantity Eval(std::string_view text) {
  return EvaluateQuantity(text, {});
}

// The ExpressionError that parsing `text` throws (fails the test when none is thrown).
ExpressionError ErrorOf(std::string_view text, const Table& table = {}) {
  try {
    Expression::Parse(text, table.resolver(), table.names());
  } catch (const ExpressionError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for '" << text << "'";
  return ExpressionError("", 0);
}

TEST(Expression, TextbookQuantitiesInTheirOwnUnits) {
  const Quantity d = Eval("9/8 in");
  EXPECT_TRUE(Near(d.value, 9.0 / 8.0 * kIn, kExact));  // 0.028575 m
  EXPECT_TRUE(Near(d.value, 0.028575, kExact));
  EXPECT_EQ(d.dim, kLength);
  const Quantity w = Eval("100 rpm");
  EXPECT_TRUE(Near(w.value, 100 * 2 * kPi / 60, kExact));
  EXPECT_EQ(w.dim, (Dimension{0, 0, -1}));
  EXPECT_TRUE(Near(Eval("3600 lb").value, 3600 * kLb, kExact));
  EXPECT_EQ(Eval("3600 lb").dim, kMass);
  EXPECT_TRUE(Near(Eval("1 lbf").value, kLb * kGn, kExact));
  EXPECT_EQ(Eval("1 lbf").dim, kForce);
  EXPECT_TRUE(Near(Eval("32.2 ft/s^2").value, 32.2 * kFt, kExact));
  EXPECT_EQ(Eval("32.2 ft/s^2").dim, kAcceleration);
  EXPECT_TRUE(Near(Eval("-9.81 m/s^2").value, -9.81, kExact));
  const Quantity rho = Eval("7850 kg/m^3");
  EXPECT_EQ(rho.value, 7850.0);
  EXPECT_EQ(rho.dim, kDensity);
}

TEST(Expression, PureUnitsAndTheirExactFactors) {
  const Quantity lb_ft3 = ParseUnitSuffix("lb/ft^3");
  // 0.45359237 / 0.3048^3 = 16.018463373960138 kg/m^3.
  EXPECT_TRUE(Near(lb_ft3.value, 16.018463373960138, 1e-15));
  EXPECT_EQ(lb_ft3.dim, kDensity);
  EXPECT_EQ(ParseUnitSuffix("kg/m^3").value, 1.0);
  EXPECT_EQ(ParseUnitSuffix(" m ").dim, kLength);
  EXPECT_EQ(ParseUnitSuffix("N*m").dim, (Dimension{2, 1, -2}));
  EXPECT_EQ(ParseUnitSuffix("kg/(m*s^2)").dim, (Dimension{-1, 1, -2}));
  EXPECT_EQ(ParseUnitSuffix("kg*m^2").dim, (Dimension{2, 1, 0}));
  EXPECT_TRUE(Near(ParseUnitSuffix("s^-1").value, 1.0, kExact));
  EXPECT_TRUE(Near(ParseUnitSuffix("slug").value, kLb * kGn / kFt, 1e-15));
}

TEST(Expression, UnitSuffixErrors) {
  try {
    ParseUnitSuffix("2 m");
    FAIL();
  } catch (const ExpressionError& e) {
    EXPECT_THAT(e.message(), HasSubstr("expected a unit name"));
    EXPECT_EQ(e.offset(), 0u);
  }
  try {
    ParseUnitSuffix("kg/m^1.5");
    FAIL();
  } catch (const ExpressionError& e) {
    EXPECT_THAT(e.message(), HasSubstr("exponent must be an integer"));
    EXPECT_EQ(e.offset(), 4u);
  }
  try {
    ParseUnitSuffix("kg/mm3");
    FAIL();
  } catch (const ExpressionError& e) {
    EXPECT_THAT(e.message(), HasSubstr("unknown unit 'mm3' (did you mean 'mm'?)"));
    EXPECT_EQ(e.offset(), 3u);
  }
  EXPECT_THROW(ParseUnitSuffix(""), ExpressionError);
}

TEST(Expression, JuxtapositionAppliesTheUnitToTheWholeProduct) {
  // "9/8 in" is (9/8)*in, not 9/(8 in).
  EXPECT_EQ(Eval("9/8 in").dim, kLength);
  // Sums of terms with their own units.
  EXPECT_TRUE(Near(Eval("2 m + 3 cm").value, 2.03, kExact));
  EXPECT_TRUE(Near(Eval("1 ft - 6 in").value, 0.5 * kFt, kExact));
  // '/' continues the unit only when a unit name follows: (2 m)/(4 s).
  const Quantity v = Eval("2 m / 4 s");
  EXPECT_TRUE(Near(v.value, 0.5, kExact));
  EXPECT_EQ(v.dim, (Dimension{1, 0, -1}));
  // A parameter that is not a unit ends the suffix; a unit name stays a unit.
  Table t;
  t.symbols["len"] = Symbol::Constant({3.0, kLength});
  t.symbols["L"] = Symbol::Constant({3.0, kLength});
  const Quantity p = EvaluateQuantity("2 kg/m * len", t.resolver());
  EXPECT_TRUE(Near(p.value, 6.0, kExact));
  EXPECT_EQ(p.dim, kMass);
  EXPECT_EQ(EvaluateQuantity("2 m * L", t.resolver()).dim, (Dimension{4, 0, 0}));  // litre
  EXPECT_EQ(EvaluateQuantity("(2 m)*L", t.resolver()).dim, (Dimension{2, 0, 0}));
  // Explicit products with units are fine too.
  EXPECT_TRUE(Near(Eval("2*in").value, 2 * kIn, kExact));
  EXPECT_TRUE(Near(Eval("2 m * 3").value, 6.0, kExact));
  EXPECT_TRUE(Near(Eval("(3 ft)^2").value, 9 * kFt * kFt, kExact));
  EXPECT_TRUE(Near(Eval("3 ft^2").value, 3 * kFt * kFt, kExact));
  EXPECT_TRUE(Near(Eval("sin(30 deg)").value, 0.5, kExact));
  EXPECT_TRUE(Near(Eval("1 rev/s").value, 2 * kPi, kExact));
}

// A function or pi after '*' or '/' ends a unit suffix as a parameter does: a density field
// "1000 kg/m^3 * exp(z/R)" is (1000 kg/m^3) * exp(z/R), the same value by left associativity.
TEST(Expression, AFunctionAfterAUnitAndAnOperatorEndsTheUnit) {
  Table t;
  t.symbols["z"] = Symbol::Variable(0, kLength);
  t.symbols["R"] = Symbol::Constant({0.25, kLength});
  const Expression rho = Expression::Parse("1000 kg/m^3 * exp(z/R)", t.resolver(), t.names());
  EXPECT_EQ(rho.dimension(), kDensity);
  EXPECT_TRUE(rho.unit_note().empty());
  for (const double z : {0.0, 0.1, -0.3}) {
    const double vars[1] = {z};
    EXPECT_TRUE(Near(rho.Evaluate(vars), 1000.0 * std::exp(z / 0.25), kExact)) << z;
  }
  EXPECT_TRUE(Near(Eval("2 m / sqrt(4)").value, 1.0, kExact));
  EXPECT_EQ(Eval("2 m / sqrt(4)").dim, kLength);
  EXPECT_TRUE(Near(Eval("2 m * pi").value, 2.0 * kPi, kExact));
}

// What is still refused after a unit says what was read and how to write it.
TEST(Expression, ANameAUnitSuffixCannotTakeSaysWhatWasReadAndHowToWriteIt) {
  Table t;
  t.symbols["rho0"] = Symbol::Constant({7850.0, kDensity});
  // A name that is no unit, parameter, variable or function, after '*'.
  const ExpressionError unknown = ErrorOf("1000 kg/m^3 * rhoo", t);
  EXPECT_EQ(unknown.message(),
            "'kg/m^3 * rhoo' was read as a unit: a name after a unit and '*' continues the unit, "
            "and 'rhoo' is not a unit, a parameter, a variable or a function (did you mean "
            "'rho0'?); to multiply by something else write (1000 kg/m^3) * ...");
  EXPECT_EQ(unknown.offset(), 14u);
  // A function right after a value, with no operator.
  EXPECT_THAT(ErrorOf("1000 exp(2)", t).message(),
              HasSubstr("'exp' is a function, not a unit: write '*' before it"));
  // A parameter or variable that is also a unit is read as the unit; an error that follows
  // says so. t is both the tonne and the time here: 2 N * t + 1 N*s is N*kg + N*s.
  Table time;
  time.symbols["t"] = Symbol::Variable(0, Dimension{0, 0, 1});
  EXPECT_EQ(ErrorOf("2 N * t + 1 N*s", time).message(),
            "cannot add mass^2*length/time^2 and momentum or impulse (mass*length/time); 't' "
            "after '2 N *' was read as the unit t (a name after a unit "
            "and '*' continues the unit, even when a parameter or variable has that name); to "
            "use the variable 't' write (2 N) * t");
  // The note also goes with an expression that parses, for its caller's dimension check.
  const Expression shadowed = Expression::Parse("2 N * t", time.resolver(), time.names());
  EXPECT_EQ(shadowed.dimension(), (Dimension{1, 2, -2}));
  EXPECT_THAT(shadowed.unit_note(), HasSubstr("write (2 N) * t"));
}

TEST(Expression, ParametersShadowUnitsOutsideAUnitSuffix) {
  Table t;
  t.symbols["m"] = Symbol::Constant({2.0, kMass});  // a parameter named m: 2 kg
  t.symbols["r"] = Symbol::Constant({0.5, kLength});
  // Operand position: the parameter.
  const Quantity a = EvaluateQuantity("9/16*m", t.resolver());
  EXPECT_TRUE(Near(a.value, 9.0 / 16 * 2.0, kExact));
  EXPECT_EQ(a.dim, kMass);
  // Unit suffix: always the metre.
  const Quantity b = EvaluateQuantity("9/16 m", t.resolver());
  EXPECT_TRUE(Near(b.value, 9.0 / 16, kExact));
  EXPECT_EQ(b.dim, kLength);
  // I = m r^2 / 2 of a disk.
  const Quantity I = EvaluateQuantity("m*r^2/2", t.resolver());
  EXPECT_TRUE(Near(I.value, 2.0 * 0.25 / 2, kExact));
  EXPECT_EQ(I.dim, (Dimension{2, 1, 0}));
}

TEST(Expression, ArithmeticPrecedenceAndNumbers) {
  EXPECT_EQ(Eval("2^3^2").value, 512.0);  // right-associative
  EXPECT_EQ(Eval("-2^2").value, -4.0);    // unary minus binds looser than ^
  EXPECT_EQ(Eval("2^-1").value, 0.5);
  EXPECT_EQ(Eval("1 + 2*3 - 4/2").value, 5.0);
  EXPECT_EQ(Eval("(1 + 2)*3").value, 9.0);
  EXPECT_EQ(Eval(".5").value, 0.5);
  EXPECT_EQ(Eval("1e-3").value, 1e-3);
  EXPECT_EQ(Eval("2.5E+2").value, 250.0);
  EXPECT_TRUE(Near(Eval("2*pi").value, 2 * kPi, kExact));
  EXPECT_TRUE(Near(Eval("4^0.5").value, 2.0, kExact));  // dimensionless base: any exponent
}

TEST(Expression, FunctionsCarryDimensions) {
  const Quantity r = Eval("sqrt(4 m^2)");
  EXPECT_TRUE(Near(r.value, 2.0, kExact));
  EXPECT_EQ(r.dim, kLength);
  EXPECT_EQ(Eval("cbrt(27 m^3)").dim, kLength);
  EXPECT_TRUE(Near(Eval("cbrt(27 m^3)").value, 3.0, kExact));
  EXPECT_TRUE(Near(Eval("hypot(3 m, 4 m)").value, 5.0, kExact));
  EXPECT_TRUE(Near(Eval("atan2(1 m, 1 m)").value, kPi / 4, kExact));
  EXPECT_TRUE(Eval("atan2(1 m, 1 m)").dim.IsDimensionless());
  EXPECT_EQ(Eval("min(2 kg, 3 kg)").value, 2.0);
  EXPECT_EQ(Eval("max(2 kg, 3 kg)").value, 3.0);
  EXPECT_EQ(Eval("abs(-3 kg)").value, 3.0);
  EXPECT_EQ(Eval("pow(2 m, 3)").dim, (Dimension{3, 0, 0}));
  EXPECT_TRUE(Near(Eval("log10(1000)").value, 3.0, kExact));
  EXPECT_TRUE(Near(Eval("exp(log(2))").value, 2.0, kExact));
  EXPECT_TRUE(Near(Eval("acos(0) + asin(1)").value, kPi, kExact));
  EXPECT_TRUE(Near(Eval("cos(pi)").value, -1.0, kExact));
}

TEST(Expression, VariablesAreEvaluatedLater) {
  Table t;
  t.symbols["x"] = Symbol::Variable(0, kLength);
  t.symbols["z"] = Symbol::Variable(2, kLength);
  t.symbols["rho0"] = Symbol::Constant({7850.0, kDensity});
  // A density field graded along z: rho0 * (1 + z/(2 m)) + x-term.
  const Expression e =
      Expression::Parse("rho0 * (1 + z/(2 m)) + 100 kg/m^4 * x", t.resolver(), t.names());
  EXPECT_FALSE(e.is_constant());
  EXPECT_EQ(e.variable_count(), 3);
  EXPECT_EQ(e.dimension(), kDensity);
  const double p[] = {0.5, 99.0, 1.0};
  EXPECT_TRUE(Near(e.Evaluate(p), 7850.0 * 1.5 + 100 * 0.5, kExact));
  const double q[] = {0.0, 0.0, -2.0};
  EXPECT_TRUE(Near(e.Evaluate(q), 0.0, kExact, 7850.0));
  EXPECT_THROW(e.Evaluate(std::span<const double>(p, 2)), std::invalid_argument);
  // Squares of variables, dimensionless powers of variables.
  const Expression sq = Expression::Parse("x^2 + z^2", t.resolver());
  const double r[] = {3.0, 0.0, 4.0};
  EXPECT_EQ(sq.Evaluate(r), 25.0);
  EXPECT_EQ(sq.dimension(), (Dimension{2, 0, 0}));
  const Expression pw = Expression::Parse("2^(x/(1 m))", t.resolver());
  EXPECT_TRUE(Near(pw.Evaluate(r), 8.0, kExact));
  // A constant expression needs no variables; EvaluateQuantity refuses a variable one.
  EXPECT_TRUE(Expression::Parse("2 m", t.resolver()).is_constant());
  EXPECT_THROW(EvaluateQuantity("x + 1 m", t.resolver()), ExpressionError);
}

TEST(Expression, ErrorsAreSpecificAndLocated) {
  Table t;
  t.symbols["length"] = Symbol::Constant({2.0, kLength});
  t.symbols["L"] = Symbol::Constant({1.0, kLength});
  t.symbols["L_x"] = Symbol::Constant({1.0, kLength});
  struct Case {
    const char* text;
    const char* message;
    size_t offset;
  };
  const Case cases[] = {
      {"lenght * 2", "unknown name 'lenght' (did you mean 'length'?)", 0},
      {"2 m + 3 kg", "cannot add length and mass", 4},
      {"2 m - 3 kg", "cannot subtract mass from length", 4},
      {"sqrt(2 m^3)", "sqrt of length^3: the exponent must be even", 0},
      {"1 + cbrt(2 m^2)", "cbrt of length^2: the exponents must be multiples of 3", 4},
      {"1/0", "division by zero", 1},
      {"1/(2-2)", "division by zero", 1},
      {"2*", "expected a number, a name or '(' after '*'", 2},
      {"2*)", "expected a number, a name or '(' after '*', got ')'", 2},
      {"2)", "unexpected ')'", 1},
      {"(2+3", "missing ')'", 4},
      {"sin(2 m)", "sin needs a dimensionless argument (angle); got length", 0},
      {"exp(1 s)", "exp needs a dimensionless argument; got time", 0},
      {"log(-1)", "log of a negative number", 0},
      {"2 + log(0)", "log of zero", 4},
      {"sqrt(-1)", "sqrt of a negative number", 0},
      {"asin(2)", "asin of 2: the argument must be in [-1, 1]", 0},
      {"1e300*1e300", "overflows", 5},
      {"10^400", "overflows", 2},
      {"1e999", "out of the range of a double", 0},
      {"(2 m)^1.5", "cannot raise length to the power 1.5", 5},
      {"2^(1 m)", "the exponent must be dimensionless; got length", 1},
      {"2 furlong", "unknown unit 'furlong'", 2},
      {"3 kgg", "unknown unit 'kgg' (did you mean 'kg'?)", 2},
      {"2 L_x", "a name right after a value is read as a unit", 2},
      {"sine(1)", "unknown function 'sine' (did you mean 'sin'?)", 0},
      {"L(2)", "'L' is not a function", 0},
      {"sin", "'sin' is a function", 0},
      {"min(1)", "min takes 2 arguments, got 1", 0},
      {"atan2(1 m, 1 s)", "atan2 needs arguments of the same dimension; got length and time", 0},
      {"hypot(1 m, 1 kg)", "same dimension", 0},
      {"2 3", "unexpected '3' (missing operator?)", 2},
      {"1 m # 2", "unexpected character '#'", 4},
      {"", "empty expression", 0},
      {"()", "empty parentheses", 1},
      {"2 m kg", "unexpected 'kg' (missing operator?)", 4},
      {"2 sin(1)", "'sin' is a function, not a unit", 2},
  };
  for (const Case& c : cases) {
    const ExpressionError e = ErrorOf(c.text, t);
    EXPECT_THAT(e.message(), HasSubstr(c.message)) << "'" << c.text << "'";
    EXPECT_EQ(e.offset(), c.offset) << "'" << c.text << "': " << e.message();
    EXPECT_EQ(std::string(e.what()), e.message());
  }
}

TEST(Expression, ExpressionErrorIsAnInputErrorAndResolverErrorsPropagate) {
  try {
    Eval("1 m + 1 s");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("cannot add length and time"));
  }
  const SymbolResolver cyclic = [](std::string_view name) -> std::optional<Symbol> {
    throw InputError("parameter '" + std::string(name) + "' depends on itself");
  };
  try {
    EvaluateQuantity("2*a", cyclic);
    FAIL();
  } catch (const ExpressionError&) {
    FAIL() << "the resolver's error must propagate unchanged";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("parameter 'a' depends on itself"));
  }
}

TEST(Expression, ConstantsAreFoldedToOneInstruction) {
  // A folded constant expression evaluates without variables and never to NaN.
  const Expression e = Expression::Parse("(9/8 in)^2 * pi / 4", {});
  EXPECT_TRUE(e.is_constant());
  EXPECT_TRUE(Near(e.Evaluate(), kPi / 4 * std::pow(9.0 / 8 * kIn, 2), kExact));
  EXPECT_EQ(e.dimension(), (Dimension{2, 0, 0}));
}

}  // namespace
}  // namespace chasles
