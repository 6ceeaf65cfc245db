#include "chasles/scene/expression.h"

#include "chasles/suggest.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

namespace chasles {
namespace {

// Postfix instruction codes. Unary ops replace the top of the stack, binary ops pop one.
enum Op : std::uint8_t {
  kConst,
  kVar,
  kNeg,
  kAdd,
  kSub,
  kMul,
  kDiv,
  kPowInt,  // top ^ index, integer exponent
  kPow,     // a ^ b, both on the stack
  kSqrt,
  kCbrt,
  kAbs,
  kSin,
  kCos,
  kTan,
  kAsin,
  kAcos,
  kAtan,
  kExp,
  kLog,
  kLog10,
  kAtan2,
  kMin,
  kMax,
  kHypot,
};

bool IsBinary(Op op) {
  switch (op) {
    case kAdd:
    case kSub:
    case kMul:
    case kDiv:
    case kPow:
    case kAtan2:
    case kMin:
    case kMax:
    case kHypot:
      return true;
    default:
      return false;
  }
}

struct Function {
  const char* name;
  Op op;
  int arity;
};

// kPow marks pow(a, n), handled like a^n.
constexpr std::array kFunctions{
    Function{"sqrt", kSqrt, 1},   Function{"cbrt", kCbrt, 1}, Function{"abs", kAbs, 1},
    Function{"sin", kSin, 1},     Function{"cos", kCos, 1},   Function{"tan", kTan, 1},
    Function{"asin", kAsin, 1},   Function{"acos", kAcos, 1}, Function{"atan", kAtan, 1},
    Function{"exp", kExp, 1},     Function{"log", kLog, 1},   Function{"log10", kLog10, 1},
    Function{"atan2", kAtan2, 2}, Function{"min", kMin, 2},   Function{"max", kMax, 2},
    Function{"hypot", kHypot, 2}, Function{"pow", kPow, 2},
};

const Function* FindFunction(std::string_view name) {
  for (const Function& f : kFunctions) {
    if (name == f.name) return &f;
  }
  return nullptr;
}

std::string Num(double x) {
  return fmt::format("{}", x);
}

}  // namespace

// Parses text into an AST whose constant sub-trees are folded as they are built, then emits
// the postfix program. Friend of Expression.
class ExpressionCompiler {
 public:
  using Instruction = Expression::Instruction;

  ExpressionCompiler(std::string_view text, const SymbolResolver* resolver,
                     const SymbolNames* symbol_names)
      : text_(text), resolver_(resolver), symbol_names_(symbol_names) {
    // One allocation for the nodes of a short expression ("0.1 m" makes three): a scene reads
    // every number through here.
    nodes_.reserve(16);
  }

  Expression Compile() {
    Advance();
    if (tok_.kind == Tok::kEnd) Fail("empty expression", 0);
    const int root = ParseExpr();
    ExpectEnd();
    Expression e;
    e.text_ = std::string(text_);
    e.dim_ = nodes_[root].dim;
    e.unit_note_ = unit_note_;
    int depth = 0, max_depth = 0;
    Emit(root, e.program_, depth, max_depth, e.variable_count_);
    if (max_depth > Expression::kMaxStack) {
      Fail(fmt::format("expression is too large (needs an evaluation stack of {}, limit {})",
                       max_depth, Expression::kMaxStack),
           0);
    }
    return e;
  }

  Quantity CompileUnit() {
    Advance();
    if (tok_.kind == Tok::kEnd) Fail("empty unit", 0);
    if (tok_.kind != Tok::kName && !IsOp('(') &&
        !(tok_.kind == Tok::kNumber && tok_.number == 1.0)) {
      Fail("expected a unit name, got " + TokenText(tok_), tok_.pos);
    }
    const Quantity q = ParseUnit(/*allow_groups=*/true);
    ExpectEnd();
    return q;
  }

  // Runs a postfix program. Shared by Expression::Evaluate and constant folding, so folded
  // and evaluated values agree bit for bit.
  static double Run(const Instruction* program, size_t size, const double* vars) {
    if (size == 0) return std::numeric_limits<double>::quiet_NaN();
    std::array<double, Expression::kMaxStack> stack;
    int top = -1;
    for (size_t k = 0; k < size; ++k) {
      const Instruction& in = program[k];
      double& a = stack[top < 0 ? 0 : top];
      switch (static_cast<Op>(in.op)) {
        case kConst:
          stack[++top] = in.value;
          break;
        case kVar:
          stack[++top] = vars[in.index];
          break;
        case kNeg:
          a = -a;
          break;
        case kPowInt:
          a = in.index == 2 ? a * a : std::pow(a, static_cast<double>(in.index));
          break;
        case kSqrt:
          a = std::sqrt(a);
          break;
        case kCbrt:
          a = std::cbrt(a);
          break;
        case kAbs:
          a = std::abs(a);
          break;
        case kSin:
          a = std::sin(a);
          break;
        case kCos:
          a = std::cos(a);
          break;
        case kTan:
          a = std::tan(a);
          break;
        case kAsin:
          a = std::asin(a);
          break;
        case kAcos:
          a = std::acos(a);
          break;
        case kAtan:
          a = std::atan(a);
          break;
        case kExp:
          a = std::exp(a);
          break;
        case kLog:
          a = std::log(a);
          break;
        case kLog10:
          a = std::log10(a);
          break;
        default: {
          // Binary: a (below) op b (top).
          const double b = stack[top--];
          double& x = stack[top];
          switch (static_cast<Op>(in.op)) {
            case kAdd:
              x += b;
              break;
            case kSub:
              x -= b;
              break;
            case kMul:
              x *= b;
              break;
            case kDiv:
              x /= b;
              break;
            case kPow:
              x = std::pow(x, b);
              break;
            case kAtan2:
              x = std::atan2(x, b);
              break;
            case kMin:
              x = std::min(x, b);
              break;
            case kMax:
              x = std::max(x, b);
              break;
            case kHypot:
              x = std::hypot(x, b);
              break;
            default:
              break;
          }
        }
      }
    }
    return stack[0];
  }

 private:
  enum class Tok { kNumber, kName, kOp, kEnd };
  struct Token {
    Tok kind = Tok::kEnd;
    size_t pos = 0;
    std::string_view text;
    double number = 0.0;
  };

  struct Node {
    Op op = kConst;
    double value = 0.0;  // kConst
    int index = 0;       // kVar slot, kPowInt exponent
    int a = -1, b = -1;  // children
    Dimension dim;
    size_t offset = 0;  // where errors about this node point
  };

  static constexpr int kMaxNesting = 200;
  // Largest |exponent| a dimension may reach: m^1000 is surely a mistake.
  static constexpr int kMaxDimensionExponent = 64;

  // Every error after a unit suffix took a parameter's or variable's name as a unit says so
  // (ParseUnit): that reading is the likely cause.
  [[noreturn]] void Fail(const std::string& message, size_t offset) const {
    throw ExpressionError(unit_note_.empty() ? message : message + "; " + unit_note_, offset);
  }

  // ---- lexer ----------------------------------------------------------------------------

  static bool IsNameStart(char c) {
    return std::isalpha(static_cast<unsigned char>(c)) || c == '_';
  }
  static bool IsNameChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
  static bool IsDigit(char c) { return c >= '0' && c <= '9'; }

  Token Lex(size_t pos) const {
    while (pos < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos]))) ++pos;
    Token t;
    t.pos = pos;
    if (pos >= text_.size()) return t;
    const char c = text_[pos];
    if (IsDigit(c) || (c == '.' && pos + 1 < text_.size() && IsDigit(text_[pos + 1]))) {
      size_t end = pos;
      while (end < text_.size() && IsDigit(text_[end])) ++end;
      if (end < text_.size() && text_[end] == '.') {
        ++end;
        while (end < text_.size() && IsDigit(text_[end])) ++end;
      }
      // An exponent only if digits follow: "2e" is not a number with an exponent.
      if (end < text_.size() && (text_[end] == 'e' || text_[end] == 'E')) {
        size_t k = end + 1;
        if (k < text_.size() && (text_[k] == '+' || text_[k] == '-')) ++k;
        if (k < text_.size() && IsDigit(text_[k])) {
          end = k;
          while (end < text_.size() && IsDigit(text_[end])) ++end;
        }
      }
      t.kind = Tok::kNumber;
      t.text = text_.substr(pos, end - pos);
      const auto [ptr, ec] = std::from_chars(t.text.data(), t.text.data() + t.text.size(), t.number,
                                             std::chars_format::general);
      if (ec == std::errc::result_out_of_range) {
        Fail("number '" + std::string(t.text) + "' is out of the range of a double", pos);
      }
      if (ec != std::errc() || ptr != t.text.data() + t.text.size()) {
        Fail("malformed number '" + std::string(t.text) + "'", pos);
      }
      return t;
    }
    if (IsNameStart(c)) {
      size_t end = pos + 1;
      while (end < text_.size() && IsNameChar(text_[end])) ++end;
      t.kind = Tok::kName;
      t.text = text_.substr(pos, end - pos);
      return t;
    }
    if (std::string_view("+-*/^(),").find(c) != std::string_view::npos) {
      t.kind = Tok::kOp;
      t.text = text_.substr(pos, 1);
      return t;
    }
    if (static_cast<unsigned char>(c) >= 0x80) {
      Fail(
          "unexpected non-ASCII character: write powers as ^2, products as *, and names in "
          "plain letters (e.g. 'deg', 'pi')",
          pos);
    }
    Fail(std::string("unexpected character '") + c + "'", pos);
  }

  void Advance() {
    prev_ = tok_;
    has_prev_ = true;
    tok_ = Lex(tok_.pos + tok_.text.size());
  }
  Token Peek() const { return Lex(tok_.pos + tok_.text.size()); }

  bool IsOp(char c) const { return tok_.kind == Tok::kOp && tok_.text[0] == c; }
  static bool IsOp(const Token& t, char c) { return t.kind == Tok::kOp && t.text[0] == c; }

  static std::string TokenText(const Token& t) {
    if (t.kind == Tok::kEnd) return "the end";
    std::string out = "'";
    out.append(t.text);
    out += '\'';
    return out;
  }

  void ExpectEnd() const {
    if (tok_.kind == Tok::kEnd) return;
    if (IsOp(')')) Fail("unexpected ')'", tok_.pos);
    if (tok_.kind == Tok::kNumber || tok_.kind == Tok::kName || IsOp('(')) {
      Fail("unexpected " + TokenText(tok_) + " (missing operator?)", tok_.pos);
    }
    Fail("unexpected " + TokenText(tok_), tok_.pos);
  }

  // ---- nodes and folding ----------------------------------------------------------------

  int Add(const Node& n) {
    nodes_.push_back(n);
    return static_cast<int>(nodes_.size()) - 1;
  }
  int Const(double value, const Dimension& dim, size_t offset) {
    Node n;
    n.op = kConst;
    n.value = value;
    n.dim = dim;
    n.offset = offset;
    return Add(n);
  }
  bool IsConst(int i) const { return nodes_[i].op == kConst; }

  // Builds an operation node; folds it when its operands are constant, reporting values
  // that are not finite as errors at the node's offset.
  int Make(Op op, int a, int b, const Dimension& dim, size_t offset, int index = 0) {
    if (op == kDiv && IsConst(b) && nodes_[b].value == 0.0) Fail("division by zero", offset);
    Node n;
    n.op = op;
    n.a = a;
    n.b = b;
    n.dim = dim;
    n.offset = offset;
    n.index = index;
    if (!IsConst(a) || (b >= 0 && !IsConst(b))) return Add(n);

    std::array<Instruction, 3> program{};
    size_t size = 0;
    program[size++] = Instruction{kConst, 0, nodes_[a].value};
    if (b >= 0) program[size++] = Instruction{kConst, 0, nodes_[b].value};
    program[size++] = Instruction{op, index, 0.0};
    const double value = Run(program.data(), size, nullptr);
    if (!std::isfinite(value)) {
      Fail(DomainMessage(op, nodes_[a].value, b >= 0 ? nodes_[b].value : 0.0, index), offset);
    }
    return Const(value, dim, offset);
  }

  static std::string DomainMessage(Op op, double a, double b, int index) {
    switch (op) {
      case kSqrt:
        return "sqrt of a negative number (" + Num(a) + " in SI units)";
      case kLog:
      case kLog10:
        return std::string(op == kLog ? "log" : "log10") +
               (a == 0.0 ? " of zero" : " of a negative number (" + Num(a) + ")");
      case kAsin:
      case kAcos:
        return std::string(op == kAsin ? "asin" : "acos") + " of " + Num(a) +
               ": the argument must be in [-1, 1]";
      case kPow:
        if (a == 0.0 && b < 0) return "zero raised to a negative power";
        if (a < 0)
          return "negative number " + Num(a) + " raised to the non-integer power " + Num(b);
        break;
      case kPowInt:
        if (a == 0.0 && index < 0) return "zero raised to a negative power";
        break;
      case kTan:
        return "tan of " + Num(a) + " is infinite";
      default:
        break;
    }
    return "the result overflows (too large for a double)";
  }

  // ---- grammar --------------------------------------------------------------------------

  struct DepthGuard {
    explicit DepthGuard(ExpressionCompiler& c) : c_(c) {
      if (++c_.nesting_ > kMaxNesting) c_.Fail("expression is nested too deeply", c_.tok_.pos);
    }
    ~DepthGuard() { --c_.nesting_; }
    ExpressionCompiler& c_;
  };

  // expr := term (('+' | '-') term)*
  int ParseExpr() {
    int n = ParseTerm();
    while (IsOp('+') || IsOp('-')) {
      const bool add = IsOp('+');
      const size_t pos = tok_.pos;
      Advance();
      const int r = ParseTerm();
      if (nodes_[n].dim != nodes_[r].dim) {
        Fail(add ? "cannot add " + nodes_[n].dim.Describe() + " and " + nodes_[r].dim.Describe()
                 : "cannot subtract " + nodes_[r].dim.Describe() + " from " +
                       nodes_[n].dim.Describe(),
             pos);
      }
      n = Make(add ? kAdd : kSub, n, r, nodes_[n].dim, pos);
    }
    return n;
  }

  // term := product [unit] (('*' | '/') product [unit])*
  int ParseTerm() {
    size_t start = tok_.pos;
    int n = MaybeUnitSuffix(start, ParseProduct());
    while (IsOp('*') || IsOp('/')) {
      const bool mul = IsOp('*');
      const size_t pos = tok_.pos;
      Advance();
      start = tok_.pos;
      const int r = MaybeUnitSuffix(start, ParseProduct());
      n = MulDiv(mul, n, r, pos);
    }
    return n;
  }

  int MulDiv(bool mul, int a, int b, size_t pos) {
    const Dimension dim = mul ? nodes_[a].dim * nodes_[b].dim : nodes_[a].dim / nodes_[b].dim;
    CheckDimension(dim, pos);
    return Make(mul ? kMul : kDiv, a, b, dim, pos);
  }

  void CheckDimension(const Dimension& d, size_t pos) const {
    if (std::abs(d.length) > kMaxDimensionExponent || std::abs(d.mass) > kMaxDimensionExponent ||
        std::abs(d.time) > kMaxDimensionExponent) {
      Fail("the dimension " + d.Formula() + " has an exponent beyond " +
               std::to_string(kMaxDimensionExponent),
           pos);
    }
  }

  // A name right after a product (no operator between) starts a unit suffix; the product's
  // text starts at `start` (for messages about the suffix).
  int MaybeUnitSuffix(size_t start, int n) {
    if (tok_.kind != Tok::kName) return n;
    const size_t pos = tok_.pos;
    suffix_ = {start, pos};
    const Quantity unit = ParseUnit(/*allow_groups=*/false);
    suffix_.reset();
    return MulDiv(true, n, Const(unit.value, unit.dim, pos), pos);
  }

  // product := unary (('*' | '/') unary)*
  int ParseProduct() {
    int n = ParseUnary();
    while (IsOp('*') || IsOp('/')) {
      const bool mul = IsOp('*');
      const size_t pos = tok_.pos;
      Advance();
      n = MulDiv(mul, n, ParseUnary(), pos);
    }
    return n;
  }

  // unary := ('-' | '+') unary | power
  int ParseUnary() {
    DepthGuard guard(*this);
    if (IsOp('-')) {
      const size_t pos = tok_.pos;
      Advance();
      const int u = ParseUnary();
      return Make(kNeg, u, -1, nodes_[u].dim, pos);
    }
    if (IsOp('+')) {
      Advance();
      return ParseUnary();
    }
    return ParsePower();
  }

  // power := primary ['^' unary]
  int ParsePower() {
    const int base = ParsePrimary();
    if (!IsOp('^')) return base;
    const size_t pos = tok_.pos;
    Advance();
    return MakePow(base, ParseUnary(), pos);
  }

  int MakePow(int base, int exponent, size_t pos) {
    const Node& e = nodes_[exponent];
    if (!e.dim.IsDimensionless()) {
      Fail("the exponent must be dimensionless; got " + e.dim.Describe(), pos);
    }
    const Dimension base_dim = nodes_[base].dim;
    const bool integer_exponent =
        IsConst(exponent) && e.value == std::round(e.value) && std::abs(e.value) <= 1e6;
    if (!base_dim.IsDimensionless()) {
      if (!IsConst(exponent)) {
        Fail("the exponent of a " + base_dim.Describe() +
                 " must be a constant integer, not an expression of variables",
             pos);
      }
      if (!integer_exponent) {
        Fail("cannot raise " + base_dim.Describe() + " to the power " + Num(e.value) +
                 ": a quantity with a dimension needs an integer exponent",
             pos);
      }
      const int n = static_cast<int>(e.value);
      if (std::abs(n) > kMaxDimensionExponent) {
        Fail("exponent " + std::to_string(n) + " is too large for a quantity with a dimension",
             pos);
      }
      const Dimension dim = base_dim.Pow(n);
      CheckDimension(dim, pos);
      return Make(kPowInt, base, -1, dim, pos, n);
    }
    if (integer_exponent) {
      return Make(kPowInt, base, -1, kDimensionless, pos, static_cast<int>(e.value));
    }
    return Make(kPow, base, exponent, kDimensionless, pos);
  }

  // primary := number | name | name '(' args ')' | '(' expr ')'
  int ParsePrimary() {
    DepthGuard guard(*this);
    if (tok_.kind == Tok::kNumber) {
      const int n = Const(tok_.number, kDimensionless, tok_.pos);
      Advance();
      return n;
    }
    if (IsOp('(')) {
      Advance();
      const int n = ParseExpr();
      if (!IsOp(')')) ExpectClose();
      Advance();
      return n;
    }
    if (tok_.kind == Tok::kName) return ParseName();
    if (IsOp(')') && has_prev_ && IsOp(prev_, '(')) Fail("empty parentheses", tok_.pos);
    const std::string where =
        has_prev_ && prev_.kind != Tok::kEnd ? "after " + TokenText(prev_) : "at the start";
    Fail("expected a number, a name or '(' " + where +
             (tok_.kind == Tok::kEnd ? "" : ", got " + TokenText(tok_)),
         tok_.pos);
  }

  [[noreturn]] void ExpectClose() const {
    if (tok_.kind == Tok::kEnd) Fail("missing ')'", tok_.pos);
    if (tok_.kind == Tok::kNumber || tok_.kind == Tok::kName || IsOp('(')) {
      Fail("expected ')' or an operator, got " + TokenText(tok_), tok_.pos);
    }
    Fail("missing ')' before " + TokenText(tok_), tok_.pos);
  }

  std::optional<Symbol> Resolve(std::string_view name) const {
    if (resolver_ == nullptr || !*resolver_) return std::nullopt;
    return (*resolver_)(name);
  }

  int ParseName() {
    const std::string_view name = tok_.text;
    const size_t pos = tok_.pos;
    if (IsOp(Peek(), '(')) {
      if (const Function* f = FindFunction(name)) return ParseCall(*f, pos);
      if (Resolve(name) || LookupUnit(name) || name == "pi") {
        Fail("'" + std::string(name) + "' is not a function (missing '*' before '('?)", pos);
      }
      std::vector<std::string> functions;
      for (const Function& fn : kFunctions) functions.emplace_back(fn.name);
      Fail("unknown function '" + std::string(name) + "'" +
               DidYouMeanHint(SuggestNames(name, functions)),
           pos);
    }
    Advance();
    if (const std::optional<Symbol> s = Resolve(name)) {
      if (s->kind == Symbol::Kind::kVariable) {
        if (s->index < 0) throw std::invalid_argument("variable slot must be >= 0");
        Node n;
        n.op = kVar;
        n.index = s->index;
        n.dim = s->quantity.dim;
        n.offset = pos;
        return Add(n);
      }
      if (!std::isfinite(s->quantity.value)) {
        Fail("'" + std::string(name) + "' is not a finite number", pos);
      }
      return Const(s->quantity.value, s->quantity.dim, pos);
    }
    if (name == "pi") return Const(std::numbers::pi, kDimensionless, pos);
    if (const std::optional<Quantity> u = LookupUnit(name)) return Const(u->value, u->dim, pos);
    if (FindFunction(name)) {
      Fail("'" + std::string(name) + "' is a function: write " + std::string(name) + "(...)", pos);
    }
    std::vector<std::string> candidates = SymbolNameList();
    for (const std::string& u : UnitNames()) candidates.push_back(u);
    for (const Function& fn : kFunctions) candidates.emplace_back(fn.name);
    candidates.emplace_back("pi");
    Fail(
        "unknown name '" + std::string(name) + "'" + DidYouMeanHint(SuggestNames(name, candidates)),
        pos);
  }

  int ParseCall(const Function& f, size_t pos) {
    Advance();  // name
    Advance();  // '('
    std::vector<int> args;
    if (!IsOp(')')) {
      args.push_back(ParseExpr());
      while (IsOp(',')) {
        Advance();
        args.push_back(ParseExpr());
      }
    }
    if (!IsOp(')')) ExpectClose();
    Advance();
    if (static_cast<int>(args.size()) != f.arity) {
      Fail(fmt::format("{} takes {} argument{}, got {}", f.name, f.arity, f.arity == 1 ? "" : "s",
                       args.size()),
           pos);
    }
    const std::string name = f.name;
    const Dimension d0 = nodes_[args[0]].dim;
    switch (f.op) {
      case kSqrt:
      case kCbrt: {
        const int k = f.op == kSqrt ? 2 : 3;
        if (d0.length % k != 0 || d0.mass % k != 0 || d0.time % k != 0) {
          Fail(name + " of " + d0.Formula() + ": the exponent" +
                   (f.op == kSqrt ? " must be even" : "s must be multiples of 3"),
               pos);
        }
        return Make(f.op, args[0], -1, {d0.length / k, d0.mass / k, d0.time / k}, pos);
      }
      case kAbs:
        return Make(kAbs, args[0], -1, d0, pos);
      case kSin:
      case kCos:
      case kTan:
        if (!d0.IsDimensionless()) {
          Fail(name + " needs a dimensionless argument (angle); got " + d0.Describe(), pos);
        }
        return Make(f.op, args[0], -1, kDimensionless, pos);
      case kAsin:
      case kAcos:
      case kAtan:
      case kExp:
      case kLog:
      case kLog10:
        if (!d0.IsDimensionless()) {
          Fail(name + " needs a dimensionless argument; got " + d0.Describe(), pos);
        }
        return Make(f.op, args[0], -1, kDimensionless, pos);
      case kAtan2:
      case kMin:
      case kMax:
      case kHypot: {
        const Dimension d1 = nodes_[args[1]].dim;
        if (d0 != d1) {
          Fail(name + " needs arguments of the same dimension; got " + d0.Describe() + " and " +
                   d1.Describe(),
               pos);
        }
        return Make(f.op, args[0], args[1], f.op == kAtan2 ? kDimensionless : d0, pos);
      }
      case kPow:
        return MakePow(args[0], args[1], pos);
      default:
        Fail("internal: unhandled function " + name, pos);
    }
  }

  // unit := factor (('*' | '/') factor)*; '*' and '/' continue the unit only when a unit
  // name (or, in a standalone unit, '(') follows.
  Quantity ParseUnit(bool allow_groups) {
    DepthGuard guard(*this);
    Quantity q = ParseUnitFactor(allow_groups);
    while (IsOp('*') || IsOp('/')) {
      const Token next = Peek();
      if (next.kind != Tok::kName && !(allow_groups && IsOp(next, '('))) break;
      // A name that is not a unit but a parameter or variable, a function or pi ends the
      // suffix: "100 kg/m^4 * x" is (100 kg/m^4) * x and "1000 kg/m^3 * exp(z/R)" is
      // (1000 kg/m^3) * exp(z/R). Since '*' and '/' associate left, the value is the same as
      // if the name were part of the unit. Names that are units stay units ("kg/m^3" with a
      // parameter m), which the note below explains if the expression then fails.
      if (next.kind == Tok::kName && !LookupUnit(next.text) &&
          (Resolve(next.text) || FindFunction(next.text) || next.text == "pi")) {
        break;
      }
      if (next.kind == Tok::kName && suffix_ && LookupUnit(next.text) && Resolve(next.text) &&
          unit_note_.empty()) {
        unit_note_ = fmt::format(
            "'{}' after '{}' was read as the unit {} (a name after a unit and '{}' continues the "
            "unit, even when a parameter or variable has that name); to use the {} '{}' write "
            "({}) {} {}",
            next.text, Trimmed(suffix_->value, tok_.pos + 1), next.text, tok_.text,
            IsListedSymbol(next.text) ? "variable" : "parameter", next.text,
            Trimmed(suffix_->value, tok_.pos), tok_.text, next.text);
      }
      const bool mul = IsOp('*');
      Advance();
      const size_t pos = tok_.pos;
      const Quantity f = ParseUnitFactor(allow_groups);
      q.value = mul ? q.value * f.value : q.value / f.value;
      q.dim = mul ? q.dim * f.dim : q.dim / f.dim;
      CheckDimension(q.dim, pos);
    }
    return q;
  }

  // factor := (name | '(' unit ')') ['^' ['-'] integer]
  Quantity ParseUnitFactor(bool allow_groups) {
    const size_t pos = tok_.pos;
    Quantity q;
    if (allow_groups && IsOp('(')) {
      Advance();
      q = ParseUnit(allow_groups);
      if (!IsOp(')')) ExpectClose();
      Advance();
    } else if (tok_.kind == Tok::kName) {
      q = UnitByName(tok_.text, pos);
      Advance();
    } else if (allow_groups && tok_.kind == Tok::kNumber && tok_.number == 1.0) {
      q = Quantity{1.0, kDimensionless};  // "1/s"
      Advance();
    } else {
      Fail("expected a unit name after " + TokenText(prev_) + ", got " + TokenText(tok_), tok_.pos);
    }
    if (!IsOp('^')) return q;
    const size_t caret = tok_.pos;
    Advance();
    bool negative = false;
    if (IsOp('-')) {
      negative = true;
      Advance();
    }
    if (tok_.kind != Tok::kNumber || tok_.number != std::round(tok_.number) ||
        tok_.number > kMaxDimensionExponent) {
      Fail("a unit's exponent must be an integer (like m^2 or s^-1), got " + TokenText(tok_),
           tok_.kind == Tok::kEnd ? tok_.pos : caret);
    }
    const int n = static_cast<int>(tok_.number) * (negative ? -1 : 1);
    Advance();
    q.value = std::pow(q.value, n);
    q.dim = q.dim.Pow(n);
    CheckDimension(q.dim, caret);
    if (!std::isfinite(q.value) || q.value == 0.0) {
      Fail("the unit power is out of the range of a double", caret);
    }
    return q;
  }

  Quantity UnitByName(std::string_view name, size_t pos) const {
    if (const std::optional<Quantity> u = LookupUnit(name)) {
      if (IsOp(Peek(), '(')) {
        Fail("unit '" + std::string(name) + "' followed by '(' (missing operator?)", pos);
      }
      return *u;
    }
    const std::string s(name);
    if (FindFunction(name)) {
      Fail("'" + s + "' is a function, not a unit: write '*' before it", pos);
    }
    if (Resolve(name) || name == "pi") {
      Fail("unknown unit '" + s + "': a name right after a value is read as a unit; to use '" + s +
               "' there, write the operator and parentheses, e.g. (2 m)*" + s,
           pos);
    }
    if (suffix_ && suffix_->unit < pos) {
      // After '*' or '/' inside a unit suffix: say that the suffix went on, and how to end it.
      std::vector<std::string> candidates = SymbolNameList();
      for (const std::string& u : UnitNames()) candidates.push_back(u);
      for (const Function& fn : kFunctions) candidates.emplace_back(fn.name);
      const size_t op = text_.find_last_of("*/", pos);
      Fail(fmt::format("'{}' was read as a unit: a name after a unit and '{}' continues the unit, "
                       "and '{}' is not a unit, a parameter, a variable or a function{}; to "
                       "multiply by something else write ({}) {} ...",
                       Trimmed(suffix_->unit, pos + name.size()), text_[op], s,
                       DidYouMeanHint(SuggestNames(name, candidates)), Trimmed(suffix_->value, op),
                       text_[op]),
           pos);
    }
    Fail("unknown unit '" + s + "'" + DidYouMeanHint(SuggestUnitNames(name)), pos);
  }

  // ---- emission -------------------------------------------------------------------------

  void Emit(int i, std::vector<Instruction>& out, int& depth, int& max_depth,
            int& variable_count) const {
    const Node& n = nodes_[i];
    if (n.op == kConst || n.op == kVar) {
      out.push_back(Instruction{n.op, n.index, n.value});
      if (n.op == kVar) variable_count = std::max(variable_count, n.index + 1);
      max_depth = std::max(max_depth, ++depth);
      return;
    }
    Emit(n.a, out, depth, max_depth, variable_count);
    if (IsBinary(n.op)) {
      Emit(n.b, out, depth, max_depth, variable_count);
      --depth;
    }
    out.push_back(Instruction{n.op, n.index, 0.0});
  }

  std::string_view text_;
  const SymbolResolver* resolver_;
  const SymbolNames* symbol_names_;

  std::vector<std::string> SymbolNameList() const {
    return symbol_names_ != nullptr && *symbol_names_ ? (*symbol_names_)()
                                                      : std::vector<std::string>();
  }
  bool IsListedSymbol(std::string_view name) const {
    const std::vector<std::string> names = SymbolNameList();
    return std::find(names.begin(), names.end(), name) != names.end();
  }
  std::vector<Node> nodes_;
  Token tok_;
  Token prev_;
  bool has_prev_ = false;
  /// While a unit suffix is read (MaybeUnitSuffix): where its value's text and the unit start.
  struct Suffix {
    size_t value = 0;
    size_t unit = 0;
  };
  std::optional<Suffix> suffix_;
  /// Set when a unit suffix took a parameter's or variable's name as a unit.
  std::string unit_note_;

  /// text_[begin, end) without the spaces around it.
  std::string Trimmed(size_t begin, size_t end) const {
    std::string_view t = text_.substr(begin, end > begin ? end - begin : 0);
    while (!t.empty() && std::isspace(static_cast<unsigned char>(t.front()))) t.remove_prefix(1);
    while (!t.empty() && std::isspace(static_cast<unsigned char>(t.back()))) t.remove_suffix(1);
    return std::string(t);
  }
  int nesting_ = 0;
};

Expression Expression::Parse(std::string_view text, const SymbolResolver& resolver,
                             const SymbolNames& symbol_names) {
  return ExpressionCompiler(text, &resolver, &symbol_names).Compile();
}

double Expression::Evaluate(std::span<const double> variables) const {
  if (static_cast<int>(variables.size()) < variable_count_) {
    throw std::invalid_argument(fmt::format("expression '{}' needs {} variable values, got {}",
                                            text_, variable_count_, variables.size()));
  }
  return ExpressionCompiler::Run(program_.data(), program_.size(), variables.data());
}

Quantity EvaluateQuantity(std::string_view text, const SymbolResolver& resolver,
                          const SymbolNames& symbol_names) {
  const Expression e = Expression::Parse(text, resolver, symbol_names);
  if (!e.is_constant()) {
    throw ExpressionError("a constant is needed here, but the expression depends on a variable", 0);
  }
  return Quantity{e.Evaluate(), e.dimension()};
}

Quantity ParseUnitSuffix(std::string_view text) {
  return ExpressionCompiler(text, nullptr, nullptr).CompileUnit();
}

}  // namespace chasles
