#pragma once
/// @file
/// Primitive shapes of the chapter's Appendix A: their measure (length, area or volume),
/// centroid and inertia per unit mass, and for solids a smooth map of the unit cube onto the
/// volume (used to integrate a varying density, see density_field.h).
///
/// Every shape lives in its own frame S. Shapes with an axis of symmetry have it along z.
/// Thin shapes (rods, hoops, disks, plates, shells) are the limits of zero thickness; their
/// measure is a length or an area and they cannot carry a volumetric density.
///
/// Frames (all centred at the centroid unless stated):
/// - rod: length L along z.                       - ring (hoop): radius R in the xy plane.
/// - disk: radius R in the xy plane.              - plate: a along x by b along y, in xy.
/// - cylinder: radius R, length h along z.        - cylindrical_shell: wall of radius R,
///                                                  length h along z; closed: with the two
///                                                  end disks.
/// - tube: inner radius Ri, outer Ro, length h along z.
/// - sphere: radius R.  spherical_shell (thin): radius R.  thick_spherical_shell: Ri, Ro.
/// - hemisphere: radius R; origin at the centre of the flat face, dome towards +z
///   (centroid at z = 3R/8). hemispherical_shell: the dome alone, same frame; closed: with
///   the flat disk.
/// - cone (solid, right circular): base radius R, height h; origin at the centre of the
///   base, apex at z = h (centroid at z = h/4). conical_shell: its lateral surface, same
///   frame; closed: with the base disk. Hollow cone (a cone with a wall thickness t): see
///   MakeHollowCone.
/// - toroidal_shell: the surface of the torus below.
/// - box: a x b x c along x, y, z.                - ellipsoid: semi-axes a, b, c along x, y, z.
/// - torus: axis z, major radius R (to the centre of the tube), minor (tube) radius r.
/// - triangular_prism: the triangle with vertices v0, v1, v2 (given in the xy plane of S)
///   extruded along z over length h, centred in z. The origin of S is where the vertices
///   are measured from, not the centroid (the centroid is the mean of the vertices).

#include <limits>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "chasles/mass/mass_properties.h"
#include "chasles/mass/rotational_inertia.h"
#include "chasles/math/types.h"

namespace chasles {

/// One named dimension of a shape, as a scene file would state it (e.g. {"radius", 0.1}).
struct ShapeDimension {
  /// Key name, e.g. "inner_radius".
  std::string name;
  /// Value [m]; NaN until set.
  double value = std::numeric_limits<double>::quiet_NaN();
};

/// A primitive shape of uniform density (Appendix A). Immutable once made.
class Shape {
 public:
  /// What the shape's mass is spread over.
  enum class Measure {
    kLength,  ///< slender rod, thin ring: mass per unit length
    kArea,    ///< thin disk, plate, shells: mass per unit area
    kVolume,  ///< solids
  };

  virtual ~Shape() = default;

  /// The shape's type name as a scene file writes it, e.g. "cylinder".
  virtual std::string_view kind() const = 0;
  /// Whether the shape is a curve, a surface or a solid.
  virtual Measure measure() const = 0;
  /// The dimensions the shape was made with, in the order of its factory's arguments [m].
  virtual std::vector<ShapeDimension> dimensions() const = 0;
  /// "cylinder (radius 0.1 m, length 0.5 m)": for messages and reports.
  std::string Describe() const;

  /// Length [m], area [m²] or volume [m³], according to measure().
  virtual double CalcMeasure() const = 0;
  /// Area of the bounding surface [m²]: a solid's whole boundary, a surface shape's own area
  /// (one side of the sheet), 0 for a curve.
  virtual double CalcSurfaceArea() const = 0;
  /// Centroid from S's origin, expressed in S [m].
  virtual Vec3 CalcCentroid() const = 0;
  /// Inertia of unit mass about the centroid, expressed in S [m²] (= I_SScm_S / mass).
  virtual RotationalInertia CalcUnitInertia() const = 0;
  /// Mass properties in S for a uniform distribution of `mass` [kg] (> 0, finite; throws
  /// InputError otherwise).
  MassProperties CalcMassProperties(double mass) const;

  /// True for a shell or hollow solid whose flat faces are included (a scene's `closed: true`:
  /// the end disks of a cylindrical shell, the base of a conical or hemispherical shell or of
  /// a hollow cone). Describe() says so.
  virtual bool closed() const { return false; }

  /// True for solids (measure() == kVolume): only they can carry a density field.
  bool is_solid() const { return measure() == Measure::kVolume; }

  /// A smooth map p(u) of the unit cube [0,1]³ onto the solid, so that
  ///   ∫_V f dV = ∫_[0,1]³ f(p(u)) J(u) du,   J = |det ∂p/∂u| [m³].
  /// Cylindrical, spherical and toroidal coordinates keep polynomial densities smooth in u.
  /// `p_S` receives the point in S [m], `jacobian` receives J [m³].
  /// Throws InputError for thin shapes (they have no volume).
  virtual void MapUnitCube(const Vec3& u, Vec3* p_S, double* jacobian) const;

 protected:
  Shape() = default;
};

// Factories. Each validates its dimensions (finite, > 0, and the shape's own rules) and
// throws InputError naming the shape, the dimension and the rule, e.g.
// "tube: inner radius 0.05 m must be smaller than outer radius 0.04 m".

/// Surface area of the ellipsoid with semi-axes `a`, `b`, `c` [m] (any order), exact by
/// Legendre's formula with incomplete elliptic integrals [m²].
double EllipsoidSurfaceArea(double a, double b, double c);

/// Slender rod of length `length` [m] along z ("rod").
std::unique_ptr<Shape> MakeSlenderRod(double length);
/// Thin ring (hoop) of radius `radius` [m] in the xy plane ("ring").
std::unique_ptr<Shape> MakeThinRing(double radius);
/// Thin disk of radius `radius` [m] in the xy plane ("disk").
std::unique_ptr<Shape> MakeThinDisk(double radius);
/// Thin rectangular plate `size_x` by `size_y` [m] in the xy plane ("plate").
std::unique_ptr<Shape> MakeThinPlate(double size_x, double size_y);
/// Solid cylinder of radius `radius` and length `length` along z [m] ("cylinder").
std::unique_ptr<Shape> MakeSolidCylinder(double radius, double length);
/// Thin cylindrical shell (tube wall) of radius `radius`, length `length` [m]; `closed` adds
/// the two end disks of the same areal density ("cylindrical_shell").
std::unique_ptr<Shape> MakeThinCylindricalShell(double radius, double length, bool closed = false);
/// Thick tube: `inner_radius` < `outer_radius`, length `length` along z [m] ("tube").
std::unique_ptr<Shape> MakeTube(double inner_radius, double outer_radius, double length);
/// Solid sphere of radius `radius` [m] ("sphere").
std::unique_ptr<Shape> MakeSolidSphere(double radius);
/// Thin spherical shell of radius `radius` [m] ("spherical_shell").
std::unique_ptr<Shape> MakeThinSphericalShell(double radius);
/// Thick spherical shell, `inner_radius` < `outer_radius` [m] ("thick_spherical_shell").
std::unique_ptr<Shape> MakeThickSphericalShell(double inner_radius, double outer_radius);
/// Solid hemisphere of radius `radius` [m], flat face at z = 0, dome towards +z
/// ("hemisphere").
std::unique_ptr<Shape> MakeSolidHemisphere(double radius);
/// Thin hemispherical shell (a bowl) of radius `radius` [m]: the dome of the hemisphere
/// above, rim in the plane z = 0; `closed` adds the flat disk of the same areal density
/// ("hemispherical_shell").
std::unique_ptr<Shape> MakeThinHemisphericalShell(double radius, bool closed = false);
/// Solid right circular cone, base radius `radius` at z = 0, apex at z = `height` [m]
/// ("cone").
std::unique_ptr<Shape> MakeSolidCone(double radius, double height);
/// Thin conical shell: the lateral surface of the cone above (base radius `radius` at z = 0,
/// apex at z = `height` [m]); `closed` adds the base disk of the same areal density
/// ("conical_shell").
std::unique_ptr<Shape> MakeThinConicalShell(double radius, double height, bool closed = false);
/// Hollow cone ("cone" with a thickness): the solid cone above (base radius `radius`, height
/// `height` [m]) minus the cone whose lateral surface is its own moved inwards by `thickness`
/// [m], measured normal to that surface. The inner cone is the outer one scaled about a point
/// of the axis: open (`closed` false), it shares the base plane and the base is open, which
/// needs thickness < R h / s (s = √(R² + h²), the distance from the base centre to the
/// lateral surface); closed, its base is raised by `thickness` too, a base wall of the same
/// thickness, which needs thickness < R h / (R + s) (the radius of the inscribed sphere).
/// Either way the wall is exact, not a thin-wall approximation.
std::unique_ptr<Shape> MakeHollowCone(double radius, double height, double thickness,
                                      bool closed = false);
/// Rectangular box `size_x` x `size_y` x `size_z` [m] ("box").
std::unique_ptr<Shape> MakeBox(double size_x, double size_y, double size_z);
/// Solid ellipsoid with semi-axes `semi_axis_x`, `semi_axis_y`, `semi_axis_z` [m]
/// ("ellipsoid").
std::unique_ptr<Shape> MakeEllipsoid(double semi_axis_x, double semi_axis_y, double semi_axis_z);
/// Solid torus about z: `major_radius` to the tube's centre, `minor_radius` of the tube [m];
/// minor < major ("torus").
std::unique_ptr<Shape> MakeTorus(double major_radius, double minor_radius);
/// Thin toroidal shell: the surface of the torus above, `major_radius` to the tube's centre,
/// `minor_radius` of the tube [m]; minor < major ("toroidal_shell").
std::unique_ptr<Shape> MakeThinToroidalShell(double major_radius, double minor_radius);
/// Triangular prism: the triangle (v0, v1, v2) in the xy plane of S [m], extruded along z
/// over `length` [m] and centred in z; the triangle must not be degenerate
/// ("triangular_prism").
std::unique_ptr<Shape> MakeTriangularPrism(const Eigen::Vector2d& v0, const Eigen::Vector2d& v1,
                                           const Eigen::Vector2d& v2, double length);

}  // namespace chasles
