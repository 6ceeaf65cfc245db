// Mesh parts of a scene: `shape: mesh` with a file, its length unit, solid or shell mode and
// a mass; and mesh files given straight to the command line.

#include <filesystem>

#include <fmt/format.h>

#include "chasles/scene/mesh_file.h"
#include "chasles/scene/scene_error.h"
#include "internal/scene_reader.h"

namespace chasles::scene_internal {

namespace {

// The remarks a mesh part shows in the report: what was read and what was repaired.
std::vector<std::string> MeshNotes(const MeshMassReport& r) {
  std::vector<std::string> notes;
  std::string read = fmt::format("{}, {} triangles", r.format, r.triangles);
  if (r.repair.vertices_in != r.repair.vertices_out) {
    read += fmt::format(", {} vertices welded to {}", r.repair.vertices_in, r.repair.vertices_out);
  }
  if (r.repair.degenerate_dropped > 0) {
    read += fmt::format(", {} degenerate triangles dropped", r.repair.degenerate_dropped);
  }
  if (r.repair.triangles_flipped > 0) {
    read += fmt::format(", {} triangles re-oriented", r.repair.triangles_flipped);
  }
  if (r.repair.inside_out_flipped) read += ", turned right side out";
  notes.push_back(read);
  if (r.single_precision) {
    // The file's floats place a vertex only to their spacing at its magnitude: what that is
    // here, absolutely and against the mesh's size (its bounding-box diagonal).
    notes.push_back(fmt::format(
        "{} stores float32: coordinates resolved to {:.2g} m at this mesh's extent (|x| up to "
        "{:.6g} m), relative {:.1e} of its size {:.3g} m (ASCII STL, OBJ, OFF or PLY double "
        "keep every digit)",
        r.format == "PLY" ? "binary PLY 'float'" : r.format, r.float32_spacing,
        r.max_abs_coordinate, r.float32_spacing / r.extent, r.extent));
  }
  return notes;
}
}  // namespace

MassProperties SceneReader::ReadMeshPart(const At& at, const At& body_at, const std::string& what,
                                         ScenePart& part) {
  report_.CheckMap(at,
                   {"name", "shape", "subtract", "file", "unit", "mode", "mass", "density",
                    "material", "areal_density", "thickness", "weld_tolerance", "position", "axis",
                    "rotation", "euler", "quaternion"},
                   "a mesh part");
  const At file_at = report_.Require(at, "file", what);
  std::filesystem::path path(report_.Text(file_at, "a mesh file name"));
  if (path.is_relative()) {
    // Relative to the scene file, so a scene and its meshes move together.
    const std::filesystem::path dir = std::filesystem::path(report_.file()).parent_path();
    if (!dir.empty() && std::filesystem::exists(dir)) path = dir / path;
  }
  MeshMassOptions options;
  // Mesh files carry no units: the scene says how long one file unit is ("mm", "0.5 in").
  options.scale = PositiveValue(report_.Require(at, "unit", what + " (mesh files carry no units)"),
                                kLength, "the length of one file unit");
  if (at.Has("mode")) {
    const std::string mode = report_.Text(at.Child("mode"), "solid or shell");
    if (mode == "shell") {
      options.mode = MeshMassMode::kShell;
    } else if (mode != "solid") {
      report_.Fail(at.Child("mode"),
                   fmt::format("mode '{}' is not known: use solid (a closed surface bounding a "
                               "volume) or shell (a thin sheet)",
                               mode));
    }
  }
  const bool shell = options.mode == MeshMassMode::kShell;
  if (at.Has("weld_tolerance")) {
    const At w = at.Child("weld_tolerance");
    options.weld_tolerance = Value(w, kLength, "the weld tolerance");
    if (options.weld_tolerance < 0) report_.Fail(w, "the weld tolerance cannot be negative");
  }

  const auto [source, key] =
      FindMassSource(at, body_at, {"mass", "density", "material", "areal_density"},
                     fmt::format("{} has no mass: give 'mass', 'density' or 'material'{}", what,
                                 shell ? " (with 'thickness'), or 'areal_density'" : ""));
  if (at.Has("thickness") && !shell) {
    report_.Fail(at.Child("thickness"), "'thickness' is for mode: shell");
  }
  if (key == "areal_density" && !shell) {
    report_.Fail(source, "'areal_density' is for mode: shell; a solid takes 'density'");
  }
  if (key == "mass") {
    options.mass = PositiveValue(source, kMass, "the mass");
    part.mass_source = "mass";
  } else if (key == "areal_density") {
    options.areal_density = PositiveValue(source, kArealDensity, "the areal density");
    part.mass_source = "areal_density";
  } else {
    const double rho = key == "material" ? MaterialDensity(source)
                                         : PositiveValue(source, kDensity, "the density");
    part.density = rho;
    part.mass_source = key == "material" ? std::string(source.node.Scalar()) : "density";
    options.density = rho;
    if (shell) {
      if (!at.Has("thickness")) {
        report_.Fail(source,
                     "a shell is a thin sheet (an area, no volume): give 'thickness' "
                     "with a density or material, or 'areal_density', or 'mass'");
      }
      options.thickness = PositiveValue(at.Child("thickness"), kLength, "the thickness");
    }
  }

  MeshMassResult result;
  try {
    result = LoadMeshMassProperties(path.string(), options);
  } catch (const InputError& e) {
    report_.Fail(file_at, e.what());
  }
  part.notes = MeshNotes(result.report);
  part.geometry.mesh_file = path.string();
  part.geometry.mesh_scale = options.scale;
  // A shell is a sheet: no volume, its area; a solid: the divergence-theorem volume and the
  // sum of the triangles' areas.
  part.volume = shell ? 0.0 : result.report.volume;
  part.surface_area = result.report.surface_area;
  for (const std::string& w : result.report.repair.warnings) {
    warnings_.push_back(fmt::format("{}: {}", what, w));
  }
  return result.mass_properties;
}

}  // namespace chasles::scene_internal

namespace chasles {

bool IsMeshFileName(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".stl" || ext == ".obj" || ext == ".ply" || ext == ".off";
}

Scene LoadMeshAsScene(const std::string& path, const MeshCommandOptions& o) {
  // The options are written as they would be in a scene, so they go through the same checks
  // and messages as a `shape: mesh` part; errors then name the option, not a scene key.
  if (o.unit.empty()) {
    throw SceneError("command line", 0, 0, "--unit",
                     "a mesh file carries no units: say how long one of its units is, e.g. "
                     "--unit mm");
  }
  if ((o.density + o.material + o.mass + o.areal_density).empty()) {
    throw SceneError("command line", 0, 0, "",
                     "the mesh needs a mass: give --density, --material or --mass (shell mode: "
                     "--areal-density, or --thickness with --density or --material)");
  }
  scene_internal::YamlDocument doc;
  using Pairs = std::vector<
      std::pair<scene_internal::YamlDocument::Index, scene_internal::YamlDocument::Index>>;
  Pairs part;
  const auto add = [&doc](Pairs& map, const char* key, const std::string& value) {
    if (!value.empty()) map.emplace_back(doc.AddScalar(key), doc.AddScalar(value));
  };
  add(part, "name", std::filesystem::path(path).filename().string());
  add(part, "shape", "mesh");
  add(part, "file", std::filesystem::absolute(path).string());
  add(part, "unit", o.unit);
  add(part, "mode", o.mode);
  add(part, "density", o.density);
  add(part, "material", o.material);
  add(part, "mass", o.mass);
  add(part, "areal_density", o.areal_density);
  add(part, "thickness", o.thickness);
  Pairs body;
  add(body, "name", std::filesystem::path(path).stem().string());
  body.emplace_back(doc.AddScalar("parts"), doc.AddSequence({doc.AddMap(part)}));
  Pairs document;
  add(document, "title", std::filesystem::path(path).filename().string());
  document.emplace_back(doc.AddScalar("bodies"), doc.AddSequence({doc.AddMap(body)}));
  doc.SetRoot(doc.AddMap(document));
  try {
    return scene_internal::ReadSceneDocument(doc.Root(), path, SceneOptions{});
  } catch (const SceneError& e) {
    std::string key = e.key();
    const std::string prefix = "bodies[0].parts[0]";
    if (key.rfind(prefix, 0) == 0) {
      key = key.size() > prefix.size() ? "--" + key.substr(prefix.size() + 1) : "";
      for (char& c : key) c = c == '_' ? '-' : c;
    }
    if (key == "--file") key.clear();
    throw SceneError("command line", 0, 0, key, e.message());
  }
}

}  // namespace chasles
