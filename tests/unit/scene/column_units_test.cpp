// The units, groups and expansion of a scene's run columns (chasles/scene/column_units.h), for
// the groups of docs/scene-format.md, "Output".

#include "chasles/scene/column_units.h"

#include <string>
#include <vector>

#include "chasles/error.h"
// clang-format off
#include <gtest/gtest.h>
// clang-format on

namespace chasles {
namespace {

constexpr const char* kScene = R"(chasles: 1
bodies:
  - name: block
    parts: [{shape: box, size: [4 cm, 4 cm, 4 cm], mass: 2 kg}]
simulation: {until: 1 s}
)";

using Names = std::vector<std::string>;

TEST(ColumnUnits, UnitsFollowTheQuantity) {
  const Scene scene = LoadSceneText(kScene, "block.yaml");
  EXPECT_EQ(StudyColumnUnits(scene, {"t", "block_x", "block_qw", "block_wz", "E", "Hx"}),
            (Names{"s", "m", "", "rad/s", "J", "kg*m^2/s"}));
  EXPECT_THROW(StudyColumnUnit(scene, "block_nope"), InputError);
}

// A column's group is the group that names it in docs/scene-format.md; a name that is not a
// column has none.
TEST(ColumnUnits, GroupsOfColumns) {
  const Scene scene = LoadSceneText(kScene, "block.yaml");
  EXPECT_EQ(StudyColumnGroups(scene, {"block_ox", "block_qz", "T_rot", "W_nc", "residual", "nope"}),
            (Names{"origin", "quaternion", "energy", "work", "residual", ""}));
}

// A group stands for its columns in the documented order, a column for itself, anything else
// for nothing; the expansions follow one another in the order of the names.
TEST(ColumnUnits, ExpandGroupsAndColumns) {
  const Scene scene = LoadSceneText(kScene, "block.yaml");
  EXPECT_EQ(
      ExpandStudyColumns(scene, {"origin", "nope", "block_tilt", "energy"}),
      (Names{"block_ox", "block_oy", "block_oz", "block_tilt", "T_trans", "T_rot", "T", "V", "E"}));
  EXPECT_TRUE(ExpandStudyColumns(scene, {"nope"}).empty());
}

}  // namespace
}  // namespace chasles
