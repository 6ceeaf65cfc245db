// End-to-end: the conical hopper example (thin conical and cylindrical shells, and the exact
// hollow cone) through `chasles mass`, against the closed forms in its comments.

#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "cli_runner.h"
#include "test_support.h"

namespace chasles::test {
namespace {

using std::numbers::pi;

// Closed forms against the program's sums and unit conversions: a few dozen roundings.
constexpr double kTight = 1e-12;

const nlohmann::json& Body(const nlohmann::json& report, const std::string& name) {
  for (const auto& b : report.at("bodies")) {
    if (b.at("name") == name) return b;
  }
  throw std::runtime_error("no body " + name);
}

// Hopper: steel (7850 kg/m³) sheet t = 3 mm; bottom cone R = 0.5 m, H = 0.6 m, apex at the
// origin, base at z = H; bin wall radius R, length L = 0.8 m, centred at z = H + L/2.
// Cone side: A_c = π R s, centroid at 2H/3 (H/3 from its base), Izz = m R²/2, transverse about
// the apex m (R²/4 + H²/2). Bin: A_b = 2π R L, Izz = m R², transverse about its centre
// m (R²/2 + L²/12), moved to the outlet by m (H + L/2)² (eq. 8.29).
TEST(RoundShells, ConicalHopperExample) {
  const double rho = 7850, t = 0.003, R = 0.5, H = 0.6, L = 0.8;
  const double s = std::sqrt(R * R + H * H);
  const double mc = rho * t * pi * R * s, mb = rho * t * 2 * pi * R * L;
  const auto j = MassJson("examples/conical-hopper.yaml");

  const auto& hopper = Body(j, "hopper");
  EXPECT_TRUE(Near(hopper.at("mass").get<double>(), mc + mb, kTight));
  const double zc = (mc * 2 * H / 3 + mb * (H + L / 2)) / (mc + mb);
  EXPECT_TRUE(MatNear(ToVec(hopper.at("center_of_mass")), Vec3(0, 0, zc), kTight, H));
  const double Izz = mc * R * R / 2 + mb * R * R;
  const double Ixx =
      mc * (R * R / 4 + H * H / 2) + mb * (R * R / 2 + L * L / 12 + (H + L / 2) * (H + L / 2));
  const auto& outlet = hopper.at("points").at(0);
  ASSERT_EQ(outlet.at("name"), "outlet");
  EXPECT_TRUE(MatNear(ToMat(outlet.at("inertia")), Mat3(Vec3(Ixx, Ixx, Izz).asDiagonal()), kTight));

  // The bottom alone: a body of one part has the part's surface area, the sheet's π R s.
  const auto& sheet = Body(j, "bottom sheet");
  EXPECT_TRUE(Near(sheet.at("surface_area").get<double>(), pi * R * s, kTight));
  EXPECT_TRUE(Near(sheet.at("mass").get<double>(), mc, kTight));

  // The exact wall: the cone minus the cone scaled by k = 1 - t s / (R H) on the same base;
  // volume (π R² H / 3)(1 - k³); surfaces π R s (1 + k²) and the annulus π R² (1 - k²).
  const double k = 1 - t * s / (R * H);
  const double V = pi * R * R * H / 3 * (1 - k * k * k);
  const auto& wall = Body(j, "bottom wall");
  EXPECT_TRUE(Near(wall.at("volume").get<double>(), V, kTight));
  EXPECT_TRUE(Near(wall.at("mass").get<double>(), rho * V, kTight));
  EXPECT_TRUE(Near(wall.at("surface_area").get<double>(),
                   pi * R * s * (1 + k * k) + pi * R * R * (1 - k * k), kTight));
  // Lighter than the thin sheet: V = t π R s (1 - δ + δ²/3) with δ = 1 - k, the wall lying
  // inside the outer surface.
  const double delta = 1 - k;
  EXPECT_TRUE(Near(rho * V / mc, 1 - delta + delta * delta / 3, kTight));
}

}  // namespace
}  // namespace chasles::test
