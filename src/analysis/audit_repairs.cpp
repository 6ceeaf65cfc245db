// A link's inertial against its geometry (analysis/internal/audit_steps.h): implied density,
// radius of gyration, centre of mass, agreement; and when they disagree, the single slip that
// explains it (a decimal point, swapped entries, the sign of the products, another frame).

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include "analysis/internal/audit_steps.h"

namespace chasles::internal {

namespace {

using T = AuditThresholds;

/// A candidate explanation of a disagreement: the values it gives and how close they come.
struct Candidate {
  FindingCode code;
  std::string what;  // "izz 0.21942 → 0.0021942"
  MassProperties values;
  double factor = std::numeric_limits<double>::infinity();
};

/// The file's tensor (in I) turned into L.
Mat3 ToLink(const RobotInertial& in, const Mat3& W) {
  return in.R_LI * W * in.R_LI.transpose();
}

const char* const kEntry[6] = {"ixx", "iyy", "izz", "ixy", "ixz", "iyz"};
const int kRow[6] = {0, 1, 2, 0, 0, 1}, kCol[6] = {0, 1, 2, 1, 2, 2};

/// Every single slip of the written numbers, scored against the geometry at its mass.
std::vector<Candidate> Candidates(const RobotInertial& in, const GeometryEstimate& geo) {
  std::vector<Candidate> out;
  const double m = in.mass;
  const Vec3 c = in.p_LoLcm_L;
  const Mat3& W = in.I_LcmI_I;
  auto score = [&](FindingCode code, std::string what, double mass, const Vec3& com,
                   const Mat3& I_L) {
    Candidate k{code, std::move(what),
                MassProperties(mass, com, RotationalInertia::FromMatrix(I_L))};
    k.factor = TensorFactor(I_L, geo.AtMass(mass).I_BBcm_B().matrix());
    out.push_back(std::move(k));
  };
  for (int k = -3; k <= 3; ++k) {
    if (k == 0) continue;
    const double f = std::pow(10.0, k);
    for (int e = 0; e < 6; ++e) {
      Mat3 V = W;
      V(kRow[e], kCol[e]) *= f;
      V(kCol[e], kRow[e]) = V(kRow[e], kCol[e]);
      if (V(kRow[e], kCol[e]) == 0.0) continue;
      score(FindingCode::kDecimalSlip,
            fmt::format("{} {:g} → {:g}", kEntry[e], W(kRow[e], kCol[e]), V(kRow[e], kCol[e])), m,
            c, ToLink(in, V));
    }
    const double rho = m * f / geo.volume;
    if (rho >= T::kDensityLow && rho <= T::kDensityHigh) {
      score(FindingCode::kDecimalSlip, fmt::format("mass {:g} → {:g} kg", m, m * f), m * f, c,
            ToLink(in, W));
    }
  }
  // Swapped diagonal entries (the products kept where they are).
  const std::array<std::array<int, 3>, 5> perms = {
      {{1, 0, 2}, {2, 1, 0}, {0, 2, 1}, {1, 2, 0}, {2, 0, 1}}};
  for (const auto& p : perms) {
    Mat3 V = W;
    for (int i = 0; i < 3; ++i) V(i, i) = W(p[i], p[i]);
    score(FindingCode::kTransposedEntries,
          fmt::format("ixx, iyy, izz {:g}, {:g}, {:g} → {:g}, {:g}, {:g}", W(0, 0), W(1, 1),
                      W(2, 2), V(0, 0), V(1, 1), V(2, 2)),
          m, c, ToLink(in, V));
  }
  // The products with the other sign (+∫xy dm written where the tensor holds -∫xy dm).
  const Mat3 off = W - Mat3(W.diagonal().asDiagonal());
  if (off.norm() > 0.05 * std::abs(W.trace())) {
    score(FindingCode::kSignOfProducts, "ixy, ixz, iyz with the other sign", m, c,
          ToLink(in, Mat3(W - 2 * off)));
  }
  // Another frame: the tensor about the link origin instead of the centre of mass (shifted
  // back by the parallel-axis theorem, eq. 8.29), or about axes turned from the geometry's.
  const Mat3 I_L = ToLink(in, W);
  const Mat3 shift = m * (c.squaredNorm() * Mat3::Identity() - c * c.transpose());
  if (c.norm() > 0.0) {
    score(FindingCode::kFrame,
          "the tensor taken about the link origin, moved to the centre of mass", m, c, I_L - shift);
  }
  const Eigen::SelfAdjointEigenSolver<Mat3> given(I_L), geom(geo.unit_density.I_BBcm_B().matrix());
  score(FindingCode::kFrame, "the given principal moments on the geometry's principal axes", m, c,
        geom.eigenvectors() * given.eigenvalues().asDiagonal() * geom.eigenvectors().transpose());
  return out;
}

/// A smaller disagreement that the products' sign alone explains: products of at least
/// kProducts of the trace, and with their sign turned the tensor agrees within kSignAgree.
bool SignSlip(const RobotInertial& in, const GeometryEstimate& geo, double factor) {
  const Mat3& W = in.I_LcmI_I;
  const Mat3 off = W - Mat3(W.diagonal().asDiagonal());
  if (!(factor > T::kAgree) || !(off.norm() >= T::kProducts * std::abs(W.trace()))) return false;
  const Mat3 flipped = in.R_LI * (W - 2 * off) * in.R_LI.transpose();
  return TensorFactor(flipped, geo.AtMass(in.mass).I_BBcm_B().matrix()) <= T::kSignAgree;
}

/// The one slip that explains the disagreement, if exactly one does (for decimal slips: one
/// number); preference: decimal point, swapped entries, signs, frame.
const Candidate* Explain(const std::vector<Candidate>& candidates) {
  for (const FindingCode code : {FindingCode::kDecimalSlip, FindingCode::kTransposedEntries,
                                 FindingCode::kSignOfProducts, FindingCode::kFrame}) {
    const Candidate* best = nullptr;
    int working = 0;
    for (const Candidate& k : candidates) {
      if (k.code != code || !(k.factor <= T::kAgree)) continue;
      ++working;
      if (!best || k.factor < best->factor) best = &k;
    }
    if (best && (code != FindingCode::kDecimalSlip || working == 1)) return best;
  }
  return nullptr;
}

/// Implausible density, with the slips that explain it. False when the geometry itself is
/// not to be trusted (its scale looks wrong).
bool CheckDensity(const RobotLink& link, LinkAudit& a, const GeometryEstimate& geo) {
  const double m = link.inertial.mass, V = geo.volume, rho = m / V;
  if (rho >= T::kDensityLow && rho <= T::kDensityHigh) return true;
  const auto plausible = [](double r) { return r >= 300.0 && r <= 10000.0; };
  std::string why;
  std::optional<MassProperties> fix;
  bool geometry_ok = true;
  if (rho / 1000 >= T::kDensityLow && rho / 1000 <= T::kDensityHigh) {
    why = fmt::format(
        "the mass looks like grams taken as kilograms: {:g} kg / 1000 gives {:.4g} "
        "kg/m³; write mass {:g} (and the tensor, in g·m² too, divided by 1000)",
        m, rho / 1000, m / 1000);
    fix = MassProperties(m / 1000, a.given.p_BoBcm_B(), a.given.I_BBcm_B() * 1e-3);
  } else if (plausible(rho * 1e9) || plausible(rho / 1e9)) {
    why =
        fmt::format("the geometry looks {} (its volume is off by 10⁹): give the mesh scale=\"{}\"",
                    rho < 1 ? "like millimetres read as metres" : "scaled to millimetres twice",
                    rho < 1 ? "0.001 0.001 0.001" : "1 1 1");
    geometry_ok = false;
  } else if (plausible(rho * 1000)) {
    why = fmt::format("the mass looks like tonnes or the geometry like a part 10 times larger");
  }
  AddFinding(a, Severity::kError, FindingCode::kImplausibleDensity, link.inertial.mass_line,
             fmt::format("mass {:g} kg in the {} geometry's {:.4g} m³ ({}) is a density of {:.4g} "
                         "kg/m³, outside {:g} to {:g} kg/m³ (hollow covers to tungsten){}{}",
                         m, GeometrySetName(geo.set), V, GeometryMethodName(geo.method), rho,
                         T::kDensityLow, T::kDensityHigh, why.empty() ? "" : ": ", why),
             fix, fix ? "the mass and the tensor divided by 1000" : "");
  return geometry_ok;
}

}  // namespace

void CheckAgainstGeometry(const RobotLink& link, LinkAudit& a) {
  if (!link.has_inertial || !a.computed) return;
  const GeometryEstimate& geo = a.estimates[*a.computed];
  const RobotInertial& in = link.inertial;
  const double m = in.mass;
  if (!(m > 0.0) || !(geo.volume > 0.0)) return;
  if (!CheckDensity(link, a, geo)) return;
  const MassProperties expected = geo.AtMass(m);
  const std::string geometry_rule = "the geometry's centre of mass and tensor at the given mass";
  const Mat3 I = a.given.I_BBcm_B().matrix();
  const Vec3 c = a.given.p_BoBcm_B();
  // An unusable tensor is better replaced by the geometry's than by the nearest valid one.
  for (Finding& f : a.findings) {
    if (f.code == FindingCode::kNotPositiveDefinite || f.code == FindingCode::kTriangleInequality) {
      f.fix = expected;
      f.fix_rule = geometry_rule;
    }
  }
  // Centre of mass: a positive mass distribution has its centre inside its convex hull, so
  // within the box of the geometry (with a margin for meshes slightly smaller than the part).
  const double diag = (geo.box_max - geo.box_min).norm();
  const Vec3 lo = geo.box_min.array() - T::kComMargin * diag;
  const Vec3 hi = geo.box_max.array() + T::kComMargin * diag;
  if ((c.array() < lo.array()).any() || (c.array() > hi.array()).any()) {
    AddFinding(
        a, Severity::kError, FindingCode::kComOutsideGeometry, in.line,
        fmt::format("the centre of mass [{:.4g}, {:.4g}, {:.4g}] m lies outside the {} "
                    "geometry (box [{:.4g}, {:.4g}, {:.4g}] to [{:.4g}, {:.4g}, {:.4g}] m); "
                    "the geometry's is [{:.4g}, {:.4g}, {:.4g}] m",
                    c.x(), c.y(), c.z(), GeometrySetName(geo.set), geo.box_min.x(), geo.box_min.y(),
                    geo.box_min.z(), geo.box_max.x(), geo.box_max.y(), geo.box_max.z(),
                    expected.p_BoBcm_B().x(), expected.p_BoBcm_B().y(), expected.p_BoBcm_B().z()),
        expected, geometry_rule);
  }
  const double trace = I.trace();
  if (!(trace > 0.0)) return;
  // Radius of gyration: tr I / 2 = ∫ r² dm <= m R², R the farthest point from the centre of
  // mass, whatever the density (eq. 8.19).
  const double k = std::sqrt(trace / (2 * m)), R = geo.RadiusAbout(c);
  if (k > T::kReach * R) {
    AddFinding(a, Severity::kError, FindingCode::kRadiusOfGyration, in.inertia_line,
               fmt::format("the radius of gyration √(tr I / 2m) = {:.4g} m is larger than {:.4g} "
                           "m, the farthest point of the {} geometry from the centre of mass: no "
                           "mass inside the link has this inertia ({:.3g} times too large); the "
                           "geometry gives {}",
                           k, R, GeometrySetName(geo.set), k * k / (R * R),
                           TensorText(expected.I_BBcm_B().matrix())),
               expected, geometry_rule);
  }
  const double factor = TensorFactor(I, expected.I_BBcm_B().matrix());
  const bool small = !(factor > T::kMismatchWarning);
  if (small && !SignSlip(in, geo, factor)) return;
  std::vector<Candidate> candidates = Candidates(in, geo);
  if (small) {  // only the sign explains a disagreement this small
    std::erase_if(candidates,
                  [](const Candidate& k) { return k.code != FindingCode::kSignOfProducts; });
  }
  if (const Candidate* k = Explain(candidates)) {
    const char* rules[] = {"the unique decimal repair", "the entries put back in place",
                           "the products with their sign restored",
                           "the tensor moved to the frame the file means"};
    const int r = k->code == FindingCode::kDecimalSlip         ? 0
                  : k->code == FindingCode::kTransposedEntries ? 1
                  : k->code == FindingCode::kSignOfProducts    ? 2
                                                               : 3;
    AddFinding(a, Severity::kError, k->code, in.inertia_line,
               fmt::format("the inertial disagrees with its {} geometry by a factor {:.3g}, and "
                           "one slip explains it: {} (then within {:.3g} of the geometry)",
                           GeometrySetName(geo.set), factor, k->what, k->factor),
               k->values, rules[r]);
    return;
  }
  for (Finding& f : a.findings) {
    // A placeholder is an error when the geometry shows it is far off.
    if (f.code == FindingCode::kPlaceholderInertia) {
      if (factor > T::kMismatchError) f.severity = Severity::kError;
      f.fix = expected;
      f.fix_rule = geometry_rule;
      f.effect = DynamicEffect(I, expected.I_BBcm_B().matrix());
      return;
    }
  }
  if (factor > T::kMismatchWarning && std::isfinite(factor)) {
    const Vec3 r = TensorRatios(I, expected.I_BBcm_B().matrix());
    AddFinding(a, factor > T::kMismatchError ? Severity::kError : Severity::kWarning,
               FindingCode::kMismatchGeometry, in.inertia_line,
               fmt::format("the inertia {} differs from the {} geometry's at {:g} kg, {}, by "
                           "factors {:.3g}, {:.3g}, {:.3g} along the directions where they differ "
                           "most (the geometry: {}, {:.4g} m³)",
                           TensorText(I), GeometrySetName(geo.set), m,
                           TensorText(expected.I_BBcm_B().matrix()), r[0], r[1], r[2],
                           GeometryMethodName(geo.method), geo.volume),
               expected, geometry_rule);
  }
}

}  // namespace chasles::internal
