#pragma once
/// @file
/// A YAML document as a tree of nodes that know their place in the file. libyaml's event parser
/// reads the text; the nodes are built in one pass into three flat arrays (nodes, child indices,
/// scalar texts). Private to the scene layer.
///
/// Why not a YAML library's own node tree: yaml-cpp's took 6 s and 1 GB for a 100 000-body scene
/// (several heap objects and reference-counted pointers per node, a key looked up through them);
/// here a node is 32 bytes in one array, the scalars' texts share one buffer, and looking a
/// key up compares strings in place (docs/reliability-limits.md, "Loading cost").

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace chasles::scene_internal {

/// A place in the text: 0-based line and column (the column counts bytes) and the byte offset,
/// all counted from after a byte-order mark. line < 0: no place (text not from a file).
struct YamlMark {
  YamlMark() = default;
  YamlMark(int line_, int column_, size_t pos_) : line(line_), column(column_), pos(pos_) {}
  int line = -1;
  int column = -1;
  size_t pos = 0;
};

class YamlDocument;

/// A view of one node of a YamlDocument (which must outlive it), or of no node ("undefined":
/// the value of a key that is not there).
class YamlNode {
 public:
  enum class Type : std::uint8_t { kUndefined, kNull, kScalar, kSequence, kMap };

  YamlNode() = default;

  Type type() const;
  bool IsDefined() const { return type() != Type::kUndefined; }
  explicit operator bool() const { return IsDefined(); }
  /// An empty value, `~` or `null` (unquoted).
  bool IsNull() const { return type() == Type::kNull; }
  bool IsScalar() const { return type() == Type::kScalar; }
  bool IsSequence() const { return type() == Type::kSequence; }
  bool IsMap() const { return type() == Type::kMap; }

  /// The text of a scalar; "" for any other node. Valid as long as the document.
  std::string_view Scalar() const;
  YamlMark Mark() const;
  /// A scalar written in quotes (its mark is the opening quote's).
  bool Quoted() const;
  /// A sequence or mapping written in flow style, [..] or {..}.
  bool Flow() const;
  /// Items of a sequence, pairs of a mapping; 0 for anything else.
  size_t size() const;

  /// The i-th item of a sequence; undefined past the end or for anything else.
  YamlNode operator[](size_t i) const;
  /// The value of the first pair of a mapping whose key is the scalar `key`; undefined if none.
  YamlNode operator[](std::string_view key) const;
  YamlNode operator[](const char* key) const { return (*this)[std::string_view(key)]; }
  YamlNode operator[](const std::string& key) const { return (*this)[std::string_view(key)]; }

  /// A mapping's pairs in file order: `for (const auto& kv : node)` gives kv.first, kv.second.
  class PairIterator {
   public:
    std::pair<YamlNode, YamlNode> operator*() const;
    PairIterator& operator++() {
      ++i_;
      return *this;
    }
    bool operator!=(const PairIterator& o) const { return i_ != o.i_; }

   private:
    friend class YamlNode;
    PairIterator(const YamlNode* map, size_t i) : map_(map), i_(i) {}
    const YamlNode* map_;
    size_t i_;
  };
  PairIterator begin() const { return {this, 0}; }
  PairIterator end() const { return {this, IsMap() ? size() : 0}; }

 private:
  friend class YamlDocument;
  static constexpr std::uint32_t kNone = 0xFFFFFFFFu;
  YamlNode(const YamlDocument* doc, std::uint32_t index) : doc_(doc), index_(index) {}
  YamlNode Child(size_t k) const;

  const YamlDocument* doc_ = nullptr;
  std::uint32_t index_ = kNone;
};

/// The nodes of one document. Built by ParseYaml, or by hand (a scene assembled from command-
/// line options) with the Add functions, which return the new node's index.
class YamlDocument {
 public:
  using Index = std::uint32_t;

  /// The document's root: the value of a one-scalar document, or undefined when empty.
  YamlNode Root() const { return YamlNode(this, root_); }

  Index AddScalar(std::string_view text, YamlMark mark = {}, bool quoted = false);
  Index AddNull(YamlMark mark = {});
  Index AddSequence(const std::vector<Index>& items);
  Index AddMap(const std::vector<std::pair<Index, Index>>& pairs);
  void SetRoot(Index root) { root_ = root; }

 private:
  friend class YamlNode;
  friend class YamlBuilder;
  struct Entry {
    YamlNode::Type type = YamlNode::Type::kUndefined;
    bool quoted = false;
    bool flow = false;
    /// A scalar's offset in text_; a container's first child in children_ (a mapping's
    /// children are key, value, key, value...).
    Index first = 0;
    /// A scalar's length; a container's items (a mapping's pairs).
    Index count = 0;
    int line = -1;
    int column = -1;
    /// 32 bits, as the offsets (ParseYaml refuses a text of 4 GiB or more): 24 bytes a node.
    std::uint32_t pos = 0;
  };
  Index Add(const Entry& e);

  std::vector<Entry> nodes_;
  std::vector<Index> children_;
  std::string text_;
  Index root_ = YamlNode::kNone;
};

/// Parses `text` (checked UTF-8) as one YAML document. A syntax error, a second document, an
/// alias of an anchor not defined before it or nesting deeper than 1000 levels is a SceneError
/// naming `name` and the place.
YamlDocument ParseYaml(std::string_view text, const std::string& name);

/// YAML 1.1's booleans as scene files write them: true/false, yes/no, on/off, y/n, each all
/// lower case, all upper case or capitalised. False (and `out` untouched) for anything else.
bool DecodeBool(const YamlNode& node, bool& out);

}  // namespace chasles::scene_internal
