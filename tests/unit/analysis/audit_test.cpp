// The audit (chasles/analysis/audit.h): the geometry's mass properties against closed forms,
// a Collada mesh against the same mesh as STL, and the published defects of the shared robots.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "chasles/analysis/audit.h"
#include "chasles/files/collada_reader.h"
#include "chasles/files/mesh_reader.h"
#include "chasles/files/robot_reader.h"
#include "chasles/mass/mesh_mass.h"
#include "chasles/scene/robot_file.h"
#include "test_paths.h"
#include "test_support.h"

namespace chasles {
namespace {

/// Tolerance of closed forms evaluated in a few operations.
constexpr double kClosedForm = 1e-12;

const LinkAudit& Link(const RobotAudit& a, const std::string& name) {
  for (const LinkAudit& l : a.links) {
    if (l.name == name) return l;
  }
  throw std::runtime_error("no link " + name);
}

bool HasCode(const LinkAudit& l, FindingCode code) {
  for (const Finding& f : l.findings) {
    if (f.code == code) return true;
  }
  return false;
}

RobotAudit AuditText(const std::string& urdf) {
  AuditOptions o;
  o.load_mesh = LoadMeshTriangles;
  return AuditRobot(ReadRobotBytes(urdf, "primitives.urdf"), o);
}

std::string OneLink(const std::string& geometry, double mass) {
  return "<robot name=\"p\"><link name=\"l\"><inertial><mass value=\"" + std::to_string(mass) +
         "\"/><inertia ixx=\"1\" iyy=\"1\" izz=\"1\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial>"
         "<collision><geometry>" +
         geometry + "</geometry></collision></link></robot>";
}

// Appendix A: box Ixx = m(b² + c²)/12; cylinder Izz = m r²/2, Ixx = m(3r² + h²)/12; sphere
// 2/5 m r²; capsule = cylinder + two hemispheres (each (83/320) m r² about its centroid, which
// lies 3r/8 from its flat face).
TEST(Audit, PrimitivesAgainstClosedForms) {
  const double m = 2.0;
  {
    const double a = 0.1, b = 0.2, c = 0.3;
    const RobotAudit audit = AuditText(OneLink("<box size=\"0.1 0.2 0.3\"/>", m));
    const LinkAudit& l = audit.links[0];
    const Mat3 I = l.estimates[*l.computed].AtMass(m).I_BBcm_B().matrix();
    EXPECT_TRUE(test::Near(l.estimates[*l.computed].volume, a * b * c, kClosedForm));
    EXPECT_TRUE(test::Near(I(0, 0), m * (b * b + c * c) / 12, kClosedForm));
    EXPECT_TRUE(test::Near(I(1, 1), m * (a * a + c * c) / 12, kClosedForm));
    EXPECT_TRUE(test::Near(I(2, 2), m * (a * a + b * b) / 12, kClosedForm));
  }
  {
    const double r = 0.05, h = 0.4;
    const RobotAudit audit = AuditText(OneLink("<cylinder radius=\"0.05\" length=\"0.4\"/>", m));
    const LinkAudit& l = audit.links[0];
    const Mat3 I = l.estimates[*l.computed].AtMass(m).I_BBcm_B().matrix();
    EXPECT_TRUE(test::Near(l.estimates[*l.computed].volume, M_PI * r * r * h, kClosedForm));
    EXPECT_TRUE(test::Near(I(2, 2), m * r * r / 2, kClosedForm));
    EXPECT_TRUE(test::Near(I(0, 0), m * (3 * r * r + h * h) / 12, kClosedForm));
  }
  {
    const double r = 0.3;
    const RobotAudit audit = AuditText(OneLink("<sphere radius=\"0.3\"/>", m));
    const LinkAudit& l = audit.links[0];
    const Mat3 I = l.estimates[*l.computed].AtMass(m).I_BBcm_B().matrix();
    EXPECT_TRUE(test::MatNear(I, Mat3(Mat3::Identity() * 0.4 * m * r * r), kClosedForm));
  }
  {
    const double r = 0.05, L = 0.2;
    const RobotAudit audit = AuditText(OneLink("<capsule radius=\"0.05\" length=\"0.2\"/>", m));
    const LinkAudit& l = audit.links[0];
    const double Vc = M_PI * r * r * L, Vh = 2.0 / 3.0 * M_PI * r * r * r;
    const double mc = m * Vc / (Vc + 2 * Vh), mh = m * Vh / (Vc + 2 * Vh);
    const double izz = mc * r * r / 2 + 2 * 0.4 * mh * r * r;
    const double d = L / 2 + 3 * r / 8;
    const double ixx = mc * (3 * r * r + L * L) / 12 + 2 * (83.0 / 320 * mh * r * r + mh * d * d);
    const Mat3 I = l.estimates[*l.computed].AtMass(m).I_BBcm_B().matrix();
    EXPECT_TRUE(test::Near(I(2, 2), izz, kClosedForm));
    EXPECT_TRUE(test::Near(I(0, 0), ixx, kClosedForm));
    EXPECT_TRUE(test::Near(l.estimates[*l.computed].volume, Vc + 2 * Vh, kClosedForm));
  }
  {
    // MJCF's ellipsoid (size: the semi-axes): V = 4/3 π a b c, Ixx = m (b² + c²)/5.
    const double a = 0.1, b = 0.2, c = 0.3;
    AuditOptions o;
    const RobotAudit audit = AuditRobot(
        ReadRobotBytes("<mujoco><worldbody><body name=\"l\"><inertial pos=\"0 0 0\" mass=\"2\" "
                       "diaginertia=\"1 1 1\"/><geom type=\"ellipsoid\" size=\"0.1 0.2 0.3\"/>"
                       "</body></worldbody></mujoco>",
                       "ellipsoid.xml"),
        o);
    const LinkAudit& l = Link(audit, "l");
    const Mat3 I = l.estimates[*l.computed].AtMass(m).I_BBcm_B().matrix();
    EXPECT_TRUE(
        test::Near(l.estimates[*l.computed].volume, 4.0 / 3.0 * M_PI * a * b * c, kClosedForm));
    EXPECT_TRUE(test::Near(I(0, 0), m * (b * b + c * c) / 5, kClosedForm));
    EXPECT_TRUE(test::Near(I(1, 1), m * (a * a + c * c) / 5, kClosedForm));
    EXPECT_TRUE(test::Near(I(2, 2), m * (a * a + b * b) / 5, kClosedForm));
  }
}

// The same box as Collada and as binary STL: the same volume, centre of mass and inertia (the
// Collada reader's double precision against STL's single: the coordinates are exact in both).
TEST(Audit, ColladaAndStlOfOneMeshAgree) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("chasles-audit-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const double v[8][3] = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0},
                          {0, 0, 4}, {2, 0, 4}, {2, 1, 4}, {0, 1, 4}};
  const int t[12][3] = {{0, 3, 2}, {0, 2, 1}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                        {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  std::string floats, indices;
  for (auto& p : v)
    floats += std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) + " ";
  for (auto& f : t)
    indices += std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) + " ";
  std::ofstream(dir / "box.dae")
      << "<COLLADA><asset><up_axis>Z_UP</up_axis></asset><library_geometries><geometry id=\"g\">"
         "<mesh><source id=\"p\"><float_array id=\"a\" count=\"24\">"
      << floats
      << "</float_array></source><vertices id=\"v\"><input semantic=\"POSITION\" source=\"#p\"/>"
         "</vertices><triangles count=\"12\"><input semantic=\"VERTEX\" source=\"#v\" "
         "offset=\"0\"/><p>"
      << indices << "</p></triangles></mesh></geometry></library_geometries></COLLADA>";
  {
    std::ofstream stl(dir / "box.stl", std::ios::binary);
    const char header[80] = {};
    stl.write(header, 80);
    const std::uint32_t n = 12;
    stl.write(reinterpret_cast<const char*>(&n), 4);
    for (auto& f : t) {
      const float zero[3] = {0, 0, 0};
      stl.write(reinterpret_cast<const char*>(zero), 12);
      for (int k = 0; k < 3; ++k) {
        const float p[3] = {static_cast<float>(v[f[k]][0]), static_cast<float>(v[f[k]][1]),
                            static_cast<float>(v[f[k]][2])};
        stl.write(reinterpret_cast<const char*>(p), 12);
      }
      const std::uint16_t attr = 0;
      stl.write(reinterpret_cast<const char*>(&attr), 2);
    }
  }
  MeshMassOptions o;
  o.density = 1000.0;
  TriangleSoup dae = ReadColladaFile((dir / "box.dae").string());
  MeshFileData stl = ReadMeshFile((dir / "box.stl").string());
  const MassProperties a =
      ComputeMeshMassProperties(std::move(dae.xyz), std::move(dae.indices), o, "dae")
          .mass_properties;
  const MassProperties b =
      ComputeMeshMassProperties(std::move(stl.xyz), std::move(stl.indices), o, "stl")
          .mass_properties;
  // A 2 x 1 x 4 box: m = 8000 kg, Ixx = m (1 + 16)/12.
  EXPECT_TRUE(test::Near(a.mass(), 8000.0, kClosedForm));
  EXPECT_TRUE(test::Near(b.mass(), 8000.0, kClosedForm));
  EXPECT_TRUE(test::MatNear(a.p_BoBcm_B(), Vec3(1, 0.5, 2), kClosedForm));
  EXPECT_TRUE(test::MatNear(a.I_BBcm_B().matrix(), b.I_BBcm_B().matrix(), kClosedForm));
  EXPECT_TRUE(test::Near(a.I_BBcm_B().Ixx(), 8000.0 * 17 / 12, kClosedForm));
  // And as the audit reads them, each the visual mesh of a link of 8 kg (density 1000 kg/m³):
  // the same method, volume, centre of mass and tensor.
  AuditOptions options;
  options.load_mesh = LoadMeshTriangles;
  std::vector<GeometryEstimate> estimates;
  for (const char* mesh : {"box.dae", "box.stl"}) {
    const std::string urdf = std::string("<robot name=\"r\"><link name=\"l\"><inertial>") +
                             "<mass value=\"8\"/><inertia ixx=\"11.3\" iyy=\"13.3\" izz=\"3.3\" "
                             "ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial><visual><geometry><mesh "
                             "filename=\"" +
                             mesh + "\"/></geometry></visual></link></robot>";
    const RobotAudit audit = AuditRobot(ReadRobotBytes(urdf, (dir / "r.urdf").string()), options);
    ASSERT_TRUE(audit.links[0].computed.has_value()) << mesh;
    estimates.push_back(audit.links[0].estimates[*audit.links[0].computed]);
  }
  EXPECT_EQ(estimates[0].method, GeometryMethod::kExactMesh);
  EXPECT_EQ(estimates[1].method, GeometryMethod::kExactMesh);
  EXPECT_TRUE(test::Near(estimates[0].volume, 8.0, kClosedForm));
  EXPECT_TRUE(test::Near(estimates[1].volume, 8.0, kClosedForm));
  const MassProperties da = estimates[0].AtMass(8.0), db = estimates[1].AtMass(8.0);
  EXPECT_TRUE(test::MatNear(da.p_BoBcm_B(), db.p_BoBcm_B(), kClosedForm));
  EXPECT_TRUE(test::MatNear(da.I_BBcm_B().matrix(), db.I_BBcm_B().matrix(), kClosedForm));
  EXPECT_TRUE(test::Near(da.I_BBcm_B().Iyy(), 8.0 * (4 + 16) / 12, kClosedForm));
  std::filesystem::remove_all(dir);
}

/// The shared robots (../shared/robots beside the repository), or "" with a message.
std::string SharedRobots() {
  const std::filesystem::path p =
      std::filesystem::path(chasles::test::SourceDir()) / ".." / "shared" / "robots";
  return std::filesystem::is_directory(p) ? p.string() : "";
}

TEST(Audit, PublishedDefectsOfTheSharedRobots) {
  const std::string root = SharedRobots();
  if (root.empty())
    GTEST_SKIP() << "../shared/robots is absent: the published defects are not checked";
  AuditOptions o;
  o.load_mesh = LoadMeshTriangles;
  const RobotAudit abb = AuditRobot(
      ReadRobotFile(root +
                    "/compas_fab/robot_library/abb_irb4600_40_255/urdf/robot_description.urdf"),
      o);
  EXPECT_TRUE(HasCode(Link(abb, "base_link"), FindingCode::kNotPositiveDefinite));
  EXPECT_TRUE(HasCode(Link(abb, "link_2"), FindingCode::kNotPositiveDefinite));
  EXPECT_TRUE(HasCode(Link(abb, "link_3"), FindingCode::kTriangleInequality));
  EXPECT_TRUE(HasCode(Link(abb, "base_link"), FindingCode::kDuplicateInertial));
  EXPECT_TRUE(HasCode(Link(abb, "link_1"), FindingCode::kDuplicateInertial));
  const RobotAudit ur5 = AuditRobot(
      ReadRobotFile(root + "/example-robot-data/robots/ur_description/urdf/ur5_robot.urdf"), o);
  for (const char* wrist : {"wrist_1_link", "wrist_2_link"}) {
    const LinkAudit& l = Link(ur5, wrist);
    EXPECT_TRUE(HasCode(l, FindingCode::kRadiusOfGyration)) << wrist;
    EXPECT_EQ(l.findings.front().severity, Severity::kError);
    // √(tr I / 2m) of the published tensor: √((0.1112 + 0.1112 + 0.2194) / (2 · 1.219)).
    EXPECT_NE(l.findings[1].message.find("0.4257 m"), std::string::npos) << l.findings[1].message;
  }
  EXPECT_TRUE(Link(ur5, "upper_arm_link").findings.empty());  // its visual mesh agrees
}

}  // namespace
}  // namespace chasles
