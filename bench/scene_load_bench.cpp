// Cost of loading a scene of n bodies (one sphere each, `initial: {position: [i m, 0 m, 0 m]}`,
// about 124 bytes a body): the text read into a Scene (LoadSceneText: the YAML parse, every
// value and expression checked, the state-variable names and output columns), and the Study
// built from it (the Model and the initial state). The reference, timed in the same run, is
// libyaml's parser alone walking the same text's events: the floor any YAML reader pays.
// Linear cost shows as a constant time per body over n = 1e3, 1e4, 1e5.

#include <yaml.h>

#include <map>
#include <string>

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include "chasles/scene/scene.h"
#include "chasles/scene/study.h"

namespace chasles {
namespace {

const std::string& SceneText(int n) {
  static std::map<int, std::string> texts;
  std::string& text = texts[n];
  if (text.empty()) {
    text = "chasles: 3\nbodies:\n";
    for (int i = 0; i < n; ++i) {
      text += fmt::format(
          "  - name: b{}\n    parts:\n      - {{shape: sphere, radius: 0.1 m, mass: 1 kg}}\n"
          "    initial: {{position: [{} m, 0 m, 0 m]}}\n",
          i, i);
    }
  }
  return text;
}

void LoadScene(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const std::string& text = SceneText(n);
  for (auto _ : st) {
    const Scene scene = LoadSceneText(text, "bench.yaml");
    benchmark::DoNotOptimize(scene.bodies.data());
  }
  st.SetItemsProcessed(st.iterations() * n);
  st.SetBytesProcessed(st.iterations() * static_cast<int64_t>(text.size()));
}

void LoadSceneAndBuildStudy(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const std::string& text = SceneText(n);
  for (auto _ : st) {
    const Study study = BuildStudy(LoadSceneText(text, "bench.yaml"), 1.0);
    benchmark::DoNotOptimize(&study);
  }
  st.SetItemsProcessed(st.iterations() * n);
}

// The reference: libyaml's events of the same text, nothing kept.
void YamlEventsOnly(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const std::string& text = SceneText(n);
  for (auto _ : st) {
    yaml_parser_t parser;
    yaml_parser_initialize(&parser);
    yaml_parser_set_input_string(&parser, reinterpret_cast<const unsigned char*>(text.data()),
                                 text.size());
    size_t events = 0;
    for (bool done = false; !done;) {
      yaml_event_t event;
      if (!yaml_parser_parse(&parser, &event)) {
        st.SkipWithError("libyaml refused the scene");
        break;
      }
      done = event.type == YAML_STREAM_END_EVENT;
      ++events;
      yaml_event_delete(&event);
    }
    yaml_parser_delete(&parser);
    benchmark::DoNotOptimize(events);
  }
  st.SetItemsProcessed(st.iterations() * n);
  st.SetBytesProcessed(st.iterations() * static_cast<int64_t>(text.size()));
}

BENCHMARK(LoadScene)->RangeMultiplier(10)->Range(1000, 100000)->Unit(benchmark::kMillisecond);
BENCHMARK(LoadSceneAndBuildStudy)
    ->RangeMultiplier(10)
    ->Range(1000, 100000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(YamlEventsOnly)->RangeMultiplier(10)->Range(1000, 100000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace chasles

BENCHMARK_MAIN();
