#pragma once
/// @file
/// The scene reader: turns a YAML document into a Scene, evaluating every expression with the
/// scene's units and parameters and failing with file, line, column and key. Private to the
/// scene layer; its parts live in one .cpp per section of the format (scene_loader.cpp for
/// parameters, materials, bodies and parts).

#include <functional>
#include <initializer_list>
#include <limits>
#include <list>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "chasles/mass/mass_properties.h"
#include "chasles/mass/shape.h"
#include "chasles/model/contact_set.h"
#include "chasles/scene/expression.h"
#include "chasles/scene/scene.h"
#include "chasles/scene/units.h"
#include "scene_rewrite.h"
#include "shape_table.h"
#include "yaml_reader.h"

namespace chasles::scene_internal {

/// Where `at` stands in the file (marks are 0-based; the spot's are 1-based).
inline SceneSpot SpotAt(const At& at) {
  const YamlMark mark = at.node.Mark();
  return {mark.line >= 0 ? mark.line + 1 : 0, mark.column >= 0 ? mark.column + 1 : 0, at.path};
}

/// Where the key `key` of the mapping at `map` stands (the key itself, e.g. the line of
/// `simulation:`), with the path of its value.
SceneSpot KeySpotAt(const At& map, std::string_view key);

/// Names already taken (contacts, joints, rolling contacts, drivers).
using NameSet = std::unordered_set<std::string>;

class SceneReader {
 public:
  SceneReader(std::string file, const SceneOptions& options)
      : report_(std::move(file)), options_(options) {}

  Scene Read(const YamlNode& document);
  /// The version-1 spellings the last Read met, in the order met (the version line first).
  const std::vector<SceneRewrite>& rewrites() const { return rewrites_; }

  /// A reader that evaluates command-line text against a loaded scene's units and parameters.
  SceneReader(const Scene& scene, std::string source, const SceneOptions& options)
      : report_(std::move(source)), options_(options) {
    units_text_ = scene.units;
    units_ = std::make_unique<UnitSystem>(UnitSystem::Parse(scene.units));
    for (const auto& [name, q] : scene.parameters) {
      Parameter p{At{}, "", ""};
      p.state = Parameter::State::kDone;
      p.value = q;
      parameters_.emplace(name, p);
    }
  }
  Vec3 PointOption(const YamlNode& node) { return Vector(At{node, ""}, kLength, "a point"); }
  Mat3 RotationOption(const YamlNode& node) {
    const At holder{node, ""};
    report_.CheckMap(holder, {"axis", "rotation", "euler", "quaternion"}, "an orientation");
    return ReadOrientation(holder);
  }

 private:
  struct Parameter {
    At at;               // where it is defined (for messages)
    std::string text;    // its expression
    std::string origin;  // "" for the file, "--set NAME" for an override
    enum class State { kPending, kResolving, kDone } state = State::kPending;
    Quantity value{};
  };

  // Expressions --------------------------------------------------------------------------
  std::optional<Symbol> ResolveParameter(std::string_view name);
  Quantity EvaluateParameter(const std::string& name);
  Expression Compile(const At& at, const std::string& text, const SymbolResolver& resolver);
  /// A scalar of the given dimension; bare numbers are in the scene's default units.
  double Value(const At& at, const Dimension& expected, std::string_view what);
  double PositiveValue(const At& at, const Dimension& expected, std::string_view what);
  Vec3 Vector(const At& at, const Dimension& expected, std::string_view what);
  double DefaultUnitFactor(const Dimension& d) const;

  // Structure ----------------------------------------------------------------------------
  void ReadUnits(const At& root);
  void ReadParameters(const At& root);
  void ReadMaterials(const At& root);
  SceneBody ReadBody(const At& at, size_t index);
  ScenePart ReadPart(const At& at, size_t index, const At& body_at, const std::string& body_name);
  /// A `point` or `custom` part, and a part of a shape in the shape table (shape_table.cpp):
  /// mass properties in the part frame P, with P's position and orientation in B.
  MassProperties ReadPointOrCustomPart(const At& at, ScenePart& part, Vec3& p_BoPo_B, Mat3& R_BP);
  MassProperties ReadTableShapePart(const At& at, const At& shape_at, const At& body_at,
                                    ScenePart& part, Vec3& p_BoPo_B, Mat3& R_BP);
  std::vector<double> ReadDimension(const At& at, const scene_internal::DimensionKey& d);
  MassProperties ReadShapeMass(const At& at, const At& body_at, const Shape& geometry,
                               const std::string& what, ScenePart& part);
  Mat3 ReadOrientation(const At& part);
  /// Where a part's mass comes from: the one mass key it gives (two is an error), or else its
  /// body's material or density; fails with `missing` when there is none.
  struct MassSource {
    At at;
    std::string key;
  };
  MassSource FindMassSource(const At& at, const At& body_at,
                            std::initializer_list<const char*> keys, const std::string& missing);
  /// A `shape: mesh` part (scene_mesh.cpp): mass properties in the part frame. `what` names
  /// the body and the part, in errors and in the repair warnings.
  MassProperties ReadMeshPart(const At& at, const At& body_at, const std::string& what,
                              ScenePart& part);
  double MaterialDensity(const At& at);

  // Dynamics (scene_dynamics.cpp) ---------------------------------------------------------
  /// Reads gravity, every body's `initial`, forces, events, impulses, impacts, simulation and
  /// output into scene.dynamics (the bodies are already read).
  void ReadDynamics(const At& root, Scene& scene);
  /// Steps of ReadDynamics.
  void DeclareStateVariables(const Scene& scene);
  /// The slot of state variable `name` (StateVariableLayout), or -1 if it names none.
  int StateSlot(std::string_view name) const;
  /// Every state variable's name in slot order, for "did you mean" hints.
  std::vector<std::string> StateVariableNames() const;
  void ReadGravity(const At& g, SceneDynamics& dynamics);
  void ReadInitialStates(const At& root, Scene& scene);
  void ReadForces(const At& root, Scene& scene);
  SceneImpulse ReadImpulse(const At& at, const Scene& scene);
  SceneImpact ReadImpact(const At& at, const Scene& scene);
  void ReadInitial(const At& at, const SceneBody& body, SceneInitialState& initial);
  /// `v` read at `at` (an initial position or velocity); fails there when its magnitude
  /// passes kMotionScale.
  Vec3 InitialMotion(const At& at, const Vec3& v, std::string_view what, std::string_view unit);
  void ReadCable(const At& at, const Scene& scene, const std::string& what, SceneForce& f);
  void ReadStringPull(const At& at, const Scene& scene, const std::string& what, SceneForce& f);
  /// A rolling contact's `surface` (scene_surface_rolling.cpp).
  void ReadRollingSurface(const At& at, const std::string& what, SceneRolling& r);
  /// A radial bearing (scene_bearing.cpp).
  void ReadBearing(const At& at, const Scene& scene, const std::string& what, SceneForce& f);
  /// One value, or two ([along e1, along e2]), of a bearing's stiffness or damping.
  Eigen::Vector2d PairAt(const At& at, const Dimension& expected, std::string_view what);
  void ReadJointTorque(const At& at, const Scene& scene, const std::string& what, SceneForce& f);
  SceneForce ReadForce(const At& at, const Scene& scene, size_t index);
  SceneEvent ReadEvent(const At& at, size_t index, const Scene& scene);
  /// The `contact` and `change` of a contact-mode event (scene_events.cpp).
  void ReadModeEvent(const At& at, const Scene& scene, SceneEvent& event);
  /// An event's `action` (stop or record) into `event`.
  void ReadEventAction(const At& at, SceneEvent& event);
  void ReadSimulation(const At& at, SceneSimulation& simulation);
  void ReadBallCollisions(const At& at, Scene& scene);
  void ReadOutput(const At& at, Scene& scene);
  /// A body named at `at` (scene index), with a did-you-mean among the scene's bodies.
  int BodyIndexAt(const At& at, const Scene& scene);
  /// A point of body `body`: a name from its `points` or a position [x, y, z] in B.
  Vec3 BodyPointAt(const At& at, const SceneBody& body);
  /// An expression of t and the state, dimension-checked against `expected`.
  Expression StateExpression(const At& at, const Dimension& expected, std::string_view what);
  SceneVectorExpression StateVector(const At& at, const Dimension& expected, std::string_view what);
  /// A time-or-state expression's resolver: t, <body>_<suffix>, then parameters.
  std::optional<Symbol> ResolveStateSymbol(const At& at, std::string_view name);
  /// Fails with the planar names when `name` is a body's 3-D state variable (a planar scene).
  void PlanarNameHint(const At& at, std::string_view name);
  VectorFrame FrameAt(const At& at);

  // Constraints (scene_constraints.cpp) ---------------------------------------------------
  /// Reads `joints`, `rolling`, `drivers`, `gears` and `strings` into
  /// scene.dynamics.constraints.
  void ReadConstraints(const At& root, Scene& scene);
  /// Entry `i` of `joints`, `rolling`, `drivers` or `gears` (its name added to `taken`).
  SceneJoint ReadJoint(const At& at, size_t i, const Scene& scene, std::vector<std::string>& taken);
  SceneRolling ReadRolling(const At& at, size_t i, const Scene& scene,
                           std::vector<std::string>& taken);
  SceneDriver ReadDriver(const At& at, size_t i, const Scene& scene,
                         std::vector<std::string>& taken);
  SceneGear ReadGear(const At& at, size_t i, const Scene& scene, std::vector<std::string>& taken);
  /// Entry `i` of `strings`, its ends and a drum's or pulley's sense (+1 counterclockwise).
  SceneString ReadString(const At& at, size_t i, const Scene& scene,
                         std::vector<std::string>& taken);
  SceneStringEnd ReadStringEnd(const At& at, const Scene& scene, const std::string& what);
  int StringSenseAt(const At& at);
  /// Fails unless the gear's pitch circles touch at the initial configuration.
  void CheckPitchCirclesTouch(const At& at, const SceneGear& gear);
  /// A body name or `world` (kWorld).
  int ParentIndexAt(const At& at, const Scene& scene);
  /// A unit direction from a vector of any length; fails for a zero vector.
  Vec3 AxisAt(const At& at, std::string_view what);
  /// The entry's name (or "<kind>N"), unique among all constraints (`taken`).
  std::string ConstraintName(const At& at, const char* kind, size_t index,
                             std::vector<std::string>& taken);

  // Format versions (scene_versions.cpp) ----------------------------------------------------
  /// Reads `chasles` (the format version; a file without it is version 1) into version_ and
  /// scene.format_version; a file of an older version gets the rewrite of its version line.
  void ReadVersion(const At& root, Scene& scene);
  /// A world vector of a planar scene given as three values at `at` (`form` is its planar
  /// form, "[x, y]" or "[Fx, Fy]"): in a version-1 file whose third value is 0 (`zero_z`,
  /// asked only there) a warning and a rewrite to two values, after which the caller reads the
  /// first two; otherwise fails naming the two-value form.
  void PlanarThreeValues(const At& at, std::string_view what, const char* form,
                         const std::function<bool()>& zero_z);
  /// A version-1 name of a planar scene's body variable ("rod_wz" for "rod_omega"): in a
  /// version-1 file the symbol of its new name, with a warning and a rewrite for each use in
  /// the expression at `at`; in a later one fails naming the new name. nullopt for any other
  /// name.
  std::optional<Symbol> PlanarOldName(const At& at, std::string_view name);
  /// After `simulation`: a scene with contacts that names no integrator runs `auto` in version
  /// 3 (sim.auto_by_default); in versions 1 and 2 it runs `adaptive`, with a warning and a
  /// rewrite that writes `integrator: adaptive` into the file.
  void DefaultIntegrator(const At& root, Scene& scene);
  /// A warning naming the place and the new spelling of an old version's one (rewritten by
  /// `chasles upgrade`), and the rewrite.
  void OldSpelling(SceneRewrite rewrite, const std::string& what);

  // Planar scenes (scene_planar.cpp) -------------------------------------------------------
  /// Reads `planar` (before the bodies).
  void ReadPlanar(const At& root, Scene& scene);
  /// A world-frame vector: [x, y] in a planar scene (z = 0; three values are an error),
  /// [x, y, z] otherwise.
  Vec3 WorldVector(const At& at, const Dimension& expected, std::string_view what);
  /// A body-frame vector: [x, y] or [x, y, z] in a planar scene, [x, y, z] otherwise.
  Vec3 BodyVector(const At& at, const Dimension& expected, std::string_view what);
  /// A unit direction in the body frame: [x, y] or [x, y, z] in a planar scene, [x, y, z]
  /// otherwise; fails for a zero vector.
  Vec3 BodyAxisAt(const At& at, std::string_view what);
  /// The axis `key` of `holder` in a planar scene: z when absent; present, it must point along
  /// +z (anything else, [x, y] included, is an error naming `what`).
  Vec3 PlanarZAxis(const At& holder, const char* key, std::string_view what);
  /// A force [Fx, Fy] or a moment Mz (a scalar about z) of t and the state, as a 3-vector.
  SceneVectorExpression PlanarStateVector(const At& at, const Dimension& expected,
                                          std::string_view what, bool moment);
  /// `initial` of a body in a planar scene: position [x, y], theta, velocity [vx, vy], omega.
  void ReadPlanarInitial(const At& at, const SceneBody& body, SceneInitialState& initial);
  /// A `shape: planar` part (mass, inertia_z or radius_of_gyration, center_of_mass [x, y]).
  MassProperties ReadPlanarPart(const At& at, ScenePart& part, Vec3& p_BoPo_B);
  /// A joint's type and axis in a planar scene (in-plane joint kinds).
  void ReadPlanarJointType(const At& at, const std::string& what, SceneJoint& joint);
  /// A rolling contact in a planar scene: a wheel on a line of the plane.
  void ReadPlanarRolling(const At& at, const SceneBody& body, const std::string& what,
                         SceneRolling& rolling);
  // Contacts (scene_contacts.cpp) ---------------------------------------------------------
  /// Reads `material_pairs` and `contacts` into scene.dynamics.contacts (after the
  /// constraints, whose names contacts must not reuse).
  void ReadContacts(const At& root, Scene& scene);
  /// An entry of `material_pairs` (not one of `pairs`, those read before it).
  SceneMaterialPair ReadMaterialPair(const At& at, const std::vector<SceneMaterialPair>& pairs);
  /// Entry `i` of `contacts` (its name added to `taken`), and its steps: the shape and its
  /// keys, the body's points of it (`points`, `center`), the plane or other body, the material
  /// pair named at `m`.
  SceneContact ReadContact(const At& at, size_t i, const Scene& scene, NameSet& taken);
  void ReadContactShape(const At& at, const std::string& what, const SceneBody& body,
                        SceneContact& c);
  void ReadContactBodyPoints(const At& at, const SceneBody& body, SceneContact& c);
  // Contact entries naming sets of bodies (scene_contact_sets.cpp) ------------------------
  /// Whether entry `at` names a set (`between`, or a list, a pattern or `all` in `body` or
  /// `with` where no body has that name).
  bool IsContactSet(const At& at, const Scene& scene);
  /// Entry `i` naming a set: the contacts it stands for (ExpandContactSet), appended to `out`
  /// with their names added to `taken` and their targets to `targets`.
  void ReadContactSet(const At& at, size_t i, const Scene& scene, NameSet& taken,
                      ContactTargetIndex& targets, std::vector<SceneContact>& out);
  /// The set written at `at` (a list, a pattern, `all`, or a body's name).
  BodySet BodySetAt(const At& at);
  /// The template of a set entry's contacts: shape, plane or other sphere, coefficients
  /// (read once; `first` stands for the body-dependent keys until each body's are read).
  SceneContact ReadContactSetTemplate(const At& at, const std::string& what,
                                      const ContactBodySets& sets, const Scene& scene,
                                      const SceneBody& first);
  /// Fails at the item (`item`) that brought `body` into the set written at `set_at` when one
  /// of its parts has a shape that the contact's shape does not describe.
  void CheckSetBodyFits(const At& set_at, int item, const SceneBody& body, SceneContactShape shape);
  /// Fails with the error of ExpandContactSet or ResolveBodySet at its set and item.
  [[noreturn]] void FailAtSet(const At& at, const BodySetError& e);
  /// Fails at `at` when `c` (contact `index` of `contacts`, from a set or not) touches what an
  /// earlier contact does that it may not share with (ContactTargetIndex), naming both.
  void CheckContactTarget(const At& at, const std::vector<SceneContact>& contacts,
                          const SceneContact& c, int index, bool from_set,
                          ContactTargetIndex& targets);
  void ReadContactCounterpart(const At& at, const std::string& what, const Scene& scene,
                              SceneContact& c);
  void ReadContactMaterials(const At& m, const std::vector<SceneMaterialPair>& pairs,
                            SceneContact& c);
  /// mu_s, mu_k, mu_r, restitution and restitution_law of a contact or material pair,
  /// validated; with `have_defaults` the values passed in (a material pair's) are kept where a
  /// key is absent.
  void ReadContactCoefficients(const At& at, double& mu_s, double& mu_k, double& mu_r,
                               double& restitution, RestitutionLaw& law, bool have_defaults);

  Reporter report_;
  SceneOptions options_;
  /// The file's format version (`chasles`; 1 when it has none).
  int version_ = 1;
  std::vector<SceneRewrite> rewrites_;
  bool planar_ = false;
  std::unique_ptr<UnitSystem> units_;
  std::string units_text_ = "SI";
  std::map<std::string, Parameter, std::less<>> parameters_;
  /// The text of each --set override as a one-scalar document, which its parameter's node
  /// points into (a list: the documents do not move).
  std::list<YamlDocument> override_documents_;
  std::vector<std::string> resolving_;  // parameters being evaluated, for cycle messages
  std::map<std::string, double, std::less<>> materials_;  // the scene's own, by name
  std::vector<std::string> warnings_;
  /// Names hashed as views, so a name's parts are looked up without copies.
  struct NameHash {
    using is_transparent = void;
    size_t operator()(std::string_view s) const { return std::hash<std::string_view>{}(s); }
  };
  using NameIndex = std::unordered_map<std::string, size_t, NameHash, std::equal_to<>>;
  /// The owners of state-variable names, by index: bodies (scene order), constraints (their
  /// reactions), contact points (SceneContacts::point_labels() order); identifiers only.
  NameIndex state_bodies_, state_constraints_, state_points_;
  bool state_planar_ = false;
  // First slot of the constraints' reaction variables (after every body's block), and whether
  // the expression being read may use them (only events' `when`).
  int reaction_slot_begin_ = std::numeric_limits<int>::max();
  // First slot of the contact points' variables (after the reactions; kContactSuffixes each).
  int contact_slot_begin_ = std::numeric_limits<int>::max();
  bool allow_reactions_ = false;
};

/// Reads a parsed YAML document as a scene named `name` in messages.
Scene ReadSceneDocument(const YamlNode& document, const std::string& name,
                        const SceneOptions& options);

}  // namespace chasles::scene_internal
