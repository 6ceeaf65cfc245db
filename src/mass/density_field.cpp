#include "chasles/mass/density_field.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <fmt/format.h>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>

#include "chasles/error.h"

namespace chasles {

// Why a cubature of our own rather than nested boost::math::quadrature::gauss_kronrod: the
// ten moments share every density evaluation, and a tensor-product Gauss–Kronrod rule on a
// box of the unit cube integrates all ten in one pass with one error estimate per direction,
// so the box is bisected along the direction that needs it. Three nested one-dimensional
// adaptive integrators would need ten passes (or a vector type they do not support), with
// the inner tolerances chosen blindly. Boost still supplies the node and weight tables.

namespace {

constexpr int kNodes = 15;    // Kronrod points per direction; Gauss uses 7 of them
constexpr int kMoments = 10;  // 1, x, y, z, xx, yy, zz, xy, xz, yz
constexpr long kMaxEvaluations = 4'000'000;
constexpr long kEvaluationsPerBox = kNodes * kNodes * kNodes;

using Moments = Eigen::Matrix<double, kMoments, 1>;

// The 15-point Kronrod rule and its embedded 7-point Gauss rule moved to [0, 1]; the Gauss
// weight is zero at the Kronrod-only nodes.
struct Rule {
  std::array<double, kNodes> x{}, wk{}, wg{};
};

const Rule& GetRule() {
  static const Rule rule = [] {
    using boost::math::quadrature::gauss;
    using boost::math::quadrature::gauss_kronrod;
    const auto& xk = gauss_kronrod<double, kNodes>::abscissa();  // 0 and the positive nodes
    const auto& wk = gauss_kronrod<double, kNodes>::weights();
    const auto& wg = gauss<double, 7>::weights();  // at the Kronrod nodes of even index
    Rule r;
    for (int i = 0; i < kNodes; ++i) {
      const int k = std::abs(i - kNodes / 2);
      const double t = i < kNodes / 2 ? -xk[k] : xk[k];
      r.x[i] = 0.5 * (1 + t);
      r.wk[i] = 0.5 * wk[k];
      r.wg[i] = k % 2 == 0 ? 0.5 * wg[k / 2] : 0.0;
    }
    return r;
  }();
  return rule;
}

// A box [lo, lo + width] of the unit cube with its Kronrod estimate and, per direction d,
// the difference to the rule that uses Gauss in direction d (Kronrod in the others).
struct Box {
  Vec3 lo, width;
  Moments value;
  Eigen::Matrix<double, kMoments, 3> error;
};

// Error scales of the three moment classes: the mass, mass times the radius of gyration about
// the geometric centroid, and the trace of the second moments.
struct Scales {
  double s0, s1, s2;
  double Normalized(const Moments& e) const {
    double r = e[0] / s0;
    for (int k = 1; k < 4; ++k) r = std::max(r, e[k] / s1);
    for (int k = 4; k < kMoments; ++k) r = std::max(r, e[k] / s2);
    return r;
  }
};

class Integrator {
 public:
  Integrator(const Shape& solid, const std::function<double(const Vec3&)>& rho)
      : solid_(solid), rho_(rho), rule_(GetRule()), c_(solid.CalcCentroid()) {}

  Box Evaluate(const Vec3& lo, const Vec3& width) {
    // Sums are built from the innermost direction (k, u2) out, one weight set per rule.
    Moments kkk = Moments::Zero(), gkk = Moments::Zero(), kgk = Moments::Zero(),
            kkg = Moments::Zero();
    for (int i = 0; i < kNodes; ++i) {
      Moments s_kk = Moments::Zero(), s_gk = Moments::Zero(), s_kg = Moments::Zero();
      for (int j = 0; j < kNodes; ++j) {
        Moments s_k = Moments::Zero(), s_g = Moments::Zero();
        for (int k = 0; k < kNodes; ++k) {
          const Vec3 u(lo[0] + width[0] * rule_.x[i], lo[1] + width[1] * rule_.x[j],
                       lo[2] + width[2] * rule_.x[k]);
          Vec3 p;
          double J = 0;
          solid_.MapUnitCube(u, &p, &J);
          const double r = rho_(p);
          if (!(r >= 0.0) || !std::isfinite(r)) ThrowBadDensity(r, p);
          const double w = r * J;
          // Moments about the geometric centroid, so that a part far from its frame's origin
          // keeps its digits.
          const Vec3 q = p - c_;
          Moments f;
          f << w, w * q[0], w * q[1], w * q[2], w * q[0] * q[0], w * q[1] * q[1], w * q[2] * q[2],
              w * q[0] * q[1], w * q[0] * q[2], w * q[1] * q[2];
          s_k += rule_.wk[k] * f;
          s_g += rule_.wg[k] * f;
        }
        s_kk += rule_.wk[j] * s_k;
        s_gk += rule_.wg[j] * s_k;
        s_kg += rule_.wk[j] * s_g;
      }
      kkk += rule_.wk[i] * s_kk;
      gkk += rule_.wg[i] * s_kk;
      kgk += rule_.wk[i] * s_gk;
      kkg += rule_.wk[i] * s_kg;
    }
    evaluations_ += kEvaluationsPerBox;
    const double volume = width.prod();
    Box box{lo, width, volume * kkk, {}};
    box.error.col(0) = (volume * (kkk - gkk)).cwiseAbs();
    box.error.col(1) = (volume * (kkk - kgk)).cwiseAbs();
    box.error.col(2) = (volume * (kkk - kkg)).cwiseAbs();
    return box;
  }

  long evaluations() const { return evaluations_; }
  const Vec3& centroid() const { return c_; }

 private:
  [[noreturn]] void ThrowBadDensity(double r, const Vec3& p) const {
    const std::string where =
        fmt::format("at ({:.6g}, {:.6g}, {:.6g}) m of the part's frame", p[0], p[1], p[2]);
    if (std::isfinite(r)) {
      throw InputError(fmt::format("{}: density is {:.6g} kg/m^3 {}; a density cannot be negative",
                                   solid_.kind(), r, where));
    }
    throw InputError(
        fmt::format("{}: density is {} {}; a density must be a finite number of kg/m^3",
                    solid_.kind(), std::isnan(r) ? "not a number" : "infinite", where));
  }

  const Shape& solid_;
  const std::function<double(const Vec3&)>& rho_;
  const Rule& rule_;
  Vec3 c_;
  long evaluations_ = 0;
};

}  // namespace

MassProperties IntegrateDensity(const Shape& solid,
                                const std::function<double(const Vec3& p_S)>& rho, double rel_tol,
                                DensityIntegrationReport* report) {
  if (!solid.is_solid()) {
    throw InputError(fmt::format(
        "{}: a density field needs a solid, but this is a thin shape (a {}) with no volume; "
        "give it a mass instead, or model it as a solid of finite thickness",
        solid.kind(), solid.measure() == Shape::Measure::kLength ? "curve" : "surface"));
  }
  if (!(rel_tol >= 1e-14 && rel_tol < 1)) {
    throw InputError(
        fmt::format("density integration: relative tolerance {:.6g} must be at least 1e-14 (double "
                    "precision cannot do better) and below 1",
                    rel_tol));
  }
  if (!rho) throw InputError(fmt::format("{}: no density function was given", solid.kind()));

  Integrator integrator(solid, rho);
  std::vector<Box> boxes;
  boxes.push_back(integrator.Evaluate(Vec3::Zero(), Vec3::Ones()));

  Moments total, total_error;
  Scales scales{};
  double reached = 0;
  for (;;) {
    // Totals are re-summed from the boxes on every pass (cheap next to 3375 evaluations per
    // box) rather than updated, so that no cancellation error creeps into them.
    total.setZero();
    total_error.setZero();
    for (const Box& b : boxes) {
      total += b.value;
      total_error += b.error.rowwise().sum();
    }
    const double trace2 = total[4] + total[5] + total[6];
    if (!(total[0] > 0) || !(trace2 > 0)) {
      throw InputError(fmt::format(
          "{}: the density integrates to a total mass of {:.6g} kg; a part needs positive mass "
          "(is the density zero everywhere in it?)",
          solid.kind(), total[0]));
    }
    scales = Scales{total[0], std::sqrt(total[0] * trace2), trace2};
    reached = scales.Normalized(total_error);
    if (reached <= rel_tol) break;
    if (integrator.evaluations() + 2 * kEvaluationsPerBox > kMaxEvaluations) {
      throw InputError(fmt::format(
          "{}: density integration reached an estimated relative error of {:.3g} after {} "
          "density evaluations, short of the requested {:.3g}; the density is probably "
          "discontinuous or sharply peaked: split the part where the density jumps, or ask for "
          "a looser tolerance",
          solid.kind(), reached, integrator.evaluations(), rel_tol));
    }
    // Bisect the box with the largest error along its worst direction.
    size_t worst = 0;
    double worst_error = -1;
    for (size_t b = 0; b < boxes.size(); ++b) {
      const double e = scales.Normalized(boxes[b].error.rowwise().sum());
      if (e > worst_error) worst_error = e, worst = b;
    }
    const Box parent = boxes[worst];
    int dir = 0;
    double dir_error = -1;
    for (int d = 0; d < 3; ++d) {
      const double e = scales.Normalized(parent.error.col(d));
      if (e > dir_error) dir_error = e, dir = d;
    }
    Vec3 half = parent.width;
    half[dir] /= 2;
    Vec3 lo2 = parent.lo;
    lo2[dir] += half[dir];
    boxes[worst] = integrator.Evaluate(parent.lo, half);
    boxes.push_back(integrator.Evaluate(lo2, half));
  }

  if (report != nullptr) {
    report->estimated_relative_error = reached;
    report->evaluations = integrator.evaluations();
    report->regions = static_cast<int>(boxes.size());
  }

  // Eq. 8.6: centre of mass = first moments / mass, here relative to the geometric centroid.
  const double m = total[0];
  const Vec3 d = total.segment<3>(1) / m;
  Mat3 Q;  // ∫ q qᵀ dm about the geometric centroid
  Q << total[4], total[7], total[8], total[7], total[5], total[9], total[8], total[9], total[6];
  const Mat3 Q_cm = Q - m * d * d.transpose();  // shifted to the centre of mass
  // Eq. 8.16 in the chapter's convention: I = tr(Q) E - Q (diagonal ∫(y²+z²) dm, off-diagonal
  // -∫xy dm).
  const Mat3 I = Q_cm.trace() * Mat3::Identity() - Q_cm;
  return MassProperties(m, integrator.centroid() + d, RotationalInertia::FromMatrix(I));
}

}  // namespace chasles
