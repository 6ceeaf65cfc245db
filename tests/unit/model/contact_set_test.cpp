// Sets of bodies in contact entries: which bodies a set holds, the pairs and their order, the
// names of the contacts, what counts as a contact given twice, and the errors.

#include "chasles/model/contact_set.h"

#include <string>
#include <vector>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/error.h"
#include "chasles/model/model.h"

namespace chasles {
namespace {

using ::testing::HasSubstr;

const std::vector<std::string> kNames = {"cue", "ball1", "ball2", "ball10", "table", "ball*"};

std::vector<BodyIndex> Bodies(const std::vector<BodySetMember>& members) {
  std::vector<BodyIndex> out;
  for (const BodySetMember& m : members) out.push_back(m.body);
  return out;
}

BodySet Items(std::vector<std::string> items) {
  return {false, std::move(items)};
}

// The error ResolveBodySet or ExpandContactSet throws, with its item.
template <typename F>
BodySetError ErrorOf(F f) {
  try {
    f();
  } catch (const BodySetError& e) {
    return e;
  }
  ADD_FAILURE() << "no BodySetError";
  return BodySetError(BodySetRole::kBodies, -2, "");
}

TEST(BodyPattern, StarAndQuestionMarkOnly) {
  EXPECT_TRUE(MatchesBodyPattern("ball*", "ball"));  // `*` may match nothing
  EXPECT_TRUE(MatchesBodyPattern("ball*", "ball10"));
  EXPECT_FALSE(MatchesBodyPattern("ball*", "cue"));
  EXPECT_TRUE(MatchesBodyPattern("ball?", "ball1"));
  EXPECT_FALSE(MatchesBodyPattern("ball?", "ball10"));
  EXPECT_FALSE(MatchesBodyPattern("ball?", "ball"));
  EXPECT_TRUE(MatchesBodyPattern("*a*l*", "table"));
  EXPECT_TRUE(MatchesBodyPattern("*", ""));
  EXPECT_TRUE(MatchesBodyPattern("b*1*0", "ball10"));
  EXPECT_FALSE(MatchesBodyPattern("b*1*0", "ball1"));
  EXPECT_TRUE(MatchesBodyPattern("**x", "x"));
  // No character classes: `[` is itself.
  EXPECT_FALSE(MatchesBodyPattern("ball[12]", "ball1"));
  EXPECT_TRUE(MatchesBodyPattern("ball[12]", "ball[12]"));
  // `?` is one character, not one byte: "é" is two bytes in UTF-8.
  EXPECT_TRUE(MatchesBodyPattern("b?ll", "b\xC3\xA9ll"));
  EXPECT_FALSE(MatchesBodyPattern("b??ll", "b\xC3\xA9ll"));
  EXPECT_TRUE(MatchesBodyPattern("*?ll", "b\xC3\xA9ll"));
  EXPECT_TRUE(IsBodyPattern("a?"));
  EXPECT_FALSE(IsBodyPattern("all"));
}

TEST(BodySet, AllListAndPatternInBodyOrder) {
  EXPECT_EQ(Bodies(ResolveBodySet({true, {}}, kNames, BodySetRole::kBodies)),
            (std::vector<BodyIndex>{0, 1, 2, 3, 4, 5}));
  // A list keeps body order, not the list's order.
  EXPECT_EQ(Bodies(ResolveBodySet(Items({"table", "cue"}), kNames, BodySetRole::kBodies)),
            (std::vector<BodyIndex>{0, 4}));
  // "ball*" is a body's exact name, so it names that body and is no pattern.
  EXPECT_EQ(Bodies(ResolveBodySet(Items({"ball*"}), kNames, BodySetRole::kBodies)),
            (std::vector<BodyIndex>{5}));
  // A pattern matches names with `*` in them like any other ("ball*" has five characters).
  EXPECT_EQ(Bodies(ResolveBodySet(Items({"ball?"}), kNames, BodySetRole::kBodies)),
            (std::vector<BodyIndex>{1, 2, 5}));
  const std::vector<BodySetMember> m =
      ResolveBodySet(Items({"cue", "ball?*"}), kNames, BodySetRole::kBodies);
  ASSERT_EQ(Bodies(m), (std::vector<BodyIndex>{0, 1, 2, 3, 5}));
  EXPECT_EQ(m[0].item, 0);  // each body remembers the item that brought it in
  EXPECT_EQ(m[3].item, 1);
}

TEST(BodySet, AllIsTheBodyCalledAllWhenThereIsOne) {
  EXPECT_EQ(BodySetOfText("all").all, true);
  EXPECT_EQ(BodySetOfText("ball*").items, std::vector<std::string>{"ball*"});
  EXPECT_EQ(Bodies(ResolveBodySet({true, {}}, {"a", "all", "b"}, BodySetRole::kBodies)),
            std::vector<BodyIndex>{1});
}

TEST(BodySet, Errors) {
  BodySetError e = ErrorOf([] {
    ResolveBodySet(Items({"cue", "c?t"}), kNames, BodySetRole::kWith);
  });
  EXPECT_EQ(e.item(), 1);
  EXPECT_EQ(e.role(), BodySetRole::kWith);
  EXPECT_THAT(e.what(), HasSubstr("the pattern 'c?t' matches no body"));
  e = ErrorOf([] { ResolveBodySet(Items({"bal1"}), kNames, BodySetRole::kBodies); });
  EXPECT_EQ(e.item(), 0);
  EXPECT_THAT(e.what(), HasSubstr("no body 'bal1' (did you mean 'ball1'?)"));
  e = ErrorOf([] { ResolveBodySet(Items({"ball?", "ball2"}), kNames, BodySetRole::kBodies); });
  EXPECT_EQ(e.item(), 1);
  EXPECT_THAT(e.what(), HasSubstr("body 'ball2' is already in the set (item 1, 'ball?')"));
  e = ErrorOf([] { ResolveBodySet(Items({}), kNames, BodySetRole::kBodies); });
  EXPECT_EQ(e.item(), -1);
  EXPECT_THAT(e.what(), HasSubstr("an empty list names no body"));
  e = ErrorOf([] { ResolveBodySet(Items({"cue", "all"}), kNames, BodySetRole::kBodies); });
  EXPECT_THAT(e.what(), HasSubstr("'all' stands alone"));
}

TEST(ContactSet, OnePerBodyAgainstAPlane) {
  const std::vector<SetContact> c =
      ExpandContactSet("cloth", {Items({"ball?*"}), {}, false, false}, kNames);
  ASSERT_EQ(c.size(), 4u);
  EXPECT_EQ(c[0].name, "cloth_ball1");
  EXPECT_EQ(c[2].name, "cloth_ball10");
  EXPECT_EQ(c[3].name, "cloth_ball*");
  EXPECT_EQ(c[3].body, 5);
  EXPECT_EQ(c[3].other, kWorld);
}

TEST(ContactSet, BetweenEveryUnorderedPairOnceInBodyOrder) {
  // n bodies give n (n - 1) / 2 pairs (a, b), a < b in body order, ordered by a then b.
  const std::vector<SetContact> c = ExpandContactSet("hit", {{true, {}}, {}, false, true}, kNames);
  const size_t n = kNames.size();
  ASSERT_EQ(c.size(), n * (n - 1) / 2);
  size_t k = 0;
  for (size_t a = 0; a < n; ++a) {
    for (size_t b = a + 1; b < n; ++b, ++k) {
      EXPECT_EQ(c[k].body, static_cast<BodyIndex>(a));
      EXPECT_EQ(c[k].other, static_cast<BodyIndex>(b));
      EXPECT_EQ(c[k].name, fmt::format("hit_{}_{}", kNames[a], kNames[b]));
    }
  }
}

TEST(ContactSet, BetweenNeedsTwoBodies) {
  const BodySetError e = ErrorOf([] {
    ExpandContactSet("hit", {Items({"tab*"}), {}, false, true}, kNames);
  });
  EXPECT_THAT(e.what(), HasSubstr("the set holds one body ('table'), which has no pair"));
}

TEST(ContactSet, WithPairsEachBodyWithEachOther) {
  const std::vector<SetContact> c = ExpandContactSet(
      "hit", {Items({"ball1", "ball2"}), Items({"table", "cue"}), true, false}, kNames);
  ASSERT_EQ(c.size(), 4u);
  EXPECT_EQ(c[0].name, "hit_ball1_cue");
  EXPECT_EQ(c[1].name, "hit_ball1_table");
  EXPECT_EQ(c[2].name, "hit_ball2_cue");
  EXPECT_EQ(c[3].name, "hit_ball2_table");
  EXPECT_EQ(c[1].other_item, 0);  // `table` is the with-list's item 0
  // Two sets that share a body: that body would touch itself.
  const BodySetError e = ErrorOf([] {
    ExpandContactSet("hit", {Items({"ball?"}), Items({"cue", "ball2"}), true, false}, kNames);
  });
  EXPECT_EQ(e.role(), BodySetRole::kWith);
  EXPECT_EQ(e.item(), 1);
  EXPECT_THAT(e.what(), HasSubstr("body 'ball2' is in both 'body' and 'with'"));
}

TEST(ContactSet, TooManyContactsRefusedBeforeTheyAreMade) {
  // 201 bodies in pairs: 201 * 200 / 2 = 20,100 > kMaxSetContacts = 20,000; 200 give 19,900.
  static_assert(kMaxSetContacts == 20000);
  std::vector<std::string> names;
  for (int i = 0; i < 201; ++i) names.push_back(fmt::format("b{}", i));
  const BodySetError e = ErrorOf([&] {
    ExpandContactSet("hit", {{true, {}}, {}, false, true}, names);
  });
  EXPECT_THAT(e.what(), HasSubstr("stands for 20100 contacts (201 bodies, every pair)"));
  names.pop_back();
  EXPECT_EQ(ExpandContactSet("hit", {{true, {}}, {}, false, true}, names).size(), 19900u);
}

TEST(ContactTargetIndex, ASetMayNotRepeatAContactTwoSingleEntriesMay) {
  ContactTargetIndex index;
  EXPECT_EQ(index.Add(PairTarget(0, 1), 0, false), -1);
  EXPECT_EQ(index.Add(PairTarget(1, 0), 1, false), -1);  // one by one: allowed, as before
  EXPECT_EQ(index.Add(PairTarget(0, 1), 2, true), 0);    // from a set: the first one clashes
  EXPECT_EQ(index.Add(PairTarget(0, 2), 3, true), -1);
  EXPECT_EQ(index.Add(PairTarget(2, 0), 4, false), 3);  // a single entry after a set's
  // The same plane written with another point on it and a longer normal.
  EXPECT_EQ(index.Add(PlaneTarget(0, Vec3(0, 0, 1), Vec3(0, 0, 1)), 5, true), -1);
  EXPECT_EQ(index.Add(PlaneTarget(0, Vec3(4, -3, 1), Vec3(0, 0, 2)), 6, false), 5);
  EXPECT_EQ(index.Add(PlaneTarget(0, Vec3(0, 0, 2), Vec3(0, 0, 1)), 7, true), -1);
}

Model Balls(int n) {
  Model model;
  const MassProperties ball(1.0, Vec3::Zero(),
                            RotationalInertia::FromMatrix(Mat3::Identity() * 0.004));
  for (int i = 0; i < n; ++i) model.AddBody(fmt::format("ball{}", i + 1), ball);
  return model;
}

TEST(AddContactSet, AddsTheExpandedContactsToAModel) {
  Model model = Balls(4);
  ContactSpec floor;
  floor.name = "floor";
  floor.radius = 0.1;
  EXPECT_EQ(AddContactSet(model, floor, {{true, {}}, {}, false, false}),
            (std::vector<int>{0, 1, 2, 3}));
  ContactSpec hit;
  hit.name = "hit";
  hit.shape = ContactShape::kSphereSphere;
  hit.radius = hit.other_radius = 0.1;
  EXPECT_EQ(AddContactSet(model, hit, {Items({"ball?"}), {}, false, true}).size(), 6u);
  EXPECT_EQ(model.contact(4).name(), "hit_ball1_ball2");
  EXPECT_EQ(model.contact(9).other_body(), 3);
  // A set that repeats a pair leaves the model as it was.
  const int before = model.num_contacts();
  EXPECT_THROW(AddContactSet(model, hit, {Items({"ball1"}), Items({"ball4"}), true, false}),
               BodySetError);
  EXPECT_EQ(model.num_contacts(), before);
  floor.shape = ContactShape::kSphereSphere;
  EXPECT_THROW(AddContactSet(model, floor, {{true, {}}, {}, false, false}), InputError);
}

}  // namespace
}  // namespace chasles
