#include "chasles/files/mesh_reader.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <system_error>
#include <vector>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/error.h"
#include "chasles/files/mapped_file.h"
#include "chasles/mass/mesh_mass.h"
#include "chasles/scene/mesh_file.h"
#include "test_support.h"

namespace chasles {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

// Box a x b x c at the origin: 8 corners and 6 outward counter-clockwise quads.
constexpr double kA = 0.5, kB = 1.25, kC = 2.0;  // exactly representable in float
Vec3 Corner(int i) {
  return Vec3((i & 1) ? kA : 0, (i & 2) ? kB : 0, (i & 4) ? kC : 0);
}
constexpr int kQuads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                              {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
std::vector<std::array<int, 3>> BoxTriangles() {
  std::vector<std::array<int, 3>> t;
  for (const auto& q : kQuads) {
    t.push_back({q[0], q[1], q[2]});
    t.push_back({q[0], q[2], q[3]});
  }
  return t;
}

class MeshReaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           fmt::format("chasles_mesh_reader_{}_{}", ::getpid(),
                       ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }

  std::string WriteBinaryStl(const std::string& name, const char* header_text = "chasles test") {
    const std::string p = Path(name);
    std::ofstream f(p, std::ios::binary);
    char header[80] = {};
    std::strncpy(header, header_text, 79);
    f.write(header, 80);
    const auto tris = BoxTriangles();
    const auto n = std::uint32_t(tris.size());
    f.write(reinterpret_cast<const char*>(&n), 4);
    for (const auto& t : tris) {
      const float normal[3] = {0, 0, 0};
      f.write(reinterpret_cast<const char*>(normal), 12);
      for (int k : t) {
        const Vec3 v = Corner(k);
        const float xyz[3] = {float(v.x()), float(v.y()), float(v.z())};
        f.write(reinterpret_cast<const char*>(xyz), 12);
      }
      const std::uint16_t attr = 0;
      f.write(reinterpret_cast<const char*>(&attr), 2);
    }
    return p;
  }
  std::string WriteText(const std::string& name, const std::string& text) {
    const std::string p = Path(name);
    std::ofstream(p) << text;
    return p;
  }
  std::string AsciiStl() const {
    std::string s = "solid box\n";
    for (const auto& t : BoxTriangles()) {
      s += "  facet normal 0 0 0\n    outer loop\n";
      for (int k : t) {
        const Vec3 v = Corner(k);
        s += fmt::format("      vertex {} {} {}\n", v.x(), v.y(), v.z());
      }
      s += "    endloop\n  endfacet\n";
    }
    return s + "endsolid box\n";
  }
  std::string Obj() const {  // quads, 1-based indices: the reader triangulates
    std::string s = "# box\n";
    for (int i = 0; i < 8; ++i) {
      s += fmt::format("v {} {} {}\n", Corner(i).x(), Corner(i).y(), Corner(i).z());
    }
    for (const auto& q : kQuads) {
      s += fmt::format("f {} {} {} {}\n", q[0] + 1, q[1] + 1, q[2] + 1, q[3] + 1);
    }
    return s;
  }
  std::string Ply() const {
    std::string s =
        "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
        "property float z\nelement face 6\nproperty list uchar int vertex_indices\nend_header\n";
    for (int i = 0; i < 8; ++i) {
      s += fmt::format("{} {} {}\n", Corner(i).x(), Corner(i).y(), Corner(i).z());
    }
    for (const auto& q : kQuads) s += fmt::format("4 {} {} {} {}\n", q[0], q[1], q[2], q[3]);
    return s;
  }

  // The box's mass properties through the whole path: exact for any of the formats.
  static void ExpectBoxMass(const std::string& path) {
    MeshMassOptions o;
    o.density = 1000;
    const MeshMassResult r = LoadMeshMassProperties(path, o);
    const double m = 1000 * kA * kB * kC;
    EXPECT_TRUE(test::Near(r.mass_properties.mass(), m, 1e-14)) << path;
    // Appendix A, rectangular prism.
    const Mat3 I = Vec3(m * (kB * kB + kC * kC) / 12, m * (kA * kA + kC * kC) / 12,
                        m * (kA * kA + kB * kB) / 12)
                       .asDiagonal();
    EXPECT_TRUE(test::MatNear(r.mass_properties.I_BBcm_B().matrix(), I, 1e-13)) << path;
    EXPECT_EQ(r.report.repair.vertices_out, 8u);
    EXPECT_TRUE(r.report.repair.warnings.empty());
  }

  fs::path dir_;
};

TEST_F(MeshReaderTest, BinaryStl) {
  const std::string p = WriteBinaryStl("box.stl");
  const MeshFileData d = ReadMeshFile(p);
  EXPECT_EQ(d.format, "binary STL");
  EXPECT_EQ(d.triangle_count(), 12u);
  EXPECT_EQ(d.vertex_count(), 36u);  // STL shares no vertex
  EXPECT_EQ(d.xyz[3 * 5 + 2], float(Corner(BoxTriangles()[1][2]).z()));
  ExpectBoxMass(p);
}

TEST_F(MeshReaderTest, BinaryStlWhoseHeaderSaysSolid) {
  // Many exporters start the binary header with "solid"; the size decides the format.
  const std::string p = WriteBinaryStl("box.STL", "solid exported by a CAD tool");
  EXPECT_EQ(ReadMeshFile(p).format, "binary STL");
  ExpectBoxMass(p);
}

TEST_F(MeshReaderTest, AsciiStl) {
  const std::string p = WriteText("box.stl", AsciiStl());
  const MeshFileData d = ReadMeshFile(p);
  EXPECT_EQ(d.format, "ASCII STL");
  EXPECT_EQ(d.triangle_count(), 12u);
  ExpectBoxMass(p);
}

TEST_F(MeshReaderTest, ObjWithQuads) {
  const std::string p = WriteText("box.obj", Obj());
  const MeshFileData d = ReadMeshFile(p);
  EXPECT_EQ(d.format, "OBJ");
  EXPECT_EQ(d.triangle_count(), 12u);
  ExpectBoxMass(p);
}

TEST_F(MeshReaderTest, AsciiPly) {
  const std::string p = WriteText("box.ply", Ply());
  const MeshFileData d = ReadMeshFile(p);
  EXPECT_EQ(d.format, "PLY");
  EXPECT_EQ(d.triangle_count(), 12u);
  ExpectBoxMass(p);
}

TEST_F(MeshReaderTest, MissingFile) {
  const std::string p = Path("nowhere.stl");
  EXPECT_THAT([&] { ReadMeshFile(p); }, ::testing::ThrowsMessage<InputError>(::testing::AllOf(
                                            HasSubstr(p), HasSubstr("not found"))));
}

TEST_F(MeshReaderTest, TruncatedBinaryStlIsASizeMismatch) {
  const std::string p = WriteBinaryStl("cut.stl");
  fs::resize_file(p, fs::file_size(p) - 20);
  EXPECT_THAT([&] { ReadMeshFile(p); },
              ::testing::ThrowsMessage<InputError>(::testing::AllOf(
                  HasSubstr(p), HasSubstr("size mismatch"), HasSubstr("announces 12 triangles"),
                  HasSubstr("84 + 50 x 12 = 684 bytes, but the file has 664 bytes"))));
}

TEST_F(MeshReaderTest, EmptyBinaryStl) {
  const std::string p = Path("empty.stl");
  {
    std::ofstream f(p, std::ios::binary);
    const char header[84] = {};  // zero triangles
    f.write(header, 84);
  }
  EXPECT_THAT([&] { ReadMeshFile(p); }, ::testing::ThrowsMessage<InputError>(::testing::AllOf(
                                            HasSubstr(p), HasSubstr("empty mesh"))));
}

TEST_F(MeshReaderTest, ObjWithoutFacesIsEmpty) {
  const std::string p = WriteText("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  EXPECT_THAT([&] { ReadMeshFile(p); }, ::testing::ThrowsMessage<InputError>(::testing::AllOf(
                                            HasSubstr(p), HasSubstr("empty mesh"))));
}

TEST_F(MeshReaderTest, GarbledPlyIsNotAPly) {
  const std::string p = WriteText("junk.ply", "this is not a mesh at all\n\x01\x02\x03");
  EXPECT_THAT([&] { ReadMeshFile(p); }, ::testing::ThrowsMessage<InputError>(::testing::HasSubstr(
                                            "mesh file '" + p +
                                            "': PLY header: not a PLY file (the first line is not "
                                            "'ply') (line 1)")));
}

TEST_F(MeshReaderTest, Off) {
  std::string s = "OFF\n8 6 0\n";
  for (int i = 0; i < 8; ++i) {
    s += fmt::format("{} {} {}\n", Corner(i).x(), Corner(i).y(), Corner(i).z());
  }
  for (const auto& q : kQuads) s += fmt::format("4 {} {} {} {}\n", q[0], q[1], q[2], q[3]);
  const std::string p = WriteText("box.off", s);
  EXPECT_EQ(ReadMeshFile(p).format, "OFF");
  ExpectBoxMass(p);
}

TEST_F(MeshReaderTest, UnknownExtensionListsTheSupportedFormats) {
  const std::string p = WriteText("box.dae", Obj());
  EXPECT_THAT([&] { ReadMeshFile(p); },
              ::testing::ThrowsMessage<InputError>(
                  ::testing::HasSubstr("mesh file '" + p +
                                       "': unsupported format '.dae'; supported: .stl (binary or "
                                       "ASCII), .obj, .ply (ASCII or binary), .off")));
}

TEST_F(MeshReaderTest, TruncatedAsciiStlNamesTheLine) {
  std::string stl = AsciiStl();
  stl.resize(stl.find("endloop", stl.size() / 2));  // half-way, inside a facet
  const std::string p = WriteText("cut.stl", stl);
  EXPECT_THAT([&] { ReadMeshFile(p); },
              ::testing::ThrowsMessage<InputError>(::testing::AllOf(
                  HasSubstr("mesh file '" + p + "': truncated ASCII STL: the file ends in facet"),
                  HasSubstr("where 'endloop' was expected (line "))));
}

TEST_F(MeshReaderTest, GarbledBinaryIsUnreadable) {
  std::string junk(1000, '\0');
  for (std::size_t i = 0; i < junk.size(); ++i) junk[i] = char((i * 7919) % 251);
  const std::string p = WriteText("junk.stl", junk);
  EXPECT_THAT([&] { ReadMeshFile(p); }, ::testing::ThrowsMessage<InputError>(::testing::AllOf(
                                            HasSubstr(p), HasSubstr("size mismatch"))));
}

TEST_F(MeshReaderTest, ScaleAppliesToFileUnits) {
  // The same box read as millimetres: lengths x 1e-3, mass for a given density x 1e-9.
  const std::string p = WriteBinaryStl("box_mm.stl");
  MeshMassOptions o;
  o.density = 1000;
  o.scale = 1e-3;
  const MeshMassResult r = LoadMeshMassProperties(p, o);
  EXPECT_TRUE(test::Near(r.mass_properties.mass(), 1000 * kA * kB * kC * 1e-9, 1e-14));
  EXPECT_TRUE(test::MatNear(r.mass_properties.p_BoBcm_B(), Vec3(kA, kB, kC) * 0.5e-3, 1e-14));
  EXPECT_EQ(r.report.format, "binary STL");
  EXPECT_EQ(r.report.path, p);
  EXPECT_GE(r.report.read_seconds, 0.0);
}

TEST_F(MeshReaderTest, OpenMeshFileErrorNamesTheFile) {
  std::string obj = Obj();
  obj = obj.substr(0, obj.rfind("f "));  // drop the last face
  const std::string p = WriteText("open.obj", obj);
  MeshMassOptions o;
  o.density = 1000;
  EXPECT_THAT([&] { LoadMeshMassProperties(p, o); },
              ::testing::ThrowsMessage<InputError>(::testing::AllOf(
                  HasSubstr(p), HasSubstr("4 boundary edge(s)"), HasSubstr("use mode: shell"))));
}

// A torus of 2 x 40 x 24 float triangles about an off-centre point, written as a binary STL
// record by record, with a few corners nudged by one float step (within the weld tolerance the
// test sets, so welding merges them) and one triangle reversed (so validation repairs it).
std::string TorusStlBytes() {
  constexpr int kMajor = 40, kMinor = 24;
  const double pi = std::acos(-1.0);
  auto corner = [&](int i, int j) {
    const double th = 2 * pi * (i % kMajor) / kMajor, ph = 2 * pi * (j % kMinor) / kMinor;
    return std::array<float, 3>{float(3.7 + (0.1 + 0.03 * std::cos(ph)) * std::cos(th)),
                                float(-1.3 + (0.1 + 0.03 * std::cos(ph)) * std::sin(th)),
                                float(0.2 + 0.03 * std::sin(ph))};
  };
  std::string out(80, ' ');
  const std::uint32_t n = 2 * kMajor * kMinor;
  out.append(reinterpret_cast<const char*>(&n), 4);
  std::uint32_t t = 0;
  for (int i = 0; i < kMajor; ++i) {
    for (int j = 0; j < kMinor; ++j) {
      const int tri[2][3][2] = {{{i, j}, {i + 1, j}, {i + 1, j + 1}},
                                {{i, j}, {i + 1, j + 1}, {i, j + 1}}};
      for (const auto& c : tri) {
        out.append(12, '\0');  // normal
        for (int k = 0; k < 3; ++k) {
          const int kk = t == 7 ? 2 - k : k;  // triangle 7 reversed
          std::array<float, 3> v = corner(c[kk][0], c[kk][1]);
          if (t % 97 == 5) v[0] = std::nextafter(v[0], 10.0f);  // a near, not equal, copy
          out.append(reinterpret_cast<const char*>(v.data()), 12);
        }
        out.append(2, '\0');  // attribute word
        ++t;
      }
    }
  }
  return out;
}

TEST_F(MeshReaderTest, BinaryStlMassFromItsFloatsIsBitwiseThatOfTheWidenedDoubles) {
  // LoadMeshMassProperties keeps a binary STL's floats and welds them as a triangle soup; the
  // general path reads them widened to double with indices 0, 1, 2, ... Widening is exact,
  // so the two must agree bit for bit, repairs included.
  const std::string p = WriteText("torus.stl", TorusStlBytes());
  const std::optional<std::vector<float>> floats = TryReadBinaryStlFloats(p);
  ASSERT_TRUE(floats.has_value());
  MeshFileData d = ReadMeshFile(p);
  ASSERT_EQ(floats->size(), d.xyz.size());
  for (std::size_t i = 0; i < d.xyz.size(); ++i) ASSERT_EQ(double((*floats)[i]), d.xyz[i]);
  MeshMassOptions o;
  o.density = 7850;
  o.scale = 1e-3;
  o.weld_tolerance = 1e-8;  // 1e-5 file units: a float step at 3.8 is 4.8e-7
  const MeshMassResult soup = LoadMeshMassProperties(p, o);
  MeshMassReport as_read;  // what LoadMeshMassProperties fills in from the reader
  as_read.format = d.format;
  as_read.single_precision = d.single_precision;
  const MeshMassResult general = ComputeMeshMassProperties(std::move(d.xyz), std::move(d.indices),
                                                           o, "torus", std::move(as_read));
  EXPECT_EQ(soup.mass_properties.mass(), general.mass_properties.mass());
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(soup.mass_properties.p_BoBcm_B()[k], general.mass_properties.p_BoBcm_B()[k]);
    for (int l = 0; l < 3; ++l) {
      EXPECT_EQ(soup.mass_properties.I_BBcm_B().matrix()(k, l),
                general.mass_properties.I_BBcm_B().matrix()(k, l));
    }
  }
  EXPECT_EQ(soup.report.volume, general.report.volume);
  EXPECT_EQ(soup.report.surface_area, general.report.surface_area);
  EXPECT_EQ(soup.report.float32_spacing, general.report.float32_spacing);
  EXPECT_TRUE(soup.report.single_precision);
  EXPECT_EQ(soup.report.format, "binary STL");
  EXPECT_EQ(soup.report.repair.triangles_in, 2u * 40 * 24);
  EXPECT_EQ(soup.report.repair.vertices_in, general.report.repair.vertices_in);
  EXPECT_EQ(soup.report.repair.vertices_out, 40u * 24);  // the nudged copies welded
  EXPECT_EQ(soup.report.repair.vertices_out, general.report.repair.vertices_out);
  EXPECT_EQ(soup.report.repair.triangles_flipped, 1u);
  EXPECT_EQ(soup.report.repair.triangles_flipped, general.report.repair.triangles_flipped);
  EXPECT_EQ(soup.report.repair.weld_tolerance, general.report.repair.weld_tolerance);
  EXPECT_EQ(soup.report.repair.warnings, general.report.repair.warnings);
}

TEST_F(MeshReaderTest, OnlyConsistentBinaryStlIsReadAsFloats) {
  EXPECT_FALSE(TryReadBinaryStlFloats(WriteText("box.stl", AsciiStl())).has_value());
  EXPECT_FALSE(TryReadBinaryStlFloats(WriteText("box.obj", Obj())).has_value());
  EXPECT_FALSE(TryReadBinaryStlFloats(Path("missing.stl")).has_value());
  std::string cut = TorusStlBytes();
  cut.resize(cut.size() - 1);
  EXPECT_FALSE(TryReadBinaryStlFloats(WriteText("cut.stl", cut)).has_value());
  // A non-finite coordinate is refused on either path, with the same message.
  std::string nan = TorusStlBytes();
  const float q = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(nan.data() + 84 + 50 * 3 + 12 + 4, &q, 4);  // triangle 4, vertex 0, y
  const std::string p = WriteText("nan.stl", nan);
  MeshMassOptions o;
  o.density = 1000;
  const std::string message =
      "mesh file '" + p +
      "': triangle 4 has a non-finite vertex coordinate (nan) (byte offset 250)";
  // LoadMeshMassProperties reads it in place (TryMapBinaryStl), the others copy it.
  EXPECT_THAT([&] { LoadMeshMassProperties(p, o); },
              ::testing::ThrowsMessage<InputError>(::testing::StrEq(message)));
  EXPECT_THAT([&] { TryReadBinaryStlFloats(p); },
              ::testing::ThrowsMessage<InputError>(::testing::StrEq(message)));
  EXPECT_THAT([&] { ReadMeshFile(p); },
              ::testing::ThrowsMessage<InputError>(::testing::StrEq(message)));
}

TEST_F(MeshReaderTest, BinaryStlReadInPlaceHoldsTheFloatsOfTheFile) {
  const std::string p = WriteText("torus.stl", TorusStlBytes());
  const std::optional<std::vector<float>> floats = TryReadBinaryStlFloats(p);
  std::optional<MappedBinaryStl> stl = TryMapBinaryStl(p);
  ASSERT_TRUE(floats.has_value());
  ASSERT_TRUE(stl.has_value());
  ASSERT_EQ(std::size_t{stl->triangles} * 9, floats->size());
  for (std::size_t t = 0; t < stl->triangles; ++t) {
    float f[9];
    std::memcpy(f, stl->coordinates + t * MappedBinaryStl::kRecordBytes, sizeof f);
    for (int k = 0; k < 9; ++k) ASSERT_EQ(f[k], (*floats)[9 * t + k]);
    stl->ThrowIfNonFinite(t);  // returns: all finite
  }
  EXPECT_TRUE(stl->file.mapped());  // a regular file on a POSIX system
  // The same files are refused as by TryReadBinaryStlFloats, the same way.
  EXPECT_FALSE(TryMapBinaryStl(WriteText("box.stl", AsciiStl())).has_value());
  EXPECT_FALSE(TryMapBinaryStl(WriteText("box.obj", Obj())).has_value());
  EXPECT_FALSE(TryMapBinaryStl(Path("missing.stl")).has_value());
  EXPECT_FALSE(TryMapBinaryStl(Path("")).has_value());
  std::string cut = TorusStlBytes();
  cut.resize(cut.size() - 1);
  EXPECT_FALSE(TryMapBinaryStl(WriteText("cut.stl", cut)).has_value());
  const std::string empty = WriteText("empty.stl", std::string(80, ' ') + std::string(4, '\0'));
  EXPECT_THAT([&] { TryMapBinaryStl(empty); },
              ::testing::ThrowsMessage<InputError>(::testing::StrEq(
                  "mesh file '" + empty + "': empty mesh (the binary STL holds 0 triangles)")));
  EXPECT_THAT([&] { ReadMeshFile(empty); },
              ::testing::ThrowsMessage<InputError>(::testing::StrEq(
                  "mesh file '" + empty + "': empty mesh (the binary STL holds 0 triangles)")));
}

TEST_F(MeshReaderTest, MappedFileMapsRegularFilesAndReadsTheRest) {
  const std::string p = WriteText("bytes.bin", "0123456789");
  MappedFile f(p);
  EXPECT_TRUE(f.regular());
  EXPECT_EQ(f.size(), 10u);
  char head[4] = {};
  EXPECT_EQ(f.ReadAt(8, head, 4), 2u);  // fewer at the end
  EXPECT_EQ(std::string(head, 2), "89");
  const std::span<const unsigned char> bytes = f.Bytes();
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(bytes.data()), bytes.size()), "0123456789");
  EXPECT_TRUE(f.mapped());
  EXPECT_EQ(f.Bytes().data(), bytes.data());  // the same bytes again
  MappedFile moved = std::move(f);
  EXPECT_EQ(moved.Bytes().data(), bytes.data());
  // Not a regular file: read to its end, not mapped.
  MappedFile null("/dev/null");
  EXPECT_FALSE(null.regular());
  EXPECT_TRUE(null.Bytes().empty());
  EXPECT_FALSE(null.mapped());
  // An empty regular file.
  MappedFile none(WriteText("none.bin", ""));
  EXPECT_TRUE(none.Bytes().empty());
  EXPECT_THROW(MappedFile(Path("missing.bin")), std::system_error);
}

TEST(PrefaultForWrite, LeavesTheContentsAsTheyWere) {
  std::vector<std::uint32_t> v(1 << 20);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = static_cast<std::uint32_t>(i * 2654435761u);
  v.reserve(v.size() * 3);
  PrefaultForWrite(v.data(), v.capacity() * sizeof(std::uint32_t));
  PrefaultForWrite(v.data() + 1, 100);  // too small to bother: nothing
  PrefaultForWrite(nullptr, 1 << 20);
  for (std::size_t i = 0; i < v.size(); ++i) {
    ASSERT_EQ(v[i], static_cast<std::uint32_t>(i * 2654435761u));
  }
}

}  // namespace
}  // namespace chasles
