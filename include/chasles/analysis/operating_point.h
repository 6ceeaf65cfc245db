#pragma once
/// @file
/// Operating points for small motions (docs/modes.md): a static equilibrium (every body at
/// rest, every acceleration zero, the constraints holding), or a steady motion — a relative
/// equilibrium of a symmetry of the scene: a motion x₀(t) = G(t) x₀(0) where G(t) = exp(t ξ)
/// turns the whole system uniformly about a world axis, translates it uniformly, and spins
/// bodies of revolution about their own axes (a sleeping top, a top in steady precession, a
/// disk or a bicycle rolling straight, a rotor on its bearings). In coordinates that move with
/// G, y = G(-t) x, the motion obeys ẏ = f(y) - ξ·y and x₀(0) is an equilibrium of it; the
/// residual |f(y₀) - ξ·y₀| says how nearly the scene's state is one.

#include <string>
#include <vector>

#include "chasles/math/types.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {

/// The generator ξ of a steady motion: a world rotation about an axis through the world
/// origin, a world translation, and a spin of each body of revolution about its own axis.
struct SteadyGenerator {
  /// Rotation rate vector of the whole system, in W [rad/s] (about an axis through Wo).
  Vec3 w_W = Vec3::Zero();
  /// Translation velocity of the whole system, in W [m/s].
  Vec3 v_W = Vec3::Zero();
  /// Per body: spin rate about its axis of symmetry [rad/s] (0 for a body without one).
  std::vector<double> spin;
  /// Per body: that unit axis, in B (zero for a body without one).
  std::vector<Vec3> spin_axis_B;
};

enum class OperatingPointKind { kEquilibrium, kSteadyMotion };

/// "equilibrium" or "steady_motion".
const char* OperatingPointKindName(OperatingPointKind kind);

struct OperatingPoint {
  OperatingPointKind kind = OperatingPointKind::kEquilibrium;
  /// The state (on the constraints).
  State state;
  /// Zero for an equilibrium.
  SteadyGenerator generator;
  /// Largest |f(y₀) - ξ·y₀| over the bodies' accelerations, scaled to be dimensionless by the
  /// problem's accelerations (g, v²/ℓ, ω² ℓ): ~1e-15 for an exact operating point.
  double residual = 0.0;
  /// Newton iterations an equilibrium took (0 when the given state was one already).
  int iterations = 0;
  /// What the analysis should be read with: a steady motion whose residual is above
  /// kSteadyResidual (the state is not exactly steady; slow modes are its artefacts).
  std::vector<std::string> warnings;
};

/// A steady motion's residual above this is reported (OperatingPoint::warnings): the state
/// given is near one, not one (an exact one is at round-off, about 1e-15).
inline constexpr double kSteadyResidual = 1e-9;
/// A residual above this is no steady motion at all: an InputError.
inline constexpr double kNotSteady = 1e-2;

struct EquilibriumOptions {
  /// Stop when the scaled residual is below this.
  double tolerance = 1e-12;
  /// Most Newton iterations.
  int max_iterations = 50;
};

/// A static equilibrium found by Newton's method on the constrained equations from `guess`
/// (its velocities are set to zero): each step solves the linearised accelerations for the
/// correction of the minimal coordinates, takes it (halved while the residual grows) and
/// projects onto the constraints. Throws InputError when there is none near the guess: "no
/// static equilibrium: ..." with the body whose acceleration stays and its value.
OperatingPoint FindEquilibrium(const Model& model, const State& guess,
                               const EquilibriumOptions& options = {});

/// The steady motion the state `start` begins: the generator ξ that best explains its
/// velocities (least squares over the scene's candidate symmetries: rotation about the
/// gravity axis, or any axis without gravity; translations; spins of bodies whose inertia is
/// symmetric about an axis through the centre of mass), and its residual. Throws InputError
/// when the state's velocities are not those of any such motion, or when a uniform turn of the
/// state by ξ changes its accelerations otherwise than by the turn (ξ is no symmetry of the
/// scene: the linearisation would not be time-invariant).
OperatingPoint MakeSteadyMotion(const Model& model, const State& start);

/// An equilibrium when every body of `state` is at rest (FindEquilibrium), a steady motion
/// otherwise (MakeSteadyMotion).
OperatingPoint FindOperatingPoint(const Model& model, const State& state,
                                  const EquilibriumOptions& options = {});

}  // namespace chasles
