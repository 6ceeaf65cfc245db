// A rolling contact's `surface`: a round body rolling on the inside or outside of a fixed
// sphere or circular cylinder of the world (model/surface_rolling.h; docs/scene-format.md,
// `rolling`, "Rolling on a curved surface").

#include <fmt/format.h>

#include "chasles/suggest.h"
#include "internal/scene_reader.h"

namespace chasles::scene_internal {
namespace {}  // namespace

// surface: {shape: sphere | cylinder, center: [x, y, z], axis: [x, y, z] (a cylinder),
//           radius: R, side: inside | outside}
void SceneReader::ReadRollingSurface(const At& at, const std::string& what, SceneRolling& r) {
  const At s = at.Child("surface");
  report_.CheckMap(s, {"shape", "center", "axis", "radius", "side"},
                   "a surface ({shape, center, axis, radius, side})");
  if (at.Has("plane")) {
    report_.Fail(at.Child("plane"), "give a 'plane' or a 'surface' to roll on, not both");
  }
  if (at.Has("on")) {
    report_.Fail(at.Child("on"), "a curved surface is fixed in the world; remove 'on'");
  }
  if (r.shape == RollingShape::kDisk) {
    report_.Fail(at.Child("shape"),
                 "a disk rolls on a plane; on a curved surface give a sphere or a cylinder");
  }
  r.on_surface = true;
  const At shape_at = report_.Require(s, "shape", what + ": 'surface'");
  const std::string shape = report_.Text(shape_at, "sphere or cylinder");
  if (shape == "sphere") {
    r.surface_shape = SurfaceShape::kSphere;
  } else if (shape == "cylinder") {
    r.surface_shape = SurfaceShape::kCylinder;
    r.surface_axis_W = AxisAt(report_.Require(s, "axis", what + ": 'surface'"), "the axis");
  } else {
    report_.Fail(shape_at, fmt::format("unknown surface '{}'{}; surfaces: sphere, cylinder", shape,
                                       DidYouMean(shape, {"sphere", "cylinder"})));
  }
  if (r.surface_shape == SurfaceShape::kSphere && s.Has("axis")) {
    report_.Fail(s.Child("axis"), "a sphere has no axis; remove 'axis'");
  }
  if (r.shape == RollingShape::kCylinder && r.surface_shape == SurfaceShape::kSphere) {
    report_.Fail(shape_at, "a cylinder rolls on a cylinder (axes parallel), not on a sphere");
  }
  r.surface_center_W =
      s.Has("center") ? Vector(s.Child("center"), kLength, "the centre") : Vec3::Zero();
  r.surface_radius = PositiveValue(report_.Require(s, "radius", what + ": 'surface'"), kLength,
                                   "the surface's radius");
  const At side = report_.Require(s, "side", what + ": 'surface'");
  const std::string where = report_.Text(side, "inside or outside");
  if (where != "inside" && where != "outside") {
    report_.Fail(side, fmt::format("side '{}' is neither inside nor outside", where));
  }
  r.inside = where == "inside";
  if (r.inside && !(r.radius < r.surface_radius)) {
    report_.Fail(at.Child("radius"),
                 fmt::format("a body of radius {:.6g} m cannot roll inside a surface of radius "
                             "{:.6g} m; it must be smaller",
                             r.radius, r.surface_radius));
  }
}

}  // namespace chasles::scene_internal
