#pragma once
/// @file
/// The primitive shapes a scene part may name, the keys of their dimensions and how to build
/// them. One table drives the loader, its key checking and the documentation's shape list.

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "chasles/mass/shape.h"
#include "chasles/math/types.h"

namespace chasles::scene_internal {

/// How a dimension is written: one length, a list of lengths, a list of 2-D points, or a
/// switch (true or false, e.g. `closed`).
enum class DimensionKind { kLength, kLengths2, kLengths3, kTriangle2, kFlag };

struct DimensionKey {
  const char* key;
  DimensionKind kind = DimensionKind::kLength;
  /// One line for the format reference, e.g. "radius of the cylinder".
  const char* meaning = "";
  /// True when the key may be left out (a switch then reads false).
  bool optional = false;
};

/// Dimension values read from a part, in metres; a switch is 1 (true) or 0 (false).
struct Dimensions {
  std::map<std::string, std::vector<double>, std::less<>> values;
  double at(std::string_view key, size_t i = 0) const { return values.find(key)->second.at(i); }
  /// Whether the part gave `key` (an optional key may be absent).
  bool has(std::string_view key) const { return values.contains(key); }
  /// A switch: true when given as true.
  bool flag(std::string_view key) const { return has(key) && at(key) != 0.0; }
};

struct ShapeEntry {
  const char* name;
  std::vector<DimensionKey> dimensions;
  /// The dimension that 'from'/'to' give (the length along the shape's z axis), or nullptr
  /// when the shape has no axis to place that way.
  const char* axial_key = nullptr;
  /// For 'from'/'to': true when the shape's origin is at 'from' (cone: the base centre),
  /// false when it is midway.
  bool origin_at_from = false;
  /// Where the shape's frame is and which way its axes point, for the format reference.
  const char* frame = "";
  std::function<std::unique_ptr<Shape>(const Dimensions&)> make;
};

/// The entry for a shape name or alias ("hoop" is "ring"), or nullptr.
const ShapeEntry* FindShape(std::string_view name);
/// Canonical shape names, in the order of the format reference.
const std::vector<std::string>& ShapeNames();
/// Every entry, in the same order.
const std::vector<ShapeEntry>& ShapeTable();

}  // namespace chasles::scene_internal
