// `forces: - {type: bearing, ...}`: a radial bearing on a shaft (model/bearing.h,
// docs/scene-format.md, `forces`).

#include <fmt/format.h>

#include "internal/scene_reader.h"

namespace chasles::scene_internal {
namespace {}  // namespace

Eigen::Vector2d SceneReader::PairAt(const At& at, const Dimension& expected,
                                    std::string_view what) {
  if (!at.node.IsSequence()) {
    const double v = Value(at, expected, what);
    return {v, v};
  }
  if (at.node.size() != 2) {
    report_.Fail(at, fmt::format("{} takes one value, or two [along e1, along e2]; got {}", what,
                                 at.node.size()));
  }
  return {Value(at.Item(0), expected, what), Value(at.Item(1), expected, what)};
}

// {body, at, axis, stiffness, damping, cross_stiffness, cross_damping}: `at` the bearing's
// centre in W, where the journal is at the initial configuration.
void SceneReader::ReadBearing(const At& at, const Scene& scene, const std::string& what,
                              SceneForce& f) {
  report_.CheckMap(at,
                   {"type", "name", "body", "at", "axis", "stiffness", "damping", "cross_stiffness",
                    "cross_damping"},
                   "a bearing element");
  f.type = SceneForce::Type::kBearing;
  f.body = BodyIndexAt(report_.Require(at, "body", what), scene);
  f.bearing_at_W = WorldVector(report_.Require(at, "at", what), kLength, "the bearing's centre");
  f.bearing_axis_W = AxisAt(report_.Require(at, "axis", what), "the bearing's axis");
  const Eigen::Vector2d k =
      PairAt(report_.Require(at, "stiffness", what), kStiffness, "the bearing's stiffness");
  const Eigen::Vector2d c =
      at.Has("damping") ? PairAt(at.Child("damping"), kLinearDamping, "the bearing's damping")
                        : Eigen::Vector2d::Zero();
  if (k.minCoeff() < 0) report_.Fail(at.Child("stiffness"), "the stiffness must be >= 0");
  if (c.minCoeff() < 0) report_.Fail(at.Child("damping"), "the damping must be >= 0");
  const auto cross = [&](const char* key, const Dimension& dim, const char* name) {
    if (!at.Has(key)) return Eigen::Vector2d::Zero().eval();
    const At a = at.Child(key);
    if (!a.node.IsSequence() || a.node.size() != 2) {
      report_.Fail(a, fmt::format("{} is two values [e1 from e2, e2 from e1]", name));
    }
    return PairAt(a, dim, name);
  };
  const Eigen::Vector2d kx = cross("cross_stiffness", kStiffness, "the cross-coupled stiffness");
  const Eigen::Vector2d cx = cross("cross_damping", kLinearDamping, "the cross-coupled damping");
  f.bearing_K << k[0], kx[0], kx[1], k[1];
  f.bearing_C << c[0], cx[0], cx[1], c[1];
}

}  // namespace chasles::scene_internal
