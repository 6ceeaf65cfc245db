#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <regex>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include <fmt/format.h>

#include "chasles/mass/density_field.h"
#include "chasles/mass/materials.h"
#include "chasles/mass/shape.h"
#include "chasles/math/rotation.h"
#include "chasles/scene/expression.h"
#include "chasles/scene/scene.h"
#include "chasles/scene/units.h"
#include "chasles/suggest.h"
#include "internal/scene_reader.h"
#include "internal/scene_text.h"
#include "internal/shape_table.h"
#include "internal/yaml_reader.h"

namespace chasles {

using scene_internal::At;
using scene_internal::KindOf;
using scene_internal::Reporter;
using scene_internal::SceneReader;
using scene_internal::ShapeEntry;

namespace {

const std::vector<std::string> kRootKeys = {
    "chasles",    "title",    "description",    "units",           "parameters", "materials",
    "bodies",     "gravity",  "forces",         "events",          "impulses",   "impacts",
    "simulation", "output",   "joints",         "rolling",         "drivers",    "gears",
    "planar",     "contacts", "material_pairs", "project_initial", "strings"};
const std::vector<std::string> kBodyKeys = {"name",   "material", "density",
                                            "points", "parts",    "initial"};
// Keys every part may have; each shape adds its dimensions (see shape_table.cpp).
const std::vector<std::string> kPartKeys = {
    "name",       "shape",          "subtract",      "mass",      "density",
    "material",   "position",       "axis",          "rotation",  "euler",
    "quaternion", "linear_density", "areal_density", "thickness", "cross_section"};

// The keys of a part of a shape of the table, made once for each shape.
const std::vector<std::string>& TableShapePartKeys(const scene_internal::ShapeEntry& shape) {
  static const auto keys = [] {
    std::unordered_map<const scene_internal::ShapeEntry*, std::vector<std::string>> all;
    for (const std::string& name : scene_internal::ShapeNames()) {
      const scene_internal::ShapeEntry* entry = scene_internal::FindShape(name);
      std::vector<std::string>& allowed = all[entry];
      allowed = kPartKeys;
      for (const auto& d : entry->dimensions) allowed.emplace_back(d.key);
      if (entry->axial_key) {
        allowed.emplace_back("from");
        allowed.emplace_back("to");
      }
    }
    return all;
  }();
  return keys.at(&shape);
}

// True when an expression's text names no parameter or unit, only numbers, operators and
// functions: such a bare number is read in the scene's default unit for what is expected.
// Anything with a name in it must carry its own dimension, so that a ratio of two lengths is
// never silently taken for a length.
bool IsPureNumber(const std::string& text) {
  static const std::regex name_re("[A-Za-z_][A-Za-z_0-9]*");
  static const std::vector<std::string> functions = {"sqrt",  "cbrt", "abs",  "sin",   "cos", "tan",
                                                     "asin",  "acos", "atan", "atan2", "exp", "log",
                                                     "log10", "min",  "max",  "hypot", "pow", "pi"};
  for (auto it = std::sregex_iterator(text.begin(), text.end(), name_re);
       it != std::sregex_iterator(); ++it) {
    // A letter right after a digit is an exponent ("1e-3"), not a name.
    const auto pos = static_cast<size_t>(it->position());
    if (pos > 0 &&
        (std::isdigit(static_cast<unsigned char>(text[pos - 1])) || text[pos - 1] == '.')) {
      const std::string s = it->str();
      if (s.size() == 1 && (s[0] == 'e' || s[0] == 'E')) continue;
      if ((s[0] == 'e' || s[0] == 'E') &&
          s.find_first_not_of("0123456789", 1) == std::string::npos) {
        continue;
      }
    }
    if (std::find(functions.begin(), functions.end(), it->str()) == functions.end()) return false;
  }
  return true;
}

}  // namespace

namespace scene_internal {

// --- expressions ---------------------------------------------------------------------------

std::optional<Symbol> SceneReader::ResolveParameter(std::string_view name) {
  auto it = parameters_.find(name);
  if (it == parameters_.end()) return std::nullopt;
  return Symbol::Constant(EvaluateParameter(it->first));
}

Quantity SceneReader::EvaluateParameter(const std::string& name) {
  Parameter& p = parameters_.at(name);
  if (p.state == Parameter::State::kDone) return p.value;
  if (p.state == Parameter::State::kResolving) {
    std::string chain;
    auto start = std::find(resolving_.begin(), resolving_.end(), name);
    for (auto it = start; it != resolving_.end(); ++it) chain += *it + " -> ";
    report_.Fail(p.at, fmt::format("parameter '{}' depends on itself ({}{})", name, chain, name));
  }
  p.state = Parameter::State::kResolving;
  resolving_.push_back(name);
  const Expression e =
      Compile(p.at, p.text, [this](std::string_view n) { return ResolveParameter(n); });
  resolving_.pop_back();
  if (!e.is_constant()) report_.Fail(p.at, "a parameter must not depend on x, y or z");
  p.value = Quantity{e.Evaluate({}), e.dimension()};
  p.state = Parameter::State::kDone;
  return p.value;
}

Expression SceneReader::Compile(const At& at, const std::string& text,
                                const SymbolResolver& resolver) {
  try {
    return Expression::Parse(text, resolver);
  } catch (const SceneError&) {
    throw;  // from a parameter evaluated on the way: it already points at the parameter
  } catch (const ExpressionError& e) {
    report_.Fail(at, e.message(), at.node.IsScalar() && at.node.Scalar() == text ? e.offset() : 0);
  }
}

double SceneReader::DefaultUnitFactor(const Dimension& d) const {
  return 1.0 / units_->FromSI(1.0, d);
}

double SceneReader::Value(const At& at, const Dimension& expected, std::string_view what) {
  // The message is made only for a value that is not there: every number of a scene comes here.
  if (!at.node.IsScalar() || at.node.Scalar().empty()) {
    report_.Text(at, fmt::format("{} ({})", what, expected.Describe()));
  }
  const std::string text(at.node.Scalar());
  const Expression e =
      Compile(at, text, [this](std::string_view n) { return ResolveParameter(n); });
  if (!e.is_constant()) report_.Fail(at, "x, y and z may appear only in a density field");
  double value = e.Evaluate({});
  if (e.dimension() != expected) {
    if (e.dimension() == kDimensionless && IsPureNumber(text)) {
      value *= DefaultUnitFactor(expected);
    } else {
      std::string hint;
      if (!e.unit_note().empty()) {
        hint = "; " + e.unit_note();
      } else if (e.dimension() == kDimensionless) {
        hint =
            "; give it a unit (e.g. '2 m') — parameters written without a unit are plain "
            "numbers";
      }
      report_.Fail(at, fmt::format("expected {} for {}, got {}{}", expected.Describe(), what,
                                   e.dimension().Describe(), hint));
    }
  }
  if (!std::isfinite(value)) report_.Fail(at, fmt::format("{} is not a finite number", what));
  return value;
}

double SceneReader::PositiveValue(const At& at, const Dimension& expected, std::string_view what) {
  const double v = Value(at, expected, what);
  if (!(v > 0)) {
    report_.Fail(at, fmt::format("{} must be positive, got {:.6g} {}", what,
                                 units_->FromSI(v, expected), units_->FormatUnit(expected)));
  }
  return v;
}

Vec3 SceneReader::Vector(const At& at, const Dimension& expected, std::string_view what) {
  if (!at.node.IsSequence() || at.node.size() != 3) {
    report_.Fail(at, fmt::format("expected {} as a list of three values [x, y, z], got {}", what,
                                 KindOf(at.node)));
  }
  Vec3 v;
  for (size_t i = 0; i < 3; ++i) v[static_cast<int>(i)] = Value(at.Item(i), expected, what);
  return v;
}

// --- structure -----------------------------------------------------------------------------

void SceneReader::ReadUnits(const At& root) {
  if (root.Has("units")) {
    const At at = root.Child("units");
    units_text_ = report_.Text(at, "a unit choice such as 'SI', 'US' or 'in, lb, deg'");
    try {
      units_ = std::make_unique<UnitSystem>(UnitSystem::Parse(units_text_));
    } catch (const InputError& e) {
      report_.Fail(at, e.what());
    }
  } else {
    units_ = std::make_unique<UnitSystem>(UnitSystem::Parse("SI"));
  }
}

void SceneReader::ReadParameters(const At& root) {
  if (root.Has("parameters")) {
    const At at = root.Child("parameters");
    if (!at.node.IsMap()) {
      report_.Fail(at,
                   fmt::format("expected a mapping of names to values, got {}", KindOf(at.node)));
    }
    static const std::regex ident("[A-Za-z_][A-Za-z_0-9]*");
    for (const auto& kv : at.node) {
      const std::string name(kv.first.Scalar());
      const At p{kv.second, at.path + "." + name};
      if (!std::regex_match(name, ident)) {
        report_.Fail(At{kv.first, at.path},
                     fmt::format("parameter name '{}' is not a name (letters, digits and _, "
                                 "not starting with a digit)",
                                 name));
      }
      if (name == "x" || name == "y" || name == "z" || name == "pi") {
        report_.Fail(At{kv.first, at.path},
                     fmt::format("'{}' is reserved (x, y, z are coordinates in density fields; pi "
                                 "is the constant)",
                                 name));
      }
      if (parameters_.count(name))
        report_.Fail(p, fmt::format("parameter '{}' appears twice", name));
      parameters_.emplace(name, Parameter{p, report_.Text(p, "a value or an expression"), ""});
    }
  }
  for (const auto& [name, text] : options_.parameter_overrides) {
    auto it = parameters_.find(name);
    if (it == parameters_.end()) {
      std::vector<std::string> known;
      for (const auto& kv : parameters_) known.push_back(kv.first);
      throw SceneError(
          "command line", 0, 0, "--set " + name,
          fmt::format("the scene has no parameter '{}'{}", name, DidYouMean(name, known)));
    }
    it->second.text = text;
    it->second.origin = "--set " + name;
    // Errors in an override point at the command line, not the file.
    YamlDocument& doc = override_documents_.emplace_back();
    doc.SetRoot(doc.AddScalar(text));
    it->second.at = At{doc.Root(), "--set " + name};
  }
}

void SceneReader::ReadMaterials(const At& root) {
  if (!root.Has("materials")) return;
  const At at = root.Child("materials");
  if (!at.node.IsMap()) {
    report_.Fail(at, fmt::format("expected a mapping of material names to densities, got {}",
                                 KindOf(at.node)));
  }
  for (const auto& kv : at.node) {
    const std::string name(kv.first.Scalar());
    if (materials_.count(name)) {
      report_.Fail(At{kv.first, at.path + "." + name},
                   fmt::format("material '{}' appears twice", name));
    }
    materials_[name] = PositiveValue(At{kv.second, at.path + "." + name}, kDensity,
                                     "the density of material '" + name + "'");
  }
}

double SceneReader::MaterialDensity(const At& at) {
  const std::string name = report_.Text(at, "a material name");
  if (auto it = materials_.find(name); it != materials_.end()) return it->second;
  if (const std::optional<double> rho = FindMaterialDensity(name)) return *rho;
  std::vector<std::string> known = MaterialNames();
  for (const auto& kv : materials_) known.push_back(kv.first);
  report_.Fail(at, fmt::format("unknown material '{}'{}; define it under 'materials:' with its "
                               "density, or use one of the built-in materials (chasles "
                               "materials lists them)",
                               name, DidYouMean(name, known)));
}

Scene SceneReader::Read(const YamlNode& document) {
  const At root{document, ""};
  if (!document.IsMap()) {
    report_.Fail(root, fmt::format("a scene file is a mapping with keys such as 'bodies:', got {}",
                                   KindOf(document)));
  }
  report_.CheckMap(root, kRootKeys, "the scene");
  Scene scene;
  scene.file = report_.file();
  ReadVersion(root, scene);
  if (root.Has("title")) scene.title = report_.Text(root.Child("title"), "a title");
  if (root.Has("description")) {
    scene.description = report_.Text(root.Child("description"), "a description");
  }
  ReadUnits(root);
  scene.units = units_text_;
  ReadParameters(root);
  // Every parameter is evaluated, used or not, so that a mistake in one never hides.
  for (const auto& kv : parameters_) EvaluateParameter(kv.first);
  ReadMaterials(root);
  ReadPlanar(root, scene);

  const At bodies = report_.Require(root, "bodies", "a scene");
  report_.CheckSequence(bodies, "a list of bodies");
  if (bodies.node.size() == 0) report_.Fail(bodies, "the scene has no bodies; add at least one");
  std::unordered_set<std::string> names;  // a set: a scene may have 100 000 bodies
  names.reserve(bodies.node.size());
  scene.bodies.reserve(bodies.node.size());
  for (size_t i = 0; i < bodies.node.size(); ++i) {
    scene.bodies.push_back(ReadBody(bodies.Item(i), i));
    if (!names.insert(scene.bodies[i].name).second) {
      report_.Fail(
          bodies.Item(i).Child("name"),
          fmt::format("two bodies are named '{}'; names must be unique", scene.bodies[i].name));
    }
  }
  ReadConstraints(root, scene);
  ReadContacts(root, scene);
  ReadDynamics(root, scene);
  for (const auto& kv : parameters_) scene.parameters.emplace_back(kv.first, kv.second.value);
  scene.warnings = std::move(warnings_);
  return scene;
}

SceneBody SceneReader::ReadBody(const At& at, size_t index) {
  report_.CheckMap(at, kBodyKeys, "a body");
  SceneBody body;
  body.line = at.node.Mark().line + 1;
  body.where = {body.line, at.node.Mark().column + 1, at.path};
  body.name = at.Has("name") ? report_.Text(at.Child("name"), "a body name")
                             : fmt::format("body {}", index + 1);
  if (at.Has("material") && at.Has("density")) {
    report_.Fail(at.Child("density"), "give a body either 'material' or 'density', not both");
  }
  if (at.Has("points")) {
    const At pts = at.Child("points");
    if (!pts.node.IsMap()) {
      report_.Fail(pts, fmt::format("expected a mapping of point names to positions, got {}",
                                    KindOf(pts.node)));
    }
    for (const auto& kv : pts.node) {
      const std::string name(kv.first.Scalar());
      for (const auto& p : body.points) {
        if (p.name == name) {
          report_.Fail(At{kv.first, pts.path + "." + name},
                       fmt::format("point '{}' appears twice", name));
        }
      }
      const At value{kv.second, pts.path + "." + name};
      body.points.push_back(
          {name, BodyVector(value, kLength, "a point's position"), SpotAt(value)});
    }
  }
  const At parts = report_.Require(at, "parts", fmt::format("body '{}'", body.name));
  report_.CheckSequence(parts, "a list of parts");
  if (parts.node.size() == 0) report_.Fail(parts, "the body has no parts; add at least one");
  MassProperties sum = MassProperties::Zero();
  for (size_t i = 0; i < parts.node.size(); ++i) {
    ScenePart part = ReadPart(parts.Item(i), i, at, body.name);
    try {
      sum = sum + part.mass_properties;
    } catch (const InputError& e) {
      report_.Fail(parts.Item(i), fmt::format("body '{}': {}", body.name, e.what()));
    }
    body.parts.push_back(std::move(part));
  }
  try {
    sum.Validate(fmt::format("body '{}'", body.name));
  } catch (const InputError& e) {
    report_.Fail(at, e.what());
  }
  if (planar_) {
    // A planar body turns about z (eq. 8.43): it needs a moment about z.
    const RotationalInertia& I = sum.I_BBcm_B();
    if (!(I.Izz() > 1e-12 * (I.Ixx() + I.Iyy() + I.Izz()))) {
      report_.Fail(at, fmt::format("body '{}' has no moment of inertia about z (the plane's "
                                   "normal); a planar body needs one (a point mass or a rod "
                                   "along z cannot turn in the plane)",
                                   body.name));
    }
  }
  body.mass_properties = sum;
  return body;
}

Mat3 SceneReader::ReadOrientation(const At& part) {
  const char* keys[] = {"axis", "rotation", "euler", "quaternion"};
  const char* given = nullptr;
  for (const char* k : keys) {
    if (!part.Has(k)) continue;
    if (given) {
      report_.Fail(part.Child(k),
                   fmt::format("give one orientation, not both '{}' and '{}'", given, k));
    }
    given = k;
  }
  try {
    if (!given) return Mat3::Identity();
    const std::string key = given;
    const At at = part.Child(key);
    if (key == "axis") {
      return RotationTakingZTo(
          BodyVector(at, kDimensionless, "the direction of the shape's z axis"));
    }
    if (key == "rotation") {
      report_.CheckMap(at, {"axis", "angle"}, "a rotation");
      const Vec3 axis =
          BodyVector(report_.Require(at, "axis", "a rotation"), kDimensionless, "a rotation axis");
      const double angle =
          Value(report_.Require(at, "angle", "a rotation"), kDimensionless, "a rotation angle");
      return RotationFromAxisAngle(axis, angle);
    }
    if (key == "euler") {
      report_.CheckMap(at, {"sequence", "angles"}, "Euler angles");
      const std::string seq =
          report_.Text(report_.Require(at, "sequence", "Euler angles"), "a sequence such as ZYX");
      const Vec3 angles =
          Vector(report_.Require(at, "angles", "Euler angles"), kDimensionless, "Euler angles");
      return RotationFromEuler(seq, angles);
    }
    report_.CheckSequence(at, "a quaternion [w, x, y, z]");
    if (at.node.size() != 4) report_.Fail(at, "a quaternion has four values [w, x, y, z]");
    double q[4];
    for (size_t i = 0; i < 4; ++i) q[i] = Value(at.Item(i), kDimensionless, "a quaternion entry");
    return RotationFromQuaternion(q[0], q[1], q[2], q[3]);
  } catch (const SceneError&) {
    throw;
  } catch (const InputError& e) {
    report_.Fail(part.Child(given), e.what());
  }
}

ScenePart SceneReader::ReadPart(const At& at, size_t index, const At& body_at,
                                const std::string& body_name) {
  if (!at.node.IsMap()) {
    report_.Fail(at, fmt::format("expected a part (a mapping with 'shape:' and its dimensions), "
                                 "got {}",
                                 KindOf(at.node)));
  }
  ScenePart part;
  part.line = at.node.Mark().line + 1;
  part.name = at.Has("name") ? report_.Text(at.Child("name"), "a part name")
                             : fmt::format("part {}", index + 1);
  const At shape_at = report_.Require(at, "shape", fmt::format("part '{}'", part.name));
  part.shape = report_.Text(shape_at, "a shape name");

  MassProperties local;  // in the part's own frame P
  Vec3 p_BoPo_B = Vec3::Zero();
  Mat3 R_BP = Mat3::Identity();
  if (part.shape == "point" || part.shape == "custom") {
    local = ReadPointOrCustomPart(at, part, p_BoPo_B, R_BP);
  } else if (part.shape == "planar") {
    local = ReadPlanarPart(at, part, p_BoPo_B);
  } else if (part.shape == "mesh") {
    local = ReadMeshPart(at, body_at,
                         fmt::format("body '{}', part '{}' (mesh)", body_name, part.name), part);
    if (at.Has("position")) p_BoPo_B = BodyVector(at.Child("position"), kLength, "a position");
    R_BP = ReadOrientation(at);
  } else {
    local = ReadTableShapePart(at, shape_at, body_at, part, p_BoPo_B, R_BP);
  }

  if (at.Has("subtract")) {
    const At s = at.Child("subtract");
    bool subtract = false;
    if (!s.node.IsScalar() || !DecodeBool(s.node, subtract)) {
      report_.Fail(s, fmt::format("expected true or false, got {}", KindOf(s.node)));
    }
    part.subtractive = subtract;
  }
  part.where = SpotAt(at.Has("position") ? at.Child("position") : at);
  part.geometry.p_BoPo_B = p_BoPo_B;
  part.geometry.R_BP = R_BP;
  part.mass_properties = local.ExpressedInParent(R_BP, p_BoPo_B);
  if (part.subtractive) part.mass_properties = part.mass_properties.Negated();
  return part;
}

MassProperties SceneReader::ReadPointOrCustomPart(const At& at, ScenePart& part, Vec3& p_BoPo_B,
                                                  Mat3& R_BP) {
  MassProperties local;
  const bool custom = part.shape == "custom";
  // A point has neither volume nor area; a custom part has no geometry (NaN: not known).
  if (!custom) part.volume = part.surface_area = 0.0;
  std::vector<std::string> allowed = {"name", "shape", "subtract", "mass", "position"};
  if (custom) {
    for (const char* k : {"center_of_mass", "inertia", "axis", "rotation", "euler", "quaternion"}) {
      allowed.emplace_back(k);
    }
  }
  report_.CheckMap(at, allowed, fmt::format("a {} part", part.shape));
  const std::string what = fmt::format("part '{}' ({})", part.name, part.shape);
  const double mass = PositiveValue(report_.Require(at, "mass", what), kMass, "the mass");
  part.mass_source = "mass";
  if (!custom) {
    local = MassProperties::PointMass(mass, Vec3::Zero());
  } else {
    const Vec3 com = at.Has("center_of_mass")
                         ? BodyVector(at.Child("center_of_mass"), kLength, "the centre of mass")
                         : Vec3::Zero();
    const At inertia_at = report_.Require(at, "inertia", what);
    report_.CheckMap(inertia_at, {"Ixx", "Iyy", "Izz", "Ixy", "Ixz", "Iyz"},
                     "an inertia (about the centre of mass; products as tensor entries, "
                     "Ixy = -∫xy dm)");
    double I[6] = {0, 0, 0, 0, 0, 0};
    const char* names[6] = {"Ixx", "Iyy", "Izz", "Ixy", "Ixz", "Iyz"};
    for (int i = 0; i < 6; ++i) {
      if (i < 3) {
        I[i] = Value(report_.Require(inertia_at, names[i], "an inertia"), kInertia, names[i]);
      } else if (inertia_at.Has(names[i])) {
        I[i] = Value(inertia_at.Child(names[i]), kInertia, names[i]);
      }
    }
    const RotationalInertia inertia(I[0], I[1], I[2], I[3], I[4], I[5]);
    const std::string why = inertia.CheckPhysicallyValid();
    if (!why.empty()) {
      report_.Fail(inertia_at, fmt::format("{}: {} (values in kg*m^2)", what, why));
    }
    local = MassProperties(mass, com, inertia);
    R_BP = ReadOrientation(at);
  }
  if (at.Has("position")) p_BoPo_B = BodyVector(at.Child("position"), kLength, "a position");
  return local;
}

MassProperties SceneReader::ReadTableShapePart(const At& at, const At& shape_at, const At& body_at,
                                               ScenePart& part, Vec3& p_BoPo_B, Mat3& R_BP) {
  MassProperties local;
  const ShapeEntry* shape = scene_internal::FindShape(part.shape);
  if (!shape) {
    std::vector<std::string> names = scene_internal::ShapeNames();
    names.emplace_back("point");
    names.emplace_back("custom");
    names.emplace_back("mesh");
    names.emplace_back("planar");
    report_.Fail(shape_at, fmt::format("unknown shape '{}'{}; shapes: {}", part.shape,
                                       DidYouMean(part.shape, names), fmt::join(names, ", ")));
  }
  part.shape = shape->name;
  report_.CheckMap(at, TableShapePartKeys(*shape), fmt::format("a {} part", shape->name));
  const std::string what = fmt::format("part '{}' ({})", part.name, shape->name);

  const bool segment = at.Has("from") || at.Has("to");
  if (segment) {
    if (!at.Has("from") || !at.Has("to")) {
      report_.Fail(at.Child(at.Has("from") ? "from" : "to"), "'from' and 'to' go together");
    }
    if (at.Has("position")) {
      report_.Fail(at.Child("position"), "'from'/'to' already place the part; remove 'position'");
    }
  }
  scene_internal::Dimensions dims;
  for (const auto& d : shape->dimensions) {
    if (segment && shape->axial_key == std::string_view(d.key)) {
      if (at.Has(d.key)) {
        report_.Fail(at.Child(d.key),
                     fmt::format("'from'/'to' already give the {}; remove '{}'", d.key, d.key));
      }
      continue;
    }
    if (d.optional && !at.Has(d.key)) continue;
    dims.values[d.key] = ReadDimension(report_.Require(at, d.key, what), d);
  }
  if (segment) {
    const Vec3 from = BodyVector(at.Child("from"), kLength, "the start point");
    const Vec3 to = BodyVector(at.Child("to"), kLength, "the end point");
    const double length = (to - from).norm();
    if (!(length > 0)) report_.Fail(at.Child("to"), "'from' and 'to' are the same point");
    dims.values[shape->axial_key] = {length};
    R_BP = RotationTakingZTo(to - from);
    p_BoPo_B = shape->origin_at_from ? from : Vec3(0.5 * (from + to));
    if (at.Has("axis") || at.Has("rotation") || at.Has("euler") || at.Has("quaternion")) {
      report_.Fail(at, "'from'/'to' already orient the part; remove its orientation");
    }
  } else {
    if (at.Has("position")) p_BoPo_B = BodyVector(at.Child("position"), kLength, "a position");
    R_BP = ReadOrientation(at);
  }
  for (const auto& [key, values] : dims.values) part.geometry.dimensions.emplace_back(key, values);
  std::unique_ptr<Shape> geometry;
  try {
    geometry = shape->make(dims);
  } catch (const InputError& e) {
    report_.Fail(at, fmt::format("{}: {}", what, e.what()));
  }
  part.volume = geometry->is_solid() ? geometry->CalcMeasure() : 0.0;
  part.surface_area = geometry->CalcSurfaceArea();
  try {
    local = ReadShapeMass(at, body_at, *geometry, what, part);
  } catch (const SceneError&) {
    throw;
  } catch (const InputError& e) {
    // The mass properties themselves out of range (a mass that overflows to inf).
    report_.Fail(at, fmt::format("{}: {}", what, e.what()));
  }
  return local;
}

std::vector<double> SceneReader::ReadDimension(const At& at,
                                               const scene_internal::DimensionKey& d) {
  using scene_internal::DimensionKind;
  const std::string what = std::string_view(d.key) == d.meaning
                               ? fmt::format("the {}", d.key)
                               : fmt::format("the {} ({})", d.key, d.meaning);
  switch (d.kind) {
    case DimensionKind::kLength:
      return {PositiveValue(at, kLength, what)};
    case DimensionKind::kLengths2:
    case DimensionKind::kLengths3: {
      const size_t n = d.kind == DimensionKind::kLengths2 ? 2 : 3;
      if (!at.node.IsSequence() || at.node.size() != n) {
        report_.Fail(at, fmt::format("expected {} as a list of {} lengths, got {}", what, n,
                                     KindOf(at.node)));
      }
      std::vector<double> out;
      for (size_t i = 0; i < n; ++i) out.push_back(PositiveValue(at.Item(i), kLength, what));
      return out;
    }
    case DimensionKind::kTriangle2: {
      if (!at.node.IsSequence() || at.node.size() != 3) {
        report_.Fail(at, fmt::format("expected {}, got {}", what, KindOf(at.node)));
      }
      std::vector<double> out;
      for (size_t i = 0; i < 3; ++i) {
        const At v = at.Item(i);
        if (!v.node.IsSequence() || v.node.size() != 2) {
          report_.Fail(v, fmt::format("expected a vertex [x, y], got {}", KindOf(v.node)));
        }
        for (size_t j = 0; j < 2; ++j) out.push_back(Value(v.Item(j), kLength, "a coordinate"));
      }
      return out;
    }
    case DimensionKind::kFlag: {
      bool on = false;
      if (!at.node.IsScalar() || !DecodeBool(at.node, on)) {
        report_.Fail(at, fmt::format("'{}' is a switch: expected true or false ({}), got {}", d.key,
                                     d.meaning, KindOf(at.node)));
      }
      return {on ? 1.0 : 0.0};
    }
  }
  return {};
}

SceneReader::MassSource SceneReader::FindMassSource(const At& at, const At& body_at,
                                                    std::initializer_list<const char*> keys,
                                                    const std::string& missing) {
  const char* given = nullptr;
  for (const char* k : keys) {
    if (!at.Has(k)) continue;
    if (given) {
      report_.Fail(at.Child(k),
                   fmt::format("give the part's mass one way: '{}' or '{}', not both", given, k));
    }
    given = k;
  }
  if (given) return {at.Child(given), given};
  // A part that gives none takes its body's material or density.
  if (body_at.Has("material")) return {body_at.Child("material"), "material"};
  if (body_at.Has("density")) return {body_at.Child("density"), "density"};
  report_.Fail(at, missing);
}

MassProperties SceneReader::ReadShapeMass(const At& at, const At& body_at, const Shape& geometry,
                                          const std::string& what, ScenePart& part) {
  // Not a structured binding: the lambdas below capture `source` (clang 14 cannot capture a
  // binding).
  const auto found = FindMassSource(
      at, body_at, {"mass", "density", "material", "linear_density", "areal_density"},
      fmt::format("{} has no mass: give 'mass', 'density' or 'material' (on the part or on its "
                  "body)",
                  what));
  const At& source = found.at;
  const std::string& key = found.key;
  const Shape::Measure measure = geometry.measure();
  const bool slender = measure == Shape::Measure::kLength;
  const bool sheet = measure == Shape::Measure::kArea;
  // A hollow solid (a cone with a wall) took its 'thickness' as a dimension.
  const auto dims = geometry.dimensions();
  const bool wall = std::any_of(dims.begin(), dims.end(),
                                [](const ShapeDimension& d) { return d.name == "thickness"; });
  if (at.Has("thickness") && !sheet && !wall) {
    report_.Fail(at.Child("thickness"),
                 fmt::format("'thickness' is for thin sheets (disks, plates, shells), not a {}",
                             geometry.kind()));
  }
  if (at.Has("cross_section") && !slender) {
    report_.Fail(
        at.Child("cross_section"),
        fmt::format("'cross_section' is for slender rods and rings, not a {}", geometry.kind()));
  }
  // A volume density becomes a density per length or per area through the cross-section or
  // the thickness of a thin shape.
  auto uniform = [&](double rho) {
    double per_measure = rho;
    if (slender) {
      if (!at.Has("cross_section")) {
        report_.Fail(source, fmt::format("a {} is slender (a length, no volume): give "
                                         "'cross_section' (its area) with a density or material, "
                                         "or 'linear_density', or 'mass'",
                                         geometry.kind()));
      }
      per_measure *= PositiveValue(at.Child("cross_section"), kArea, "the cross-section area");
    } else if (sheet) {
      if (!at.Has("thickness")) {
        report_.Fail(source, fmt::format("a {} is a thin sheet (an area, no volume): give "
                                         "'thickness' with a density or material, or "
                                         "'areal_density', or 'mass'",
                                         geometry.kind()));
      }
      per_measure *= PositiveValue(at.Child("thickness"), kLength, "the thickness");
    }
    part.density = rho;
    return geometry.CalcMassProperties(per_measure * geometry.CalcMeasure());
  };

  if (key == "mass") {
    part.mass_source = "mass";
    return geometry.CalcMassProperties(PositiveValue(source, kMass, "the mass"));
  }
  if (key == "material") {
    part.mass_source = std::string(source.node.Scalar());
    return uniform(MaterialDensity(source));
  }
  if (key == "linear_density" || key == "areal_density") {
    const bool per_length = key == "linear_density";
    if ((per_length && !slender) || (!per_length && !sheet)) {
      report_.Fail(source, fmt::format("'{}' does not fit a {}: use {}", key, geometry.kind(),
                                       slender ? "'linear_density'"
                                       : sheet ? "'areal_density'"
                                               : "'density'"));
    }
    part.mass_source = key;
    const double rho =
        PositiveValue(source, per_length ? kLinearDensity : kArealDensity, "the " + key);
    return geometry.CalcMassProperties(rho * geometry.CalcMeasure());
  }
  // density: a constant, or a field of x, y, z in the part's own frame.
  const std::string text = report_.Text(source, "a density");
  const Expression e = Compile(source, text, [this](std::string_view n) -> std::optional<Symbol> {
    if (n == "x") return Symbol::Variable(0, kLength);
    if (n == "y") return Symbol::Variable(1, kLength);
    if (n == "z") return Symbol::Variable(2, kLength);
    return ResolveParameter(n);
  });
  if (e.is_constant()) {
    part.mass_source = "density";
    return uniform(PositiveValue(source, kDensity, "the density"));
  }
  if (e.dimension() != kDensity) {
    report_.Fail(source, fmt::format("expected a density field ({}), got {}{}", kDensity.Describe(),
                                     e.dimension().Describe(),
                                     e.unit_note().empty() ? "" : "; " + e.unit_note()));
  }
  if (measure != Shape::Measure::kVolume) {
    report_.Fail(source,
                 fmt::format("a density field needs a solid; a {} has no volume", geometry.kind()));
  }
  DensityIntegrationReport integration;
  MassProperties local;
  try {
    local = IntegrateDensity(
        geometry,
        [&e](const Vec3& p) {
          const double xyz[3] = {p.x(), p.y(), p.z()};
          return e.Evaluate(std::span<const double>(xyz, 3));
        },
        1e-10, &integration);
  } catch (const InputError& err) {
    report_.Fail(source, fmt::format("{}: {}", what, err.what()));
  }
  part.mass_source = "density field";
  part.notes.push_back(
      fmt::format("density field integrated to an estimated relative error of "
                  "{:.1e} ({} evaluations)",
                  integration.estimated_relative_error, integration.evaluations));
  return local;
}

}  // namespace scene_internal

Scene scene_internal::ReadSceneDocument(const YamlNode& document, const std::string& name,
                                        const SceneOptions& options) {
  SceneReader reader(name, options);
  return reader.Read(document);
}

Scene LoadSceneText(std::string_view text, const std::string& name, const SceneOptions& options) {
  scene_internal::CheckSceneText(text, name);
  for (const auto& [key, value] : options.parameter_overrides) {
    scene_internal::CheckSceneText(key + "=" + value, "command line --set");
  }
  const scene_internal::YamlDocument document = scene_internal::ParseYaml(text, name);
  return scene_internal::ReadSceneDocument(document.Root(), name, options);
}

namespace {
constexpr std::string_view kNotYaml = "this is not valid YAML: ";

scene_internal::YamlDocument ParseOptionText(std::string_view text, std::string_view option) {
  scene_internal::CheckSceneText(text, fmt::format("command line {}", option));
  try {
    return scene_internal::ParseYaml(text, "command line");
  } catch (const SceneError& e) {
    std::string_view problem = e.message();
    if (problem.starts_with(kNotYaml)) problem.remove_prefix(kNotYaml.size());
    throw SceneError("command line", 0, 0, std::string(option),
                     fmt::format("'{}' is not valid YAML: {}", text, problem));
  }
}
}  // namespace

Vec3 ReadPointOption(const Scene& scene, std::string_view text, std::string_view option) {
  SceneReader reader(scene, fmt::format("command line {}", option), SceneOptions{});
  return reader.PointOption(ParseOptionText(text, option).Root());
}

Mat3 ReadRotationOption(const Scene& scene, std::string_view text, std::string_view option) {
  SceneReader reader(scene, fmt::format("command line {}", option), SceneOptions{});
  return reader.RotationOption(ParseOptionText(text, option).Root());
}

Scene LoadSceneFile(const std::string& path, const SceneOptions& options) {
  return LoadSceneText(scene_internal::ReadSceneFileText(path, options.max_scene_bytes), path,
                       options);
}

}  // namespace chasles
