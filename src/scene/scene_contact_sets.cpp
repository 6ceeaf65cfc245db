// Contact entries that name sets of bodies (docs/scene-format.md, "Sets of bodies"): `body`
// or `with` given as a list, a name pattern or `all`, or `between`. The expansion itself (which
// bodies, which pairs, their order and names) is chasles/model/contact_set.h, shared with the
// Python module; here the sets are read, the entry's keys are read once, and the body-dependent
// ones (`center`, `points`, `other_center`) once per body.

#include <algorithm>
#include <optional>
#include <string_view>

#include <fmt/format.h>

#include "chasles/scene/scene.h"
#include "chasles/scene/scene_contacts.h"
#include "internal/scene_reader.h"

namespace chasles::scene_internal {

namespace {

// The questions this file asks about a value's YAML form, in one place: is it a list and how
// long, or is it a text and which.
bool IsList(const At& at) {
  return at.node.IsSequence();
}
size_t ListLength(const At& at) {
  return at.node.size();
}
std::optional<std::string> TextOf(const At& at) {
  if (!at.node.IsScalar()) return std::nullopt;
  return std::string(at.node.Scalar());
}

// Item `item` of the set written at `set_at`, or the set itself (`all`, a pattern, a name).
At ItemAt(const At& set_at, int item) {
  return item >= 0 && IsList(set_at) ? set_at.Item(static_cast<size_t>(item)) : set_at;
}

bool IsBodyName(const Scene& scene, std::string_view name) {
  return std::any_of(scene.bodies.begin(), scene.bodies.end(),
                     [&](const SceneBody& b) { return b.name == name; });
}

// Whether the value at `at` is a set rather than one body's name: a list, or a text that is no
// body's name and reads `all` or holds a pattern's `*` or `?`.
bool IsSetValue(const At& at, const Scene& scene) {
  if (IsList(at)) return true;
  const std::optional<std::string> text = TextOf(at);
  return text && (*text == "all" || IsBodyPattern(*text)) && !IsBodyName(scene, *text);
}

// The part shapes a contact shape describes when it is put on every body of a set. Parts
// without a shape of their own (point, custom, planar, mesh) and cut-outs fit every shape.
std::vector<std::string_view> FittingPartShapes(SceneContactShape shape) {
  switch (shape) {
    case SceneContactShape::kSphere:
      return {"sphere", "spherical_shell", "thick_spherical_shell"};
    case SceneContactShape::kDisk:
    case SceneContactShape::kDiskFace:
      return {"disk", "ring", "cylinder", "cylindrical_shell", "tube"};
    case SceneContactShape::kCylinder:
      return {"cylinder", "cylindrical_shell", "tube"};
    case SceneContactShape::kBox:
      return {"box", "plate"};
    case SceneContactShape::kCapsule:
      return {"cylinder", "cylindrical_shell", "rod",
              "sphere",   "hemisphere",        "hemispherical_shell"};
    case SceneContactShape::kPoints:
      break;
  }
  return {};  // points: any body
}

}  // namespace

bool SceneReader::IsContactSet(const At& at, const Scene& scene) {
  if (at.Has("between")) return true;
  return (at.Has("body") && IsSetValue(at.Child("body"), scene)) ||
         (at.Has("with") && IsSetValue(at.Child("with"), scene));
}

BodySet SceneReader::BodySetAt(const At& at) {
  BodySet set;
  if (IsList(at)) {
    for (size_t k = 0; k < ListLength(at); ++k) {
      set.items.push_back(report_.Text(at.Item(k), "a body name or a pattern such as 'ball*'"));
    }
    return set;
  }
  return BodySetOfText(report_.Text(at, "a body name, a list of them, a pattern or all"));
}

void SceneReader::ReadContactSet(const At& at, size_t i, const Scene& scene, NameSet& taken,
                                 ContactTargetIndex& targets, std::vector<SceneContact>& out) {
  report_.CheckMap(
      at, {"name",      "body", "between", "shape", "radius",      "axis",           "center",
           "length",    "size", "points",  "plane", "with",        "other_radius",   "other_center",
           "materials", "mu_s", "mu_k",    "mu_r",  "restitution", "restitution_law"},
      "a contact");
  const std::string base =
      at.Has("name") ? report_.Text(at.Child("name"), "a name") : fmt::format("contact{}", i + 1);
  const std::string what = fmt::format("contact '{}'", base);
  ContactBodySets sets;
  if (at.Has("between")) {
    for (const char* key : {"body", "with"}) {
      if (at.Has(key)) {
        report_.Fail(at.Child(key),
                     "give either 'between' (every pair within one set) or "
                     "'body' (with 'plane' or 'with'), not both");
      }
    }
    sets.bodies = BodySetAt(at.Child("between"));
    sets.between = true;
  } else {
    sets.bodies = BodySetAt(report_.Require(at, "body", what));
    sets.has_with = at.Has("with");
    if (sets.has_with) sets.with = BodySetAt(at.Child("with"));
  }
  std::vector<std::string> names;
  for (const SceneBody& b : scene.bodies) names.push_back(b.name);
  std::vector<SetContact> expanded;
  try {
    expanded = ExpandContactSet(base, sets, names);
  } catch (const BodySetError& e) {
    FailAtSet(at, e);
  }
  const SceneContact model = ReadContactSetTemplate(
      at, what, sets, scene, scene.bodies[static_cast<size_t>(expanded[0].body)]);
  const At body_at = at.Child(sets.between ? "between" : "body");
  const At with_at = sets.between ? body_at : at.Child("with");
  // A pair's sphere centres, read once per body and side (the `center` of the body's sphere;
  // the `other_center` of a `with` body's, the `center` with `between`).
  std::vector<std::optional<Vec3>> centers(2 * scene.bodies.size());
  auto center_of = [&](int side, BodyIndex b, int item) {
    std::optional<Vec3>& p = centers[2 * static_cast<size_t>(b) + static_cast<size_t>(side)];
    if (p) return *p;
    const SceneBody& body = scene.bodies[static_cast<size_t>(b)];
    CheckSetBodyFits(side == 0 ? body_at : with_at, item, body, model.shape);
    const char* key = side == 1 && sets.has_with ? "other_center" : "center";
    p = at.Has(key) ? BodyPointAt(at.Child(key), body) : body.mass_properties.p_BoBcm_B();
    return *p;
  };
  out.reserve(out.size() + expanded.size());
  for (const SetContact& e : expanded) {
    SceneContact c = model;
    c.name = e.name;
    c.body = e.body;
    if (model.with_plane) {
      const SceneBody& body = scene.bodies[static_cast<size_t>(e.body)];
      CheckSetBodyFits(body_at, e.item, body, c.shape);
      ReadContactBodyPoints(at, body, c);
    } else {
      c.other_body = e.other;
      c.p_BoC_B = center_of(0, e.body, e.item);
      c.p_OoD_O = center_of(1, e.other, e.other_item);
    }
    const At item_at = model.with_plane ? ItemAt(body_at, e.item) : ItemAt(with_at, e.other_item);
    if (!taken.insert(c.name).second) {
      report_.Fail(item_at, fmt::format("the name '{}' of a contact this set stands for is already "
                                        "used by a contact, joint, rolling contact or driver; "
                                        "names must be unique: rename the entry ('name')",
                                        c.name));
    }
    out.push_back(std::move(c));
    CheckContactTarget(item_at, out, out.back(), static_cast<int>(out.size()) - 1, true, targets);
  }
}

void SceneReader::FailAtSet(const At& at, const BodySetError& e) {
  const At set_at = at.Has("between")                ? at.Child("between")
                    : e.role() == BodySetRole::kWith ? at.Child("with")
                                                     : at.Child("body");
  report_.Fail(ItemAt(set_at, e.item()), e.what());
}

void SceneReader::CheckSetBodyFits(const At& set_at, int item, const SceneBody& body,
                                   SceneContactShape shape) {
  const std::vector<std::string_view> fitting = FittingPartShapes(shape);
  if (fitting.empty()) return;
  for (const ScenePart& part : body.parts) {
    if (part.subtractive || part.geometry.dimensions.empty()) continue;
    if (std::find(fitting.begin(), fitting.end(), part.shape) != fitting.end()) continue;
    report_.Fail(ItemAt(set_at, item),
                 fmt::format("body '{}' of the set has part '{}', a {}, which a {} contact does "
                             "not describe (it fits bodies made of {}, and parts without a shape "
                             "of their own: point, custom, mesh); leave the body out of the set "
                             "(a list or a pattern) and give its contact on its own",
                             body.name, part.name, part.shape, SceneContactShapeName(shape),
                             fmt::join(fitting, ", ")));
  }
}

SceneContact SceneReader::ReadContactSetTemplate(const At& at, const std::string& what,
                                                 const ContactBodySets& sets, const Scene& scene,
                                                 const SceneBody& first) {
  SceneContact c;
  c.where = SpotAt(at);
  ReadContactShape(at, what, first, c);
  const bool pairs = sets.between || sets.has_with;
  if (pairs && c.shape != SceneContactShape::kSphere) {
    report_.Fail(at.Child("shape"),
                 "contact between two bodies is for spheres: give shape sphere (and, with "
                 "'with', the other bodies' sphere with other_radius)");
  }
  if (sets.between) {
    for (const char* key : {"plane", "other_radius", "other_center"}) {
      if (at.Has(key)) {
        report_.Fail(at.Child(key),
                     fmt::format("'between' puts the sphere of 'radius' and 'center' on each body "
                                 "of the set and lets each pair touch; remove '{}'",
                                 key));
      }
    }
    c.with_plane = false;
    c.other_radius = c.radius;
  } else if (sets.has_with) {
    if (at.Has("plane")) {
      report_.Fail(at.Child("with"), "give either 'plane' or 'with' (other bodies), not both");
    }
    c.with_plane = false;
    c.other_radius = PositiveValue(report_.Require(at, "other_radius", what), kLength,
                                   "the other bodies' sphere radius");
  } else {
    ReadContactCounterpart(at, what, scene, c);
  }
  if (at.Has("materials")) {
    ReadContactMaterials(at.Child("materials"), scene.dynamics.contacts.material_pairs, c);
  }
  ReadContactCoefficients(at, c.mu_s, c.mu_k, c.mu_r, c.restitution, c.restitution_law,
                          at.Has("materials"));
  return c;
}

void SceneReader::CheckContactTarget(const At& at, const std::vector<SceneContact>& contacts,
                                     const SceneContact& c, int index, bool from_set,
                                     ContactTargetIndex& targets) {
  const ContactTarget target = c.with_plane ? PlaneTarget(c.body, c.plane_point_W, c.plane_normal_W)
                                            : PairTarget(c.body, c.other_body);
  const int clash = targets.Add(target, index, from_set);
  if (clash < 0) return;
  const SceneContact& earlier = contacts[static_cast<size_t>(clash)];
  const SceneSpot& spot = earlier.where;
  report_.Fail(at,
               fmt::format("contact '{}' touches what contact '{}' ({}:{}:{}: {}) touches, {}; "
                           "a contact that a set stands for may not repeat another (neither "
                           "would be dropped silently): narrow the set (a list or a "
                           "pattern) or remove the other entry",
                           c.name, earlier.name, report_.file(), spot.line, spot.column, spot.key,
                           target.other == kWorld ? "the same body on the same plane"
                                                  : "the same pair of bodies"));
}

}  // namespace chasles::scene_internal
