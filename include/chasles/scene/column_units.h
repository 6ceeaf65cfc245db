#pragma once
/// @file
/// The SI unit of each column of a scene's run (RunStudy's CSV columns, docs/scene-format.md
/// "Output"), for reports and for tables handed to other programs; the columns' groups and the
/// columns a group stands for, for the browser report's data (chasles/report/report_data.h).

#include <string>
#include <vector>

#include "chasles/scene/scene.h"

namespace chasles {

/// The SI unit of the run column `column` of `scene`: "s", "m", "m/s", "rad", "rad/s",
/// "rad/s^2", "m/s^2", "J", "kg*m/s", "kg*m^2/s", "N", "N*m"; "" for pure numbers (quaternion
/// components, contact modes). Angles are in radians. Throws InputError for a name that is
/// not a column of the scene's run.
std::string StudyColumnUnit(const Scene& scene, const std::string& column);

/// StudyColumnUnit of each column.
std::vector<std::string> StudyColumnUnits(const Scene& scene,
                                          const std::vector<std::string>& columns);

/// The group of each run column of `scene` ("position", "energy", "reactions", ...); "" for a
/// name that is not a column of the run.
std::vector<std::string> StudyColumnGroups(const Scene& scene,
                                           const std::vector<std::string>& columns);

/// The run columns that `names` stand for, in order: a group's columns, or the one column of
/// that name; a name that is neither stands for none.
std::vector<std::string> ExpandStudyColumns(const Scene& scene,
                                            const std::vector<std::string>& names);

}  // namespace chasles
