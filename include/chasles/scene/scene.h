#pragma once
/// @file
/// A scene as read from a scene file: bodies made of parts, each part's mass properties placed
/// in its body's frame. Everything here is SI; units exist only in the file and in reports.
/// The format is documented key by key in docs/scene-format.md.

#include <cstddef>
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "chasles/mass/mass_properties.h"
#include "chasles/math/types.h"
#include "chasles/scene/scene_dynamics.h"
#include "chasles/scene/units.h"

namespace chasles {

/// The scene format version this chasles writes (`chasles: 3`). It also reads versions 1 and 2
/// with the meanings they had, with a warning for each spelling a later version reads
/// differently (docs/scene-format.md, "Changes between versions").
inline constexpr int kSceneFormatVersion = 3;

/// What a drawing of a part needs (the browser report, docs/report.md): the shape's dimensions
/// and the part's own frame P in the body frame B.
struct ScenePartGeometry {
  /// The shape's dimensions [m] by key, as the scene file names them ("radius", "length",
  /// "size": three values, "vertices": six); empty for point, custom, planar and mesh parts.
  std::vector<std::pair<std::string, std::vector<double>>> dimensions;
  /// Origin of P from Bo and the orientation of P in B (the part's position and axis).
  Vec3 p_BoPo_B = Vec3::Zero();
  Mat3 R_BP = Mat3::Identity();
  /// A mesh part: the file (resolved against the scene's folder) and the length of one file
  /// unit [m].
  std::string mesh_file;
  double mesh_scale = std::numeric_limits<double>::quiet_NaN();
};

/// One part of a body, as the scene file states it.
struct ScenePart {
  /// Name from the file, or "part N" (1-based) when none was given.
  std::string name;
  /// Shape keyword ("cylinder", "mesh", "custom", ...).
  std::string shape;
  /// True for a hole or cut-out: its mass is removed from the body.
  bool subtractive = false;
  /// Where the density came from, for the report: a material name, "density", "field", "mass".
  std::string mass_source;
  /// Uniform density [kg/m³] when the part has one; NaN otherwise.
  double density = std::numeric_limits<double>::quiet_NaN();
  /// Mass properties in the body frame B; a subtractive part carries negative mass.
  MassProperties mass_properties;
  /// The part's own volume [m³] (0 for curves, surfaces and points) and the area of its
  /// bounding surface [m²] (a surface's own area; 0 for curves and points), positive for a
  /// cut too; NaN when the part has no geometry (custom).
  double volume = std::numeric_limits<double>::quiet_NaN();
  double surface_area = std::numeric_limits<double>::quiet_NaN();
  /// Remarks for the report (integration error estimates, mesh repairs).
  std::vector<std::string> notes;
  /// Line of the part in the scene file (1-based).
  int line = 0;
  /// The part's `position` value (its entry when it has none), for errors found when a run
  /// or a solve is set up.
  SceneSpot where;
  /// Its shape and place, for drawings.
  ScenePartGeometry geometry;
};

/// A named point of a body at which the report also gives the inertia.
struct ScenePoint {
  std::string name;
  /// Position from the body origin, expressed in B [m].
  Vec3 p_BoP_B;
  /// Its value in the scene file, for errors about it.
  SceneSpot where;
};

/// A rigid body: the sum of its parts.
struct SceneBody {
  std::string name;
  std::vector<ScenePart> parts;
  std::vector<ScenePoint> points;
  /// Sum of the parts, validated (positive mass, physically valid inertia).
  MassProperties mass_properties;
  int line = 0;
  /// The body's entry, for errors found when the motion is built or run.
  SceneSpot where;
};

struct Scene {
  /// File name as given (or "<built-in>" for the demonstration scene).
  std::string file;
  /// The format version the file was read as: its `chasles` key, 1 when it has none.
  int format_version = kSceneFormatVersion;
  std::string title;
  std::string description;
  /// The scene's unit choice (key `units`), e.g. "SI" or "in, lb": bare numbers in the file are
  /// read in these units and reports use them unless the user asks for others.
  std::string units = "SI";
  /// Key `planar: true`: every body moves in W's x-y plane; inputs and reports use x, y, θ
  /// (docs/scene-format.md, "Planar scenes").
  bool planar = false;
  std::vector<SceneBody> bodies;
  /// The scene's parameters with their values (SI), in the order of the file.
  std::vector<std::pair<std::string, Quantity>> parameters;
  /// Things the user should know that are not errors.
  std::vector<std::string> warnings;
  /// Gravity, initial motion, forces, events, impulses, impacts, simulation and output
  /// settings (read by `chasles simulate`; `chasles mass` ignores them).
  SceneDynamics dynamics;
};

/// The default cap on a scene file's size: 16 MiB, some 200 000 parts, which load in a few
/// seconds and well under 2 GB (docs/reliability-io.md).
inline constexpr size_t kDefaultMaxSceneBytes = size_t{16} << 20;

struct SceneOptions {
  /// Parameter overrides NAME=EXPRESSION (command line --set), applied before evaluation; each
  /// NAME must be a parameter of the scene.
  std::vector<std::pair<std::string, std::string>> parameter_overrides;
  /// The largest scene file read (bytes); a larger one is refused before it is parsed, and a
  /// pipe or device is read no further (command line --max-scene-bytes).
  size_t max_scene_bytes = kDefaultMaxSceneBytes;
};

/// Reads and validates a scene file. Throws SceneError (an InputError) with file, line, column
/// and key for anything wrong in it.
Scene LoadSceneFile(const std::string& path, const SceneOptions& options = {});

/// A point written as in a scene file ("[0, 0, 0.5 m]", "[0, L/2, 0]"), read with the scene's
/// units and parameters; for command-line options such as --about. `option` names the source
/// in errors.
Vec3 ReadPointOption(const Scene& scene, std::string_view text, std::string_view option);

/// An orientation written as in a scene file ("{axis: [0, 0, 1], angle: 30 deg}",
/// "{euler: {sequence: ZYX, angles: [...]}}"): the rotation R_BF of a frame F in the body.
Mat3 ReadRotationOption(const Scene& scene, std::string_view text, std::string_view option);

/// The same for text in memory; `name` stands for the file in messages.
Scene LoadSceneText(std::string_view text, const std::string& name,
                    const SceneOptions& options = {});

}  // namespace chasles
