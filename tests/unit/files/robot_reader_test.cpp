// The robot readers (chasles/files/robot_reader.h) and the Collada reader: what they read from
// small files written here, and the errors, with file and line, of hostile ones.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "chasles/error.h"
#include "chasles/files/collada_reader.h"
#include "chasles/files/robot_reader.h"
#include "chasles/files/robot_writer.h"
#include "test_support.h"

namespace chasles {
namespace {

constexpr const char* kUrdf = R"(<?xml version="1.0"?>
<robot name="arm">
  <link name="base">
    <inertial>
      <origin xyz="0 0 0.1" rpy="0 0 1.5707963267948966"/>
      <mass value="2.0"/>
      <inertia ixx="0.1" ixy="0.01" ixz="0" iyy="0.2" iyz="0" izz="0.3"/>
    </inertial>
    <collision><origin xyz="0 0 0.1"/><geometry><box size="0.1 0.2 0.3"/></geometry></collision>
  </link>
  <link name="arm"/>
  <joint name="j1" type="revolute">
    <parent link="base"/><child link="arm"/>
    <origin xyz="0 0 0.5"/><axis xyz="0 1 0"/><limit lower="-1" upper="1"/>
  </joint>
</robot>
)";

std::string ErrorOf(const std::string& text, const std::string& name = "robot.urdf") {
  try {
    ReadRobotBytes(text, name);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(RobotReader, UrdfLinksInertialsGeometryJoints) {
  const RobotModel m = ReadRobotBytes(kUrdf, "robot.urdf");
  EXPECT_EQ(m.format, RobotFormat::kUrdf);
  EXPECT_EQ(m.name, "arm");
  ASSERT_EQ(m.links.size(), 2u);
  ASSERT_EQ(m.joints.size(), 1u);
  EXPECT_EQ(m.links[m.root].name, "base");
  const RobotLink& base = m.links[0];
  EXPECT_EQ(base.line, 3);
  ASSERT_TRUE(base.has_inertial);
  EXPECT_EQ(base.inertial.line, 4);
  EXPECT_EQ(base.inertial.mass, 2.0);
  EXPECT_EQ(base.inertial.p_LoLcm_L, Vec3(0, 0, 0.1));
  // rpy (0, 0, π/2): R = Rz(π/2).
  EXPECT_TRUE(test::MatNear(base.inertial.R_LI, Mat3(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ())),
                            test::kExact));
  EXPECT_EQ(base.inertial.I_LcmI_I(0, 1), 0.01);
  EXPECT_EQ(base.inertial.I_LcmI_I(2, 2), 0.3);
  // The spans point at the attribute values in the text.
  const TextSpan& izz = base.inertial.text.entries[2];
  EXPECT_EQ(m.text.substr(izz.offset, izz.length), "0.3");
  EXPECT_EQ(m.text.substr(base.inertial.text.mass.offset, base.inertial.text.mass.length), "2.0");
  ASSERT_EQ(base.geometries.size(), 1u);
  EXPECT_EQ(base.geometries[0].type, GeometryType::kBox);
  EXPECT_EQ(base.geometries[0].size, Vec3(0.1, 0.2, 0.3));
  EXPECT_EQ(m.joints[0].type, JointType::kRevolute);
  EXPECT_EQ(m.joints[0].axis, Vec3(0, 1, 0));
  EXPECT_EQ(m.joints[0].p_PoJo_P, Vec3(0, 0, 0.5));
  EXPECT_EQ(m.joints[0].lower, -1.0);
}

TEST(RobotReader, MjcfDefaultsDegreesAndHalfSizes) {
  const char* text = R"(<mujoco model="m">
  <compiler angle="degree"/>
  <default><geom type="box" size="0.1 0.2 0.3"/><default class="round"><geom type="sphere"/></default></default>
  <worldbody>
    <body name="b" pos="0 0 1" euler="0 0 90">
      <joint name="h" type="hinge" axis="0 0 1" range="-90 90"/>
      <inertial pos="0 0 0" mass="3" diaginertia="1 2 3"/>
      <geom/>
      <geom class="round" size="0.5" pos="1 0 0"/>
      <geom type="cylinder" fromto="0 0 0 0 0 2" size="0.1"/>
    </body>
  </worldbody>
</mujoco>)";
  const RobotModel m = ReadRobotBytes(text, "m.xml");
  EXPECT_EQ(m.format, RobotFormat::kMjcf);
  ASSERT_EQ(m.links.size(), 2u);  // the world and b
  const RobotLink& b = m.links[1];
  ASSERT_EQ(b.geometries.size(), 3u);
  EXPECT_EQ(b.geometries[0].type, GeometryType::kBox);
  EXPECT_EQ(b.geometries[0].size, Vec3(0.2, 0.4, 0.6));  // MuJoCo's half sizes, doubled
  EXPECT_EQ(b.geometries[1].type, GeometryType::kSphere);
  EXPECT_EQ(b.geometries[1].size[0], 0.5);
  EXPECT_EQ(b.geometries[2].type, GeometryType::kCylinder);
  EXPECT_EQ(b.geometries[2].size[1], 2.0);
  EXPECT_EQ(b.geometries[2].p_LoGo_L, Vec3(0, 0, 1));
  ASSERT_EQ(m.joints.size(), 1u);
  EXPECT_TRUE(test::Near(m.joints[0].upper, M_PI / 2, test::kExact));
  EXPECT_TRUE(test::MatNear(m.joints[0].R_PJ, Mat3(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ())),
                            test::kExact));
  EXPECT_EQ(b.inertial.I_LcmI_I.diagonal(), Vec3(1, 2, 3));
}

TEST(RobotReader, SdfPosesRelativeToFrames) {
  const char* text = R"(<sdf version="1.9"><model name="s">
  <link name="a"><pose>1 0 0 0 0 0</pose>
    <inertial><pose>0 0 0.5 0 0 0</pose><mass>2</mass>
      <inertia><ixx>1</ixx><iyy>1</iyy><izz>1</izz><ixy>0</ixy><ixz>0</ixz><iyz>0</iyz></inertia>
    </inertial></link>
  <joint name="j" type="revolute"><pose relative_to="a">0 0 1 0 0 0</pose>
    <parent>a</parent><child>b</child><axis><xyz>0 0 1</xyz></axis></joint>
  <link name="b"><pose relative_to="j">0 0 0 0 0 0</pose></link>
</model></sdf>)";
  const RobotModel m = ReadRobotBytes(text, "s.sdf");
  EXPECT_EQ(m.format, RobotFormat::kSdf);
  ASSERT_EQ(m.joints.size(), 1u);
  // j is 1 m above a; b sits at j.
  EXPECT_TRUE(test::MatNear(m.joints[0].p_PoJo_P, Vec3(0, 0, 1), test::kExact, 1.0));
  EXPECT_TRUE(test::MatNear(m.joints[0].p_JoCo_J, Vec3(0, 0, 0), test::kExact, 1.0));
  EXPECT_EQ(m.links[0].inertial.mass, 2.0);
  EXPECT_EQ(m.links[0].inertial.p_LoLcm_L, Vec3(0, 0, 0.5));
}

TEST(RobotReader, HostileFilesNameFileAndLine) {
  const std::string lol =
      "<?xml version=\"1.0\"?>\n<!DOCTYPE r [\n<!ENTITY a \"aaaa\">\n]>\n<robot name=\"&a;\"/>";
  EXPECT_EQ(ErrorOf(lol).substr(0, 15), "robot.urdf:3: a");
  EXPECT_NE(ErrorOf("<robot name=\"x\">\n<link name=\"a\">").find("robot.urdf:2: malformed XML"),
            std::string::npos)
      << ErrorOf("<robot name=\"x\">\n<link name=\"a\">");
  const std::string nan =
      "<robot name=\"x\">\n<link name=\"a\"><inertial>\n<mass value=\"nan\"/>\n"
      "<inertia ixx=\"1\" iyy=\"1\" izz=\"1\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link>\n"
      "</robot>";
  EXPECT_EQ(ErrorOf(nan), "robot.urdf:3: <mass value>: nan is not a finite number within ±1e+18");
  std::string huge = nan;
  huge.replace(huge.find("nan"), 3, "1e308");
  EXPECT_EQ(ErrorOf(huge),
            "robot.urdf:3: <mass value>: 1e308 is not a finite number within ±1e+18");
  const std::string cycle =
      "<robot name=\"x\">\n<link name=\"a\"/>\n<link name=\"b\"/>\n"
      "<joint name=\"j1\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint>\n"
      "<joint name=\"j2\" type=\"fixed\"><parent link=\"b\"/><child link=\"a\"/></joint>\n</robot>";
  EXPECT_NE(ErrorOf(cycle).find("robot.urdf:"), std::string::npos);
  EXPECT_NE(ErrorOf(cycle).find("cycle"), std::string::npos) << ErrorOf(cycle);
  const std::string escape =
      "<robot name=\"x\">\n<link name=\"a\"><visual><geometry>\n"
      "<mesh filename=\"../../../../../../etc/passwd\"/></geometry></visual></link></robot>";
  EXPECT_NE(ErrorOf(escape, "/tmp/r/urdf/robot.urdf").find("robot.urdf:3: mesh path"),
            std::string::npos)
      << ErrorOf(escape, "/tmp/r/urdf/robot.urdf");
  const std::string device =
      "<robot name=\"x\">\n<link name=\"a\"><visual><geometry>\n"
      "<mesh filename=\"file:///dev/zero\"/></geometry></visual></link></robot>";
  EXPECT_NE(ErrorOf(device).find("robot.urdf:3: mesh URI 'file:///dev/zero' cannot be read: it "
                                 "points into /dev"),
            std::string::npos)
      << ErrorOf(device);
  std::string deep = "<robot name=\"x\">";
  for (int i = 0; i < 300; ++i) deep += "<a>";
  for (int i = 0; i < 300; ++i) deep += "</a>";
  deep += "</robot>";
  EXPECT_NE(ErrorOf(deep).find("nested deeper than 200"), std::string::npos) << ErrorOf(deep);
}

// A unit cube as Collada (Y_UP, in centimetres) and as its closed form: the reader turns it to
// z up and metres.
TEST(ColladaReader, CubeInCentimetresYUp) {
  const char* dae = R"(<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
<asset><unit name="centimeter" meter="0.01"/><up_axis>Y_UP</up_axis></asset>
<library_geometries><geometry id="g"><mesh>
<source id="p"><float_array id="pa" count="24">0 0 0 1 0 0 1 1 0 0 1 0 0 0 2 1 0 2 1 1 2 0 1 2</float_array>
<technique_common><accessor source="#pa" count="8" stride="3"/></technique_common></source>
<vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
<polylist count="6"><input semantic="VERTEX" source="#v" offset="0"/><vcount>4 4 4 4 4 4</vcount>
<p>0 3 2 1 4 5 6 7 0 1 5 4 1 2 6 5 2 3 7 6 3 0 4 7</p></polylist>
</mesh></geometry></library_geometries>
<library_visual_scenes><visual_scene id="s"><node><translate>1 0 0</translate>
<instance_geometry url="#g"/></node></visual_scene></library_visual_scenes>
<scene><instance_visual_scene url="#s"/></scene></COLLADA>)";
  const TriangleSoup s = ReadColladaBytes(dae, "cube.dae");
  EXPECT_EQ(s.triangle_count(), 12u);
  // Vertex 6 (1, 1, 2) cm moved by x + 1: (2, 1, 2) cm, then y up → z up: (2, -2, 1) cm.
  EXPECT_TRUE(test::Near(s.xyz[18], 0.02, test::kExact));
  EXPECT_TRUE(test::Near(s.xyz[19], -0.02, test::kExact));
  EXPECT_TRUE(test::Near(s.xyz[20], 0.01, test::kExact));
}

TEST(ColladaReader, CountsAndIndicesChecked) {
  auto error = [](const std::string& body) {
    const std::string dae = "<COLLADA><library_geometries><geometry id=\"g\"><mesh>\n" + body +
                            "\n</mesh></geometry></library_geometries></COLLADA>";
    try {
      ReadColladaBytes(dae, "m.dae");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  const std::string src =
      "<source id=\"p\"><float_array id=\"a\" count=\"9\">0 0 0 1 0 0 0 1 0</float_array>"
      "</source><vertices id=\"v\"><input semantic=\"POSITION\" source=\"#p\"/></vertices>\n";
  EXPECT_EQ(error(src + "<triangles count=\"1\"><input semantic=\"VERTEX\" source=\"#v\" "
                        "offset=\"0\"/><p>0 1 7</p></triangles>"),
            "m.dae:3: vertex index 7 out of range: the mesh has 3 vertices");
  EXPECT_EQ(error(src + "<triangles count=\"1000000000\"><input semantic=\"VERTEX\" "
                        "source=\"#v\" offset=\"0\"/><p>0 1 2</p></triangles>"),
            "m.dae:3: <triangles count=\"1000000000\">: <p> holds only 3 indices");
  std::string big = src;
  big.replace(big.find("count=\"9\""), 9, "count=\"99999999\"");
  EXPECT_EQ(error(big), "m.dae:2: <float_array count=\"99999999\"> holds 9 numbers");
}

TEST(RobotWriter, RewritesOnlyTheNumbersAndComments) {
  const RobotModel m = ReadRobotBytes(kUrdf, "robot.urdf");
  InertialRewrite r;
  r.link = 0;
  r.mass = 2.0;
  r.p_LoLcm_L = Vec3(0, 0, 0.1);
  // The same tensor in L but for izz (in I, rpy = Rz(π/2)): I_L = R I_I Rᵀ.
  Mat3 I_I = m.links[0].inertial.I_LcmI_I;
  I_I(2, 2) = 0.25;
  r.I_LcmL_L = m.links[0].inertial.R_LI * I_I * m.links[0].inertial.R_LI.transpose();
  r.comment = "izz -- was 0.3";
  const std::string out = RewriteInertials(m, {r});
  std::string expected = kUrdf;
  expected.replace(expected.find("izz=\"0.3\""), 9, "izz=\"0.25\"");
  expected.replace(expected.find("    <inertial>"), 0,
                   "    <!-- chasles audit: izz - - was 0.3 -->\n");
  EXPECT_EQ(out, expected);
  const std::string diff = UnifiedDiff(kUrdf, out, "a", "b");
  EXPECT_NE(diff.find("-      <inertia ixx=\"0.1\" ixy=\"0.01\" ixz=\"0\" iyy=\"0.2\" iyz=\"0\" "
                      "izz=\"0.3\"/>\n+      <inertia ixx=\"0.1\" ixy=\"0.01\" ixz=\"0\" "
                      "iyy=\"0.2\" iyz=\"0\" izz=\"0.25\"/>"),
            std::string::npos)
      << diff;
  EXPECT_EQ(diff.substr(0, 30), "--- a\n+++ b\n@@ -1,10 +1,11 @@\n");
}

}  // namespace
}  // namespace chasles
