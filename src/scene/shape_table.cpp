#include "internal/shape_table.h"

#include <Eigen/Core>

#include "chasles/error.h"

namespace chasles::scene_internal {

namespace {
using K = DimensionKind;

// Thin shapes with a straight or flat form: rod, ring, disk, plate.
std::vector<ShapeEntry> CurvesAndSheets() {
  return {
      {"rod",
       {{"length", K::kLength, "length of the rod"}},
       "length",
       false,
       "centred, along z",
       [](const Dimensions& d) { return MakeSlenderRod(d.at("length")); }},
      {"ring",
       {{"radius", K::kLength, "radius of the ring"}},
       nullptr,
       false,
       "centred, in the xy plane (axis z)",
       [](const Dimensions& d) { return MakeThinRing(d.at("radius")); }},
      {"disk",
       {{"radius", K::kLength, "radius of the disk"}},
       nullptr,
       false,
       "centred, in the xy plane (axis z)",
       [](const Dimensions& d) { return MakeThinDisk(d.at("radius")); }},
      {"plate",
       {{"size", K::kLengths2, "[side along x, side along y]"}},
       nullptr,
       false,
       "centred, in the xy plane",
       [](const Dimensions& d) { return MakeThinPlate(d.at("size", 0), d.at("size", 1)); }},
  };
}

// Cylinders, spheres and hemispheres: solid, thin shell and thick.
std::vector<ShapeEntry> CylindersAndSpheres() {
  return {
      {"cylinder",
       {{"radius", K::kLength, "radius"}, {"length", K::kLength, "length along the axis"}},
       "length",
       false,
       "centred, axis z",
       [](const Dimensions& d) { return MakeSolidCylinder(d.at("radius"), d.at("length")); }},
      {"cylindrical_shell",
       {{"radius", K::kLength, "radius"},
        {"length", K::kLength, "length along the axis"},
        {"closed", K::kFlag, "true adds the two end disks", true}},
       "length",
       false,
       "centred, axis z",
       [](const Dimensions& d) {
         return MakeThinCylindricalShell(d.at("radius"), d.at("length"), d.flag("closed"));
       }},
      {"tube",
       {{"inner_radius", K::kLength, "inner radius"},
        {"outer_radius", K::kLength, "outer radius"},
        {"length", K::kLength, "length along the axis"}},
       "length",
       false,
       "centred, axis z",
       [](const Dimensions& d) {
         return MakeTube(d.at("inner_radius"), d.at("outer_radius"), d.at("length"));
       }},
      {"sphere",
       {{"radius", K::kLength, "radius"}},
       nullptr,
       false,
       "centred",
       [](const Dimensions& d) { return MakeSolidSphere(d.at("radius")); }},
      {"spherical_shell",
       {{"radius", K::kLength, "radius"}},
       nullptr,
       false,
       "centred; thin wall",
       [](const Dimensions& d) { return MakeThinSphericalShell(d.at("radius")); }},
      {"thick_spherical_shell",
       {{"inner_radius", K::kLength, "inner radius"}, {"outer_radius", K::kLength, "outer radius"}},
       nullptr,
       false,
       "centred",
       [](const Dimensions& d) {
         return MakeThickSphericalShell(d.at("inner_radius"), d.at("outer_radius"));
       }},
      {"hemisphere",
       {{"radius", K::kLength, "radius"}},
       nullptr,
       false,
       "origin at the centre of the flat face, dome towards +z",
       [](const Dimensions& d) { return MakeSolidHemisphere(d.at("radius")); }},
      {"hemispherical_shell",
       {{"radius", K::kLength, "radius"}, {"closed", K::kFlag, "true adds the flat disk", true}},
       nullptr,
       false,
       "origin at the centre of the rim, dome towards +z",
       [](const Dimensions& d) {
         return MakeThinHemisphericalShell(d.at("radius"), d.flag("closed"));
       }},
  };
}

// The cone (solid, or hollow with a wall thickness) and its thin shell.
std::vector<ShapeEntry> Cones() {
  return {
      {"cone",
       {{"radius", K::kLength, "radius of the base"},
        {"height", K::kLength, "height"},
        {"thickness", K::kLength, "wall thickness of a hollow cone, normal to its side", true},
        {"closed", K::kFlag, "with thickness: a base wall of the same thickness", true}},
       "height",
       true,
       "origin at the centre of the base, apex at +z",
       [](const Dimensions& d) -> std::unique_ptr<Shape> {
         if (d.has("thickness")) {
           return MakeHollowCone(d.at("radius"), d.at("height"), d.at("thickness"),
                                 d.flag("closed"));
         }
         if (d.has("closed")) {
           throw InputError(
               "'closed' is for a hollow cone: give its wall 'thickness' too (a solid cone has "
               "its base already), or remove 'closed'");
         }
         return MakeSolidCone(d.at("radius"), d.at("height"));
       }},
      {"conical_shell",
       {{"radius", K::kLength, "radius of the base"},
        {"height", K::kLength, "height"},
        {"closed", K::kFlag, "true adds the base disk", true}},
       "height",
       true,
       "origin at the centre of the base, apex at +z",
       [](const Dimensions& d) {
         return MakeThinConicalShell(d.at("radius"), d.at("height"), d.flag("closed"));
       }},
  };
}

// The box, the ellipsoid, the torus and its shell, the triangular prism.
std::vector<ShapeEntry> OtherSolids() {
  return {
      {"box",
       {{"size", K::kLengths3, "[side along x, along y, along z]"}},
       nullptr,
       false,
       "centred, sides along x, y, z",
       [](const Dimensions& d) {
         return MakeBox(d.at("size", 0), d.at("size", 1), d.at("size", 2));
       }},
      {"ellipsoid",
       {{"semi_axes", K::kLengths3, "[semi-axis along x, along y, along z]"}},
       nullptr,
       false,
       "centred, semi-axes along x, y, z",
       [](const Dimensions& d) {
         return MakeEllipsoid(d.at("semi_axes", 0), d.at("semi_axes", 1), d.at("semi_axes", 2));
       }},
      {"torus",
       {{"major_radius", K::kLength, "radius of the tube's centre line"},
        {"minor_radius", K::kLength, "radius of the tube"}},
       nullptr,
       false,
       "centred, axis z",
       [](const Dimensions& d) { return MakeTorus(d.at("major_radius"), d.at("minor_radius")); }},
      {"toroidal_shell",
       {{"major_radius", K::kLength, "radius of the tube's centre line"},
        {"minor_radius", K::kLength, "radius of the tube"}},
       nullptr,
       false,
       "centred, axis z",
       [](const Dimensions& d) {
         return MakeThinToroidalShell(d.at("major_radius"), d.at("minor_radius"));
       }},
      {"triangular_prism",
       {{"vertices", K::kTriangle2, "[[x, y], [x, y], [x, y]]: the triangle in the xy plane"},
        {"length", K::kLength, "extrusion length along z"}},
       "length",
       false,
       "triangle in the xy plane as given, extruded along z, centred in z",
       [](const Dimensions& d) {
         const auto& v = d.values.find("vertices")->second;
         return MakeTriangularPrism(Eigen::Vector2d(v[0], v[1]), Eigen::Vector2d(v[2], v[3]),
                                    Eigen::Vector2d(v[4], v[5]), d.at("length"));
       }},
  };
}

std::vector<ShapeEntry> MakeTable() {
  std::vector<ShapeEntry> table;
  for (auto&& group : {CurvesAndSheets(), CylindersAndSpheres(), Cones(), OtherSolids()}) {
    table.insert(table.end(), group.begin(), group.end());
  }
  return table;
}
}  // namespace

const std::vector<ShapeEntry>& ShapeTable() {
  static const std::vector<ShapeEntry> table = MakeTable();
  return table;
}

const std::vector<std::string>& ShapeNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const auto& e : ShapeTable()) n.emplace_back(e.name);
    return n;
  }();
  return names;
}

const ShapeEntry* FindShape(std::string_view name) {
  if (name == "hoop") name = "ring";
  if (name == "cuboid") name = "box";
  if (name == "slender_rod") name = "rod";
  for (const auto& e : ShapeTable()) {
    if (name == e.name) return &e;
  }
  return nullptr;
}

}  // namespace chasles::scene_internal
