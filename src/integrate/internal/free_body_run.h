#pragma once
/// @file
/// Simulate's free-body batch path (RunPath::kFreeBodyBatch), the batch it keeps its bodies
/// in, and the fixed-step grid it shares with MakeIntegrator.

#include <cstddef>
#include <memory>

#include "chasles/integrate/free_body_batch.h"
#include "chasles/integrate/simulate.h"
#include "chasles/math/types.h"
#include "chasles/model/state.h"

namespace chasles::internal {

/// The step a fixed-step run takes: `options.fixed_step` (> 0, finite; InputError otherwise)
/// shortened to divide the output interval (the whole run from `t_start` when it is 0) evenly,
/// so that every output time is a step end.
double FixedGridStep(const SimulationOptions& options, double t_start);

/// FreeBodyBatch's arrays and steps for one run (free_body_batch.cpp, sharing the class's
/// set-up, conversions and stepping code, so the bodies come out bit for bit as the class's).
/// The arrays live in one buffer that is written before it is read (no fill). On one thread
/// each tile of bodies is set up from the model and loaded from the initial state as the first
/// steps reach it, while it is in cache (on more, all are loaded before the first step), and
/// its compensation is zeroed there; the sums of the gravity ledger (M = Σ m, S = Σ m p,
/// P = Σ m v, in the body order) are taken as the bodies are loaded and stored.
class FreeBodyRunBatch {
 public:
  /// The bodies of `model` (FreeBodyBatchObstacle(model) must be empty; it is not checked
  /// again) with the motion of `initial` (checked by ValidateState). Both are read until the
  /// first Advance or Store and must outlive the batch.
  FreeBodyRunBatch(const Model& model, const State& initial);

  /// As FreeBodyBatch::Advance.
  void Advance(FreeBodyStepper stepper, double h, long long steps, int threads);
  /// Writes the bodies' motion into `state.bodies` (made to the model's size; t and the other
  /// fields are left as they are) and, with `sums`, takes their S and P.
  void Store(State& state, bool sums);

  /// Total mass M [kg], S = Σ m p [kg·m] and P = Σ m v [kg·m/s] of the bodies as last loaded
  /// (by the first Advance) or stored with their sums.
  double mass() const { return mass_; }
  const Vec3& sum_mp() const { return sum_mp_; }
  const Vec3& sum_mv() const { return sum_mv_; }

 private:
  /// Column j of the buffer (n doubles).
  double* Column(size_t j) const;
  /// Sets up and loads the bodies [b, e) (in order: after those before b).
  void LoadBodies(int b, int e);
  /// Loads all the bodies unless they are.
  void Load();

  const Model& model_;
  const State& initial_;
  int n_ = 0;
  Vec3 g_W_ = Vec3::Zero();
  /// The time as the batch counts it (only for the message naming a body that became
  /// non-finite, as FreeBodyBatch's).
  double t_ = 0.0;
  double mass_ = 0.0;
  Vec3 sum_mp_ = Vec3::Zero(), sum_mv_ = Vec3::Zero();
  std::unique_ptr<double[]> columns_;
  std::unique_ptr<bool[]> principal_is_B_;
  bool loaded_ = false;
  bool compensation_valid_ = false;
  FreeBodyStepper compensated_stepper_ = FreeBodyStepper::kRk4;
};

/// Runs free bodies under uniform gravity alone (FreeBodyBatchObstacle empty) with the RK4 or
/// the splitting stepper of FreeBodyBatch: the bodies stay in the batch's arrays
/// (FreeBodyRunBatch) from the start to the end, each stretch between output times advanced
/// tile by tile through its steps, and are written back into a State only at the output
/// times. The bodies come out bit for bit as the batch's own Advance makes them (and as
/// MakeIntegrator's step-by-step wrapper of the batch does); the gravity elements' force
/// integrals are added per step in closed form.
SimulationResult RunFreeBodyBatch(const Model& model, const State& initial,
                                  const SimulationOptions& o);

}  // namespace chasles::internal
