// The text report of `chasles solve`: the instantaneous problem of chapter 8.2-8.3 at a scene's
// initial state, every body's acceleration, every constraint's reaction, each contact point's
// mode and forces, the energies and momenta, and the checks.

#include "chasles/report/solve_text.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "chasles/report/certificate_text.h"
#include "chasles/report/json_report.h"
#include "chasles/report/result_names.h"
#include "chasles/report/solve_json.h"

namespace chasles {

namespace {

/// The scales of the report's quantities: the largest of each kind over bodies and reactions.
struct ReportScales {
  double a = 0.0, alpha = 0.0, force = 0.0, moment = 0.0, p = 0.0, h = 0.0, v = 0.0, w = 0.0,
         hdot = 0.0;
};

ReportScales CalcScales(const SolveReport& s) {
  ReportScales k;
  for (const auto& b : s.solution.bodies) {
    k.a = std::max(k.a, b.a_WBcm_W.stableNorm());
    k.alpha = std::max(k.alpha, b.alpha_WB_W.stableNorm());
  }
  double arm = 0.0;
  for (const ContactPointReport& c : s.contacts) {
    k.force = std::max({k.force, c.out.normal_force, c.out.friction_force_W.stableNorm()});
  }
  for (const auto& r : s.solution.reactions) {
    k.force = std::max(k.force, r.F_Jc_W.stableNorm());
    k.moment = std::max(k.moment, r.M_Jc_W.stableNorm());
    arm = std::max(arm, r.p_WJ.stableNorm());
  }
  // A moment's round-off comes from forces times lever arms as well as from other moments.
  k.moment = std::max(k.moment, k.force * arm);
  for (const BodyMotionReport& m : s.motion) {
    k.p = std::max(k.p, m.P.stableNorm());
    k.h = std::max({k.h, m.H_cm.stableNorm(), m.H_O.stableNorm()});
    k.v = std::max(k.v, m.v_WBcm_W.stableNorm());
    k.w = std::max(k.w, m.w_WB_W.stableNorm());
    k.hdot = std::max({k.hdot, m.Hdot_cm.stableNorm(), m.Hdot_O.stableNorm(), k.moment});
    for (const PointMotionReport& p : m.points) {
      k.v = std::max(k.v, p.v_WP_W.stableNorm());
      k.a = std::max(k.a, p.a_WP_W.stableNorm());
    }
  }
  return k;
}

/// The velocities, the named points' velocities and accelerations and dH/dt of every body.
std::string KinematicsText(const SolveReport& s, const ReportScales& k, const Show& u) {
  std::string out;
  // ΣM = dH/dt (eq. 8.30): the Checks section's angular momentum balance compares the
  // moments on each body with this dH_cm/dt.
  out +=
      "\nVelocities, named points and dH/dt (about each centre of mass; dH_O/dt about the "
      "origin)\n";
  const auto hdot = [&](const Vec3& cm, const Vec3& o) {
    if (s.planar) {
      return fmt::format("    dH_z/dt  {}\n    dH_Oz/dt {}\n", u(u.Clean(cm.z(), k.hdot), kMoment),
                         u(u.Clean(o.z(), k.hdot), kMoment));
    }
    return fmt::format("    dH/dt   {}\n    dH_O/dt {}\n", u(cm, kMoment, Angular::kNo, k.hdot),
                       u(o, kMoment, Angular::kNo, k.hdot));
  };
  for (const BodyMotionReport& m : s.motion) {
    out += fmt::format("  {}\n", m.name);
    if (s.planar) {
      out += fmt::format("    v_x   {}\n    v_y   {}\n    omega {}\n",
                         u(u.Clean(m.v_WBcm_W.x(), k.v), kVelocity),
                         u(u.Clean(m.v_WBcm_W.y(), k.v), kVelocity),
                         u(u.Clean(m.w_WB_W.z(), k.w), kRate, Angular::kYes));
    } else {
      out +=
          fmt::format("    v_cm  {}\n    omega {}\n", u(m.v_WBcm_W, kVelocity, Angular::kNo, k.v),
                      u(m.w_WB_W, kRate, Angular::kYes, k.w));
    }
    for (const PointMotionReport& p : m.points) {
      if (s.planar) {
        out +=
            fmt::format("    point {} at {}: v {}, a {}\n", p.name,
                        u.InPlane(true, p.p_WP, kLength), u.InPlane(true, p.v_WP_W, kVelocity, k.v),
                        u.InPlane(true, p.a_WP_W, kAcceleration, k.a));
      } else {
        out += fmt::format("    point {} at {}\n      v {}\n      a {}\n", p.name,
                           u(p.p_WP, kLength), u(p.v_WP_W, kVelocity, Angular::kNo, k.v),
                           u(p.a_WP_W, kAcceleration, Angular::kNo, k.a));
      }
    }
    out += hdot(m.Hdot_cm, m.Hdot_O);
  }
  if (s.motion.size() > 1) {
    out += "  all bodies (dH/dt about the system's centre of mass)\n";
    out += hdot(s.total.Hdot_cm, s.total.Hdot_O);
  }
  return out;
}

/// Each body's acceleration and angular acceleration.
std::string AccelerationsText(const SolveReport& s, const ReportScales& k, const Show& u) {
  std::string out;
  for (const auto& b : s.solution.bodies) {
    if (s.planar) {
      out +=
          fmt::format("  {}\n    a_x   {}\n    a_y   {}\n    alpha {}\n", b.name,
                      u(u.Clean(b.a_WBcm_W.x(), k.a), kAcceleration),
                      u(u.Clean(b.a_WBcm_W.y(), k.a), kAcceleration),
                      u(u.Clean(b.alpha_WB_W.z(), k.alpha), kAngularAcceleration, Angular::kYes));
      continue;
    }
    out += fmt::format("  {}\n    a_cm  {}\n    alpha {}\n", b.name,
                       u(b.a_WBcm_W, kAcceleration, Angular::kNo, k.a),
                       u(b.alpha_WB_W, kAngularAcceleration, Angular::kYes, k.alpha));
  }
  return out;
}

/// Each constraint's reaction; for a string its mode, for rolling the friction it needs.
std::string ReactionsText(const SolveReport& s, const ReportScales& k, const Show& u) {
  if (s.solution.reactions.empty()) return "";
  std::string out = "\nReactions (on the child at the joint point)\n";
  for (size_t i = 0; i < s.solution.reactions.size(); ++i) {
    const ReactionReport& r = s.solution.reactions[i];
    if (s.planar) {
      out += fmt::format("  {} ({}) at {}\n", r.name, r.kind, u.InPlane(true, r.p_WJ, kLength));
      out += fmt::format("    Fx {}, Fy {}, Mz {}\n", u(u.Clean(r.F_Jc_W.x(), k.force), kForce),
                         u(u.Clean(r.F_Jc_W.y(), k.force), kForce),
                         u(u.Clean(r.M_Jc_W.z(), k.moment), kMoment));
    } else {
      out += fmt::format("  {} ({}) at {}\n", r.name, r.kind, u(r.p_WJ, kLength));
      out += fmt::format("    force  {}\n", u(r.F_Jc_W, kForce, Angular::kNo, k.force));
      out += fmt::format("    moment {}\n", u(r.M_Jc_W, kMoment, Angular::kNo, k.moment));
      // What a bearing fixed in the child feels, and what its housing (the parent) feels;
      // a joint to the world has the world as its parent frame (the lines above).
      out += fmt::format("    in the child's frame: force {}, moment {}\n",
                         u(r.F_Jc_B, kForce, Angular::kNo, k.force),
                         u(r.M_Jc_B, kMoment, Angular::kNo, k.moment));
      if (r.parent != kWorld) {
        out += fmt::format("    in the parent's frame: force {}, moment {}\n",
                           u(r.F_Jc_P, kForce, Angular::kNo, k.force),
                           u(r.M_Jc_P, kMoment, Angular::kNo, k.moment));
      }
    }
    if (r.mode) {
      out += fmt::format(
          "    {}: tension {}, slack {} (chosen by T >= 0, slack acceleration >= 0, "
          "T * slack acceleration = 0)\n",
          StringModeName(*r.mode), u(u.Clean(r.lambda[0], k.force), kForce), u(r.gap, kLength));
    }
    if (r.is_rolling) {
      out +=
          fmt::format("    normal force {}, friction {}, f/N = {:.9g}", u(r.normal_force, kForce),
                      u(r.friction_W.norm(), kForce), r.friction_needed);
      if (!std::isnan(s.mu_s[i])) {
        out += fmt::format(" against mu_s = {:.6g}: {}", s.mu_s[i],
                           r.friction_needed <= s.mu_s[i] ? "rolls" : "slips");
      }
      out += "\n";
    }
  }
  return out;
}

/// A sticking round point's rolling resistance: the moment holding its rolling, or resisting it.
std::string RollingResistanceText(const SolveReport& s, const ContactPointReport& c,
                                  const ReportScales& k, const Show& u) {
  const Vec3& M = c.out.rolling_moment_W;
  const double cap = c.out.rolling_moment_capacity;
  const double scale = std::max({k.moment, M.stableNorm(), cap});
  // A planar scene's moments are about z.
  const std::string moment =
      s.planar ? "Mz " + u(u.Clean(M.z(), scale), kMoment) : u(M, kMoment, Angular::kNo, scale);
  if (c.out.rolling_held) {
    return fmt::format(
        "    rolling held: moment {} (|M| {}) within mu_r N R = {} (|M|/(mu_r N R) = {:.9g})\n",
        moment, u(M.norm(), kMoment), u(cap, kMoment), cap > 0.0 ? M.norm() / cap : 0.0);
  }
  return fmt::format("    rolling: moment {} = mu_r N R = {} against the rolling (mu_r = {:.6g})\n",
                     moment, u(cap, kMoment), c.mu_r);
}

/// Each contact point's mode and forces.
std::string ContactsText(const SolveReport& s, const ReportScales& k, const Show& u) {
  if (s.contacts.empty()) return "";
  std::string out = "\nContacts (modes chosen at the initial state; friction on the body)\n";
  for (const ContactPointReport& c : s.contacts) {
    out += fmt::format("  {}: {} ({})\n", c.point, c.Regime(), ContactModeName(c.out.mode));
    if (c.out.mode == ContactMode::kSeparated) {
      out += fmt::format("    gap {}\n", u(c.out.gap, kLength));
      continue;
    }
    out += fmt::format("    normal force {}, friction {} (|f| {})\n", u(c.out.normal_force, kForce),
                       u.InPlane(s.planar, c.out.friction_force_W, kForce, k.force),
                       u(c.out.friction_force_W.norm(), kForce));
    if (c.out.mode == ContactMode::kSticking) {
      out += fmt::format("    f/N = {:.9g} against mu_s = {:.6g}\n", c.FrictionRatio(), c.mu_s);
      if (c.round && c.mu_r > 0.0) out += RollingResistanceText(s, c, k, u);
    } else {
      out += fmt::format("    slip velocity {}, f/N = mu_k = {:.6g}\n",
                         u.InPlane(s.planar, c.out.slip_velocity_W, kVelocity), c.mu_k);
    }
  }
  return out;
}

}  // namespace

std::string SolveText(const Scene& scene, const SolveReport& s, const TextOptions& options) {
  // Every value of the report is in the JSON form: checked there first, by name.
  CheckFiniteJson(SolveJson(s), "the solve report");
  const UnitSystem units = TextUnits(scene, options);
  const Show u{units, 9, kRunRoundOff, "a value of the solve report"};
  std::string out = TitleLine(scene);
  out += fmt::format(
      "Instantaneous solution at the initial state (report in {} units; JSON and CSV in SI; "
      "{})\n\nAccelerations\n",
      units.spec(), s.planar ? "planar: x-y plane, moments about z" : "world frame");
  const ReportScales k = CalcScales(s);
  out += AccelerationsText(s, k, u);
  out += ReactionsText(s, k, u);
  out += ContactsText(s, k, u);
  out += "\nKinetic energy and momenta (H about each centre of mass, H_O about the origin)\n";
  const auto motion = [&out, &k, &s, &u](const BodyMotionReport& m, const char* cm) {
    out += fmt::format("    T {} (translational {}, rotational {})\n",
                       u.Energy(m.T_trans + m.T_rot), u.Energy(m.T_trans), u.Energy(m.T_rot));
    if (s.planar) {
      // In the plane: p = (p_x, p_y), H about z (eq. 8.38).
      out += fmt::format("    p   {}\n", u.InPlane(true, m.P, kMomentum, k.p));
      out +=
          fmt::format("    H_z {} (about {})\n", u(u.Clean(m.H_cm.z(), k.h), kAngularMomentum), cm);
      out += fmt::format("    H_Oz {}\n", u(u.Clean(m.H_O.z(), k.h), kAngularMomentum));
      return;
    }
    out += fmt::format("    p   {}\n", u(m.P, kMomentum, Angular::kNo, k.p));
    out +=
        fmt::format("    H   {} (about {})\n", u(m.H_cm, kAngularMomentum, Angular::kNo, k.h), cm);
    out += fmt::format("    H_O {}\n", u(m.H_O, kAngularMomentum, Angular::kNo, k.h));
  };
  for (const BodyMotionReport& m : s.motion) {
    out += fmt::format("  {}\n", m.name);
    motion(m, "its centre of mass");
  }
  if (s.motion.size() > 1) {
    out += "  all bodies\n";
    motion(s.total, "the system's centre of mass");
  }
  out += KinematicsText(s, k, u);
  for (const auto& w : s.solution.warnings) out += fmt::format("warning: {}\n", w);
  for (const auto& w : s.certificate.FailureMessages()) out += fmt::format("warning: {}\n", w);
  out += CertificateText(s.certificate);
  return out;
}

}  // namespace chasles
