// The browser report of a scene's modes (docs/report.md, "Modes"; docs/modes.md): the bodies at
// the operating point and, per mode, each body's complex displacement and rotation, scaled so
// that the page animates x(t) = x0 + ε Re(shape e^{λt}) at a size one can see.

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <string>
#include <vector>

#include "chasles/error.h"
#include "chasles/math/quaternion.h"
#include "chasles/report/json_report.h"
#include "chasles/report/modes_json.h"
#include "chasles/report/report_data.h"

namespace chasles {

namespace {

/// The largest excursion of a mode is drawn as this fraction of the scene's size.
constexpr double kModeAmplitude = 0.1;
/// A decaying or growing mode is shown until its amplitude has changed by this factor...
constexpr double kLoopFactor = 10.0;
/// ...over at most this many periods when it oscillates.
constexpr int kMostPeriods = 5;

nlohmann::json ComplexJson(const Eigen::Vector3cd& v) {
  return {{"re", VecJson(v.real())}, {"im", VecJson(v.imag())}};
}

/// The root-mean-square distance ρ of a body's mass from its centre of mass: ∫|r|² dm =
/// tr(I_cm)/2 (each moment is ∫ of the squared distance from its axis, and every |r|² is counted
/// twice over the three axes), so a small rotation δθ moves its mass by ρ|δθ| on average.
double MassRadius(const MassProperties& m) {
  return std::sqrt(std::max(m.I_BBcm_B().Trace(), 0.0) / (2.0 * m.mass()));
}

/// The scene's size at the operating point: the diagonal of the box around the bodies' centres
/// of mass and the reaction points (joints, rolling contacts), plus the largest body's 2ρ.
double SceneSize(const OperatingPointModes& s, const std::vector<double>& rho) {
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  const auto add = [&](const Vec3& p) { lo = lo.cwiseMin(p), hi = hi.cwiseMax(p); };
  for (const BodyState& b : s.operating_point.state.bodies) add(b.p_WBcm);
  for (const ReactionReport& r : s.solution.reactions) add(r.p_WJ);
  const double largest = rho.empty() ? 0.0 : *std::max_element(rho.begin(), rho.end());
  return (s.operating_point.state.bodies.empty() ? 0.0 : (hi - lo).norm()) + 2.0 * largest;
}

/// What the page loops over of the motion Re(ẑ e^{λt}), λ = σ + iω, the amplitude largest at
/// t = 0 (docs/report.md, "Modes"):
///  - a neutral oscillation (|σ| <= kNeutral of the largest |λ|): one period [0, 2π/ω], which
///    loops without a jump;
///  - a decaying or growing oscillation: until the amplitude e^{σt} has changed by kLoopFactor
///    (ln 10 / |σ|), cut down to whole periods (the loop then jumps less) when that is more
///    than one, and to at most kMostPeriods: [0, T] when it decays, [-T, 0] when it grows;
///  - a real λ: until the amplitude has changed by kLoopFactor, [0, ln 10/|σ|] or [-ln 10/σ, 0];
///  - a neutral real λ (a zero no symmetry explains): a constant displacement over [0, 1 s].
struct Loop {
  double t0 = 0.0, t1 = 1.0;
  /// The loop's length in periods (0 for a real λ).
  double periods = 0.0;
  const char* shown = "constant";
};

Loop LoopOf(std::complex<double> lambda, double largest) {
  const double sigma = lambda.real(), omega = lambda.imag();
  const bool neutral = std::abs(sigma) <= kNeutral * largest;
  Loop loop;
  const double fade = std::log(kLoopFactor) / std::abs(sigma);
  if (omega > 0.0) {
    const double period = 2.0 * std::numbers::pi / omega;
    loop.periods = neutral          ? 1.0
                   : fade >= period ? std::min(std::floor(fade / period), double{kMostPeriods})
                                    : fade / period;
    loop.t1 = loop.periods * period;
    loop.shown = neutral       ? "oscillation"
                 : sigma < 0.0 ? "decaying oscillation"
                               : "growing oscillation";
  } else if (!neutral) {
    loop.t1 = fade;
    loop.shown = sigma < 0.0 ? "decay" : "growth";
  }
  if (!neutral && sigma > 0.0) loop.t0 = -loop.t1, loop.t1 = 0.0;
  return loop;
}

/// The index of the shape's unit entry: the largest coordinate entry, else the largest speed
/// entry (CalcModes normalises so).
Eigen::Index UnitEntry(const Mode& m, Eigen::Index coordinates) {
  Eigen::Index at = 0;
  if (coordinates > 0 && m.shape.head(coordinates).cwiseAbs().maxCoeff() > 0.0) {
    m.shape.head(coordinates).cwiseAbs().maxCoeff(&at);
  } else if (m.shape.size() > 0) {
    m.shape.cwiseAbs().maxCoeff(&at);
  }
  return at;
}

nlohmann::json ModePageJson(const Mode& m, const Linearization& lin,
                            const std::vector<std::string>& names, const std::vector<double>& rho,
                            double size, double largest) {
  nlohmann::json j = ModeJson(m);
  j["animated"] = false;
  if (m.rigid) return j;
  const std::vector<BodyModeShape> bodies = CalcBodyModeShapes(lin, m);
  double excursion = 0.0;  // per unit of the shape: max_b |dp_b| + ρ_b |dθ_b| (complex norms)
  for (size_t b = 0; b < bodies.size(); ++b) {
    excursion = std::max(excursion, bodies[b].dp.norm() + rho[b] * bodies[b].dtheta.norm());
  }
  if (!(excursion > 0.0) || !(size > 0.0)) return j;  // a motion of the speeds alone
  const double scale = kModeAmplitude * size / excursion;
  const Loop loop = LoopOf(m.eigenvalue, largest);
  nlohmann::json motion = nlohmann::json::array();
  for (size_t b = 0; b < bodies.size(); ++b) {
    motion.push_back({{"name", names[b]},
                      {"dp", ComplexJson(scale * bodies[b].dp)},
                      {"dtheta", ComplexJson(scale * bodies[b].dtheta)}});
  }
  j["animated"] = true;
  j["scale"] = scale;
  j["reference"] = UnitEntry(m, static_cast<Eigen::Index>(lin.coordinates.size()));
  j["loop"] = {loop.t0, loop.t1};
  j["periods"] = loop.periods;
  j["shown"] = loop.shown;
  j["bodies"] = motion;
  return j;
}

nlohmann::json CoordinatesJson(const std::vector<LinearCoordinate>& c) {
  nlohmann::json out = nlohmann::json::array();
  for (const LinearCoordinate& x : c) out.push_back({{"name", x.name}, {"unit", x.unit}});
  return out;
}

}  // namespace

nlohmann::json ModesReportData(const Scene& scene, const OperatingPointModes& s) {
  nlohmann::json j = ReportSceneJson(scene, "modes");
  const OperatingPoint& op = s.operating_point;
  // The bodies at the operating point: frame origin Bo = Bcm - R_WB p_BoBcm_B, orientation and
  // centre of mass (what the modes displace), and ρ per body (MassRadius).
  std::vector<double> rho;
  nlohmann::json poses = nlohmann::json::array();
  for (size_t b = 0; b < s.bodies.size(); ++b) {
    const auto found = std::find_if(scene.bodies.begin(), scene.bodies.end(),
                                    [&](const SceneBody& x) { return x.name == s.bodies[b]; });
    if (found == scene.bodies.end()) {
      throw UsageError("ModesReportData: body '" + s.bodies[b] + "' is not in the scene");
    }
    const BodyState& bs = op.state.bodies[b];
    const Vec3 p_WBo = bs.p_WBcm - bs.q_WB.toRotationMatrix() * found->mass_properties.p_BoBcm_B();
    const Eigen::Vector4d q = QuatToWxyz(bs.q_WB.w() < 0 ? Quat(-bs.q_WB.coeffs()) : bs.q_WB);
    poses.push_back({{"name", s.bodies[b]},
                     {"origin", VecJson(p_WBo)},
                     {"quaternion", {q[0], q[1], q[2], q[3]}},
                     {"center_of_mass", VecJson(bs.p_WBcm)}});
    rho.push_back(MassRadius(found->mass_properties));
  }
  const double size = SceneSize(s, rho);
  double largest = 0.0;
  for (const Mode& m : s.modes.modes) largest = std::max(largest, std::abs(m.eigenvalue));
  nlohmann::json modes = nlohmann::json::array();
  const Linearization& lin = s.modes.linearization;
  for (const Mode& m : s.modes.modes) {
    modes.push_back(ModePageJson(m, lin, s.bodies, rho, size, largest));
  }
  j["operating_point"] = {{"kind", OperatingPointKindName(op.kind)}, {"residual", op.residual}};
  j["poses"] = poses;
  j["coordinates"] = CoordinatesJson(lin.coordinates);
  j["speeds"] = CoordinatesJson(lin.speeds);
  j["amplitude"] = {{"fraction", kModeAmplitude}, {"scene_size", size}};
  j["modes"] = modes;
  j["stable"] = s.modes.stable;
  CheckFiniteJson(j, "the report data");
  return j;
}

}  // namespace chasles
