// What a scene costs over the library doing the same run, timed in the same process.
//
// Dzhanibekov (examples/dzhanibekov.yaml: moments (1, 2, 3) kg·m², ω₀ = (0.01, 10, 0.01) rad/s,
// 10 s at tolerance 1e-12, the event 'flip' on ω_y crossing zero, 201 output rows):
// - SceneDzhanibekov: what `chasles simulate` does short of writing its files: the scene file
//   read (LoadSceneFile), then RunStudy (the Model and options built, the run, the rows of the
//   scene's columns, the certificate);
// - LibraryDzhanibekov: Simulate on the same Model, initial state and options, the event
//   function written in C++ (the body's ω_y, the model body's axes being the scene body's).
// SceneDzhanibekov times a library run before each scene run (outside its own time); counters:
// library_ms and scene_ms, the CPU time of the fastest of each, scene_over_library their ratio,
// and flip_t_diff the difference of the two runs' flip times [s].
//
// Rolling cylinder (examples/contact-cylinder-incline.yaml: a solid cylinder on a 30° incline,
// its two rim points sticking, 0.5 s at tolerance 1e-12): LibraryCylinder is Simulate on the
// scene's Model, initial state and options. The two sticking points' six rows hold five
// degrees of freedom, so every evaluation's contact system is singular: it is solved least-norm
// and again weighted from one pivoted LDLᵀ's null space (dynamics/contact_solve.cpp).
//
// Spinning balls (examples/problem-8.26-spinning-ball.yaml n times over, ball i at
// w0 (1 + i/n), each its own stick event at t*_i = 2 R w_i / (7 mu_k g)): SceneSpinningBalls
// runs the scene of 10 balls and the scene of 1,000 as `chasles simulate` does with no
// integrator named (`auto`, the default for a scene with contacts from format version 3:
// RunStudy runs the islands apart, each checked at its own transitions), 60 ms
// at tolerance 1e-12 with rows every ms. Counters: ms_10 and ms_1000 (CPU time, fastest of the
// iterations), their ratio (the acceptance: at most 150), the islands of the 1,000-ball run and
// the worst relative error of its t* from the event log.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <ctime>
#include <string>

#include <fmt/format.h>

#include <benchmark/benchmark.h>

#include "chasles/analysis/initial_state.h"
#include "chasles/integrate/simulate.h"
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

const std::string kDzhanibekov = CHASLES_SOURCE_DIR "/examples/dzhanibekov.yaml";
const std::string kCylinder = CHASLES_SOURCE_DIR "/examples/contact-cylinder-incline.yaml";

// This thread's CPU time [s] (the machine is shared: wall time would count other jobs).
double CpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// The scene's Model and options with the event 'flip' written in C++: ω_y in the body frame.
struct LibraryRun {
  Study study = Settled(BuildStudy(LoadSceneFile(kDzhanibekov)));
  LibraryRun() {
    study.options.events.at(0).g = [](const Model&, const State& s) {
      return s.bodies[0].w_WB_B.y();
    };
  }
  SimulationResult Run() const { return Simulate(*study.model, study.initial, study.options); }
};

const LibraryRun& Library() {
  static const LibraryRun run;
  return run;
}

void LibraryDzhanibekov(benchmark::State& st) {
  double flip = 0.0;
  for (auto _ : st) {
    const SimulationResult res = Library().Run();
    flip = res.events.at(0).t;
    benchmark::DoNotOptimize(res.samples.data());
  }
  st.counters["flip_t"] = flip;
}

// Each iteration times a library run and then the scene's, and the ratio is that of the
// fastest of each (the least disturbed by other work on the machine).
void SceneDzhanibekov(benchmark::State& st) {
  double library = 1e9;
  double scene = 1e9;
  double flip_diff = 0.0;
  for (auto _ : st) {
    st.PauseTiming();
    double t0 = CpuSeconds();
    const SimulationResult lib = Library().Run();
    library = std::min(library, CpuSeconds() - t0);
    st.ResumeTiming();
    t0 = CpuSeconds();
    const StudyResult res = RunStudy(MakeStudyDefinition(LoadSceneFile(kDzhanibekov)));
    scene = std::min(scene, CpuSeconds() - t0);
    flip_diff = std::abs(res.events.at(0).t - lib.events.at(0).t);
    benchmark::DoNotOptimize(res.events.data());
  }
  st.counters["library_ms"] = 1e3 * library;
  st.counters["scene_ms"] = 1e3 * scene;
  st.counters["scene_over_library"] = scene / library;
  st.counters["flip_t_diff"] = flip_diff;
}

void LibraryCylinder(benchmark::State& st) {
  const Study study = Settled(BuildStudy(LoadSceneFile(kCylinder)));
  std::int64_t evaluations = 0;
  for (auto _ : st) {
    const SimulationResult res = Simulate(*study.model, study.initial, study.options);
    evaluations = res.stats.function_evaluations;
    benchmark::DoNotOptimize(res.samples.data());
  }
  st.counters["evaluations"] = static_cast<double>(evaluations);
}

// n balls 1 m apart along y, set down spinning about y; one floor contact for all of them.
constexpr double kMuK = 0.2;
constexpr double kSpinRpm = 100.0;
std::string SpinningBallsScene(int n) {
  std::string text = "chasles: 3\nparameters: {R: 9/8 in, m: 0.17 kg}\nbodies:\n";
  for (int i = 0; i < n; ++i) {
    text += fmt::format(
        "  - {{name: ball{}, parts: [{{shape: sphere, radius: R, mass: m}}], initial: {{position: "
        "[0, {} m, R], angular_velocity: [0, {:.17g} rad/s, 0]}}}}\n",
        i, i, kSpinRpm * 2 * M_PI / 60 * (1.0 + double(i) / n));
  }
  return text + fmt::format(
                    "gravity: standard\ncontacts:\n  - {{name: floor, body: all, shape: sphere, "
                    "radius: R, mu_s: 0.5, mu_k: {}, plane: {{point: [0, 0, 0], normal: [0, 0, "
                    "1]}}}}\nsimulation: {{until: 60 ms, tolerance: 1e-12, output_interval: 1 "
                    "ms}}\noutput:\n  columns: [position, velocity, angular_velocity, energy, "
                    "contacts, ledger]\n",
                    kMuK);
}

void SceneSpinningBalls(benchmark::State& st) {
  const Scene ten = LoadSceneText(SpinningBallsScene(10), "balls-10.yaml");
  const Scene thousand = LoadSceneText(SpinningBallsScene(1000), "balls-1000.yaml");
  double ms_10 = 1e9, ms_1000 = 1e9, worst = 0.0;
  int islands = 0;
  for (auto _ : st) {
    double t0 = CpuSeconds();
    benchmark::DoNotOptimize(RunStudy(MakeStudyDefinition(ten)).rows.data());
    ms_10 = std::min(ms_10, 1e3 * (CpuSeconds() - t0));
    t0 = CpuSeconds();
    const StudyResult r = RunStudy(MakeStudyDefinition(thousand));
    ms_1000 = std::min(ms_1000, 1e3 * (CpuSeconds() - t0));
    // Under auto (the default here) each event-driven stretch counts the islands it ran apart.
    islands = r.segments.empty() ? r.run_path.islands : r.segments.front().islands;
    for (const StudyContactEvent& e : r.contact_events) {
      if (e.reason != ContactEventReason::kSlipStopped) continue;
      const int i = std::stoi(e.point.substr(e.point.find("ball") + 4));
      const double w0 = kSpinRpm * 2 * M_PI / 60 * (1.0 + i / 1000.0);
      const double t_star = 2 * 0.028575 * w0 / (7 * kMuK * 9.80665);
      worst = std::max(worst, std::abs(e.t - t_star) / t_star);
    }
    if (!r.certificate.passed()) st.SkipWithError("the certificate failed");
  }
  st.counters["ms_10"] = ms_10;
  st.counters["ms_1000"] = ms_1000;
  st.counters["ratio"] = ms_1000 / ms_10;
  st.counters["islands"] = islands;
  st.counters["worst_t_star_rel_error"] = worst;
}

BENCHMARK(LibraryDzhanibekov)->Unit(benchmark::kMillisecond)->Iterations(30);
BENCHMARK(SceneDzhanibekov)->Unit(benchmark::kMillisecond)->Iterations(30);
BENCHMARK(LibraryCylinder)->Unit(benchmark::kMillisecond)->Iterations(30);
BENCHMARK(SceneSpinningBalls)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace
}  // namespace chasles

BENCHMARK_MAIN();
