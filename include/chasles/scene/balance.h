#pragma once
/// @file
/// A scene's rotor to balance (`chasles balance`, docs/modes.md "Rotors") as a
/// RotorBalanceDefinition for the analysis layer's AnalyseRotorBalance: the command's options,
/// written as in the scene (its parameters and units known), read into the axis, the planes,
/// the speed and the whirl spins; the scene's Model and initial state; and the locator that
/// brings the analysis's errors back at the scene entry they concern.

#include <string>

#include "chasles/analysis/balance.h"
#include "chasles/scene/scene.h"

namespace chasles {

/// The options of `chasles balance`, as its command line (or the Python module's
/// chasles.balance) writes them.
struct BalanceOptions {
  /// The rotor: a body of the scene.
  std::string body;
  /// Spin axis in W and a point of it in W, as in a scene ("[0, 0, 1]", "[0, 0, 5 cm]").
  std::string axis = "[0, 0, 1]";
  std::string through = "[0, 0, 0]";
  /// "A, B": the two bearing and correction planes' positions along the axis from `through`
  /// ("-10 cm, 10 cm"); the correction radius ("8 cm").
  std::string planes, radius;
  /// The spin for the bearing forces and the grade ("3000 rpm"; "": none).
  std::string speed;
  /// ISO 21940-11 balance grade G [mm/s]; 0: none (it needs `speed`).
  double grade = 0.0;
  /// "A:B:N": N spins (2 to 1,000) from A to B, 0 <= A < B, of the whirl rows ("": chosen by
  /// CalcRotorWhirl); only for a rotor a bearing element holds.
  std::string whirl;
  /// Errors in an option are SceneErrors at file `source`, key the prefix and the option's name
  /// ("command line: --planes: ...").
  std::string source = "command line";
  std::string option_prefix = "--";
};

/// The definition of the scene's rotor balance with `options`: the Model, the initial state and
/// its settling (BuildStudy), the rotor, the axis and planes, the speed, the grade and the whirl
/// spins. An option that does not read (a quantity of the wrong dimension, planes that are not
/// two positions, a grade without a speed, a body the scene does not have, whirl spins for a
/// rotor no bearing holds) is a SceneError at `options.source` and key the option; the
/// scene's own errors, here or in the analysis of the definition, SceneErrors at the entry
/// they concern.
RotorBalanceDefinition MakeBalanceDefinition(const Scene& scene, const BalanceOptions& options);

}  // namespace chasles
