#include "chasles/integrate/engine_choice.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include "chasles/error.h"
#include "chasles/model/forces.h"

namespace chasles {

EngineChoiceRule MakeEngineChoiceRule(double step) {
  if (!(step > 0.0) || !std::isfinite(step)) {
    throw InputError(fmt::format(
        "the time-stepping step of integrator auto is {:.6g} s; it must be a positive time", step));
  }
  EngineChoiceRule rule;
  rule.step = step;
  rule.changes = kWindowChanges;
  rule.window = kWindowChanges * kStepsPerChange * step;
  rule.quiet_span = kQuietSteps * step;
  return rule;
}

double DefaultEngineStep(const Model& model, double output_interval) {
  Vec3 g_W = Vec3::Zero();
  for (int e = 0; e < model.num_force_elements(); ++e) {
    if (const auto* u = dynamic_cast<const UniformGravity*>(&model.force_element(e))) {
      g_W += u->g_W();
    }
  }
  double rho = std::numeric_limits<double>::infinity();
  for (int c = 0; c < model.num_contacts(); ++c) {
    const Contact& con = model.contact(c);
    for (const BodyIndex b : {con.body(), con.other_body()}) {
      if (b == kWorld) continue;
      const Body& body = model.body(b);
      const Eigen::SelfAdjointEigenSolver<Mat3> principal(body.I_BBcm_B(), Eigen::EigenvaluesOnly);
      rho = std::min(rho, std::sqrt(principal.eigenvalues().maxCoeff() / body.mass()));
    }
  }
  const double g = g_W.norm();
  if (g > 0.0 && rho > 0.0 && std::isfinite(rho)) return kStepOfFallTime * std::sqrt(rho / g);
  if (!(output_interval > 0.0) || !std::isfinite(output_interval)) {
    throw InputError(fmt::format(
        "integrator auto needs a step for its time-stepping segments: the model has no gravity "
        "to derive one from and the output interval is {:.6g} s; give 'step'",
        output_interval));
  }
  return 0.1 * output_interval;
}

}  // namespace chasles
