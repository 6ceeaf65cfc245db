#include <algorithm>
#include <tuple>
#include <unordered_set>
#include <utility>

#include <fmt/format.h>

#include "chasles/scene/scene_error.h"
#include "chasles/scene/study.h"
#include "chasles/suggest.h"
#include "internal/study_columns.h"

namespace chasles::scene_internal {

namespace {

struct BodyGroup {
  const char* group;
  std::vector<const char*> suffixes;
};

// Per-body groups and the suffixes of their columns.
const std::vector<BodyGroup>& BodyGroups() {
  static const std::vector<BodyGroup> groups = {
      {"position", {"x", "y", "z"}},
      {"origin", {"ox", "oy", "oz"}},
      {"quaternion", {"qw", "qx", "qy", "qz"}},
      {"euler", {"yaw", "pitch", "roll"}},
      {"tilt", {"tilt"}},
      {"velocity", {"vx", "vy", "vz"}},
      {"speed", {"speed"}},
      {"angular_velocity", {"wx", "wy", "wz"}},
      {"angular_velocity_body", {"wbx", "wby", "wbz"}},
      {"acceleration", {"ax", "ay", "az"}},
      {"angular_acceleration", {"alx", "aly", "alz"}},
      {"angular_acceleration_body", {"albx", "alby", "albz"}},
      // The body's own energy, momenta and their rates: T = ½ m v² + ½ ωᵀ I ω, P = m v, H = I ω
      // about its centre of mass, H_O about the world origin, dH/dt = I α + ω × I ω and
      // dH_O/dt = dH/dt + r_cm × m a_cm (ΣM = dH/dt, eq. 8.30).
      {"body_energy", {"T_trans", "T_rot", "T"}},
      {"body_momentum", {"Px", "Py", "Pz"}},
      {"body_angular_momentum", {"Hx", "Hy", "Hz"}},
      {"body_angular_momentum_origin", {"HOx", "HOy", "HOz"}},
      {"angular_momentum_rate", {"dHx", "dHy", "dHz"}},
      {"angular_momentum_rate_origin", {"dHOx", "dHOy", "dHOz"}},
  };
  return groups;
}

// A planar scene's per-body columns (group "planar"): x, y of the centre of mass, θ
// (continuous), vx, vy, ω and α about z (chapter eqs. 8.41-8.43). x, y, vx, vy are the same
// columns as in the 3-D groups.
const std::vector<const char*>& PlanarSuffixes() {
  static const std::vector<const char*> suffixes = {"x",  "y",     "theta", "vx",
                                                    "vy", "omega", "alpha"};
  return suffixes;
}

struct PointGroup {
  const char* group;
  /// Column suffixes and the quantities they read.
  std::vector<std::pair<const char*, const char*>> columns;
};

// Per named body point "<body>_<point>_<suffix>": v_P = v + ω × r and
// a_P = a + α × r + ω × (ω × r), r from the centre of mass to P, in W.
const std::vector<PointGroup>& PointGroups() {
  static const std::vector<PointGroup> groups = {
      {"point_velocity", {{"vx", "pvx"}, {"vy", "pvy"}, {"vz", "pvz"}}},
      {"point_acceleration", {{"ax", "pax"}, {"ay", "pay"}, {"az", "paz"}}},
  };
  return groups;
}

}  // namespace

std::vector<std::string> ColumnGroups() {
  std::vector<std::string> g;
  for (const auto& b : BodyGroups()) g.emplace_back(b.group);
  for (const auto& b : PointGroups()) g.emplace_back(b.group);
  for (const char* s : {"energy", "work", "residual", "momentum", "angular_momentum",
                        "angular_momentum_origin", "ledger", "reactions", "contacts"}) {
    g.emplace_back(s);
  }
  g.emplace_back("planar");
  g.emplace_back("reactions_3d");
  g.emplace_back("momentum_3d");
  return g;
}

namespace {

/// The columns that are not a body's, in the order after the bodies': the ledger, each
/// force's and constraint's work, the momenta, the reactions and the contacts. Some tens per
/// force, constraint and contact point: few enough to list.
std::vector<ColumnInfo> SceneColumns(const Scene& scene) {
  std::vector<ColumnInfo> cols;
  for (const char* s : {"T_trans", "T_rot", "T", "V", "E"})
    cols.push_back({s, "energy", -1, s, ""});
  cols.push_back({"W_nc", "work", -1, "W_nc", ""});
  for (const auto& f : scene.dynamics.forces) {
    cols.push_back({"W_" + f.name, "work", -1, "W", f.name});
  }
  // Work of each joint, rolling contact and driver (zero for the ideal ones).
  for (const auto& n : scene.dynamics.constraints.names()) {
    cols.push_back({"W_" + n, "work", -1, "W", n});
  }
  if (!scene.dynamics.contacts.empty()) {
    // Work of sliding friction, of rolling resistance and the kinetic energy lost in impacts
    // at all contacts since t = 0 (each <= 0; part of W_nc).
    for (const char* s : {"W_friction", "W_rolling", "W_impacts"}) {
      cols.push_back({s, "work", -1, s, ""});
    }
  }
  cols.push_back({"dissipated", "work", -1, "dissipated", ""});
  cols.push_back({"jumps", "work", -1, "jumps", ""});
  cols.push_back({"residual", "residual", -1, "residual", ""});
  // A planar scene's momentum is in the plane and its angular momenta about z (eqs.
  // 8.34-8.38): the other components are zero by construction and stay selectable by name
  // only (the group momentum_3d), as the out-of-plane reactions do.
  const auto momentum = [&](const char* s, const char* group) {
    const std::string q = s;
    const bool in_plane = q[0] == 'P' ? q != "Pz" : q.back() == 'z';
    cols.push_back({s, scene.planar && !in_plane ? "momentum_3d" : group, -1, s, ""});
  };
  for (const char* s : {"Px", "Py", "Pz"}) momentum(s, "momentum");
  for (const char* s : {"Hx", "Hy", "Hz"}) momentum(s, "angular_momentum");
  for (const char* s : {"HOx", "HOy", "HOz"}) momentum(s, "angular_momentum_origin");
  // Reaction on the child at the joint point, in W, then in the child's frame B
  // (Data::constraints), then in the parent's frame P (W for a joint to the world). A planar
  // scene's reactions are Fx, Fy and Mz; the out-of-plane components (held by the bodies' plane
  // constraints, not physical for a planar body) stay selectable one by one or as the group
  // reactions_3d.
  for (const auto& n : scene.dynamics.constraints.names()) {
    for (const char* s : {"Fx", "Fy", "Fz", "Mx", "My", "Mz"}) {
      const std::string q = s;
      const bool in_plane = q == "Fx" || q == "Fy" || q == "Mz";
      cols.push_back(
          {n + "_" + s, scene.planar && !in_plane ? "reactions_3d" : "reactions", -1, s, n});
    }
    for (const char* frame : {"_B", "_P"}) {
      for (const char* c : {"Fx", "Fy", "Fz", "Mx", "My", "Mz"}) {
        const std::string q = std::string(c) + frame;
        const bool in_plane = q[0] == 'F' ? q[1] != 'z' : q[1] == 'z';  // Fx, Fy, Mz
        cols.push_back(
            {n + "_" + q, scene.planar && !in_plane ? "reactions_3d" : "reactions", -1, q, n});
      }
    }
  }
  // Per contact point: mode (0 separated, 1 sliding, 2 sticking), normal force N, friction
  // force size f, slip speed, gap (Data::contact_points).
  const std::vector<std::string> labels = scene.dynamics.contacts.point_labels();
  for (size_t p = 0; p < labels.size(); ++p) {
    for (const char* s : {"mode", "N", "f", "slip", "gap"}) {
      ColumnInfo c{labels[p] + "_" + s, "contacts", -1, s, ""};
      c.point = static_cast<int>(p);
      cols.push_back(c);
    }
  }
  return cols;
}

}  // namespace

ColumnIndex::ColumnIndex(const Scene& scene) : scene_(scene), others_(SceneColumns(scene)) {
  // The first of equal names wins, as in the order of the columns.
  for (size_t i = 0; i < scene.bodies.size(); ++i) body_.emplace(scene.bodies[i].name, i);
  for (size_t i = 0; i < others_.size(); ++i) other_.emplace(others_[i].name, i);
  for (size_t b = 0; b < scene.bodies.size(); ++b) {
    const auto& points = scene.bodies[b].points;
    for (size_t p = 0; p < points.size(); ++p) {
      point_.emplace(scene.bodies[b].name + "_" + points[p].name, std::make_pair(b, p));
    }
  }
}

ColumnInfo ColumnIndex::BodyColumn(size_t b, const char* group, const char* suffix) const {
  return {scene_.bodies[b].name + "_" + suffix, group, static_cast<int>(b), suffix, ""};
}

ColumnInfo ColumnIndex::PointColumn(size_t b, size_t p, size_t group, size_t k) const {
  const ScenePoint& point = scene_.bodies[b].points[p];
  const auto& [suffix, quantity] = PointGroups()[group].columns[k];
  ColumnInfo c{scene_.bodies[b].name + "_" + point.name + "_" + suffix, PointGroups()[group].group,
               static_cast<int>(b), quantity, ""};
  c.p_BoP_B = point.p_BoP_B;
  return c;
}

std::optional<ColumnInfo> ColumnIndex::Find(const std::string& name) const {
  if (name == "t") return ColumnInfo{"t", "t", -1, "t", ""};
  // A body's column is "<body>_<suffix>": every split at an underscore whose head is a body
  // and whose tail a suffix is a candidate; the first in the columns' order (the planar ones,
  // then group by group, body by body) wins, as the first of equal names would.
  std::optional<ColumnInfo> best;
  std::tuple<int, size_t, size_t, size_t> best_key{3, 0, 0, 0};
  for (size_t at = name.find('_'); at != std::string::npos; at = name.find('_', at + 1)) {
    const auto body = body_.find(name.substr(0, at));
    if (body == body_.end()) continue;
    const std::string suffix = name.substr(at + 1);
    const size_t b = body->second;
    if (scene_.planar) {
      const auto& planar = PlanarSuffixes();
      for (size_t k = 0; k < planar.size(); ++k) {
        if (suffix != planar[k]) continue;
        const std::tuple<int, size_t, size_t, size_t> key{0, b, k, 0};
        if (key < best_key) best_key = key, best = BodyColumn(b, "planar", planar[k]);
      }
    }
    const auto& groups = BodyGroups();
    for (size_t g = 0; g < groups.size(); ++g) {
      for (size_t k = 0; k < groups[g].suffixes.size(); ++k) {
        if (suffix != groups[g].suffixes[k]) continue;
        const std::tuple<int, size_t, size_t, size_t> key{1, g, b, k};
        if (key < best_key)
          best_key = key, best = BodyColumn(b, groups[g].group, groups[g].suffixes[k]);
      }
    }
  }
  if (best) return best;
  // A named point's column is "<body>_<point>_<suffix>".
  const size_t last = name.rfind('_');
  if (last != std::string::npos) {
    const auto point = point_.find(name.substr(0, last));
    const std::string suffix = name.substr(last + 1);
    if (point != point_.end()) {
      for (size_t g = 0; g < PointGroups().size(); ++g) {
        for (size_t k = 0; k < PointGroups()[g].columns.size(); ++k) {
          if (suffix == PointGroups()[g].columns[k].first) {
            return PointColumn(point->second.first, point->second.second, g, k);
          }
        }
      }
    }
  }
  const auto other = other_.find(name);
  if (other != other_.end()) return others_[other->second];
  return std::nullopt;
}

bool ColumnIndex::IsGroup(const std::string& name) {
  const std::vector<std::string> groups = ColumnGroups();
  return std::find(groups.begin(), groups.end(), name) != groups.end();
}

void ColumnIndex::AddGroup(const std::string& name, std::vector<std::string>& out) const {
  const size_t n = scene_.bodies.size();
  // "<body>_<suffix>", made in place: a scene of 100,000 bodies has 1.3 million of them.
  const auto add_body_columns = [&](const auto& suffixes) {
    for (size_t b = 0; b < n; ++b) {
      const std::string& body = scene_.bodies[b].name;
      for (const char* s : suffixes) {
        const std::string_view suffix(s);
        std::string& column = out.emplace_back();
        column.reserve(body.size() + 1 + suffix.size());
        column.append(body).append(1, '_').append(suffix);
      }
    }
  };
  if (name == "planar" && scene_.planar) add_body_columns(PlanarSuffixes());
  for (const BodyGroup& g : BodyGroups()) {
    if (name == g.group) add_body_columns(g.suffixes);
  }
  for (size_t g = 0; g < PointGroups().size(); ++g) {
    if (name != PointGroups()[g].group) continue;
    for (size_t b = 0; b < n; ++b) {
      for (size_t p = 0; p < scene_.bodies[b].points.size(); ++p) {
        for (size_t k = 0; k < PointGroups()[g].columns.size(); ++k) {
          out.push_back(PointColumn(b, p, g, k).name);
        }
      }
    }
  }
  static const std::vector<std::string> ledger = {
      "energy", "work", "residual", "momentum", "angular_momentum", "angular_momentum_origin"};
  for (const ColumnInfo& c : others_) {
    const bool in_ledger =
        name == "ledger" && std::find(ledger.begin(), ledger.end(), c.group) != ledger.end();
    const bool all_reactions = name == "reactions_3d" && c.group == "reactions";
    if (c.group == name || in_ledger || all_reactions) out.push_back(c.name);
  }
}

std::vector<std::string> ColumnIndex::Expand(const std::string& name) const {
  std::vector<std::string> out;
  ExpandInto(name, out);
  return out;
}

void ColumnIndex::ExpandInto(const std::string& name, std::vector<std::string>& out) const {
  const size_t first = out.size();
  if (IsGroup(name)) AddGroup(name, out);
  const std::optional<ColumnInfo> one = Find(name);
  if (one && std::find(out.begin() + static_cast<std::ptrdiff_t>(first), out.end(), one->name) ==
                 out.end()) {
    out.push_back(one->name);
  }
}

std::string ColumnIndex::Unknown(const std::string& name) const {
  // Suggestions from the groups, the scene's own columns and the columns of the bodies whose
  // names start the unknown one (not every column of every body: there may be millions).
  std::vector<std::string> known = ColumnGroups();
  for (const ColumnInfo& c : others_) known.push_back(c.name);
  for (size_t at = name.find('_'); at != std::string::npos; at = name.find('_', at + 1)) {
    const auto body = body_.find(name.substr(0, at));
    if (body == body_.end()) continue;
    for (const BodyGroup& g : BodyGroups()) {
      for (const char* s : g.suffixes) known.push_back(body->first + "_" + s);
    }
  }
  const std::string example =
      scene_.bodies.empty() ? std::string("t") : scene_.bodies.front().name + "_x";
  return fmt::format("unknown column '{}'{}; groups: {}; or a single column such as '{}'", name,
                     DidYouMean(name, known), fmt::join(ColumnGroups(), ", "), example);
}

std::vector<std::string> ExpandColumn(const Scene& scene, const std::string& name,
                                      std::string* why) {
  const ColumnIndex index(scene);
  std::vector<std::string> out = index.Expand(name);
  if (out.empty() && why) *why = index.Unknown(name);
  return out;
}

std::vector<std::string> DefaultColumns(const Scene& scene) {
  const ColumnIndex index(scene);
  std::vector<std::string> cols;
  // t, 13 per body (position, quaternion, velocity, angular velocity) and the scene's own.
  cols.reserve(13 * scene.bodies.size() + 64);
  const std::vector<const char*> groups =
      scene.planar
          ? std::vector<const char*>{"t", "planar", "reactions", "energy", "W_nc", "residual"}
          : std::vector<const char*>{"t",        "position",         "quaternion",
                                     "velocity", "angular_velocity", "energy",
                                     "W_nc",     "residual"};
  for (const char* g : groups) index.ExpandInto(g, cols);
  return cols;
}

}  // namespace chasles::scene_internal

namespace chasles {

std::vector<std::string> SelectColumns(const Scene& scene, const std::vector<std::string>& names) {
  const scene_internal::ColumnIndex index(scene);
  std::vector<std::string> columns = {"t"};
  std::unordered_set<std::string> seen = {"t"};
  for (const std::string& name : names) {
    const std::vector<std::string> expanded = index.Expand(name);
    if (expanded.empty()) throw SceneError("command line", 0, 0, "--columns", index.Unknown(name));
    for (const auto& e : expanded) {
      if (seen.insert(e).second) columns.push_back(e);
    }
  }
  return columns;
}

}  // namespace chasles
