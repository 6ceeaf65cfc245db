// End-to-end: mesh parts in scenes and mesh files on the command line, against the exact mass
// properties of the boxes and cylinders they are made of (Appendix A, eq. 8.29).

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include <fmt/format.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_runner.h"
#include "test_support.h"

namespace chasles::test {
namespace {

constexpr double kTight = 1e-12;

// A piece of a composite: mass, centre and central inertia.
struct Piece {
  double m;
  Vec3 c;
  Mat3 I;
};

Piece Box(double rho, const Vec3& size, const Vec3& c) {
  const double m = rho * size.prod();
  const Vec3 s2 = size.cwiseProduct(size);
  return {m, c,
          Mat3(Vec3(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y()).asDiagonal()) * m / 12};
}

// A solid cylinder of radius r and length L along coordinate axis `axis`.
Piece Cylinder(double rho, double r, double L, int axis, const Vec3& c) {
  const double m = rho * M_PI * r * r * L;
  Vec3 d = Vec3::Constant(m * (3 * r * r + L * L) / 12);
  d[axis] = m * r * r / 2;
  return {m, c, Mat3(d.asDiagonal())};
}

// Eq. 8.4 and 8.29: the sum of the pieces about its centre of mass.
Piece Sum(const std::vector<Piece>& pieces) {
  Piece total{0, Vec3::Zero(), Mat3::Zero()};
  for (const Piece& p : pieces) {
    total.m += p.m;
    total.c += p.m * p.c;
  }
  total.c /= total.m;
  for (const Piece& p : pieces) {
    const Vec3 d = p.c - total.c;
    total.I += p.I + p.m * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
  }
  return total;
}

Piece Negate(Piece p) {
  p.m = -p.m;
  p.I = -p.I;
  return p;
}

const double mm = 1e-3;
const double kAluminium = 2700, kSteel = 7850;

// The bracket of examples/meshes/l-bracket.obj: two boxes.
std::vector<Piece> Bracket() {
  return {Box(kAluminium, Vec3(60, 40, 10) * mm, Vec3(30, 20, 5) * mm),
          Box(kAluminium, Vec3(10, 40, 40) * mm, Vec3(5, 20, 30) * mm)};
}

TEST(Mesh, MeshFileOnTheCommandLine) {
  const CliResult r = RunCli("mass " + Quote(SourcePath("examples/meshes/l-bracket.obj")) +
                             " --unit mm --density 2700 --format json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto body = nlohmann::json::parse(r.out).at("bodies").at(0);
  const Piece expected = Sum(Bracket());
  EXPECT_TRUE(Near(body.at("mass").get<double>(), expected.m, kTight));
  EXPECT_TRUE(MatNear(ToVec(body.at("center_of_mass")), expected.c, kTight));
  EXPECT_TRUE(MatNear(ToMat(body.at("inertia_about_center_of_mass")), expected.I, kTight));
  // One mesh part: the body's volume and surface area are the mesh's. The L profile in xz
  // (60 x 10 plus 10 x 40: area 1000 mm², perimeter 60 + 10 + 50 + 40 + 10 + 50 = 220 mm)
  // extruded 40 mm along y: volume 40000 mm³, surface 2 * 1000 + 220 * 40 = 10800 mm².
  EXPECT_TRUE(Near(body.at("volume").get<double>(), 40000 * mm * mm * mm, kTight));
  EXPECT_TRUE(Near(body.at("surface_area").get<double>(), 10800 * mm * mm, kTight));
  EXPECT_TRUE(
      Near(body.at("parts").at(0).at("surface_area").get<double>(), 10800 * mm * mm, kTight));
}

TEST(Mesh, SceneCombinesMeshPrimitivesAndTwoMaterials) {
  const CliResult r = RunCli("mass " + Quote(SourcePath("examples/mesh-bracket-assembly.yaml")) +
                             " --format json --units SI");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto body = nlohmann::json::parse(r.out).at("bodies").at(0);
  std::vector<Piece> pieces = Bracket();
  pieces.push_back(Cylinder(kSteel, 4 * mm, 30 * mm, 2, Vec3(35, 20, 25) * mm));
  pieces.push_back(Negate(Cylinder(kAluminium, 3 * mm, 10 * mm, 0, Vec3(5, 20, 35) * mm)));
  const Piece expected = Sum(pieces);
  EXPECT_TRUE(Near(body.at("mass").get<double>(), expected.m, kTight));
  EXPECT_TRUE(MatNear(ToVec(body.at("center_of_mass")), expected.c, kTight));
  EXPECT_TRUE(MatNear(ToMat(body.at("inertia_about_center_of_mass")), expected.I, kTight));
  EXPECT_EQ(body.at("parts").at(0).at("shape"), "mesh");
  // Volume: the bracket's 40000 mm³, plus the pin's π 4² 30 mm³, minus the hole's π 3² 10 mm³;
  // the surface area of parts that cut each other is not given.
  const double pi = 3.14159265358979323846;
  EXPECT_TRUE(Near(body.at("volume").get<double>(),
                   (40000 + pi * 16 * 30 - pi * 9 * 10) * mm * mm * mm, kTight));
  EXPECT_TRUE(body.at("surface_area").is_null());
}

TEST(Mesh, CommandLineMistakes) {
  const std::string obj = Quote(SourcePath("examples/meshes/l-bracket.obj"));
  const CliResult no_unit = RunCli("mass " + obj + " --density 2700");
  EXPECT_EQ(no_unit.exit_code, 2);
  EXPECT_THAT(no_unit.err, ::testing::HasSubstr("--unit"));
  const CliResult no_mass = RunCli("mass " + obj + " --unit mm");
  EXPECT_EQ(no_mass.exit_code, 2);
  EXPECT_THAT(no_mass.err, ::testing::HasSubstr("--density, --material or --mass"));
  const CliResult bad_dim = RunCli("mass " + obj + " --unit mm --density '3 kg'");
  EXPECT_EQ(bad_dim.exit_code, 2);
  EXPECT_THAT(bad_dim.err, ::testing::HasSubstr("--density"));
  const CliResult scene_with_mesh_option =
      RunCli("mass " + Quote(SourcePath("examples/section-8.5-cube.yaml")) + " --density 2700");
  EXPECT_EQ(scene_with_mesh_option.exit_code, 2);
  EXPECT_THAT(scene_with_mesh_option.err, ::testing::HasSubstr("for a mesh file"));
}

TEST(Mesh, OpenMeshInSolidModeSuggestsShell) {
  // A cube with its top missing, written as an ASCII STL.
  const auto path = std::filesystem::temp_directory_path() / "chasles_open_box.stl";
  {
    std::ofstream f(path);
    f << "solid open\n";
    const double v[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                            {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    const int t[10][3] = {{0, 2, 1}, {0, 3, 2}, {0, 1, 5}, {0, 5, 4}, {1, 2, 6},
                          {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
    for (const auto& tri : t) {
      f << " facet normal 0 0 0\n  outer loop\n";
      for (int k : tri) f << "   vertex " << v[k][0] << " " << v[k][1] << " " << v[k][2] << "\n";
      f << "  endloop\n endfacet\n";
    }
    f << "endsolid open\n";
  }
  const CliResult solid = RunCli("mass " + Quote(path.string()) + " --unit m --density 1000");
  EXPECT_EQ(solid.exit_code, 2);
  EXPECT_THAT(solid.err, ::testing::HasSubstr("shell"));
  // As a sheet of 1 kg/m^2: five unit squares, centre of mass at z = (4 * 0.5 + 0) / 5 = 0.4.
  const CliResult shell = RunCli("mass " + Quote(path.string()) +
                                 " --unit m --mode shell --areal-density 1 --format json");
  ASSERT_EQ(shell.exit_code, 0) << shell.err;
  const auto body = nlohmann::json::parse(shell.out).at("bodies").at(0);
  EXPECT_TRUE(Near(body.at("mass").get<double>(), 5.0, kTight));
  EXPECT_TRUE(MatNear(ToVec(body.at("center_of_mass")), Vec3(0.5, 0.5, 0.4), kTight));
  std::filesystem::remove(path);
}

// A cube of edge 7 mm whose lower corner is (500000, 500000, 500000) mm, as STL triangles:
// corner i has the upper coordinate on axis k when bit k of i is set.
constexpr int kCubeQuads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                  {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
Vec3 FarCubeCorner(int i) {
  const auto c = [i](int k) { return ((i >> k) & 1) != 0 ? 500007.0 : 500000.0; };
  return Vec3(c(0), c(1), c(2));
}

// The cube as a binary STL (each triangle's corners as floats; these are integers below 2^24,
// so exact) or as an ASCII STL; `reversed`, inside out.
void WriteFarCube(const std::filesystem::path& path, bool binary, bool reversed = false) {
  std::ofstream f(path, std::ios::binary);
  if (!binary) f << "solid cube\n";
  if (binary) {
    const std::string header(80, ' ');
    const std::uint32_t n = 12;
    f.write(header.data(), 80);
    f.write(reinterpret_cast<const char*>(&n), 4);
  }
  for (const auto& q : kCubeQuads) {
    for (const std::array<int, 3> t :
         {std::array<int, 3>{q[0], q[1], q[2]}, std::array<int, 3>{q[0], q[2], q[3]}}) {
      const std::array<int, 3> corners = reversed ? std::array<int, 3>{t[0], t[2], t[1]} : t;
      if (binary) {
        float xyz[12] = {};  // the normal, then the three corners
        for (int v = 0; v < 3; ++v) {
          for (int k = 0; k < 3; ++k) {
            xyz[3 + 3 * v + k] = static_cast<float>(FarCubeCorner(corners[v])[k]);
          }
        }
        const std::uint16_t attribute = 0;
        f.write(reinterpret_cast<const char*>(xyz), sizeof xyz);
        f.write(reinterpret_cast<const char*>(&attribute), 2);
        continue;
      }
      f << "facet normal 0 0 0\n outer loop\n";
      for (int v : corners) {
        const Vec3 p = FarCubeCorner(v);
        f << "  vertex " << p.x() << " " << p.y() << " " << p.z() << "\n";
      }
      f << " endloop\nendfacet\n";
    }
  }
  if (!binary) f << "endsolid cube\n";
}

TEST(Mesh, BinaryStlSaysItStoresFloatsInTheMassReport) {
  const auto dir = OutDir("mesh");
  const auto stl = dir / "far-cube.stl";
  WriteFarCube(stl, true);
  // Its largest coordinate, 500007 mm, lies in [2^18, 2^19) mm, where floats are 2^(18 - 23)
  // mm = 3.1e-05 m apart (IEEE 754 binary32: a 24-bit significand).
  const std::string note = fmt::format(
      "binary STL stores float32: coordinates resolved to {:.2g} m at this mesh's extent (|x| "
      "up to 500.007 m)",
      std::ldexp(1.0, 18 - 23) * 1e-3);
  EXPECT_THAT(note, ::testing::HasSubstr("resolved to 3.1e-05 m"));
  const std::string args = "mass " + Quote(stl.string()) + " --unit mm --density 7850";
  const CliResult text = RunCli(args);
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_THAT(text.out, ::testing::HasSubstr(note));
  const CliResult json = RunCli(args + " --format json --units SI");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const auto part = nlohmann::json::parse(json.out).at("bodies").at(0).at("parts").at(0);
  ASSERT_EQ(part.at("notes").size(), 2u);
  EXPECT_THAT(part.at("notes").at(1).get<std::string>(), ::testing::HasSubstr(note));
  // The floats here are the integers of the text: the exact cube, m = ρ a³, I = m a²/6.
  const double a = 7e-3, m = 7850 * a * a * a;
  const auto body = nlohmann::json::parse(json.out).at("bodies").at(0);
  EXPECT_TRUE(Near(body.at("mass").get<double>(), m, kTight));
  EXPECT_TRUE(MatNear(ToMat(body.at("inertia_about_center_of_mass")),
                      Mat3(Mat3::Identity() * m * a * a / 6), kTight));
  // The same cube as text: no such note.
  const auto ascii = dir / "far-cube-ascii.stl";
  WriteFarCube(ascii, false);
  const CliResult from_text = RunCli("mass " + Quote(ascii.string()) + " --unit mm --density 7850");
  ASSERT_EQ(from_text.exit_code, 0) << from_text.err;
  EXPECT_THAT(from_text.out, ::testing::Not(::testing::HasSubstr("float32")));
}

TEST(Mesh, RepairWarningsNameTheBodyAndThePart) {
  const auto dir = OutDir("mesh");
  WriteFarCube(dir / "inside-out.stl", false, true);
  const auto scene = dir / "inside-out.yaml";
  std::ofstream(scene) << "chasles: 1\nbodies:\n  - name: bracket\n    parts:\n"
                          "      - {name: housing, shape: mesh, file: inside-out.stl, unit: mm, "
                          "density: 7850 kg/m^3}\n";
  const CliResult r = RunCli("mass " + Quote(scene.string()) + " --format json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto warnings = nlohmann::json::parse(r.out).at("warnings");
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_THAT(warnings.at(0).get<std::string>(),
              ::testing::StartsWith("body 'bracket', part 'housing' (mesh): mesh was inside out"));
}

}  // namespace
}  // namespace chasles::test
