#include "chasles/scene/expression.h"
#include <gtest/gtest.h>
TEST(Expression, Smoke) {
  EXPECT_EQ(chasles::EvaluateQuantity("2 m", {}).value, 2.0);
}
