// The Whipple bicycle benchmark: J. P. Meijaard, J. M. Papadopoulos, A. Ruina, A. L. Schwab,
// "Linearized dynamics equations for the balance and steer of a bicycle: a benchmark and
// review", Proc. R. Soc. A 463 (2007) 1955-1982. Parameters: its Table 1
// (examples/whipple-bicycle.yaml). Eigenvalues of the lean-and-steer motion at the forward
// speeds 0, 1, ..., 10 m/s and the weave and capsize speeds: its Table 2, as printed (14
// decimals). chasles has no bicycle equations: the scene is four bodies, three hinges and two
// rolling disks, linearised on the constraint manifold about steady straight running.

#include <gtest/gtest.h>

#include <algorithm>
#include <complex>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "chasles/analysis/initial_state.h"
#include "chasles/analysis/modes.h"
#include "chasles/scene/scene.h"
#include "chasles/scene/study.h"
#include "test_paths.h"

namespace chasles {
namespace {

/// The scene's study with its initial state settled on the constraints (SettleInitialState),
/// as a run or a solve starts from it.
Study Settled(Study s) {
  std::vector<std::string> warnings;
  s.initial = SettleInitialState(*s.model, s.initial, s.settling, warnings);
  return s;
}

const std::string kScene =
    std::string(chasles::test::SourceDir()) + "/examples/whipple-bicycle.yaml";

ModalAnalysis AtSpeed(double v) {
  SceneOptions options;
  options.parameter_overrides = {{"v", fmt::format("{:.17g} m/s", v)}};
  const Study s = Settled(BuildStudy(LoadSceneFile(kScene, options), 1.0));
  return AnalyseModes(*s.model, FindOperatingPoint(*s.model, s.initial));
}

/// The non-rigid eigenvalues, with both members of a complex pair, sorted by real part then
/// imaginary part.
std::vector<std::complex<double>> Eigenvalues(const ModalAnalysis& a) {
  std::vector<std::complex<double>> out;
  for (const Mode& m : a.modes) {
    if (m.rigid) continue;
    out.push_back(m.eigenvalue);
    if (m.eigenvalue.imag() > 0.0) out.push_back(std::conj(m.eigenvalue));
  }
  std::sort(out.begin(), out.end(), [](auto a, auto b) {
    return a.real() != b.real() ? a.real() < b.real() : a.imag() < b.imag();
  });
  return out;
}

// Table 2 (b), (c): at v = 0 four real eigenvalues; from 1 m/s on the capsize (real), the
// weave pair and the castering (real) eigenvalues.
struct Row {
  double v, capsize, weave_re, weave_im, castering;
};
const Row kTable2[] = {
    {1.0, -3.13423125066578, 3.52696170990070, 0.80774027519930, -7.11008014637442},
    {2.0, -3.07158645641514, 2.68234517512745, 1.68066296590675, -8.67387984831735},
    {3.0, -2.63366137253667, 1.70675605663975, 2.31582447384325, -10.35101467245920},
    {4.0, -1.42944427361326, 0.41325331521125, 3.07910818603206, -12.15861426576450},
    {5.0, -0.32286642900409, -0.77534188219585, 4.46486771378823, -14.07838969279820},
    {6.0, -0.00406690076970, -1.52644486584142, 5.87673060598709, -16.08537123098030},
    {7.0, 0.10268170574766, -2.13875644258362, 7.19525913329805, -18.15788466125262},
    {8.0, 0.14327879765713, -2.69348683581097, 8.46037971396931, -20.27940894394569},
    {9.0, 0.15790184030917, -3.21675402252485, 9.69377351531791, -22.43788559040858},
    {10.0, 0.16105338653172, -3.72016840437287, 10.90681139476287, -24.62459635017404},
};
// The table prints 14 decimals: agreement to its last digit.
constexpr double kTableDigits = 1e-13;

TEST(WhippleBicycle, EigenvaluesAtRest) {
  const std::vector<std::complex<double>> e = Eigenvalues(AtSpeed(0.0));
  const double want[4] = {-5.53094371765393, -3.13164324790656, 3.13164324790656, 5.53094371765393};
  ASSERT_EQ(e.size(), 4u);
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(e[i].real(), want[i], kTableDigits * 10) << i;
    EXPECT_EQ(e[i].imag(), 0.0);
  }
}

TEST(WhippleBicycle, EigenvaluesAtThePublishedSpeeds) {
  for (const Row& r : kTable2) {
    const ModalAnalysis a = AtSpeed(r.v);
    const std::vector<std::complex<double>> e = Eigenvalues(a);
    ASSERT_EQ(e.size(), 4u) << "v = " << r.v;
    // Sorted by real part: castering, then the others.
    EXPECT_NEAR(e[0].real(), r.castering, kTableDigits * std::abs(r.castering) * 10) << r.v;
    std::complex<double> weave = e[1].imag() != 0.0 ? e[1] : e[2];
    std::complex<double> capsize = e[1].imag() != 0.0 ? e[3] : e[1];
    if (weave.imag() < 0.0) weave = std::conj(weave);
    EXPECT_NEAR(capsize.real(), r.capsize, kTableDigits * 10) << r.v;
    EXPECT_NEAR(weave.real(), r.weave_re, kTableDigits * 10) << r.v;
    EXPECT_NEAR(weave.imag(), r.weave_im, kTableDigits * 10) << r.v;
    EXPECT_EQ(a.stable, r.v > 4.29238253634111 && r.v < 6.02426201538837) << r.v;
  }
}

// Table 2 (a): the weave speed 4.29238253634111 m/s (the weave pair crosses Re λ = 0,
// Im λ = 3.43503384866144 there) and the capsize speed 6.02426201538837 m/s (the capsize
// eigenvalue crosses 0), found by root-finding on the stability verdict. Its cost (about
// 0.1 s) is measured by bench/modes_bench.cpp, not here.
TEST(WhippleBicycle, WeaveAndCapsizeSpeedsByRootFinding) {
  std::vector<double> grid;
  for (int i = 0; i <= 10; ++i) grid.push_back(i);
  const std::vector<StabilityChange> changes = FindStabilityChanges(AtSpeed, grid, 1e-13);
  ASSERT_EQ(changes.size(), 2u);
  EXPECT_NEAR(changes[0].value, 4.29238253634111, 1e-10 * 4.29238253634111);
  EXPECT_EQ(changes[0].kind, StabilityChangeKind::kOscillatory);
  EXPECT_TRUE(changes[0].stable_after);
  EXPECT_NEAR(changes[1].value, 6.02426201538837, 1e-10 * 6.02426201538837);
  EXPECT_EQ(changes[1].kind, StabilityChangeKind::kDivergent);
  EXPECT_FALSE(changes[1].stable_after);
}

}  // namespace
}  // namespace chasles
