// The strict XML layer of the robot and Collada readers (files/internal/xml_file.h).

#include "files/internal/xml_file.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <system_error>
#include <utility>

#include <fmt/format.h>

#include "chasles/error.h"

namespace chasles::internal {

namespace {

bool IsSpace(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

/// The first `limit` bytes of `text` from `pos` shown in a message, cut at a line end.
std::string Excerpt(std::string_view text, std::size_t pos, std::size_t limit = 40) {
  std::string out;
  for (std::size_t i = pos; i < text.size() && out.size() < limit; ++i) {
    if (text[i] == '\n' || text[i] == '\r') break;
    out += text[i];
  }
  return out;
}

}  // namespace

std::string ReadFileBytes(const std::string& path, std::string_view what, std::size_t max_bytes) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) {
    throw InputError(fmt::format("{} '{}': no such file", what, path));
  }
  if (!std::filesystem::is_regular_file(status)) {
    throw InputError(fmt::format("{} '{}': not a regular file (a folder or a device)", what, path));
  }
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(fmt::format("{} '{}': cannot read its size", what, path));
  if (size > max_bytes) {
    throw InputError(fmt::format("{} '{}': {} bytes, larger than the limit of {} bytes", what, path,
                                 size, max_bytes));
  }
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!f) {
    throw InputError(fmt::format("{} '{}': cannot be opened for reading ({})", what, path,
                                 std::strerror(errno)));
  }
  std::string bytes(static_cast<std::size_t>(size), '\0');
  bytes.resize(std::fread(bytes.data(), 1, bytes.size(), f.get()));
  if (std::ferror(f.get())) {
    throw InputError(fmt::format("{} '{}': read error ({})", what, path, std::strerror(errno)));
  }
  return bytes;
}

XmlFile::XmlFile(std::string bytes, std::string name)
    : name_(std::move(name)), original_(std::move(bytes)) {
  line_starts_.push_back(0);
  for (std::size_t i = 0; i < original_.size(); ++i) {
    if (original_[i] == '\n') line_starts_.push_back(i + 1);
  }
  if (original_.find('\0') != std::string::npos) {
    Fail(LineAt(original_.find('\0')), "a NUL byte: this is not an XML text file");
  }
  CheckEntities();
  buffer_ = original_;
  // In place and as UTF-8, so that every string pugixml returns points into buffer_ at the
  // offset of its text in the file. parse_eol turns CR LF into LF in place (strings keep their
  // start). No DOCTYPE node: its declarations were refused above.
  const pugi::xml_parse_result r = doc_.load_buffer_inplace(
      buffer_.data(), buffer_.size(), pugi::parse_default, pugi::encoding_utf8);
  if (!r) {
    Fail(LineAt(static_cast<std::size_t>(std::max<std::ptrdiff_t>(r.offset, 0))),
         fmt::format("malformed XML: {}", r.description()));
  }
  if (!root()) Fail(1, "no root element");
  CheckDepth();
}

void XmlFile::CheckEntities() const {
  // Entity declarations (the "billion laughs" and external entities) are refused outright;
  // references other than XML's own five and character references would stay unexpanded.
  // One pass, stepping over comments and CDATA sections (where '&' is text).
  const std::string_view text = original_;
  std::size_t i = 0;
  while (i < text.size()) {
    const std::string_view rest = text.substr(i);
    if (rest.starts_with("<!--") || rest.starts_with("<![CDATA[")) {
      const std::size_t end = text.find(rest[2] == '-' ? "-->" : "]]>", i + 4);
      if (end == std::string_view::npos) break;  // pugixml names the unclosed section
      i = end + 3;
      continue;
    }
    if (rest.starts_with("<!ENTITY")) {
      Fail(LineAt(i),
           "an entity declaration (<!ENTITY ...>): robot and mesh files may not "
           "declare entities, which are never expanded");
    }
    if (rest[0] == '&') {
      const std::size_t end = rest.find(';');
      const std::string_view ref =
          end == std::string_view::npos || end > 12 ? rest.substr(0, 1) : rest.substr(0, end + 1);
      if (!(ref == "&amp;" || ref == "&lt;" || ref == "&gt;" || ref == "&quot;" ||
            ref == "&apos;" || (ref.size() > 3 && ref[1] == '#'))) {
        Fail(LineAt(i), fmt::format("'{}': not one of XML's entity references (&amp; &lt; &gt; "
                                    "&quot; &apos; or a character reference); entities are "
                                    "never expanded",
                                    Excerpt(text, i, 16)));
      }
    }
    ++i;
  }
}

void XmlFile::CheckDepth() const {
  // pugixml parses without recursion; the readers recurse, so the depth is bounded here.
  std::vector<std::pair<pugi::xml_node, int>> stack{{root(), 1}};
  while (!stack.empty()) {
    auto [node, depth] = stack.back();
    stack.pop_back();
    if (depth > kMaxXmlDepth) {
      Fail(node, fmt::format("elements nested deeper than {} levels", kMaxXmlDepth));
    }
    for (pugi::xml_node c = node.first_child(); c; c = c.next_sibling()) {
      if (c.type() == pugi::node_element) stack.emplace_back(c, depth + 1);
    }
  }
}

int XmlFile::LineAt(std::size_t offset) const {
  const auto it = std::upper_bound(line_starts_.begin(), line_starts_.end(), offset);
  return static_cast<int>(it - line_starts_.begin());
}

int XmlFile::Line(pugi::xml_node node) const {
  const std::ptrdiff_t at = node.offset_debug();
  return at < 0 ? 0 : LineAt(static_cast<std::size_t>(at));
}

int XmlFile::Line(pugi::xml_attribute attr) const {
  const TextSpan s = Span(attr);
  return s.found() ? LineAt(s.offset) : 0;
}

TextSpan XmlFile::Span(pugi::xml_attribute attr) const {
  const char* v = attr.value();
  const char* base = buffer_.data();
  if (v < base || v > base + buffer_.size() || v == base) return {};
  const std::size_t start = static_cast<std::size_t>(v - base);
  const char quote = original_[start - 1];
  if (quote != '"' && quote != '\'') return {};
  const std::size_t end = original_.find(quote, start);
  if (end == std::string::npos) return {};
  std::size_t b = start, e = end;
  while (b < e && IsSpace(original_[b])) ++b;
  while (e > b && IsSpace(original_[e - 1])) --e;
  return TextSpan{b, e - b};
}

TextSpan XmlFile::TextSpanOf(pugi::xml_node element) const {
  for (pugi::xml_node c = element.first_child(); c; c = c.next_sibling()) {
    if (c.type() != pugi::node_pcdata) continue;
    const char* v = c.value();
    const char* base = buffer_.data();
    if (v < base || v >= base + buffer_.size()) return {};
    const std::size_t start = static_cast<std::size_t>(v - base);
    std::size_t e = original_.find('<', start);
    if (e == std::string::npos) e = original_.size();
    std::size_t b = start;
    while (b < e && IsSpace(original_[b])) ++b;
    while (e > b && IsSpace(original_[e - 1])) --e;
    return TextSpan{b, e - b};
  }
  return {};
}

std::size_t XmlFile::Begin(pugi::xml_node element) const {
  const std::ptrdiff_t at = element.offset_debug();
  return at <= 0 ? TextSpan::kNone : static_cast<std::size_t>(at) - 1;
}

std::size_t XmlFile::StartTagEnd(pugi::xml_node element) const {
  const std::size_t begin = Begin(element);
  if (begin == TextSpan::kNone) return TextSpan::kNone;
  char quote = 0;
  for (std::size_t i = begin; i < original_.size(); ++i) {
    const char c = original_[i];
    if (quote) {
      if (c == quote) quote = 0;
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '>') {
      return i + 1;
    }
  }
  return TextSpan::kNone;
}

void XmlFile::Fail(int line, std::string_view what) const {
  if (line > 0) throw InputError(fmt::format("{}:{}: {}", name_, line, what));
  throw InputError(fmt::format("{}: {}", name_, what));
}

std::vector<double> XmlFile::ParseNumbers(std::string_view text, int line, std::string_view what,
                                          std::size_t count) const {
  std::vector<double> out;
  std::size_t i = 0;
  while (true) {
    while (i < text.size() && (IsSpace(text[i]) || text[i] == ',')) ++i;
    if (i >= text.size()) break;
    std::size_t j = i;
    while (j < text.size() && !IsSpace(text[j]) && text[j] != ',') ++j;
    std::string_view tok = text.substr(i, j - i);
    if (!tok.empty() && tok[0] == '+') tok.remove_prefix(1);
    double v = 0.0;
    const auto [end, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
    if (tok.empty() || end != tok.data() + tok.size() ||
        (ec != std::errc() && ec != std::errc::result_out_of_range)) {
      Fail(line, fmt::format("{}: '{}' is not a number", what, Excerpt(text, i, 24)));
    }
    if (ec == std::errc::result_out_of_range || !std::isfinite(v) ||
        std::abs(v) > kMaxRobotNumber) {
      Fail(line, fmt::format("{}: {} is not a finite number within ±{:g}", what,
                             Excerpt(text, i, 24), kMaxRobotNumber));
    }
    out.push_back(v);
    if (count > 0 && out.size() > count) break;
    i = j;
  }
  if (count > 0 && out.size() != count) {
    Fail(line, fmt::format("{}: expected {} number{}, found {}", what, count, count == 1 ? "" : "s",
                           out.size() > count ? "more" : std::to_string(out.size())));
  }
  return out;
}

std::vector<double> XmlFile::Numbers(pugi::xml_node element, const char* attribute,
                                     std::size_t count) const {
  const pugi::xml_attribute a = element.attribute(attribute);
  const int line = a ? Line(a) : Line(element);
  return ParseNumbers(a.value(), line > 0 ? line : Line(element),
                      fmt::format("<{} {}>", element.name(), attribute), count);
}

std::vector<double> XmlFile::TextNumbers(pugi::xml_node element, std::size_t count) const {
  return ParseNumbers(element.text().get(), Line(element), fmt::format("<{}>", element.name()),
                      count);
}

double XmlFile::Number(pugi::xml_node element, const char* attribute, double fallback) const {
  if (!element.attribute(attribute)) return fallback;
  return Numbers(element, attribute, 1)[0];
}

double XmlFile::RequiredNumber(pugi::xml_node element, const char* attribute) const {
  if (!element.attribute(attribute)) {
    Fail(element, fmt::format("<{}> needs the attribute '{}'", element.name(), attribute));
  }
  return Numbers(element, attribute, 1)[0];
}

Vec3 XmlFile::Vector(pugi::xml_node element, const char* attribute, const Vec3& fallback) const {
  if (!element.attribute(attribute)) return fallback;
  const std::vector<double> v = Numbers(element, attribute, 3);
  return Vec3(v[0], v[1], v[2]);
}

std::string XmlFile::RequiredText(pugi::xml_node element, const char* attribute) const {
  const std::string v = element.attribute(attribute).value();
  if (v.empty()) {
    Fail(element, fmt::format("<{}> needs a non-empty attribute '{}'", element.name(), attribute));
  }
  return v;
}

}  // namespace chasles::internal
