// The cost of small-motion analysis (docs/modes.md): the Whipple bicycle (Meijaard et al. 2007;
// examples/whipple-bicycle.yaml, four bodies, three hinges, two rolling wheels) from the scene
// to its eigenvalues at one speed, and its weave and capsize speeds located over 0 to 10 m/s;
// and a chain of n rods on hinges, the linearisation and eigenvalue solve as n grows (6 n
// maximal coordinates per state entry, reduced to n angles and n rates).
// Benchmarks never assert: each reports its error as a counter — against the paper's Table 2
// for the bicycle, the finite-difference self-check of the Jacobian for the chain.
// Results and the command: docs/benchmarks.md.

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include "chasles/analysis/initial_state.h"
#include "chasles/analysis/modes.h"
#include "chasles/scene/scene.h"
#include "chasles/scene/study.h"

namespace chasles {
namespace {

/// The scene's study with its initial state settled on the constraints (SettleInitialState),
/// as a run or a solve starts from it.
Study Settled(Study s) {
  std::vector<std::string> warnings;
  s.initial = SettleInitialState(*s.model, s.initial, s.settling, warnings);
  return s;
}

const std::string kBicycle = std::string(CHASLES_SOURCE_DIR) + "/examples/whipple-bicycle.yaml";

ModalAnalysis BicycleAt(double v) {
  SceneOptions options;
  options.parameter_overrides = {{"v", fmt::format("{:.17g} m/s", v)}};
  const Study s = Settled(BuildStudy(LoadSceneFile(kBicycle, options), 1.0));
  return AnalyseModes(*s.model, FindOperatingPoint(*s.model, s.initial));
}

// Table 2 at 5 m/s: the weave pair -0.77534188219585 ± 4.46486771378823i, the capsize
// -0.32286642900409 and the castering -14.07838969279820.
double BicycleError(const ModalAnalysis& a) {
  const std::complex<double> want[3] = {
      {-0.32286642900409, 0.0}, {-0.77534188219585, 4.46486771378823}, {-14.07838969279820, 0.0}};
  double e = 0.0;
  for (const std::complex<double>& w : want) {
    double best = INFINITY;
    for (const Mode& m : a.modes) {
      if (!m.rigid) best = std::min(best, std::abs(m.eigenvalue - w));
    }
    e = std::max(e, best);
  }
  return e;
}

void BM_BicycleModesAtOneSpeed(benchmark::State& state) {
  double error = 0.0;
  for (auto _ : state) {
    const ModalAnalysis a = BicycleAt(5.0);
    error = BicycleError(a);
    benchmark::DoNotOptimize(error);
  }
  state.counters["table2_error"] = error;
}
BENCHMARK(BM_BicycleModesAtOneSpeed)->Unit(benchmark::kMillisecond);

// The weave speed 4.29238253634111 m/s and the capsize speed 6.02426201538837 m/s (Table 2),
// located to 1e-13 of the span from an 11-point grid.
void BM_BicycleWeaveAndCapsizeSpeeds(benchmark::State& state) {
  std::vector<double> grid;
  for (int i = 0; i <= 10; ++i) grid.push_back(i);
  double error = 0.0;
  long analyses = 0;
  for (auto _ : state) {
    const std::vector<StabilityChange> c = FindStabilityChanges(
        [&](double v) {
          ++analyses;
          return BicycleAt(v);
        },
        grid, 1e-13);
    error = c.size() != 2 ? INFINITY
                          : std::max(std::abs(c[0].value - 4.29238253634111),
                                     std::abs(c[1].value - 6.02426201538837));
  }
  state.counters["speed_error"] = error;
  state.counters["analyses"] =
      static_cast<double>(analyses) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_BicycleWeaveAndCapsizeSpeeds)->Unit(benchmark::kMillisecond);

// n slender rods (1 kg, 0.25 m) hanging on hinges about y, each from the end of the one above.
std::string Chain(int n) {
  std::string bodies, joints;
  for (int i = 0; i < n; ++i) {
    bodies += fmt::format(
        "  - {{name: rod{0}, parts: [{{shape: box, size: [0.01, 0.01, 0.25], mass: 1, "
        "position: [0, 0, {1}]}}]}}\n",
        i, -0.125 - 0.25 * i);
    joints += fmt::format(
        "  - {{name: hinge{0}, type: revolute, parent: {1}, child: rod{0}, at: [0, 0, {2}], "
        "axis: [0, 1, 0]}}\n",
        i, i == 0 ? "world" : fmt::format("rod{}", i - 1), -0.25 * i);
  }
  return "chasles: 1\ngravity: standard\nbodies:\n" + bodies + "joints:\n" + joints;
}

void BM_ChainModes(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const Study s = Settled(BuildStudy(LoadSceneText(Chain(n), "chain.yaml"), 1.0));
  const OperatingPoint op = FindOperatingPoint(*s.model, s.initial);
  LinearizeOptions check;
  check.finite_difference_check = true;
  state.counters["fd_check"] =
      AnalyseModes(*s.model, op, check).linearization.finite_difference_check;
  for (auto _ : state) {
    const ModalAnalysis a = AnalyseModes(*s.model, op);
    benchmark::DoNotOptimize(a.modes.data());
  }
  state.counters["bodies"] = n;
}
BENCHMARK(BM_ChainModes)->RangeMultiplier(2)->Range(1, 32)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace chasles

BENCHMARK_MAIN();
