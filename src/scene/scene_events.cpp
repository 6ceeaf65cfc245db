// Contact-mode events of a scene: `events: [{contact: ball, change: stops_sliding}]`
// (docs/scene-format.md, `events`).

#include <fmt/format.h>

#include "chasles/suggest.h"
#include "internal/scene_reader.h"

namespace chasles::scene_internal {

void SceneReader::ReadEventAction(const At& at, SceneEvent& e) {
  if (!at.Has("action")) return;
  const std::string a = report_.Text(at.Child("action"), "stop or record");
  if (a == "stop") {
    e.action = EventAction::kStop;
  } else if (a == "record") {
    e.action = EventAction::kRecord;
  } else {
    report_.Fail(at.Child("action"), fmt::format("action must be stop or record, got '{}'", a));
  }
}

void SceneReader::ReadModeEvent(const At& at, const Scene& scene, SceneEvent& e) {
  // A mode change is not a crossing: the keys of a crossing have no meaning here.
  for (const char* key : {"when", "crosses", "direction"}) {
    if (at.Has(key)) {
      report_.Fail(at.Child(key),
                   fmt::format("event '{}' watches a contact's mode ('contact' and 'change'); "
                               "'{}' belongs to a crossing event: remove one or the other",
                               e.name, key));
    }
  }
  const std::string what = fmt::format("event '{}'", e.name);
  const At contact = report_.Require(at, "contact", what);
  const At change = report_.Require(at, "change", what);
  // The contact: a contact's name (all its points) or one point's label.
  e.contact = report_.Text(contact, "a contact's name or a contact point's label");
  const SceneContacts& sc = scene.dynamics.contacts;
  std::vector<std::string> known;
  int first = 0;
  for (const SceneContact& c : sc.contacts) {
    const std::vector<std::string> labels = ContactPointLabels(c);
    known.push_back(c.name);
    for (size_t i = 0; i < labels.size(); ++i) {
      if (c.name == e.contact || labels[i] == e.contact) {
        e.points.push_back(first + static_cast<int>(i));
      }
      if (labels[i] != c.name) known.push_back(labels[i]);
    }
    first += static_cast<int>(labels.size());
  }
  if (e.points.empty()) {
    report_.Fail(
        contact,
        sc.empty() ? fmt::format("the scene has no contacts; '{}' cannot be watched "
                                 "(add it under 'contacts:')",
                                 e.contact)
                   : fmt::format("no contact or contact point is named '{}'{}; known: {}",
                                 e.contact, DidYouMean(e.contact, known), fmt::join(known, ", ")));
  }
  const std::string c = report_.Text(change, "a mode change");
  static const std::vector<std::pair<std::string, SceneModeChange>> kChanges = {
      {"starts_sliding", SceneModeChange::kStartsSliding},
      {"stops_sliding", SceneModeChange::kStopsSliding},
      {"separates", SceneModeChange::kSeparates},
      {"touches", SceneModeChange::kTouches},
      {"any", SceneModeChange::kAny}};
  std::vector<std::string> names;
  for (const auto& [name, kind] : kChanges) {
    names.push_back(name);
    if (name == c) e.change = kind;
  }
  if (e.change == SceneModeChange::kNone) {
    report_.Fail(change, fmt::format("unknown mode change '{}'{}; changes: {}", c,
                                     DidYouMean(c, names), fmt::join(names, ", ")));
  }
  ReadEventAction(at, e);
}

}  // namespace chasles::scene_internal
