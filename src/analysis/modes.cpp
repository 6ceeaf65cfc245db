#include "chasles/analysis/modes.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SVD>

#include "chasles/error.h"

namespace chasles {
namespace {

using Eigen::MatrixXd;

/// Takes out rigid coordinates — a zero column (nothing depends on it), a zero row (its rate
/// is identically zero), the system's free centre of mass — until none is left; returns them
/// in order and the kept ones.
std::vector<int> SplitRigid(const Linearization& lin, std::vector<int>& kept) {
  const MatrixXd& A = lin.A;
  const int m = static_cast<int>(lin.coordinates.size());
  const double tol = 1e-11 * std::max(A.norm(), 1e-300);
  std::vector<int> removed;
  kept.resize(static_cast<size_t>(A.rows()));
  for (int i = 0; i < A.rows(); ++i) kept[static_cast<size_t>(i)] = i;
  // The system's free centre of mass (linearize.h): in a turning frame its drift couples
  // its own coordinates (Coriolis) but nothing else; taken out whole.
  std::vector<int> group;
  const auto named = [&](int i) {
    const std::string& s = i < m ? lin.coordinates[static_cast<size_t>(i)].name
                                 : lin.speeds[static_cast<size_t>(i - m)].name;
    return s.rfind("system.", 0) == 0 || s.rfind("d(system.", 0) == 0;
  };
  for (int i = 0; i < A.rows(); ++i) {
    if (named(i)) group.push_back(i);
  }
  bool apart = !group.empty();
  for (int i : group) {
    for (int j = 0; j < A.rows(); ++j) {
      const bool in = std::find(group.begin(), group.end(), j) != group.end();
      if (!in && (std::abs(A(j, i)) > tol || std::abs(A(i, j)) > tol)) apart = false;
    }
  }
  if (apart) {
    for (int i : group) {
      removed.push_back(i);
      kept.erase(std::find(kept.begin(), kept.end(), i));
    }
  }
  for (bool again = true; again;) {
    again = false;
    for (size_t k = 0; k < kept.size(); ++k) {
      const int i = kept[k];
      double col = 0.0, row = 0.0;
      for (int j : kept)
        col = std::max(col, std::abs(A(j, i))), row = std::max(row, std::abs(A(i, j)));
      if (col <= tol || row <= tol) {
        removed.push_back(i);
        kept.erase(kept.begin() + static_cast<long>(k));
        again = true;
        break;
      }
    }
  }
  return removed;
}

/// Takes out of `Ak` the zero eigenvalues left by conserved quantities (a precessing top's
/// momenta, a rolling disk's): while its smallest singular value is round-off (1e-13 of
/// |A|), turns its null vector into the first coordinate by a Householder reflection Q (then
/// Qᵀ Ak Q has a zero first column) and keeps the rest. Returns how many it took out.
int DeflateConserved(MatrixXd& Ak, double scale) {
  int count = 0;
  while (Ak.rows() > 0) {
    Eigen::JacobiSVD<MatrixXd> svd(Ak, Eigen::ComputeFullV);
    const Eigen::Index k = Ak.rows();
    if (svd.singularValues()[k - 1] > 1e-13 * scale) break;
    const Eigen::VectorXd v = svd.matrixV().col(k - 1);
    Eigen::HouseholderQR<MatrixXd> qr(v);
    const MatrixXd Q = qr.householderQ();
    const MatrixXd B = Q.transpose() * Ak * Q;
    Ak = B.bottomRightCorner(k - 1, k - 1);
    ++count;
  }
  return count;
}

/// The eigenvector of A for λ: the right singular vector of A - λ E for its smallest
/// singular value.
Eigen::VectorXcd ShapeOf(const MatrixXd& A, std::complex<double> lambda) {
  const Eigen::MatrixXcd M =
      A.cast<std::complex<double>>() - lambda * Eigen::MatrixXcd::Identity(A.rows(), A.cols());
  Eigen::JacobiSVD<Eigen::MatrixXcd> svd(M, Eigen::ComputeFullV);
  return svd.matrixV().col(A.cols() - 1);
}

Mode MakeMode(std::complex<double> lambda, Eigen::VectorXcd shape, int m, double scale) {
  Mode mode;
  mode.eigenvalue = lambda;
  mode.frequency_hz = std::abs(lambda.imag()) / (2.0 * std::numbers::pi);
  const double mag = std::abs(lambda);
  mode.damping_ratio = mag > 0.0 ? -lambda.real() / mag : 0.0;
  mode.stable = lambda.real() <= kNeutral * scale;
  mode.neutral = std::abs(lambda.real()) <= kNeutral * scale;
  mode.growth_rate = mode.stable ? 0.0 : lambda.real();
  // Normalise: the largest coordinate entry (else speed entry) becomes 1.
  Eigen::Index at = 0;
  const bool coords = m > 0 && shape.head(m).cwiseAbs().maxCoeff() > 0.0;
  if (coords) {
    shape.head(m).cwiseAbs().maxCoeff(&at);
  } else {
    shape.cwiseAbs().maxCoeff(&at);
  }
  if (std::abs(shape[at]) > 0.0) shape /= shape[at];
  mode.shape = shape;
  return mode;
}

}  // namespace

ModalAnalysis CalcModes(const Linearization& lin) {
  ModalAnalysis out;
  out.linearization = lin;
  const MatrixXd& A = lin.A;
  const int d = static_cast<int>(A.rows());
  const int m = static_cast<int>(lin.coordinates.size());
  std::vector<int> kept;
  const std::vector<int> removed = SplitRigid(lin, kept);
  const int k = static_cast<int>(kept.size());
  MatrixXd Ak(k, k);
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k; ++j)
      Ak(i, j) = A(kept[static_cast<size_t>(i)], kept[static_cast<size_t>(j)]);
  }
  std::vector<Mode> modes;
  const double scale = std::max(A.norm(), 1e-300);
  const int conserved = DeflateConserved(Ak, scale);
  if (Ak.rows() > 0) {
    Eigen::EigenSolver<MatrixXd> es(Ak, false);
    for (int e = 0; e < Ak.rows(); ++e) {
      const std::complex<double> lambda = es.eigenvalues()[e];
      if (lambda.imag() < 0.0) continue;
      modes.push_back(MakeMode(lambda, ShapeOf(A, lambda), m, scale));
    }
    std::sort(modes.begin(), modes.end(), [](const Mode& a, const Mode& b) {
      return std::abs(a.eigenvalue) < std::abs(b.eigenvalue);
    });
  }
  for (int c = 0; c < conserved; ++c) {
    Mode mode = MakeMode(0.0, ShapeOf(A, 0.0), m, 1.0);
    mode.rigid = true;
    mode.rigid_coordinate = "conserved quantity";
    modes.push_back(mode);
  }
  out.max_real_part = -std::numeric_limits<double>::infinity();
  for (const Mode& mode : modes) {
    if (mode.rigid) continue;
    out.stable = out.stable && mode.stable;
    out.max_real_part = std::max(out.max_real_part, mode.eigenvalue.real());
  }
  if (!std::isfinite(out.max_real_part)) out.max_real_part = 0.0;
  for (const int r : removed) {
    Eigen::VectorXcd v = Eigen::VectorXcd::Zero(d);
    v[r] = 1.0;
    Mode mode = MakeMode(0.0, v, m, 1.0);
    mode.rigid = true;
    mode.rigid_coordinate = r < m ? lin.coordinates[static_cast<size_t>(r)].name
                                  : lin.speeds[static_cast<size_t>(r - m)].name;
    modes.push_back(mode);
  }
  out.modes = std::move(modes);
  return out;
}

std::vector<BodyModeShape> CalcBodyModeShapes(const Linearization& lin, const Mode& mode) {
  // x = [coordinates; speeds] and ẋ = A x (linearize.h); Mode::shape is x̂ with A x̂ = λ x̂,
  // its entries in the same order (ShapeOf: the null vector of A - λE over all of x). The
  // linearisation keeps w (the reduced state, z = V w) and x = S w, and stores
  // basis = V S⁻¹: column j is the maximal perturbation z of a unit x_j. So the mode's
  // maximal perturbation is ẑ = basis · x̂, and since basis is real, x(t) = Re(x̂ e^{λt})
  // moves the bodies by z(t) = Re(ẑ e^{λt}). z is [δq; δu], δq = [δp_0, δθ_0, δp_1, δθ_1, ...]
  // over the n bodies (6 each) followed by δu = [δv_0, δω_0, ...] (PerturbState's order), so
  // body b's δp and δθ are ẑ's entries 6b..6b+2 and 6b+3..6b+5 of its first 6n rows.
  if (mode.shape.size() != lin.basis.cols() || lin.basis.rows() % 12 != 0) {
    throw UsageError(fmt::format(
        "CalcBodyModeShapes: a shape of {} entries for a linearisation of {} coordinates and "
        "speeds",
        mode.shape.size(), lin.basis.cols()));
  }
  const Eigen::Index n = lin.basis.rows() / 12;
  const Eigen::VectorXcd z = lin.basis.topRows(6 * n).cast<std::complex<double>>() * mode.shape;
  std::vector<BodyModeShape> out(static_cast<size_t>(n));
  for (Eigen::Index b = 0; b < n; ++b) {
    out[static_cast<size_t>(b)].dp = z.segment<3>(6 * b);
    out[static_cast<size_t>(b)].dtheta = z.segment<3>(6 * b + 3);
  }
  return out;
}

ModalAnalysis AnalyseModes(const Model& model, const OperatingPoint& op,
                           const LinearizeOptions& options) {
  return CalcModes(Linearize(model, op, options));
}

}  // namespace chasles

namespace chasles {

namespace {

/// Whether the largest real part `f` of an analysis is clearly on its verdict's side: clearly
/// negative on a stable side (decaying, not neutral), positive on an unstable one.
bool Transversal(const ModalAnalysis& a) {
  double scale = 0.0;
  for (const Mode& m : a.modes) scale = std::max(scale, std::abs(m.eigenvalue));
  return a.stable ? a.max_real_part < -kNeutral * scale : a.max_real_part > 0.0;
}

/// The value in [a, b] where the verdict changes, `sa` the analysis at a and `sb` at b. When
/// both sides are transversal the boundary is the zero of the largest real part, a continuous
/// function of the parameter: regula falsi with the Illinois modification (superlinear), the
/// bracket kept by its sign. Otherwise (a neutral side, whose real parts are round-off) it is
/// the verdict's change, by bisection. Either to `width`. Returns the value and the end of the
/// final bracket on the unstable side.
std::pair<double, double> LocateChange(const std::function<ModalAnalysis(double)>& analyse,
                                       double a, double b, const ModalAnalysis& sa,
                                       const ModalAnalysis& sb, double width) {
  const bool before = sa.stable;
  if (!Transversal(sa) || !Transversal(sb)) {
    while (std::abs(b - a) > width) {
      const double mid = 0.5 * (a + b);
      (analyse(mid).stable == before ? a : b) = mid;
    }
    return {0.5 * (a + b), before ? b : a};
  }
  double fa = sa.max_real_part, fb = sb.max_real_part;
  int side = 0;  // which end stayed last time (Illinois: halve its value when it stays twice)
  for (int it = 0; it < 200 && std::abs(b - a) > width; ++it) {
    double x = (a * fb - b * fa) / (fb - fa);
    if (!(x > a && x < b)) x = 0.5 * (a + b);
    const double fx = analyse(x).max_real_part;
    if (fx == 0.0) return {x, x};
    if ((fx < 0.0) == (fa < 0.0)) {
      a = x, fa = fx;
      if (side == -1) fb *= 0.5;
      side = -1;
    } else {
      b = x, fb = fx;
      if (side == 1) fa *= 0.5;
      side = 1;
    }
  }
  return {std::abs(fa) < std::abs(fb) ? a : b, fa > 0.0 ? a : b};
}

}  // namespace

std::vector<StabilityChange> FindStabilityChanges(
    const std::function<ModalAnalysis(double)>& analyse, const std::vector<double>& grid,
    double tolerance) {
  std::vector<StabilityChange> out;
  if (grid.size() < 2) return out;
  const double span = std::abs(grid.back() - grid.front());
  ModalAnalysis before = analyse(grid[0]);
  for (size_t i = 1; i < grid.size(); ++i) {
    ModalAnalysis after = analyse(grid[i]);
    if (after.stable != before.stable) {
      StabilityChange c;
      const auto [value, unstable_end] =
          LocateChange(analyse, grid[i - 1], grid[i], before, after, tolerance * span);
      c.value = value;
      c.stable_after = after.stable;
      // The kind: that of the mode with the largest real part on the unstable side, next to
      // the boundary (where it may be within the neutral band: its verdict is not asked).
      const ModalAnalysis near = analyse(unstable_end);
      const Mode* crossing = nullptr;
      for (const Mode& m : near.modes) {
        if (!m.rigid && (!crossing || m.eigenvalue.real() > crossing->eigenvalue.real())) {
          crossing = &m;
        }
      }
      const bool oscillatory =
          crossing && crossing->eigenvalue.imag() > kNeutral * std::abs(crossing->eigenvalue);
      c.kind = oscillatory ? StabilityChangeKind::kOscillatory : StabilityChangeKind::kDivergent;
      out.push_back(c);
    }
    before = std::move(after);
  }
  return out;
}

}  // namespace chasles

namespace chasles {
namespace {

/// |Im λ| of the non-rigid modes, by |λ|.
std::vector<double> WhirlFrequencies(const ModalAnalysis& a) {
  std::vector<double> w;
  for (const Mode& m : a.modes) {
    if (!m.rigid) w.push_back(std::abs(m.eigenvalue.imag()));
  }
  return w;
}

}  // namespace

std::vector<CriticalSpeed> FindCriticalSpeeds(const std::function<ModalAnalysis(double)>& analyse,
                                              const std::vector<double>& grid, double tolerance) {
  std::vector<CriticalSpeed> out;
  if (grid.size() < 2) return out;
  const double span = std::abs(grid.back() - grid.front());
  std::vector<double> before = WhirlFrequencies(analyse(grid[0]));
  for (size_t i = 1; i < grid.size(); ++i) {
    const std::vector<double> after = WhirlFrequencies(analyse(grid[i]));
    const size_t n = std::min(before.size(), after.size());
    for (size_t k = 0; k < n; ++k) {
      const double ga = before[k] - grid[i - 1], gb = after[k] - grid[i];
      if ((ga > 0.0) == (gb > 0.0) || ga == 0.0) continue;
      double a = grid[i - 1], b = grid[i];
      while (std::abs(b - a) > tolerance * span) {
        const double mid = 0.5 * (a + b);
        const std::vector<double> w = WhirlFrequencies(analyse(mid));
        const double g = k < w.size() ? w[k] - mid : gb;
        ((g > 0.0) == (ga > 0.0) ? a : b) = mid;
      }
      out.push_back({0.5 * (a + b), static_cast<int>(k)});
    }
    before = after;
  }
  std::sort(out.begin(), out.end(),
            [](const CriticalSpeed& x, const CriticalSpeed& y) { return x.speed < y.speed; });
  return out;
}

}  // namespace chasles

namespace chasles {

OperatingPointModes AnalyseOperatingPointModes(const ModesDefinition& definition) {
  try {
    if (!definition.model)
      throw InputError("a modes analysis needs its Model (ModesDefinition::model)");
    const Model& model = *definition.model;
    OperatingPointModes out;
    for (int b = 0; b < model.num_bodies(); ++b) out.bodies.push_back(model.body(b).name());
    std::vector<std::string> warnings;
    const State initial =
        definition.settle_initial
            ? SettleInitialState(model, definition.initial, *definition.settle_initial, warnings)
            : definition.initial;
    out.operating_point = FindOperatingPoint(model, initial);
    LinearizeOptions options;
    options.finite_difference_check = true;
    out.modes = AnalyseModes(model, out.operating_point, options);
    out.solution = SolveInstantaneous(model, out.operating_point.state);
    return out;
  } catch (const InputError& e) {
    if (!definition.locate_error) throw;
    definition.locate_error(e);
    throw;  // a locator that returns leaves the error as it is
  }
}

ModesSweep SweepModes(const ParameterGrid& grid,
                      const std::function<ModesDefinition(double value)>& point) {
  if (grid.names.size() != 1) throw UsageError("a modes sweep is over one parameter");
  ModesSweep out;
  out.parameter = grid.names[0];
  out.unit = grid.units[0];
  const auto at = [&](double value) { return AnalyseOperatingPointModes(point(value)); };
  for (std::int64_t k = 0; k < grid.size(); ++k) {
    out.values.push_back(grid.Values(k)[0]);
    out.points.push_back(at(out.values.back()));
  }
  // The grid's points are analysed already: the narrowing analyses only between them.
  const auto analyse = [&](double value) {
    for (size_t k = 0; k < out.values.size(); ++k) {
      if (out.values[k] == value) return out.points[k].modes;
    }
    return at(value).modes;
  };
  out.changes = FindStabilityChanges(analyse, out.values);
  if (out.unit == "rad/s" || out.unit == "1/s") {
    out.critical_speeds = FindCriticalSpeeds(analyse, out.values);
  }
  return out;
}

}  // namespace chasles
