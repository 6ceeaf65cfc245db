#include "chasles/suggest.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace chasles {
namespace {

using ::testing::ElementsAre;

TEST(Suggest, EditDistanceCountsSwapsOnce) {
  EXPECT_EQ(EditDistance("steel", "steel"), 0);
  EXPECT_EQ(EditDistance("stele", "steel"), 1);  // swap of neighbours
  EXPECT_EQ(EditDistance("raduis", "radius"), 1);
  EXPECT_EQ(EditDistance("bodys", "bodies"), 2);
  EXPECT_EQ(EditDistance("", "abc"), 3);
  EXPECT_EQ(EditDistance("kitten", "sitting"), 3);
}

TEST(Suggest, ClosestOnlyAndCaseInsensitive) {
  EXPECT_THAT(SuggestNames("lenght", {"width", "length", "height"}), ElementsAre("length"));
  EXPECT_THAT(SuggestNames("KG", {"kg", "g", "mg"}), ElementsAre("kg"));
  EXPECT_THAT(SuggestNames("bodys", {"title", "units", "bodies"}), ElementsAre("bodies"));
  EXPECT_TRUE(SuggestNames("furlong", {"m", "ft", "in"}).empty());
  // Short names allow one edit only: "ab" is not a typo of "al".
  EXPECT_THAT(SuggestNames("ab", {"al"}), ElementsAre());
}

TEST(Suggest, HintText) {
  EXPECT_EQ(DidYouMeanHint({}), "");
  EXPECT_EQ(DidYouMeanHint({"a"}), " (did you mean 'a'?)");
  EXPECT_EQ(DidYouMeanHint({"a", "b", "c"}), " (did you mean 'a', 'b' or 'c'?)");
  EXPECT_EQ(DidYouMean("cylindre", {"sphere", "cylinder"}), " (did you mean 'cylinder'?)");
}

}  // namespace
}  // namespace chasles
