// Mesh files keep every digit they store, however far the part sits from the file's origin: a
// box written as text (ASCII STL, OBJ, OFF, ASCII PLY) or as PLY double gives, in solid and in
// shell mode, the exact volume, centre of mass and central inertia of the box whose corners are
// the doubles its text denotes; binary STL and binary PLY float give those of the box whose
// corners are the stored floats, and say that they are floats.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "chasles/mass/mesh_mass.h"
#include "files/internal/mesh_readers.h"
#include "test_support.h"

namespace chasles::internal {
namespace {

using test::kExact;
using test::MatNear;
using test::Near;

// What "exact" is held to here: the closed forms below take a few roundings of double, and
// so does the mesh pipeline about its local origin; single precision missed the far boxes'
// volumes by 1e-5 (5 m) to 5e-3 (500 m).
constexpr double kTight = 1e-12;

// An axis-aligned box as a file's text gives it: the decimal text of its lower and upper
// corner coordinates per axis, in the file's unit, `unit` metres long.
struct BoxText {
  std::array<std::string, 3> lo, hi;
  double unit = 1.0;
};

// The double a decimal text denotes (strtod rounds correctly to nearest, as the readers'
// std::from_chars does).
double Denoted(const std::string& text) {
  return std::strtod(text.c_str(), nullptr);
}

// The stored corner values of axis k: the doubles the text denotes, or (single) the nearest
// floats, widened.
double Lo(const BoxText& b, int k, bool single) {
  const double v = Denoted(b.lo[k]);
  return single ? static_cast<double>(static_cast<float>(v)) : v;
}
double Hi(const BoxText& b, int k, bool single) {
  const double v = Denoted(b.hi[k]);
  return single ? static_cast<double>(static_cast<float>(v)) : v;
}

// The exact mass properties of the box with those stored corners, in metres.
struct Expected {
  double volume, area, solid_mass, shell_mass;
  Vec3 centre;
  Mat3 solid_inertia, shell_inertia;
};

// Edges e_k = hi_k - lo_k, computed exactly: hi_k and lo_k are of one sign and within a factor
// of two of each other (or lo_k = 0), so their difference is a double (Sterbenz's lemma); the
// unit multiplies it once. Solid of density rho (Appendix A, rectangular prism): m = rho e0 e1
// e2, I_kk = m (e_u² + e_v²)/12 with u, v the other two axes, no products. Shell of areal
// density sigma (the six faces, thin plates as in tests/unit/mass/mesh_mass_test.cpp): area
// 2 (e0 e1 + e1 e2 + e2 e0); about axis k through the centre, the two faces normal to k
// (plates e_u x e_v) give sigma e_u e_v (e_u² + e_v²)/12 each, the two normal to u (plates
// e_k x e_v, at e_u/2 from the axis) sigma e_k e_v (e_v²/12 + e_u²/4) each (parallel axes, eq.
// 8.29), the two normal to v sigma e_k e_u (e_u²/12 + e_v²/4) each; no products by symmetry.
Expected Exact(const BoxText& b, bool single, double rho, double sigma) {
  Vec3 e, lo;
  for (int k = 0; k < 3; ++k) {
    const double l = Lo(b, k, single), h = Hi(b, k, single);
    EXPECT_TRUE(l == 0.0 ||
                (l * h > 0 && std::abs(l) / 2 <= std::abs(h) && std::abs(h) <= 2 * std::abs(l)))
        << "Sterbenz's lemma needs the corners of one sign within a factor of two: " << l << ", "
        << h;
    e[k] = (h - l) * b.unit;
    lo[k] = l * b.unit;
  }
  Expected x;
  x.volume = e.prod();
  x.area = 2 * (e[0] * e[1] + e[1] * e[2] + e[2] * e[0]);
  x.solid_mass = rho * x.volume;
  x.shell_mass = sigma * x.area;
  x.centre = lo + e / 2;
  x.solid_inertia.setZero();
  x.shell_inertia.setZero();
  for (int k = 0; k < 3; ++k) {
    const double ek = e[k], eu = e[(k + 1) % 3], ev = e[(k + 2) % 3];
    x.solid_inertia(k, k) = x.solid_mass * (eu * eu + ev * ev) / 12;
    x.shell_inertia(k, k) =
        2 * sigma *
        (eu * ev * (eu * eu + ev * ev) / 12 + ek * ev * (ev * ev / 12 + eu * eu / 4) +
         ek * eu * (eu * eu / 12 + ev * ev / 4));
  }
  return x;
}

// ---- The box in each format; corner i has the upper value on axis k when bit k of i is set.

// Faces as outward counter-clockwise quads of corners.
constexpr int kQuads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                              {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};

// The two triangles of a quad, as the readers' fans split it.
std::array<std::array<int, 3>, 2> Split(const int (&q)[4]) {
  return {{{q[0], q[1], q[2]}, {q[0], q[2], q[3]}}};
}

bool Upper(int corner, int axis) {
  return ((corner >> axis) & 1) != 0;
}

std::string CornerText(const BoxText& b, int i) {
  return fmt::format("{} {} {}", Upper(i, 0) ? b.hi[0] : b.lo[0], Upper(i, 1) ? b.hi[1] : b.lo[1],
                     Upper(i, 2) ? b.hi[2] : b.lo[2]);
}

std::string AsciiStl(const BoxText& b) {
  std::string out = "solid box\n";
  for (const auto& q : kQuads) {
    for (const std::array<int, 3>& t : Split(q)) {
      out += "facet normal 0 0 0\n outer loop\n";
      for (int i : t) out += "  vertex " + CornerText(b, i) + "\n";
      out += " endloop\nendfacet\n";
    }
  }
  return out + "endsolid box\n";
}

std::string Obj(const BoxText& b) {
  std::string out;
  for (int i = 0; i < 8; ++i) out += "v " + CornerText(b, i) + "\n";
  for (const auto& q : kQuads)
    out += fmt::format("f {} {} {} {}\n", q[0] + 1, q[1] + 1, q[2] + 1, q[3] + 1);
  return out;
}

std::string Off(const BoxText& b) {
  std::string out = "OFF\n8 6 12\n";
  for (int i = 0; i < 8; ++i) out += CornerText(b, i) + "\n";
  for (const auto& q : kQuads) out += fmt::format("4 {} {} {} {}\n", q[0], q[1], q[2], q[3]);
  return out;
}

template <class T>
void Put(std::string& out, T value, bool big_endian) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big)) {
    std::reverse(bytes, bytes + sizeof(T));
  }
  out.append(bytes, sizeof(T));
}

// PLY with x, y, z of `type` (double or float) in `format`; the binary values are the stored
// corners (the doubles the text denotes, or their floats).
std::string Ply(const BoxText& b, const std::string& format, const std::string& type) {
  std::string out = fmt::format(
      "ply\nformat {} 1.0\nelement vertex 8\nproperty {} x\nproperty {} y\nproperty {} z\n"
      "element face 6\nproperty list uchar int vertex_indices\nend_header\n",
      format, type, type, type);
  const bool ascii = format == "ascii", be = format == "binary_big_endian";
  const bool single = type == "float";
  for (int i = 0; i < 8; ++i) {
    if (ascii) {
      out += CornerText(b, i) + "\n";
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      const double v = Upper(i, k) ? Hi(b, k, single) : Lo(b, k, single);
      single ? Put(out, static_cast<float>(v), be) : Put(out, v, be);
    }
  }
  for (const auto& q : kQuads) {
    if (ascii) {
      out += fmt::format("4 {} {} {} {}\n", q[0], q[1], q[2], q[3]);
      continue;
    }
    Put(out, std::uint8_t{4}, be);
    for (int i : q) Put(out, std::int32_t{i}, be);
  }
  return out;
}

// Binary STL: the corners as floats.
std::string BinaryStl(const BoxText& b) {
  std::string out(80, ' ');
  Put(out, std::uint32_t{12}, false);
  for (const auto& q : kQuads) {
    for (const std::array<int, 3>& t : Split(q)) {
      for (int k = 0; k < 3; ++k) Put(out, 0.0f, false);
      for (int i : t) {
        for (int k = 0; k < 3; ++k) {
          Put(out, static_cast<float>(Upper(i, k) ? Hi(b, k, true) : Lo(b, k, true)), false);
        }
      }
      Put(out, std::uint16_t{0}, false);
    }
  }
  return out;
}

// ---- The boxes ----

// A unit cube at the origin, and a 7 mm one at 5 m, 50 m and 500 m from it with all three
// axes offset (x and z positive, y negative, so the three edges round differently), in
// metres; and the 500 m one in millimetres, where the unit's 0.001 (not a double) must scale
// the result, not the far-away corners.
std::vector<BoxText> Boxes() {
  return {{{"0", "0", "0"}, {"1", "1", "1"}, 1.0},
          {{"5", "-5.007", "2.5"}, {"5.007", "-5", "2.507"}, 1.0},
          {{"50", "-50.007", "25"}, {"50.007", "-50", "25.007"}, 1.0},
          {{"500", "-500.007", "250"}, {"500.007", "-500", "250.007"}, 1.0},
          {{"500000", "-500007", "250000"}, {"500007", "-500000", "250007"}, 1e-3}};
}

struct Read {
  std::string label;
  MeshFileData data;
};

// The box in every format that stores the text's doubles.
std::vector<Read> TextAndDoubleFormats(const BoxText& b) {
  std::vector<Read> reads = {{"ASCII STL", ReadStl(AsciiStl(b), "b.stl")},
                             {"OBJ", ReadObj(Obj(b), "b.obj")},
                             {"OFF", ReadOff(Off(b), "b.off")}};
  for (const char* format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
    reads.push_back(
        {fmt::format("PLY {} double", format), ReadPly(Ply(b, format, "double"), "b.ply")});
  }
  // An ascii PLY declaring float is text all the same: read as written.
  reads.push_back({"PLY ascii float", ReadPly(Ply(b, "ascii", "float"), "b.ply")});
  return reads;
}

constexpr double kRho = 7850, kSigma = 2.5;

MeshMassResult Compute(const MeshFileData& d, double unit, bool shell) {
  MeshMassOptions o;
  o.scale = unit;
  if (shell) {
    o.mode = MeshMassMode::kShell;
    o.areal_density = kSigma;
  } else {
    o.density = kRho;
  }
  std::vector<double> xyz = d.xyz;
  std::vector<std::uint32_t> indices = d.indices;
  MeshMassReport report;
  report.format = d.format;
  report.single_precision = d.single_precision;
  return ComputeMeshMassProperties(std::move(xyz), std::move(indices), o, "mesh", report);
}

// The mass properties of `d` in solid and shell mode against the exact ones of box `b`.
void ExpectExact(const Read& r, const BoxText& b, bool single) {
  const Expected x = Exact(b, single, kRho, kSigma);
  const std::string what = fmt::format("{} at ({}, {}, {})", r.label, b.lo[0], b.lo[1], b.lo[2]);
  const MeshMassResult solid = Compute(r.data, b.unit, false);
  EXPECT_TRUE(Near(solid.report.volume, x.volume, kTight)) << what;
  EXPECT_TRUE(Near(solid.report.surface_area, x.area, kTight)) << what;
  EXPECT_TRUE(Near(solid.mass_properties.mass(), x.solid_mass, kTight)) << what;
  // The centre is a position hundreds of metres out: exact to a few of its own roundings.
  EXPECT_TRUE(MatNear(solid.mass_properties.p_BoBcm_B(), x.centre, kExact)) << what;
  EXPECT_TRUE(MatNear(solid.mass_properties.I_BBcm_B().matrix(), x.solid_inertia, kTight)) << what;
  const MeshMassResult shell = Compute(r.data, b.unit, true);
  EXPECT_TRUE(Near(shell.report.area, x.area, kTight)) << what;
  EXPECT_TRUE(Near(shell.mass_properties.mass(), x.shell_mass, kTight)) << what;
  EXPECT_TRUE(MatNear(shell.mass_properties.p_BoBcm_B(), x.centre, kExact)) << what;
  EXPECT_TRUE(MatNear(shell.mass_properties.I_BBcm_B().matrix(), x.shell_inertia, kTight)) << what;
}

TEST(MeshPrecision, TextAndDoubleFormatsGiveTheBoxTheirTextDenotes) {
  for (const BoxText& b : Boxes()) {
    for (const Read& r : TextAndDoubleFormats(b)) {
      EXPECT_FALSE(r.data.single_precision) << r.label;
      ExpectExact(r, b, false);
    }
  }
}

TEST(MeshPrecision, FloatFormatsGiveTheBoxOfTheirFloatsAndSaySo) {
  for (const BoxText& b : Boxes()) {
    const std::vector<Read> reads = {
        {"binary STL", ReadStl(BinaryStl(b), "b.stl")},
        {"PLY binary float", ReadPly(Ply(b, "binary_little_endian", "float"), "b.ply")},
        {"PLY binary big-endian float", ReadPly(Ply(b, "binary_big_endian", "float"), "b.ply")}};
    for (const Read& r : reads) {
      EXPECT_TRUE(r.data.single_precision) << r.label;
      ExpectExact(r, b, true);
    }
  }
}

// The diagonal of the box with the stored corners [m].
double Diagonal(const BoxText& b, bool single) {
  Vec3 e;
  for (int k = 0; k < 3; ++k) e[k] = (Hi(b, k, single) - Lo(b, k, single)) * b.unit;
  return e.norm();
}

TEST(MeshPrecision, ReportGivesTheFloatSpacingAtTheMeshsPosition) {
  // The 7 mm box at 500 m: its largest coordinate, |y| = x = 500.007 m, lies in [2^8, 2^9),
  // where floats are 2^(8 - 23) m apart (IEEE 754 binary32: a 24-bit significand).
  const BoxText b = Boxes()[3];
  const MeshMassResult single = Compute(ReadStl(BinaryStl(b), "b.stl"), b.unit, false);
  EXPECT_TRUE(single.report.single_precision);
  EXPECT_EQ(single.report.float32_spacing, std::ldexp(1.0, 8 - 23));
  EXPECT_EQ(single.report.max_abs_coordinate, Hi(b, 0, true));
  EXPECT_TRUE(Near(single.report.extent, Diagonal(b, true), kTight));
  // In millimetres, 500007 mm lies in [2^18, 2^19): 2^(18 - 23) mm.
  const BoxText mm = Boxes()[4];
  const MeshMassResult in_mm = Compute(ReadStl(BinaryStl(mm), "b.stl"), mm.unit, false);
  EXPECT_TRUE(Near(in_mm.report.float32_spacing, std::ldexp(1.0, 18 - 23) * 1e-3, kExact));
  // Text: no float spacing, the text's extent.
  const MeshMassResult text = Compute(ReadStl(AsciiStl(b), "b.stl"), b.unit, false);
  EXPECT_FALSE(text.report.single_precision);
  EXPECT_TRUE(std::isnan(text.report.float32_spacing));
  EXPECT_TRUE(Near(text.report.extent, Diagonal(b, false), kTight));
}

TEST(MeshPrecision, CubeFiveMetresOutHasEqualPrincipalMomentsFromAsciiStl) {
  // A 7.3 mm cube 5 m from the origin on every axis: its three edges are the same double
  // fl(5.0073) - 5, so its three principal moments are equal. In single precision they came
  // out unequal by 3e-5 and the volume wrong by 1.3e-5.
  const BoxText b{{"5", "5", "5"}, {"5.0073", "5.0073", "5.0073"}, 1.0};
  const MeshMassResult r = Compute(ReadStl(AsciiStl(b), "c.stl"), 1.0, false);
  const Vec3 moments = r.mass_properties.I_BBcm_B().CalcPrincipalAxes().moments;
  EXPECT_TRUE(Near(moments.minCoeff(), moments.maxCoeff(), kTight));
  const double e = Denoted("5.0073") - 5;  // exact (Sterbenz)
  EXPECT_TRUE(Near(r.report.volume, e * e * e, kTight));
  EXPECT_TRUE(Near(moments.maxCoeff(), kRho * e * e * e * e * e / 6, kTight));  // m e²/6
}

}  // namespace
}  // namespace chasles::internal
