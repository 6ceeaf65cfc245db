#pragma once
/// @file
/// Why a Model cannot run on one of the engines that take only some models (time stepping,
/// the event-driven spheres, the free-body batch).

#include <optional>
#include <string>

#include "chasles/error.h"

namespace chasles {

/// Why a Model cannot run on an engine: the reason, which names the element that does not fit,
/// and that element (none when the model as a whole does not fit: no gravity, a tilted table).
/// Empty when it can run.
struct ModelObstacle {
  std::string why;
  std::optional<ErrorElement> element;
  bool empty() const { return why.empty(); }
};

}  // namespace chasles
