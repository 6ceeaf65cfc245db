#pragma once
/// @file
/// Exact mass properties of triangle meshes (CAD parts).
///
/// Solid mode: the mesh bounds a homogeneous solid; volume, first and second moments follow
/// exactly from the divergence theorem (signed tetrahedra, see mesh_mass.cpp). Shell mode: the
/// mesh is a sheet of uniform areal density in the thin-shell limit (mass on the surface).
/// Both are exact for the polyhedral surface given; a tessellated curved part is off by the
/// tessellation error, which falls with the square of the edge length.
///
/// Precision: the integrals are taken about a reference point inside the mesh's bounding box
/// (its centre), in the mesh's own unit, and only then scaled to metres and shifted back by the
/// parallel-axis theorem; so a small part far from its frame's origin (CAD assembly
/// coordinates) keeps every digit of its vertices: a vertex minus a nearby reference point is
/// exact in double (Sterbenz), and the unit's scale multiplies the results, not the vertices.

#include <limits>
#include <string>
#include <vector>

#include "chasles/mass/mass_properties.h"
#include "chasles/mass/triangle_mesh.h"
#include "chasles/math/types.h"

namespace chasles {

/// Integrals over a mesh about a reference point R chosen near it (for round-off).
/// measure = ∫ dΩ, first_moment = ∫ r dΩ, second_moment = ∫ r rᵀ dΩ with r measured from R,
/// where Ω is the enclosed solid (volume) or the surface (area).
struct MeshIntegrals {
  /// Reference point R, from the mesh frame's origin [m].
  Vec3 p_BoR_B = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  /// Volume [m³] (solid) or area [m²] (shell).
  double measure = std::numeric_limits<double>::quiet_NaN();
  /// ∫ r dΩ about R [m⁴ or m³].
  Vec3 first_moment = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  /// ∫ r rᵀ dΩ about R [m⁵ or m⁴].
  Mat3 second_moment = Mat3::Constant(std::numeric_limits<double>::quiet_NaN());
};

/// Volume integrals of the solid bounded by a closed, outward-oriented mesh (ValidateSolid).
/// Compensated summation keeps the error near round-off for 10^7 triangles.
MeshIntegrals CalcSolidIntegrals(const TriangleMesh& mesh);
/// Area integrals over the surface of any mesh (open or closed, orientation irrelevant).
MeshIntegrals CalcShellIntegrals(const TriangleMesh& mesh);
/// Mass properties of a uniform distribution over the integrals' domain: `density` is per
/// unit measure [kg/m³ for a solid, kg/m² for a shell]. Centre of mass and inertia about it,
/// in the mesh's frame.
MassProperties MassPropertiesFromIntegrals(const MeshIntegrals& integrals, double density);

/// How a mesh's material is given.
enum class MeshMassMode {
  /// The mesh bounds a solid (must be closed and manifold): give density or mass.
  kSolid,
  /// The mesh is a thin sheet: give areal_density, or thickness and density, or mass.
  kShell,
};

/// Options of ComputeMeshMassProperties. Exactly one way to give the material must be set.
struct MeshMassOptions {
  /// Solid or thin shell.
  MeshMassMode mode = MeshMassMode::kSolid;
  /// Length of one file unit [m] (0.001 for a file in millimetres).
  double scale = 1.0;
  /// Density [kg/m³]: solid mode, or shell mode together with thickness.
  double density = std::numeric_limits<double>::quiet_NaN();
  /// Total mass [kg], instead of a density.
  double mass = std::numeric_limits<double>::quiet_NaN();
  /// Areal density [kg/m²], shell mode.
  double areal_density = std::numeric_limits<double>::quiet_NaN();
  /// Sheet thickness [m], shell mode (with density).
  double thickness = std::numeric_limits<double>::quiet_NaN();
  /// Vertices closer than this are merged [m, after scaling]; NaN means
  /// kDefaultWeldRelativeTolerance times the bounding-box diagonal; 0 merges exact duplicates.
  double weld_tolerance = std::numeric_limits<double>::quiet_NaN();
};

/// What ComputeMeshMassProperties read, repaired and computed.
struct MeshMassReport {
  /// File read (empty for an in-memory mesh).
  std::string path;
  /// Format read ("binary STL", "ASCII STL", "OBJ", "PLY", ...).
  std::string format;
  /// True when the file stores its coordinates as floats (MeshFileData::single_precision: binary
  /// STL, binary PLY `float`); the caller that read the file sets it.
  bool single_precision = false;
  /// Largest |x|, |y| or |z| of the welded vertices, in the mesh's frame [m].
  double max_abs_coordinate = std::numeric_limits<double>::quiet_NaN();
  /// Diagonal of the welded vertices' bounding box [m].
  double extent = std::numeric_limits<double>::quiet_NaN();
  /// When single_precision: the spacing of floats at max_abs_coordinate (in the file's unit,
  /// then scaled) [m], how finely the file can place this mesh's vertices; NaN otherwise.
  double float32_spacing = std::numeric_limits<double>::quiet_NaN();
  /// Welding, degenerate triangles, orientation repairs and warnings.
  MeshRepairReport repair;
  /// Triangles used in the integrals.
  std::size_t triangles = 0;
  /// Enclosed volume [m³] (solid mode; NaN in shell mode).
  double volume = std::numeric_limits<double>::quiet_NaN();
  /// Surface area [m²] (shell mode; NaN in solid mode).
  double area = std::numeric_limits<double>::quiet_NaN();
  /// Surface area [m²] in either mode: the sum of the triangles' areas.
  double surface_area = std::numeric_limits<double>::quiet_NaN();
  /// Density used per unit measure [kg/m³ solid, kg/m² shell] (derived when mass is given).
  double density = std::numeric_limits<double>::quiet_NaN();
  /// Wall time reading the file [s].
  double read_seconds = 0.0;
  /// Wall time welding and dropping degenerate triangles [s].
  double weld_seconds = 0.0;
  /// Wall time validating and orienting the solid [s].
  double validate_seconds = 0.0;
  /// Wall time integrating [s].
  double integrate_seconds = 0.0;
};

/// Mass properties of a mesh and the report of how they were obtained.
struct MeshMassResult {
  /// Mass, centre of mass and inertia about it, in the file's frame after scaling.
  MassProperties mass_properties;
  /// Counts, repairs, warnings, timings.
  MeshMassReport report;
};

/// Mass properties of a triangle soup as a file reader returns it: `xyz` holds vertex
/// coordinates in the unit given by opts.scale, `indices` three vertex indices per triangle.
/// Welds and cleans it (BuildTriangleMesh), validates and orients it in solid mode
/// (ValidateSolid), integrates and applies the material, all in the file's unit (coordinates
/// and volumes in repair warnings and errors are the file's), then scales the results to SI.
/// The arrays are taken by value and released once welded, so peak memory stays near the
/// welded mesh. `what` names the source in errors ("mesh file 'part.stl'"); `report` arrives
/// with what the reader filled in (path, format, single_precision, read time). Throws
/// InputError on a bad mesh or bad options.
MeshMassResult ComputeMeshMassProperties(std::vector<double>&& xyz,
                                         std::vector<std::uint32_t>&& indices,
                                         const MeshMassOptions& opts, const std::string& what,
                                         MeshMassReport report = {});

/// The same for a triangle soup of floats (a binary STL; see BuildTriangleSoup): the same
/// result as the overload above given these floats widened to double and the indices 0, 1,
/// 2, ..., with 36 bytes of coordinates a triangle instead of 84 in memory.
MeshMassResult ComputeMeshMassProperties(std::vector<float>&& soup, const MeshMassOptions& opts,
                                         const std::string& what, MeshMassReport report = {});

/// The same for a triangle soup of floats read in place (a binary STL mapped into memory; see
/// FloatSoupRecords): no copy of the coordinates at all. The records must stay readable until
/// this returns.
MeshMassResult ComputeMeshMassProperties(const FloatSoupRecords& soup, const MeshMassOptions& opts,
                                         const std::string& what, MeshMassReport report = {});

/// The same for an in-memory mesh whose vertices are in the unit given by opts.scale (welded,
/// validated and integrated in that unit too).
MeshMassResult ComputeMeshMassProperties(const TriangleMesh& mesh, const MeshMassOptions& opts);

}  // namespace chasles
