#include "chasles/scene/units.h"
#include <gtest/gtest.h>
TEST(Units, Smoke) {
  EXPECT_TRUE(chasles::LookupUnit("m"));
}
