#pragma once
/// @file
/// Many contacts from one entry (docs/scene-format.md, "Sets of bodies"): a scene's contact
/// entry, or Model contacts added from Python, may name a set of bodies instead of one body, and
/// stands for one contact per body of the set (against a plane) or per pair of bodies (sphere
/// against sphere). This is the one expansion both use: which bodies a set holds, which pairs
/// two sets make, in which order, how the contacts are named, and which contact a new one
/// repeats.
///
/// A set is `all` (every body) or a list of items, each a body's name or a name pattern: `*`
/// stands for any run of characters (none included), `?` for one character (a UTF-8 sequence),
/// and no other character is special. A text that is a body's exact name is that body, even if
/// it holds `*` or `?` or reads `all`, so a set never changes what a name meant.

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include "chasles/error.h"
#include "chasles/math/types.h"
#include "chasles/model/body.h"
#include "chasles/model/contact.h"

namespace chasles {

class Model;

/// A set of bodies as written: `all`, or items (names or patterns).
struct BodySet {
  bool all = false;
  std::vector<std::string> items;
};

/// The set one text stands for: `all`, or the one item `text` (a name or a pattern).
BodySet BodySetOfText(const std::string& text);

/// A body of a resolved set and the item that brought it in (-1 for `all`).
struct BodySetMember {
  BodyIndex body = kWorld;
  int item = -1;
};

/// The sets of a contact entry: `bodies` carry the shape; with `with`, each pair of a body of
/// `bodies` and a body of `with` touches (sphere on sphere); with `between`, each pair of two
/// bodies of `bodies` does.
struct ContactBodySets {
  BodySet bodies;
  BodySet with;
  bool has_with = false;
  bool between = false;
};

/// Which set of a ContactBodySets an error is about.
enum class BodySetRole { kBodies, kWith };

/// A set that names no body, a name that is no body's, a body given twice, two sets that share
/// a body, a set too large: the set (and its item, or -1 for the set as a whole) and why.
class BodySetError : public InputError {
 public:
  BodySetError(BodySetRole role, int item, const std::string& message)
      : InputError(message), role_(role), item_(item) {}
  BodySetRole role() const { return role_; }
  int item() const { return item_; }

 private:
  BodySetRole role_;
  int item_;
};

/// Most contacts one entry may stand for. A listed contact has its own state in every sample,
/// its own report lines and columns, and joins its bodies in one island: 1,000 balls in pairs
/// would be 499,500 contacts. Balls on a table that may all collide need no list: the
/// event-driven engine's `ball_collisions` (SphereEventOptions::collide_all_pairs) lets every
/// pair collide and its broadphase finds the pairs that meet.
inline constexpr std::int64_t kMaxSetContacts = 20000;

/// True when `text` holds `*` or `?`.
bool IsBodyPattern(std::string_view text);

/// Whether `name` matches `pattern` (`*` any run of characters, `?` one character; every other
/// character itself).
bool MatchesBodyPattern(std::string_view pattern, std::string_view name);

/// The bodies of `set` among `names` (the bodies' names in body order), in body order, each
/// once; `all` is the body called "all" when there is one, else every body. BodySetError (with
/// `role`) for an empty list, an item that is neither a body's name nor a pattern matching one,
/// `all` as an item of a list, and a body that two items give.
std::vector<BodySetMember> ResolveBodySet(const BodySet& set, const std::vector<std::string>& names,
                                          BodySetRole role);

/// One contact an entry stands for: the body carrying the shape, the other body of a pair
/// (kWorld against a plane), its name, and the items of the sets that brought them in.
struct SetContact {
  BodyIndex body = kWorld;
  BodyIndex other = kWorld;
  std::string name;
  int item = -1;
  int other_item = -1;
};

/// The contacts `sets` stands for, named from `base` (docs/scene-format.md, "Sets of bodies"):
///  - `bodies` alone: one per body, in body order, named `<base>_<body>`;
///  - `between`: one per unordered pair of distinct bodies of `bodies`, the earlier body first,
///    in the order (a, b) of body order, named `<base>_<a>_<b>`;
///  - `with`: one per pair (a from `bodies`, b from `with`), in the order (a, b) of body order,
///    named `<base>_<a>_<b>`; the two sets must not share a body (use `between` for the pairs
///    within one set).
/// BodySetError for what ResolveBodySet refuses, sets that share a body, `between` over one
/// body, or more than kMaxSetContacts contacts (refused before they are made).
std::vector<SetContact> ExpandContactSet(const std::string& base, const ContactBodySets& sets,
                                         const std::vector<std::string>& names);

/// What a contact touches, to find a contact listed twice: a body against a plane (its unit
/// normal and its offset n·p), or an unordered pair of bodies.
struct ContactTarget {
  BodyIndex body = kWorld;
  BodyIndex other = kWorld;
  Vec3 n_W = Vec3::Zero();
  double offset = 0.0;
};

/// The target of a contact against the world plane through `point_W` with normal `normal_W`.
ContactTarget PlaneTarget(BodyIndex body, const Vec3& point_W, const Vec3& normal_W);
/// The target of a contact between bodies a and b (either order).
ContactTarget PairTarget(BodyIndex a, BodyIndex b);

/// The contacts listed so far by what they touch. A contact that a set stands for may not touch
/// what another contact touches: one of the two would be a mistake (the same pair of balls
/// twice, the same ball twice on one floor), and neither is dropped silently. Two contacts
/// given one by one may (a dumbbell's two spheres against one ball), as before sets existed.
class ContactTargetIndex {
 public:
  /// The earlier contact that a new one (from a set or not) may not share `target` with, or -1;
  /// then records it as contact `contact`.
  int Add(const ContactTarget& target, int contact, bool from_set);

 private:
  using Key = std::tuple<BodyIndex, BodyIndex, double, double, double, double>;
  struct Seen {
    int first = -1;           // the first contact with this target
    int first_from_set = -1;  // the first from a set, or -1
  };
  std::map<Key, Seen> seen_;
};

/// Adds to `model` the contacts that `sets` stands for, each a copy of `spec` (its body, other
/// body and name set per contact; spec.name is the base): ExpandContactSet over the model's
/// bodies, then Model::AddContact for each. InputError (BodySetError for the sets) naming the
/// contact when one touches what a contact of the model already touches. Returns the indices of
/// the contacts added. A sphere against a sphere with `with` or `between` (spec.shape must be
/// kSphereSphere then, and kSphereSphere needs one of them).
std::vector<int> AddContactSet(Model& model, const ContactSpec& spec, const ContactBodySets& sets);

}  // namespace chasles
