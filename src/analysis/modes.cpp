#include "chasles/analysis/modes.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Eigenvalues>

namespace chasles {
namespace {

using Eigen::MatrixXd;

/// A coordinate taken out as rigid: by its zero column (nothing depends on it) or its zero
/// row (its rate is identically zero).
struct Removed {
  int index = 0;
  bool by_column = true;
};

/// Takes out rigid coordinates until none is left; returns them in order and the kept ones.
std::vector<Removed> SplitRigid(const MatrixXd& A, std::vector<int>& kept) {
  const double tol = 1e-11 * std::max(A.norm(), 1e-300);
  std::vector<Removed> removed;
  kept.resize(static_cast<size_t>(A.rows()));
  for (int i = 0; i < A.rows(); ++i) kept[static_cast<size_t>(i)] = i;
  for (bool again = true; again;) {
    again = false;
    for (size_t k = 0; k < kept.size(); ++k) {
      const int i = kept[k];
      double col = 0.0, row = 0.0;
      for (int j : kept)
        col = std::max(col, std::abs(A(j, i))), row = std::max(row, std::abs(A(i, j)));
      if (col <= tol || row <= tol) {
        removed.push_back({i, col <= tol});
        kept.erase(kept.begin() + static_cast<long>(k));
        again = true;
        break;
      }
    }
  }
  return removed;
}

Mode MakeMode(std::complex<double> lambda, Eigen::VectorXcd shape, int m, double scale) {
  Mode mode;
  mode.eigenvalue = lambda;
  mode.frequency_hz = std::abs(lambda.imag()) / (2.0 * std::numbers::pi);
  const double mag = std::abs(lambda);
  mode.damping_ratio = mag > 0.0 ? -lambda.real() / mag : 0.0;
  mode.stable = lambda.real() <= kNeutral * scale;
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
  const std::vector<Removed> removed = SplitRigid(A, kept);
  const int k = static_cast<int>(kept.size());
  MatrixXd Ak(k, k);
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k; ++j)
      Ak(i, j) = A(kept[static_cast<size_t>(i)], kept[static_cast<size_t>(j)]);
  }
  std::vector<Mode> modes;
  if (k > 0) {
    Eigen::EigenSolver<MatrixXd> es(Ak);
    const double scale = std::max(es.eigenvalues().cwiseAbs().maxCoeff(), 1e-300);
    for (int e = 0; e < k; ++e) {
      const std::complex<double> lambda = es.eigenvalues()[e];
      if (lambda.imag() < 0.0) continue;
      Eigen::VectorXcd v = Eigen::VectorXcd::Zero(d);
      for (int i = 0; i < k; ++i) v[kept[static_cast<size_t>(i)]] = es.eigenvectors()(i, e);
      // Complete the shape over the rigid coordinates, last taken out first: a zero-column
      // coordinate follows λ x_i = Σ_j A_ij x_j; a zero-row one stays 0.
      for (auto it = removed.rbegin(); it != removed.rend(); ++it) {
        if (!it->by_column || std::abs(lambda) == 0.0) continue;
        std::complex<double> s = 0.0;
        for (int j = 0; j < d; ++j) s += A(it->index, j) * v[j];
        v[it->index] = s / lambda;
      }
      modes.push_back(MakeMode(lambda, v, m, scale));
    }
    std::sort(modes.begin(), modes.end(), [](const Mode& a, const Mode& b) {
      return std::abs(a.eigenvalue) < std::abs(b.eigenvalue);
    });
  }
  out.max_real_part = modes.empty() ? 0.0 : -std::numeric_limits<double>::infinity();
  for (const Mode& mode : modes) {
    out.stable = out.stable && mode.stable;
    out.max_real_part = std::max(out.max_real_part, mode.eigenvalue.real());
  }
  for (const Removed& r : removed) {
    Eigen::VectorXcd v = Eigen::VectorXcd::Zero(d);
    v[r.index] = 1.0;
    Mode mode = MakeMode(0.0, v, m, 1.0);
    mode.rigid = true;
    mode.rigid_coordinate = r.index < m ? lin.coordinates[static_cast<size_t>(r.index)].name
                                        : lin.speeds[static_cast<size_t>(r.index - m)].name;
    modes.push_back(mode);
  }
  out.modes = std::move(modes);
  return out;
}

ModalAnalysis AnalyseModes(const Model& model, const OperatingPoint& op,
                           const LinearizeOptions& options) {
  return CalcModes(Linearize(model, op, options));
}

}  // namespace chasles

namespace chasles {

std::vector<StabilityChange> FindStabilityChanges(
    const std::function<ModalAnalysis(double)>& analyse, const std::vector<double>& grid,
    double tolerance) {
  std::vector<StabilityChange> out;
  if (grid.size() < 2) return out;
  const double span = std::abs(grid.back() - grid.front());
  bool before = analyse(grid[0]).stable;
  for (size_t i = 1; i < grid.size(); ++i) {
    const bool after = analyse(grid[i]).stable;
    if (after == before) continue;
    double a = grid[i - 1], b = grid[i];
    while (std::abs(b - a) > tolerance * span) {
      const double mid = 0.5 * (a + b);
      (analyse(mid).stable == before ? a : b) = mid;
    }
    // The kind: the mode that is unstable on the unstable side.
    const ModalAnalysis bad = analyse(after ? a : b);
    StabilityChange c;
    c.value = 0.5 * (a + b);
    c.stable_after = after;
    c.kind = "divergent";
    for (const Mode& m : bad.modes) {
      if (!m.stable && m.eigenvalue.imag() > kNeutral * std::abs(m.eigenvalue))
        c.kind = "oscillatory";
    }
    out.push_back(c);
    before = after;
  }
  return out;
}

}  // namespace chasles
