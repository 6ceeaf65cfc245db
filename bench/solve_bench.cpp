// The cost of one contact-and-joint evaluation (CalcAccelerations at a state in fixed modes:
// the constraint or contact stage) as the number of bodies n grows, sparse against dense
// (Data::linear_solver; docs/design.md, "Sparse constraint and contact solves"):
//  - chain: n rods hanging from revolute joints (5 n rows), at rest;
//  - pile, sticking: a row of n equal spheres at rest on the floor, touching each other
//    (3 (2n - 1) rows; redundant: the sparse path's least-norm solve, SolveSparseLeastNorm,
//    against the dense complete orthogonal decomposition);
//  - pile, sliding: the same row moving at 1 m/s along x, the floor points sliding, the
//    sphere-sphere points sticking (LU).
// The plain reference loop is the same n bodies without joints or contacts (the Newton–Euler
// stage alone): the ratio stage / free is the stage's cost per unit of free-body work, flat in
// n for an O(n) stage. Dense stops at n = 300 (n³: about 20 s per evaluation at 1,000).
// Mode selection (SelectContactModes) on the rows of spheres, at a state where the modes must
// be chosen: every point newly touching (all separated in the state); the row at rest (every
// point sticks), moving sideways at 1 m/s (along y: the floor points slide, the sphere-sphere
// points stick), or moving lengthwise at 1 m/s (along x: the floor friction spins the spheres
// alike, the sphere-sphere points, carrying no normal force, cannot hold the spins together
// and start to slip, one per pass of the selection: n - 1 passes); and on the hanging chain
// whose last link's end touches a wall (5 n joint rows, one contact point). Its plan solves (the
// LCP on the normal forces, the velocity projection) sparse against dense (internal::
// SelectContactModes' solver; the evaluations of the chosen modes use Data's kAuto either
// way); dense to n = 300 (lengthwise: 100).
// Benchmarks never assert: each reports its error against the closed form as a counter.
// Results, the commands and the plot (docs/images/cost-curves.png): docs/benchmarks.md.

#include <algorithm>
#include <cmath>
#include <vector>

#include <benchmark/benchmark.h>

#include "chasles/dynamics/contact_solve.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/model/data.h"
#include "dynamics/internal/mode_selection.h"
#include "reference/solve_scenes.h"

namespace chasles {
namespace {

using reference::kGravity;
using reference::Scene;

constexpr double kRodMass = 1.0, kRodLength = 0.25;
constexpr double kBallMass = 0.17, kBallRadius = 0.028575;

Scene Chain(int n) {
  return reference::MakeChain(n, std::vector<double>(static_cast<size_t>(n), kRodMass), kRodLength);
}

Scene Pile(int n, bool sliding) {
  return reference::MakeRowPile(n, std::vector<double>(static_cast<size_t>(n), kBallRadius),
                                std::vector<double>(static_cast<size_t>(n), kBallMass), sliding);
}

// Hanging at rest: joint i carries the weight of the n - i links below it, g (n - i) m ẑ.
double ChainError(const Scene& s, const Data& data) {
  const int n = s.model.num_bodies();
  double e = 0.0;
  for (int i = 0; i < n; ++i) {
    const double T = kGravity * kRodMass * (n - i);
    e = std::max(e, (data.constraints[static_cast<size_t>(i)].F_Jc_W - Vec3(0, 0, T)).norm() / T);
  }
  return e;
}

// At rest (sticking): equal spheres in a level row stand on the floor, N = m g each, the
// sphere-sphere points carry nothing, a = 0 (the least-norm answer of the indeterminate row).
// Sliding, the spheres' spins couple them through the sticking sphere-sphere points, so the
// check is Newton's second law for the whole row, the inner forces cancelling:
// Σ m a_i = Σ_floor (N n + f) + n m g, relative to n m g.
double PileError(const Scene& s, const Data& data, bool sliding) {
  const int n = s.model.num_bodies();
  const double W = kBallMass * kGravity;
  double e = 0.0;
  if (sliding) {
    Vec3 lhs = Vec3::Zero(), rhs = Vec3(0, 0, -n * W);
    for (const Vec3& a : data.a_WBcm_W) lhs += kBallMass * a;
    for (int p = 0; p < n; ++p) {
      const ContactPointOutput& c = data.contact_points[static_cast<size_t>(p)];
      rhs += c.normal_force * c.n_W + c.friction_force_W;
    }
    return (lhs - rhs).norm() / (n * W);
  }
  for (int p = 0; p < s.model.num_contact_points(); ++p) {
    const double N = data.contact_points[static_cast<size_t>(p)].normal_force;
    e = std::max(e, std::abs(N - (p < n ? W : 0.0)) / W);
  }
  for (const Vec3& a : data.a_WBcm_W) e = std::max(e, a.norm() / kGravity);
  return e;
}

enum class Kind { kChain, kPileSticking, kPileSliding };

void Stage(benchmark::State& st, Kind kind, LinearSolver solver) {
  const int n = static_cast<int>(st.range(0));
  const Scene s = kind == Kind::kChain ? Chain(n) : Pile(n, kind == Kind::kPileSliding);
  Data data = MakeData(s.model);
  data.linear_solver = solver;
  CalcAccelerations(s.model, s.state, data);  // sizes the workspaces, analyses the pattern
  for (auto _ : st) {
    CalcAccelerations(s.model, s.state, data);
    benchmark::DoNotOptimize(data.a_WBcm_W.data());
  }
  st.SetComplexityN(n);
  st.counters["closed_form_error"] =
      kind == Kind::kChain ? ChainError(s, data) : PileError(s, data, kind == Kind::kPileSliding);
}

// The plain reference: the same n free bodies (Newton–Euler only).
void FreeBodies(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  Scene s = Pile(n, false);
  Model free;
  for (int b = 0; b < n; ++b)
    free.AddBody(s.model.body(b).name(), s.model.body(b).mass_properties());
  free.AddForceElement(std::make_shared<UniformGravity>("g", Vec3(0, 0, -kGravity)));
  State x = MakeRestState(free);
  x.bodies = s.state.bodies;
  Data data = MakeData(free);
  for (auto _ : st) {
    CalcAccelerations(free, x, data);
    benchmark::DoNotOptimize(data.a_WBcm_W.data());
  }
  st.SetComplexityN(n);
}

void ChainSparse(benchmark::State& st) {
  Stage(st, Kind::kChain, LinearSolver::kSparse);
}
void ChainDense(benchmark::State& st) {
  Stage(st, Kind::kChain, LinearSolver::kDense);
}
void PileStickingSparse(benchmark::State& st) {
  Stage(st, Kind::kPileSticking, LinearSolver::kSparse);
}
void PileStickingDense(benchmark::State& st) {
  Stage(st, Kind::kPileSticking, LinearSolver::kDense);
}
void PileSlidingSparse(benchmark::State& st) {
  Stage(st, Kind::kPileSliding, LinearSolver::kSparse);
}
void PileSlidingDense(benchmark::State& st) {
  Stage(st, Kind::kPileSliding, LinearSolver::kDense);
}

enum class Select { kResting, kSideways, kLengthwise, kChainOnWall };

// The hanging chain at rest, the far end of its last link touching a frictionless wall with
// normal ŷ (the direction the revolute joints, axes along x, let it swing): the plan is the 5 n
// joint rows and the contact's normal row. The end stays in contact (sliding: frictionless)
// with no force (nothing pushes it against the wall) and each joint carries the weight below
// it (ChainError). (With friction the end's tangent rows would hold it up as the joints do: a
// statically indeterminate chain.)
Scene ChainOnWall(int n) {
  return reference::MakeChainOnWall(n, std::vector<double>(static_cast<size_t>(n), kRodMass),
                                    kRodLength);
}

double ChainOnWallError(const Scene& s, const Data& data) {
  const ContactPointOutput& c = data.contact_points[0];
  const double W = kRodMass * kGravity;
  return std::max(
      {ChainError(s, data), std::abs(c.normal_force) / W, c.friction_force_W.norm() / W});
}

// Sideways at 1 m/s along y: every floor point slides with N = m g and friction -mu_k m g ŷ
// (mu_k = 0.3), the sphere-sphere points carry nothing (the floor friction spins every sphere
// alike about x, which moves the sphere-sphere points of neighbours alike), each sphere
// decelerates at mu_k g. The largest error relative to m g (and to g for the accelerations).
double SidewaysError(const Scene& s, const Data& data) {
  const int n = s.model.num_bodies();
  const double W = kBallMass * kGravity;
  double e = 0.0;
  for (int p = 0; p < s.model.num_contact_points(); ++p) {
    const ContactPointOutput& c = data.contact_points[static_cast<size_t>(p)];
    const Vec3 f = p < n ? Vec3(0, -0.3 * W, 0) : Vec3::Zero();
    e = std::max(
        {e, std::abs(c.normal_force - (p < n ? W : 0.0)) / W, (c.friction_force_W - f).norm() / W});
  }
  for (const Vec3& a : data.a_WBcm_W)
    e = std::max(e, (a - Vec3(0, -0.3 * kGravity, 0)).norm() / kGravity);
  return e;
}

// Mode selection from all points newly touching (see the file comment). Counters: the modes
// chosen (points separated, sliding, sticking), the plan solves (passes of the selection and
// the velocity projection), those of them the dense path made, the sparse LCP's pivots, and the
// closed-form error of the forces in the chosen modes (PileError, SidewaysError), and whether
// the selection's Data had the dense Data::J sized (1: below kSparseMinRows rows, MakeData's).
void ModeSelection(benchmark::State& st, Select kind, LinearSolver solver) {
  const int n = static_cast<int>(st.range(0));
  Scene s = kind == Select::kChainOnWall ? ChainOnWall(n) : Pile(n, kind == Select::kLengthwise);
  for (int i = 0; kind == Select::kSideways && i < n; ++i)
    SetBodyVelocity(s.model, i, Vec3(0, 1, 0), Vec3::Zero(), s.state);
  for (ContactPointState& ps : s.state.contacts) ps = ContactPointState{};
  State x = s.state;
  for (auto _ : st) {
    x = s.state;  // a copy of the n body states: O(n), small against the selection
    internal::SelectContactModes(s.model, x, {}, {}, nullptr, solver);
    benchmark::DoNotOptimize(x.contacts.data());
  }
  int count[3] = {0, 0, 0};
  for (const ContactPointState& ps : x.contacts) ++count[static_cast<int>(ps.mode)];
  st.counters["separated"] = count[static_cast<int>(ContactMode::kSeparated)];
  st.counters["sliding"] = count[static_cast<int>(ContactMode::kSliding)];
  st.counters["sticking"] = count[static_cast<int>(ContactMode::kSticking)];
  const internal::ModeSelectionStats& stats = internal::LastModeSelectionStats();
  st.counters["plan_solves"] = stats.sparse_solves + stats.dense_solves;
  st.counters["sparse_pivots"] = stats.sparse_pivots;
  st.counters["dense_plan_solves"] = stats.dense_solves;
  st.counters["dense_jacobian"] = stats.dense_jacobian ? 1 : 0;
  Data data = MakeData(s.model);
  CalcAccelerations(s.model, x, data);
  st.SetComplexityN(n);
  st.counters["closed_form_error"] = kind == Select::kSideways ? SidewaysError(s, data)
                                     : kind == Select::kChainOnWall
                                         ? ChainOnWallError(s, data)
                                         : PileError(s, data, kind == Select::kLengthwise);
}

void SelectRestingSparse(benchmark::State& st) {
  ModeSelection(st, Select::kResting, LinearSolver::kSparse);
}
void SelectRestingDense(benchmark::State& st) {
  ModeSelection(st, Select::kResting, LinearSolver::kDense);
}
void SelectSidewaysSparse(benchmark::State& st) {
  ModeSelection(st, Select::kSideways, LinearSolver::kSparse);
}
void SelectSidewaysDense(benchmark::State& st) {
  ModeSelection(st, Select::kSideways, LinearSolver::kDense);
}
void SelectChainSparse(benchmark::State& st) {
  ModeSelection(st, Select::kChainOnWall, LinearSolver::kSparse);
}
void SelectChainDense(benchmark::State& st) {
  ModeSelection(st, Select::kChainOnWall, LinearSolver::kDense);
}
void SelectLengthwiseSparse(benchmark::State& st) {
  ModeSelection(st, Select::kLengthwise, LinearSolver::kSparse);
}
void SelectLengthwiseDense(benchmark::State& st) {
  ModeSelection(st, Select::kLengthwise, LinearSolver::kDense);
}

void AllSizes(benchmark::internal::Benchmark* b) {
  for (int n : {10, 30, 100, 300, 1000}) b->Arg(n);
  b->Complexity(benchmark::oNLogN)->Unit(benchmark::kMicrosecond);
}
void DenseSizes(benchmark::internal::Benchmark* b) {
  for (int n : {10, 30, 100, 300}) b->Arg(n);
  b->Complexity(benchmark::oNCubed)->Unit(benchmark::kMicrosecond);
}
void SmallDenseSizes(benchmark::internal::Benchmark* b) {
  for (int n : {10, 30, 100}) b->Arg(n);
  b->Unit(benchmark::kMicrosecond);
}
// Around the dense/sparse crossover (kSparseMinRows).
void SmallSizes(benchmark::internal::Benchmark* b) {
  for (int n : {2, 4, 6, 8, 12, 16}) b->Arg(n);
  b->Unit(benchmark::kMicrosecond);
}

BENCHMARK(FreeBodies)->Apply(AllSizes);
BENCHMARK(ChainSparse)->Apply(AllSizes);
BENCHMARK(ChainDense)->Apply(DenseSizes);
// A sticking row is statically indeterminate (J M⁻¹ Jᵀ singular, docs/design.md): the sparse
// path's least-norm solve (iterated Tikhonov on one sparse LDLᵀ) runs to 1,000.
BENCHMARK(PileStickingSparse)->Apply(AllSizes);
BENCHMARK(PileStickingDense)->Apply(DenseSizes);
BENCHMARK(PileSlidingSparse)->Apply(AllSizes);
BENCHMARK(PileSlidingDense)->Apply(DenseSizes);
BENCHMARK(SelectRestingSparse)->Apply(AllSizes);
BENCHMARK(SelectRestingDense)->Apply(DenseSizes);
BENCHMARK(SelectChainSparse)->Apply(AllSizes);
BENCHMARK(SelectChainDense)->Apply(DenseSizes);
BENCHMARK(SelectSidewaysSparse)->Apply(AllSizes);
BENCHMARK(SelectSidewaysDense)->Apply(DenseSizes);
// n - 1 passes: n² sparse, n⁴ dense (4.7 s at n = 100).
BENCHMARK(SelectLengthwiseSparse)->Apply(AllSizes)->Complexity(benchmark::oNSquared);
BENCHMARK(SelectLengthwiseDense)
    ->Apply(SmallDenseSizes)
    ->Complexity([](benchmark::IterationCount n) { return std::pow(static_cast<double>(n), 4); });
BENCHMARK(ChainSparse)->Name("ChainSparseSmall")->Apply(SmallSizes);
BENCHMARK(ChainDense)->Name("ChainDenseSmall")->Apply(SmallSizes);
BENCHMARK(PileStickingSparse)->Name("PileStickingSparseSmall")->Apply(SmallSizes);
BENCHMARK(PileStickingDense)->Name("PileStickingDenseSmall")->Apply(SmallSizes);

}  // namespace
}  // namespace chasles

BENCHMARK_MAIN();
