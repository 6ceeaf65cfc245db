#include "chasles/analysis/operating_point.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include <fmt/format.h>
#include <Eigen/Dense>

#include "analysis/internal/comoving.h"
#include "chasles/analysis/linearize.h"
#include "chasles/dynamics/constraint_solve.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/error.h"
#include "chasles/math/quaternion.h"
#include "chasles/model/forces.h"

namespace chasles {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

double Residual(const Model& model, const State& state, const SteadyGenerator& xi) {
  Data data = MakeData(model);
  const VectorXd r = internal::CalcComovingRates(model, state, xi, data);
  return internal::ScaledResidual(r, internal::CalcRateScales(model, state, data));
}

/// The body whose acceleration is largest, for the message of a failed search, and that body
/// as the error's element.
std::pair<std::string, ErrorElement> WorstBody(const Model& model, const State& state) {
  Data data = MakeData(model);
  CalcAccelerations(model, state, data);
  int worst = 0;
  for (int b = 1; b < model.num_bodies(); ++b) {
    if (data.a_WBcm_W[static_cast<size_t>(b)].norm() >
        data.a_WBcm_W[static_cast<size_t>(worst)].norm()) {
      worst = b;
    }
  }
  const Vec3 a = data.a_WBcm_W[static_cast<size_t>(worst)];
  const Vec3 alpha = data.wdot_WB_B[static_cast<size_t>(worst)];
  return {fmt::format("body '{}' keeps an acceleration [{:.6g}, {:.6g}, {:.6g}] m/s² and an "
                      "angular acceleration of {:.6g} rad/s²",
                      model.body(worst).name(), a.x(), a.y(), a.z(), alpha.norm()),
          ErrorElement{ErrorElement::Kind::kBody, worst}};
}

State AtRest(const Model& model, const State& state) {
  State s = state;
  for (BodyState& b : s.bodies) b.v_WBcm_W.setZero(), b.w_WB_B.setZero();
  Data data = MakeData(model);
  ProjectOntoConstraints(model, s, data);
  return s;
}

/// Whether the body's inertia is symmetric about an axis through its centre of mass; its
/// axes of symmetry in B (one, or three for equal moments).
std::vector<Vec3> SymmetryAxes(const Body& body) {
  Eigen::SelfAdjointEigenSolver<Mat3> es(body.I_BBcm_B());
  const Vec3 I = es.eigenvalues();
  const double tol = 1e-9 * I.maxCoeff();
  const bool e01 = std::abs(I[0] - I[1]) <= tol, e12 = std::abs(I[1] - I[2]) <= tol;
  if (e01 && e12) return {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
  if (e01) return {es.eigenvectors().col(2)};
  if (e12) return {es.eigenvectors().col(0)};
  return {};
}

Vec3 GravityAxis(const Model& model) {
  for (int i = 0; i < model.num_force_elements(); ++i) {
    if (const auto* g = dynamic_cast<const UniformGravity*>(&model.force_element(i))) {
      if (g->g_W().norm() > 0.0) return g->g_W().normalized();
    }
  }
  return Vec3::Zero();
}

/// The system's angular momentum about its centre of mass, in W.
Vec3 SystemAngularMomentum(const Model& model, const State& state, const Data& data) {
  double mass = 0.0;
  Vec3 c = Vec3::Zero(), v = Vec3::Zero(), H = Vec3::Zero();
  for (int b = 0; b < model.num_bodies(); ++b) {
    const auto i = static_cast<size_t>(b);
    const double m = model.body(b).mass();
    mass += m, c += m * state.bodies[i].p_WBcm, v += m * state.bodies[i].v_WBcm_W;
  }
  c /= mass, v /= mass;
  for (int b = 0; b < model.num_bodies(); ++b) {
    const auto i = static_cast<size_t>(b);
    const Mat3 I_W = data.R_WB[i] * model.body(b).I_BBcm_B() * data.R_WB[i].transpose();
    H += I_W * data.w_WB_W[i] +
         model.body(b).mass() * (state.bodies[i].p_WBcm - c).cross(state.bodies[i].v_WBcm_W - v);
  }
  return H;
}

/// `state` moved by the finite element exp(τ ξ) of the generator's group.
State MoveByGenerator(const Model& model, const State& state, const SteadyGenerator& xi, double tau,
                      Mat3& Q) {
  const double wn = xi.w_W.norm(), th = tau * wn;
  Q = wn > 0.0 ? Mat3(Eigen::AngleAxisd(th, xi.w_W / wn)) : Mat3::Identity();
  // ∫₀^τ Q(s) ds v: the translation the screw's flow adds.
  Mat3 integral = tau * Mat3::Identity();
  if (wn > 0.0) {
    Mat3 W;
    W << 0.0, -xi.w_W.z(), xi.w_W.y(), xi.w_W.z(), 0.0, -xi.w_W.x(), -xi.w_W.y(), xi.w_W.x(), 0.0;
    integral +=
        (1.0 - std::cos(th)) / (wn * wn) * W + (tau - std::sin(th) / wn) / (wn * wn) * W * W;
  }
  State s = state;
  for (int b = 0; b < model.num_bodies(); ++b) {
    const auto i = static_cast<size_t>(b);
    BodyState& bs = s.bodies[i];
    const Quat E(Eigen::AngleAxisd(tau * xi.spin[i], xi.spin_axis_B[i].normalized()));
    const Quat q = xi.spin[i] != 0.0 ? E : Quat::Identity();
    bs.p_WBcm = Q * bs.p_WBcm + integral * xi.v_W;
    bs.v_WBcm_W = Q * bs.v_WBcm_W;
    bs.q_WB = (Quat(Q) * bs.q_WB * q).normalized();
    bs.w_WB_B = q.conjugate() * bs.w_WB_B;
  }
  return s;
}

/// Throws unless a finite move by the generator carries the accelerations along with it.
void CheckSymmetry(const Model& model, const State& state, const SteadyGenerator& xi) {
  double fastest = xi.w_W.norm();
  for (double s : xi.spin) fastest = std::max(fastest, std::abs(s));
  const double tau = fastest > 0.0 ? 0.7 / fastest : 1.0;
  Mat3 Q;
  const State moved = MoveByGenerator(model, state, xi, tau, Q);
  Data d0 = MakeData(model), d1 = MakeData(model);
  CalcAccelerations(model, state, d0);
  CalcAccelerations(model, moved, d1);
  const internal::RateScales k = internal::CalcRateScales(model, state, d0);
  const ConstraintViolation cv = CalcConstraintViolation(model, moved, d1);
  CalcAccelerations(model, moved, d1);
  double worst = cv.position / k.length;
  for (int b = 0; b < model.num_bodies(); ++b) {
    const auto i = static_cast<size_t>(b);
    worst = std::max(worst, (d1.a_WBcm_W[i] - Q * d0.a_WBcm_W[i]).norm() / k.accel);
    worst =
        std::max(worst, (d1.R_WB[i] * d1.wdot_WB_B[i] - Q * d0.R_WB[i] * d0.wdot_WB_B[i]).norm() *
                            k.length / k.accel);
  }
  if (!(worst <= 1e-8)) {
    throw InputError(fmt::format(
        "steady motion: the state's motion is not a uniform turn, translation or spin that "
        "leaves the scene's equations unchanged (moved along it, the accelerations change by "
        "{:.3g} of their scale); a linearisation about it would not be time-invariant",
        worst));
  }
}

}  // namespace

const char* OperatingPointKindName(OperatingPointKind kind) {
  return kind == OperatingPointKind::kEquilibrium ? "equilibrium" : "steady_motion";
}

OperatingPoint FindEquilibrium(const Model& model, const State& guess,
                               const EquilibriumOptions& options) {
  OperatingPoint op;
  op.generator = internal::ZeroGenerator(model);
  op.state = AtRest(model, guess);
  op.residual = Residual(model, op.state, op.generator);
  while (op.residual > options.tolerance) {
    if (op.iterations == options.max_iterations) {
      const auto [worst, body] = WorstBody(model, op.state);
      throw InputError(
          fmt::format("no static equilibrium found in {} Newton steps from the initial state "
                      "(residual {:.3g}): {}",
                      options.max_iterations, op.residual, worst),
          body);
    }
    ++op.iterations;
    const Linearization lin = Linearize(model, op);
    const int m = static_cast<int>(lin.coordinates.size());
    const int p = static_cast<int>(lin.speeds.size());
    const int N = 6 * model.num_bodies();
    // The speeds' rates at δx = 0 are the accelerations now; their change with the
    // coordinates is A's lower-left block: solve A₂₁ δc = -(rates now).
    Data data = MakeData(model);
    const VectorXd rates = internal::CalcComovingRates(model, op.state, op.generator, data);
    // A Newton step needs coordinates and speeds to solve for; without (the named
    // coordinates of the reduced state came out as no speed at all, or it is not finite) the
    // answer is an error, not a solve of an empty system.
    if (m == 0 || p == 0 || !lin.A.allFinite() || !lin.basis.allFinite() || !rates.allFinite()) {
      throw InputError(fmt::format(
          "no static equilibrium found from the initial state: after {} Newton steps (residual "
          "{:.3g}) the reduced state has {} coordinates and {} speeds to solve for; start the "
          "scene nearer its equilibrium",
          op.iterations - 1, op.residual, m, p));
    }
    const MatrixXd Bu = lin.basis.bottomRows(N).rightCols(p);
    const VectorXd now = Bu.completeOrthogonalDecomposition().solve(rates.tail(N));
    const VectorXd dc = lin.A.bottomLeftCorner(p, m).completeOrthogonalDecomposition().solve(-now);
    VectorXd z = VectorXd::Zero(2 * N);
    z.head(N) = lin.basis.topRows(N).leftCols(m) * dc;
    // A trust region: no body turns by more than half a radian or moves by more than half
    // the length scale in one step. Where the linearisation is nearly singular (a pendulum
    // held level: the restoring stiffness m g L cos θ is 0) the full step is unbounded and
    // would carry the joints beyond what their projection can restore.
    const double length = internal::CalcRateScales(model, op.state, data).length;
    double largest = 0.0;
    for (int b = 0; b < model.num_bodies(); ++b) {
      largest =
          std::max({largest, z.segment<3>(6 * b).norm() / length, z.segment<3>(6 * b + 3).norm()});
    }
    const double first = largest > 0.5 ? 0.5 / largest : 1.0;
    double step = first;
    for (; step > 1e-6 * first; step *= 0.5) {
      State trial;
      try {
        trial = AtRest(model, internal::PerturbState(model, op.state, z, step));
      } catch (const InputError&) {
        continue;  // the constraints cannot be restored from this far: a shorter step
      }
      const double r = Residual(model, trial, op.generator);
      if (r < op.residual) {
        op.state = trial, op.residual = r;
        break;
      }
    }
    if (step <= 1e-6 * first) {
      const auto [worst, body] = WorstBody(model, op.state);
      throw InputError(fmt::format("no static equilibrium near the initial state (no Newton "
                                   "step lowers the residual {:.3g}): {}",
                                   op.residual, worst),
                       body);
    }
  }
  return op;
}

OperatingPoint MakeSteadyMotion(const Model& model, const State& start) {
  const int n = model.num_bodies();
  OperatingPoint op;
  op.kind = OperatingPointKind::kSteadyMotion;
  op.state = start;
  op.generator = internal::ZeroGenerator(model);
  Data data = MakeData(model);
  CalcAccelerations(model, start, data);
  const internal::RateScales k = internal::CalcRateScales(model, start, data);
  // Candidate generators, each as its 6 n velocity rates (lengths scaled by ℓ).
  // The turn: about the gravity axis; in a system no external moment acts on, about its
  // angular momentum H (conserved, so a motion steady in a turning frame turns about H: a
  // torque-free precession); else about any world axis.
  const Vec3 g = GravityAxis(model);
  const Vec3 H = SystemAngularMomentum(model, start, data);
  std::vector<Vec3> turns = g.norm() > 0.0 ? std::vector<Vec3>{g}
                            : internal::TorqueFree(model) && H.norm() > 0.0
                                ? std::vector<Vec3>{H.normalized()}
                                : std::vector<Vec3>{Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
  std::vector<std::pair<int, Vec3>> spins;
  for (int b = 0; b < n; ++b) {
    for (const Vec3& a : SymmetryAxes(model.body(b))) spins.emplace_back(b, a);
  }
  const int cols = static_cast<int>(turns.size() + 3 + spins.size());
  MatrixXd X = MatrixXd::Zero(6 * n, cols);
  VectorXd target(6 * n);
  for (int b = 0; b < n; ++b) {
    const auto i = static_cast<size_t>(b);
    const Vec3& p = start.bodies[i].p_WBcm;
    target.segment<3>(6 * b) = start.bodies[i].v_WBcm_W / k.length;
    target.segment<3>(6 * b + 3) = data.w_WB_W[i];
    for (size_t t = 0; t < turns.size(); ++t) {
      X.block<3, 1>(6 * b, static_cast<int>(t)) = turns[t].cross(p) / k.length;
      X.block<3, 1>(6 * b + 3, static_cast<int>(t)) = turns[t];
    }
    for (int a = 0; a < 3; ++a) {
      X(6 * b + a, static_cast<int>(turns.size()) + a) = 1.0 / k.length;
    }
  }
  for (size_t s = 0; s < spins.size(); ++s) {
    const auto [b, a] = spins[s];
    X.block<3, 1>(6 * b + 3, static_cast<int>(turns.size() + 3 + s)) =
        data.R_WB[static_cast<size_t>(b)] * a;
  }
  // Spins and translations first: a body spinning about a vertical axis of symmetry (a
  // sleeping top) is then seen as spinning, not as the world turning, so that the modes'
  // frequencies are the inertial ones; the turns only when they are needed (a precession).
  MatrixXd X0 = X;
  X0.leftCols(static_cast<int>(turns.size())).setZero();
  VectorXd c = X0.completeOrthogonalDecomposition().solve(target);
  if ((X0 * c - target).norm() > 1e-10 * target.norm()) {
    c = X.completeOrthogonalDecomposition().solve(target);
  }
  for (size_t t = 0; t < turns.size(); ++t) op.generator.w_W += c[static_cast<int>(t)] * turns[t];
  op.generator.v_W = c.segment<3>(static_cast<int>(turns.size()));
  for (size_t s = 0; s < spins.size(); ++s) {
    const auto [b, a] = spins[s];
    const double rate = c[static_cast<int>(turns.size() + 3 + s)];
    if (std::abs(rate) <= 1e-14 * (k.rate + k.speed / k.length)) continue;
    const auto i = static_cast<size_t>(b);
    // Several axes of a sphere: one spin about their resultant.
    const Vec3 total = op.generator.spin[i] * op.generator.spin_axis_B[i] + rate * a;
    op.generator.spin[i] = total.norm();
    op.generator.spin_axis_B[i] = total.normalized();
  }
  op.residual = Residual(model, start, op.generator);
  CheckSymmetry(model, start, op.generator);
  if (op.residual > kNotSteady) {
    throw InputError(fmt::format(
        "the initial motion is not a steady motion (residual {:.3g} of its accelerations; about "
        "1e-15 for one): its modes are not defined. Give a steady motion: a uniform rotation "
        "about a principal axis, a steady precession, steady rolling, a uniform translation; or "
        "all bodies at rest for a static equilibrium",
        op.residual));
  }
  if (op.residual > kSteadyResidual) {
    // The rates of f(y) - ξ·y are the residual times the motion's acceleration scale, so the
    // linearisation carries errors of the order of residual × (the motion's rate) in its
    // eigenvalues; ten times that is the bound stated (the Dzhanibekov box's spurious mode is
    // 1.33 times it).
    const double rate = 10.0 * op.residual * std::max(k.rate, k.speed / k.length);
    op.warnings.push_back(fmt::format(
        "the initial motion is near a steady one but not one (residual {:.3g}; about 1e-15 for "
        "a steady motion): the linearisation is about the state as given, and modes slower "
        "than about {:.3g} 1/s are artefacts of its unsteadiness",
        op.residual, rate));
  }
  return op;
}

OperatingPoint FindOperatingPoint(const Model& model, const State& state,
                                  const EquilibriumOptions& options) {
  for (const BodyState& b : state.bodies) {
    if (b.v_WBcm_W.norm() > 0.0 || b.w_WB_B.norm() > 0.0) return MakeSteadyMotion(model, state);
  }
  return FindEquilibrium(model, state, options);
}

}  // namespace chasles
