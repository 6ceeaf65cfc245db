#pragma once
/// @file
/// The equations of motion in the frame that moves with a steady motion's generator ξ
/// (analysis/operating_point.h), evaluated by the engine itself (CalcAccelerations): shared by
/// the operating points, the linearisation's finite-difference check and the tests.

#include <Eigen/Core>

#include "chasles/analysis/operating_point.h"
#include "chasles/model/data.h"

namespace chasles::internal {

/// Scales that make the rates dimensionless: a length ℓ (radii of gyration, distances of the
/// centres of mass from Wo), a speed, an angular rate and an acceleration (g, v²/ℓ, ω² ℓ).
struct RateScales {
  double length = 1.0, speed = 0.0, rate = 0.0, accel = 0.0;
};

/// The 12 n rates of the co-moving state, per body [ṗ - w_ξ × p - v_ξ; w_W - w_ξ - s R a;
/// a - w_ξ × v; α_W - w_ξ × w_W] (zero at an operating point), with the engine's accelerations.
Eigen::VectorXd CalcComovingRates(const Model& model, const State& state, const SteadyGenerator& xi,
                                  Data& data);

/// Scales of `state` and its rates (needs the acceleration stage of `data` at `state`).
RateScales CalcRateScales(const Model& model, const State& state, const Data& data);

/// The largest rate relative to its scale (velocity rows by max(speed, rate ℓ), acceleration
/// rows by the acceleration scale).
double ScaledResidual(const Eigen::VectorXd& rates, const RateScales& s);

/// `state` moved by the maximal perturbation z (12 per body: δp, δθ about W's axes, δv, δω in
/// W) times h: p += h δp, q = exp(h δθ) q, v += h δv, w_W += h δω.
State PerturbState(const Model& model, const State& state, const Eigen::VectorXd& z, double h);

/// Whether nothing ties the system to a place: no constraint, spring or bearing to the world
/// (then its centre of mass moves freely, and in a turning frame its drift is a frame's
/// artefact).
bool TranslationInvariant(const Model& model);

/// Whether no external force or moment acts: translation invariant, and every force element
/// a spring between two bodies or zero gravity (then the angular momentum is conserved, and a
/// steady motion turns about it).
bool TorqueFree(const Model& model);

/// A generator with no motion, sized for `model`.
SteadyGenerator ZeroGenerator(const Model& model);

}  // namespace chasles::internal
