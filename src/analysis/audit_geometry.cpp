// What a link's geometry implies (analysis/internal/audit_steps.h): each geometry set's
// volume, centre of mass and inertia at unit density, exact for primitives (Appendix A) and
// closed meshes (divergence theorem), and by a stated approximation otherwise.

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>

#include <fmt/format.h>

#include "analysis/internal/audit_steps.h"
#include "chasles/error.h"
#include "chasles/mass/mesh_mass.h"
#include "chasles/mass/shape.h"
#include "chasles/mass/triangle_mesh.h"

namespace chasles {

const char* GeometryMethodName(GeometryMethod method) {
  switch (method) {
    case GeometryMethod::kPrimitive:
      return "primitive";
    case GeometryMethod::kExactMesh:
      return "exact closed mesh";
    case GeometryMethod::kRepairedMesh:
      return "repaired mesh";
    case GeometryMethod::kConvexHull:
      return "convex hull";
    case GeometryMethod::kBoundingBox:
      return "bounding box";
  }
  return "?";
}

MassProperties GeometryEstimate::AtMass(double mass) const {
  // Uniform density: every moment scales with the mass, the centre of mass stays.
  const double s = mass / unit_density.mass();
  return MassProperties(mass, unit_density.p_BoBcm_B(), unit_density.I_BBcm_B() * s);
}

double GeometryEstimate::RadiusAbout(const Vec3& p) const {
  double r = 0.0;
  for (const Vec3& q : points) r = std::max(r, (q - p).norm());
  return r;
}

std::shared_ptr<AuditMeshCache> MakeAuditMeshCache(MeshLoader load) {
  return std::make_shared<AuditMeshCache>(std::move(load));
}

const TriangleSoup* AuditMeshCache::Get(const std::string& path, std::string* problem) {
  if (const auto it = problems_.find(path); it != problems_.end()) {
    *problem = it->second;
    return nullptr;
  }
  if (const auto it = soups_.find(path); it != soups_.end()) return &*it->second;
  if (!load_) {
    *problem = problems_[path] = "meshes are not read in this audit";
    return nullptr;
  }
  // A malformed mesh is an error of the input, as a malformed robot file is (the caller says
  // where the robot file names it); a missing one was found when its URI was resolved.
  TriangleSoup soup = load_(path);
  return &*(soups_[path] = std::move(soup));
}

namespace internal {

namespace {

/// One part of a set: its unit-density mass properties in L, its points in L and its method.
struct Part {
  MassProperties mp;
  std::vector<Vec3> points;
  GeometryMethod method = GeometryMethod::kPrimitive;
  std::string note;
};

std::vector<Vec3> BoxCorners(const Vec3& half, const Mat3& R, const Vec3& p) {
  std::vector<Vec3> out;
  for (int k = 0; k < 8; ++k) {
    const Vec3 s((k & 1) ? 1 : -1, (k & 2) ? 1 : -1, (k & 4) ? 1 : -1);
    out.push_back(p + R * half.cwiseProduct(s));
  }
  return out;
}

Part PrimitivePart(const RobotGeometry& g) {
  const double r = g.size[0];
  std::unique_ptr<Shape> shape;
  Vec3 half = Vec3::Zero();
  MassProperties mp;
  switch (g.type) {
    case GeometryType::kBox:
      shape = MakeBox(g.size[0], g.size[1], g.size[2]);
      half = g.size / 2;
      break;
    case GeometryType::kCylinder:
      shape = MakeSolidCylinder(r, g.size[1]);
      half = Vec3(r, r, g.size[1] / 2);
      break;
    case GeometryType::kSphere:
      shape = MakeSolidSphere(r);
      half = Vec3::Constant(r);
      break;
    case GeometryType::kEllipsoid:
      shape = MakeEllipsoid(g.size[0], g.size[1], g.size[2]);
      half = g.size;
      break;
    case GeometryType::kCapsule: {
      // A cylinder and two hemispheres (flat faces at z = ±L/2, domes outwards).
      const double L = g.size[1];
      const std::unique_ptr<Shape> cyl = MakeSolidCylinder(r, L), hemi = MakeSolidHemisphere(r);
      const MassProperties h = hemi->CalcMassProperties(hemi->CalcMeasure());
      Mat3 flip = Mat3::Identity();
      flip(1, 1) = flip(2, 2) = -1;
      mp = cyl->CalcMassProperties(cyl->CalcMeasure()) +
           h.ExpressedInParent(Mat3::Identity(), Vec3(0, 0, L / 2)) +
           h.ExpressedInParent(flip, Vec3(0, 0, -L / 2));
      half = Vec3(r, r, L / 2 + r);
      break;
    }
    case GeometryType::kMesh:
      break;
  }
  if (shape) mp = shape->CalcMassProperties(shape->CalcMeasure());
  return {mp.ExpressedInParent(g.R_LG, g.p_LoGo_L), BoxCorners(half, g.R_LG, g.p_LoGo_L),
          GeometryMethod::kPrimitive, ""};
}

/// The solid a mesh bounds: exact when closed, else capped, else its hull, else its box.
MassProperties MeshSolid(TriangleMesh mesh, GeometryMethod* method, std::string* note) {
  MeshRepairReport report;
  TriangleMesh work = mesh;
  try {
    ValidateSolid(work, &report);
    *method = GeometryMethod::kExactMesh;
    return MassPropertiesFromIntegrals(CalcSolidIntegrals(work), 1.0);
  } catch (const InputError& e) {
    *note = e.what();
  }
  work = mesh;
  if (CapHoles(work)) {
    try {
      ValidateSolid(work, &report);
      *method = GeometryMethod::kRepairedMesh;
      return MassPropertiesFromIntegrals(CalcSolidIntegrals(work), 1.0);
    } catch (const InputError&) {
    }
  }
  work = ConvexHull(mesh.vertices);
  if (!work.triangles.empty()) {
    try {
      ValidateSolid(work, &report);
      *method = GeometryMethod::kConvexHull;
      return MassPropertiesFromIntegrals(CalcSolidIntegrals(work), 1.0);
    } catch (const InputError&) {
    }
  }
  Vec3 lo = mesh.vertices[0], hi = lo;
  for (const Vec3& v : mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  const Vec3 size = (hi - lo).cwiseMax(1e-9 * (hi - lo).norm());
  const std::unique_ptr<Shape> box = MakeBox(size.x(), size.y(), size.z());
  *method = GeometryMethod::kBoundingBox;
  return box->CalcMassProperties(box->CalcMeasure())
      .ExpressedInParent(Mat3::Identity(), (lo + hi) / 2);
}

/// A mesh part, or nullopt with `problem` set.
std::optional<Part> MeshPart(const RobotGeometry& g, MeshCache& meshes, const std::string& file,
                             std::string* problem) {
  if (g.mesh_path.empty()) {
    *problem = g.mesh_problem;
    return std::nullopt;
  }
  const std::array<double, 3> scale = {g.mesh_scale.x(), g.mesh_scale.y(), g.mesh_scale.z()};
  auto cached = meshes.solids.find({g.mesh_path, scale});
  if (cached == meshes.solids.end()) {
    const TriangleSoup* soup = nullptr;
    try {
      soup = meshes.Get(g.mesh_path, problem);
    } catch (const InputError& e) {
      throw InputError(fmt::format("{}:{}: {}", file, g.line, e.what()));
    }
    if (!soup) return std::nullopt;
    std::vector<double> xyz = soup->xyz;
    for (std::size_t i = 0; i < xyz.size(); ++i) xyz[i] *= scale[i % 3];
    TriangleMesh mesh;
    try {
      mesh = BuildTriangleMesh(std::span<const double>(xyz), soup->indices, 1.0,
                               std::numeric_limits<double>::quiet_NaN(), nullptr);
    } catch (const InputError& e) {
      *problem = e.what();
      return std::nullopt;
    }
    MeshSolidPart solid;
    solid.unit_density = MeshSolid(mesh, &solid.method, &solid.why_open);
    solid.vertices = std::move(mesh.vertices);
    cached = meshes.solids.emplace(std::make_pair(g.mesh_path, scale), std::move(solid)).first;
  }
  const MeshSolidPart& solid = cached->second;
  Part part;
  part.method = solid.method;
  part.mp = solid.unit_density.ExpressedInParent(g.R_LG, g.p_LoGo_L);
  part.points.reserve(solid.vertices.size());
  for (const Vec3& v : solid.vertices) part.points.push_back(g.p_LoGo_L + g.R_LG * v);
  if (part.method != GeometryMethod::kExactMesh) {
    part.note = fmt::format("mesh '{}' (line {}) bounds no solid ({}); its {} is used instead",
                            g.mesh_uri, g.line, solid.why_open, GeometryMethodName(part.method));
  }
  return part;
}

}  // namespace

std::vector<GeometryEstimate> EstimateGeometry(const RobotLink& link, MeshCache& meshes,
                                               const std::string& file) {
  std::vector<GeometryEstimate> out;
  // The visual geometry first: it is the part's shape, where collision geometry is often a
  // coarser, larger stand-in (capsules, boxes); the collision set only when the visual one
  // could not be computed.
  for (const GeometrySet set : {GeometrySet::kVisual, GeometrySet::kCollision}) {
    if (set == GeometrySet::kCollision && !out.empty() && out.front().volume > 0.0) break;
    GeometryEstimate e;
    e.set = set;
    std::optional<MassProperties> sum;
    bool complete = true, any = false;
    for (const RobotGeometry& g : link.geometries) {
      if (g.set != set) continue;
      any = true;
      e.lines.push_back(g.line);
      std::string problem;
      const std::optional<Part> part =
          g.type == GeometryType::kMesh ? MeshPart(g, meshes, file, &problem) : PrimitivePart(g);
      if (!part) {
        complete = false;
        e.notes.push_back(fmt::format("{} mesh '{}' (line {}) not used: {}", GeometrySetName(set),
                                      g.mesh_uri, g.line, problem));
        continue;
      }
      sum = sum ? *sum + part->mp : part->mp;
      e.points.insert(e.points.end(), part->points.begin(), part->points.end());
      e.method = std::max(e.method, part->method);
      if (!part->note.empty()) e.notes.push_back(part->note);
    }
    if (!any) continue;
    if (!complete || !sum) {
      e.volume = std::numeric_limits<double>::quiet_NaN();
      out.push_back(std::move(e));
      continue;
    }
    e.unit_density = *sum;
    e.volume = sum->mass();
    e.box_min = e.box_max = e.points.front();
    for (const Vec3& q : e.points)
      e.box_min = e.box_min.cwiseMin(q), e.box_max = e.box_max.cwiseMax(q);
    out.push_back(std::move(e));
  }
  return out;
}

}  // namespace internal

}  // namespace chasles
