// The cost of calling chasles from Python: the same work called through the module (an
// embedded interpreter importing chasles) and directly in C++, side by side in one run.
//  - Simulate: one body under gravity for 1 s, samples every 10 ms (Dormand-Prince, 1e-9).
//  - Sweep: 10,000 instantaneous solves of a pinned bar (revolute joint) over its angle,
//    each setting the pose and solving (what a parameter sweep does per value).
// Built when pybind11's embedding support is found (bench/CMakeLists.txt).

#include <cmath>
#include <numbers>

#include <benchmark/benchmark.h>
#include <pybind11/embed.h>

#include "chasles/analysis/instantaneous.h"
#include "chasles/integrate/simulate.h"
#include "chasles/mass/shape.h"
#include "chasles/math/quaternion.h"
#include "chasles/model/constraints.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace py = pybind11;
using namespace chasles;

namespace {

constexpr int kSweep = 10000;
constexpr double kG = 9.80665;

const char* const kPython = R"(
import math
import chasles

def one_body():
    model = chasles.Model()
    b = model.add_body("ball", chasles.sphere(0.1).mass_properties(1.0))
    model.add_force_element(chasles.UniformGravity("gravity", [0, 0, -9.80665]))
    state = chasles.make_rest_state(model)
    return model, state

sim_model, sim_state = one_body()
sim_options = chasles.SimulationOptions(t_end=1.0, output_interval=0.01)

def simulate():
    return chasles.simulate(sim_model, sim_state, sim_options).final_state.t

def pinned_bar():
    model = chasles.Model()
    L, m = 1.2, 2.0
    I = m * L * L / 12
    b = model.add_body("bar", chasles.MassProperties(
        m, [L / 2, 0, 0], chasles.RotationalInertia(1e-4, I, I + 1e-4)))
    model.add_force_element(chasles.UniformGravity("gravity", [0, 0, -9.80665]))
    state = chasles.make_rest_state(model)
    chasles.set_body_pose(model, b, [0, 0, 0], [1, 0, 0, 0], state)
    R = chasles.frame_with_z_axis([0, 1, 0])
    model.add_constraint(chasles.Joint(
        "pin", chasles.JointKind.REVOLUTE, chasles.WORLD,
        chasles.attachment_frame_at_world_pose(model, state, chasles.WORLD, [0, 0, 0], R), b,
        chasles.attachment_frame_at_world_pose(model, state, b, [0, 0, 0], R)))
    return model, state

bar_model, bar_state = pinned_bar()

def sweep(n):
    total = 0.0
    for k in range(n):
        th = math.pi * k / n
        q = [math.cos(th / 2), 0.0, math.sin(th / 2), 0.0]
        chasles.set_body_pose(bar_model, 0, [0, 0, 0], q, bar_state)
        total += chasles.solve_instantaneous(bar_model, bar_state).bodies[0].angular_acceleration[1]
    return total
)";

py::module_& Main() {
  static py::module_ m = py::module_::import("__main__");
  return m;
}

void SimulatePython(benchmark::State& st) {
  py::object f = Main().attr("simulate");
  for (auto _ : st) benchmark::DoNotOptimize(f().cast<double>());
}

void SimulateCpp(benchmark::State& st) {
  Model model;
  model.AddBody("ball", MakeSolidSphere(0.1)->CalcMassProperties(1.0));
  model.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -kG)));
  const State state = MakeRestState(model);
  SimulationOptions options;
  options.t_end = 1.0;
  options.output_interval = 0.01;
  for (auto _ : st) benchmark::DoNotOptimize(Simulate(model, state, options).final_state.t);
}

void SweepPython(benchmark::State& st) {
  py::object f = Main().attr("sweep");
  for (auto _ : st) benchmark::DoNotOptimize(f(kSweep).cast<double>());
  st.SetItemsProcessed(st.iterations() * kSweep);
}

void SweepCpp(benchmark::State& st) {
  const double L = 1.2, m = 2.0, I = m * L * L / 12;
  Model model;
  const BodyIndex b = model.AddBody(
      "bar", MassProperties(m, Vec3(L / 2, 0, 0), RotationalInertia(1e-4, I, I + 1e-4)));
  model.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -kG)));
  State state = MakeRestState(model);
  SetBodyPose(model, b, Vec3::Zero(), Quat::Identity(), state);
  const Mat3 R = FrameWithZAxis(Vec3::UnitY());
  model.AddConstraint(
      std::make_shared<Joint>("pin", JointKind::kRevolute, kWorld,
                              AttachmentFrameAtWorldPose(model, state, kWorld, Vec3::Zero(), R), b,
                              AttachmentFrameAtWorldPose(model, state, b, Vec3::Zero(), R)));
  for (auto _ : st) {
    double total = 0.0;
    for (int k = 0; k < kSweep; ++k) {
      const double th = std::numbers::pi * k / kSweep;
      SetBodyPose(model, b, Vec3::Zero(), QuatFromWxyz(std::cos(th / 2), 0, std::sin(th / 2), 0),
                  state);
      total += SolveInstantaneous(model, state).bodies[0].alpha_WB_W.y();
    }
    benchmark::DoNotOptimize(total);
  }
  st.SetItemsProcessed(st.iterations() * kSweep);
}

}  // namespace

BENCHMARK(SimulatePython)->Unit(benchmark::kMicrosecond);
BENCHMARK(SimulateCpp)->Unit(benchmark::kMicrosecond);
BENCHMARK(SweepPython)->Unit(benchmark::kMillisecond);
BENCHMARK(SweepCpp)->Unit(benchmark::kMillisecond);

int main(int argc, char** argv) {
  py::scoped_interpreter interpreter;
  py::module_::import("sys").attr("path").attr("insert")(0, CHASLES_PYTHON_DIR);
  py::exec(kPython);
  // Both ways compute the same: check once before timing.
  const double py_total = Main().attr("sweep")(100).cast<double>();
  if (!std::isfinite(py_total)) return 1;
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  Main().release();
  return 0;
}
