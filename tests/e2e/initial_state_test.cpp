// Initial states that violate the constraints (an error naming constraint, residual and what
// to give; or, with `project_initial: true`, a projection whose every change is a warning) and
// redundant supports (the indeterminate reaction components named, a determinate model
// suggested, reactions independent of the unit of length). docs/constraints.md.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "cli_runner.h"

namespace chasles::test {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string Write(const std::string& name, const std::string& text) {
  const std::filesystem::path p = OutDir("initial") / name;
  std::ofstream(p) << text;
  return p.string();
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  if (at == std::string::npos) throw std::runtime_error("no '" + from + "' in the scene");
  return text.replace(at, from.size(), to);
}

const nlohmann::json& Named(const nlohmann::json& list, const std::string& name) {
  for (const auto& x : list) {
    if (x.at("name") == name) return x;
  }
  throw std::runtime_error("no entry named " + name);
}

Eigen::Vector3d Force(const nlohmann::json& j, const std::string& name) {
  return ToVec(Named(j.at("reactions"), name).at("force"));
}
Eigen::Vector3d Moment(const nlohmann::json& j, const std::string& name) {
  return ToVec(Named(j.at("reactions"), name).at("moment"));
}

nlohmann::json SolveJson(const std::string& path) {
  const CliResult r = RunCli("solve " + Quote(path) + " --format json");
  if (r.exit_code != 0) throw std::runtime_error("chasles solve " + path + " failed: " + r.err);
  return nlohmann::json::parse(r.out);
}

std::string AllWarnings(const nlohmann::json& j) {
  std::string all;
  for (const auto& w : j.at("warnings")) all += w.get<std::string>() + "\n";
  return all;
}

// The door of tests/bad_input/initial-door-inconsistent-velocity.yaml: a 30 kg box 1 m wide
// (x), 40 mm thick (y), 2 m tall (z), hinge line x = y = 0, centre of mass at d = 0.5 m from it.
// Standard gravity g_n (3rd CGPM, 1901), the scenes' `gravity: standard` [m/s²].
constexpr double kStandardGravity = 9.80665;
constexpr double kDoorMass = 30.0, kDoorWidth = 1.0, kDoorThickness = 0.04, kDoorHeight = 2.0;

// --- Inconsistent initial states are errors ---------------------------------------------------

TEST(InitialState, DoorAskedToTurnWithItsCentreAtRestIsAnError) {
  const std::string file = SourcePath("tests/bad_input/initial-door-inconsistent-velocity.yaml");
  const CliResult r = RunCli("solve " + Quote(file));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(r.out.empty());
  // Each hinge point would move at |w x (p_J - p_G)| = w d = 0.5 m/s (along y; the point's z
  // offset from G is along w and drops out).
  EXPECT_THAT(r.err, HasSubstr(file + ":"));
  EXPECT_THAT(r.err, HasSubstr("revolute 'top' (body 'door'): residual velocity 0.5 m/s"));
  EXPECT_THAT(r.err, HasSubstr("revolute 'bottom' (body 'door'): residual velocity 0.5 m/s"));
  EXPECT_THAT(r.err, HasSubstr("give `velocity` (of `velocity_point`) and `angular_velocity` "
                               "of 'door' consistent with revolute 'top'"));
  EXPECT_THAT(r.err, HasSubstr("`project_initial: true`"));
  // The nearest consistent state (mass-weighted): the door turning about the hinge line at w'
  // minimising m (w' d)² + I_G (w' - w)², i.e. w' = I_G w / (I_G + m d²) with
  // I_G = m (a² + t²) / 12 about the vertical through G.
  const double I_G = kDoorMass * (kDoorWidth * kDoorWidth + kDoorThickness * kDoorThickness) / 12;
  const double d = kDoorWidth / 2, w_used = I_G / (I_G + kDoorMass * d * d);
  EXPECT_THAT(
      r.err, HasSubstr(fmt::format(
                 "body 'door': angular velocity [0, 0, 1] rad/s -> [0, 0, {:.6g}] rad/s", w_used)));
}

TEST(InitialState, Section83DiskWithoutItsCentreVelocityIsAnError) {
  const std::string file = SourcePath("tests/bad_input/initial-disk-no-centre-velocity.yaml");
  const CliResult r = RunCli("solve " + Quote(file));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  // The pivot O would move at |w x (O - G)| with G at 41/25 r along the axle (eq. 8.88) and
  // w = Omega (k - 2j): w x (-41/25 r j) = (41/25) r Omega i.
  const double r_disk = 0.1, Omega = 4.0;
  EXPECT_THAT(r.err, HasSubstr(fmt::format(
                         "spherical 'pivot' (body 'assembly'): residual velocity {:.4g} m/s",
                         41.0 / 25.0 * r_disk * Omega)));
  EXPECT_THAT(r.err, HasSubstr("its joint point is at rest: e.g. `velocity_point` at the joint "
                               "with `velocity: [0, 0, 0]`"));
  EXPECT_THAT(r.err, Not(HasSubstr("'floor'")));  // the floor row holds: w_x = 0
}

// --- Projection on request: every change is a warning -----------------------------------------

TEST(InitialState, ProjectionOnRequestListsEveryChangeInTextAndJson) {
  const std::string scene =
      Write("door-projected.yaml",
            ReadText(SourcePath("tests/bad_input/initial-door-inconsistent-velocity.yaml")) +
                "project_initial: true\n");
  const double I_G = kDoorMass * (kDoorWidth * kDoorWidth + kDoorThickness * kDoorThickness) / 12;
  const double d = kDoorWidth / 2, w_used = I_G / (I_G + kDoorMass * d * d);
  const std::string w_change = fmt::format(
      "initial state projected onto the constraints: body 'door': angular velocity [0, 0, 1] "
      "rad/s -> [0, 0, {:.6g}] rad/s",
      w_used);
  // G moves on its circle about the hinge line: v_G = w' k x (d i) = w' d j.
  const std::string v_change = fmt::format(
      "initial state projected onto the constraints: body 'door': velocity of its centre of mass "
      "[0, 0, 0] m/s -> [0, {:.6g}, 0] m/s",
      w_used * d);
  const nlohmann::json j = SolveJson(scene);
  EXPECT_THAT(AllWarnings(j), HasSubstr(w_change));
  EXPECT_THAT(AllWarnings(j), HasSubstr(v_change));
  const CliResult text = RunCli("solve " + Quote(scene));
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_THAT(text.out, HasSubstr("warning: " + w_change));
  EXPECT_THAT(text.out, HasSubstr("warning: " + v_change));
  // simulate: the same warnings, and the run starts at the projected w'.
  const auto out = OutDir("initial_projected");
  const nlohmann::json s = SimulateJson(scene, out, "--until 0.1");
  EXPECT_THAT(AllWarnings(s), HasSubstr(w_change));
  EXPECT_THAT(AllWarnings(s), HasSubstr(v_change));
  const auto& door = Named(s.at("final").at("bodies"), "door");
  EXPECT_NEAR(ToVec(door.at("angular_velocity")).z(), w_used, 1e-9 * w_used);
  const CliResult sim_text =
      RunCli("simulate " + Quote(scene) + " --until 0.1 --out " + Quote(out.string()));
  ASSERT_EQ(sim_text.exit_code, 0) << sim_text.err;
  EXPECT_THAT(sim_text.out, HasSubstr("warning: " + w_change));
}

TEST(InitialState, ProjectedSection83DiskListsItsChanges) {
  const std::string scene =
      Write("disk-projected.yaml",
            ReadText(SourcePath("tests/bad_input/initial-disk-no-centre-velocity.yaml")) +
                "project_initial: true\n");
  const nlohmann::json j = SolveJson(scene);
  const std::string all = AllWarnings(j);
  EXPECT_THAT(all, HasSubstr("initial state projected onto the constraints: body 'assembly': "
                             "velocity of its centre of mass [0, 0, 0] m/s -> ["));
  EXPECT_THAT(all, HasSubstr("initial state projected onto the constraints: body 'assembly': "
                             "angular velocity [0, -8, 4] rad/s -> ["));
  // The consistent scene (the shipped example) has no such warning and the chapter's
  // N = m Omega² r / 2 + (41/32) m g (eq. 8.109) at the floor.
  const nlohmann::json ok = SolveJson(SourcePath("examples/section-8.3-rolling-disk.yaml"));
  EXPECT_THAT(AllWarnings(ok), Not(HasSubstr("projected")));
  const double m = 2.0, r = 0.1, Omega = 4.0, g = kStandardGravity;
  const double N = 0.5 * m * Omega * Omega * r + 41.0 / 32.0 * m * g;
  EXPECT_NEAR(Force(ok, "floor").z(), N, 1e-9 * N);
  EXPECT_GT(std::abs(Force(j, "floor").z() - N), 1e-3 * N);  // the projection changes the answer
}

TEST(InitialState, ConsistentDoorRunsAtExactlyTheAskedRate) {
  const auto out = OutDir("initial_door");
  const nlohmann::json j = SimulateJson(SourcePath("examples/door-on-two-hinges.yaml"), out);
  EXPECT_THAT(AllWarnings(j), Not(HasSubstr("projected")));
  const auto csv = ReadCsv(j.at("csv").get<std::string>());
  ASSERT_FALSE(csv.at("door_wz").empty());
  // No moment about the hinge line (gravity is along it): w stays at 1 rad/s.
  for (double w : csv.at("door_wz")) EXPECT_NEAR(w, 1.0, 1e-12);
}

// --- Redundant supports ------------------------------------------------------------------------

// The door of examples/door-on-two-hinges.yaml: hinges at z_t = H - e and z_b = e on the line
// x = y = 0, G at (w/2, 0, H/2), turning at omega about z.
struct DoorHinges {
  Eigen::Vector3d top, bottom;
};

DoorHinges TextbookHinges() {
  const double m = kDoorMass, H = kDoorHeight, w = kDoorWidth, e = 0.2, omega = 1.0;
  const double g = kStandardGravity;
  const double z_t = H - e, h = H - 2 * e;
  // Product of inertia about the top hinge: P_xz = ∫ x (z - z_t) dm = m (w/2)(H/2 - z_t) (the
  // box's own product about G is zero). Moments about the top hinge, about y:
  //   (w/2) m g - h F_bx = (omega x [I_top] omega)_y = -omega² P_xz.
  const double P_xz = m * (w / 2) * (H / 2 - z_t);
  const double F_bx = ((w / 2) * m * g + omega * omega * P_xz) / h;
  // Along x: F_tx + F_bx = m a_Gx = -m omega² w/2; along z the top hinge carries the weight.
  const double F_tx = -m * omega * omega * w / 2 - F_bx;
  return {{F_tx, 0.0, m * g}, {F_bx, 0.0, 0.0}};
}

TEST(RedundantSupports, TwoHingesNameTheIndeterminateComponentsInTextAndJson) {
  const std::string door = SourcePath("examples/door-on-two-hinges.yaml");
  const nlohmann::json j = SolveJson(door);
  EXPECT_EQ(j.at("rows"), 10);
  EXPECT_EQ(j.at("rank"), 5);
  const std::string all = AllWarnings(j);
  EXPECT_THAT(all, HasSubstr("'top' and 'bottom': only the sum of their z forces is determined"));
  EXPECT_THAT(all, HasSubstr("'top' x force, 'top' y moment, 'bottom' x force and 'bottom' y "
                             "moment: equilibrium fixes only 2 combinations of these 4"));
  EXPECT_THAT(all, HasSubstr("'top' y force, 'top' x moment, 'bottom' y force and 'bottom' x "
                             "moment: equilibrium fixes only 2 combinations of these 4"));
  EXPECT_THAT(all, HasSubstr("a determinate model (forces before moments): make 'top' a "
                             "`spherical` joint and 'bottom' a `point_on_line` joint along its "
                             "z axis"));
  const CliResult text = RunCli("solve " + Quote(door));
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_THAT(text.out, HasSubstr("only the sum of their z forces is determined"));
  const auto out = OutDir("redundant_door");
  const nlohmann::json s = SimulateJson(door, out, "--until 0.2");
  EXPECT_THAT(AllWarnings(s),
              HasSubstr("'top' and 'bottom': only the sum of their z forces is determined"));
}

TEST(RedundantSupports, TheSuggestedDeterminateModelGivesTheTextbookHingeForces) {
  std::string text = ReadText(SourcePath("examples/door-on-two-hinges.yaml"));
  text = Replace(text, "{name: top, type: revolute,", "{name: top, type: spherical,");
  text = Replace(text, "{name: bottom, type: revolute,", "{name: bottom, type: point_on_line,");
  const nlohmann::json j = SolveJson(Write("door-determinate.yaml", text));
  EXPECT_EQ(j.at("rank"), 5);
  EXPECT_EQ(j.at("rows"), 5);
  EXPECT_TRUE(j.at("warnings").empty()) << j.at("warnings");
  const DoorHinges t = TextbookHinges();
  const double scale = kDoorMass * kStandardGravity;
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(Force(j, "top")[i], t.top[i], 1e-9 * scale) << i;
    EXPECT_NEAR(Force(j, "bottom")[i], t.bottom[i], 1e-9 * scale) << i;
  }
  EXPECT_NEAR(Moment(j, "top").norm(), 0.0, 1e-9 * scale);
  EXPECT_NEAR(Moment(j, "bottom").norm(), 0.0, 1e-9 * scale);
}

TEST(RedundantSupports, RedundantReactionsDoNotDependOnTheUnitOfLength) {
  const std::string metres = SourcePath("examples/door-on-two-hinges.yaml");
  // The same door with every length in millimetres.
  std::string mm = ReadText(metres);
  mm = Replace(mm, "chasles: 3\n", "chasles: 3\nunits: mm, kg\n");
  mm = Replace(mm, "H: 2 m", "H: 2000 mm");
  mm = Replace(mm, "w: 1 m", "w: 1000 mm");
  mm = Replace(mm, "t: 40 mm", "t: 40 mm");
  mm = Replace(mm, "e: 0.2 m", "e: 200 mm");
  const nlohmann::json a = SolveJson(metres);
  const nlohmann::json b = SolveJson(Write("door-mm.yaml", mm));
  const double scale = kDoorMass * kStandardGravity;
  for (const char* name : {"top", "bottom"}) {
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(Force(a, name)[i], Force(b, name)[i], 1e-9 * scale) << name << i;
      EXPECT_NEAR(Moment(a, name)[i], Moment(b, name)[i], 1e-9 * scale) << name << i;
    }
  }
  // Whatever their split, the two hinges together exert the determinate total: the same force
  // and the same moment about the top hinge (the bottom hinge is h below it).
  const DoorHinges t = TextbookHinges();
  const Eigen::Vector3d total = Force(a, "top") + Force(a, "bottom");
  const Eigen::Vector3d total_textbook = t.top + t.bottom;
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(total[i], total_textbook[i], 1e-9 * scale) << i;
  const Eigen::Vector3d down(0, 0, -(kDoorHeight - 0.4));
  const Eigen::Vector3d M_top =
      Moment(a, "top") + Moment(a, "bottom") + down.cross(Force(a, "bottom"));
  const Eigen::Vector3d M_top_textbook = down.cross(t.bottom);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(M_top[i], M_top_textbook[i], 1e-9 * scale) << i;
}

}  // namespace
}  // namespace chasles::test
