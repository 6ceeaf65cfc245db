// The JSON report of `chasles mass` (chasles/scene/mass_report.h).

#include "chasles/scene/mass_report.h"

#include <cmath>
#include <string>
#include <vector>

#include "chasles/mass/mass_properties.h"
#include "chasles/mass/rotational_inertia.h"

namespace chasles {

const char* const kInertiaConvention =
    "Inertia matrices are the tensor [I]: moments on the diagonal, products as tensor entries "
    "Ixy = -∫xy dm, so that H = [I] ω.";

namespace {

// A vector and a matrix as every report writes them: the same form as VecJson and MatJson of
// chasles/report/json_report.h, a layer above this one (the mass sweep, in this layer, reads
// its quantities from this report).

/// [x, y, z].
nlohmann::json VecJson(const Vec3& v) {
  return {v.x(), v.y(), v.z()};
}

/// Rows: [[m00, m01, m02], [m10, m11, m12], [m20, m21, m22]].
nlohmann::json MatJson(const Mat3& m) {
  return {{m(0, 0), m(0, 1), m(0, 2)}, {m(1, 0), m(1, 1), m(1, 2)}, {m(2, 0), m(2, 1), m(2, 2)}};
}

/// A value in `dim`, or null (NaN: not given).
nlohmann::json OrNull(const UnitSystem& units, double v, const Dimension& dim) {
  return std::isnan(v) ? nlohmann::json(nullptr) : nlohmann::json(units.FromSI(v, dim));
}

/// Values in the report's units.
struct Convert {
  const UnitSystem& units;
  double Mass(double v) const { return units.FromSI(v, kMass); }
  double Inertia(double v) const { return units.FromSI(v, kInertia); }
  Vec3 Lengths(const Vec3& v) const {
    return Vec3(units.FromSI(v.x(), kLength), units.FromSI(v.y(), kLength),
                units.FromSI(v.z(), kLength));
  }
  Mat3 InertiaMatrix(const Mat3& m) const {
    return m.unaryExpr([this](double v) { return Inertia(v); });
  }
};

nlohmann::json PartJson(const ScenePart& p, const Convert& P) {
  const MassProperties& q = p.mass_properties;
  nlohmann::json pj = {
      {"name", p.name},
      {"shape", p.shape},
      {"subtractive", p.subtractive},
      {"mass_source", p.mass_source},
      {"mass", P.Mass(q.mass())},
      {"center_of_mass", VecJson(P.Lengths(q.p_BoBcm_B()))},
      {"inertia_about_center_of_mass", MatJson(P.InertiaMatrix(q.I_BBcm_B().matrix()))},
      {"volume", OrNull(P.units, p.volume, kVolume)},
      {"surface_area", OrNull(P.units, p.surface_area, kArea)},
      {"notes", p.notes}};
  if (std::isfinite(p.density)) pj["density"] = P.units.FromSI(p.density, kDensity);
  return pj;
}

/// "principal_moments" (ascending), "principal_axes" (unit, in body axes) and
/// "radii_of_gyration" (k = sqrt(I/m), eq. 8.19, about the body axes and about the principal
/// axes through the same point) of inertia `I` of a body of mass `mass`.
void AddPrincipalJson(nlohmann::json& j, const RotationalInertia& I, double mass,
                      const Convert& P) {
  const PrincipalAxes pa = I.CalcPrincipalAxes();
  j["principal_moments"] =
      VecJson(Vec3(P.Inertia(pa.moments[0]), P.Inertia(pa.moments[1]), P.Inertia(pa.moments[2])));
  j["principal_axes"] = {VecJson(pa.axes.col(0)), VecJson(pa.axes.col(1)), VecJson(pa.axes.col(2))};
  j["radii_of_gyration"] = {
      {"body_axes", VecJson(P.Lengths(I.CalcRadiiOfGyration(mass)))},
      {"principal_axes",
       VecJson(P.Lengths(RotationalInertia(pa.moments[0], pa.moments[1], pa.moments[2])
                             .CalcRadiiOfGyration(mass)))}};
}

nlohmann::json BodyJson(const SceneBody& body, const Convert& P,
                        const std::vector<MassReportPoint>& extra,
                        const std::optional<Mat3>& R_BF) {
  const MassProperties& mp = body.mass_properties;
  const RotationalInertia& Icm = mp.I_BBcm_B();
  nlohmann::json b;
  b["name"] = body.name;
  b["mass"] = P.Mass(mp.mass());
  b["center_of_mass"] = VecJson(P.Lengths(mp.p_BoBcm_B()));
  b["inertia_about_center_of_mass"] = MatJson(P.InertiaMatrix(Icm.matrix()));
  AddPrincipalJson(b, Icm, mp.mass(), P);
  const BodyMeasures measures = CalcBodyMeasures(body);
  b["volume"] = OrNull(P.units, measures.volume, kVolume);
  b["surface_area"] = OrNull(P.units, measures.surface_area, kArea);
  if (!measures.volume_note.empty()) b["volume_note"] = measures.volume_note;
  if (!measures.surface_area_note.empty()) b["surface_area_note"] = measures.surface_area_note;
  b["points"] = nlohmann::json::array();
  for (const MassReportPoint& p : MassReportPoints(body, extra)) {
    // I_P by the parallel-axis theorem (eqs. 8.24-8.29); its principal moments and axes are
    // the eigenvalues and eigenvectors of I_P, and k = sqrt(I/m) (eq. 8.19) about the axes
    // through P.
    const RotationalInertia I_P = mp.CalcInertiaAbout(p.p_BoP_B);
    nlohmann::json pj = {{"name", p.name},
                         {"position", VecJson(P.Lengths(p.p_BoP_B))},
                         {"inertia", MatJson(P.InertiaMatrix(I_P.matrix()))}};
    AddPrincipalJson(pj, I_P, mp.mass(), P);
    b["points"].push_back(pj);
  }
  if (R_BF) {
    // The central inertia re-expressed in F: I_F = R_FB I_B R_FBᵀ with R_FB = R_BFᵀ.
    b["frame"] = {{"rotation_body_from_frame", MatJson(*R_BF)},
                  {"inertia_about_center_of_mass",
                   MatJson(P.InertiaMatrix(Icm.ReExpressedIn(R_BF->transpose()).matrix()))}};
  }
  b["parts"] = nlohmann::json::array();
  for (const ScenePart& p : body.parts) b["parts"].push_back(PartJson(p, P));
  return b;
}

}  // namespace

BodyMeasures CalcBodyMeasures(const SceneBody& body) {
  BodyMeasures m;
  // Volume: the parts' own volumes, a cut's subtracted (curves, surfaces and points have none).
  m.volume = 0.0;
  for (const ScenePart& p : body.parts) {
    if (std::isnan(p.volume)) {
      m.volume = std::numeric_limits<double>::quiet_NaN();
      m.volume_note = "n/a: part '" + p.name + "' (" + p.shape + ") has no geometry";
      break;
    }
    m.volume += p.subtractive ? -p.volume : p.volume;
  }
  // Surface area: exact only for one part; parts may share or cut faces.
  if (body.parts.size() == 1 && !std::isnan(body.parts[0].surface_area)) {
    m.surface_area = body.parts[0].surface_area;
  } else if (body.parts.size() == 1) {
    m.surface_area_note =
        "n/a: part '" + body.parts[0].name + "' (" + body.parts[0].shape + ") has no geometry";
  } else {
    m.surface_area_note = "n/a: parts may share or cut faces";
  }
  return m;
}

std::vector<MassReportPoint> MassReportPoints(const SceneBody& body,
                                              const std::vector<MassReportPoint>& extra) {
  std::vector<MassReportPoint> points;
  for (const auto& p : body.points) points.push_back({p.name, p.p_BoP_B});
  points.insert(points.end(), extra.begin(), extra.end());
  return points;
}

nlohmann::json MassReportJson(const Scene& scene, const UnitSystem& units,
                              const std::vector<MassReportPoint>& extra,
                              const std::optional<Mat3>& R_BF) {
  const Convert P{units};
  nlohmann::json j;
  j["scene"] = scene.file;
  j["title"] = scene.title;
  j["units"] = {{"length", units.FormatUnit(kLength)},   {"mass", units.FormatUnit(kMass)},
                {"inertia", units.FormatUnit(kInertia)}, {"density", units.FormatUnit(kDensity)},
                {"volume", units.FormatUnit(kVolume)},   {"area", units.FormatUnit(kArea)}};
  j["inertia_convention"] = kInertiaConvention;
  j["parameters"] = nlohmann::json::object();
  for (const auto& [name, q] : scene.parameters) {
    j["parameters"][name] = {{"value_si", q.value}, {"dimension", q.dim.Formula()}};
  }
  j["bodies"] = nlohmann::json::array();
  for (const SceneBody& body : scene.bodies) j["bodies"].push_back(BodyJson(body, P, extra, R_BF));
  j["warnings"] = scene.warnings;
  return j;
}

}  // namespace chasles
