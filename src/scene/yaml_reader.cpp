#include "internal/yaml_reader.h"

#include <algorithm>
#include <charconv>

#include <fmt/format.h>

#include "chasles/suggest.h"

namespace chasles::scene_internal {

namespace {

// One allocation per path: a scene of 100,000 bodies makes millions of them.
std::string JoinPath(const std::string& path, std::string_view key) {
  std::string joined;
  joined.reserve(path.size() + 1 + key.size());
  joined.append(path);
  if (!path.empty()) joined.push_back('.');
  joined.append(key);
  return joined;
}

}  // namespace

At At::Child(std::string_view key) const {
  At child{node[key], JoinPath(path, key)};
  if (child.node.IsDefined() && child.node.IsNull() && node.IsMap()) {
    for (const auto& kv : node) {
      if (kv.first.IsScalar() && kv.first.Scalar() == key) child.key_mark = kv.first.Mark();
    }
  }
  return child;
}

At At::Item(size_t index) const {
  char digits[24];
  const auto end = std::to_chars(digits, digits + sizeof digits, index).ptr;
  std::string indexed;
  indexed.reserve(path.size() + 2 + static_cast<size_t>(end - digits));
  indexed.append(path).append(1, '[').append(digits, end).append(1, ']');
  return At{node[index], std::move(indexed)};
}

bool At::Has(std::string_view key) const {
  return node.IsMap() && node[key].IsDefined();
}

std::string KindOf(const YamlNode& node) {
  switch (node.type()) {
    case YamlNode::Type::kSequence:
      return "a list";
    case YamlNode::Type::kMap:
      return "a mapping";
    case YamlNode::Type::kScalar:
      return fmt::format("the value '{}'", node.Scalar());
    default:
      return "nothing";
  }
}

void Reporter::Fail(const At& at, const std::string& message, size_t offset) const {
  int line = 0;
  int column = 0;
  if (at.node.IsDefined()) {
    const bool empty = at.node.IsNull() && at.key_mark.line >= 0;
    const YamlMark mark = empty ? at.key_mark : at.node.Mark();
    if (mark.line >= 0) {
      line = mark.line + 1;
      column = mark.column + 1;
      // Quoted scalars start one column before their text.
      if (offset > 0 && at.node.IsScalar() && at.node.Quoted()) ++column;
      column += static_cast<int>(offset);
    }
  }
  throw SceneError(file_, line, column, at.path, message);
}

void Reporter::CheckMap(const At& at, const std::vector<std::string>& allowed,
                        std::string_view what) const {
  if (!at.node.IsMap()) {
    Fail(at,
         fmt::format("expected {} (a mapping of keys to values), got {}", what, KindOf(at.node)));
  }
  // Nothing is allocated unless a key is wrong: a mapping has a handful of keys, so a repeat is
  // found by comparing with the keys before it.
  const size_t n = at.node.size();
  size_t k = 0;
  for (auto it = at.node.begin(); k < n; ++it, ++k) {
    const YamlNode key_node = (*it).first;
    if (!key_node.IsScalar()) Fail(At{key_node, at.path}, "keys must be plain names");
    const std::string_view key = key_node.Scalar();
    const auto named = [&] { return At{key_node, JoinPath(at.path, key)}; };
    size_t j = 0;
    for (auto before = at.node.begin(); j < k; ++before, ++j) {
      const YamlNode earlier = (*before).first;
      if (earlier.IsScalar() && earlier.Scalar() == key) {
        Fail(named(), fmt::format("key '{}' appears twice", key));
      }
    }
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
      std::string known;
      for (const auto& a : allowed) known += (known.empty() ? "" : ", ") + a;
      Fail(named(), fmt::format("unknown key '{}'{} in {}; known keys: {}", key,
                                DidYouMean(key, allowed), what, known));
    }
  }
}

At Reporter::Require(const At& at, std::string_view key, std::string_view what) const {
  if (!at.Has(key)) Fail(at, fmt::format("{} needs the key '{}'", what, key));
  return at.Child(key);
}

std::string Reporter::Text(const At& at, std::string_view what) const {
  if (!at.node.IsScalar()) Fail(at, fmt::format("expected {}, got {}", what, KindOf(at.node)));
  if (at.node.Scalar().empty()) Fail(at, fmt::format("expected {}, got an empty value", what));
  return std::string(at.node.Scalar());
}

void Reporter::CheckSequence(const At& at, std::string_view what) const {
  if (!at.node.IsSequence()) Fail(at, fmt::format("expected {}, got {}", what, KindOf(at.node)));
}

}  // namespace chasles::scene_internal
