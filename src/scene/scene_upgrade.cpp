// A scene file rewritten to the current format version (chasles/scene/scene_upgrade.h): the
// reader records each old version's spelling with the marks of its nodes
// (scene_versions.cpp); here each becomes an edit of the file's bytes at those marks.

#include "chasles/scene/scene_upgrade.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "chasles/scene/scene_error.h"
#include "internal/scene_reader.h"
#include "internal/scene_rewrite.h"
#include "internal/scene_text.h"

namespace chasles {

namespace {

using scene_internal::ScalarSource;
using scene_internal::SceneRewrite;

/// Replace bytes [begin, end) of the text by `text`.
struct TextEdit {
  size_t begin = 0;
  size_t end = 0;
  std::string text;
};

/// Turns the reader's rewrites into edits of `source`, checking that each mark stands where the
/// reader saw the node.
class EditPlanner {
 public:
  EditPlanner(std::string_view source, std::string file)
      : source_(source), file_(std::move(file)) {}

  TextEdit Plan(const SceneRewrite& r) const {
    switch (r.kind) {
      case SceneRewrite::Kind::kVersion:
        return Version(r);
      case SceneRewrite::Kind::kDropZ:
        return DropZ(r);
      case SceneRewrite::Kind::kKeepAdaptive:
        return KeepAdaptive(r);
      case SceneRewrite::Kind::kRename:
        break;
    }
    // A name inside an expression: its bytes in the file are the value's, after the opening
    // quote of a quoted scalar, as long as nothing before it was escaped or folded.
    const size_t at = Pos(r.scalar) + (r.scalar.quoted ? 1 : 0) + r.offset;
    if (source_.substr(at, r.old_text.size()) != r.old_text) {
      Refuse(r, fmt::format("write '{}' in place of '{}' here", r.new_text, r.old_text));
    }
    return {at, at + r.old_text.size(), r.new_text};
  }

 private:
  size_t Pos(const ScalarSource& s) const { return s.mark.line >= 0 ? s.mark.pos : source_.size(); }

  /// The bytes of a scalar in the file, its quotes included.
  std::pair<size_t, size_t> ScalarBytes(const SceneRewrite& r, const ScalarSource& s) const {
    const size_t begin = Pos(s);
    const char open = begin < source_.size() ? source_[begin] : '\0';
    if (open == '\'' || open == '"') {
      // YAML escapes: '' inside single quotes, a backslash inside double quotes.
      for (size_t i = begin + 1; i < source_.size(); ++i) {
        if (open == '"' && source_[i] == '\\') {
          ++i;
        } else if (source_[i] == open) {
          if (open == '\'' && i + 1 < source_.size() && source_[i + 1] == '\'') {
            ++i;
            continue;
          }
          return {begin, i + 1};
        }
      }
    } else if (source_.substr(begin, s.value.size()) == s.value) {
      return {begin, begin + s.value.size()};
    }
    Refuse(r, "edit this value by hand");
  }

  TextEdit Version(const SceneRewrite& r) const {
    const std::string current = std::to_string(kSceneFormatVersion);
    if (!r.insert) {
      const auto [begin, end] = ScalarBytes(r, r.scalar);
      if (r.scalar.quoted) return {begin + 1, end - 1, current};  // the quotes stay
      return {begin, end, current};
    }
    // No `chasles` key: a line of its own before the first key (after any leading comments),
    // or the first entry of a flow mapping.
    return EntryBefore(r, fmt::format("chasles: {}", current),
                       fmt::format("add 'chasles: {}' as the file's first key by hand", current));
  }

  /// `entry` ("key: value") inserted before the mapping key at r.scalar.mark: a line of its own
  /// indented as that key, ended as that key's line is (CR LF or LF), or in a flow mapping
  /// (r.flow) an entry before it. `by_hand` says what to do where the key's line holds more.
  TextEdit EntryBefore(const SceneRewrite& r, const std::string& entry,
                       const std::string& by_hand) const {
    const size_t key = Pos(r.scalar);
    if (r.flow) return {key, key, entry + ", "};
    const auto column = static_cast<size_t>(std::max(r.scalar.mark.column, 0));
    const size_t line = key >= column ? key - column : key;
    if (source_.substr(line, key - line).find_first_not_of(' ') != std::string_view::npos) {
      Refuse(r, by_hand);
    }
    return {line, line, fmt::format("{}{}{}", std::string(key - line, ' '), entry, LineEnd(key))};
  }

  /// How the line holding byte `at` ends ("\r\n" or "\n").
  std::string LineEnd(size_t at) const {
    const size_t eol = source_.find('\n', at);
    return eol != std::string_view::npos && eol > 0 && source_[eol - 1] == '\r' ? "\r\n" : "\n";
  }

  /// `integrator: adaptive` as the first key of `simulation`, or a `simulation` section of its
  /// own at the end of a file that has none.
  TextEdit KeepAdaptive(const SceneRewrite& r) const {
    const std::string keep = "integrator: adaptive";
    if (r.insert) {
      if (r.flow) Refuse(r, "add 'simulation: {integrator: adaptive}' to the scene by hand");
      const std::string eol = LineEnd(0);
      const bool ends_line = source_.empty() || source_.back() == '\n';
      return {source_.size(), source_.size(),
              fmt::format("{}simulation:{}  {}{}", ends_line ? "" : eol, eol, keep, eol)};
    }
    if (r.scalar.mark.line < 0) Refuse(r, "add 'integrator: adaptive' to 'simulation' by hand");
    return EntryBefore(r, keep, "add 'integrator: adaptive' to 'simulation' by hand");
  }

  TextEdit DropZ(const SceneRewrite& r) const {
    const auto [z_begin, z_end] = ScalarBytes(r, r.last);
    if (r.flow) {
      // [x, y, 0]: from the end of y to the end of 0 (the comma and the spaces go with it).
      return {ScalarBytes(r, r.scalar).second, z_end, ""};
    }
    // A block sequence: the third item's line, "  - 0", goes whole.
    size_t line = z_begin;
    while (line > 0 && source_[line - 1] != '\n') --line;
    const std::string_view lead = source_.substr(line, z_begin - line);
    if (lead.find_first_not_of(" -") != std::string_view::npos || lead.find('-') == lead.npos) {
      Refuse(r, "remove the third value by hand");
    }
    size_t end = source_.find('\n', z_end);
    end = end == std::string_view::npos ? source_.size() : end + 1;
    return {line, end, ""};
  }

  [[noreturn]] void Refuse(const SceneRewrite& r, const std::string& what) const {
    throw SceneError(file_, r.spot.line, r.spot.column, r.spot.key,
                     fmt::format("this old version's spelling cannot be rewritten in place "
                                 "(the value is escaped, folded or laid out unusually); {} and "
                                 "run chasles upgrade again",
                                 what));
  }

  std::string_view source_;
  std::string file_;
};

/// "FILE:LINE:COL: KEY: OLD -> NEW" for a rewrite.
std::string ChangeLine(const std::string& file, const SceneRewrite& r, std::string_view source,
                       const TextEdit& e) {
  std::string what;
  if (r.kind == SceneRewrite::Kind::kVersion) {
    what = r.insert
               ? fmt::format("no version (version 1) -> chasles: {}", kSceneFormatVersion)
               : fmt::format("chasles: {} -> chasles: {}", r.scalar.value, kSceneFormatVersion);
  } else if (r.kind == SceneRewrite::Kind::kDropZ) {
    what = fmt::format("third value '{}' of a planar world vector removed", r.last.value);
  } else if (r.kind == SceneRewrite::Kind::kKeepAdaptive) {
    what =
        "integrator: adaptive added (what a scene with contacts that names none ran before "
        "version 3, which runs auto there)";
  } else {
    what = fmt::format("'{}' -> '{}'", source.substr(e.begin, e.end - e.begin), e.text);
  }
  return fmt::format("{}:{}:{}: {}: {}", file, r.spot.line, r.spot.column, r.spot.key, what);
}

}  // namespace

SceneUpgrade UpgradeSceneText(std::string_view text, const std::string& name,
                              const SceneOptions& options) {
  scene_internal::CheckSceneText(text, name);
  const scene_internal::YamlDocument document = scene_internal::ParseYaml(text, name);
  scene_internal::SceneReader reader(name, options);
  SceneUpgrade upgrade;
  upgrade.before = std::string(text);
  upgrade.from_version = reader.Read(document.Root()).format_version;
  // The parser's places count from after a byte-order mark: the edits are made after it.
  const std::string_view bom = "\xEF\xBB\xBF";
  const std::string_view lead = text.starts_with(bom) ? bom : std::string_view();
  text.remove_prefix(lead.size());
  const EditPlanner planner(text, name);
  std::vector<std::pair<TextEdit, const SceneRewrite*>> edits;
  for (const SceneRewrite& r : reader.rewrites()) edits.emplace_back(planner.Plan(r), &r);
  std::sort(edits.begin(), edits.end(),
            [](const auto& a, const auto& b) { return a.first.begin < b.first.begin; });
  for (size_t i = 1; i < edits.size(); ++i) {
    if (edits[i].first.begin < edits[i - 1].first.end) {
      throw std::logic_error(
          fmt::format("{}: two rewrites overlap at byte {}", name, edits[i].first.begin));
    }
  }
  std::string result(lead);
  size_t done = 0;
  for (const auto& [e, r] : edits) {
    result.append(text.substr(done, e.begin - done));
    result += e.text;
    done = e.end;
    upgrade.changes.push_back(ChangeLine(name, *r, text, e));
  }
  result.append(text.substr(done));
  upgrade.text = std::move(result);
  if (upgrade.changed()) {
    // The result must read as the current version, which refuses every old spelling.
    try {
      const Scene check = LoadSceneText(upgrade.text, name, options);
      if (check.format_version != kSceneFormatVersion) throw InputError("the version stayed");
    } catch (const InputError& e) {
      throw std::logic_error(
          fmt::format("the upgraded text of {} does not load: {}", name, e.what()));
    }
  }
  return upgrade;
}

SceneUpgrade UpgradeSceneFile(const std::string& path, const SceneOptions& options) {
  return UpgradeSceneText(scene_internal::ReadSceneFileText(path, options.max_scene_bytes), path,
                          options);
}

}  // namespace chasles
