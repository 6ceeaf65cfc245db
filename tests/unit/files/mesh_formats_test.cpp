// The mesh readers of src/files/internal/mesh_readers.h, in memory: every format gives the exact
// mass properties of a tetrahedron and a box (closed forms derived below), and every family of
// malformed input (truncated, huge declared counts, bad indices, non-finite coordinates,
// missing header lines, wrong property types, empty) is an InputError naming the file, what is
// wrong and where, never a crash, a hang or an allocation out of proportion to the input.

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/error.h"
#include "chasles/mass/mesh_mass.h"
#include "files/internal/mesh_readers.h"
#include "test_support.h"

namespace chasles::internal {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

// Edge lengths exactly representable in float and in short decimal text.
constexpr double kA = 0.5, kB = 1.25, kC = 2.0;

// A polyhedron as vertices and outward counter-clockwise polygons (0-based).
struct Shape {
  std::vector<Vec3> vertices;
  std::vector<std::vector<int>> faces;
  double volume;
  Vec3 centroid;
  Mat3 inertia_per_mass;  // central, per unit mass (chapter's tensor: -∫xy dm off the diagonal)
};

// The tetrahedron (0,0,0), (a,0,0), (0,b,0), (0,0,c). With x = a u, y = b v, z = c w over the
// unit simplex (volume 1/6): ∫x dV = abc a/24, ∫x² dV = abc a²/60, ∫xy dV = abc ab/120. So
// V = abc/6, centroid (a, b, c)/4, ∫x² dm/m = a²/10, ∫xy dm/m = ab/20; about the centroid
// (parallel axes, eq. 8.29) ∫x'² dm/m = a²/10 - a²/16 = 3a²/80 and ∫x'y' dm/m = ab/20 - ab/16 =
// -ab/80, so I_xx/m = 3(b² + c²)/80 and I_xy/m = +ab/80.
Shape Tetrahedron() {
  Shape s;
  s.vertices = {Vec3(0, 0, 0), Vec3(kA, 0, 0), Vec3(0, kB, 0), Vec3(0, 0, kC)};
  s.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  s.volume = kA * kB * kC / 6;
  s.centroid = Vec3(kA, kB, kC) / 4;
  s.inertia_per_mass << 3 * (kB * kB + kC * kC) / 80, kA * kB / 80, kA * kC / 80,  //
      kA * kB / 80, 3 * (kA * kA + kC * kC) / 80, kB * kC / 80,                    //
      kA * kC / 80, kB * kC / 80, 3 * (kA * kA + kB * kB) / 80;
  return s;
}

// The box [0,a] x [0,b] x [0,c] with quadrilateral faces (Appendix A, rectangular prism:
// I_xx = m (b² + c²)/12 about the centre).
Shape Box() {
  Shape s;
  for (int i = 0; i < 8; ++i) {
    s.vertices.push_back(Vec3((i & 1) ? kA : 0, (i & 2) ? kB : 0, (i & 4) ? kC : 0));
  }
  s.faces = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  s.volume = kA * kB * kC;
  s.centroid = Vec3(kA, kB, kC) / 2;
  s.inertia_per_mass =
      Vec3(kB * kB + kC * kC, kA * kA + kC * kC, kA * kA + kB * kB).asDiagonal() * (1.0 / 12);
  return s;
}

// Fan triangles of every face, as the readers make them.
std::vector<std::array<int, 3>> Triangles(const Shape& s) {
  std::vector<std::array<int, 3>> t;
  for (const auto& f : s.faces) {
    for (std::size_t k = 2; k < f.size(); ++k) t.push_back({f[0], f[k - 1], f[k]});
  }
  return t;
}

// ---- Writers ----

template <class T>
void Put(std::string& out, T value, bool big_endian = false) {
  char b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big)) std::reverse(b, b + sizeof(T));
  out.append(b, sizeof(T));
}

std::string BinaryStl(const Shape& s) {
  std::string out(80, ' ');
  const auto tris = Triangles(s);
  Put(out, static_cast<std::uint32_t>(tris.size()));
  for (const auto& t : tris) {
    for (int k = 0; k < 3; ++k) Put(out, 0.0f);
    for (int v : t) {
      for (int k = 0; k < 3; ++k) Put(out, static_cast<float>(s.vertices[v][k]));
    }
    Put(out, std::uint16_t{0});
  }
  return out;
}

std::string AsciiStl(const Shape& s) {
  std::string out = "solid shape\n";
  for (const auto& t : Triangles(s)) {
    out += "  facet normal 0 0 0\n    outer loop\n";
    for (int v : t) {
      const Vec3& p = s.vertices[v];
      out += fmt::format("      vertex {} {} {}\n", p.x(), p.y(), p.z());
    }
    out += "    endloop\n  endfacet\n";
  }
  return out + "endsolid shape\n";
}

// OBJ in three styles: plain 1-based, v/vt/vn with a texture and normal list, and negative
// (relative) indices with each face after its vertices.
std::string Obj(const Shape& s, int style) {
  std::string out = "# shape\nmtllib none.mtl\no shape\n";
  for (const Vec3& p : s.vertices) out += fmt::format("v {} {} {}\n", p.x(), p.y(), p.z());
  out += "vt 0 0\nvn 0 0 1\ns off\n";
  const int n = static_cast<int>(s.vertices.size());
  for (const auto& f : s.faces) {
    out += "f";
    for (int v : f) {
      if (style == 0) out += fmt::format(" {}", v + 1);
      if (style == 1) out += fmt::format(" {}/1/1", v + 1);
      if (style == 2) out += fmt::format(" {}//1", v - n);
    }
    out += "\n";
  }
  return out;
}

std::string Off(const Shape& s, const std::string& keyword = "OFF") {
  std::string out =
      fmt::format("{}\n# a comment\n{} {} 0\n", keyword, s.vertices.size(), s.faces.size());
  for (const Vec3& p : s.vertices) {
    out +=
        fmt::format("{} {} {}{}\n", p.x(), p.y(), p.z(), keyword == "COFF" ? " 0.5 0.5 0.5" : "");
  }
  for (const auto& f : s.faces) {
    out += fmt::format("{}", f.size());
    for (int v : f) out += fmt::format(" {}", v);
    out += "  # face\n";
  }
  return out;
}

// PLY with an extra vertex property before x, coordinates of type `coord` ("float", "double",
// "int" scaled by 1), an extra element between vertex and face, and a second list on the face.
struct PlyStyle {
  std::string format = "ascii";  // or binary_little_endian, binary_big_endian
  std::string coord = "float";
  std::string count_type = "uchar";
  std::string index_type = "int";
  std::string index_name = "vertex_indices";
};

std::string Ply(const Shape& s, const PlyStyle& st) {
  std::string out = fmt::format(
      "ply\nformat {} 1.0\ncomment made for a test\nelement vertex {}\nproperty uchar red\n"
      "property {} x\nproperty {} y\nproperty {} z\nelement extra 2\nproperty short a\n"
      "property list uchar float b\nelement face {}\nproperty list {} {} {}\nproperty list "
      "uchar float texcoord\nend_header\n",
      st.format, s.vertices.size(), st.coord, st.coord, st.coord, s.faces.size(), st.count_type,
      st.index_type, st.index_name);
  const bool ascii = st.format == "ascii";
  const bool be = st.format == "binary_big_endian";
  auto put_typed = [&](const std::string& type, double v) {
    if (ascii) {
      out += fmt::format(" {}", v);
    } else if (type == "float") {
      Put(out, static_cast<float>(v), be);
    } else if (type == "double") {
      Put(out, v, be);
    } else if (type == "int") {
      Put(out, static_cast<std::int32_t>(v), be);
    } else if (type == "char" || type == "int8") {
      Put(out, static_cast<std::int8_t>(v), be);
    } else if (type == "uchar") {
      Put(out, static_cast<std::uint8_t>(v), be);
    } else if (type == "short") {
      Put(out, static_cast<std::int16_t>(v), be);
    } else if (type == "ushort" || type == "uint16") {
      Put(out, static_cast<std::uint16_t>(v), be);
    } else if (type == "uint" || type == "uint32") {
      Put(out, static_cast<std::uint32_t>(v), be);
    } else {
      ADD_FAILURE() << type;
    }
  };
  auto end_record = [&] {
    if (ascii) out += "\n";
  };
  for (const Vec3& p : s.vertices) {
    put_typed("uchar", 7);
    for (int k = 0; k < 3; ++k) put_typed(st.coord, p[k]);
    end_record();
  }
  for (int e = 0; e < 2; ++e) {
    put_typed("short", -3);
    put_typed("uchar", 2);
    put_typed("float", 0.25);
    put_typed("float", 0.75);
    end_record();
  }
  for (const auto& f : s.faces) {
    put_typed(st.count_type, static_cast<double>(f.size()));
    for (int v : f) put_typed(st.index_type, v);
    put_typed("uchar", 1);
    put_typed("float", 0.5);
    end_record();
  }
  return out;
}

// ---- Mass properties of what a reader returns ----

std::vector<double> Xyz(const Shape& s) {
  std::vector<double> xyz;
  for (const Vec3& p : s.vertices) {
    for (int k = 0; k < 3; ++k) xyz.push_back(p[k]);
  }
  return xyz;
}

// The shape scaled by k: volume x k³, centroid x k, inertia per mass x k².
Shape Scaled(Shape s, double k) {
  for (Vec3& p : s.vertices) p *= k;
  s.volume *= k * k * k;
  s.centroid *= k;
  s.inertia_per_mass *= k * k;
  return s;
}

void ExpectShape(const MeshFileData& d, const Shape& s, const std::string& what) {
  MeshMassOptions o;
  o.density = 1000;
  std::vector<double> xyz = d.xyz;
  std::vector<std::uint32_t> indices = d.indices;
  const MeshMassResult r =
      ComputeMeshMassProperties(std::move(xyz), std::move(indices), o, "mesh " + what);
  const double m = 1000 * s.volume;
  EXPECT_TRUE(test::Near(r.mass_properties.mass(), m, 1e-13)) << what;
  EXPECT_TRUE(test::MatNear(r.mass_properties.p_BoBcm_B(), s.centroid, 1e-13)) << what;
  EXPECT_TRUE(test::MatNear(r.mass_properties.I_BBcm_B().matrix(), m * s.inertia_per_mass, 1e-12))
      << what;
  EXPECT_TRUE(r.report.repair.warnings.empty()) << what;
}

TEST(MeshFormats, EveryFormatGivesTheClosedFormsOfTetrahedronAndBox) {
  for (const Shape& s : {Tetrahedron(), Box()}) {
    const std::string label = fmt::format("{} vertices", s.vertices.size());
    const MeshFileData bin = ReadStl(BinaryStl(s), "s.stl");
    EXPECT_EQ(bin.format, "binary STL");
    ExpectShape(bin, s, label + " binary STL");
    const MeshFileData ascii = ReadStl(AsciiStl(s), "s.stl");
    EXPECT_EQ(ascii.format, "ASCII STL");
    EXPECT_EQ(ascii.xyz, bin.xyz);  // the same triangles, vertex for vertex
    ExpectShape(ascii, s, label + " ASCII STL");
    for (int style = 0; style < 3; ++style) {
      const MeshFileData obj = ReadObj(Obj(s, style), "s.obj");
      EXPECT_EQ(obj.format, "OBJ");
      EXPECT_EQ(obj.vertex_count(), s.vertices.size());
      EXPECT_EQ(obj.triangle_count(), Triangles(s).size());
      ExpectShape(obj, s, fmt::format("{} OBJ style {}", label, style));
    }
    for (const char* keyword : {"OFF", "COFF"}) {
      const MeshFileData off = ReadOff(Off(s, keyword), "s.off");
      EXPECT_EQ(off.format, "OFF");
      EXPECT_EQ(off.triangle_count(), Triangles(s).size());
      ExpectShape(off, s, label + " " + keyword);
    }
    for (const char* format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
      for (const char* coord : {"float", "double"}) {
        PlyStyle st;
        st.format = format;
        st.coord = coord;
        const MeshFileData ply = ReadPly(Ply(s, st), "s.ply");
        EXPECT_EQ(ply.format, "PLY");
        EXPECT_EQ(ply.vertex_count(), s.vertices.size());
        EXPECT_EQ(ply.xyz, Xyz(s));
        ExpectShape(ply, s, fmt::format("{} PLY {} {}", label, format, coord));
      }
    }
  }
}

TEST(MeshFormats, PlyOfAnyNumericTypes) {
  // Scaled by 4 the box has integer corners (2, 5, 8), so integer coordinates are exact too.
  const Shape s = Scaled(Box(), 4);
  const char* kIndexTypes[] = {"char", "uchar", "short",  "ushort", "int",
                               "uint", "int8",  "uint16", "uint32"};
  for (const char* format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
    for (const char* coord : {"int", "short", "uchar", "float", "double"}) {
      for (const char* index : kIndexTypes) {
        for (const char* count : {"uchar", "int", "ushort"}) {
          PlyStyle st{format, coord, count, index, "vertex_index"};
          const std::string text = Ply(s, st);
          const MeshFileData d = ReadPly(text, "s.ply");
          ASSERT_EQ(d.xyz, Xyz(s)) << format << coord << index << count;
          ASSERT_EQ(d.triangle_count(), 12u);
        }
      }
      PlyStyle st{format, coord, "uchar", "int", "vertex_indices"};
      ExpectShape(ReadPly(Ply(s, st), "s.ply"), s, fmt::format("PLY {} {}", format, coord));
    }
  }
}

TEST(MeshFormats, DispatchByExtension) {
  const Shape s = Tetrahedron();
  EXPECT_EQ(ReadMeshBytes(BinaryStl(s), "a/b.STL").format, "binary STL");
  EXPECT_EQ(ReadMeshBytes(AsciiStl(s), "b.stl").format, "ASCII STL");
  EXPECT_EQ(ReadMeshBytes(Obj(s, 0), "b.Obj").format, "OBJ");
  EXPECT_EQ(ReadMeshBytes(Off(s), "b.off").format, "OFF");
  EXPECT_EQ(ReadMeshBytes(Ply(s, {}), "b.PLY").format, "PLY");
  for (const char* name : {"b.3ds", "b.fbx", "b", "b.stl.gz"}) {
    EXPECT_THAT([&] { ReadMeshBytes(Obj(s, 0), name); },
                ThrowsMessage<InputError>(AllOf(
                    HasSubstr(fmt::format("mesh file '{}': unsupported format", name)),
                    HasSubstr(".stl (binary or ASCII), .obj, .ply (ASCII or binary), .off"))));
  }
}

// ---- Malformed input ----

using Reader = std::function<MeshFileData(std::string_view, const std::string&)>;

// The message of the InputError `read` throws on `bytes` (a failure when it returns).
std::string ErrorOf(const Reader& read, std::string_view bytes, const std::string& name) {
  try {
    read(bytes, name);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for " << name << ": " << std::string(bytes.substr(0, 200));
  return "";
}

#define EXPECT_MESH_ERROR(read, bytes, name, ...) \
  EXPECT_THAT(ErrorOf(read, bytes, name), AllOf(HasSubstr("mesh file '" name "': "), __VA_ARGS__))

struct Format {
  std::string name;
  Reader read;
  std::string good;
  bool binary;
};

std::vector<Format> Formats() {
  const Shape s = Box();
  PlyStyle le{"binary_little_endian"}, be{"binary_big_endian"};
  return {{"box.stl", ReadStl, BinaryStl(s), true}, {"box.stl", ReadStl, AsciiStl(s), false},
          {"box.obj", ReadObj, Obj(s, 1), false},   {"box.off", ReadOff, Off(s), false},
          {"box.ply", ReadPly, Ply(s, {}), false},  {"box.ply", ReadPly, Ply(s, le), true},
          {"box.ply", ReadPly, Ply(s, be), true}};
}

TEST(MeshFormats, EveryTruncationIsAnError) {
  // Cut anywhere, a file is refused with "mesh file 'NAME'" (an OBJ cut at a line end is
  // still a valid, smaller OBJ, so it may also be read; it must then hold whole faces).
  for (const Format& f : Formats()) {
    // Text files: cuts in the last line may leave a valid file (a shorter number, a shorter
    // name after endsolid, part of a comment); cuts before it must not.
    std::size_t must_fail = f.good.size();
    if (!f.binary) must_fail = f.good.rfind('\n', f.good.size() - 2) + 1;
    for (std::size_t n = 0; n < f.good.size(); ++n) {
      const std::string_view cut = std::string_view(f.good).substr(0, n);
      try {
        const MeshFileData d = f.read(cut, f.name);
        ASSERT_TRUE(f.name == "box.obj" || n >= must_fail)
            << n << " bytes of " << f.good.substr(0, 60) << " read";
        EXPECT_EQ(d.indices.size() % 3, 0u);
      } catch (const InputError& e) {
        ASSERT_THAT(e.what(), HasSubstr("mesh file '" + f.name + "': ")) << n;
      }
    }
  }
}

TEST(MeshFormats, RandomCorruptionNeverCrashes) {
  // Seeded byte flips, insertions and deletions: every outcome is a mesh or an InputError
  // (AddressSanitizer checks the reads of these runs).
  std::mt19937 rng(20261123);
  for (const Format& f : Formats()) {
    for (int trial = 0; trial < 300; ++trial) {
      std::string bytes = f.good;
      const int edits = 1 + static_cast<int>(rng() % 4);
      for (int e = 0; e < edits && !bytes.empty(); ++e) {
        const std::size_t at = rng() % bytes.size();
        static constexpr char kChars[] = "0123456789 -.\nabcefnxyz#/\xff\x00";
        const char c = kChars[rng() % (sizeof kChars - 1)];
        switch (rng() % 3) {
          case 0:
            bytes[at] = c;
            break;
          case 1:
            bytes.insert(at, 1, c);
            break;
          default:
            bytes.erase(at, 1);
            break;
        }
      }
      try {
        const MeshFileData d = f.read(bytes, f.name);
        EXPECT_EQ(d.indices.size() % 3, 0u);
        for (std::uint32_t i : d.indices) ASSERT_LT(i, d.vertex_count());
        for (double x : d.xyz) ASSERT_TRUE(std::abs(x) <= kMaxMeshCoordinate);
      } catch (const InputError& e) {
        ASSERT_THAT(e.what(), HasSubstr("mesh file '" + f.name + "': "));
      }
    }
  }
}

TEST(MeshFormats, EmptyInputs) {
  EXPECT_MESH_ERROR(ReadStl, "", "e.stl", HasSubstr("too short for a binary STL (0 bytes"));
  EXPECT_MESH_ERROR(ReadStl, "solid x\nendsolid x\n", "e.stl",
                    HasSubstr("empty mesh (the ASCII STL holds no facet)"));
  EXPECT_MESH_ERROR(ReadAsciiStl, "", "e.stl", HasSubstr("empty ASCII STL (no 'solid' line)"));
  EXPECT_MESH_ERROR(ReadObj, "", "e.obj",
                    HasSubstr("empty mesh (the OBJ holds 0 vertices and no face)"));
  EXPECT_MESH_ERROR(ReadObj, "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "e.obj",
                    HasSubstr("empty mesh (the OBJ holds 3 vertices and no face)"));
  EXPECT_MESH_ERROR(ReadOff, "", "e.off", HasSubstr("empty file"));
  EXPECT_MESH_ERROR(ReadOff, "OFF\n0 0 0\n", "e.off",
                    HasSubstr("empty mesh (the OFF holds no face)"));
  EXPECT_MESH_ERROR(ReadPly, "", "e.ply", HasSubstr("PLY header: empty file (line 1)"));
  EXPECT_MESH_ERROR(ReadPly,
                    "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float "
                    "y\nproperty float z\nelement face 0\nproperty list uchar int "
                    "vertex_indices\nend_header\n",
                    "e.ply", HasSubstr("empty mesh (the PLY holds no face)"));
  EXPECT_MESH_ERROR(ReadPly,
                    "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float "
                    "y\nproperty float z\nend_header\n0 0 0\n",
                    "e.ply", HasSubstr("empty mesh (the PLY declares no 'face' element"));
}

TEST(MeshFormats, TruncationNamesTheLineOrOffset) {
  const Shape s = Tetrahedron();
  // ASCII STL cut inside the third facet: line 1 + 2 x 7 + 3 holds "outer loop".
  std::string stl = AsciiStl(s);
  std::size_t cut = 0;
  for (int line = 0; line < 18; ++line) cut = stl.find('\n', cut) + 1;
  EXPECT_MESH_ERROR(ReadStl, stl.substr(0, cut), "t.stl",
                    HasSubstr("truncated ASCII STL: the file ends in facet 3 where 'vertex' was "
                              "expected (line 18)"));
  // Without endsolid.
  stl = AsciiStl(s);
  stl.resize(stl.rfind("endsolid"));
  EXPECT_MESH_ERROR(ReadStl, stl, "t.stl",
                    HasSubstr("truncated ASCII STL: the file ends after 4 facets without "
                              "'endsolid' (line 29)"));
  // OFF: the "OFF\n8 4 " (a header promising 8 vertices and 4 faces, then nothing).
  EXPECT_MESH_ERROR(ReadOff, "OFF\n8 4 ", "t.off",
                    HasSubstr("the header declares 8 vertices and 4 faces, which take at least "
                              "79 bytes, but only 0 bytes follow it"),
                    HasSubstr("(line 2)"));
  // Cut short, the counts no longer fit the bytes, or the data runs out.
  EXPECT_MESH_ERROR(ReadOff, Off(s).substr(0, Off(s).find("3 0 1 3")), "t.off",
                    HasSubstr("the header declares 4 vertices and 4 faces, which take at least "
                              "55 bytes, but only 45 bytes follow it: the file is truncated or "
                              "the counts are wrong (line 3)"));
  const std::string off = Off(s).substr(0, Off(s).find("3 1 2 3"));
  EXPECT_MESH_ERROR(ReadOff, off, "t.off",
                    HasSubstr("truncated: the file ends after 3 of 4 faces (line 10)"));
  EXPECT_MESH_ERROR(ReadOff, off + "# no last face, only a comment\n", "t.off",
                    HasSubstr("truncated: the file ends after 3 of 4 faces (line 11)"));
  // PLY ascii cut inside the vertices, binary cut inside a face.
  const std::string ply = Ply(s, {});
  EXPECT_MESH_ERROR(ReadPly, ply.substr(0, ply.find("7 0.5")), "t.ply",
                    HasSubstr("PLY header declares 4 'vertex' records of at least 8 bytes each, "
                              "but only 10 bytes follow the header: the file is truncated or the "
                              "count is wrong (line 4)"));
  EXPECT_MESH_ERROR(ReadPly, ply.substr(0, ply.find("7 0.5")) + std::string(100, ' '), "t.ply",
                    HasSubstr("truncated: the file ends inside a record (line 17)"));
  const std::string bin = Ply(s, {"binary_little_endian"});
  EXPECT_MESH_ERROR(ReadPly, std::string_view(bin).substr(0, bin.size() - 7), "t.ply",
                    HasSubstr("a face declares 3 values of 4 bytes but only 10 bytes are left "
                              "(byte offset "));
  EXPECT_MESH_ERROR(ReadPly, std::string_view(bin).substr(0, bin.size() - 18), "t.ply",
                    HasSubstr("truncated: the file ends inside a list's count (byte offset "));
}

// A PLY header for `n` float vertices and `f` faces (no body).
std::string PlyHeader(const std::string& format, const std::string& n, const std::string& f,
                      const std::string& list = "list uchar int vertex_indices") {
  return fmt::format(
      "ply\nformat {} 1.0\nelement vertex {}\nproperty float x\nproperty float y\nproperty "
      "float z\nelement face {}\nproperty {}\nend_header\n",
      format, n, f, list);
}

TEST(MeshFormats, HugeDeclaredCountsAreRefusedBeforeAllocating) {
  // A billion vertices in a 220-byte file: 12 GB if believed.
  std::string ply = PlyHeader("binary_little_endian", "1000000000", "1");
  ply.resize(220, '\0');
  EXPECT_MESH_ERROR(ReadPly, ply, "h.ply",
                    HasSubstr("PLY header declares 1000000000 'vertex' records of at least 12 "
                              "bytes each, but only"),
                    HasSubstr("(line 3)"));
  EXPECT_MESH_ERROR(ReadPly, PlyHeader("ascii", "1000000000", "1") + "0 0 0\n", "h.ply",
                    HasSubstr("1000000000 'vertex' records of at least 6 bytes each, but only 6 "
                              "bytes follow"));
  EXPECT_MESH_ERROR(ReadPly, PlyHeader("ascii", "18446744073709551615", "1"), "h.ply",
                    HasSubstr("count '18446744073709551615' is not a non-negative integer"));
  EXPECT_MESH_ERROR(ReadPly, PlyHeader("ascii", "-1", "1"), "h.ply",
                    HasSubstr("count '-1' is not a non-negative integer (line 3)"));
  // A face claiming 4e9 indices in a binary file of a few bytes.
  std::string face = PlyHeader("binary_little_endian", "3", "1", "list uint int vertex_indices");
  for (int i = 0; i < 9; ++i) Put(face, 0.0f);
  Put(face, std::uint32_t{4000000000u});
  Put(face, std::int32_t{0});
  EXPECT_MESH_ERROR(ReadPly, face, "h.ply",
                    HasSubstr("a face declares 4000000000 values of 4 bytes but only 4 bytes are "
                              "left (byte offset "));
  EXPECT_MESH_ERROR(ReadOff, "OFF\n1000000000 1000000000 0\n0 0 0\n", "h.off",
                    HasSubstr("declares 1000000000 vertices and 1000000000 faces"),
                    HasSubstr("(line 2)"));
  EXPECT_MESH_ERROR(ReadOff, "OFF\n99999999999999999999 1 0\n", "h.off",
                    HasSubstr("the vertex count: '99999999999999999999' is not an integer"));
  // A binary STL announcing more triangles than it holds.
  std::string stl = BinaryStl(Tetrahedron());
  stl[80] = '\xff';
  stl[83] = '\x7f';
  EXPECT_MESH_ERROR(ReadStl, stl, "h.stl", HasSubstr("binary STL size mismatch"));
}

TEST(MeshFormats, BadIndices) {
  const Shape s = Tetrahedron();
  EXPECT_MESH_ERROR(ReadObj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "i.obj",
                    HasSubstr("face 1: vertex index 4 is out of range (3 vertices defined before "
                              "this face"),
                    HasSubstr("(line 4)"));
  EXPECT_MESH_ERROR(ReadObj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "i.obj",
                    HasSubstr("vertex index 0 is out of range"));
  EXPECT_MESH_ERROR(ReadObj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", "i.obj",
                    HasSubstr("vertex index -4 is out of range"));
  EXPECT_MESH_ERROR(ReadObj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", "i.obj",
                    HasSubstr("face 1 has 2 vertices; a face needs at least 3 (line 4)"));
  EXPECT_MESH_ERROR(ReadObj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x/1\n", "i.obj",
                    HasSubstr("'x/1' is not a vertex index"));
  std::string off = Off(s);
  off.replace(off.find("3 1 2 3"), 7, "3 1 2 4");
  EXPECT_MESH_ERROR(ReadOff, off, "i.off",
                    HasSubstr("face 4: vertex index 4 is out of range (0 to 3) (line 11)"));
  off = Off(s);
  off.replace(off.find("3 1 2 3"), 7, "3 1 2 -1");
  EXPECT_MESH_ERROR(ReadOff, off, "i.off", HasSubstr("vertex index -1 is out of range"));
  off = Off(s);
  off.replace(off.find("3 1 2 3"), 7, "3 1 2");
  EXPECT_MESH_ERROR(ReadOff, off, "i.off",
                    HasSubstr("face 4 declares 3 vertices but its line holds 2 (line 11)"));
  std::string ply = Ply(s, {});
  ply.replace(ply.find("3 1 2 3"), 7, "3 1 2 4");
  EXPECT_MESH_ERROR(ReadPly, ply, "i.ply",
                    HasSubstr("face 3: vertex index 4 is out of range (0 to 3)"),
                    HasSubstr("(line 25)"));
  ply = Ply(s, {});
  ply.replace(ply.find("3 1 2 3"), 7, "2 1 2");
  EXPECT_MESH_ERROR(ReadPly, ply, "i.ply", HasSubstr("face 3 has 2 vertices"));
  ply = Ply(s, {});
  ply.replace(ply.find("3 1 2 3"), 7, "3 1 2 300");
  EXPECT_MESH_ERROR(ReadPly, ply, "i.ply", HasSubstr("vertex index 300 is out of range"));
  ply = Ply(s, {});
  ply.replace(ply.find("3 1 2 3"), 7, "3 1 2 3.5");
  EXPECT_MESH_ERROR(ReadPly, ply, "i.ply",
                    HasSubstr("'3.5' is not an integer (its type is int) (line 25)"));
  PlyStyle uc{"binary_big_endian", "float", "uchar", "uchar"};
  std::string bin = Ply(s, uc);
  bin[bin.size() - 6] = 9;  // the last face's last index (then the uchar 1 and float 0.5)
  EXPECT_MESH_ERROR(ReadPly, bin, "i.ply",
                    HasSubstr("face 3: vertex index 9 is out of range (0 to 3) (byte offset "));
  PlyStyle neg{"binary_little_endian", "float", "char", "int"};
  bin = Ply(s, neg);
  bin[bin.size() - 5 - 12 - 1] = -3;  // the last face's count
  EXPECT_MESH_ERROR(ReadPly, bin, "i.ply", HasSubstr("a list's count is negative (-3)"));
}

TEST(MeshFormats, NonFiniteCoordinates) {
  const Shape s = Tetrahedron();
  for (const char* bad : {"nan", "inf", "-inf", "1e39"}) {
    std::string stl = AsciiStl(s);
    stl.replace(stl.find("vertex 0.5 0 0"), 14, std::string("vertex 0.5 ") + bad + " 0");
    EXPECT_MESH_ERROR(ReadStl, stl, "n.stl", HasSubstr("facet 1: vertex coordinate"),
                      HasSubstr("is not a finite number within ±3.4e38 (line 6)"));
    std::string obj = Obj(s, 0);
    obj.replace(obj.find("v 0.5 0 0"), 9, std::string("v 0.5 0 ") + bad);
    EXPECT_MESH_ERROR(ReadObj, obj, "n.obj",
                      HasSubstr(std::string("vertex z is ") + bad +
                                ", not a finite number within ±3.4e38 (line 5)"));
    std::string off = Off(s);
    off.replace(off.find("0.5 0 0"), 7, std::string(bad) + " 0 0");
    EXPECT_MESH_ERROR(ReadOff, off, "n.off", HasSubstr(std::string("vertex x is ") + bad),
                      HasSubstr("(line 5)"));
    std::string ply = Ply(s, {});
    ply.replace(ply.find("7 0.5 0 0"), 9, std::string("7 0.5 ") + bad + " 0");
    EXPECT_MESH_ERROR(ReadPly, ply, "n.ply", HasSubstr("vertex 1: coordinate y is"),
                      HasSubstr("(line 17)"));
  }
  std::string bin = BinaryStl(s);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(bin.data() + 84 + 50 + 12 + 4, &nan, 4);  // triangle 2, first vertex, y
  EXPECT_MESH_ERROR(ReadStl, bin, "n.stl",
                    HasSubstr("triangle 2 has a non-finite vertex coordinate (nan) (byte offset "
                              "150)"));
  std::string ply = Ply(s, {"binary_little_endian", "double"});
  const double inf = std::numeric_limits<double>::infinity();
  const std::size_t body = ply.find("end_header\n") + 11;
  std::memcpy(ply.data() + body + 1 + 8 * 2, &inf, 8);  // vertex 0, z
  EXPECT_MESH_ERROR(ReadPly, ply, "n.ply",
                    HasSubstr(fmt::format("vertex 0: coordinate z is inf, not a finite "
                                          "number within ±3.4e38 (byte offset {})",
                                          body + 17)));
}

TEST(MeshFormats, MissingOrWrongHeaderLines) {
  const std::string v = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
  const std::string f = "element face 1\nproperty list uchar int vertex_indices\n";
  const std::string body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  // The hang: a header without end_header.
  EXPECT_MESH_ERROR(ReadPly, "ply\nformat ascii 1.0\n", "m.ply",
                    HasSubstr("PLY header: the file ends before 'end_header' (line 2)"));
  EXPECT_MESH_ERROR(ReadPly, "PLY\n", "m.ply", HasSubstr("not a PLY file"));
  EXPECT_MESH_ERROR(ReadPly, "ply\n" + v + f + "end_header\n" + body, "m.ply",
                    HasSubstr("no 'format' line before 'end_header' (line 8)"));
  EXPECT_MESH_ERROR(ReadPly, "ply\nformat ascii 2.0\n", "m.ply",
                    HasSubstr("unsupported version '2.0' (1.0) (line 2)"));
  EXPECT_MESH_ERROR(ReadPly, "ply\nformat binary_middle_endian 1.0\n", "m.ply",
                    HasSubstr("unknown format 'binary_middle_endian'"));
  EXPECT_MESH_ERROR(ReadPly, "ply\nformat ascii 1.0\nproperty float x\n", "m.ply",
                    HasSubstr("'property' before any 'element' (line 3)"));
  EXPECT_MESH_ERROR(ReadPly, "ply\nformat ascii 1.0\nelement vertex 3\nproperty real x\n", "m.ply",
                    HasSubstr("unknown property type 'real'"), HasSubstr("(line 4)"));
  EXPECT_MESH_ERROR(ReadPly, "ply\nformat ascii 1.0\nelment vertex 3\n", "m.ply",
                    HasSubstr("unknown header line 'elment vertex 3' (line 3)"));
  EXPECT_MESH_ERROR(ReadPly, "ply\nformat ascii 1.0\n" + f + "end_header\n3 0 1 2\n", "m.ply",
                    HasSubstr("PLY header declares no 'vertex' element"));
  EXPECT_MESH_ERROR(ReadPly,
                    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float "
                    "y\n" +
                        f + "end_header\n" + body,
                    "m.ply", HasSubstr("element 'vertex' has no property 'z' (line 3)"));
  EXPECT_MESH_ERROR(ReadPly, "ply\nformat ascii 1.0\n" + v + f + "end_header\n" + body + "7\n",
                    "m.ply", HasSubstr("unexpected data after the last element (line 14)"));
  // OFF without its keyword, or binary, or 4-D.
  EXPECT_MESH_ERROR(ReadOff, "3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "m.off",
                    HasSubstr("'3' where the keyword 'OFF' was expected (line 1)"));
  EXPECT_MESH_ERROR(ReadOff, "OFF BINARY\n", "m.off", HasSubstr("binary OFF is not supported"));
  EXPECT_MESH_ERROR(ReadOff, "4OFF\n", "m.off", HasSubstr("only 3-D OFF"));
  EXPECT_MESH_ERROR(ReadOff, "OFF\n3\n", "m.off", HasSubstr("the face count is missing (line 2)"));
  EXPECT_MESH_ERROR(ReadOff, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n", "m.off",
                    HasSubstr("unexpected data after the 3 vertices and 1 faces the header "
                              "declares (line 7)"));
  EXPECT_MESH_ERROR(ReadOff, "OFF 3 1 0\n0 0 0\n1 0 0\n0 1                \n3 0 1 2\n", "m.off",
                    HasSubstr("vertex z is missing (line 4)"));
  // ASCII STL out of order.
  EXPECT_MESH_ERROR(
      ReadAsciiStl, "solid\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n",
      "m.stl", HasSubstr("'endloop' where 'vertex' was expected in facet 1 (line 6)"));
  EXPECT_MESH_ERROR(ReadAsciiStl, "solid\nfacet 0 0 1\n", "m.stl",
                    HasSubstr("'0' where 'normal' was expected in facet 1 (line 2)"));
  EXPECT_MESH_ERROR(ReadAsciiStl, "solid\nfacet normal 0 0 one\n", "m.stl",
                    HasSubstr("facet 1: a normal component 'one' is not a number (line 2)"));
  EXPECT_MESH_ERROR(ReadAsciiStl, "solid\nvertex 0 0 0\n", "m.stl",
                    HasSubstr("'vertex' where 'facet' or 'endsolid' was expected (line 2)"));
}

TEST(MeshFormats, WrongPropertyTypes) {
  const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 3\n";
  EXPECT_MESH_ERROR(ReadPly,
                    head + xyz + "element face 1\nproperty int vertex_indices\nend_header\n",
                    "w.ply", HasSubstr("face property 'vertex_indices' must be a list (line 7)"));
  EXPECT_MESH_ERROR(
      ReadPly,
      head + xyz + "element face 1\nproperty list uchar float vertex_indices\nend_header\n",
      "w.ply",
      HasSubstr("face property 'vertex_indices' has items of type float; vertex "
                "indices must be integers (line 7)"));
  EXPECT_MESH_ERROR(
      ReadPly, head + xyz + "element face 1\nproperty list float int vertex_indices\n", "w.ply",
      HasSubstr("list 'vertex_indices': its count type 'float' is not an "
                "integer type (line 8)"));
  EXPECT_MESH_ERROR(ReadPly,
                    head +
                        "property list uchar float x\nproperty float y\nproperty float z\n"
                        "element face 1\nproperty list uchar int vertex_indices\nend_header\n",
                    "w.ply",
                    HasSubstr("vertex property 'x' is a list; it must be a number (line 3)"));
  EXPECT_MESH_ERROR(ReadPly,
                    head + xyz + "element face 1\nproperty list uchar int corners\nend_header\n",
                    "w.ply",
                    HasSubstr("element 'face' has no list property 'vertex_indices' (or "
                              "'vertex_index') (line 7)"));
  EXPECT_MESH_ERROR(ReadPly,
                    head + xyz +
                        "element face 1\nproperty list uchar uchar vertex_indices\nend_header\n"
                        "0 0 0\n1 0 0\n0 1 0\n3 0 1 256\n",
                    "w.ply", HasSubstr("256 does not fit its type uchar (line 13)"));
}

TEST(MeshFormats, BinaryPlyWithTrailingBytes) {
  std::string bin = Ply(Tetrahedron(), {"binary_little_endian"});
  const std::size_t size = bin.size();
  bin += "xyz";
  EXPECT_MESH_ERROR(ReadPly, bin, "b.ply",
                    HasSubstr(fmt::format("3 bytes follow the last element: the header's counts "
                                          "or types do not match the data (byte offset {})",
                                          size)));
}

}  // namespace
}  // namespace chasles::internal
