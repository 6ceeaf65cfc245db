#pragma once
/// @file
/// Whirl of a rotor on elastic bearings against its spin (docs/modes.md, "Whirl and critical
/// speeds"): the rotor, at its static equilibrium on the bearings, is set spinning at Ω about
/// an axis a through its centre of mass, the steady motion is linearised (modes.h), and each
/// mode's direction of whirl is read from its shape. For a complex amplitude u (a body's
/// displacement δp or small rotation δθ, x(t) = Re(u e^{iωt}), ω = Im λ > 0) the mean of
/// x × ẋ is -ω Re u × Im u, so the mode's whirl angular momentum about a is
///   h = -ω Σ_b [m_b (Re δp × Im δp) + I_t,b (Re δθ × Im δθ)] · a,
/// I_t,b = (tr I_b - aᵀ I_b a)/2 the body's mean moment across a. h > 0 (with Ω >= 0 about a)
/// is forward whirl, h < 0 backward. h is a Hermitian form in u; where an eigenvalue is
/// repeated (a symmetric rotor's translation: forward and backward at one frequency) the
/// eigenspace is split by that form into its forward and backward members. A critical speed is
/// a spin at which a whirl frequency |Im λ| equals Ω (FindCriticalSpeeds).

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "chasles/analysis/modes.h"
#include "chasles/model/model.h"

namespace chasles {

enum class WhirlDirection { kForward, kBackward, kNone };

/// "forward", "backward", "none".
const char* WhirlDirectionName(WhirlDirection d);

struct WhirlMode {
  /// λ [1/s] with Im λ > 0.
  std::complex<double> eigenvalue;
  double frequency_hz = 0.0, damping_ratio = 0.0;
  /// kNone: no whirl about the axis (axial or torsional motion), or at Ω = 0, where forward
  /// and backward whirl are one.
  WhirlDirection direction = WhirlDirection::kNone;
};

struct WhirlPoint {
  /// Spin [rad/s] and the non-rigid modes there, by |λ|.
  double speed = 0.0;
  std::vector<WhirlMode> modes;
};

struct WhirlCriticalSpeed {
  /// Spin [rad/s] at which a whirl frequency equals it, and the direction(s) of the modes
  /// crossing there ("forward", "backward", or both for a repeated frequency).
  double speed = 0.0;
  std::vector<WhirlDirection> directions;
};

struct WhirlMap {
  std::vector<WhirlPoint> points;
  std::vector<WhirlCriticalSpeed> critical_speeds;
};

/// The whirl of body `rotor` of `model` about the axis a_W (through its centre of mass) over the
/// ascending `speeds` [rad/s, >= 0], starting from `state` (its static equilibrium is found
/// first, FindEquilibrium; the other bodies stay at rest). The rotor must be a body of
/// revolution about a (else the motion is not steady: InputError). Critical speeds are located
/// by bisection between the grid's points to 1e-12 of the span.
WhirlMap CalcWhirl(const Model& model, const State& state, BodyIndex rotor, const Vec3& a_W,
                   const std::vector<double>& speeds);

/// Whether a bearing element of `model` (model/bearing.h) holds body `body`: whirl needs the
/// rotor on elastic bearings.
bool HeldByBearing(const Model& model, BodyIndex body);

/// `count` (2 or more) spins from `from` to `to` [rad/s], evenly spaced, the last exactly `to`.
std::vector<double> WhirlSpeedGrid(double from, double to, int count);

/// The whirl rows of a rotor's balance (`chasles balance`, docs/modes.md "Rotors"): CalcWhirl
/// over `speeds` when given, else over 21 spins from 0 to twice `speed` [rad/s] when it is
/// positive and finite, else from 0 to twice the highest whirl frequency at rest. None when no
/// bearing holds the rotor (with `speeds` given, an InputError: they ask for rows there cannot
/// be) or when nothing whirls.
std::optional<WhirlMap> CalcRotorWhirl(const Model& model, const State& state, BodyIndex rotor,
                                       const Vec3& a_W, const std::vector<double>& speeds,
                                       double speed);

}  // namespace chasles
