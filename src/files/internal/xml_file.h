#pragma once
/// @file
/// The strict XML layer under the robot and Collada readers: pugixml parses the bytes in place
/// (so every attribute value and element text keeps its byte offset, which gives its line and
/// lets a fix rewrite it), and this class refuses what pugixml would let through: entity
/// declarations and references other than XML's five and character references (pugixml never
/// expands them; refusing them says so instead of reading "&x;" as text), documents deeper or
/// larger than the limits, and numbers that are not finite or are beyond any physical scale.
/// Every error is an InputError "NAME:LINE: WHAT".

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include <pugixml.hpp>

#include "chasles/files/robot_model.h"
#include "chasles/math/types.h"

namespace chasles::internal {

/// Largest robot or Collada file read [bytes].
inline constexpr std::size_t kMaxXmlBytes = std::size_t{512} << 20;
/// Deepest nesting of elements.
inline constexpr int kMaxXmlDepth = 200;
/// Largest magnitude of a number in a robot file (a length in m, a mass in kg, an inertia in
/// kg·m², a scale): far beyond any robot (sdformat writes ±1e16 for the limits of a continuous
/// joint), and small enough that no product of a few of them overflows.
inline constexpr double kMaxRobotNumber = 1e18;

/// The bytes of a file, or an InputError "what 'PATH': cannot be opened ..." / "... is larger
/// than N bytes".
std::string ReadFileBytes(const std::string& path, std::string_view what, std::size_t max_bytes);

class XmlFile {
 public:
  /// Parses `bytes`; `name` is what errors call the file. Throws InputError on malformed XML
  /// (with pugixml's description and the line), entity declarations or undefined entity
  /// references, and nesting deeper than kMaxXmlDepth.
  XmlFile(std::string bytes, std::string name);
  XmlFile(const XmlFile&) = delete;
  XmlFile& operator=(const XmlFile&) = delete;

  /// The root element.
  pugi::xml_node root() const { return doc_.document_element(); }
  /// The file's name as errors give it, and its bytes as read.
  const std::string& name() const { return name_; }
  const std::string& original() const { return original_; }

  /// 1-based line of a byte offset, of an element, of an attribute.
  int LineAt(std::size_t offset) const;
  int Line(pugi::xml_node node) const;
  int Line(pugi::xml_attribute attr) const;
  /// The bytes of an attribute's value, or of an element's text, in the original file
  /// (leading and trailing white space excluded).
  TextSpan Span(pugi::xml_attribute attr) const;
  TextSpan TextSpanOf(pugi::xml_node element) const;
  /// Byte offset of an element's '<', and just after the '>' of its start tag.
  std::size_t Begin(pugi::xml_node element) const;
  std::size_t StartTagEnd(pugi::xml_node element) const;

  /// Throws InputError "NAME:LINE: WHAT" at `line`.
  [[noreturn]] void Fail(int line, std::string_view what) const;
  [[noreturn]] void Fail(pugi::xml_node node, std::string_view what) const {
    Fail(Line(node), what);
  }

  /// The numbers of an attribute (white-space separated), each finite and within
  /// kMaxRobotNumber; `count` of them (0: any number of them). Errors name the element,
  /// the attribute and the line.
  std::vector<double> Numbers(pugi::xml_node element, const char* attribute,
                              std::size_t count) const;
  /// The same for an element's text.
  std::vector<double> TextNumbers(pugi::xml_node element, std::size_t count) const;
  /// One number: the attribute's, or `fallback` when the attribute is absent.
  double Number(pugi::xml_node element, const char* attribute, double fallback) const;
  /// One number that must be there.
  double RequiredNumber(pugi::xml_node element, const char* attribute) const;
  /// Three numbers, or `fallback` when the attribute is absent.
  Vec3 Vector(pugi::xml_node element, const char* attribute, const Vec3& fallback) const;
  /// An attribute that must be there and not be empty.
  std::string RequiredText(pugi::xml_node element, const char* attribute) const;

  /// Parses `text` (the value of something at `line`, called `what` in errors) as numbers.
  std::vector<double> ParseNumbers(std::string_view text, int line, std::string_view what,
                                   std::size_t count) const;

 private:
  void CheckEntities() const;
  void CheckDepth() const;

  std::string name_;
  std::string original_;
  std::string buffer_;  // parsed in place by pugixml: strings point into it
  pugi::xml_document doc_;
  std::vector<std::size_t> line_starts_;
};

}  // namespace chasles::internal
