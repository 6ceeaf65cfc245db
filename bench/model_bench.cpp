// Cost of building a Model of n free bodies (each AddBody checks its name against the others
// through a name → index hash table), against a plain reference loop timed in the same run:
// the same Body objects constructed into a std::vector with no name check. Linear cost shows
// as a constant time per body over n = 1e3, 1e4, 1e5.

#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include "chasles/model/model.h"

namespace chasles {
namespace {

std::vector<std::string> Names(int n) {
  std::vector<std::string> names;
  names.reserve(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) names.push_back(fmt::format("body{}", i));
  return names;
}

const MassProperties kMass(1.0, Vec3::Zero(), RotationalInertia(1.0, 2.0, 3.0));

void BuildModel(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const std::vector<std::string> names = Names(n);
  for (auto _ : st) {
    Model m;
    for (const std::string& name : names) m.AddBody(name, kMass);
    benchmark::DoNotOptimize(m.num_bodies());
  }
  st.SetItemsProcessed(st.iterations() * n);
}

// The reference: the bodies alone, no Model and no name check.
void PlainBodyVector(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const std::vector<std::string> names = Names(n);
  for (auto _ : st) {
    std::vector<Body> bodies;
    for (const std::string& name : names) bodies.emplace_back(name, kMass);
    benchmark::DoNotOptimize(bodies.data());
  }
  st.SetItemsProcessed(st.iterations() * n);
}

BENCHMARK(BuildModel)
    ->RangeMultiplier(10)
    ->Range(1000, 100000)

    ->Unit(benchmark::kMillisecond);
BENCHMARK(PlainBodyVector)
    ->RangeMultiplier(10)
    ->Range(1000, 100000)

    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace chasles

BENCHMARK_MAIN();
