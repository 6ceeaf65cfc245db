#pragma once
/// @file
/// A fast path for many free bodies under uniform gravity: the bodies are stored as a structure
/// of arrays (one array per coordinate) in their principal frames and stepped by loops the
/// compiler vectorises, with the quaternion renormalised once per step (not per evaluation).
/// Two steppers:
///  - kRk4: classical RK4 with compensated updates (as Rk4Integrator) on Newton's equation m a = m
///  g and Euler's equations in the
///    principal frame P (chapter eqs. 8.79-8.81 with M = 0: I₁ω̇₁ = (I₂ − I₃) ω₂ω₃ and cyclic) with
///    q̇ = ½ q ⊗ (0, ω). The same method and step as Rk4Integrator; the translation is taken
///    in closed form (RK4 is exact on it too).
///  - kSplitting: a second-order symmetric splitting (docs/design.md, "Batched free bodies"):
///    the translation exact under uniform gravity, the free rotation split into the flows of
///    L₁²/2I₁, L₂²/2I₂, L₃²/2I₃ (half, half, full, half, half; McLachlan 1993, Reich 1994,
///    Dullweber, Leimkuhler & McLachlan 1997), each a rotation about a principal axis by the
///    Cayley angle 2 atan(hω_i/2): orthogonal, no sin or cos, |L_W| and |q| kept to round-off.
/// The state is independent per body, so bodies may be split into `threads` contiguous blocks:
/// results are bitwise the same for any thread count.

#include <array>
#include <limits>
#include <string>
#include <vector>

#include "chasles/integrate/obstacle.h"
#include "chasles/integrate/stats.h"
#include "chasles/math/types.h"
#include "chasles/model/state.h"

namespace chasles {

class Model;

enum class FreeBodyStepper { kRk4, kSplitting };

/// Why FreeBodyBatch cannot step `model` (empty when it can): it needs only bodies with three
/// positive principal moments, only UniformGravity force elements, and no constraints or
/// contacts.
ModelObstacle FreeBodyBatchObstacle(const Model& model);

class FreeBodyBatch {
 public:
  /// Takes the bodies' masses, principal moments and axes and the total gravity from `model`
  /// (which need not outlive the batch). Throws InputError with FreeBodyBatchObstacle's reason.
  explicit FreeBodyBatch(const Model& model);

  /// Number of bodies.
  int size() const { return n_; }
  /// Total uniform gravitational acceleration (sum of the model's UniformGravity elements), in W
  /// [m/s²].
  const Vec3& g_W() const { return g_W_; }
  /// Time of the batch's state [s].
  double t() const { return t_; }

  /// Takes t and the bodies' motion from `state` (in the model's body order), re-expressed in
  /// the principal frames (exactly when a body's inertia is already diagonal in B).
  void Load(const State& state);
  /// Writes t and the bodies' motion back into `state` (sized for the model); other fields are
  /// left as they are.
  void Store(State& state) const;

  /// Advances every body by `steps` steps of `h` [s] > 0 with `stepper`, the bodies split into
  /// `threads` >= 1 contiguous blocks (bitwise the same result for any number).
  void Advance(FreeBodyStepper stepper, double h, long long steps, int threads = 1);

 private:
  int n_ = 0;
  Vec3 g_W_;
  double t_ = 0.0;
  /// Per body: mass [kg]; principal moments [kg·m²]; Euler coefficients a₁ = (I₂ − I₃)/I₁ and
  /// cyclic [1]; the principal frame's orientation in B, q_BP (w, x, y, z), and whether it is
  /// the identity (then no conversion is made).
  std::vector<double> mass_, I1_, I2_, I3_, a1_, a2_, a3_;
  std::vector<Quat> q_BP_;
  std::vector<char> principal_is_B_;
  /// State, one array per coordinate: p_WBcm [m] (0–2), v_WBcm_W [m/s] (3–5), q_WP (w, x, y,
  /// z) (6–9), w_WP_P [rad/s] (10–12); and the compensation of each (compensated updates,
  /// internal/compensated.h: every coordinate for RK4, the translation's for the splitting),
  /// valid while one stepper has stepped since the last Load.
  std::array<std::vector<double>, 13> y_, c_;
  bool compensation_valid_ = false;
  FreeBodyStepper compensated_stepper_ = FreeBodyStepper::kRk4;
};

/// One of FreeBodyBatch's steppers behind the Rk4Integrator-like stepping interface that the
/// fixed-step grid (MakeIntegrator) drives: Simulate uses it with kRk4 for fixed-step RK4 runs of
/// models that qualify (FreeBodyBatchObstacle empty), and with kSplitting for the `splitting`
/// integrator (IntegratorKind::kSplitting, which only such models may use). The force integrals of
/// the UniformGravity elements are added in closed form: work m g·Δp, impulse m g h, angular
/// impulse (∫ Σ m p dt) × g. The result agrees with Rk4Integrator's to round-off
/// (tests/unit/integrate/free_body_batch_test.cpp); Rk4Integrator additionally carries the rounding
/// of its state updates from step to step (compensated sums), this one does not.
class FreeBodyBatchIntegrator {
 public:
  /// `model` must outlive the integrator.
  FreeBodyBatchIntegrator(const Model& model, FreeBodyStepper stepper);
  /// Advances `state` (t, bodies, force integrals) by one step of `h` [s] > 0.
  void Step(State& state, double h);
  /// Work done so far; function_evaluations counts 4 per step for RK4 (like Rk4Integrator) and
  /// 1 for the splitting (one pass over the bodies, no force evaluation).
  const IntegratorStats& stats() const { return stats_; }

 private:
  const Model& model_;
  FreeBodyStepper stepper_;
  FreeBodyBatch batch_;
  std::vector<Vec3> element_g_W_;
  /// The bodies as the last step left them: the batch's own state stands for them.
  std::vector<BodyState> last_;
  bool carried_ = false;
  /// Total mass [kg].
  double mass_ = 0.0;
  /// Compensation of the time and the time the last step ended at (as in Rk4Integrator).
  double c_t_ = 0.0, t_end_ = std::numeric_limits<double>::quiet_NaN();
  IntegratorStats stats_;
};

}  // namespace chasles
