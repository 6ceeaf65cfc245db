#include <algorithm>
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

std::vector<ColumnInfo> AllColumns(const Scene& scene) {
  std::vector<ColumnInfo> cols;
  cols.push_back({"t", "t", -1, "t", ""});
  if (scene.planar) {
    // Planar scenes: x, y of the centre of mass, θ (continuous), vx, vy, ω and α about z
    // (chapter eqs. 8.41-8.43). x, y, vx, vy are the same columns as in the 3-D groups.
    for (size_t b = 0; b < scene.bodies.size(); ++b) {
      for (const char* s : {"x", "y", "theta", "vx", "vy", "omega", "alpha"}) {
        cols.push_back({scene.bodies[b].name + "_" + s, "planar", static_cast<int>(b), s, ""});
      }
    }
  }
  for (const auto& g : BodyGroups()) {
    for (size_t b = 0; b < scene.bodies.size(); ++b) {
      for (const char* s : g.suffixes) {
        cols.push_back({scene.bodies[b].name + "_" + s, g.group, static_cast<int>(b), s, ""});
      }
    }
  }
  for (const auto& g : PointGroups()) {
    for (size_t b = 0; b < scene.bodies.size(); ++b) {
      for (const ScenePoint& p : scene.bodies[b].points) {
        for (const auto& [suffix, quantity] : g.columns) {
          ColumnInfo c{scene.bodies[b].name + "_" + p.name + "_" + suffix, g.group,
                       static_cast<int>(b), quantity, ""};
          c.p_BoP_B = p.p_BoP_B;
          cols.push_back(c);
        }
      }
    }
  }
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

std::vector<std::string> ExpandColumn(const Scene& scene, const std::string& name,
                                      std::string* why) {
  const std::vector<ColumnInfo> all = AllColumns(scene);
  std::vector<std::string> out;
  static const std::vector<std::string> ledger = {
      "energy", "work", "residual", "momentum", "angular_momentum", "angular_momentum_origin"};
  for (const auto& c : all) {
    const bool in_ledger =
        name == "ledger" && std::find(ledger.begin(), ledger.end(), c.group) != ledger.end();
    const bool all_reactions = name == "reactions_3d" && c.group == "reactions";
    const bool match = c.group == name || c.name == name || in_ledger || all_reactions;
    if (match && std::find(out.begin(), out.end(), c.name) == out.end()) out.push_back(c.name);
  }
  if (out.empty() && why) {
    std::vector<std::string> known = ColumnGroups();
    for (const auto& c : all) known.push_back(c.name);
    *why = fmt::format("unknown column '{}'{}; groups: {}; or a single column such as '{}'", name,
                       DidYouMean(name, known), fmt::join(ColumnGroups(), ", "),
                       all.size() > 1 ? all[1].name : "t");
  }
  return out;
}

std::vector<std::string> DefaultColumns(const Scene& scene) {
  std::vector<std::string> cols;
  if (scene.planar) {
    for (const char* g : {"t", "planar", "reactions", "energy", "W_nc", "residual"}) {
      for (auto& c : ExpandColumn(scene, g, nullptr)) cols.push_back(std::move(c));
    }
    return cols;
  }
  for (const char* g : {"t", "position", "quaternion", "velocity", "angular_velocity", "energy",
                        "W_nc", "residual"}) {
    for (auto& c : ExpandColumn(scene, g, nullptr)) cols.push_back(std::move(c));
  }
  return cols;
}

}  // namespace chasles::scene_internal

namespace chasles {

std::vector<std::string> SelectColumns(const Scene& scene, const std::vector<std::string>& names) {
  std::vector<std::string> columns = {"t"};
  for (const std::string& name : names) {
    std::string why;
    const std::vector<std::string> expanded = scene_internal::ExpandColumn(scene, name, &why);
    if (expanded.empty()) throw SceneError("command line", 0, 0, "--columns", why);
    for (const auto& e : expanded) {
      if (std::find(columns.begin(), columns.end(), e) == columns.end()) columns.push_back(e);
    }
  }
  return columns;
}

}  // namespace chasles
