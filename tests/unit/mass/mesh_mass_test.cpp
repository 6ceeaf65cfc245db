#include "chasles/mass/mesh_mass.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/error.h"
#include "chasles/math/rotation.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::kExact;
using test::MatNear;
using test::Near;
using ::testing::HasSubstr;
constexpr double kPi = std::numbers::pi;

// ---- Test meshes, outward counter-clockwise triangles --------------------------------------

// Box [x0, x0 + a] x [y0, y0 + b] x [z0, z0 + c], 8 vertices, 12 triangles.
TriangleMesh Box(double a, double b, double c, const Vec3& p0 = Vec3::Zero()) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i) {
    m.vertices.push_back(p0 + Vec3((i & 1) ? a : 0, (i & 2) ? b : 0, (i & 4) ? c : 0));
  }
  // Each face as a quad (counter-clockwise from outside), split along its first diagonal.
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.push_back({std::uint32_t(q[0]), std::uint32_t(q[1]), std::uint32_t(q[2])});
    m.triangles.push_back({std::uint32_t(q[0]), std::uint32_t(q[2]), std::uint32_t(q[3])});
  }
  return m;
}

// Torus about z: major radius R, minor radius r, n_major x n_minor quads split in two.
TriangleMesh Torus(double R, double r, int n_major, int n_minor) {
  TriangleMesh m;
  for (int i = 0; i < n_major; ++i) {
    const double th = 2 * kPi * i / n_major;
    for (int j = 0; j < n_minor; ++j) {
      const double ph = 2 * kPi * j / n_minor;
      m.vertices.emplace_back((R + r * std::cos(ph)) * std::cos(th),
                              (R + r * std::cos(ph)) * std::sin(th), r * std::sin(ph));
    }
  }
  auto id = [&](int i, int j) { return std::uint32_t(((i % n_major) * n_minor) + (j % n_minor)); };
  for (int i = 0; i < n_major; ++i) {
    for (int j = 0; j < n_minor; ++j) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return m;
}

// Latitude-longitude sphere of radius R about the origin, or (hemisphere) its upper half
// z >= 0, open at the equator. n rings of latitude from pole to pole, 2n meridians.
TriangleMesh Sphere(double R, int n, bool hemisphere = false) {
  TriangleMesh m;
  const int rings = hemisphere ? n / 2 : n;  // latitude bands
  const int lon = 2 * n;
  m.vertices.emplace_back(0, 0, R);  // north pole
  for (int i = 1; i <= rings; ++i) {
    if (!hemisphere && i == n) break;
    const double th = kPi * i / n;
    for (int j = 0; j < lon; ++j) {
      const double ph = 2 * kPi * j / lon;
      m.vertices.emplace_back(R * std::sin(th) * std::cos(ph), R * std::sin(th) * std::sin(ph),
                              R * std::cos(th));
    }
  }
  auto id = [&](int ring, int j) { return std::uint32_t(1 + (ring - 1) * lon + (j % lon)); };
  for (int j = 0; j < lon; ++j) m.triangles.push_back({0, id(1, j), id(1, j + 1)});
  const int last = hemisphere ? rings : n - 1;
  for (int i = 1; i < last; ++i) {
    for (int j = 0; j < lon; ++j) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  if (!hemisphere) {
    const auto south = std::uint32_t(m.vertices.size());
    m.vertices.emplace_back(0, 0, -R);
    for (int j = 0; j < lon; ++j) m.triangles.push_back({id(n - 1, j), south, id(n - 1, j + 1)});
  }
  return m;
}

MeshMassOptions Solid(double density) {
  MeshMassOptions o;
  o.density = density;
  return o;
}

// ---- Exact polyhedra -----------------------------------------------------------------------

TEST(MeshMass, BoxIsExact) {
  const double a = 0.3, b = 0.7, c = 1.9, rho = 7850;
  const Vec3 p0(-2.0, 5.0, 1.0);
  const MeshMassResult res = ComputeMeshMassProperties(Box(a, b, c, p0), Solid(rho));
  const double m = rho * a * b * c;
  const MassProperties& mp = res.mass_properties;
  EXPECT_TRUE(Near(mp.mass(), m, 1e-14));
  EXPECT_TRUE(MatNear(mp.p_BoBcm_B(), p0 + 0.5 * Vec3(a, b, c), 1e-14));
  // Appendix A, rectangular prism: Ixx = m (b² + c²) / 12, ...; no products about the centre.
  const Mat3 I = Vec3(m * (b * b + c * c) / 12, m * (a * a + c * c) / 12, m * (a * a + b * b) / 12)
                     .asDiagonal();
  EXPECT_TRUE(MatNear(mp.I_BBcm_B().matrix(), I, 1e-13));
  EXPECT_TRUE(Near(res.report.volume, a * b * c, 1e-14));
  // The six faces: 2 (ab + bc + ca), the sum of the twelve triangles' areas.
  EXPECT_TRUE(Near(res.report.surface_area, 2 * (a * b + b * c + c * a), 1e-14));
  EXPECT_EQ(res.report.triangles, 12u);
  EXPECT_TRUE(res.report.repair.warnings.empty());
}

TEST(MeshMass, TetrahedronIsExact) {
  // Corner tetrahedron with edges a, b, c along the axes. Over it (substituting x = a u, ...
  // into the unit-simplex integrals ∫1 = 1/6, ∫u = 1/24, ∫u² = 1/60, ∫uv = 1/120):
  // V = abc/6, centroid (a, b, c)/4, ∫x² dV = a³bc/60, ∫xy dV = a²b²c/120. About the origin
  // Ixx = ρ(∫y² + ∫z²) = m (b² + c²)/10 and ∫xy dm = m ab/20; shifting to the centroid
  // (eq. 8.29): Ixx = m (b² + c²)(1/10 - 1/16) = 3 m (b² + c²)/80, and the tensor entry
  // Ixy = -(m ab/20 - m ab/16) = m ab/80.
  const double a = 2.0, b = 3.0, c = 5.0, mass = 12.5;
  TriangleMesh t;
  t.vertices = {Vec3::Zero(), Vec3(a, 0, 0), Vec3(0, b, 0), Vec3(0, 0, c)};
  t.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  MeshMassOptions o;
  o.mass = mass;
  const MeshMassResult res = ComputeMeshMassProperties(t, o);
  const MassProperties& mp = res.mass_properties;
  EXPECT_TRUE(Near(res.report.volume, a * b * c / 6, 1e-15));
  // Three right-triangle faces ab/2, bc/2, ca/2 and the slanted face |(b - a) × (c - a)|/2
  // = sqrt((bc)² + (ca)² + (ab)²)/2 with the edge vectors (-a, b, 0) and (-a, 0, c).
  EXPECT_TRUE(
      Near(res.report.surface_area,
           (a * b + b * c + c * a + std::sqrt(b * b * c * c + c * c * a * a + a * a * b * b)) / 2,
           1e-15));
  EXPECT_TRUE(Near(mp.mass(), mass, 1e-15));
  EXPECT_TRUE(MatNear(mp.p_BoBcm_B(), Vec3(a, b, c) / 4, 1e-15));
  const double m = mass;
  Mat3 I;
  I << 3 * m * (b * b + c * c) / 80, m * a * b / 80, m * a * c / 80,  //
      m * a * b / 80, 3 * m * (a * a + c * c) / 80, m * b * c / 80,   //
      m * a * c / 80, m * b * c / 80, 3 * m * (a * a + b * b) / 80;
  EXPECT_TRUE(MatNear(mp.I_BBcm_B().matrix(), I, 1e-14));
}

TEST(MeshMass, MillionTriangleBoxIsExactToRoundOff) {
  // Each face of the box cut into k x k squares (12 k² = 1,080,000 triangles): the polyhedron
  // is still exactly the box, so the integrals must be too, up to the round-off of the
  // (compensated) summation over a million terms.
  const int k = 300;
  const double a = 1.0, b = 2.0, c = 3.0, rho = 1000;
  TriangleMesh m;
  auto add_face = [&](const Vec3& o, const Vec3& u, const Vec3& v) {  // u x v points out
    const auto base = std::uint32_t(m.vertices.size());
    for (int i = 0; i <= k; ++i) {
      for (int j = 0; j <= k; ++j)
        m.vertices.push_back(o + u * (double(i) / k) + v * (double(j) / k));
    }
    auto id = [&](int i, int j) { return base + std::uint32_t(i * (k + 1) + j); };
    for (int i = 0; i < k; ++i) {
      for (int j = 0; j < k; ++j) {
        m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    }
  };
  const Vec3 X(a, 0, 0), Y(0, b, 0), Z(0, 0, c), O = Vec3::Zero();
  add_face(O, Y, X);                                                    // z = 0, normal -z
  add_face(Z, X, Y);                                                    // z = c, normal +z
  add_face(O, X, Z);                                                    // y = 0, normal -y
  add_face(Y, Z, X);                                                    // y = b, normal +y
  add_face(O, Z, Y);                                                    // x = 0, normal -x
  add_face(X, Y, Z);                                                    // x = a, normal +x
  const MeshMassResult res = ComputeMeshMassProperties(m, Solid(rho));  // welds the face seams
  EXPECT_EQ(res.report.triangles, 12u * k * k);
  EXPECT_EQ(res.report.repair.vertices_out, std::size_t(6 * k * k + 2));  // Euler: V = T/2 + 2
  const double mass = rho * a * b * c;
  constexpr double kRoundOff = 1e-15;
  EXPECT_TRUE(Near(res.mass_properties.mass(), mass, kRoundOff));
  EXPECT_TRUE(MatNear(res.mass_properties.p_BoBcm_B(), Vec3(a, b, c) / 2, kRoundOff));
  const Mat3 I =
      Vec3(mass * (b * b + c * c) / 12, mass * (a * a + c * c) / 12, mass * (a * a + b * b) / 12)
          .asDiagonal();
  EXPECT_TRUE(MatNear(res.mass_properties.I_BBcm_B().matrix(), I, kRoundOff));
}

// ---- Convergence on curved parts -----------------------------------------------------------

struct Errors {
  double volume, izz, ixx;
};

// Analytic torus (solid of revolution): V = 2π²Rr², Izz = m (R² + 3r²/4),
// Ixx = m (R²/2 + 5r²/8) (Appendix A).
Errors TorusErrors(int n) {
  const double R = 1.0, r = 0.25, rho = 1000.0;
  const MeshMassResult res = ComputeMeshMassProperties(Torus(R, r, 4 * n, n), Solid(rho));
  const double V = 2 * kPi * kPi * R * r * r, m = rho * V;
  const RotationalInertia& I = res.mass_properties.I_BBcm_B();
  return {std::abs(res.report.volume / V - 1), std::abs(I.Izz() / (m * (R * R + 0.75 * r * r)) - 1),
          std::abs(I.Ixx() / (m * (0.5 * R * R + 0.625 * r * r)) - 1)};
}

TEST(MeshMass, TorusConvergesAtSecondOrder) {
  const Errors e1 = TorusErrors(32), e2 = TorusErrors(64), e3 = TorusErrors(128);
  // Inscribed polyhedron: error ∝ h², so halving the edge length divides it by ~4.
  for (const auto& [a, b] : {std::pair{e1, e2}, std::pair{e2, e3}}) {
    EXPECT_NEAR(a.volume / b.volume, 4.0, 0.1);
    EXPECT_NEAR(a.izz / b.izz, 4.0, 0.1);
    EXPECT_NEAR(a.ixx / b.ixx, 4.0, 0.1);
  }
  EXPECT_LT(e3.volume, 2e-3);
  EXPECT_LT(e3.izz, 2e-3);
}

TEST(MeshMass, SphereConvergesAtSecondOrder) {
  // Solid sphere: V = 4πR³/3, I = 2 m R²/5 about any diameter (Appendix A).
  const double R = 0.5, rho = 2700.0;
  double prev_v = 0, prev_i = 0;
  for (int n : {16, 32, 64, 128}) {
    const MeshMassResult res = ComputeMeshMassProperties(Sphere(R, n), Solid(rho));
    const double V = 4 * kPi * R * R * R / 3, m = rho * V;
    const double ev = std::abs(res.report.volume / V - 1);
    const double ei = std::abs(res.mass_properties.I_BBcm_B().Ixx() / (0.4 * m * R * R) - 1);
    EXPECT_TRUE(Near(res.mass_properties.I_BBcm_B().Izz(), 0.4 * m * R * R, 2 * ei + 1e-12));
    EXPECT_TRUE(MatNear(res.mass_properties.p_BoBcm_B(), Vec3::Zero(), 1e-12, R));
    if (n >= 64) {
      EXPECT_NEAR(prev_v / ev, 4.0, 0.15) << "n = " << n;
      EXPECT_NEAR(prev_i / ei, 4.0, 0.15) << "n = " << n;
    }
    prev_v = ev;
    prev_i = ei;
  }
  EXPECT_LT(prev_v, 1e-3);
}

// ---- Round-off: far from the origin and rotated -------------------------------------------

TEST(MeshMass, TranslatedFarAndRotatedGivesSameCentralInertia) {
  const TriangleMesh base = Torus(0.2, 0.05, 96, 32);
  // A box attached off-centre so the inertia has products and distinct moments.
  TriangleMesh part = base;
  const TriangleMesh box = Box(0.1, 0.05, 0.3, Vec3(0.3, 0.0, -0.1));
  const auto off = std::uint32_t(part.vertices.size());
  part.vertices.insert(part.vertices.end(), box.vertices.begin(), box.vertices.end());
  for (auto t : box.triangles) part.triangles.push_back({t[0] + off, t[1] + off, t[2] + off});
  const MeshMassResult ref = ComputeMeshMassProperties(part, Solid(1000));

  const Mat3 R_WB = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Vec3 p_WBo(1e4, -1e4, 1e4);
  TriangleMesh moved = part;
  for (Vec3& v : moved.vertices) v = p_WBo + R_WB * v;
  const MeshMassResult res = ComputeMeshMassProperties(moved, Solid(1000));

  constexpr double kRel = 1e-9;
  EXPECT_TRUE(Near(res.mass_properties.mass(), ref.mass_properties.mass(), kRel));
  const Mat3 I_back = R_WB.transpose() * res.mass_properties.I_BBcm_B().matrix() * R_WB;
  EXPECT_TRUE(MatNear(I_back, ref.mass_properties.I_BBcm_B().matrix(), kRel));
  const Vec3 c_back = R_WB.transpose() * (res.mass_properties.p_BoBcm_B() - p_WBo);
  EXPECT_TRUE(MatNear(c_back, ref.mass_properties.p_BoBcm_B(), kRel, 0.3));
}

// ---- Repairs and errors --------------------------------------------------------------------

TEST(MeshMass, InsideOutMeshIsFlippedWithWarning) {
  TriangleMesh t = Torus(1.0, 0.3, 48, 16);
  const MeshMassResult ref = ComputeMeshMassProperties(t, Solid(500));
  for (auto& tri : t.triangles) std::swap(tri[1], tri[2]);
  const MeshMassResult res = ComputeMeshMassProperties(t, Solid(500));
  EXPECT_TRUE(res.report.repair.inside_out_flipped);
  ASSERT_EQ(res.report.repair.warnings.size(), 1u);
  EXPECT_THAT(res.report.repair.warnings[0], HasSubstr("inside out"));
  EXPECT_TRUE(Near(res.mass_properties.mass(), ref.mass_properties.mass(), kExact));
  EXPECT_TRUE(MatNear(res.mass_properties.I_BBcm_B().matrix(),
                      ref.mass_properties.I_BBcm_B().matrix(), kExact));
}

TEST(MeshMass, MixedOrientationIsRepairedWithWarning) {
  TriangleMesh t = Torus(1.0, 0.3, 48, 16);
  const MeshMassResult ref = ComputeMeshMassProperties(t, Solid(500));
  std::size_t flipped = 0;
  for (std::size_t i = 0; i < t.triangles.size(); i += 7, ++flipped) {
    std::swap(t.triangles[i][1], t.triangles[i][2]);
  }
  const MeshMassResult res = ComputeMeshMassProperties(t, Solid(500));
  EXPECT_EQ(res.report.repair.triangles_flipped, flipped);
  EXPECT_FALSE(res.report.repair.inside_out_flipped);
  ASSERT_EQ(res.report.repair.warnings.size(), 1u);
  EXPECT_THAT(res.report.repair.warnings[0], HasSubstr("inconsistent triangle orientation"));
  EXPECT_TRUE(Near(res.mass_properties.mass(), ref.mass_properties.mass(), kExact));
  EXPECT_TRUE(MatNear(res.mass_properties.I_BBcm_B().matrix(),
                      ref.mass_properties.I_BBcm_B().matrix(), kExact));
}

TEST(MeshMass, OpenMeshInSolidModeIsAnError) {
  TriangleMesh box = Box(1, 2, 3);
  box.triangles.pop_back();  // a hole: three edges now used once
  try {
    ComputeMeshMassProperties(box, Solid(1000));
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("3 boundary edge(s)"));
    EXPECT_THAT(e.what(), HasSubstr("0 non-manifold edge(s)"));
    EXPECT_THAT(e.what(), HasSubstr("boundary edge from ("));
    EXPECT_THAT(e.what(), HasSubstr("use mode: shell with a thickness or areal density"));
  }
}

TEST(MeshMass, NonManifoldMeshInSolidModeIsAnError) {
  // Two unit cubes touching along the edge x = y = 1: four triangles share it.
  TriangleMesh m = Box(1, 1, 1);
  const TriangleMesh b = Box(1, 1, 1, Vec3(1, 1, 0));
  const auto off = std::uint32_t(m.vertices.size());
  m.vertices.insert(m.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (auto t : b.triangles) m.triangles.push_back({t[0] + off, t[1] + off, t[2] + off});
  EXPECT_THAT([&] { ComputeMeshMassProperties(m, Solid(1000)); },
              ::testing::ThrowsMessage<InputError>(::testing::AllOf(
                  HasSubstr("0 boundary edge(s) (used by one triangle) and 1 non-manifold"),
                  HasSubstr("non-manifold edge from (1, 1, 1) to (1, 1, 0)"),
                  HasSubstr("use mode: shell"))));
}

TEST(MeshMass, OptionsAreValidated) {
  MeshMassOptions o;
  EXPECT_THAT([&] { ComputeMeshMassProperties(Box(1, 1, 1), o); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("exactly one of density")));
  o.density = -3;
  EXPECT_THAT([&] { ComputeMeshMassProperties(Box(1, 1, 1), o); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("density is -3 kg/m^3")));
  o.density = 1000;
  o.scale = 0;
  EXPECT_THAT([&] { ComputeMeshMassProperties(Box(1, 1, 1), o); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("scale is 0")));
  MeshMassOptions s;
  s.mode = MeshMassMode::kShell;
  s.thickness = 0.002;
  EXPECT_THAT([&] { ComputeMeshMassProperties(Box(1, 1, 1), s); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("thickness [m] with density")));
}

TEST(MeshMass, ScaleConvertsFileUnits) {
  // A 10 x 20 x 30 mm box given in millimetres.
  MeshMassOptions o = Solid(1000);
  o.scale = 1e-3;
  const MeshMassResult res = ComputeMeshMassProperties(Box(10, 20, 30), o);
  const double m = 1000 * 0.01 * 0.02 * 0.03;
  EXPECT_TRUE(Near(res.mass_properties.mass(), m, 1e-14));
  EXPECT_TRUE(Near(res.mass_properties.I_BBcm_B().Izz(), m * (1e-4 + 4e-4) / 12, 1e-13));
}

TEST(MeshMass, HollowPartCavityReducesMassWithWarning) {
  // Outer box with an inner box oriented inwards (a closed cavity).
  TriangleMesh m = Box(2, 2, 2);
  TriangleMesh inner = Box(1, 1, 1, Vec3(0.5, 0.5, 0.5));
  const auto off = std::uint32_t(m.vertices.size());
  m.vertices.insert(m.vertices.end(), inner.vertices.begin(), inner.vertices.end());
  for (auto t : inner.triangles) m.triangles.push_back({t[0] + off, t[2] + off, t[1] + off});
  const MeshMassResult res = ComputeMeshMassProperties(m, Solid(1));
  EXPECT_TRUE(Near(res.report.volume, 8 - 1, 1e-14));
  // Appendix A cube of side s and mass m: I = m s²/6; the cavity subtracts.
  EXPECT_TRUE(Near(res.mass_properties.I_BBcm_B().Ixx(), 8 * 4 / 6.0 - 1 * 1 / 6.0, 1e-14));
  ASSERT_EQ(res.report.repair.warnings.size(), 1u);
  EXPECT_THAT(res.report.repair.warnings[0], HasSubstr("treated as a cavity"));
  EXPECT_EQ(res.report.repair.components, 2u);
}

// ---- Shell mode ----------------------------------------------------------------------------

TEST(MeshMass, ShellOpenBoxMatchesThinPlates) {
  // Open box a x b x c without its top (z = c), areal density σ. Each face is a thin
  // rectangular plate p x q of mass σpq whose central tensor is diagonal in its own axes:
  // m q²/12 about the in-plane axis along p, m p²/12 about the one along q, m (p² + q²)/12
  // about the normal (Appendix A, thin plate). The parts add by eq. 8.4 / 8.29.
  const double a = 0.4, b = 0.25, c = 0.15, sigma = 7.8;
  auto plate = [&](double p, double q, int normal_axis, const Vec3& centre) {
    const double m = sigma * p * q;
    Vec3 d;
    // In-plane axes: the other two in cyclic order carry extents p then q.
    const int u = (normal_axis + 1) % 3, v = (normal_axis + 2) % 3;
    d[normal_axis] = m * (p * p + q * q) / 12;
    d[u] = m * q * q / 12;  // about the axis along p (u): the extent q is along v
    d[v] = m * p * p / 12;
    return MassProperties(m, centre, RotationalInertia::FromMatrix(d.asDiagonal()));
  };
  // Bottom z = 0: x-extent a (axis u = x for normal z), y-extent b.
  MassProperties expect = plate(a, b, 2, Vec3(a / 2, b / 2, 0));
  // x = 0 and x = a: normal x, u = y (extent b), v = z (extent c).
  expect = expect + plate(b, c, 0, Vec3(0, b / 2, c / 2)) + plate(b, c, 0, Vec3(a, b / 2, c / 2));
  // y = 0 and y = b: normal y, u = z (extent c), v = x (extent a).
  expect = expect + plate(c, a, 1, Vec3(a / 2, 0, c / 2)) + plate(c, a, 1, Vec3(a / 2, b, c / 2));

  TriangleMesh box = Box(a, b, c);
  box.triangles.erase(box.triangles.begin() + 2, box.triangles.begin() + 4);  // the z = c face
  MeshMassOptions o;
  o.mode = MeshMassMode::kShell;
  o.areal_density = sigma;
  const MeshMassResult res = ComputeMeshMassProperties(box, o);
  EXPECT_TRUE(Near(res.report.area, a * b + 2 * b * c + 2 * a * c, 1e-14));
  EXPECT_TRUE(Near(res.mass_properties.mass(), expect.mass(), 1e-14));
  EXPECT_TRUE(MatNear(res.mass_properties.p_BoBcm_B(), expect.p_BoBcm_B(), 1e-14));
  EXPECT_TRUE(MatNear(res.mass_properties.I_BBcm_B().matrix(), expect.I_BBcm_B().matrix(), 1e-13));
}

TEST(MeshMass, ShellRightTriangleMatchesPlateFormulas) {
  // One right triangle with legs a (x) and b (y): an odd triangle count exercises the
  // integrator's last, half-filled lane. Over it ∫x² dA = a³b/12, ∫xy dA = a²b²/24,
  // A = ab/2, centroid (a, b)/3; about the centroid ∫x² dm = m a²/18, ∫y² dm = m b²/18,
  // ∫xy dm = -m ab/36, so Ixx = m b²/18, Iyy = m a²/18, Izz = m (a² + b²)/18 and the
  // tensor entry Ixy = -∫xy dm = m ab/36.
  const double a = 3.0, b = 2.0, mass = 4.0;
  TriangleMesh t;
  t.vertices = {Vec3(0, 0, 1), Vec3(a, 0, 1), Vec3(0, b, 1)};
  t.triangles = {{0, 1, 2}};
  MeshMassOptions o;
  o.mode = MeshMassMode::kShell;
  o.mass = mass;
  const MeshMassResult res = ComputeMeshMassProperties(t, o);
  EXPECT_TRUE(Near(res.report.area, a * b / 2, 1e-15));
  EXPECT_TRUE(Near(res.report.density, mass / (a * b / 2), 1e-15));
  EXPECT_TRUE(MatNear(res.mass_properties.p_BoBcm_B(), Vec3(a / 3, b / 3, 1), 1e-15));
  Mat3 I;
  I << mass * b * b / 18, mass * a * b / 36, 0,  //
      mass * a * b / 36, mass * a * a / 18, 0,   //
      0, 0, mass * (a * a + b * b) / 18;
  EXPECT_TRUE(MatNear(res.mass_properties.I_BBcm_B().matrix(), I, 1e-14));
}

TEST(MeshMass, ShellHemisphereConvergesToThinShellFormulas) {
  // Thin hemispherical shell, radius R, areal density σ: m = 2πR²σ. On a sphere ∫z dA over
  // the upper half is πR³, so the centroid is R/2 above the flat face. By symmetry
  // ∫x² = ∫y² = ∫z² = (1/3)∫R² dA = 2πR⁴/3 over the half, so about the base centre
  // Izz = σ(∫x² + ∫y²) = 2/3 m R² and Ixx = σ(∫y² + ∫z²) = 2/3 m R²; about the centroid
  // Ixx = 2/3 m R² - m (R/2)² = 5/12 m R², Izz unchanged (the centroid is on the z axis).
  const double R = 0.8, thickness = 0.001, rho = 2700.0, sigma = thickness * rho;
  const double m = 2 * kPi * R * R * sigma;
  MeshMassOptions o;
  o.mode = MeshMassMode::kShell;
  o.thickness = thickness;
  o.density = rho;
  double prev = 0;
  for (int n : {32, 64, 128}) {
    const MeshMassResult res = ComputeMeshMassProperties(Sphere(R, n, true), o);
    const MassProperties& mp = res.mass_properties;
    const double em = std::abs(mp.mass() / m - 1);
    EXPECT_TRUE(Near(mp.p_BoBcm_B().z(), R / 2, 4 * em));
    EXPECT_TRUE(Near(mp.I_BBcm_B().Izz(), 2.0 / 3 * m * R * R, 4 * em));
    EXPECT_TRUE(Near(mp.I_BBcm_B().Ixx(), 5.0 / 12 * m * R * R, 4 * em));
    EXPECT_TRUE(Near(mp.I_BBcm_B().Iyy(), 5.0 / 12 * m * R * R, 4 * em));
    const RotationalInertia I_base = mp.CalcInertiaAbout(Vec3::Zero());  // base centre
    EXPECT_TRUE(Near(I_base.Ixx(), 2.0 / 3 * m * R * R, 4 * em));
    EXPECT_TRUE(Near(I_base.Iyy(), 2.0 / 3 * m * R * R, 4 * em));
    if (prev > 0) {
      EXPECT_NEAR(prev / em, 4.0, 0.1) << "n = " << n;
    }
    prev = em;
  }
  EXPECT_LT(prev, 2e-4);
}

}  // namespace
}  // namespace chasles
