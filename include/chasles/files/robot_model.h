#pragma once
/// @file
/// A robot description as its file states it (URDF, MJCF or SDF), in one form for all three:
/// links with their inertials and geometry, joints with their origins, axes and limits, and
/// where in the file each came from. Nothing is computed or corrected here (that is the audit,
/// chasles/analysis/audit.h); the readers (robot_reader.h) only parse, check and convert to SI.
///
/// Frames, after the notation table (docs/notation.md): L a link's frame, Lcm its centre of
/// mass, I the frame in which the file writes the inertia tensor (URDF's `<inertial><origin
/// rpy>`, MJCF's `quat`, SDF's `<inertial><pose>`), G a geometry's frame, P and C a joint's
/// parent and child links, J the joint frame. Products of inertia are tensor entries
/// (Ixy = -∫xy dm), as URDF, MJCF's fullinertia and SDF write them and as chasles does.

#include <array>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "chasles/math/types.h"

namespace chasles {

/// The file formats read.
enum class RobotFormat { kUrdf, kMjcf, kSdf };

/// "URDF", "MJCF" or "SDF".
const char* RobotFormatName(RobotFormat format);

/// Where a value's text stands in the file, so that a fix can rewrite it and nothing else:
/// the bytes [offset, offset + length) of an attribute's value or an element's text.
struct TextSpan {
  static constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  std::size_t offset = kNone;
  std::size_t length = 0;
  bool found() const { return offset != kNone; }
};

/// The primitive and mesh geometries of the three formats. Every primitive is in its own frame
/// G with any axis of symmetry along z (as URDF, MJCF and SDF place them).
enum class GeometryType { kBox, kCylinder, kSphere, kCapsule, kEllipsoid, kMesh };

/// "box", "cylinder", "sphere", "capsule", "ellipsoid" or "mesh".
const char* GeometryTypeName(GeometryType type);

/// Which description of a link's shape a geometry belongs to: URDF's and SDF's `<collision>`
/// and `<visual>`; MJCF's geoms are collision geometry unless contype and conaffinity are both
/// 0 (MuJoCo's visual-only geoms).
enum class GeometrySet { kCollision, kVisual };

/// "collision" or "visual".
const char* GeometrySetName(GeometrySet set);

/// One geometry of a link.
struct RobotGeometry {
  GeometrySet set = GeometrySet::kCollision;
  GeometryType type = GeometryType::kBox;
  /// Dimensions [m]: box: the full edge lengths along x, y, z; sphere: (radius, -, -);
  /// cylinder and capsule: (radius, length of the cylindrical part along z, -); ellipsoid:
  /// the semi-axes. NaN where unused.
  Vec3 size = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  /// A mesh: the URI as written, the file it resolves to (empty when it could not be
  /// resolved: `mesh_problem` says why) and the scale of each axis.
  std::string mesh_uri, mesh_path, mesh_problem;
  Vec3 mesh_scale = Vec3::Ones();
  /// G's orientation and origin in the link frame L.
  Mat3 R_LG = Mat3::Identity();
  Vec3 p_LoGo_L = Vec3::Zero();
  /// Line of the geometry's element (1-based).
  int line = 0;
};

/// The text of an inertial's numbers, for rewriting them (robot_writer.h). Which spans exist
/// depends on the format: URDF has attributes `xyz`, `rpy`, `value` and `ixx`...; MJCF has
/// `pos`, the orientation, `mass`, `diaginertia` or `fullinertia`; SDF has element texts.
struct InertialText {
  /// The centre of mass (URDF xyz, MJCF pos, SDF the pose's whole text "x y z r p y").
  TextSpan position;
  /// The orientation of I in L (URDF rpy; MJCF quat, euler, axisangle, xyaxes or zaxis;
  /// SDF: inside `position`).
  TextSpan orientation;
  /// MJCF: the name of the orientation attribute ("quat", "euler", ...); empty otherwise.
  std::string orientation_key;
  /// The mass.
  TextSpan mass;
  /// The tensor entries ixx, iyy, izz, ixy, ixz, iyz (URDF attributes, SDF elements).
  std::array<TextSpan, 6> entries;
  /// MJCF: the whole `diaginertia` or `fullinertia` value, and which (`full` true).
  TextSpan mjcf_inertia;
  bool mjcf_full = false;
  /// The whole element: its start (the '<') and the end of its start tag (after '>'); where
  /// a comment goes and where a missing child (URDF `<origin>`) is inserted.
  std::size_t element_begin = TextSpan::kNone;
  std::size_t start_tag_end = TextSpan::kNone;
};

/// A link's `<inertial>` as written, converted to SI.
struct RobotInertial {
  /// Mass [kg] as written (may be zero or negative: the audit says so).
  double mass = std::numeric_limits<double>::quiet_NaN();
  /// Centre of mass from the link origin, in L [m].
  Vec3 p_LoLcm_L = Vec3::Zero();
  /// Orientation of the inertia's frame I in L.
  Mat3 R_LI = Mat3::Identity();
  /// The tensor about the centre of mass in I, as written [kg·m²] (MJCF's diaginertia: the
  /// diagonal).
  Mat3 I_LcmI_I = Mat3::Zero();
  /// Line of the element (1-based), and of its mass and tensor elements where they differ.
  int line = 0, mass_line = 0, inertia_line = 0;
  /// Where its numbers stand, for a fix.
  InertialText text;
};

/// A link (an MJCF body, an SDF link).
struct RobotLink {
  std::string name;
  /// Line of the link's element (1-based).
  int line = 0;
  /// Whether the file gives an inertial (SDF's and MJCF's defaults are not taken as given).
  bool has_inertial = false;
  RobotInertial inertial;
  std::vector<RobotGeometry> geometries;
};

/// Joint types of the three formats; anything that is not a revolute or a prismatic joint
/// moves nothing at the configuration given (kFixed), or has no single coordinate (kFloating,
/// kPlanar, kBall).
enum class JointType { kFixed, kRevolute, kContinuous, kPrismatic, kFloating, kPlanar, kBall };

/// A joint between two links.
struct RobotJoint {
  std::string name;
  JointType type = JointType::kFixed;
  /// Indices into RobotModel::links.
  std::size_t parent = 0, child = 0;
  /// The joint frame J in the parent link P: R_PJ, p_PoJo_P [m]; and the child frame C in J at
  /// zero joint value: R_JC, p_JoCo_J [m] (identity in URDF, where C is J; an SDF joint may sit
  /// anywhere in its child). The joint's value moves C with respect to J about (or along) the
  /// axis: X_PC(q) = X_PJ · M(q) · X_JC.
  Mat3 R_PJ = Mat3::Identity();
  Vec3 p_PoJo_P = Vec3::Zero();
  Mat3 R_JC = Mat3::Identity();
  Vec3 p_JoCo_J = Vec3::Zero();
  /// The axis in J (unit), and a point of it from J's origin [m] (not J's origin for an MJCF
  /// joint placed away from its body's origin).
  Vec3 axis = Vec3::UnitX();
  Vec3 p_JoA_J = Vec3::Zero();
  /// Limits [rad or m]; NaN when not given.
  double lower = std::numeric_limits<double>::quiet_NaN();
  double upper = std::numeric_limits<double>::quiet_NaN();
  /// Line of the joint's element (1-based).
  int line = 0;
};

/// A robot description.
struct RobotModel {
  /// The file read (as given) and its format.
  std::string file;
  RobotFormat format = RobotFormat::kUrdf;
  /// The robot's (model's) name.
  std::string name;
  std::vector<RobotLink> links;
  /// A tree: every link but the root is the child of exactly one joint.
  std::vector<RobotJoint> joints;
  /// Index of the root link (the base).
  std::size_t root = 0;
  /// The file's bytes, as read (for a fix that rewrites a few numbers and keeps the rest).
  std::string text;
  /// What the reader noticed and took a decision on (an unknown geometry type read over, an
  /// MJCF body's inertia left to MuJoCo's defaults): said, never silent.
  std::vector<std::string> warnings;
};

}  // namespace chasles
