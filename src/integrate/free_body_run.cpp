#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/integrate/free_body_batch.h"
#include "chasles/model/forces.h"
#include "integrate/internal/free_body_run.h"

namespace chasles::internal {
namespace {

/// Steps per FreeBodyBatch::Advance call: each tile of bodies goes through this many steps
/// while it is in cache, and on_step hears of the run's progress at least this often.
constexpr long long kChunkSteps = 128;

/// The force ledger of the UniformGravity elements, exact for p(τ) = p₀ + v₀τ + ½gτ² (g the
/// total; RK4 integrates these polynomials exactly, and the splitting's translation is this
/// closed form), as FreeBodyBatchIntegrator::Step adds it. Over a step h from S = Σ m p,
/// P = Σ m v (M = Σ m), for each element g_e:
///   work       ∫ Σ m g_e·v dτ = g_e·(h P + ½h² M g),
///   impulse    ∫ Σ m g_e dτ = h M g_e,
///   angular    ∫ Σ m p × g_e dτ = (h S + ½h² P + ⅙h³ M g) × g_e  (about Wo),
/// and then S ← S + h P + ½h² M g, P ← P + h M g: the sums follow the bodies in closed form
/// between output times and are taken from the bodies again at each (FreeBodyRunBatch sums
/// them as it loads and stores the bodies).
class GravityLedger {
 public:
  explicit GravityLedger(const Model& model) {
    for (int e = 0; e < model.num_force_elements(); ++e) {
      element_g_W_.push_back(static_cast<const UniformGravity&>(model.force_element(e)).g_W());
      g_W_ += element_g_W_.back();
    }
  }

  /// The bodies' M, S and P at the start of a stretch.
  void Start(double M, const Vec3& S, const Vec3& P) {
    mass_ = M;
    S_ = S;
    P_ = P;
  }

  /// One step of h [s] into `s`'s force integrals.
  void Step(double h, State& s) {
    const Vec3 dS = h * P_ + (0.5 * h * h * mass_) * g_W_;
    const Vec3 S_int = h * S_ + (0.5 * h * h) * P_ + (h * h * h / 6.0 * mass_) * g_W_;
    for (size_t e = 0; e < element_g_W_.size(); ++e) {
      ForceIntegrals& fi = s.force_integrals[e];
      const Vec3& ge = element_g_W_[e];
      fi.work += ge.dot(dS);
      fi.linear_impulse_W += (h * mass_) * ge;
      fi.angular_impulse_Wo_W += S_int.cross(ge);
    }
    S_ += dS;
    P_ += (h * mass_) * g_W_;
  }

 private:
  std::vector<Vec3> element_g_W_;
  Vec3 g_W_ = Vec3::Zero(), S_ = Vec3::Zero(), P_ = Vec3::Zero();
  double mass_ = 0.0;
};

/// `s` without its bodies, which FreeBodyRunBatch::Store writes (a copy of them would be
/// overwritten unread). Every other field of State is copied.
State WithoutBodies(const State& s) {
  static_assert(sizeof(State) == sizeof(double) + sizeof(s.bodies) + sizeof(s.force_integrals) +
                                     sizeof(s.constraint_work) + sizeof(s.contacts) +
                                     sizeof(s.constraint_modes) + sizeof(s.unlisted_contact_work),
                "a field of State is not copied here");
  State x;
  x.t = s.t;
  x.force_integrals = s.force_integrals;
  x.constraint_work = s.constraint_work;
  x.contacts = s.contacts;
  x.constraint_modes = s.constraint_modes;
  x.unlisted_contact_work = s.unlisted_contact_work;
  return x;
}

}  // namespace

double FixedGridStep(const SimulationOptions& options, double t_start) {
  if (!(options.fixed_step > 0.0) || !std::isfinite(options.fixed_step)) {
    throw InputError(fmt::format("fixed step {:.6g} s must be positive", options.fixed_step));
  }
  const double span =
      options.output_interval > 0.0 ? options.output_interval : options.t_end - t_start;
  const auto n = static_cast<long long>(std::ceil(span / options.fixed_step - 1e-9));
  return span / static_cast<double>(std::max(1LL, n));
}

SimulationResult RunFreeBodyBatch(const Model& model, const State& initial,
                                  const SimulationOptions& o) {
  const FreeBodyStepper stepper = o.integrator == IntegratorKind::kSplitting
                                      ? FreeBodyStepper::kSplitting
                                      : FreeBodyStepper::kRk4;
  const double h = FixedGridStep(o, initial.t);
  SimulationResult r;
  r.stats.free_body_batch = true;
  const auto emit = [&](const State& s) {
    if (o.on_sample) o.on_sample(s);
    if (o.store_samples) r.samples.push_back(s);
  };
  FreeBodyRunBatch batch(model, initial);
  GravityLedger ledger(model);
  State state = WithoutBodies(initial);
  emit(initial);
  for (long long k = 1; state.t < o.t_end; ++k) {
    const double t_out =
        o.output_interval > 0.0
            ? std::min(initial.t + static_cast<double>(k) * o.output_interval, o.t_end)
            : o.t_end;
    // The stretch cut into n equal steps as the fixed-step grid cuts it (the 1e-9 forgives a
    // ratio that round-off put just above an integer); the last lands on t_out exactly.
    const double t0 = state.t, span = t_out - t0;
    const long long n = std::max(1LL, static_cast<long long>(std::ceil(span / h - 1e-9)));
    const double step = span / static_cast<double>(n);
    for (long long done = 0; done < n;) {
      const long long m = std::min(kChunkSteps, n - done);
      batch.Advance(stepper, step, m, o.threads);
      // The sums of the bodies at the stretch's start (the first Advance loads them).
      if (done == 0) ledger.Start(batch.mass(), batch.sum_mp(), batch.sum_mv());
      for (long long i = 0; i < m; ++i) {
        ledger.Step(step, state);
        if (o.on_step)
          o.on_step(done + i + 1 == n ? t_out : t0 + static_cast<double>(done + i + 1) * step);
      }
      done += m;
    }
    // The sums of the bodies for the ledger's next stretch, if there is one.
    batch.Store(state, t_out < o.t_end);
    state.t = t_out;
    r.stats.steps += n;
    r.stats.function_evaluations += (stepper == FreeBodyStepper::kRk4 ? 4 : 1) * n;
    if (t_out < o.t_end) emit(state);
  }
  r.final_state = std::move(state);
  emit(r.final_state);
  return r;
}

}  // namespace chasles::internal
