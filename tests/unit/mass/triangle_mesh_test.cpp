#include "chasles/mass/triangle_mesh.h"

#include <cmath>
#include <vector>

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

}  // namespace
}  // namespace chasles
