// Reading the contact keys of a scene (docs/scene-format.md, "Contacts"): `material_pairs`
// and `contacts`. Geometry is in the body frame; planes are in the world frame.

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "chasles/scene/scene.h"
#include "chasles/scene/scene_contacts.h"
#include "chasles/suggest.h"
#include "internal/scene_reader.h"

namespace chasles {

const char* SceneContactShapeName(SceneContactShape shape) {
  switch (shape) {
    case SceneContactShape::kSphere:
      return "sphere";
    case SceneContactShape::kDisk:
      return "disk";
    case SceneContactShape::kDiskFace:
      return "disk_face";
    case SceneContactShape::kCylinder:
      return "cylinder";
    case SceneContactShape::kBox:
      return "box";
    case SceneContactShape::kPoints:
      return "points";
    case SceneContactShape::kCapsule:
      return "capsule";
  }
  return "";
}

std::vector<std::string> ContactPointLabels(const SceneContact& c) {
  int n = 1;
  switch (c.shape) {
    case SceneContactShape::kSphere:
    case SceneContactShape::kDisk:
      n = 1;
      break;
    case SceneContactShape::kDiskFace:
      n = kDiskFacePoints;
      break;
    case SceneContactShape::kCylinder:
    case SceneContactShape::kCapsule:
      n = 2;
      break;
    case SceneContactShape::kBox:
      n = 8;
      break;
    case SceneContactShape::kPoints:
      n = static_cast<int>(c.points_B.size());
      break;
  }
  if (n == 1) return {c.name};
  std::vector<std::string> labels;
  for (int i = 0; i < n; ++i) {
    const bool named =
        c.shape == SceneContactShape::kPoints && !c.point_names[static_cast<size_t>(i)].empty();
    labels.push_back(named ? fmt::format("{}_{}", c.name, c.point_names[static_cast<size_t>(i)])
                           : fmt::format("{}_{}", c.name, i));
  }
  return labels;
}

std::vector<std::string> SceneContacts::point_labels() const {
  std::vector<std::string> all;
  for (const SceneContact& c : contacts) {
    for (auto& l : ContactPointLabels(c)) all.push_back(std::move(l));
  }
  return all;
}

namespace scene_internal {

namespace {

constexpr SceneContactShape kShapes[] = {SceneContactShape::kSphere,   SceneContactShape::kDisk,
                                         SceneContactShape::kDiskFace, SceneContactShape::kCylinder,
                                         SceneContactShape::kBox,      SceneContactShape::kPoints,
                                         SceneContactShape::kCapsule};

bool HasAxis(SceneContactShape s) {
  return s == SceneContactShape::kDisk || s == SceneContactShape::kDiskFace ||
         s == SceneContactShape::kCylinder || s == SceneContactShape::kCapsule;
}
bool HasRadius(SceneContactShape s) {
  return s != SceneContactShape::kBox && s != SceneContactShape::kPoints;
}
bool HasLength(SceneContactShape s) {
  return s == SceneContactShape::kCylinder || s == SceneContactShape::kCapsule;
}

bool SamePair(const SceneMaterialPair& p, const std::string& a, const std::string& b) {
  return (p.a == a && p.b == b) || (p.a == b && p.b == a);
}

}  // namespace

void SceneReader::ReadContactCoefficients(const At& at, double& mu_s, double& mu_k, double& mu_r,
                                          double& restitution, RestitutionLaw& law,
                                          bool have_defaults) {
  // Each coefficient is a plain number; the rules (>= 0, mu_k <= mu_s, e in [0, 1]) are
  // Coulomb's model and Newton's restitution law: a negative coefficient would make friction
  // push along the slip, e > 1 would create energy at every impact.
  auto coefficient = [&](const char* key, const char* what, double& value) {
    if (!at.Has(key)) return false;
    value = Value(at.Child(key), kDimensionless, what);
    if (!(value >= 0) || !std::isfinite(value)) {
      report_.Fail(at.Child(key),
                   fmt::format("{} must be >= 0 (got {:.6g}); a friction coefficient is the "
                               "ratio of a friction force to the normal force, never negative",
                               key, value));
    }
    return true;
  };
  const bool has_s = coefficient("mu_s", "the coefficient of static friction", mu_s);
  const bool has_k = coefficient("mu_k", "the coefficient of kinetic friction", mu_k);
  coefficient("mu_r", "the coefficient of rolling resistance", mu_r);
  if (!have_defaults) {
    // Only one of the two given: the other takes its value (one coefficient of friction).
    if (has_s && !has_k) mu_k = mu_s;
    if (has_k && !has_s) mu_s = mu_k;
  }
  if (mu_k > mu_s) {
    report_.Fail(at.Has("mu_k") ? at.Child("mu_k") : at,
                 fmt::format("mu_k = {:.6g} is larger than mu_s = {:.6g}; kinetic friction cannot "
                             "exceed static friction in Coulomb's model (a body would stick "
                             "again as soon as it slipped): give mu_k <= mu_s",
                             mu_k, mu_s));
  }
  if (at.Has("restitution")) {
    restitution = Value(at.Child("restitution"), kDimensionless, "the coefficient of restitution");
    if (!(restitution >= 0 && restitution <= 1)) {
      report_.Fail(at.Child("restitution"),
                   fmt::format("restitution must be in [0, 1] (0: no bounce, 1: elastic), got "
                               "{:.6g}; a value above 1 would create energy at every impact",
                               restitution));
    }
  }
  if (at.Has("restitution_law")) {
    // The restitution hypothesis (docs/contact.md, Impacts).
    const At law_at = at.Child("restitution_law");
    const std::string name = report_.Text(law_at, "newton, poisson or energetic");
    if (name == "newton") {
      law = RestitutionLaw::kNewton;
    } else if (name == "poisson") {
      law = RestitutionLaw::kPoisson;
    } else if (name == "energetic") {
      law = RestitutionLaw::kEnergetic;
    } else {
      report_.Fail(law_at,
                   fmt::format("unknown restitution_law '{}'{}; expected newton "
                               "(v_n after = -e v_n before), poisson (P_n = (1 + e) x the "
                               "compression impulse) or energetic (restitution work = e^2 x "
                               "compression work, the default)",
                               name, DidYouMean(name, {"newton", "poisson", "energetic"})));
    }
  }
}

void SceneReader::ReadContacts(const At& root, Scene& scene) {
  SceneContacts& out = scene.dynamics.contacts;
  if (root.Has("material_pairs")) {
    const At list = root.Child("material_pairs");
    report_.CheckSequence(list, "a list of material pairs");
    for (size_t i = 0; i < list.node.size(); ++i) {
      out.material_pairs.push_back(ReadMaterialPair(list.Item(i), out.material_pairs));
    }
  }
  if (!root.Has("contacts")) return;
  const At list = root.Child("contacts");
  report_.CheckSequence(list, "a list of contacts");
  const std::vector<std::string> constraints = scene.dynamics.constraints.names();
  NameSet taken(constraints.begin(), constraints.end());
  ContactTargetIndex targets;
  for (size_t i = 0; i < list.node.size(); ++i) {
    const At entry = list.Item(i);
    if (IsContactSet(entry, scene)) {
      ReadContactSet(entry, i, scene, taken, targets, out.contacts);
    } else {
      out.contacts.push_back(ReadContact(entry, i, scene, taken));
      const SceneContact& c = out.contacts.back();
      CheckContactTarget(entry.Child(c.with_plane ? "body" : "with"), out.contacts, c,
                         static_cast<int>(out.contacts.size()) - 1, false, targets);
    }
  }
}

SceneMaterialPair SceneReader::ReadMaterialPair(const At& at,
                                                const std::vector<SceneMaterialPair>& pairs) {
  report_.CheckMap(at, {"materials", "mu_s", "mu_k", "mu_r", "restitution", "restitution_law"},
                   "a material pair");
  const At names = report_.Require(at, "materials", "a material pair");
  if (!names.node.IsSequence() || names.node.size() != 2) {
    report_.Fail(names, "expected two material names, e.g. [steel, oak]");
  }
  SceneMaterialPair p;
  p.a = report_.Text(names.Item(0), "a material name");
  p.b = report_.Text(names.Item(1), "a material name");
  for (const SceneMaterialPair& q : pairs) {
    if (SamePair(q, p.a, p.b)) {
      report_.Fail(names, fmt::format("the pair {}/{} is given twice", p.a, p.b));
    }
  }
  ReadContactCoefficients(at, p.mu_s, p.mu_k, p.mu_r, p.restitution, p.restitution_law, false);
  return p;
}

SceneContact SceneReader::ReadContact(const At& at, size_t i, const Scene& scene, NameSet& taken) {
  report_.CheckMap(at,
                   {"name", "body", "shape", "radius", "axis", "center", "length", "size", "points",
                    "plane", "with", "other_radius", "other_center", "materials", "mu_s", "mu_k",
                    "mu_r", "restitution", "restitution_law"},
                   "a contact");
  SceneContact c;
  c.where = SpotAt(at);
  c.name =
      at.Has("name") ? report_.Text(at.Child("name"), "a name") : fmt::format("contact{}", i + 1);
  if (!taken.insert(c.name).second) {
    report_.Fail(at.Has("name") ? at.Child("name") : at,
                 fmt::format("the name '{}' is already used by a contact, joint, rolling "
                             "contact or driver; names must be unique",
                             c.name));
  }
  const std::string what = fmt::format("contact '{}'", c.name);
  c.body = BodyIndexAt(report_.Require(at, "body", what), scene);
  const SceneBody& body = scene.bodies[static_cast<size_t>(c.body)];

  ReadContactShape(at, what, body, c);
  ReadContactCounterpart(at, what, scene, c);
  if (at.Has("materials")) {
    ReadContactMaterials(at.Child("materials"), scene.dynamics.contacts.material_pairs, c);
  }
  ReadContactCoefficients(at, c.mu_s, c.mu_k, c.mu_r, c.restitution, c.restitution_law,
                          at.Has("materials"));
  return c;
}

void SceneReader::ReadContactShape(const At& at, const std::string& what, const SceneBody& body,
                                   SceneContact& c) {
  const At shape_at = report_.Require(at, "shape", what);
  const std::string shape = report_.Text(shape_at, "a contact shape");
  std::vector<std::string> shapes;
  bool found = false;
  for (SceneContactShape s : kShapes) {
    shapes.emplace_back(SceneContactShapeName(s));
    if (shape == SceneContactShapeName(s)) c.shape = s, found = true;
  }
  if (!found) {
    report_.Fail(shape_at, fmt::format("unknown contact shape '{}'{}; shapes: {}", shape,
                                       DidYouMean(shape, shapes), fmt::join(shapes, ", ")));
  }
  // Keys that belong to other shapes are errors, not silently ignored.
  auto refuse = [&](const char* key, const char* why) {
    if (at.Has(key)) report_.Fail(at.Child(key), fmt::format("a {} contact {}", shape, why));
  };
  if (HasRadius(c.shape)) {
    c.radius = PositiveValue(report_.Require(at, "radius", what), kLength, "the radius");
  } else {
    refuse("radius", "has no radius");
  }
  if (HasAxis(c.shape) && planar_ &&
      (c.shape == SceneContactShape::kDisk || c.shape == SceneContactShape::kCylinder)) {
    // A disk or cylinder of a planar scene turns about z (read as a planar rolling contact's
    // axis): its rim is the circle of the plane of motion.
    c.axis_B = PlanarZAxis(at, "axis", fmt::format("the axis of a {} contact", shape));
  } else if (HasAxis(c.shape) && planar_ && c.shape == SceneContactShape::kCapsule &&
             !at.Has("axis")) {
    c.axis_B = Vec3::UnitZ();  // a capsule seen end-on: its two end spheres at one circle
  } else if (HasAxis(c.shape)) {
    c.axis_B = BodyAxisAt(report_.Require(at, "axis", what), "the symmetry axis (body frame)");
  } else {
    refuse("axis", "has no axis");
  }
  if (HasLength(c.shape)) {
    c.length = PositiveValue(report_.Require(at, "length", what), kLength,
                             c.shape == SceneContactShape::kCylinder
                                 ? "the cylinder's length"
                                 : "the distance between the capsule's end centres");
  } else {
    refuse("length", "has no length");
  }
  if (c.shape == SceneContactShape::kBox) {
    const At s = report_.Require(at, "size", what);
    c.size = Vector(s, kLength, "the box's edge lengths");
    if (!(c.size.minCoeff() > 0)) {
      report_.Fail(s, "every edge length of the box must be positive");
    }
  } else {
    refuse("size", "has no size (only a box has)");
  }
  if (c.shape == SceneContactShape::kPoints) {
    const At pts = report_.Require(at, "points", what);
    report_.CheckSequence(pts, "a list of body points (names or [x, y, z])");
    if (pts.node.size() == 0) report_.Fail(pts, "give at least one point");
  } else {
    refuse("points", "has no point list (only shape points has)");
  }
  ReadContactBodyPoints(at, body, c);
}

void SceneReader::ReadContactBodyPoints(const At& at, const SceneBody& body, SceneContact& c) {
  c.points_B.clear();
  c.point_names.clear();
  if (c.shape == SceneContactShape::kPoints) {
    const At pts = at.Child("points");
    for (size_t k = 0; k < pts.node.size(); ++k) {
      const At p = pts.Item(k);
      c.points_B.push_back(BodyPointAt(p, body));
      c.point_names.push_back(std::string(p.node.Scalar()));
    }
  }
  c.p_BoC_B =
      at.Has("center") ? BodyPointAt(at.Child("center"), body) : body.mass_properties.p_BoBcm_B();
}

void SceneReader::ReadContactCounterpart(const At& at, const std::string& what, const Scene& scene,
                                         SceneContact& c) {
  auto refuse = [&](const char* key, const char* why) {
    if (at.Has(key)) {
      report_.Fail(at.Child(key),
                   fmt::format("a {} contact {}", SceneContactShapeName(c.shape), why));
    }
  };
  if (at.Has("with")) {
    if (at.Has("plane")) {
      report_.Fail(at.Child("with"), "give either 'plane' or 'with' (another body), not both");
    }
    if (c.shape != SceneContactShape::kSphere) {
      report_.Fail(at.Child("with"),
                   "contact between two bodies is for spheres: give shape sphere (and the "
                   "other body's sphere with other_radius)");
    }
    c.with_plane = false;
    c.other_body = BodyIndexAt(at.Child("with"), scene);
    if (c.other_body == c.body) {
      report_.Fail(at.Child("with"), "a body cannot touch itself; name another body");
    }
    const SceneBody& other = scene.bodies[static_cast<size_t>(c.other_body)];
    c.other_radius = PositiveValue(report_.Require(at, "other_radius", what), kLength,
                                   "the other body's sphere radius");
    c.p_OoD_O = at.Has("other_center") ? BodyPointAt(at.Child("other_center"), other)
                                       : other.mass_properties.p_BoBcm_B();
  } else {
    refuse("other_radius", "against a plane has no other body (see 'with')");
    refuse("other_center", "against a plane has no other body (see 'with')");
    if (!at.Has("plane")) {
      report_.Fail(at, fmt::format("{} needs 'plane: {{point: {}, normal: {}}}' "
                                   "(a world plane) or 'with: BODY' (another body's sphere)",
                                   what, planar_ ? "[x, y]" : "[x, y, z]",
                                   planar_ ? "[x, y]" : "[x, y, z]"));
    }
    const At plane = at.Child("plane");
    report_.CheckMap(plane, {"point", "normal"}, "a plane ({point, normal})");
    if (plane.Has("point")) {
      c.plane_point_W = WorldVector(plane.Child("point"), kLength, "a point of the plane");
    }
    c.plane_normal_W = AxisAt(report_.Require(plane, "normal", "a plane"), "the plane's normal");
  }
}

void SceneReader::ReadContactMaterials(const At& m, const std::vector<SceneMaterialPair>& pairs,
                                       SceneContact& c) {
  if (!m.node.IsSequence() || m.node.size() != 2) {
    report_.Fail(m,
                 "expected two material names [body's, plane's or other body's], e.g. "
                 "[steel, oak], as listed in 'material_pairs'");
  }
  const std::string a = report_.Text(m.Item(0), "a material name");
  const std::string b = report_.Text(m.Item(1), "a material name");
  const SceneMaterialPair* pair = nullptr;
  std::vector<std::string> known;
  for (const SceneMaterialPair& p : pairs) {
    if (SamePair(p, a, b)) pair = &p;
    known.push_back(fmt::format("{}/{}", p.a, p.b));
    known.push_back(fmt::format("{}/{}", p.b, p.a));
  }
  if (!pair) {
    const std::string asked = fmt::format("{}/{}", a, b);
    std::vector<std::string> listed;
    for (const SceneMaterialPair& p : pairs) {
      listed.push_back(fmt::format("{}/{}", p.a, p.b));
    }
    report_.Fail(m,
                 fmt::format("no material pair {}{} in 'material_pairs'; {}", asked,
                             DidYouMean(asked, known),
                             listed.empty() ? "the scene defines none: add 'material_pairs:' with "
                                              "the pair's mu_s, mu_k and restitution"
                                            : fmt::format("pairs: {}", fmt::join(listed, ", "))));
  }
  c.mu_s = pair->mu_s;
  c.mu_k = pair->mu_k;
  c.mu_r = pair->mu_r;
  c.restitution = pair->restitution;
  c.restitution_law = pair->restitution_law;
  c.materials = fmt::format("{}/{}", a, b);
}

}  // namespace scene_internal
}  // namespace chasles
