#pragma once
/// @file
/// Natural frequencies, damping and stability of small motions about an operating point
/// (docs/modes.md): the eigenvalues λ of the linearisation ẋ = A x (linearize.h).
///
/// Rigid modes — the exact zero eigenvalues a symmetry leaves (a free body's drift, a rolling
/// body's position and heading, a wheel's angle, a steady speed) — are split off before the
/// eigenvalue solve, not read off tiny computed eigenvalues (a zero of multiplicity two, a free
/// body's drift, comes out of an eigenvalue solver as ±1e-8): a coordinate on which no rate
/// depends (its column of A is zero) or a rate that is identically zero (its row is zero) is
/// one rigid mode, and is taken out; this repeats until none is left. The others are the
/// eigenvalues of what remains, their shapes completed over the coordinates taken out.

#include <complex>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "chasles/analysis/error_locator.h"
#include "chasles/analysis/initial_state.h"
#include "chasles/analysis/instantaneous.h"
#include "chasles/analysis/linearize.h"
#include "chasles/analysis/sweep.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {

struct Mode {
  /// λ [1/s]: a complex pair is listed once, with Im λ > 0.
  std::complex<double> eigenvalue;
  /// |Im λ| / 2π [Hz].
  double frequency_hz = 0.0;
  /// ζ = -Re λ / |λ| (1 for a real negative λ, -1 for a real positive one; 0 for λ = 0).
  double damping_ratio = 0.0;
  /// Re λ when it is positive (the mode grows as e^{Re λ t}) [1/s], else 0.
  double growth_rate = 0.0;
  /// Re λ <= kNeutral · (the largest |λ|): decaying or neutral.
  bool stable = true;
  /// |Re λ| <= kNeutral · (the largest |λ|): neither growing nor decaying; its Re λ and
  /// damping ratio are round-off and print as 0.
  bool neutral = false;
  /// A rigid mode (λ = 0 by a symmetry).
  bool rigid = false;
  /// For a rigid mode, the coordinate or speed it frees ("conserved quantity" for one that
  /// none does).
  std::string rigid_coordinate;
  /// The shape over Linearization::coordinates then ::speeds (complex; the largest
  /// coordinate entry is 1, or the largest speed entry when no coordinate moves).
  Eigen::VectorXcd shape;
};

/// Relative size (to the largest |λ|) of Re λ below which a mode counts as neutral, not
/// growing: the round-off of a simple eigenvalue.
inline constexpr double kNeutral = 1e-12;
/// Relative size of |λ| below which a mode that no coordinate frees is rigid all the same (a
/// conserved quantity's zero eigenvalue: a steady precession's momenta).
inline constexpr double kConservedZero = 1e-11;

struct ModalAnalysis {
  Linearization linearization;
  /// Non-rigid modes by increasing |λ| (frequency), then the rigid ones.
  std::vector<Mode> modes;
  /// Every mode is stable (decaying or neutral).
  bool stable = true;
  /// max Re λ over the non-rigid modes [1/s] (what a stability boundary is a zero of).
  double max_real_part = 0.0;
};

/// The modes of a linearisation.
ModalAnalysis CalcModes(const Linearization& lin);

/// One body's motion in a mode: the complex amplitudes of its centre of mass's displacement
/// and of its small rotation about W's axes per unit of Mode::shape, so that the mode's motion
/// is δp(t) = Re(dp e^{λt}), δθ(t) = Re(dtheta e^{λt}) (R = exp(δθ) R₀), in the frame that
/// moves with the operating point's generator (a still frame at an equilibrium).
struct BodyModeShape {
  /// δp: displacement of Bcm in W [m per unit of the shape].
  Eigen::Vector3cd dp;
  /// δθ: small rotation of B about W's axes [rad per unit of the shape].
  Eigen::Vector3cd dtheta;
};

/// Each body's motion (Model order) in `mode`, a mode of `lin`: the maximal perturbation
/// Linearization::basis · Mode::shape read per body. Throws UsageError when the shape is not
/// over lin's coordinates and speeds.
std::vector<BodyModeShape> CalcBodyModeShapes(const Linearization& lin, const Mode& mode);

/// Linearise about `op` and find the modes.
ModalAnalysis AnalyseModes(const Model& model, const OperatingPoint& op,
                           const LinearizeOptions& options = {});

}  // namespace chasles

namespace chasles {

/// How the stability changes.
enum class StabilityChangeKind {
  kOscillatory,  ///< a complex pair crosses Re λ = 0: a flutter or Hopf boundary
  kDivergent,    ///< a real eigenvalue crosses 0
};

/// A parameter value where the stability of a family of operating points changes.
struct StabilityChange {
  /// The parameter's value [its SI unit].
  double value = 0.0;
  StabilityChangeKind kind = StabilityChangeKind::kDivergent;
  /// Whether the family is stable above the value (towards the grid's end).
  bool stable_after = false;
};

/// The stability changes of `analyse` over the sorted `grid`: each change of the verdict
/// between neighbouring values (Mode::stable's: neutral counts as stable) is located to
/// `tolerance` relative to the grid's span. Where a mode crosses Re λ = 0 from clearly decaying
/// to growing, the value is the zero of the largest real part (ModalAnalysis::max_real_part),
/// by regula falsi with the Illinois modification; where one side is neutral (a sleeping top,
/// whose real parts are round-off above its threshold), the verdict's change by bisection.
std::vector<StabilityChange> FindStabilityChanges(
    const std::function<ModalAnalysis(double)>& analyse, const std::vector<double>& grid,
    double tolerance = 1e-12);

}  // namespace chasles

namespace chasles {

/// A critical speed of a spinning system: where the k-th whirl frequency (the k-th non-rigid
/// mode by |λ|, its |Im λ| in rad/s) equals the spin Ω, the parameter of `analyse` [rad/s].
struct CriticalSpeed {
  double speed = 0.0;
  /// Which mode (0-based, by |λ|) crosses.
  int mode = 0;
};

/// The critical speeds of `analyse` over the sorted `grid` of spins [rad/s]: each sign change
/// of |Im λ_k| - Ω between neighbouring values, narrowed by bisection to `tolerance` relative
/// to the span.
std::vector<CriticalSpeed> FindCriticalSpeeds(const std::function<ModalAnalysis(double)>& analyse,
                                              const std::vector<double>& grid,
                                              double tolerance = 1e-12);

}  // namespace chasles

namespace chasles {

/// The small motions of a Model from a state (`chasles modes`): the scene layer makes one from
/// a scene (MakeModesDefinition), a program in code.
struct ModesDefinition {
  std::shared_ptr<const Model> model;
  /// The state the operating point is found from (a static equilibrium near it, or the steady
  /// motion it begins).
  State initial;
  /// Settle `initial` onto the constraints first (SettleInitialState; its warnings are not
  /// kept); none: as it is.
  std::optional<InitialSettling> settle_initial;
  /// Places the analysis's errors at their source (the scene layer's file:line:col); null:
  /// they are thrown as they are.
  ErrorLocator locate_error;
};

struct OperatingPointModes {
  /// Body names, Model order (for the operating point's state).
  std::vector<std::string> bodies;
  OperatingPoint operating_point;
  /// The modes (their linearisation inside, with the finite-difference check done).
  ModalAnalysis modes;
  /// The reactions at the operating point (chapter 8.2: what the supports exert there).
  InstantaneousSolution solution;
};

/// The definition's operating point (FindOperatingPoint), its modes (AnalyseModes with the
/// finite-difference check) and the reactions there. Throws InputError for a Model or state it
/// cannot analyse, through the definition's `locate_error` when it has one.
OperatingPointModes AnalyseOperatingPointModes(const ModesDefinition& definition);

struct ModesSweep {
  /// The swept parameter and its SI unit ("" for a number).
  std::string parameter, unit;
  /// The grid's SI values and each point's modes.
  std::vector<double> values;
  std::vector<OperatingPointModes> points;
  /// Where the stability changes, to 1e-12 of the span.
  std::vector<StabilityChange> changes;
  /// When the parameter is an angular speed (rad/s): the critical speeds, where a whirl
  /// frequency equals it (a rotor's Campbell diagram), to 1e-12 of the span.
  std::vector<CriticalSpeed> critical_speeds;
};

/// The modes over a grid of one parameter, each point analysed from `point`'s definition at the
/// parameter's value (SI); the changes of stability between points narrowed by
/// FindStabilityChanges, and the critical speeds (FindCriticalSpeeds) when the parameter's unit
/// is "rad/s" or "1/s" (each step analyses a new definition). The errors are the points'.
ModesSweep SweepModes(const ParameterGrid& grid,
                      const std::function<ModesDefinition(double value)>& point);

}  // namespace chasles
