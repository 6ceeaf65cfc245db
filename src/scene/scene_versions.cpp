// Format versions (docs/scene-format.md, "Changes between versions"). A file says its version
// with `chasles: N` (a file without the key is version 1, the format before versions meant
// anything). This chasles writes version 3 and reads versions 1 and 2 with the meanings they
// had: each spelling that a later version reads differently is read as before, with a warning
// naming its place and its new spelling, and recorded as a rewrite for `chasles upgrade`
// (scene_upgrade.cpp). A file of a later version refuses the old spellings, naming the new
// ones.
//
// Version 1 -> 2 (all in planar scenes, from the planar work's renames):
//  - a world vector written [x, y, 0] (contact planes and gear centres took three values
//    before world vectors became [x, y]) is [x, y];
//  - the body variables <body>_wz and <body>_wbz are <body>_omega (the signed rate about z, the
//    same quantity in plane motion), <body>_yaw is <body>_theta (the angle about z; yaw wrapped
//    at ±180°, theta does not, so the two agree while |theta| < 180°).
//
// Version 2 -> 3: a scene with contacts that names no integrator runs `auto` (event-driven while
// the contacts' regimes change slowly, time stepped while they chatter), where it ran
// `adaptive`. The two agree bit for bit where auto never switches; where it does, auto finishes
// a run that adaptive would stop in chatter, at first order. An older file keeps `adaptive`, and
// its upgrade writes `integrator: adaptive`.

#include <algorithm>
#include <array>
#include <cctype>
#include <utility>

#include <fmt/format.h>

#include "chasles/scene/scene.h"
#include "chasles/scene/scene_dynamics.h"
#include "internal/scene_reader.h"

namespace chasles::scene_internal {

namespace {

/// The version-1 body-variable suffixes of a planar scene and their version-2 names.
constexpr std::array<std::pair<const char*, const char*>, 3> kRenamedSuffixes = {
    {{"wz", "omega"}, {"wbz", "omega"}, {"yaw", "theta"}}};

/// What the version-2 name means (for messages).
const char* Meaning(std::string_view new_suffix) {
  return new_suffix == "omega" ? "the signed angular velocity about z"
                               : "the angle about z, which does not wrap at ±180° as yaw did";
}

/// Byte offsets of `name` in the expression `text`, as a whole name (not inside a longer name
/// or a number such as 1e5).
std::vector<size_t> NameOffsets(std::string_view text, std::string_view name) {
  std::vector<size_t> offsets;
  const auto word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  for (size_t i = 0; i < text.size();) {
    if (!word(text[i])) {
      ++i;
      continue;
    }
    size_t j = i;
    while (j < text.size() && (word(text[j]) || text[j] == '.')) ++j;
    const bool starts_a_name = std::isalpha(static_cast<unsigned char>(text[i])) || text[i] == '_';
    if (starts_a_name && text.substr(i, j - i) == name) offsets.push_back(i);
    i = j;
  }
  return offsets;
}

/// The place of byte `offset` in scalar `at` (a quoted scalar's mark is its opening quote).
SceneSpot SpotInScalar(const At& at, size_t offset) {
  SceneSpot spot = SpotAt(at);
  if (at.node.IsScalar() && at.node.Quoted()) ++spot.column;
  spot.column += static_cast<int>(offset);
  return spot;
}

}  // namespace

void SceneReader::ReadVersion(const At& root, Scene& scene) {
  SceneRewrite r;
  r.kind = SceneRewrite::Kind::kVersion;
  if (root.Has("chasles")) {
    const At v = root.Child("chasles");
    const std::string text = report_.Text(v, "the format version");
    if (text == "1" || text == "2" || text == "3") {
      version_ = text[0] - '0';
    } else {
      report_.Fail(v, fmt::format("format version '{}' is not known; this chasles reads versions "
                                  "1 to {} (it writes {}: docs/scene-format.md, \"Changes "
                                  "between versions\")",
                                  text, kSceneFormatVersion, kSceneFormatVersion));
    }
    r.scalar = SourceOf(v.node);
    r.spot = SpotAt(v);
  } else {
    // No version: the format as it was before versions meant anything.
    version_ = 1;
    r.insert = true;
    r.flow = root.node.Flow();
    if (root.node.size() > 0) r.scalar.mark = (*root.node.begin()).first.Mark();
    r.spot = {r.scalar.mark.line + 1, r.scalar.mark.column + 1, "chasles"};
  }
  scene.format_version = version_;
  if (version_ < kSceneFormatVersion) rewrites_.push_back(std::move(r));
}

void SceneReader::DefaultIntegrator(const At& root, Scene& scene) {
  SceneSimulation& sim = scene.dynamics.simulation;
  const bool has_simulation = root.Has("simulation");
  if (scene.dynamics.contacts.empty() ||
      (has_simulation && root.Child("simulation").Has("integrator"))) {
    return;
  }
  if (version_ >= 3) {
    sim.auto_engine = true;
    sim.auto_by_default = true;
    return;
  }
  SceneRewrite r;
  r.kind = SceneRewrite::Kind::kKeepAdaptive;
  if (has_simulation) {
    const At at = root.Child("simulation");
    r.spot = KeySpotAt(root, "simulation");
    r.flow = at.node.Flow();
    r.scalar.mark.line = -1;  // no keys: the upgrade leaves it to the user
    if (at.node.IsMap() && at.node.size() > 0) r.scalar.mark = (*at.node.begin()).first.Mark();
  } else {
    r.insert = true;
    r.flow = root.node.Flow();
    r.spot = {1, 1, "simulation"};
  }
  OldSpelling(std::move(r),
              fmt::format("a version-{} scene with contacts that names no integrator runs "
                          "'adaptive' (version 3 runs 'auto' there: event-driven while the "
                          "contacts' regimes change slowly, time stepped while they chatter); "
                          "write 'integrator: adaptive' to keep that",
                          version_));
}

void SceneReader::OldSpelling(SceneRewrite rewrite, const std::string& what) {
  warnings_.push_back(
      fmt::format("{}:{}:{}: {}: {}; chasles upgrade rewrites the file as version "
                  "{}",
                  report_.file(), rewrite.spot.line, rewrite.spot.column, rewrite.spot.key, what,
                  kSceneFormatVersion));
  rewrites_.push_back(std::move(rewrite));
}

void SceneReader::PlanarThreeValues(const At& at, std::string_view what, const char* form,
                                    const std::function<bool()>& zero_z) {
  const std::string three = form == std::string_view("[x, y]") ? "[x, y, z]" : "three";
  const auto text = [&](size_t i) {
    return at.node[i].IsScalar() ? at.node[i].Scalar() : std::string("...");
  };
  const std::string two = fmt::format("[{}, {}]", text(0), text(1));
  if (version_ >= 2) {
    report_.Fail(at, fmt::format("{}: a planar scene moves in the x-y plane; give {} (two "
                                 "values), not {}: write {} ([x, y, 0] is the version-1 spelling)",
                                 what, form, three, two));
  }
  if (!zero_z()) {
    report_.Fail(at, fmt::format("{}: a planar scene moves in the x-y plane; give {} (two "
                                 "values), not {}: out-of-plane components have no place in a "
                                 "planar problem",
                                 what, form, three));
  }
  SceneRewrite r;
  r.kind = SceneRewrite::Kind::kDropZ;
  r.spot = SpotAt(at);
  r.scalar = SourceOf(at.node[1]);
  r.last = SourceOf(at.node[2]);
  r.flow = at.node.Flow();
  OldSpelling(std::move(r), fmt::format("version-1 spelling [{}, {}] of a planar scene's world "
                                        "vector: write {}",
                                        two.substr(1, two.size() - 2), text(2), two));
}

std::optional<Symbol> SceneReader::PlanarOldName(const At& at, std::string_view name) {
  std::string new_name, new_suffix;
  // Every suffix is one word: the body is what comes before the last '_'.
  const size_t cut = name.rfind('_');
  if (cut != std::string_view::npos && state_bodies_.contains(name.substr(0, cut))) {
    const std::string prefix(name.substr(0, cut + 1));  // "<body>_"
    for (const auto& [old_suffix, suffix] : kRenamedSuffixes) {
      if (name.substr(cut + 1) == old_suffix) {
        new_name = prefix + suffix;
        new_suffix = suffix;
      }
    }
  }
  if (new_name.empty()) return std::nullopt;
  const std::string text(at.node.Scalar());
  const std::vector<size_t> offsets = NameOffsets(text, name);
  if (version_ >= 2) {
    report_.Fail(at,
                 fmt::format("'{}' is the version-1 name of '{}' in a planar scene ({}); write "
                             "'{}'",
                             name, new_name, Meaning(new_suffix), new_name),
                 offsets.empty() ? 0 : offsets.front());
  }
  // Each use once, however often the parser asks (it looks names up ahead). A name the scan
  // cannot place (an escaped scalar) is still warned about, at the scalar.
  const auto first = std::find_if(rewrites_.begin(), rewrites_.end(), [&](const SceneRewrite& r) {
    return r.kind == SceneRewrite::Kind::kRename && r.old_text == name &&
           r.scalar.mark.pos == at.node.Mark().pos;
  });
  if (first == rewrites_.end()) {
    for (const size_t offset : offsets.empty() ? std::vector<size_t>{0} : offsets) {
      SceneRewrite r;
      r.kind = SceneRewrite::Kind::kRename;
      r.spot = SpotInScalar(at, offset);
      r.scalar = SourceOf(at.node);
      r.offset = offset;
      r.old_text = std::string(name);
      r.new_text = new_name;
      OldSpelling(std::move(r), fmt::format("version-1 name '{}' of a planar scene, read as '{}' "
                                            "({}): write '{}'",
                                            name, new_name, Meaning(new_suffix), new_name));
    }
  }
  return ResolveStateSymbol(at, new_name);
}

}  // namespace chasles::scene_internal
