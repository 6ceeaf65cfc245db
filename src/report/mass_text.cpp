#include "chasles/report/mass_text.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "chasles/report/json_report.h"
#include "chasles/report/text_format.h"

namespace chasles {

namespace {

/// What the report shows, in the units asked for: the kit's Show with the mass report's 7
/// significant digits and round-off threshold, and the unit names of its columns.
struct Presenter {
  Show show;
  std::string L, M, I, rho;

  explicit Presenter(const UnitSystem& u)
      : show{u, 7, kMassRoundOff, "a value of the mass report"},
        L(u.FormatUnit(kLength)),
        M(u.FormatUnit(kMass)),
        I(u.FormatUnit(kInertia)),
        rho(u.FormatUnit(kDensity)) {}

  double Length(double v) const { return show.units.FromSI(v, kLength); }
  double Mass(double v) const { return show.units.FromSI(v, kMass); }
  double Inertia(double v) const { return show.units.FromSI(v, kInertia); }
  Vec3 Lengths(const Vec3& v) const { return Vec3(Length(v.x()), Length(v.y()), Length(v.z())); }
  Mat3 InertiaMatrix(const Mat3& m) const {
    return m.unaryExpr([this](double v) { return Inertia(v); });
  }
  /// A value in the report's units; round-off next to `scale` shows as an exact 0.
  std::string Num(double v, double scale) const { return show.Number(show.Clean(v, scale)); }
  std::string VecText(const Vec3& v, double scale) const {
    return fmt::format("[{}, {}, {}]", Num(v.x(), scale), Num(v.y(), scale), Num(v.z(), scale));
  }
};

void MatrixText(std::string& out, const Presenter& P, const Mat3& m, const std::string& indent) {
  const double scale = m.cwiseAbs().maxCoeff();
  std::string cells[3][3];
  size_t width = 0;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      cells[i][j] = P.Num(m(i, j), scale);
      width = std::max(width, cells[i][j].size());
    }
  }
  for (int i = 0; i < 3; ++i) {
    out += fmt::format("{}[ {:>{}}  {:>{}}  {:>{}} ]\n", indent, cells[i][0], width, cells[i][1],
                       width, cells[i][2], width);
  }
}

/// The inertia I_P about a point P of a body of mass `mass`, its principal moments and axes
/// and its radii of gyration about the axes through P.
void PointInertiaText(std::string& out, const Presenter& P, const RotationalInertia& I_P,
                      double mass) {
  // I_P (parallel-axis theorem, eqs. 8.24-8.29), its eigenvalues and eigenvectors, and
  // k = sqrt(I/m) (eq. 8.19) about the axes through P.
  MatrixText(out, P, P.InertiaMatrix(I_P.matrix()), "    ");
  const PrincipalAxes pp = I_P.CalcPrincipalAxes();
  const double Ps = P.Inertia(I_P.Trace());
  out += fmt::format("    Principal moments   {}, {}, {} {}\n", P.Num(P.Inertia(pp.moments[0]), Ps),
                     P.Num(P.Inertia(pp.moments[1]), Ps), P.Num(P.Inertia(pp.moments[2]), Ps), P.I);
  out += fmt::format("    Principal axes      e1 = {}, e2 = {}, e3 = {}  (body axes)\n",
                     P.VecText(pp.axes.col(0), 1), P.VecText(pp.axes.col(1), 1),
                     P.VecText(pp.axes.col(2), 1));
  const double kp_scale = std::sqrt(std::abs(I_P.Trace() / mass));
  out += fmt::format("    Radii of gyration   about body axes through the point: {} {}\n",
                     P.VecText(P.Lengths(I_P.CalcRadiiOfGyration(mass)), P.Length(kp_scale)), P.L);
  out +=
      fmt::format("                        about the principal axes through the point: {} {}\n",
                  P.VecText(P.Lengths(RotationalInertia(pp.moments[0], pp.moments[1], pp.moments[2])
                                          .CalcRadiiOfGyration(mass)),
                            P.Length(kp_scale)),
                  P.L);
}

// Why a body's volume is zero when no part has any (rods, rings, thin disks, points): said so
// that a 0 beside parts with mass does not read as a mistake.
std::string VolumeRemark(const SceneBody& body, double volume) {
  if (volume != 0.0) return "";
  for (const ScenePart& p : body.parts) {
    if (p.volume != 0.0) return "";
  }
  return "  (every part is idealised as a curve, a surface or a point)";
}

/// The table of a body's parts: shape, mass, centre of mass, how the mass was given, volume and
/// surface area, and each part's own central inertia.
std::string PartsText(const SceneBody& body, const Presenter& P, double Lscale) {
  std::string out;
  size_t w = 4;
  size_t ws = 5;
  for (const auto& p : body.parts) {
    w = std::max(w, p.name.size());
    ws = std::max(ws, p.shape.size() + (p.subtractive ? 6 : 0));
  }
  out += fmt::format("  {:<{}}  {:<{}}  {:>13}  {}\n", "part", w, "shape", ws, "mass [" + P.M + "]",
                     "centre of mass [" + P.L + "]");
  for (const ScenePart& p : body.parts) {
    const MassProperties& q = p.mass_properties;
    std::string shape = p.shape + (p.subtractive ? " (cut)" : "");
    out += fmt::format("  {:<{}}  {:<{}}  {:>13}  {}\n", p.name, w, shape, ws,
                       P.Num(P.Mass(q.mass()), 0),
                       P.VecText(P.Lengths(q.p_BoBcm_B()), P.Length(Lscale)));
    std::string detail;
    if (std::isfinite(p.density)) {
      detail =
          fmt::format("density {} {}", P.Num(P.show.units.FromSI(p.density, kDensity), 0), P.rho);
      if (p.mass_source != "density") detail += fmt::format(" ({})", p.mass_source);
    } else if (p.mass_source != "mass" && p.notes.empty()) {
      detail = p.mass_source;
    }
    for (const auto& n : p.notes) detail += (detail.empty() ? "" : "; ") + n;
    if (p.volume == 0.0 && p.surface_area == 0.0) {
      // A slender rod, a ring or a point: the idealisation has neither.
      detail += std::string(detail.empty() ? "" : "; ") +
                "no volume or surface area (its mass lies on a curve or at a point)";
    } else if (!std::isnan(p.volume)) {
      detail += fmt::format(
          "{}volume {} {}, surface area {} {}", detail.empty() ? "" : "; ",
          P.Num(P.show.units.FromSI(p.volume, kVolume), 0), P.show.units.FormatUnit(kVolume),
          P.Num(P.show.units.FromSI(p.surface_area, kArea), 0), P.show.units.FormatUnit(kArea));
    }
    if (!detail.empty()) out += fmt::format("  {:<{}}  {}\n", "", w, detail);
    // The part's own central inertia, in body axes: the six tensor entries on one line.
    const Mat3 Ip = P.InertiaMatrix(q.I_BBcm_B().matrix());
    const double s = Ip.cwiseAbs().maxCoeff();
    out += fmt::format(
        "  {:<{}}  inertia about its centre of mass [{}]: Ixx {}, Iyy {}, Izz {}, "
        "Ixy {}, Ixz {}, Iyz {}\n",
        "", w, P.I, P.Num(Ip(0, 0), s), P.Num(Ip(1, 1), s), P.Num(Ip(2, 2), s), P.Num(Ip(0, 1), s),
        P.Num(Ip(0, 2), s), P.Num(Ip(1, 2), s));
  }
  return out;
}

/// The report proper, once every value is known to be finite.
std::string MassReportText(const Scene& scene, const Presenter& P, const MassTextOptions& options) {
  std::string out;
  out += fmt::format("chasles mass: {}\n", scene.title.empty() ? scene.file : scene.title);
  if (!scene.title.empty()) out += fmt::format("Scene: {}\n", scene.file);
  out += fmt::format("Units: length {}, mass {}, inertia {}.\n{}\n", P.L, P.M, P.I,
                     kInertiaConvention);
  for (const SceneBody& body : scene.bodies) {
    const MassProperties& mp = body.mass_properties;
    const double Lscale =
        // stableNorm: |p| of a part at 1e200 m is 1.7e200, where norm() overflows to inf and
        // would round every coordinate to 0.
        std::max(mp.p_BoBcm_B().stableNorm(), std::sqrt(mp.I_BBcm_B().Trace() / mp.mass()));
    out += fmt::format("\nBody '{}' ({} part{})\n", body.name, body.parts.size(),
                       body.parts.size() == 1 ? "" : "s");
    if (options.parts) out += PartsText(body, P, Lscale);
    const RotationalInertia& Icm = mp.I_BBcm_B();
    out += fmt::format("  Mass                {} {}\n", P.Num(P.Mass(mp.mass()), 0), P.M);
    out += fmt::format("  Centre of mass      {} {}  (from the body origin, body axes)\n",
                       P.VecText(P.Lengths(mp.p_BoBcm_B()), P.Length(Lscale)), P.L);
    // Volume (a cut's subtracted) and the surface area where it is exact (one part).
    const BodyMeasures measures = CalcBodyMeasures(body);
    out += fmt::format(
        "  Volume              {}\n",
        std::isnan(measures.volume)
            ? measures.volume_note
            : fmt::format("{} {}{}", P.Num(P.show.units.FromSI(measures.volume, kVolume), 0),
                          P.show.units.FormatUnit(kVolume), VolumeRemark(body, measures.volume)));
    out += fmt::format(
        "  Surface area        {}\n",
        std::isnan(measures.surface_area)
            ? measures.surface_area_note
            : fmt::format("{} {}", P.Num(P.show.units.FromSI(measures.surface_area, kArea), 0),
                          P.show.units.FormatUnit(kArea)));
    out += fmt::format("  Inertia about the centre of mass, body axes [{}]\n", P.I);
    MatrixText(out, P, P.InertiaMatrix(Icm.matrix()), "    ");
    const PrincipalAxes pa = Icm.CalcPrincipalAxes();
    const double Iscale = P.Inertia(Icm.Trace());
    out += fmt::format(
        "  Principal moments   {}, {}, {} {}\n", P.Num(P.Inertia(pa.moments[0]), Iscale),
        P.Num(P.Inertia(pa.moments[1]), Iscale), P.Num(P.Inertia(pa.moments[2]), Iscale), P.I);
    out += fmt::format("  Principal axes      e1 = {}, e2 = {}, e3 = {}  (body axes)\n",
                       P.VecText(pa.axes.col(0), 1), P.VecText(pa.axes.col(1), 1),
                       P.VecText(pa.axes.col(2), 1));
    // The radii describe the spread about the centre of mass, so their round-off scale is
    // their own size, not the body's distance from its origin (a body at 1e200 m still has
    // radii of centimetres).
    const double k_scale = std::sqrt(std::abs(Icm.Trace() / mp.mass()));
    const Vec3 k_body = Icm.CalcRadiiOfGyration(mp.mass());
    const Vec3 k_principal = RotationalInertia(pa.moments[0], pa.moments[1], pa.moments[2])
                                 .CalcRadiiOfGyration(mp.mass());
    out += fmt::format("  Radii of gyration   about body axes through the centre of mass: {} {}\n",
                       P.VecText(P.Lengths(k_body), P.Length(k_scale)), P.L);
    out += fmt::format("                      about the principal axes: {} {}\n",
                       P.VecText(P.Lengths(k_principal), P.Length(k_scale)), P.L);
    for (const MassReportPoint& p : MassReportPoints(body, options.about)) {
      out += fmt::format("  Inertia about point {} = {} {}, body axes [{}]\n", p.name,
                         P.VecText(P.Lengths(p.p_BoP_B), P.Length(Lscale)), P.L, P.I);
      PointInertiaText(out, P, mp.CalcInertiaAbout(p.p_BoP_B), mp.mass());
    }
    if (options.R_BF) {
      out += fmt::format("  Inertia about the centre of mass in frame F [{}]\n", P.I);
      MatrixText(out, P, P.InertiaMatrix(Icm.ReExpressedIn(options.R_BF->transpose()).matrix()),
                 "    ");
    }
  }
  for (const auto& w : scene.warnings) out += fmt::format("\nwarning: {}\n", w);
  return out;
}

}  // namespace

std::string MassText(const Scene& scene, const MassTextOptions& options) {
  const Presenter P(TextUnits(scene, options.text));
  // Every value of the report is in the JSON form: checked there first, by name (and let go
  // before the text is made: for 100 000 bodies each takes some 400 MB).
  CheckFiniteJson(MassReportJson(scene, P.show.units, options.about, options.R_BF),
                  "the mass report");
  return MassReportText(scene, P, options);
}

}  // namespace chasles
