#pragma once
/// @file
/// Unilateral contacts with Coulomb friction (chapter 8.3, Problems 8.15-8.30): a body's shape
/// against a fixed world plane (any orientation), or a sphere on one body against a sphere on
/// another. Every shape reduces to contact *points*, one per feature:
///   - a body point (box vertex, point set, disk-face ring point): the point itself;
///   - a sphere (sphere, capsule end, sphere-sphere): the sphere's point nearest the plane
///     (or on the line of centres);
///   - a circle rim (disk rim, cylinder end rims): the rim's point nearest the plane.
/// Each point has a gap g (>= 0 apart, 0 touching), the plane's normal n (from the plane, or
/// the other sphere, towards the body) and tangents t1, t2; a mode (State::contacts) says
/// whether it is separated, sliding or sticking (for a round body: rolling without slipping).
/// See docs/contact.md for the laws, the events and the impact model.

#include <limits>
#include <string>
#include <vector>

#include "chasles/math/types.h"
#include "chasles/model/body.h"

namespace chasles {

/// The restitution hypothesis of an impact (docs/contact.md, Impacts): how the restitution
/// phase of the normal impulse P_n ends after compression (v_n = 0).
enum class RestitutionLaw {
  kEnergetic,  ///< Stronge: work of P_n in restitution = e² |work in compression| (default)
  kNewton,     ///< kinematic: v_n⁺ = -e v_n⁻
  kPoisson,    ///< kinetic: P_n = (1 + e) P_n at the end of compression
};

/// "energetic", "newton", "poisson".
const char* RestitutionLawName(RestitutionLaw law);

/// The shape of a contact; each reduces to contact points as listed.
enum class ContactShape {
  kSphere,        ///< sphere (centre, radius) on a plane: 1 point
  kDiskRim,       ///< thin disk or wheel on its rim (centre, axis, radius), may tilt: 1 point
  kDiskFace,      ///< disk lying on its face: `face_points` points on the face's edge ring
  kCylinder,      ///< cylinder (centre, axis, radius, length): its two end rims, 2 points
  kBox,           ///< box (centre, axes, half extents): its 8 vertices
  kPointSet,      ///< body points (e.g. a car's wheel contact points): 1 point each
  kCapsule,       ///< capsule (centre, axis, radius, length of the segment): 2 end spheres
  kSphereSphere,  ///< sphere on `body` against sphere on `other_body`: 1 point
};

/// Name of a shape ("sphere", "disk rim", ...).
const char* ContactShapeName(ContactShape shape);

/// Mode of one contact point.
enum class ContactMode {
  kSeparated,  ///< apart (or touching without force): no rows
  kSliding,    ///< touching and slipping: normal row, friction mu_k N against the slip
  kSticking,   ///< touching without slip (rolling without slipping for a round body)
};

/// Name of a mode ("separated", "sliding", "sticking").
const char* ContactModeName(ContactMode mode);

/// Name of a mode with its rolling sub-mode: "sticking, rolling held" for a sticking point
/// whose rolling is held by rolling resistance (ContactPointState::rolling_held), else
/// ContactModeName(mode).
const char* ContactRegimeName(ContactMode mode, bool rolling_held);

/// Everything needed to add a contact. Fields not used by the shape are ignored. Lengths are
/// given in the body's own frame B from Bo, like mass properties.
struct ContactSpec {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  /// Name used in reports and messages (points of a multi-point shape are "name_i", or their
  /// `point_labels`).
  std::string name;
  /// Which shape (decides which fields below are read).
  ContactShape shape = ContactShape::kSphere;
  /// The body that carries the shape.
  BodyIndex body = kWorld;
  /// Centre of the shape (sphere, disk, cylinder, box, capsule) from Bo, in B [m].
  Vec3 p_BoC_B = Vec3::Zero();
  /// Symmetry axis of a disk, cylinder or capsule, in B (normalised here).
  Vec3 axis_B = Vec3::UnitZ();
  /// Radius of sphere, disk, cylinder, capsule [m] (> 0).
  double radius = kNaN;
  /// Length of a cylinder, or of a capsule's segment between its sphere centres [m] (>= 0).
  double length = 0.0;
  /// Half extents of a box along its axes [m] (> 0).
  Vec3 half_extents = Vec3::Constant(kNaN);
  /// Axes of a box in B (columns; orthonormal, right-handed).
  Mat3 R_BF = Mat3::Identity();
  /// Points of a point set, from Bo in B [m].
  std::vector<Vec3> points_B;
  /// Number of ring points of a disk face (>= 3).
  int face_points = 8;
  /// Names of the points in reports and messages, one per point (optional; empty: the
  /// contact's name for a one-point shape, "name_i" otherwise; scenes give "name_<point>" for
  /// named points of a point set, the labels of docs/scene-format.md).
  std::vector<std::string> point_labels;
  /// The other body of a sphere-sphere contact (a body, not kWorld).
  BodyIndex other_body = kWorld;
  /// Centre of the other sphere from the other body's Bo, in its frame [m].
  Vec3 p_OoC_O = Vec3::Zero();
  /// Radius of the other sphere [m] (> 0).
  double other_radius = kNaN;
  /// A point of the world plane [m].
  Vec3 plane_point_W = Vec3::Zero();
  /// Normal of the world plane, pointing out of the ground towards the body (normalised here).
  Vec3 plane_normal_W = Vec3::UnitZ();
  /// Static friction coefficient (>= 0; >= mu_k).
  double mu_s = 0.0;
  /// Kinetic friction coefficient (>= 0).
  double mu_k = 0.0;
  /// Rolling-resistance coefficient: a resisting moment mu_r N R on a rolling round body
  /// (dimensionless, >= 0; 0 for none).
  double mu_r = 0.0;
  /// Coefficient of restitution e in [0, 1], read by `restitution_law`.
  double restitution = 0.0;
  /// How e ends an impact's restitution phase.
  RestitutionLaw restitution_law = RestitutionLaw::kEnergetic;
};

/// How a contact point is found on its shape.
enum class ContactFeatureKind {
  kPoint,   ///< a body point (radius 0)
  kSphere,  ///< a sphere: centre and radius
  kRim,     ///< a circle: centre, axis and radius
};

/// One candidate contact point: a feature of the shape.
struct ContactFeature {
  ContactFeatureKind kind = ContactFeatureKind::kPoint;
  /// Centre (or the point) from the body's centre of mass Bcm, in B [m].
  Vec3 p_BcmF_B = Vec3::Zero();
  /// Axis of a rim, in B (unit).
  Vec3 axis_B = Vec3::UnitZ();
  /// Radius [m] (0 for a point).
  double radius = 0.0;
};

/// A validated contact: the spec with its features, world plane frame and coefficients.
class Contact {
 public:
  /// Validates `spec` against `model` (InputError naming the contact, the value and the rule)
  /// and reduces the shape to its features.
  Contact(const class Model& model, ContactSpec spec);

  /// Name used in reports.
  const std::string& name() const { return spec_.name; }
  /// The spec as given (axes and normal normalised).
  const ContactSpec& spec() const { return spec_; }
  /// Shape.
  ContactShape shape() const { return spec_.shape; }
  /// The body carrying the shape.
  BodyIndex body() const { return spec_.body; }
  /// The other body of a sphere-sphere contact, kWorld for a plane.
  BodyIndex other_body() const { return spec_.other_body; }
  /// Number of contact points (features).
  int num_points() const { return static_cast<int>(features_.size()); }
  /// Feature `i`.
  const ContactFeature& feature(int i) const { return features_[static_cast<size_t>(i)]; }
  /// The other sphere's centre from the other body's Bcm, in its frame [m] (sphere-sphere).
  const Vec3& p_OcmC_O() const { return p_OcmC_O_; }
  /// Name of point `i`: its ContactSpec::point_labels entry if given, else the contact's name
  /// for a one-point shape and "name_i" otherwise.
  std::string point_name(int i) const;
  /// Plane normal and tangents (t1 × t2 = n), in W.
  const Vec3& n_W() const { return n_W_; }
  const Vec3& t1_W() const { return t1_W_; }
  const Vec3& t2_W() const { return t2_W_; }
  /// Coefficients.
  double mu_s() const { return spec_.mu_s; }
  double mu_k() const { return spec_.mu_k; }
  double mu_r() const { return spec_.mu_r; }
  double restitution() const { return spec_.restitution; }
  RestitutionLaw restitution_law() const { return spec_.restitution_law; }

 private:
  ContactSpec spec_;
  std::vector<ContactFeature> features_;
  Vec3 p_OcmC_O_ = Vec3::Zero();
  Vec3 n_W_, t1_W_, t2_W_;
};

/// Checks a spec without a model (coefficients and dimensions only): InputError naming the
/// contact, the value, the rule and the fix. Contact's constructor calls it.
void ValidateContactSpec(const ContactSpec& spec);

}  // namespace chasles
