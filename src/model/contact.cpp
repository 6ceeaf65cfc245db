#include "chasles/model/contact.h"

#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/model/constraints.h"
#include "chasles/model/model.h"

namespace chasles {
namespace {

void RequireLength(const ContactSpec& s, const char* what, double value, bool allow_zero) {
  const bool ok = std::isfinite(value) && (allow_zero ? value >= 0.0 : value > 0.0);
  if (!ok) {
    throw InputError(fmt::format("contact '{}' ({}): {} is {:.6g} m; it must be a {} length",
                                 s.name, ContactShapeName(s.shape), what, value,
                                 allow_zero ? "non-negative" : "positive"));
  }
}

void RequireDirection(const ContactSpec& s, const char* what, const Vec3& v) {
  if (!v.allFinite() || !(v.norm() > 0.0)) {
    throw InputError(
        fmt::format("contact '{}' ({}): the {} is zero or not finite; give a non-zero direction",
                    s.name, ContactShapeName(s.shape), what));
  }
}

}  // namespace

const char* ContactShapeName(ContactShape shape) {
  switch (shape) {
    case ContactShape::kSphere:
      return "sphere";
    case ContactShape::kDiskRim:
      return "disk rim";
    case ContactShape::kDiskFace:
      return "disk face";
    case ContactShape::kCylinder:
      return "cylinder";
    case ContactShape::kBox:
      return "box";
    case ContactShape::kPointSet:
      return "point set";
    case ContactShape::kCapsule:
      return "capsule";
    case ContactShape::kSphereSphere:
      return "sphere-sphere";
  }
  return "contact";
}

const char* ContactModeName(ContactMode mode) {
  switch (mode) {
    case ContactMode::kSeparated:
      return "separated";
    case ContactMode::kSliding:
      return "sliding";
    case ContactMode::kSticking:
      return "sticking";
  }
  return "unknown";
}

const char* ContactRegimeName(ContactMode mode, bool rolling_held) {
  return mode == ContactMode::kSticking && rolling_held ? "sticking, rolling held"
                                                        : ContactModeName(mode);
}

const char* RestitutionLawName(RestitutionLaw law) {
  switch (law) {
    case RestitutionLaw::kNewton:
      return "newton";
    case RestitutionLaw::kPoisson:
      return "poisson";
    case RestitutionLaw::kEnergetic:
      break;
  }
  return "energetic";
}

void ValidateContactSpec(const ContactSpec& s) {
  if (s.name.empty()) throw InputError("a contact needs a non-empty name");
  const char* shape = ContactShapeName(s.shape);
  // Coulomb friction: the coefficients are ratios of forces, never negative; the kinetic one
  // cannot exceed the static one (else a point that just stopped slipping could hold a load
  // it could not hold while slipping, and stick-slip would chatter).
  const struct {
    const char* name;
    double value;
  } coefficients[] = {{"mu_s (static friction)", s.mu_s},
                      {"mu_k (kinetic friction)", s.mu_k},
                      {"mu_r (rolling resistance)", s.mu_r}};
  for (const auto& c : coefficients) {
    if (!std::isfinite(c.value) || c.value < 0.0) {
      throw InputError(fmt::format(
          "contact '{}' ({}): {} is {:.6g}; a friction coefficient must be >= 0 (0 for none)",
          s.name, shape, c.name, c.value));
    }
  }
  if (s.mu_k > s.mu_s) {
    throw InputError(fmt::format(
        "contact '{}' ({}): kinetic friction mu_k = {:.6g} exceeds static friction mu_s = {:.6g}; "
        "Coulomb friction needs mu_k <= mu_s (give mu_s = mu_k when only one is known)",
        s.name, shape, s.mu_k, s.mu_s));
  }
  if (!std::isfinite(s.restitution) || s.restitution < 0.0 || s.restitution > 1.0) {
    throw InputError(fmt::format(
        "contact '{}' ({}): coefficient of restitution e = {:.6g} is outside [0, 1]; 0 is a "
        "plastic impact, 1 an elastic one (e > 1 would create energy)",
        s.name, shape, s.restitution));
  }
  if (!s.p_BoC_B.allFinite()) {
    throw InputError(
        fmt::format("contact '{}' ({}): the shape's centre is not finite", s.name, shape));
  }
  if (!s.plane_point_W.allFinite()) {
    throw InputError(
        fmt::format("contact '{}' ({}): the plane's point is not finite", s.name, shape));
  }
  if (s.shape != ContactShape::kSphereSphere) RequireDirection(s, "plane normal", s.plane_normal_W);
  switch (s.shape) {
    case ContactShape::kSphere:
      RequireLength(s, "radius", s.radius, false);
      break;
    case ContactShape::kDiskRim:
      RequireLength(s, "radius", s.radius, false);
      RequireDirection(s, "axis", s.axis_B);
      break;
    case ContactShape::kDiskFace:
      RequireLength(s, "radius", s.radius, false);
      RequireDirection(s, "axis", s.axis_B);
      if (s.face_points < 3) {
        throw InputError(fmt::format(
            "contact '{}' (disk face): face_points is {}; the face ring needs at least 3 points",
            s.name, s.face_points));
      }
      break;
    case ContactShape::kCylinder:
    case ContactShape::kCapsule:
      RequireLength(s, "radius", s.radius, false);
      RequireLength(s, "length", s.length, s.shape == ContactShape::kCapsule);
      RequireDirection(s, "axis", s.axis_B);
      break;
    case ContactShape::kBox: {
      for (int i = 0; i < 3; ++i) RequireLength(s, "half extent", s.half_extents[i], false);
      const double orth = (s.R_BF.transpose() * s.R_BF - Mat3::Identity()).cwiseAbs().maxCoeff();
      if (!s.R_BF.allFinite() || orth > 1e-9 || s.R_BF.determinant() < 0.0) {
        throw InputError(fmt::format(
            "contact '{}' (box): the box axes are not a right-handed orthonormal set; use "
            "FrameWithZAxis or the identity",
            s.name));
      }
      break;
    }
    case ContactShape::kPointSet:
      if (s.points_B.empty()) {
        throw InputError(fmt::format(
            "contact '{}' (point set): no points given; list the body points that may touch",
            s.name));
      }
      for (const Vec3& p : s.points_B) {
        if (!p.allFinite()) {
          throw InputError(fmt::format("contact '{}' (point set): a point is not finite", s.name));
        }
      }
      break;
    case ContactShape::kSphereSphere:
      RequireLength(s, "radius", s.radius, false);
      RequireLength(s, "other radius", s.other_radius, false);
      if (!s.p_OoC_O.allFinite()) {
        throw InputError(fmt::format(
            "contact '{}' (sphere-sphere): the other sphere's centre is not finite", s.name));
      }
      break;
  }
}

Contact::Contact(const Model& model, ContactSpec spec) : spec_(std::move(spec)) {
  ValidateContactSpec(spec_);
  const ContactSpec& s = spec_;
  if (s.body < 0 || s.body >= model.num_bodies()) {
    throw InputError(
        fmt::format("contact '{}': body index {} does not exist (the model has {} "
                    "bodies); the shape must be on a body",
                    s.name, s.body, model.num_bodies()));
  }
  if (s.shape == ContactShape::kSphereSphere) {
    if (s.other_body < 0 || s.other_body >= model.num_bodies() || s.other_body == s.body) {
      throw InputError(fmt::format(
          "contact '{}' (sphere-sphere): other body index {} must be a body other than {}; "
          "for a sphere on the ground use the sphere shape with a plane",
          s.name, s.other_body, s.body));
    }
    p_OcmC_O_ = model.body(s.other_body).PointFromCenterOfMass(s.p_OoC_O);
  } else {
    spec_.other_body = kWorld;
  }
  const Body& body = model.body(s.body);
  const Vec3 c = body.PointFromCenterOfMass(s.p_BoC_B);
  if (s.shape != ContactShape::kSphereSphere) {
    const Mat3 T = FrameWithZAxis(s.plane_normal_W);
    t1_W_ = T.col(0), t2_W_ = T.col(1), n_W_ = T.col(2);
    spec_.plane_normal_W = n_W_;
  } else {
    n_W_ = Vec3::UnitZ(), t1_W_ = Vec3::UnitX(), t2_W_ = Vec3::UnitY();
  }
  const Vec3 e = s.axis_B.normalized();
  spec_.axis_B = e;
  auto add = [&](ContactFeatureKind kind, const Vec3& p, double r) {
    features_.push_back({kind, p, e, r});
  };
  switch (s.shape) {
    case ContactShape::kSphere:
    case ContactShape::kSphereSphere:
      add(ContactFeatureKind::kSphere, c, s.radius);
      break;
    case ContactShape::kDiskRim:
      add(ContactFeatureKind::kRim, c, s.radius);
      break;
    case ContactShape::kDiskFace: {
      // Points on the face's edge ring, at angles 2πk/n about the axis.
      const Mat3 F = FrameWithZAxis(e);
      for (int k = 0; k < s.face_points; ++k) {
        const double a = 2.0 * std::numbers::pi * k / s.face_points;
        add(ContactFeatureKind::kPoint,
            c + s.radius * (std::cos(a) * F.col(0) + std::sin(a) * F.col(1)), 0.0);
      }
      break;
    }
    case ContactShape::kCylinder:
      add(ContactFeatureKind::kRim, c - 0.5 * s.length * e, s.radius);
      add(ContactFeatureKind::kRim, c + 0.5 * s.length * e, s.radius);
      break;
    case ContactShape::kCapsule:
      add(ContactFeatureKind::kSphere, c - 0.5 * s.length * e, s.radius);
      add(ContactFeatureKind::kSphere, c + 0.5 * s.length * e, s.radius);
      break;
    case ContactShape::kBox:
      for (int k = 0; k < 8; ++k) {
        const Vec3 sign((k & 1) ? 1.0 : -1.0, (k & 2) ? 1.0 : -1.0, (k & 4) ? 1.0 : -1.0);
        add(ContactFeatureKind::kPoint, c + s.R_BF * sign.cwiseProduct(s.half_extents), 0.0);
      }
      break;
    case ContactShape::kPointSet:
      for (const Vec3& p : s.points_B)
        add(ContactFeatureKind::kPoint, body.PointFromCenterOfMass(p), 0.0);
      break;
  }
  if (!s.point_labels.empty() && s.point_labels.size() != features_.size()) {
    throw InputError(fmt::format("contact '{}': {} point labels for {} points", s.name,
                                 s.point_labels.size(), features_.size()));
  }
}

std::string Contact::point_name(int i) const {
  if (!spec_.point_labels.empty()) return spec_.point_labels[static_cast<size_t>(i)];
  if (num_points() == 1) return spec_.name;
  return fmt::format("{}_{}", spec_.name, i);
}

}  // namespace chasles
