#include "chasles/mass/triangle_mesh.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <fmt/format.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/error.h"
#include "test_support.h"

namespace chasles {
namespace {

using ::testing::HasSubstr;

// Unit cube as an STL stores it: 12 triangles, 36 vertices, none shared. Outward
// counter-clockwise faces.
std::vector<double> CubeSoup(double s = 1.0) {
  const double c[8][3] = {{0, 0, 0}, {s, 0, 0}, {0, s, 0}, {s, s, 0},
                          {0, 0, s}, {s, 0, s}, {0, s, s}, {s, s, s}};
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  std::vector<double> xyz;
  for (const auto& q : quads) {
    for (int k : {q[0], q[1], q[2], q[0], q[2], q[3]}) xyz.insert(xyz.end(), c[k], c[k] + 3);
  }
  return xyz;
}

std::vector<std::uint32_t> Iota(std::size_t n) {
  std::vector<std::uint32_t> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = std::uint32_t(i);
  return v;
}

TEST(TriangleMesh, WeldsExactDuplicates) {
  const std::vector<double> xyz = CubeSoup();
  MeshRepairReport rep;
  const TriangleMesh m = BuildTriangleMesh(
      std::span<const double>(xyz), std::span<const std::uint32_t>(Iota(36)), 1.0, 0.0, &rep);
  EXPECT_EQ(rep.vertices_in, 36u);
  EXPECT_EQ(rep.vertices_out, 8u);  // a cube has 8 corners
  EXPECT_EQ(m.vertices.size(), 8u);
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_EQ(rep.degenerate_dropped, 0u);
  TriangleMesh copy = m;
  ValidateSolid(copy, &rep);  // closed once welded
  EXPECT_EQ(rep.components, 1u);
  EXPECT_TRUE(rep.warnings.empty());
}

// Components are numbered in the order of their first triangle, whatever the order of the rest:
// three closed cubes with their triangles interleaved (E, C, D, E, C, D, ...): E of side 1 at
// x = 10, C of side 4 at the origin, and D of side 1 at (1, 1, 1) inside C, reversed (a cavity
// of volume −1³). So E is component 0, C 1 and D 2, and the only warning is D's negative volume.
TEST(TriangleMesh, NumbersInterleavedComponentsByTheirFirstTriangle) {
  const auto cube = [](double side, const Vec3& at, bool reversed) {
    std::vector<double> xyz = CubeSoup(side);
    for (std::size_t i = 0; i < xyz.size(); ++i) xyz[i] += at[static_cast<int>(i % 3)];
    if (reversed) {
      for (std::size_t t = 0; t < 12; ++t) {
        std::swap_ranges(xyz.begin() + 9 * t + 3, xyz.begin() + 9 * t + 6, xyz.begin() + 9 * t + 6);
      }
    }
    return xyz;
  };
  const std::vector<double> e = cube(1, Vec3(10, 0, 0), false), c = cube(4, Vec3::Zero(), false),
                            d = cube(1, Vec3(1, 1, 1), true);
  std::vector<double> xyz;
  for (std::size_t t = 0; t < 12; ++t) {
    for (const std::vector<double>* part : {&e, &c, &d}) {
      xyz.insert(xyz.end(), part->begin() + 9 * t, part->begin() + 9 * t + 9);
    }
  }
  MeshRepairReport rep;
  TriangleMesh m = BuildTriangleMesh(std::span<const double>(xyz),
                                     std::span<const std::uint32_t>(Iota(108)), 1.0, 0.0, &rep);
  EXPECT_EQ(m.vertices.size(), 24u);
  ValidateSolid(m, &rep);
  EXPECT_EQ(rep.components, 3u);
  EXPECT_EQ(rep.triangles_flipped, 0u);
  ASSERT_EQ(rep.warnings.size(), 1u);
  EXPECT_THAT(rep.warnings[0],
              HasSubstr("component 2 (12 triangles) encloses a negative volume (-1)"));
}

TEST(TriangleMesh, FloatInputAndScaleAndSignedZero) {
  std::vector<float> xyz;
  for (double x : CubeSoup(10.0)) xyz.push_back(static_cast<float>(x));
  xyz[0] = -0.0f;  // -0 is the same position as +0
  MeshRepairReport rep;
  const TriangleMesh m = BuildTriangleMesh(
      std::span<const float>(xyz), std::span<const std::uint32_t>(Iota(36)), 1e-3, 0.0, &rep);
  EXPECT_EQ(m.vertices.size(), 8u);
  double max_coord = 0;
  for (const Vec3& v : m.vertices) max_coord = std::max(max_coord, v.maxCoeff());
  EXPECT_TRUE(test::Near(max_coord, 10.0 * 1e-3, test::kExact));
}

TEST(TriangleMesh, WeldsNearDuplicatesWithinRelativeTolerance) {
  // Perturb every copy of each corner by up to 1e-12 of the diagonal (sqrt 3): the default
  // tolerance 1e-9 x diagonal merges them; a zero tolerance does not.
  std::vector<double> xyz = CubeSoup();
  for (std::size_t i = 0; i < xyz.size(); ++i) xyz[i] += 1e-12 * std::sin(double(i));
  MeshRepairReport rep;
  TriangleMesh m = BuildTriangleMesh(std::span<const double>(xyz),
                                     std::span<const std::uint32_t>(Iota(36)), 1.0, NAN, &rep);
  EXPECT_EQ(m.vertices.size(), 8u);
  EXPECT_TRUE(test::Near(rep.weld_tolerance, 1e-9 * std::sqrt(3.0), 1e-6));
  EXPECT_NO_THROW(ValidateSolid(m, &rep));
  MeshRepairReport exact;
  const TriangleMesh open = BuildTriangleMesh(
      std::span<const double>(xyz), std::span<const std::uint32_t>(Iota(36)), 1.0, 0.0, &exact);
  EXPECT_GT(open.vertices.size(), 8u);
}

TEST(TriangleMesh, NearDuplicatesAcrossCellWallsAreFound) {
  // Two copies of the cube whose corners differ by 0.4 tol, straddling grid walls at every
  // corner (corners at 0 and 1 lie on walls of any grid anchored at the bounding box).
  std::vector<double> xyz = CubeSoup();
  const double tol = 1e-6;
  for (std::size_t i = 0; i < xyz.size(); i += 2) xyz[i] -= 0.4 * tol;  // alternate copies
  MeshRepairReport rep;
  const TriangleMesh m = BuildTriangleMesh(
      std::span<const double>(xyz), std::span<const std::uint32_t>(Iota(36)), 1.0, tol, &rep);
  EXPECT_EQ(m.vertices.size(), 8u);
}

TEST(TriangleMesh, DropsDegenerateTriangles) {
  std::vector<double> xyz = CubeSoup();
  std::vector<std::uint32_t> idx = Iota(36);
  // A triangle with a repeated vertex and a zero-area (collinear) one.
  idx.insert(idx.end(), {0, 0, 1});
  xyz.insert(xyz.end(), {0, 0, 0, 0.5, 0, 0, 1, 0, 0});
  idx.insert(idx.end(), {36, 37, 38});
  MeshRepairReport rep;
  const TriangleMesh m = BuildTriangleMesh(std::span<const double>(xyz),
                                           std::span<const std::uint32_t>(idx), 1.0, 0.0, &rep);
  EXPECT_EQ(rep.triangles_in, 14u);
  EXPECT_EQ(rep.degenerate_dropped, 2u);
  EXPECT_EQ(m.triangles.size(), 12u);
  ASSERT_EQ(rep.warnings.size(), 1u);
  EXPECT_THAT(rep.warnings[0], HasSubstr("2 degenerate triangle(s)"));
}

TEST(TriangleMesh, RejectsBadArrays) {
  const std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::vector<std::uint32_t> bad = {0, 1, 3};
  EXPECT_THAT(
      [&] {
        BuildTriangleMesh(std::span<const double>(xyz), std::span<const std::uint32_t>(bad), 1.0,
                          0.0, nullptr);
      },
      ::testing::ThrowsMessage<InputError>(HasSubstr("refers to vertex 3, but there are only 3")));
  std::vector<double> nan_xyz = xyz;
  nan_xyz[4] = NAN;
  const std::vector<std::uint32_t> ok = {0, 1, 2};
  EXPECT_THAT(
      [&] {
        BuildTriangleMesh(std::span<const double>(nan_xyz), std::span<const std::uint32_t>(ok), 1.0,
                          0.0, nullptr);
      },
      ::testing::ThrowsMessage<InputError>(HasSubstr("vertex 1 has a non-finite coordinate")));
  const std::vector<std::uint32_t> degenerate = {0, 0, 1};
  EXPECT_THAT(
      [&] {
        BuildTriangleMesh(std::span<const double>(xyz), std::span<const std::uint32_t>(degenerate),
                          1.0, 0.0, nullptr);
      },
      ::testing::ThrowsMessage<InputError>(HasSubstr("empty mesh")));
}

TEST(TriangleMesh, NonOrientableSurfaceIsAnError) {
  // The six-vertex triangulation of the real projective plane: closed and manifold (every
  // edge in exactly two of the ten triangles) but one-sided, so no orientation exists.
  TriangleMesh m;
  m.vertices = {Vec3(0, 0, 1),      Vec3(1, 0, 0.1),       Vec3(0.3, 1, 0.2),
                Vec3(-0.8, 0.6, 0), Vec3(-0.8, -0.6, 0.3), Vec3(0.3, -1, -0.2)};
  m.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}, {0, 5, 1},
                 {1, 2, 4}, {2, 3, 5}, {3, 4, 1}, {4, 5, 2}, {5, 1, 3}};
  EXPECT_THAT([&] { ValidateSolid(m, nullptr); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("not orientable")));
}

TEST(TriangleMesh, FlatClosedSurfaceEnclosesNoVolume) {
  // Two copies of the same square, facing opposite ways: closed and consistently oriented
  // but enclosing nothing.
  TriangleMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  m.triangles = {{0, 1, 2}, {0, 2, 3}, {1, 0, 3}, {1, 3, 2}};  // back split the other way
  EXPECT_THAT([&] { ValidateSolid(m, nullptr); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("encloses no volume")));
}

// A torus of nu x nv quads (2 nu nv triangles on nu nv vertices, R = 3, r = 1), vertex (i, j)
// numbered number[i nv + j].
TriangleMesh GridTorus(int nu, int nv, const std::vector<std::uint32_t>& number) {
  TriangleMesh m;
  m.vertices.resize(static_cast<std::size_t>(nu) * nv);
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * std::numbers::pi * i / nu, v = 2 * std::numbers::pi * j / nv;
      m.vertices[number[i * nv + j]] =
          Vec3((3 + std::cos(v)) * std::cos(u), (3 + std::cos(v)) * std::sin(u), std::sin(v));
    }
  }
  const auto id = [&](int i, int j) { return number[(i % nu) * nv + j % nv]; };
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return m;
}

std::string Point(const Vec3& p) {
  return fmt::format("({:.9g}, {:.9g}, {:.9g})", p.x(), p.y(), p.z());
}

// ValidateSolid matches the edges a range of vertices at a time when the mesh is large (here
// 30,000 vertices, several ranges), scanning for each range only the triangles from the first
// to the last that use it: with the vertices numbered along the torus those are narrow bands,
// with them scrambled every range's triangles spread over the whole mesh. Either way the
// outcome is that of matching all the edges at once: the same repairs and the same first bad
// edge (the boundary edge of lowest vertices).
TEST(TriangleMesh, ValidatesLargeMeshesARangeOfVerticesAtATime) {
  constexpr int kNu = 300, kNv = 100;
  for (const bool scrambled : {false, true}) {
    SCOPED_TRACE(scrambled ? "scrambled" : "in order");
    std::vector<std::uint32_t> number(kNu * kNv);
    for (std::size_t k = 0; k < number.size(); ++k) number[k] = static_cast<std::uint32_t>(k);
    if (scrambled) std::shuffle(number.begin(), number.end(), std::mt19937(12345));
    const TriangleMesh torus = GridTorus(kNu, kNv, number);
    const std::size_t nt = torus.triangles.size();

    TriangleMesh clean = torus;
    MeshRepairReport rep;
    ValidateSolid(clean, &rep);
    EXPECT_EQ(rep.components, 1u);
    EXPECT_EQ(rep.triangles_flipped, 0u);
    EXPECT_FALSE(rep.inside_out_flipped);  // (i, j), (i + 1, j), (i + 1, j + 1) faces outwards
    EXPECT_TRUE(rep.warnings.empty());

    // Five triangles reversed: found and turned back.
    TriangleMesh flipped = torus;
    for (std::size_t t : {0ul, 999ul, 12345ul, 40000ul, nt - 1}) {
      std::swap(flipped.triangles[t][1], flipped.triangles[t][2]);
    }
    MeshRepairReport frep;
    ValidateSolid(flipped, &frep);
    EXPECT_EQ(frep.triangles_flipped, 5u);
    EXPECT_EQ(frep.components, 1u);
    EXPECT_EQ(flipped.triangles, clean.triangles);

    // One triangle removed: three boundary edges; the first named is the one of lowest lower
    // vertex, then lowest upper vertex, traversed by the neighbour the other way.
    const std::size_t removed = 23456;
    TriangleMesh open = torus;
    const TriangleIndices tri = open.triangles[removed];
    open.triangles.erase(open.triangles.begin() + static_cast<std::ptrdiff_t>(removed));
    std::array<std::pair<std::uint32_t, std::uint32_t>, 3> edges;
    for (int k = 0; k < 3; ++k) edges[k] = {tri[k], tri[(k + 1) % 3]};
    const auto key = [](const std::pair<std::uint32_t, std::uint32_t>& e) {
      return std::pair(std::min(e.first, e.second), std::max(e.first, e.second));
    };
    const auto first = *std::min_element(edges.begin(), edges.end(),
                                         [&](auto& a, auto& b) { return key(a) < key(b); });
    EXPECT_THAT(
        [&] { ValidateSolid(open, nullptr); },
        ::testing::ThrowsMessage<InputError>(HasSubstr(
            "3 boundary edge(s) (used by one triangle) and 0 non-manifold edge(s) (used by three "
            "or more); the first is the boundary edge from " +
            Point(torus.vertices[first.second]) + " to " + Point(torus.vertices[first.first]))));

    // One triangle twice: its three edges are used three times each.
    TriangleMesh doubled = torus;
    doubled.triangles.push_back(doubled.triangles[removed]);
    EXPECT_THAT([&] { ValidateSolid(doubled, nullptr); },
                ::testing::ThrowsMessage<InputError>(
                    HasSubstr("0 boundary edge(s) (used by one triangle) and 3 non-manifold")));
  }
}

}  // namespace
}  // namespace chasles
