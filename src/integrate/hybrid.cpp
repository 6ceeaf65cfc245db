#include "integrate/internal/hybrid.h"

#include "chasles/error.h"

namespace chasles::internal {

SimulationResult RunHybrid(const Model&, const State&, const SimulationOptions&) {
  throw InputError("contacts: Simulate with contacts is not implemented yet");
}

}  // namespace chasles::internal
