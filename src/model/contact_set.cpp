// Contact entries that name sets of bodies (chasles/model/contact_set.h).

#include "chasles/model/contact_set.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <fmt/format.h>

#include "chasles/model/model.h"
#include "chasles/suggest.h"

namespace chasles {
namespace {

// Length of the UTF-8 sequence that starts at s[i] (1 for a stray continuation byte).
size_t CharLength(std::string_view s, size_t i) {
  size_t n = 1;
  while (i + n < s.size() && (static_cast<unsigned char>(s[i + n]) & 0xC0) == 0x80) ++n;
  return n;
}

// The scene's bodies for a message: all of them up to twelve, else the first twelve and a count.
std::string BodyList(const std::vector<std::string>& names) {
  constexpr size_t kShown = 12;
  if (names.size() <= kShown) return fmt::format("bodies: {}", fmt::join(names, ", "));
  return fmt::format("bodies: {}, ... ({} in all)",
                     fmt::join(names.begin(), names.begin() + kShown, ", "), names.size());
}

}  // namespace

bool IsBodyPattern(std::string_view text) {
  return text.find_first_of("*?") != std::string_view::npos;
}

bool MatchesBodyPattern(std::string_view pattern, std::string_view name) {
  // Wildcard matching with one backtrack point (the last `*`): O(|pattern| |name|) at worst.
  // Positions advance by whole UTF-8 sequences, so `?` is one character, not one byte.
  size_t p = 0, n = 0;
  size_t star = std::string_view::npos, star_n = 0;
  while (n < name.size()) {
    if (p < pattern.size() && pattern[p] == '*') {
      star = p++;
      star_n = n;
    } else if (p < pattern.size() && pattern[p] == '?') {
      ++p;
      n += CharLength(name, n);
    } else if (p < pattern.size() && pattern[p] == name[n]) {
      ++p;
      ++n;
    } else if (star != std::string_view::npos) {
      p = star + 1;
      star_n += CharLength(name, star_n);
      n = star_n;
    } else {
      return false;
    }
  }
  while (p < pattern.size() && pattern[p] == '*') ++p;
  return p == pattern.size();
}

BodySet BodySetOfText(const std::string& text) {
  if (text == "all") return {true, {}};
  return {false, {text}};
}

std::vector<BodySetMember> ResolveBodySet(const BodySet& set, const std::vector<std::string>& names,
                                          BodySetRole role) {
  std::vector<BodySetMember> members;
  if (set.all) {
    const auto named_all = std::find(names.begin(), names.end(), "all");
    if (named_all != names.end()) return {{static_cast<BodyIndex>(named_all - names.begin()), -1}};
    for (size_t b = 0; b < names.size(); ++b) members.push_back({static_cast<BodyIndex>(b), -1});
    return members;
  }
  if (set.items.empty()) {
    throw BodySetError(role, -1,
                       "an empty list names no body; list the bodies, or give a pattern such as "
                       "'ball*' or all");
  }
  std::unordered_map<std::string_view, BodyIndex> index;
  for (size_t b = 0; b < names.size(); ++b) index.emplace(names[b], static_cast<BodyIndex>(b));
  std::vector<int> given_by(names.size(), -1);  // the item that gave each body
  for (size_t i = 0; i < set.items.size(); ++i) {
    const std::string& item = set.items[i];
    const int item_index = static_cast<int>(i);
    auto take = [&](BodyIndex b) {
      const int earlier = given_by[static_cast<size_t>(b)];
      if (earlier >= 0) {
        throw BodySetError(role, item_index,
                           fmt::format("body '{}' is already in the set (item {}, '{}'); a set "
                                       "gives each body once",
                                       names[static_cast<size_t>(b)], earlier + 1,
                                       set.items[static_cast<size_t>(earlier)]));
      }
      given_by[static_cast<size_t>(b)] = item_index;
    };
    if (const auto it = index.find(item); it != index.end()) {
      take(it->second);  // an exact name first: a name never turns into a pattern
    } else if (IsBodyPattern(item)) {
      bool matched = false;
      for (size_t b = 0; b < names.size(); ++b) {
        if (MatchesBodyPattern(item, names[b])) take(static_cast<BodyIndex>(b)), matched = true;
      }
      if (!matched) {
        throw BodySetError(role, item_index,
                           fmt::format("the pattern '{}' matches no body ('*' is any run of "
                                       "characters, '?' one character); {}",
                                       item, BodyList(names)));
      }
    } else if (item == "all") {
      throw BodySetError(role, item_index,
                         "'all' stands alone ('body: all'), not as an item of a list; give all, "
                         "or list the bodies");
    } else {
      throw BodySetError(role, item_index,
                         fmt::format("the scene has no body '{}'{}; {}", item,
                                     DidYouMean(item, names), BodyList(names)));
    }
  }
  for (size_t b = 0; b < names.size(); ++b) {
    if (given_by[b] >= 0) members.push_back({static_cast<BodyIndex>(b), given_by[b]});
  }
  return members;
}

std::vector<SetContact> ExpandContactSet(const std::string& base, const ContactBodySets& sets,
                                         const std::vector<std::string>& names) {
  const std::vector<BodySetMember> a = ResolveBodySet(sets.bodies, names, BodySetRole::kBodies);
  std::vector<BodySetMember> b;
  if (sets.has_with) {
    b = ResolveBodySet(sets.with, names, BodySetRole::kWith);
    std::vector<bool> in_a(names.size(), false);
    for (const BodySetMember& m : a) in_a[static_cast<size_t>(m.body)] = true;
    for (const BodySetMember& m : b) {
      if (!in_a[static_cast<size_t>(m.body)]) continue;
      throw BodySetError(BodySetRole::kWith, m.item,
                         fmt::format("body '{}' is in both 'body' and 'with', and would touch "
                                     "itself; for the pairs within one set give it as 'between'",
                                     names[static_cast<size_t>(m.body)]));
    }
  }
  if (sets.between && a.size() < 2) {
    throw BodySetError(BodySetRole::kBodies, -1,
                       fmt::format("the set holds one body ('{}'), which has no pair: 'between' "
                                   "needs two bodies or more",
                                   names[static_cast<size_t>(a[0].body)]));
  }
  const auto n_a = static_cast<std::int64_t>(a.size());
  const std::int64_t count = sets.between    ? n_a * (n_a - 1) / 2
                             : sets.has_with ? n_a * static_cast<std::int64_t>(b.size())
                                             : n_a;
  if (count > kMaxSetContacts) {
    throw BodySetError(
        sets.has_with ? BodySetRole::kWith : BodySetRole::kBodies, -1,
        fmt::format("the set stands for {} contacts ({} bodies{}), more than the {} one entry may "
                    "list: each listed contact has its own state, columns and report lines. For "
                    "balls that may all collide, list no pairs: 'integrator: events' or "
                    "'stepping' with 'ball_collisions' lets every pair collide",
                    count, a.size(),
                    sets.between    ? ", every pair"
                    : sets.has_with ? fmt::format(" against {}", b.size())
                                    : std::string(),
                    kMaxSetContacts));
  }
  std::vector<SetContact> out;
  out.reserve(static_cast<size_t>(count));
  auto name_of = [&](BodyIndex i) -> const std::string& { return names[static_cast<size_t>(i)]; };
  if (sets.between) {
    for (size_t i = 0; i < a.size(); ++i) {
      for (size_t j = i + 1; j < a.size(); ++j) {
        out.push_back({a[i].body, a[j].body,
                       fmt::format("{}_{}_{}", base, name_of(a[i].body), name_of(a[j].body)),
                       a[i].item, a[j].item});
      }
    }
  } else if (sets.has_with) {
    for (const BodySetMember& x : a) {
      for (const BodySetMember& y : b) {
        out.push_back({x.body, y.body,
                       fmt::format("{}_{}_{}", base, name_of(x.body), name_of(y.body)), x.item,
                       y.item});
      }
    }
  } else {
    for (const BodySetMember& x : a) {
      out.push_back({x.body, kWorld, fmt::format("{}_{}", base, name_of(x.body)), x.item, -1});
    }
  }
  return out;
}

ContactTarget PlaneTarget(BodyIndex body, const Vec3& point_W, const Vec3& normal_W) {
  const Vec3 n = normal_W.normalized();
  return {body, kWorld, n, n.dot(point_W)};
}

ContactTarget PairTarget(BodyIndex a, BodyIndex b) {
  return {std::min(a, b), std::max(a, b), Vec3::Zero(), 0.0};
}

int ContactTargetIndex::Add(const ContactTarget& t, int contact, bool from_set) {
  // Planes are compared by their unit normal and offset as computed: the same plane written
  // twice gives the same doubles; planes that differ only by round-off are different planes.
  Seen& s = seen_[Key{t.body, t.other, t.n_W.x(), t.n_W.y(), t.n_W.z(), t.offset}];
  const int clash = from_set ? s.first : s.first_from_set;
  if (s.first < 0) s.first = contact;
  if (from_set && s.first_from_set < 0) s.first_from_set = contact;
  return clash;
}

std::vector<int> AddContactSet(Model& model, const ContactSpec& spec, const ContactBodySets& sets) {
  const bool pairs = sets.between || sets.has_with;
  if (pairs != (spec.shape == ContactShape::kSphereSphere)) {
    throw InputError(fmt::format(
        "contact set '{}': {}", spec.name,
        pairs ? "pairs of bodies ('with' or 'between') touch sphere on sphere: give the shape "
                "SPHERE_SPHERE"
              : "a sphere against a sphere needs the other bodies: 'with' or 'between'"));
  }
  std::vector<std::string> names;
  for (BodyIndex b = 0; b < model.num_bodies(); ++b) names.push_back(model.body(b).name());
  const std::vector<SetContact> expanded = ExpandContactSet(spec.name, sets, names);
  auto target_of = [](const ContactSpec& s) {
    return s.shape == ContactShape::kSphereSphere
               ? PairTarget(s.body, s.other_body)
               : PlaneTarget(s.body, s.plane_point_W, s.plane_normal_W);
  };
  ContactTargetIndex targets;
  for (int c = 0; c < model.num_contacts(); ++c) {
    targets.Add(target_of(model.contact(c).spec()), c, false);
  }
  // Added to a copy, kept only when every contact is good: a refused set leaves `model` as it
  // was.
  Model grown = model;
  std::vector<int> added;
  for (const SetContact& e : expanded) {
    ContactSpec s = spec;
    s.name = e.name;
    s.body = e.body;
    if (pairs) s.other_body = e.other;
    const int clash = targets.Add(target_of(s), grown.num_contacts(), true);
    if (clash >= 0) {
      throw BodySetError(
          pairs ? BodySetRole::kWith : BodySetRole::kBodies, pairs ? e.other_item : e.item,
          fmt::format("contact '{}' would touch what contact '{}' touches ({}); a set may not "
                      "repeat a contact: narrow the set",
                      s.name, grown.contact(clash).name(),
                      pairs
                          ? fmt::format("bodies '{}' and '{}'", names[static_cast<size_t>(e.body)],
                                        names[static_cast<size_t>(e.other)])
                          : fmt::format("body '{}' on the same plane",
                                        names[static_cast<size_t>(e.body)])));
    }
    added.push_back(grown.AddContact(s));
  }
  model = std::move(grown);
  return added;
}

}  // namespace chasles
