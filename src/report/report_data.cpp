// The browser report's data (docs/report.md, "The data"): the scene's bodies as drawable
// parts, and a run's samples, events and forces, as one JSON object.

#include "chasles/report/report_data.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <string_view>
#include <tuple>
#include <unordered_set>

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/files/mesh_reader.h"
#include "chasles/math/quaternion.h"
#include "chasles/report/json_report.h"
#include "chasles/report/result_names.h"
#include "chasles/report/solve_json.h"
#include "chasles/scene/column_units.h"
#include "chasles/scene/study.h"

namespace chasles {

namespace {

/// The format's name and version; the page refuses data of another major version.
constexpr const char* kFormat = "chasles-report 2";

nlohmann::json QuatJson(const Quat& q) {
  const Eigen::Vector4d w = QuatToWxyz(q.w() < 0 ? Quat(-q.coeffs()) : q);
  return {w[0], w[1], w[2], w[3]};
}

/// 64-bit floats as base64: exact.
std::string F8(const std::vector<double>& v) {
  return Base64(v.data(), v.size() * sizeof(double));
}

/// 32-bit floats as base64: seven significant digits, for drawing and plotting.
std::string F4(const std::vector<double>& v) {
  std::vector<float> f(v.size());
  std::transform(v.begin(), v.end(), f.begin(), [](double x) { return static_cast<float>(x); });
  return Base64(f.data(), f.size() * sizeof(float));
}

/// Semi-axes of the uniform solid ellipsoid with mass m and principal central moments I
/// (Legendre's ellipsoid): from I_1 = m (a_2² + a_3²) / 5 and its cyclic forms,
///   a_i² = 5 (I_j + I_k − I_i) / (2 m),
/// 0 where the moments reach the triangle inequality's limit (a flat or slender body).
Vec3 EquivalentEllipsoid(double m, const Vec3& I) {
  Vec3 a;
  for (int i = 0; i < 3; ++i) {
    const double s = 5.0 * (I[(i + 1) % 3] + I[(i + 2) % 3] - I[i]) / (2.0 * m);
    a[i] = std::sqrt(std::max(s, 0.0));
  }
  return a;
}

nlohmann::json PartJson(const ScenePart& p) {
  nlohmann::json j = {{"name", p.name},
                      {"shape", p.shape},
                      {"subtract", p.subtractive},
                      {"position", VecJson(p.geometry.p_BoPo_B)},
                      {"quaternion", QuatJson(Quat(p.geometry.R_BP))}};
  nlohmann::json dims = nlohmann::json::object();
  for (const auto& [key, values] : p.geometry.dimensions) {
    dims[key] = values.size() == 1 ? nlohmann::json(values[0]) : nlohmann::json(values);
  }
  j["dimensions"] = dims;
  if (p.geometry.dimensions.empty() && p.geometry.mesh_file.empty()) {
    // No geometry (custom, planar, point): drawn as the uniform ellipsoid of the part's own
    // mass and central inertia, in B.
    const MassProperties& m = p.mass_properties;
    const double mass = std::abs(m.mass());
    const RotationalInertia I = m.mass() < 0 ? m.I_BBcm_B() * -1.0 : m.I_BBcm_B();
    const PrincipalAxes pa = I.CalcPrincipalAxes();
    j["ellipsoid"] = {{"center", VecJson(m.p_BoBcm_B())},
                      {"semi_axes", VecJson(EquivalentEllipsoid(mass, pa.moments))},
                      {"quaternion", QuatJson(Quat(pa.axes))}};
  }
  if (!p.geometry.mesh_file.empty()) {
    // The mesh as drawn: the file's vertices scaled to metres, in the part's frame P (the
    // frame the mass properties were computed in, before the part's position and axis), as
    // the floats WebGL draws.
    const MeshFileData mesh = ReadMeshFile(p.geometry.mesh_file);
    std::vector<float> xyz(mesh.xyz.size());
    const double s = p.geometry.mesh_scale;
    std::transform(mesh.xyz.begin(), mesh.xyz.end(), xyz.begin(),
                   [s](double x) { return static_cast<float>(x * s); });
    j["mesh"] = {
        {"vertices", Base64(xyz.data(), xyz.size() * sizeof(float))},
        {"triangles", Base64(mesh.indices.data(), mesh.indices.size() * sizeof(std::uint32_t))}};
  }
  return j;
}

nlohmann::json BodyJson(const SceneBody& b) {
  nlohmann::json parts = nlohmann::json::array();
  for (const ScenePart& p : b.parts) parts.push_back(PartJson(p));
  nlohmann::json points = nlohmann::json::array();
  for (const ScenePoint& p : b.points) {
    points.push_back({{"name", p.name}, {"position", VecJson(p.p_BoP_B)}});
  }
  const MassProperties& m = b.mass_properties;
  const PrincipalAxes pa = m.I_BBcm_B().CalcPrincipalAxes();
  // Principal axes as a rotation: e3 = e1 × e2 (right-handed), so the quaternion exists.
  return {{"name", b.name},
          {"mass", m.mass()},
          {"center_of_mass", VecJson(m.p_BoBcm_B())},
          {"inertia", MatJson(m.I_BBcm_B().matrix())},
          {"principal_moments", VecJson(pa.moments)},
          // Columns of `axes` are the principal directions in B; written as rows here.
          {"principal_axes", MatJson(pa.axes.transpose())},
          {"ellipsoid", VecJson(EquivalentEllipsoid(m.mass(), pa.moments))},
          {"parts", parts},
          {"points", points}};
}

/// Index of `name` in `columns`, or -1.
int FindColumn(const std::vector<std::string>& columns, const std::string& name) {
  const auto it = std::find(columns.begin(), columns.end(), name);
  return it == columns.end() ? -1 : static_cast<int>(it - columns.begin());
}

}  // namespace

std::string Base64(const void* bytes, size_t size) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* b = static_cast<const unsigned char*>(bytes);
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 2 < size; i += 3) {
    const std::uint32_t n = (std::uint32_t{b[i]} << 16) | (std::uint32_t{b[i + 1]} << 8) | b[i + 2];
    out += kAlphabet[(n >> 18) & 63];
    out += kAlphabet[(n >> 12) & 63];
    out += kAlphabet[(n >> 6) & 63];
    out += kAlphabet[n & 63];
  }
  if (i < size) {
    std::uint32_t n = std::uint32_t{b[i]} << 16;
    if (i + 1 < size) n |= std::uint32_t{b[i + 1]} << 8;
    out += kAlphabet[(n >> 18) & 63];
    out += kAlphabet[(n >> 12) & 63];
    out += i + 1 < size ? kAlphabet[(n >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

namespace {

/// Quaternion with w >= 0 (q and −q are the same rotation; the columns print this one).
Quat PositiveW(const Quat& q) {
  return q.w() < 0 ? Quat(-q.coeffs()) : q;
}

/// The table's pose of one body at every row (PosesFromColumns), or the columns it lacks.
struct BodyColumns {
  int ox = -1, oy = -1, oz = -1, x = -1, y = -1, z = -1, theta = -1;
  std::vector<int> q;
  bool has_origin() const { return ox >= 0 && oy >= 0 && oz >= 0; }
  bool has_q() const {
    return std::all_of(q.begin(), q.end(), [](int c) { return c >= 0; });
  }
};

}  // namespace

ColumnPoses PosesFromColumns(const Scene& scene, const StudyResult& r) {
  ColumnPoses out;
  out.rows.assign(r.rows.size(), std::vector<StudyBodyPose>(scene.bodies.size()));
  for (size_t k = 0; k < scene.bodies.size(); ++k) {
    const SceneBody& b = scene.bodies[k];
    const auto col = [&](const char* s) { return FindColumn(r.columns, b.name + "_" + s); };
    BodyColumns c{col("ox"), col("oy"), col("oz"),    col("x"),
                  col("y"),  col("z"),  col("theta"), {col("qw"), col("qx"), col("qy"), col("qz")}};
    // The orientation: the quaternion, or a planar body's angle about z.
    const bool has_turn = c.has_q() || (scene.planar && c.theta >= 0);
    // The origin: its own columns, or the centre of mass (a planar one may lack z: 0).
    const bool has_cm = c.x >= 0 && c.y >= 0 && (c.z >= 0 || scene.planar);
    if (!has_turn || !(c.has_origin() || has_cm)) {
      throw InputError(fmt::format(
          "the report needs the pose of body '{0}' at every sample: its origin ({0}_ox, _oy, "
          "_oz) or centre of mass ({0}_x, _y, _z) and its quaternion ({0}_qw, _qx, _qy, _qz{1}) "
          "columns, which the table lacks: add the output groups origin and quaternion (or "
          "position and quaternion), or use the report chasles simulate --html writes, which "
          "draws the poses recorded from the run's states",
          b.name, scene.planar ? ", or _theta" : ""));
    }
    const Vec3 p_BoBcm_B = b.mass_properties.p_BoBcm_B();
    for (size_t i = 0; i < r.rows.size(); ++i) {
      const auto at = [&](int column) { return r.rows[i][static_cast<size_t>(column)]; };
      const Quat q_WB = c.has_q()
                            ? Quat(at(c.q[0]), at(c.q[1]), at(c.q[2]), at(c.q[3])).normalized()
                            : Quat(Eigen::AngleAxisd(at(c.theta), Vec3::UnitZ()));
      StudyBodyPose& pose = out.rows[i][k];
      pose.q_WB = PositiveW(q_WB);
      if (c.has_origin()) {
        pose.p_WBo = Vec3(at(c.ox), at(c.oy), at(c.oz));
      } else {
        // Bo = Bcm − R_WB p_BoBcm_B.
        const Vec3 p_WBcm(at(c.x), at(c.y), c.z >= 0 ? at(c.z) : 0.0);
        pose.p_WBo = p_WBcm - q_WB.toRotationMatrix() * p_BoBcm_B;
      }
    }
    if (!c.has_origin()) out.derived.push_back(b.name);
  }
  return out;
}

std::vector<std::string> ReportColumns(const Scene& scene,
                                       const std::vector<std::string>& columns) {
  std::vector<std::string> out = columns;
  if (out.empty() || out.front() != "t") out.insert(out.begin(), "t");
  std::unordered_set<std::string> seen(out.begin(), out.end());
  for (const std::string& c :
       ExpandStudyColumns(scene, {"energy", "work", "residual", "reactions", "contacts"})) {
    if (seen.insert(c).second) out.push_back(c);
  }
  return out;
}

nlohmann::json ReportSceneJson(const Scene& scene, const std::string& kind) {
  nlohmann::json bodies = nlohmann::json::array();
  for (const SceneBody& b : scene.bodies) bodies.push_back(BodyJson(b));
  // Contact planes, so the page can draw the floor or incline a body rolls on.
  nlohmann::json planes = nlohmann::json::array();
  for (const SceneContact& c : scene.dynamics.contacts.contacts) {
    if (!c.with_plane) continue;
    planes.push_back({{"contact", c.name},
                      {"point", VecJson(c.plane_point_W)},
                      {"normal", VecJson(c.plane_normal_W)}});
  }
  return {{"format", kFormat},      {"kind", kind},  {"title", scene.title}, {"scene", scene.file},
          {"planar", scene.planar}, {"units", "SI"}, {"bodies", bodies},     {"planes", planes}};
}

namespace {

/// The forces of the force elements at each sample (the row snapshots' `forces`), one entry per
/// force an element applies to a body (gravity on each body, each end of a spring, ...):
/// element, body, and per sample the point and the force in W (f4; zeros at a sample where it
/// is absent). Pure moments are left out (nothing to draw at a point).
nlohmann::json AppliedForcesJson(const std::vector<StudySnapshot>& snapshots, size_t n) {
  nlohmann::json out = nlohmann::json::array();
  if (snapshots.size() != n) return out;
  // The k-th force of element e on body b, in the order first seen.
  using Key = std::tuple<std::string, std::string, int>;
  std::map<Key, size_t> index;
  std::vector<Key> keys;
  std::vector<std::vector<double>> values;
  for (size_t i = 0; i < n; ++i) {
    std::map<std::pair<std::string, std::string>, int> seen;
    for (const StudyAppliedForce& f : snapshots[i].forces) {
      if (f.is_moment) continue;
      const Key key{f.element, f.body, seen[{f.element, f.body}]++};
      auto [it, added] = index.emplace(key, keys.size());
      if (added) {
        keys.push_back(key);
        values.emplace_back(6 * n, 0.0);
      }
      double* v = values[it->second].data() + 6 * i;
      for (int a = 0; a < 3; ++a) v[a] = f.p_WP[a], v[3 + a] = f.F_W[a];
    }
  }
  for (size_t k = 0; k < keys.size(); ++k) {
    out.push_back({{"element", std::get<0>(keys[k])},
                   {"body", std::get<1>(keys[k])},
                   {"data", F4(values[k])}});
  }
  return out;
}

/// Every body's origin and quaternion at every sample, by the body's index (f8: the replay
/// draws them, and the tests compare them with the run's state to round-off).
nlohmann::json PosesJson(const Scene& scene, const StudyResult& r) {
  const size_t n = r.rows.size(), bodies = scene.bodies.size();
  const bool complete =
      r.row_poses.size() == n &&
      std::all_of(r.row_poses.begin(), r.row_poses.end(),
                  [&](const std::vector<StudyBodyPose>& row) { return row.size() == bodies; });
  if (!complete) {
    throw InputError(fmt::format(
        "the report needs every body's pose at every sample, and the run recorded {} of {} "
        "rows for {} bodies: run it with StudyOptions::record_row_poses (chasles simulate "
        "--html does), or read them from its table (PosesFromColumns)",
        r.row_poses.size(), n, bodies));
  }
  nlohmann::json poses = nlohmann::json::array();
  std::vector<double> origin(3 * n), quaternion(4 * n);
  for (size_t k = 0; k < bodies; ++k) {
    for (size_t i = 0; i < n; ++i) {
      const StudyBodyPose& p = r.row_poses[i][k];
      const Eigen::Vector4d q = QuatToWxyz(PositiveW(p.q_WB));
      for (int a = 0; a < 3; ++a) origin[3 * i + static_cast<size_t>(a)] = p.p_WBo[a];
      for (int a = 0; a < 4; ++a) quaternion[4 * i + static_cast<size_t>(a)] = q[a];
    }
    poses.push_back({{"body", k}, {"origin", F8(origin)}, {"quaternion", F8(quaternion)}});
  }
  return poses;
}

}  // namespace

nlohmann::json SimulationReportData(const Scene& scene, const StudyResult& r, PoseSource from) {
  nlohmann::json j = ReportSceneJson(scene, "simulate");
  const size_t n = r.rows.size();
  // Every column of the run, column-major: t exactly (the page's clock), the rest for
  // plotting. The poses the replay draws are data of their own, not columns.
  const std::vector<std::string> units = StudyColumnUnits(scene, r.columns);
  const std::vector<std::string> groups = StudyColumnGroups(scene, r.columns);
  nlohmann::json columns = nlohmann::json::array();
  std::vector<double> values(n);
  for (size_t c = 0; c < r.columns.size(); ++c) {
    for (size_t i = 0; i < n; ++i) values[i] = r.rows[i][c];
    const bool exact = c == 0;
    columns.push_back({{"name", r.columns[c]},
                       {"unit", units[c]},
                       {"group", groups[c]},
                       {"type", exact ? "f8" : "f4"},
                       {"data", exact ? F8(values) : F4(values)}});
  }
  j["samples"] = n;
  j["columns"] = columns;
  j["poses_from"] = from == PoseSource::kStates ? "states" : "columns";
  j["poses"] = PosesJson(scene, r);

  nlohmann::json events = nlohmann::json::array();
  for (const StudyEvent& e : r.events) {
    events.push_back({{"name", e.name}, {"t", e.t}, {"stopped", e.stopped}});
  }
  j["events"] = events;
  nlohmann::json changes = nlohmann::json::array();
  for (const StudyContactEvent& e : r.contact_events) {
    changes.push_back({{"t", e.t},
                       {"point", e.point},
                       {"contact", e.contact},
                       {"from", StudyContactModeName(e.from)},
                       {"to", StudyContactModeName(e.to)},
                       {"reason", ContactEventReasonName(e.reason)}});
  }
  j["contact_events"] = changes;
  nlohmann::json impacts = nlohmann::json::array();
  for (const StudyImpact& x : r.impacts) {
    impacts.push_back({{"t", x.t}, {"point", x.point}, {"energy_lost", x.energy_lost}});
  }
  j["impacts"] = impacts;
  nlohmann::json jumps = nlohmann::json::array();
  for (const StudyJump& x : r.jumps) {
    jumps.push_back(
        {{"t", x.t}, {"kind", StudyJumpKindName(x.kind)}, {"description", x.description}});
  }
  j["jumps"] = jumps;

  // Forces at each sample, from the row snapshots: a reaction's point and force (on the child,
  // in W); a contact point's position, normal force N n and friction force (on the body, in W).
  nlohmann::json reactions = nlohmann::json::array();
  nlohmann::json contacts = nlohmann::json::array();
  if (!r.row_snapshots.empty() && r.row_snapshots.size() == n) {
    const StudySnapshot& first = r.row_snapshots.front();
    for (size_t k = 0; k < first.reactions.size(); ++k) {
      std::vector<double> v;
      v.reserve(6 * n);
      for (const StudySnapshot& s : r.row_snapshots) {
        const bool has = k < s.reactions.size();
        for (int a = 0; a < 3; ++a) v.push_back(has ? s.reactions[k].p_WJ[a] : 0.0);
        for (int a = 0; a < 3; ++a) v.push_back(has ? s.reactions[k].F_Jc_W[a] : 0.0);
      }
      reactions.push_back(
          {{"name", first.reactions[k].name}, {"kind", first.reactions[k].kind}, {"data", F4(v)}});
    }
    for (size_t k = 0; k < first.contacts.size(); ++k) {
      std::vector<double> v;
      v.reserve(9 * n);
      std::string modes;
      for (const StudySnapshot& s : r.row_snapshots) {
        const bool has = k < s.contacts.size();
        const StudyContactPoint p = has ? s.contacts[k] : StudyContactPoint{};
        for (int a = 0; a < 3; ++a) v.push_back(p.p_WC[a]);
        for (int a = 0; a < 3; ++a) v.push_back(p.normal_force * p.n_W[a]);
        for (int a = 0; a < 3; ++a) v.push_back(p.friction_force_W[a]);
        // 0 separated, 1 sliding, 2 sticking: as the CSV's mode columns.
        modes += !has || p.mode.mode == ContactMode::kSeparated ? '0'
                 : p.mode.mode == ContactMode::kSliding         ? '1'
                                                                : '2';
      }
      contacts.push_back({{"name", first.contacts[k].point}, {"data", F4(v)}, {"modes", modes}});
    }
  }
  j["reactions"] = reactions;
  j["contacts"] = contacts;
  j["forces"] = AppliedForcesJson(r.row_snapshots, n);
  CheckFiniteJson(j, "the report data");
  return j;
}

nlohmann::json MassReportData(const Scene& scene) {
  nlohmann::json j = ReportSceneJson(scene, "mass");
  CheckFiniteJson(j, "the report data");
  return j;
}

namespace {

/// The bodies' frames in the scene's initial state (on its constraints): name, origin Bo and
/// quaternion q_WB.
nlohmann::json InitialPosesJson(const Scene& scene) {
  const StudyDefinition def = MakeStudyDefinition(scene);
  nlohmann::json poses = nlohmann::json::array();
  for (size_t b = 0; b < scene.bodies.size() && b < def.initial.bodies.size(); ++b) {
    const BodyState& s = def.initial.bodies[b];
    // Bo = Bcm - R_WB p_BoBcm_B.
    const Vec3 p_WBo =
        s.p_WBcm - s.q_WB.toRotationMatrix() * scene.bodies[b].mass_properties.p_BoBcm_B();
    poses.push_back({{"name", scene.bodies[b].name},
                     {"origin", VecJson(p_WBo)},
                     {"quaternion", QuatJson(s.q_WB)}});
  }
  return poses;
}

}  // namespace

nlohmann::json SweepReportData(const Scene& scene, const SweepTable& table,
                               const std::string& command) {
  nlohmann::json j = ReportSceneJson(scene, "sweep");
  j["command"] = command;
  if (command != "mass") j["poses"] = InitialPosesJson(scene);
  nlohmann::json base = nlohmann::json::object();
  for (const auto& [name, q] : scene.parameters) base[name] = q.value;
  j["parameter_values"] = base;
  j["sweep"] = SweepJson(table);
  CheckFiniteJson(j, "the report data");
  return j;
}

nlohmann::json SolveReportData(const Scene& scene, const SolveReport& report) {
  nlohmann::json j = ReportSceneJson(scene, "solve");
  // The solved instant is the scene's initial state (on its constraints).
  j["poses"] = InitialPosesJson(scene);
  nlohmann::json reactions = nlohmann::json::array();
  for (const ReactionReport& x : report.solution.reactions) {
    reactions.push_back({{"name", x.name},
                         {"kind", x.kind},
                         {"point", VecJson(x.p_WJ)},
                         {"force", VecJson(x.F_Jc_W)},
                         {"moment", VecJson(x.M_Jc_W)}});
  }
  j["solve_reactions"] = reactions;
  nlohmann::json contacts = nlohmann::json::array();
  for (const ContactPointReport& c : report.contacts) {
    contacts.push_back({{"name", c.point},
                        {"regime", c.Regime()},
                        {"position", VecJson(c.out.p_WC)},
                        {"normal_force", VecJson(c.out.normal_force * c.out.n_W)},
                        {"friction_force", VecJson(c.out.friction_force_W)}});
  }
  j["solve_contacts"] = contacts;
  nlohmann::json accel = nlohmann::json::array();
  for (const BodyAccelerationReport& a : report.solution.bodies) {
    accel.push_back({{"name", a.name},
                     {"acceleration", VecJson(a.a_WBcm_W)},
                     {"angular_acceleration", VecJson(a.alpha_WB_W)}});
  }
  j["accelerations"] = accel;
  CheckFiniteJson(j, "the report data");
  return j;
}

}  // namespace chasles
