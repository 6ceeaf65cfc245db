// Contacts: the spinning ball of Problems 8.26/8.27 (sliding ends at t* = 2 R w0 / (7 mu_k g))
// run event-driven (the engine's hybrid Simulate, the stick event located on the dense output)
// against a fixed-step run of the same ball with small steps, the way time-stepping engines
// treat friction (the mode is fixed over a step and switched at the end of the step in which
// the slip changed sign); and 1,000 spinning spheres on one floor, event-driven. Counters:
// the relative error of t* and the kinetic energy after it. Results: docs/benchmarks.md.

#include <cmath>

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/integrate/simulate.h"
#include "chasles/model/contact.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"

namespace chasles {
namespace {

constexpr double kG = 9.80665;
constexpr double kR = 0.028575;  // 9/8 in
constexpr double kMass = 0.17;
constexpr double kMuK = 0.35;
constexpr double kW0 = 100 * 2 * M_PI / 60;  // 100 rpm

double TStar(double w0) {
  return 2 * kR * w0 / (7 * kMuK * kG);
}

Model MakeBalls(int n) {
  Model m;
  const double I = 0.4 * kMass * kR * kR;
  for (int i = 0; i < n; ++i) {
    const int b = m.AddBody(fmt::format("ball{}", i),
                            MassProperties(kMass, Vec3::Zero(), RotationalInertia(I, I, I)));
    ContactSpec c;
    c.name = fmt::format("floor{}", i);
    c.shape = ContactShape::kSphere;
    c.body = b;
    c.radius = kR;
    c.mu_s = 0.5;
    c.mu_k = kMuK;
    m.AddContact(c);
  }
  m.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -kG)));
  return m;
}

// Ball i spins at w0 (1 + i/n) about y, 1 m apart along y, resting on the floor z = 0.
State MakeSpinningBalls(const Model& m, int n) {
  State s = MakeRestState(m);
  for (int i = 0; i < n; ++i) {
    SetBodyPose(m, i, Vec3(0, i, kR), Quat::Identity(), s);
    SetBodyVelocity(m, i, Vec3::Zero(), Vec3(0, kW0 * (1 + double(i) / n), 0), s);
  }
  return s;
}

void SpinningBallEventDriven(benchmark::State& st) {
  const Model m = MakeBalls(1);
  const State s0 = MakeSpinningBalls(m, 1);
  SimulationOptions o;
  o.t_end = 2 * TStar(kW0);
  o.adaptive.rtol = 1e-12;
  o.adaptive.atol = 1e-14;
  o.store_samples = false;
  double t_event = NAN;
  for (auto _ : st) {
    try {
      const SimulationResult r = Simulate(m, s0, o);
      for (const ContactEvent& e : r.contact_events) {
        if (e.to == ContactMode::kSticking && e.from == ContactMode::kSliding) t_event = e.t;
      }
      benchmark::DoNotOptimize(r.final_state.bodies.data());
    } catch (const InputError& e) {
      st.SkipWithError(e.what());
      return;
    }
  }
  st.counters["t_star_rel_error"] = std::abs(t_event - TStar(kW0)) / TStar(kW0);
}
BENCHMARK(SpinningBallEventDriven)->Unit(benchmark::kMicrosecond);

// The same ball stepped at a fixed step h: the planar state (v, w) with the friction force
// fixed over each step from the slip sign at its start (RK4 is exact here since the sliding
// dynamics are linear), and the switch to rolling made at the end of the step in which the
// slip speed R w - v changed sign (momentum about the contact point kept: v = R w). The stick
// time is thus found to within one step.
void SpinningBallFixedStep(benchmark::State& st) {
  const double h = std::pow(10.0, -static_cast<double>(st.range(0)));
  const double t_end = 2 * TStar(kW0);
  double t_event = NAN, energy_error = NAN;
  for (auto _ : st) {
    double v = 0, w = kW0, t = 0;
    bool rolling = false;
    while (t < t_end - 0.5 * h) {
      if (!rolling) {
        const double s = (kR * w - v) > 0 ? 1.0 : -1.0;
        auto f = [&](double, double vv, double ww, double& dv, double& dw) {
          benchmark::DoNotOptimize(vv + ww);
          dv = kMuK * kG * s;
          dw = -2.5 * kMuK * kG * s / kR;
        };
        double k1v, k1w, k2v, k2w, k3v, k3w, k4v, k4w;
        f(t, v, w, k1v, k1w);
        f(t + h / 2, v + h / 2 * k1v, w + h / 2 * k1w, k2v, k2w);
        f(t + h / 2, v + h / 2 * k2v, w + h / 2 * k2w, k3v, k3w);
        f(t + h, v + h * k3v, w + h * k3w, k4v, k4w);
        v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
        w += h / 6 * (k1w + 2 * k2w + 2 * k3w + k4w);
        if ((kR * w - v) * s <= 0) {
          // Angular momentum about the contact point, m R v + I w, is kept by the switch.
          const double H = kMass * kR * v + 0.4 * kMass * kR * kR * w;
          v = H / (1.4 * kMass * kR);
          w = v / kR;
          rolling = true;
          t_event = t + h;
        }
      }
      t += h;
    }
    const double T = 0.5 * kMass * v * v + 0.2 * kMass * kR * kR * w * w;
    const double T_exact = 2.0 / 35.0 * kMass * kR * kR * kW0 * kW0;
    energy_error = std::abs(T - T_exact) / T_exact;
    benchmark::DoNotOptimize(v);
  }
  st.counters["t_star_rel_error"] = std::abs(t_event - TStar(kW0)) / TStar(kW0);
  st.counters["T_after_rel_error"] = energy_error;
}
BENCHMARK(SpinningBallFixedStep)->DenseRange(3, 6)->Unit(benchmark::kMicrosecond);

// 1,000 balls, each with its own t* (so 1,000 stick events), event-driven to after the last.
void ThousandSpheres(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const Model m = MakeBalls(n);
  const State s0 = MakeSpinningBalls(m, n);
  SimulationOptions o;
  o.t_end = 2.1 * TStar(kW0);
  o.adaptive.rtol = 1e-10;
  o.adaptive.atol = 1e-12;
  o.store_samples = false;
  double worst = 0;
  size_t events = 0;
  for (auto _ : st) {
    try {
      const SimulationResult r = Simulate(m, s0, o);
      events = r.contact_events.size();
      for (const ContactEvent& e : r.contact_events) {
        if (e.to != ContactMode::kSticking || e.from != ContactMode::kSliding) continue;
        const double t = TStar(kW0 * (1 + double(e.point) / n));
        worst = std::max(worst, std::abs(e.t - t) / t);
      }
    } catch (const InputError& e) {
      st.SkipWithError(e.what());
      return;
    }
  }
  st.counters["events"] = static_cast<double>(events);
  st.counters["worst_t_star_rel_error"] = worst;
}
BENCHMARK(ThousandSpheres)->Arg(1000)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace chasles

BENCHMARK_MAIN();
