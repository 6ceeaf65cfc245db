#include "chasles/analysis/whirl.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include <fmt/format.h>
#include <Eigen/Dense>

#include "chasles/analysis/operating_point.h"
#include "chasles/error.h"
#include "chasles/model/bearing.h"

namespace chasles {
namespace {

using cd = std::complex<double>;
using Eigen::MatrixXcd;

/// Relative difference below which two eigenvalues are one repeated eigenvalue.
constexpr double kRepeated = 1e-8;
/// |h| below this fraction of ω Σ w |u|² is no whirl (axial or torsional motion).
constexpr double kNoWhirl = 1e-9;

struct Weights {
  std::vector<double> mass, across;  // m_b and I_t,b = (tr I - aᵀ I a)/2, in W
};

Weights MakeWeights(const Model& model, const State& state, const Vec3& a) {
  Weights w;
  for (int b = 0; b < model.num_bodies(); ++b) {
    const Mat3 R = state.bodies[static_cast<size_t>(b)].q_WB.normalized().toRotationMatrix();
    const Mat3 I = R * model.body(b).I_BBcm_B() * R.transpose();
    w.mass.push_back(model.body(b).mass());
    w.across.push_back(0.5 * (I.trace() - a.dot(I * a)));
  }
  return w;
}

/// The whirl form H_ij = (iω/2) Σ_b w_b (conj(z_i) × z_j) · a over the columns of Z (maximal
/// perturbations), so that u^H H u = h(u) (whirl.h), and the norm N_ij = ω Σ_b w_b conj(z_i)·z_j.
std::pair<MatrixXcd, MatrixXcd> WhirlForm(const MatrixXcd& Z, const Weights& w, const Vec3& a,
                                          double omega) {
  const auto k = Z.cols();
  MatrixXcd H = MatrixXcd::Zero(k, k), Nrm = MatrixXcd::Zero(k, k);
  const Eigen::Vector3cd ac = a.cast<cd>();
  for (size_t b = 0; b < w.mass.size(); ++b) {
    const int at = 6 * static_cast<int>(b);
    for (int part = 0; part < 2; ++part) {
      const double weight = part == 0 ? w.mass[b] : w.across[b];
      for (Eigen::Index i = 0; i < k; ++i) {
        const Eigen::Vector3cd zi = Z.col(i).segment<3>(at + 3 * part).conjugate();
        for (Eigen::Index j = 0; j < k; ++j) {
          const Eigen::Vector3cd zj = Z.col(j).segment<3>(at + 3 * part);
          H(i, j) += cd(0.0, 0.5 * omega * weight) * zi.cross(zj).dot(ac);
          Nrm(i, j) += omega * weight * zi.dot(zj);
        }
      }
    }
  }
  return {H, Nrm};
}

/// The directions of a group of k modes sharing the eigenvalue λ: the eigenspace (the k
/// right singular vectors of A - λ E with the smallest singular values) split by the whirl
/// form into its definite members.
std::vector<WhirlDirection> GroupDirections(const Linearization& lin, cd lambda, int k,
                                            const Weights& w, const Vec3& a, double spin) {
  const auto d = lin.A.rows();
  const MatrixXcd M = lin.A.cast<cd>() - lambda * MatrixXcd::Identity(d, d);
  Eigen::JacobiSVD<MatrixXcd> svd(M, Eigen::ComputeFullV);
  const MatrixXcd Z = lin.basis.cast<cd>() * svd.matrixV().rightCols(k);
  const auto [H, Nrm] = WhirlForm(Z, w, a, lambda.imag());
  // H v = h Nrm v: the whirl of each member relative to its size.
  Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXcd> es(H, Nrm);
  std::vector<WhirlDirection> out;
  for (Eigen::Index i = 0; i < es.eigenvalues().size(); ++i) {
    const double h = es.eigenvalues()[i];
    if (!(spin > 0.0) || std::abs(h) <= kNoWhirl) {
      out.push_back(WhirlDirection::kNone);
    } else {
      out.push_back(h > 0.0 ? WhirlDirection::kForward : WhirlDirection::kBackward);
    }
  }
  // Forward first within a group, for a stable order.
  std::sort(out.begin(), out.end());
  return out;
}

WhirlPoint AnalysePoint(const Model& model, const State& rest, BodyIndex rotor, const Vec3& a,
                        const Weights& w, double spin, ModalAnalysis* modes_out) {
  State s = rest;
  BodyState& r = s.bodies[static_cast<size_t>(rotor)];
  r.w_WB_B = r.q_WB.normalized().conjugate() * (spin * a);
  const OperatingPoint op = spin == 0.0 ? FindEquilibrium(model, rest) : MakeSteadyMotion(model, s);
  ModalAnalysis modes = AnalyseModes(model, op);
  WhirlPoint p;
  p.speed = spin;
  const std::vector<Mode>& all = modes.modes;
  for (size_t i = 0; i < all.size();) {
    if (all[i].rigid) {
      ++i;
      continue;
    }
    const cd lambda = all[i].eigenvalue;
    size_t j = i + 1;
    while (j < all.size() && !all[j].rigid &&
           std::abs(all[j].eigenvalue - lambda) <= kRepeated * std::abs(lambda)) {
      ++j;
    }
    const std::vector<WhirlDirection> dirs =
        lambda.imag() > 0.0
            ? GroupDirections(modes.linearization, lambda, static_cast<int>(j - i), w, a, spin)
            : std::vector<WhirlDirection>(j - i, WhirlDirection::kNone);
    for (size_t k = i; k < j; ++k) {
      p.modes.push_back(
          {all[k].eigenvalue, all[k].frequency_hz, all[k].damping_ratio, dirs[k - i]});
    }
    i = j;
  }
  if (modes_out != nullptr) *modes_out = std::move(modes);
  return p;
}

}  // namespace

const char* WhirlDirectionName(WhirlDirection d) {
  switch (d) {
    case WhirlDirection::kForward:
      return "forward";
    case WhirlDirection::kBackward:
      return "backward";
    case WhirlDirection::kNone:
      break;
  }
  return "none";
}

WhirlMap CalcWhirl(const Model& model, const State& state, BodyIndex rotor, const Vec3& a_W,
                   const std::vector<double>& speeds) {
  if (!(a_W.norm() > 0.0) || !a_W.allFinite()) {
    throw InputError("whirl: the spin axis is zero or not finite");
  }
  for (size_t i = 0; i < speeds.size(); ++i) {
    if (!(speeds[i] >= 0.0) || !std::isfinite(speeds[i]) || (i > 0 && speeds[i] <= speeds[i - 1]))
      throw InputError("whirl: the speeds must be finite, 0 or more and increasing");
  }
  const Vec3 a = a_W.normalized();
  const State rest = FindEquilibrium(model, state).state;
  const Weights w = MakeWeights(model, rest, a);
  WhirlMap out;
  for (const double spin : speeds) {
    out.points.push_back(AnalysePoint(model, rest, rotor, a, w, spin, nullptr));
  }
  const auto analyse = [&](double spin) {
    ModalAnalysis m;
    AnalysePoint(model, rest, rotor, a, w, spin, &m);
    return m;
  };
  for (const CriticalSpeed& c : FindCriticalSpeeds(analyse, speeds)) {
    // The modes whose frequency meets the spin there, with their directions.
    const WhirlPoint at = AnalysePoint(model, rest, rotor, a, w, c.speed, nullptr);
    WhirlCriticalSpeed cs;
    cs.speed = c.speed;
    for (const WhirlMode& m : at.modes) {
      if (std::abs(std::abs(m.eigenvalue.imag()) - c.speed) <= 1e-6 * c.speed) {
        cs.directions.push_back(m.direction);
      }
    }
    // Two modes of a repeated frequency cross together; FindCriticalSpeeds lists each.
    if (!out.critical_speeds.empty() &&
        std::abs(out.critical_speeds.back().speed - c.speed) <= 1e-9 * c.speed) {
      continue;
    }
    out.critical_speeds.push_back(std::move(cs));
  }
  return out;
}

bool HeldByBearing(const Model& model, BodyIndex body) {
  for (int i = 0; i < model.num_force_elements(); ++i) {
    const auto* bearing = dynamic_cast<const Bearing*>(&model.force_element(i));
    if (bearing != nullptr && bearing->body() == body) return true;
  }
  return false;
}

std::vector<double> WhirlSpeedGrid(double from, double to, int count) {
  std::vector<double> out;
  for (int i = 0; i < count; ++i) {
    out.push_back(i + 1 == count ? to : from + (to - from) * i / (count - 1));
  }
  return out;
}

std::optional<WhirlMap> CalcRotorWhirl(const Model& model, const State& state, BodyIndex rotor,
                                       const Vec3& a_W, const std::vector<double>& speeds,
                                       double speed) {
  if (!HeldByBearing(model, rotor)) {
    if (!speeds.empty()) {
      throw InputError(fmt::format(
          "no bearing element holds '{}': whirl needs the rotor on elastic bearings (forces, "
          "type bearing)",
          model.body(rotor).name()));
    }
    return std::nullopt;
  }
  if (!speeds.empty()) return CalcWhirl(model, state, rotor, a_W, speeds);
  double top = std::isfinite(speed) ? speed : 0.0;
  if (!(top > 0.0)) {
    // Held by name: a range-for over a member of a temporary would outlive the temporary.
    const WhirlMap at_rest = CalcWhirl(model, state, rotor, a_W, {0.0});
    for (const WhirlMode& m : at_rest.points[0].modes) {
      top = std::max(top, std::abs(m.eigenvalue.imag()));
    }
  }
  if (!(top > 0.0)) return std::nullopt;  // nothing whirls: no rows
  std::vector<double> grid;
  for (int i = 0; i <= 20; ++i) grid.push_back(2.0 * top * i / 20.0);
  return CalcWhirl(model, state, rotor, a_W, grid);
}

}  // namespace chasles
