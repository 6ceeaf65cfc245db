#include "chasles/mass/mesh_mass.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <span>

#include <fmt/format.h>

#include "chasles/error.h"
#include "mass/internal/mesh_workspace.h"

namespace chasles {
namespace {

// Derivation of the per-triangle terms (solid mode).
//
// Divergence theorem: the solid's integrals are sums over signed tetrahedra (R, a, b, c), one
// per boundary triangle, with the vertices a, b, c measured from the reference point R. A
// point of the tetrahedron is r = a u + b v + c w (u, v, w >= 0, u + v + w <= 1), with
// dV = d du dv dw and d = a · (b × c) = 6 V_tet (signed: positive when the triangle faces away
// from R). Over the unit simplex ∫ 1 = 1/6, ∫ u = 1/24, ∫ u² = 1/60, ∫ u v = 1/120, so
//   ∫ dV      = d / 6,
//   ∫ r dV    = d (a + b + c) / 24                              (centroid s/4),
//   ∫ r rᵀ dV = d/60 (a aᵀ + b bᵀ + c cᵀ) + d/120 Σ_{i≠j} v_i v_jᵀ
//             = d/120 (a aᵀ + b bᵀ + c cᵀ + s sᵀ),   s = a + b + c,
// using s sᵀ = Σ v_i v_iᵀ + Σ_{i≠j} v_i v_jᵀ. (This is the canonical-tetrahedron covariance
// (V/20)(Σ v vᵀ + (Σ v)(Σ v)ᵀ) with the fourth vertex at R = 0.) For a closed surface the parts
// of the tetrahedra outside the solid cancel, whatever R is.
//
// Shell mode, a triangle (a, b, c) of area A = |(b - a) × (c - a)| / 2 = n / 2: with
// r = a + (b - a) u + (c - a) v, dA = 2 A du dv, and ∫ over the unit triangle of 1, u, u², uv
// being 1/2, 1/6, 1/12, 1/24:
//   ∫ dA = A,   ∫ r dA = A s / 3,   ∫ r rᵀ dA = A/12 (a aᵀ + b bᵀ + c cᵀ + s sᵀ).
//
// Round-off: the vertices are shifted to R (the bounding-box centre) before the products, so
// a part 10 km from its frame's origin loses no digits to the offset: a vertex coordinate x
// and R's are within a factor of two of each other whenever the part is far from the origin,
// and then x - R is exact (Sterbenz's lemma); near the origin there is no offset to lose. The
// integrals about R are shifted back by the parallel-axis theorem in
// MassPropertiesFromIntegrals, and ComputeMeshMassProperties integrates in the file's unit and
// scales the results (Scaled below), so the unit's rounding never reaches a difference of
// vertices. Each block of kBlock triangles is summed plainly in registers; block sums are added
// with Neumaier's compensated summation. The error is then that of a kBlock-term sum,
// independent of the triangle count, at the speed of the plain loop.

constexpr std::size_t kBlock = 256;

struct Neumaier {
  double sum = 0.0;
  double c = 0.0;
  void Add(double x) {
    const double t = sum + x;
    c += std::abs(sum) >= std::abs(x) ? (sum - t) + x : (x - t) + sum;
    sum = t;
  }
  double Value() const { return sum + c; }
};

// Two triangles are integrated side by side in the lanes of a 2-wide vector (GCC/Clang vector
// extension: SSE2 on x86-64, NEON on AArch64, no special compiler flags). Measured on the
// 1,000,000-triangle torus of bench/mesh_mass_bench.cpp: the scalar loop reaches about 85
// million triangles/s, the 2-lane loop about 175 million.
using Lanes = double __attribute__((vector_size(2 * sizeof(double))));
constexpr std::size_t kLanes = 2;

template <bool kShell>
MeshIntegrals Integrate(const TriangleMesh& mesh) {
  MeshIntegrals out;
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -lo;
  for (const Vec3& p : mesh.vertices) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Vec3 r = mesh.vertices.empty() ? Vec3::Zero() : Vec3(0.5 * (lo + hi));
  const double rx = r.x(), ry = r.y(), rz = r.z();
  const double* v = mesh.vertices.data()->data();
  const TriangleIndices* tri = mesh.triangles.data();
  const std::size_t n = mesh.triangles.size();

  std::array<Neumaier, 10> total;
  for (std::size_t begin = 0; begin < n; begin += kBlock) {
    const std::size_t end = std::min(n, begin + kBlock);
    Lanes w0{}, fx{}, fy{}, fz{}, sxx{}, syy{}, szz{}, sxy{}, sxz{}, syz{};
    for (std::size_t t = begin; t < end; t += kLanes) {
      // Gather both triangles' vertices, shifted to R. A missing last lane (odd count) stays
      // at a = b = c = 0, whose weight and terms are exactly zero.
      Lanes ax{}, ay{}, az{}, bx{}, by{}, bz{}, cx{}, cy{}, cz{};
      for (std::size_t l = 0; l < kLanes && t + l < end; ++l) {
        const double* pa = v + 3 * std::size_t{tri[t + l][0]};
        const double* pb = v + 3 * std::size_t{tri[t + l][1]};
        const double* pc = v + 3 * std::size_t{tri[t + l][2]};
        ax[l] = pa[0] - rx;
        ay[l] = pa[1] - ry;
        az[l] = pa[2] - rz;
        bx[l] = pb[0] - rx;
        by[l] = pb[1] - ry;
        bz[l] = pb[2] - rz;
        cx[l] = pc[0] - rx;
        cy[l] = pc[1] - ry;
        cz[l] = pc[2] - rz;
      }
      Lanes w;  // weight: d = 6 V_tet (solid) or n = 2 A (shell)
      if constexpr (kShell) {
        const Lanes ux = bx - ax, uy = by - ay, uz = bz - az;
        const Lanes vx = cx - ax, vy = cy - ay, vz = cz - az;
        const Lanes nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
        const Lanes n2 = nx * nx + ny * ny + nz * nz;
        for (std::size_t l = 0; l < kLanes; ++l) w[l] = std::sqrt(n2[l]);
      } else {
        w = ax * (by * cz - bz * cy) + ay * (bz * cx - bx * cz) + az * (bx * cy - by * cx);
      }
      const Lanes sx = ax + bx + cx, sy = ay + by + cy, sz = az + bz + cz;
      w0 += w;
      fx += w * sx;
      fy += w * sy;
      fz += w * sz;
      sxx += w * (ax * ax + bx * bx + cx * cx + sx * sx);
      syy += w * (ay * ay + by * by + cy * cy + sy * sy);
      szz += w * (az * az + bz * bz + cz * cz + sz * sz);
      sxy += w * (ax * ay + bx * by + cx * cy + sx * sy);
      sxz += w * (ax * az + bx * bz + cx * cz + sx * sz);
      syz += w * (ay * az + by * bz + cy * cz + sy * sz);
    }
    const Lanes* acc[10] = {&w0, &fx, &fy, &fz, &sxx, &syy, &szz, &sxy, &sxz, &syz};
    for (int k = 0; k < 10; ++k) {
      for (std::size_t l = 0; l < kLanes; ++l) total[k].Add((*acc[k])[l]);
    }
  }
  // Solid: d/6, d s/24, d (...)/120. Shell: n/2, n s/6, n (...)/24 (n = 2 A).
  const double c0 = kShell ? 1.0 / 2.0 : 1.0 / 6.0;
  const double c1 = kShell ? 1.0 / 6.0 : 1.0 / 24.0;
  const double c2 = kShell ? 1.0 / 24.0 : 1.0 / 120.0;
  out.p_BoR_B = r;
  out.measure = c0 * total[0].Value();
  out.first_moment = c1 * Vec3(total[1].Value(), total[2].Value(), total[3].Value());
  const double xy = c2 * total[7].Value(), xz = c2 * total[8].Value(), yz = c2 * total[9].Value();
  out.second_moment << c2 * total[4].Value(), xy, xz,  //
      xy, c2 * total[5].Value(), yz,                   //
      xz, yz, c2 * total[6].Value();
  return out;
}

bool Set(double x) {
  return !std::isnan(x);
}

void CheckPositive(double x, const char* name, const char* unit, const std::string& what) {
  if (!(std::isfinite(x) && x > 0.0)) {
    throw InputError(
        fmt::format("{}: {} is {} {}; it must be positive and finite", what, name, x, unit));
  }
}

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// Checks the options and returns the density per unit measure, or NaN when a total mass is
// given (the density then follows from the measure).
double DensityFromOptions(const MeshMassOptions& o, const std::string& what) {
  CheckPositive(o.scale, "scale", "m per file unit", what);
  const int given = Set(o.density) + Set(o.mass) + Set(o.areal_density) + Set(o.thickness);
  if (o.mode == MeshMassMode::kSolid) {
    if (Set(o.areal_density) || Set(o.thickness)) {
      throw InputError(fmt::format(
          "{}: areal density and thickness belong to shell mode; a solid takes a density "
          "[kg/m^3] or a mass [kg] (or set mode: shell)",
          what));
    }
    if (Set(o.density) == Set(o.mass)) {
      throw InputError(
          fmt::format("{}: a solid mesh needs exactly one of density [kg/m^3] or "
                      "mass [kg]",
                      what));
    }
    if (Set(o.mass)) {
      CheckPositive(o.mass, "mass", "kg", what);
      return std::numeric_limits<double>::quiet_NaN();
    }
    CheckPositive(o.density, "density", "kg/m^3", what);
    return o.density;
  }
  const bool by_areal = Set(o.areal_density) && given == 1;
  const bool by_thickness = Set(o.thickness) && Set(o.density) && given == 2;
  const bool by_mass = Set(o.mass) && given == 1;
  if (!(by_areal || by_thickness || by_mass)) {
    throw InputError(fmt::format(
        "{}: a shell mesh needs exactly one of: areal density [kg/m^2], thickness [m] with "
        "density [kg/m^3], or mass [kg]",
        what));
  }
  if (by_mass) {
    CheckPositive(o.mass, "mass", "kg", what);
    return std::numeric_limits<double>::quiet_NaN();
  }
  if (by_areal) {
    CheckPositive(o.areal_density, "areal density", "kg/m^2", what);
    return o.areal_density;
  }
  CheckPositive(o.thickness, "thickness", "m", what);
  CheckPositive(o.density, "density", "kg/m^3", what);
  return o.thickness * o.density;
}

/// The sum of the triangles' areas ½ |(b - a) × (c - a)| (compensated: Neumaier).
double CalcMeshSurfaceArea(const TriangleMesh& mesh) {
  double sum = 0.0, carry = 0.0;
  for (const TriangleIndices& t : mesh.triangles) {
    const Vec3& a = mesh.vertices[t[0]];
    const double x = 0.5 * (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a).norm();
    const double next = sum + x;
    carry += std::abs(sum) >= std::abs(x) ? (sum - next) + x : (x - next) + sum;
    sum = next;
  }
  return sum + carry;
}

// The weld tolerance in the file's unit (NaN: the default, relative to the mesh's size).
double FileUnitTolerance(const MeshMassOptions& o, const std::string& what) {
  const double tol = o.weld_tolerance;
  if (!std::isnan(tol) && !(tol >= 0.0 && std::isfinite(tol))) {
    throw InputError(
        fmt::format("{}: weld tolerance is {} m; it must be zero or positive", what, tol));
  }
  return tol / o.scale;
}

// Integrals of a mesh in its file's unit taken to metres (s metres a unit): a point scales by
// s; a solid's volume, first and second moments by s³, s⁴, s⁵; a shell's area and moments by
// s², s³, s⁴.
MeshIntegrals Scaled(MeshIntegrals g, double s, bool shell) {
  const double measure_scale = shell ? s * s : s * s * s;
  g.p_BoR_B *= s;
  g.measure *= measure_scale;
  g.first_moment *= measure_scale * s;
  g.second_moment *= measure_scale * (s * s);
  return g;
}

// The mesh's extent and position for the report, from its vertices in the file's unit; and,
// for a file of floats, the spacing of floats at its largest coordinate |x|: floats in
// [2^e, 2^(e+1)) lie 2^(e-23) apart (IEEE 754 binary32: 24-bit significand; below 2^-126 the
// subnormals, 2^-149 apart).
void DescribeExtent(const TriangleMesh& mesh, double scale, MeshMassReport& report) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -lo;
  for (const Vec3& p : mesh.vertices) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double max_abs = std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
  report.max_abs_coordinate = max_abs * scale;
  report.extent = (hi - lo).norm() * scale;
  if (report.single_precision && max_abs > 0.0) {
    const int e = std::max(std::ilogb(max_abs), -126);
    report.float32_spacing = std::ldexp(1.0, e - 23) * scale;
  }
}

// Validates (solid mode) and integrates `mesh`, whose vertices are in the file's unit.
MeshMassResult Finish(TriangleMesh& mesh, const MeshMassOptions& opts, double density,
                      const std::string& what, MeshMassReport report,
                      internal::MeshWorkspace& workspace) {
  auto t0 = std::chrono::steady_clock::now();
  if (opts.mode == MeshMassMode::kSolid) {
    try {
      internal::ValidateSolid(mesh, &report.repair, workspace);
    } catch (const InputError& e) {
      throw InputError(fmt::format("{}: {}", what, e.what()));
    }
  }
  report.validate_seconds = Seconds(t0);
  t0 = std::chrono::steady_clock::now();
  const bool shell = opts.mode == MeshMassMode::kShell;
  const double s = opts.scale;
  const MeshIntegrals integrals =
      Scaled(shell ? CalcShellIntegrals(mesh) : CalcSolidIntegrals(mesh), s, shell);
  (shell ? report.area : report.volume) = integrals.measure;
  report.surface_area = shell ? integrals.measure : CalcMeshSurfaceArea(mesh) * (s * s);
  report.repair.weld_tolerance *= s;
  DescribeExtent(mesh, s, report);
  if (!(integrals.measure > 0.0)) {
    throw InputError(fmt::format("{}: the mesh has zero {}", what, shell ? "area" : "volume"));
  }
  if (std::isnan(density)) density = opts.mass / integrals.measure;
  report.density = density;
  MassProperties mp = MassPropertiesFromIntegrals(integrals, density);
  report.integrate_seconds = Seconds(t0);
  report.triangles = mesh.triangles.size();
  mp.Validate(what);
  return MeshMassResult{mp, std::move(report)};
}

}  // namespace

MeshIntegrals CalcSolidIntegrals(const TriangleMesh& mesh) {
  return Integrate<false>(mesh);
}

MeshIntegrals CalcShellIntegrals(const TriangleMesh& mesh) {
  return Integrate<true>(mesh);
}

MassProperties MassPropertiesFromIntegrals(const MeshIntegrals& g, double density) {
  // With c the centroid relative to R, the second moment about the centroid is
  // S_c = S_R - Ω c cᵀ (parallel-axis shift of ∫ r rᵀ), and the inertia tensor (eq. 8.16,
  // products negated) is I = ρ (tr(S_c) E - S_c).
  const Vec3 c = g.first_moment / g.measure;
  const Mat3 S = g.second_moment - g.measure * c * c.transpose();
  const Mat3 I = density * (S.trace() * Mat3::Identity() - S);
  return MassProperties(density * g.measure, g.p_BoR_B + c, RotationalInertia::FromMatrix(I));
}

namespace {

// Welds by `weld(tolerance, repair, workspace)` in the file's unit (Finish scales the
// integrals), its error prefixed with `what` and its time in the report, then Finish.
template <class Weld>
MeshMassResult WeldAndFinish(const MeshMassOptions& opts, const std::string& what,
                             MeshMassReport report, Weld weld) {
  const double density = DensityFromOptions(opts, what);
  const double tolerance = FileUnitTolerance(opts, what);
  const auto t0 = std::chrono::steady_clock::now();
  TriangleMesh mesh;
  internal::MeshWorkspace workspace;
  try {
    mesh = weld(tolerance, &report.repair, workspace);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", what, e.what()));
  }
  report.weld_seconds = Seconds(t0);
  return Finish(mesh, opts, density, what, std::move(report), workspace);
}

}  // namespace

MeshMassResult ComputeMeshMassProperties(std::vector<double>&& xyz,
                                         std::vector<std::uint32_t>&& indices,
                                         const MeshMassOptions& opts, const std::string& what,
                                         MeshMassReport report) {
  return WeldAndFinish(opts, what, std::move(report), [&](double tol, auto* repair, auto& ws) {
    TriangleMesh mesh =
        internal::BuildTriangleMesh(std::span<const double>(xyz),
                                    std::span<const std::uint32_t>(indices), 1.0, tol, repair, ws);
    // Release the raw arrays before validation allocates.
    std::vector<double>().swap(xyz);
    std::vector<std::uint32_t>().swap(indices);
    return mesh;
  });
}

MeshMassResult ComputeMeshMassProperties(std::vector<float>&& soup, const MeshMassOptions& opts,
                                         const std::string& what, MeshMassReport report) {
  return WeldAndFinish(opts, what, std::move(report), [&](double tol, auto* repair, auto& ws) {
    TriangleMesh mesh =
        internal::BuildTriangleSoup(std::span<const float>(soup), 1.0, tol, repair, ws);
    std::vector<float>().swap(soup);  // released before validation allocates
    return mesh;
  });
}

MeshMassResult ComputeMeshMassProperties(const FloatSoupRecords& soup, const MeshMassOptions& opts,
                                         const std::string& what, MeshMassReport report) {
  return WeldAndFinish(opts, what, std::move(report), [&](double tol, auto* repair, auto& ws) {
    return internal::BuildTriangleSoup(soup, 1.0, tol, repair, ws);
  });
}

MeshMassResult ComputeMeshMassProperties(const TriangleMesh& in, const MeshMassOptions& opts) {
  const std::string what = "mesh";
  const double density = DensityFromOptions(opts, what);
  const double tolerance = FileUnitTolerance(opts, what);
  MeshMassReport report;
  report.format = "in-memory mesh";
  auto t0 = std::chrono::steady_clock::now();
  static_assert(sizeof(TriangleIndices) == 3 * sizeof(std::uint32_t));
  internal::MeshWorkspace workspace;
  TriangleMesh mesh = internal::BuildTriangleMesh(
      std::span<const double>(in.vertices.empty() ? nullptr : in.vertices.data()->data(),
                              3 * in.vertices.size()),
      std::span<const std::uint32_t>(in.triangles.empty() ? nullptr : in.triangles.data()->data(),
                                     3 * in.triangles.size()),
      1.0, tolerance, &report.repair, workspace);
  report.weld_seconds = Seconds(t0);
  return Finish(mesh, opts, density, what, std::move(report), workspace);
}

}  // namespace chasles
