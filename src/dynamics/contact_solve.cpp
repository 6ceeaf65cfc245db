#include "chasles/dynamics/contact_solve.h"

#include "chasles/error.h"

namespace chasles {

void SolveContactForces(const Model&, const State&, Data&) {
  throw InputError("contacts: SolveContactForces is not implemented yet");
}

std::vector<ContactPointOutput> CalcContactOutputs(const Model&, const State&) {
  throw InputError("contacts: CalcContactOutputs is not implemented yet");
}

std::vector<ContactModeChange> SelectContactModes(const Model&, State&, const ContactTolerances&) {
  throw InputError("contacts: SelectContactModes is not implemented yet");
}

ImpactResult ResolveImpacts(const Model&, State&, const ContactTolerances&) {
  throw InputError("contacts: ResolveImpacts is not implemented yet");
}

}  // namespace chasles
