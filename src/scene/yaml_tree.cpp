#include "internal/yaml_tree.h"

#include <yaml.h>

#include <array>
#include <stdexcept>
#include <unordered_map>

#include <fmt/format.h>

#include "chasles/scene/scene_error.h"

namespace chasles::scene_internal {

// ---- YamlNode ----

YamlNode::Type YamlNode::type() const {
  return index_ == kNone ? Type::kUndefined : doc_->nodes_[index_].type;
}

std::string_view YamlNode::Scalar() const {
  if (!IsScalar()) return {};
  const YamlDocument::Entry& e = doc_->nodes_[index_];
  return std::string_view(doc_->text_).substr(e.first, e.count);
}

YamlMark YamlNode::Mark() const {
  if (index_ == kNone) return {};
  const YamlDocument::Entry& e = doc_->nodes_[index_];
  return {e.line, e.column, e.pos};
}

bool YamlNode::Quoted() const {
  return IsScalar() && doc_->nodes_[index_].quoted;
}

bool YamlNode::Flow() const {
  return index_ != kNone && doc_->nodes_[index_].flow;
}

size_t YamlNode::size() const {
  return IsSequence() || IsMap() ? doc_->nodes_[index_].count : 0;
}

YamlNode YamlNode::Child(size_t k) const {
  return {doc_, doc_->children_[doc_->nodes_[index_].first + k]};
}

YamlNode YamlNode::operator[](size_t i) const {
  return IsSequence() && i < size() ? Child(i) : YamlNode();
}

YamlNode YamlNode::operator[](std::string_view key) const {
  if (!IsMap()) return {};
  for (size_t i = 0, n = size(); i < n; ++i) {
    const YamlNode k = Child(2 * i);
    if (k.IsScalar() && k.Scalar() == key) return Child(2 * i + 1);
  }
  return {};
}

std::pair<YamlNode, YamlNode> YamlNode::PairIterator::operator*() const {
  return {map_->Child(2 * i_), map_->Child(2 * i_ + 1)};
}

// ---- YamlDocument ----

YamlDocument::Index YamlDocument::Add(const Entry& e) {
  nodes_.push_back(e);
  return static_cast<Index>(nodes_.size() - 1);
}

YamlDocument::Index YamlDocument::AddScalar(std::string_view text, YamlMark mark, bool quoted) {
  const size_t first = text_.size();
  // Offsets are 32-bit: the scalars of a scene file (capped at 16 MiB by default) are far from it.
  if (first + text.size() > 0xFFFFFFFFu) throw std::length_error("YAML text over 4 GiB");
  text_.append(text);
  return Add({YamlNode::Type::kScalar, quoted, false, static_cast<Index>(first),
              static_cast<Index>(text.size()), mark.line, mark.column,
              static_cast<std::uint32_t>(mark.pos)});
}

YamlDocument::Index YamlDocument::AddNull(YamlMark mark) {
  return Add({YamlNode::Type::kNull, false, false, 0, 0, mark.line, mark.column,
              static_cast<std::uint32_t>(mark.pos)});
}

YamlDocument::Index YamlDocument::AddSequence(const std::vector<Index>& items) {
  const auto first = static_cast<Index>(children_.size());
  children_.insert(children_.end(), items.begin(), items.end());
  return Add({YamlNode::Type::kSequence, false, false, first, static_cast<Index>(items.size())});
}

YamlDocument::Index YamlDocument::AddMap(const std::vector<std::pair<Index, Index>>& pairs) {
  const auto first = static_cast<Index>(children_.size());
  for (const auto& [k, v] : pairs) {
    children_.push_back(k);
    children_.push_back(v);
  }
  return Add({YamlNode::Type::kMap, false, false, first, static_cast<Index>(pairs.size())});
}

// ---- Parsing ----

namespace {

constexpr size_t kMaxDepth = 1000;

/// libyaml counts characters; the scene's places count bytes (as the UTF-8 check and the
/// upgrade's edits do). Marks come in text order, so one cursor walks the text once.
class Places {
 public:
  explicit Places(std::string_view text) : text_(text) {}

  YamlMark At(size_t char_index) {
    while (chars_ < char_index && byte_ < text_.size()) Forward();
    while (chars_ > char_index) Back();
    return {line_, static_cast<int>(byte_ - line_start_), byte_};
  }
  /// The place of a byte offset (libyaml's reader errors give one).
  YamlMark AtByte(size_t byte) {
    while (byte_ < byte && byte_ < text_.size()) Forward();
    while (byte_ > byte) Back();
    return {line_, static_cast<int>(byte_ - line_start_), byte_};
  }

 private:
  static bool Continuation(char c) { return (static_cast<unsigned char>(c) & 0xC0) == 0x80; }
  void Forward() {
    const char c = text_[byte_++];
    while (byte_ < text_.size() && Continuation(text_[byte_])) ++byte_;
    ++chars_;
    if (c == '\n') {
      ++line_;
      line_start_ = byte_;
    }
  }
  void Back() {
    --byte_;
    while (byte_ > 0 && Continuation(text_[byte_])) --byte_;
    --chars_;
    if (text_[byte_] == '\n') {
      --line_;
      const size_t previous = byte_ == 0 ? std::string_view::npos : text_.rfind('\n', byte_ - 1);
      line_start_ = previous == std::string_view::npos ? 0 : previous + 1;
    }
  }

  std::string_view text_;
  size_t byte_ = 0;
  size_t chars_ = 0;
  int line_ = 0;
  size_t line_start_ = 0;
};

/// Frees libyaml's parser however the parse ends.
struct Parser {
  yaml_parser_t p;
  Parser() { yaml_parser_initialize(&p); }
  ~Parser() { yaml_parser_delete(&p); }
  Parser(const Parser&) = delete;
  Parser& operator=(const Parser&) = delete;
};
struct Event {
  yaml_event_t e{};
  ~Event() { yaml_event_delete(&e); }
};

bool IsNullText(const unsigned char* v, size_t n) {
  const std::string_view s(reinterpret_cast<const char*>(v), n);
  return s.empty() || s == "~" || s == "null" || s == "Null" || s == "NULL";
}

}  // namespace

/// Turns libyaml's events into a YamlDocument.
class YamlBuilder {
 public:
  YamlBuilder(std::string_view text, const std::string& name) : places_(text), name_(name) {}

  YamlDocument Build(std::string_view text) {
    // Room for the densest text likely ("[1, 2, 3]": a node per three bytes) up front, so the
    // arrays are not copied as they grow; pages never written are never touched.
    doc_.nodes_.reserve(text.size() / 3 + 16);
    doc_.children_.reserve(text.size() / 3 + 16);
    doc_.text_.reserve(text.size());
    Parser parser;
    yaml_parser_set_input_string(&parser.p, reinterpret_cast<const unsigned char*>(text.data()),
                                 text.size());
    yaml_parser_set_encoding(&parser.p, YAML_UTF8_ENCODING);
    for (;;) {
      Event ev;
      if (!yaml_parser_parse(&parser.p, &ev.e)) SyntaxError(parser.p);
      if (ev.e.type == YAML_STREAM_END_EVENT) break;
      OnEvent(ev.e);
    }
    return std::move(doc_);
  }

 private:
  struct Frame {
    YamlDocument::Index node;
    size_t first_pending;
  };

  [[noreturn]] void Fail(const YamlMark& at, const std::string& message) {
    throw SceneError(name_, at.line + 1, at.column + 1, "", message);
  }

  [[noreturn]] void SyntaxError(const yaml_parser_t& p) {
    const std::string problem = p.problem ? p.problem : "unreadable text";
    if (p.error == YAML_READER_ERROR) {
      Fail(places_.AtByte(p.problem_offset), "this is not valid YAML: " + problem);
    }
    std::string context;
    if (p.context) {
      const YamlMark c = places_.At(p.context_mark.index);
      context = fmt::format(" ({} that starts at line {}, column {})", p.context, c.line + 1,
                            c.column + 1);
    }
    // libyaml names the token it missed; in a block the usual cause is a line indented unlike
    // its siblings.
    const bool block =
        p.context && std::string_view(p.context).find("block") != std::string_view::npos;
    Fail(places_.At(p.problem_mark.index),
         "this is not valid YAML: " + problem + context +
             (block ? "; check this line's indentation against the lines above it" : ""));
  }

  void OnEvent(const yaml_event_t& e) {
    switch (e.type) {
      case YAML_DOCUMENT_START_EVENT:
        if (documents_ > 0) {
          Fail(places_.At(e.start_mark.index),
               "a second YAML document starts here; a scene file holds one document (remove "
               "this '---' and what follows, or put it in its own file)");
        }
        break;
      case YAML_DOCUMENT_END_EVENT:
        ++documents_;
        break;
      case YAML_SCALAR_EVENT:
        OnScalar(e);
        break;
      case YAML_ALIAS_EVENT:
        OnAlias(e);
        break;
      case YAML_SEQUENCE_START_EVENT:
        Open(e, YamlNode::Type::kSequence, e.data.sequence_start.anchor,
             e.data.sequence_start.style == YAML_FLOW_SEQUENCE_STYLE);
        break;
      case YAML_MAPPING_START_EVENT:
        Open(e, YamlNode::Type::kMap, e.data.mapping_start.anchor,
             e.data.mapping_start.style == YAML_FLOW_MAPPING_STYLE);
        break;
      case YAML_SEQUENCE_END_EVENT:
      case YAML_MAPPING_END_EVENT:
        Close();
        break;
      default:
        break;
    }
  }

  void OnScalar(const yaml_event_t& e) {
    const auto& s = e.data.scalar;
    const YamlMark mark = places_.At(e.start_mark.index);
    const bool plain = s.style == YAML_PLAIN_SCALAR_STYLE || s.style == YAML_ANY_SCALAR_STYLE;
    // An untagged plain empty, ~ or null is YAML's null (the core schema).
    const YamlDocument::Index node =
        plain && s.tag == nullptr && IsNullText(s.value, s.length)
            ? doc_.AddNull(mark)
            : doc_.AddScalar(std::string_view(reinterpret_cast<const char*>(s.value), s.length),
                             mark, !plain);
    if (s.anchor) anchors_[reinterpret_cast<const char*>(s.anchor)] = node;
    Append(node);
  }

  void OnAlias(const yaml_event_t& e) {
    const auto* anchor = reinterpret_cast<const char*>(e.data.alias.anchor);
    const auto it = anchors_.find(anchor);
    if (it == anchors_.end()) {
      Fail(places_.At(e.start_mark.index),
           fmt::format("this is not valid YAML: the alias *{} names no anchor &{} defined "
                       "before it",
                       anchor, anchor));
    }
    Append(it->second);
  }

  void Open(const yaml_event_t& e, YamlNode::Type type, const unsigned char* anchor, bool flow) {
    const YamlMark mark = places_.At(e.start_mark.index);
    if (frames_.size() >= kMaxDepth) {
      Fail(mark, fmt::format("this YAML nests lists and mappings more than {} levels deep; a "
                             "scene needs a few",
                             kMaxDepth));
    }
    YamlDocument::Entry entry;
    entry.type = type;
    entry.flow = flow;
    entry.line = mark.line;
    entry.column = mark.column;
    entry.pos = static_cast<std::uint32_t>(mark.pos);
    frames_.push_back({doc_.Add(entry), pending_.size()});
    open_anchors_.push_back(anchor ? reinterpret_cast<const char*>(anchor) : std::string());
  }

  void Close() {
    const Frame f = frames_.back();
    frames_.pop_back();
    YamlDocument::Entry& entry = doc_.nodes_[f.node];
    entry.first = static_cast<YamlDocument::Index>(doc_.children_.size());
    const size_t n = pending_.size() - f.first_pending;
    entry.count = static_cast<YamlDocument::Index>(entry.type == YamlNode::Type::kMap ? n / 2 : n);
    doc_.children_.insert(doc_.children_.end(), pending_.begin() + f.first_pending, pending_.end());
    pending_.resize(f.first_pending);
    // An anchor on a container is known only once it is complete: an alias inside it would
    // make the tree a cycle.
    if (!open_anchors_.back().empty()) anchors_[open_anchors_.back()] = f.node;
    open_anchors_.pop_back();
    Append(f.node);
  }

  void Append(YamlDocument::Index node) {
    if (frames_.empty()) {
      doc_.SetRoot(node);
    } else {
      pending_.push_back(node);
    }
  }

  Places places_;
  const std::string& name_;
  YamlDocument doc_;
  std::vector<Frame> frames_;
  std::vector<YamlDocument::Index> pending_;
  std::vector<std::string> open_anchors_;
  std::unordered_map<std::string, YamlDocument::Index> anchors_;
  int documents_ = 0;
};

YamlDocument ParseYaml(std::string_view text, const std::string& name) {
  // libyaml told the text is UTF-8 reads a byte-order mark as a character of the document;
  // places count from after it.
  if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);
  // Places and offsets are 32-bit (a scene file is capped at 16 MiB by default).
  if (text.size() > 0xFFFFFFFFu) throw std::length_error("YAML text over 4 GiB");
  YamlBuilder builder(text, name);
  return builder.Build(text);
}

bool DecodeBool(const YamlNode& node, bool& out) {
  if (!node.IsScalar()) return false;
  const std::string_view s = node.Scalar();
  static constexpr std::array<std::pair<std::string_view, bool>, 8> kWords = {{{"y", true},
                                                                               {"n", false},
                                                                               {"yes", true},
                                                                               {"no", false},
                                                                               {"true", true},
                                                                               {"false", false},
                                                                               {"on", true},
                                                                               {"off", false}}};
  for (const auto& [word, value] : kWords) {
    if (s.size() != word.size()) continue;
    std::string lower(s), upper = std::string(word), capital = std::string(word);
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (lower != word) continue;
    for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    capital[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(capital[0])));
    if (s == word || s == upper || s == capital) {
      out = value;
      return true;
    }
  }
  return false;
}

}  // namespace chasles::scene_internal
