#pragma once
/// @file
/// Shared pieces of the mesh readers: a scanner over a file's bytes that never allocates per
/// token, strict number parsing, and the error every reader throws. Line numbers are counted
/// only when an error is reported, so the fast path does no bookkeeping per line.

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/files/mesh_reader.h"

namespace chasles::internal {

/// Throws InputError "mesh file 'NAME': WHAT".
[[noreturn]] inline void MeshFail(std::string_view name, std::string_view what) {
  throw InputError(fmt::format("mesh file '{}': {}", name, what));
}

/// 1 + the number of line feeds before `pos`; the end of a text whose last line ends with a
/// line feed counts as that last line (where an editor shows a file cut short).
inline std::size_t LineAt(std::string_view text, std::size_t pos) {
  pos = std::min(pos, text.size());
  if (pos == text.size() && pos > 0 && text[pos - 1] == '\n') --pos;
  return 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + pos, '\n'));
}

/// Parses all of `tok` as a double (an optional leading '+' is accepted, as printf writes it).
/// Infinities and NaN parse; the callers decide whether they are allowed.
inline bool ParseDouble(std::string_view tok, double& out) {
  if (!tok.empty() && tok[0] == '+') tok.remove_prefix(1);
  if (tok.empty()) return false;
  const auto [end, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), out);
  return ec == std::errc() && end == tok.data() + tok.size();
}

/// Parses all of `tok` as a decimal integer (optional sign).
inline bool ParseInt(std::string_view tok, std::int64_t& out) {
  if (!tok.empty() && tok[0] == '+') tok.remove_prefix(1);
  if (tok.empty()) return false;
  const auto [end, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), out);
  return ec == std::errc() && end == tok.data() + tok.size();
}

/// True when `v` may be a mesh coordinate: finite and within ±kMaxMeshCoordinate.
inline bool IsMeshCoordinate(double v) {
  return std::abs(v) <= kMaxMeshCoordinate;  // false for NaN and the infinities too
}

/// How a rejected coordinate is described in messages.
inline constexpr std::string_view kCoordinateRule = "not a finite number within ±3.4e38";

/// Walks a text mesh file token by token. Tokens are runs of characters other than space,
/// tab, CR, LF (and the comment character, which starts a comment running to the end of the
/// line). Errors name the file and the line of the position they concern.
class TextScanner {
 public:
  TextScanner(std::string_view text, std::string_view name, char comment = '\0')
      : text_(text), name_(name), comment_(comment) {}

  std::size_t pos() const { return pos_; }
  void Seek(std::size_t pos) { pos_ = std::min(pos, text_.size()); }
  bool AtEnd() const { return pos_ >= text_.size(); }
  std::size_t Remaining() const { return text_.size() - pos_; }
  std::string_view name() const { return name_; }
  std::string_view text() const { return text_; }

  /// Skips spaces, tabs, CRs and a comment, staying on the current line.
  void SkipBlanks() {
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
        ++pos_;
      } else if (comment_ != '\0' && c == comment_) {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
      } else {
        return;
      }
    }
  }
  /// Skips all white space, line ends and comments.
  void SkipSpace() {
    for (;;) {
      SkipBlanks();
      if (pos_ < text_.size() && text_[pos_] == '\n') {
        ++pos_;
      } else {
        return;
      }
    }
  }
  /// After SkipBlanks: true at a line feed or at the end of the text.
  bool AtLineEnd() {
    SkipBlanks();
    return pos_ >= text_.size() || text_[pos_] == '\n';
  }
  /// Moves past the next line feed (or to the end).
  void SkipLine() {
    const std::size_t nl = text_.find('\n', pos_);
    pos_ = nl == std::string_view::npos ? text_.size() : nl + 1;
  }
  /// The next token on the current line; empty at the end of the line.
  std::string_view TokenOnLine() {
    SkipBlanks();
    return TakeToken();
  }
  /// The next token, across line ends; empty at the end of the text.
  std::string_view Token() {
    SkipSpace();
    return TakeToken();
  }

  std::size_t Line(std::size_t pos) const { return LineAt(text_, pos); }
  std::size_t Line() const { return Line(pos_); }

  /// Throws "mesh file 'NAME': WHAT (line N)" for the line holding `pos`.
  [[noreturn]] void FailAt(std::size_t pos, std::string_view what) const {
    MeshFail(name_, fmt::format("{} (line {})", what, Line(pos)));
  }
  [[noreturn]] void Fail(std::string_view what) const { FailAt(pos_, what); }

  /// A number token on the current line, named `what` in the error when it is missing or not
  /// a number. Returns the token's start in `at`.
  double NumberOnLine(std::string_view what, std::size_t* at = nullptr) {
    SkipBlanks();
    const std::size_t start = pos_;
    const std::string_view tok = TakeToken();
    if (at != nullptr) *at = start;
    if (tok.empty()) FailAt(start, fmt::format("{} is missing", what));
    double v = 0;
    if (!ParseDouble(tok, v))
      FailAt(start, fmt::format("{}: '{}' is not a number", what, Short(tok)));
    return v;
  }
  /// A coordinate on the current line: the double nearest to its text, finite and within
  /// ±kMaxMeshCoordinate.
  double CoordinateOnLine(std::string_view what) {
    std::size_t at = 0;
    const double v = NumberOnLine(what, &at);
    if (!IsMeshCoordinate(v)) {
      FailAt(at, fmt::format("{} is {}, {}", what, Short(text_.substr(at, TokenLength(at))),
                             kCoordinateRule));
    }
    return v;
  }
  /// An integer token; `same_line` keeps it on the current line.
  std::int64_t Integer(std::string_view what, bool same_line) {
    if (same_line) {
      SkipBlanks();
    } else {
      SkipSpace();
    }
    const std::size_t start = pos_;
    const std::string_view tok = TakeToken();
    if (tok.empty()) {
      FailAt(start, AtEnd() ? fmt::format("truncated: the file ends where {} was expected", what)
                            : fmt::format("{} is missing", what));
    }
    std::int64_t v = 0;
    if (!ParseInt(tok, v))
      FailAt(start, fmt::format("{}: '{}' is not an integer", what, Short(tok)));
    return v;
  }

  /// At most 40 characters of a token, for messages.
  static std::string Short(std::string_view tok) {
    if (tok.size() <= 40) return std::string(tok);
    return std::string(tok.substr(0, 40)) + "...";
  }

 private:
  bool IsTokenChar(char c) const {
    return c != ' ' && c != '\t' && c != '\r' && c != '\n' && c != '\f' && c != '\v' &&
           (comment_ == '\0' || c != comment_);
  }
  std::string_view TakeToken() {
    const std::size_t start = pos_;
    while (pos_ < text_.size() && IsTokenChar(text_[pos_])) ++pos_;
    return text_.substr(start, pos_ - start);
  }
  std::size_t TokenLength(std::size_t at) const {
    std::size_t n = 0;
    while (at + n < text_.size() && IsTokenChar(text_[at + n])) ++n;
    return n;
  }

  std::string_view text_;
  std::string_view name_;
  char comment_;
  std::size_t pos_ = 0;
};

/// Appends the fan triangulation of a polygon one corner at a time: (v0, v1, v2),
/// (v0, v2, v3), ... A convex or star-shaped-from-v0 polygon is split exactly; its area and
/// the signed volume it bounds are the sums over the fan's triangles.
class FanBuilder {
 public:
  explicit FanBuilder(std::vector<std::uint32_t>& out) : out_(out) {}
  void Start() { n_ = 0; }
  void Add(std::uint32_t v) {
    if (n_ == 0) {
      first_ = v;
    } else if (n_ >= 2) {
      out_.push_back(first_);
      out_.push_back(prev_);
      out_.push_back(v);
    }
    prev_ = v;
    ++n_;
  }

 private:
  std::vector<std::uint32_t>& out_;
  std::uint32_t first_ = 0, prev_ = 0;
  std::size_t n_ = 0;
};

}  // namespace chasles::internal
