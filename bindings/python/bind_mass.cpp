// Mass properties: inertia tensors, the shapes of Appendix A, meshes.

#include <memory>

#include "bindings.h"
#include "chasles/error.h"
#include "chasles/mass/mass_properties.h"
#include "chasles/mass/mesh_mass.h"
#include "chasles/mass/rotational_inertia.h"
#include "chasles/mass/shape.h"
#include "chasles/scene/mesh_file.h"

namespace chasles::python {

namespace {

/// sqrt(I/m) about each axis (eq. 8.19); InputError when that is not a number (a mass that is
/// not positive, a moment past a double's range), rather than NaN radii.
Vec3 RadiiOfGyration(const RotationalInertia& I, double mass) {
  const Vec3 k = I.CalcRadiiOfGyration(mass);
  if (!k.allFinite()) {
    throw InputError("the radii of gyration sqrt(I/m) are not finite numbers for a mass of " +
                     std::string(py::str(py::float_(mass))) +
                     " kg: they need a positive mass and finite moments");
  }
  return k;
}

MeshMassOptions MeshOptions(const std::string& mode, double scale, double density, double mass,
                            double areal_density, double thickness) {
  MeshMassOptions o;
  if (mode == "solid") {
    o.mode = MeshMassMode::kSolid;
  } else if (mode == "shell") {
    o.mode = MeshMassMode::kShell;
  } else {
    throw InputError("mode must be 'solid' or 'shell', got '" + mode + "'");
  }
  o.scale = scale;
  o.density = density;
  o.mass = mass;
  o.areal_density = areal_density;
  o.thickness = thickness;
  return o;
}

void BindInertia(py::module_& m) {
  py::class_<PrincipalAxes>(m, "PrincipalAxes",
                            "Principal moments (ascending) and axes of an inertia tensor.")
      .def_readonly("moments", &PrincipalAxes::moments, "I1 <= I2 <= I3 [kg*m^2]")
      .def_readonly("axes", &PrincipalAxes::axes,
                    "Columns are the unit principal axes in the tensor's frame (det +1)");

  py::class_<RotationalInertia>(
      m, "RotationalInertia",
      "An inertia tensor [kg*m^2] (eq. 8.16): moments on the diagonal, products as tensor "
      "entries Ixy = -integral(x y dm), so that H = [I] w.")
      .def(py::init<double, double, double, double, double, double>(), py::arg("Ixx"),
           py::arg("Iyy"), py::arg("Izz"), py::arg("Ixy") = 0.0, py::arg("Ixz") = 0.0,
           py::arg("Iyz") = 0.0, "From the tensor entries (products as they stand in [I]).")
      .def_static(
          "from_matrix",
          [](const Mat3& m) { return RotationalInertia::FromMatrix(RequireFinite(m, "matrix")); },
          py::arg("matrix"), "From a symmetric 3x3 matrix.")
      .def_property_readonly("matrix", &RotationalInertia::matrix, "The 3x3 tensor [kg*m^2]")
      .def("principal_axes", &RotationalInertia::CalcPrincipalAxes,
           "Principal moments (ascending) and right-handed axes.")
      .def(
          "radii_of_gyration",
          [](const RotationalInertia& I, double mass) { return RadiiOfGyration(I, mass); },
          py::arg("mass"), "Radii of gyration about the frame's axes, sqrt(I/m) (eq. 8.19) [m].")
      .def("check_physically_valid", &RotationalInertia::CheckPhysicallyValid,
           "'' when the tensor could belong to a real body, else the rule it breaks.")
      .def(
          "re_expressed_in",
          [](const RotationalInertia& I, const Mat3& R) {
            const RotationalInertia out = I.ReExpressedIn(RequireFinite(R, "R_AB"));
            FiniteResult(out.matrix(), "the re-expressed tensor");
            return out;
          },
          py::arg("R_AB"), "The tensor in frame A given R_AB: R I R^T.")
      .def(
          "shift_from_center_of_mass",
          [](const RotationalInertia& I, double mass, const Vec3& p) {
            RequireFinite(Eigen::Matrix<double, 1, 1>(mass), "mass");
            const RotationalInertia out = I.ShiftFromCenterOfMass(mass, RequireFinite(p, "p_PCm"));
            FiniteResult(out.matrix(), "the shifted tensor");
            return out;
          },
          py::arg("mass"), py::arg("p_PCm"),
          "Parallel-axis theorem (eq. 8.29): this tensor about the centre of mass; returns it "
          "about P, p_PCm being the centre of mass from P.")
      .def("__repr__", [](const RotationalInertia& I) {
        return py::str("RotationalInertia({})").format(py::cast(I.matrix()));
      });
}

void BindMassProperties(py::module_& m) {
  py::class_<MassProperties>(m, "MassProperties",
                             "Mass, centre of mass and inertia about it, in a body's frame B.")
      .def(py::init<double, const Vec3&, const RotationalInertia&>(), py::arg("mass"),
           py::arg("center_of_mass"), py::arg("inertia"),
           "mass [kg], centre of mass from B's origin [m], inertia about it [kg*m^2], in B.")
      .def_static(
          "point_mass",
          [](double mass, const Vec3& p) {
            RequireFinite(Eigen::Matrix<double, 1, 1>(mass), "mass");
            return MassProperties::PointMass(mass, RequireFinite(p, "position"));
          },
          py::arg("mass"), py::arg("position"), "A point mass at `position` [m].")
      .def_property_readonly("mass", &MassProperties::mass, "Mass [kg]")
      .def_property_readonly("center_of_mass", &MassProperties::p_BoBcm_B,
                             "Centre of mass from B's origin, in B [m]")
      .def_property_readonly(
          "inertia", [](const MassProperties& mp) { return mp.I_BBcm_B().matrix(); },
          "Inertia tensor about the centre of mass, in B [kg*m^2] (3x3)")
      .def_property_readonly("rotational_inertia", &MassProperties::I_BBcm_B,
                             "The same as a RotationalInertia")
      .def(
          "inertia_about",
          [](const MassProperties& mp, const Vec3& p) {
            return FiniteResult(mp.CalcInertiaAbout(RequireFinite(p, "point")).matrix(),
                                "the inertia about the point");
          },
          py::arg("point"),
          "Inertia tensor about a point given from B's origin in B (eq. 8.29) [kg*m^2].")
      .def_property_readonly(
          "principal_moments",
          [](const MassProperties& mp) { return mp.I_BBcm_B().CalcPrincipalAxes().moments; },
          "Principal moments about the centre of mass, ascending [kg*m^2]")
      .def_property_readonly(
          "principal_axes",
          [](const MassProperties& mp) { return mp.I_BBcm_B().CalcPrincipalAxes().axes; },
          "Principal axes (columns, in B) matching principal_moments")
      .def_property_readonly(
          "radii_of_gyration",
          [](const MassProperties& mp) { return RadiiOfGyration(mp.I_BBcm_B(), mp.mass()); },
          "Radii of gyration about B's axes through the centre of mass [m]")
      .def_property_readonly(
          "principal_radii_of_gyration",
          [](const MassProperties& mp) {
            const PrincipalAxes pa = mp.I_BBcm_B().CalcPrincipalAxes();
            return RadiiOfGyration(RotationalInertia(pa.moments[0], pa.moments[1], pa.moments[2]),
                                   mp.mass());
          },
          "Radii of gyration about the principal axes [m]")
      .def(
          "expressed_in_parent",
          [](const MassProperties& mp, const Mat3& R, const Vec3& p) {
            const MassProperties out =
                mp.ExpressedInParent(RequireFinite(R, "R_BP"), RequireFinite(p, "p_BoPo_B"));
            FiniteResult(out.I_BBcm_B().matrix(), "the inertia expressed in the parent");
            FiniteResult(out.p_BoBcm_B(), "the centre of mass expressed in the parent");
            return out;
          },
          py::arg("R_BP"), py::arg("p_BoPo_B"),
          "These properties of a part whose frame P is at p_BoPo_B in B, rotated by R_BP, "
          "expressed in B.")
      .def("__add__", &MassProperties::operator+, "Composite body (eqs. 8.4, 8.29).")
      .def("negated", &MassProperties::Negated, "The same with negative mass (a hole).")
      .def("validate", &MassProperties::Validate, py::arg("what") = "mass properties",
           "Raises InputError unless mass > 0 and the inertia is physically valid.")
      .def("__repr__", [](const MassProperties& mp) {
        return py::str("MassProperties(mass={}, center_of_mass={})")
            .format(mp.mass(), py::cast(mp.p_BoBcm_B()));
      });
}

void BindShapes(py::module_& m) {
  py::class_<Shape, std::shared_ptr<Shape>>(
      m, "Shape", "A primitive shape of Appendix A (axis of symmetry along z, see shape.h).")
      .def_property_readonly(
          "kind", [](const Shape& s) { return std::string(s.kind()); },
          "Type name as a scene writes it, e.g. 'cylinder'")
      .def("describe", &Shape::Describe, "e.g. 'cylinder (radius 0.1 m, length 0.5 m)'")
      .def("measure", &Shape::CalcMeasure, "Length [m], area [m^2] or volume [m^3]")
      .def("surface_area", &Shape::CalcSurfaceArea,
           "Area of the bounding surface [m^2] (a surface: its area; a curve: 0)")
      .def("centroid", &Shape::CalcCentroid, "Centroid in the shape's frame [m]")
      .def(
          "unit_inertia", [](const Shape& s) { return s.CalcUnitInertia().matrix(); },
          "Inertia of unit mass about the centroid [m^2]")
      .def("mass_properties", &Shape::CalcMassProperties, py::arg("mass"),
           "Mass properties for a uniform distribution of `mass` [kg].");
  const auto to_shared = [](std::unique_ptr<Shape> s) {
    return std::shared_ptr<Shape>(std::move(s));
  };
  m.def(
      "rod", [=](double L) { return to_shared(MakeSlenderRod(L)); }, py::arg("length"),
      "Slender rod along z.");
  m.def(
      "ring", [=](double R) { return to_shared(MakeThinRing(R)); }, py::arg("radius"),
      "Thin ring (hoop) in the xy plane.");
  m.def(
      "disk", [=](double R) { return to_shared(MakeThinDisk(R)); }, py::arg("radius"),
      "Thin disk in the xy plane.");
  m.def(
      "plate", [=](double a, double b) { return to_shared(MakeThinPlate(a, b)); },
      py::arg("size_x"), py::arg("size_y"), "Thin rectangular plate in the xy plane.");
  m.def(
      "cylinder", [=](double R, double h) { return to_shared(MakeSolidCylinder(R, h)); },
      py::arg("radius"), py::arg("length"), "Solid cylinder along z.");
  m.def(
      "tube", [=](double ri, double ro, double h) { return to_shared(MakeTube(ri, ro, h)); },
      py::arg("inner_radius"), py::arg("outer_radius"), py::arg("length"), "Thick tube along z.");
  m.def(
      "sphere", [=](double R) { return to_shared(MakeSolidSphere(R)); }, py::arg("radius"),
      "Solid sphere.");
  m.def(
      "spherical_shell", [=](double R) { return to_shared(MakeThinSphericalShell(R)); },
      py::arg("radius"), "Thin spherical shell.");
  m.def(
      "cone", [=](double R, double h) { return to_shared(MakeSolidCone(R, h)); }, py::arg("radius"),
      py::arg("height"), "Solid cone, base at z = 0, apex at z = height.");
  m.def(
      "box", [=](double a, double b, double c) { return to_shared(MakeBox(a, b, c)); },
      py::arg("size_x"), py::arg("size_y"), py::arg("size_z"), "Rectangular box.");
  m.def(
      "ellipsoid", [=](double a, double b, double c) { return to_shared(MakeEllipsoid(a, b, c)); },
      py::arg("semi_axis_x"), py::arg("semi_axis_y"), py::arg("semi_axis_z"), "Solid ellipsoid.");
  m.def(
      "torus", [=](double R, double r) { return to_shared(MakeTorus(R, r)); },
      py::arg("major_radius"), py::arg("minor_radius"), "Solid torus about z.");
}

void BindMesh(py::module_& m) {
  py::class_<MeshMassReport>(m, "MeshMassReport", "How a mesh's mass properties were obtained.")
      .def_readonly("path", &MeshMassReport::path)
      .def_readonly("format", &MeshMassReport::format)
      .def_readonly("triangles", &MeshMassReport::triangles, "Triangles integrated")
      .def_readonly("volume", &MeshMassReport::volume, "Enclosed volume [m^3] (solid mode)")
      .def_readonly("area", &MeshMassReport::area, "Surface area [m^2] (shell mode)")
      .def_readonly("density", &MeshMassReport::density, "Density used [kg/m^3 or kg/m^2]")
      .def_readonly("single_precision", &MeshMassReport::single_precision,
                    "True when the file stores floats (binary STL, binary PLY float)")
      .def_readonly("float32_spacing", &MeshMassReport::float32_spacing,
                    "Spacing of floats at the mesh's largest coordinate [m] (NaN for text and "
                    "double files)")
      .def_property_readonly(
          "warnings", [](const MeshMassReport& r) { return r.repair.warnings; },
          "Repairs made and suspicious input");
  py::class_<MeshMassResult>(m, "MeshMassResult", "Mass properties of a mesh and its report.")
      .def_readonly("mass_properties", &MeshMassResult::mass_properties)
      .def_readonly("report", &MeshMassResult::report);
  const char* const material =
      "Give exactly one of density [kg/m^3] (solid, or shell with thickness [m]), mass [kg], "
      "areal_density [kg/m^2] (shell). `scale` is the length of one unit of the coordinates "
      "[m] (0.001 for millimetres); mode is 'solid' (a closed surface) or 'shell'.";
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  m.def(
      "mesh_mass_properties",
      [](const std::string& path, double scale, double density, double mass,
         const std::string& mode, double areal_density, double thickness) {
        py::gil_scoped_release release;
        return LoadMeshMassProperties(
            path, MeshOptions(mode, scale, density, mass, areal_density, thickness));
      },
      py::arg("path"), py::kw_only(), py::arg("scale") = 1.0, py::arg("density") = nan,
      py::arg("mass") = nan, py::arg("mode") = "solid", py::arg("areal_density") = nan,
      py::arg("thickness") = nan,
      (std::string("Mass properties of a mesh file (STL, OBJ, PLY, OFF). ") + material).c_str());
  m.def(
      "mesh_mass_properties_from_arrays",
      [](py::array_t<double, py::array::c_style | py::array::forcecast> vertices,
         py::array_t<std::uint32_t, py::array::c_style | py::array::forcecast> triangles,
         double scale, double density, double mass, const std::string& mode, double areal_density,
         double thickness) {
        if (vertices.ndim() != 2 || vertices.shape(1) != 3) {
          throw InputError("vertices must be an array of shape (n, 3)");
        }
        if (triangles.ndim() != 2 || triangles.shape(1) != 3) {
          throw InputError("triangles must be an array of shape (m, 3) of vertex indices");
        }
        TriangleMesh mesh;
        for (py::ssize_t i = 0; i < vertices.shape(0); ++i) {
          mesh.vertices.emplace_back(vertices.at(i, 0), vertices.at(i, 1), vertices.at(i, 2));
        }
        for (py::ssize_t i = 0; i < triangles.shape(0); ++i) {
          mesh.triangles.push_back({triangles.at(i, 0), triangles.at(i, 1), triangles.at(i, 2)});
        }
        return ComputeMeshMassProperties(
            mesh, MeshOptions(mode, scale, density, mass, areal_density, thickness));
      },
      py::arg("vertices"), py::arg("triangles"), py::kw_only(), py::arg("scale") = 1.0,
      py::arg("density") = nan, py::arg("mass") = nan, py::arg("mode") = "solid",
      py::arg("areal_density") = nan, py::arg("thickness") = nan,
      (std::string("Mass properties of an in-memory triangle mesh: vertices (n, 3), triangles "
                   "(m, 3) indices, counter-clockwise seen from outside. ") +
       material)
          .c_str());
}

}  // namespace

void BindMass(py::module_& m) {
  BindInertia(m);
  BindMassProperties(m);
  BindShapes(m);
  BindMesh(m);
}

}  // namespace chasles::python
