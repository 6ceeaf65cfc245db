#include "chasles/analysis/ledger.h"

#include <algorithm>
#include <cmath>

#include "chasles/analysis/momentum.h"

namespace chasles {

LedgerSample CalcLedgerSample(const Model& model, const State& s, const State& s0) {
  LedgerSample L;
  L.t = s.t;
  L.kinetic_translational = CalcTranslationalKineticEnergy(model, s);
  L.kinetic_rotational = CalcRotationalKineticEnergy(model, s);
  const double T0 =
      CalcTranslationalKineticEnergy(model, s0) + CalcRotationalKineticEnergy(model, s0);
  double V0 = 0.0, abs_work = 0.0;
  Vec3 imp = Vec3::Zero(), ang_imp = Vec3::Zero();
  L.forces.resize(static_cast<size_t>(model.num_force_elements()));
  for (int e = 0; e < model.num_force_elements(); ++e) {
    const auto i = static_cast<size_t>(e);
    const ForceElement& fe = model.force_element(e);
    ForceLedger& f = L.forces[i];
    f.name = fe.name();
    f.has_potential = fe.has_potential();
    f.dissipative = fe.is_dissipative();
    if (f.has_potential) {
      f.potential_energy = fe.CalcPotentialEnergy(model, s);
      V0 += fe.CalcPotentialEnergy(model, s0);
    }
    const ForceIntegrals &a = s.force_integrals[i], &a0 = s0.force_integrals[i];
    f.work = a.work - a0.work;
    f.work_nonconservative = a.work_nonconservative - a0.work_nonconservative;
    f.linear_impulse_W = a.linear_impulse_W - a0.linear_impulse_W;
    f.angular_impulse_Wo_W = a.angular_impulse_Wo_W - a0.angular_impulse_Wo_W;
    L.potential += f.potential_energy;
    L.work_nonconservative += f.work_nonconservative;
    if (f.dissipative) L.dissipated -= f.work_nonconservative;
    abs_work += std::abs(f.work_nonconservative);
    imp += f.linear_impulse_W;
    ang_imp += f.angular_impulse_Wo_W;
  }
  L.constraints.resize(static_cast<size_t>(model.num_constraints()));
  for (int c = 0; c < model.num_constraints(); ++c) {
    const auto i = static_cast<size_t>(c);
    ConstraintLedger& cl = L.constraints[i];
    cl.name = model.constraint(c).name();
    // An empty list (a state made before the constraints were added) reads as zeros.
    const double w = i < s.constraint_work.size() ? s.constraint_work[i] : 0.0;
    const double w0 = i < s0.constraint_work.size() ? s0.constraint_work[i] : 0.0;
    cl.work = w - w0;
    L.constraint_work += cl.work;
    abs_work += std::abs(cl.work);
  }
  L.work_nonconservative += L.constraint_work;
  // Strings snapping taut: impacts, so dissipated (an empty list reads as zeros).
  for (int c = 0; c < model.num_constraints(); ++c) {
    const auto i = static_cast<size_t>(c);
    const double w = i < s.constraint_modes.size() ? s.constraint_modes[i].impact_work : 0.0;
    const double w0 = i < s0.constraint_modes.size() ? s0.constraint_modes[i].impact_work : 0.0;
    L.constraints[i].impact_work = w - w0;
    L.constraint_impact_work += w - w0;
  }
  L.work_nonconservative += L.constraint_impact_work;
  L.dissipated -= L.constraint_impact_work;
  abs_work += std::abs(L.constraint_impact_work);
  // Contacts: sliding friction, rolling resistance and impacts only take energy out; a state
  // without contact entries (a model without contacts) reads as zeros.
  L.contacts.resize(static_cast<size_t>(model.num_contact_points()));
  for (int p = 0; p < model.num_contact_points(); ++p) {
    const auto i = static_cast<size_t>(p);
    ContactLedger& cl = L.contacts[i];
    cl.name = model.contact_point_name(p);
    const ContactPointState none{};
    const ContactPointState& a = i < s.contacts.size() ? s.contacts[i] : none;
    const ContactPointState& a0 = i < s0.contacts.size() ? s0.contacts[i] : none;
    cl.friction_work = a.friction_work - a0.friction_work;
    cl.rolling_work = a.rolling_work - a0.rolling_work;
    cl.impact_work = a.impact_work - a0.impact_work;
    L.contact_friction_work += cl.friction_work;
    L.contact_rolling_work += cl.rolling_work;
    L.contact_impact_work += cl.impact_work;
  }
  // Contacts the model does not list (event-driven balls colliding under a pair law).
  const ContactWork &u = s.unlisted_contact_work, &u0 = s0.unlisted_contact_work;
  L.contact_friction_work += u.friction_work - u0.friction_work;
  L.contact_rolling_work += u.rolling_work - u0.rolling_work;
  L.contact_impact_work += u.impact_work - u0.impact_work;
  const double contact_work =
      L.contact_friction_work + L.contact_rolling_work + L.contact_impact_work;
  L.work_nonconservative += contact_work;
  L.dissipated -= contact_work;
  abs_work += std::abs(contact_work);
  L.mechanical_energy = L.kinetic_translational + L.kinetic_rotational + L.potential;
  L.energy_residual = (L.mechanical_energy - (T0 + V0)) - L.work_nonconservative;
  L.energy_scale =
      std::max({std::abs(T0) + std::abs(V0),
                L.kinetic_translational + L.kinetic_rotational + std::abs(L.potential), abs_work});
  L.linear_momentum_W = CalcLinearMomentum(model, s);
  L.p_WScm = CalcSystemCenterOfMass(model, s);
  L.angular_momentum_Scm_W = CalcAngularMomentum(model, s, L.p_WScm);
  L.angular_momentum_Wo_W = CalcAngularMomentum(model, s, Vec3::Zero());
  L.momentum_residual_W = L.linear_momentum_W - CalcLinearMomentum(model, s0) - imp;
  L.angular_momentum_residual_W =
      L.angular_momentum_Wo_W - CalcAngularMomentum(model, s0, Vec3::Zero()) - ang_imp;
  return L;
}

}  // namespace chasles
