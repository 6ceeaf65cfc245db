// Contact entries that name sets of bodies, read from scene text: the contacts they stand for
// are the ones the same scene lists one by one, field for field; each error points at its
// place.

#include "chasles/scene/scene_contacts.h"

#include <cmath>
#include <string>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/scene/scene.h"
#include "chasles/scene/scene_error.h"

namespace chasles {
namespace {

using ::testing::HasSubstr;

// Three balls, one with a named point `top`, and a crate; the contacts follow.
std::string Scene4(const std::string& contacts) {
  return R"(chasles: 3
parameters:
  R: 0.1 m
bodies:
  - {name: ball1, parts: [{shape: sphere, radius: R, mass: 1 kg}], initial: {position: [0, 0, R]}}
  - {name: ball2, parts: [{shape: sphere, radius: R, mass: 1 kg}], initial: {position: [1, 0, R]},
     points: {top: [0, 0, R]}}
  - {name: ball3, parts: [{shape: spherical_shell, radius: R, mass: 1 kg}], initial: {position: [2, 0, R]}}
  - {name: crate, parts: [{shape: box, size: [0.2, 0.2, 0.2], mass: 1 kg}], initial: {position: [3, 0, 0.1]}}
contacts:
)" + contacts;
}

SceneContacts Contacts(const std::string& contacts) {
  return LoadSceneText(Scene4(contacts), "s.yaml").dynamics.contacts;
}

SceneError ErrorOf(const std::string& contacts) {
  try {
    LoadSceneText(Scene4(contacts), "s.yaml");
  } catch (const SceneError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for\n" << contacts;
  return SceneError("", 0, 0, "", "");
}

// Every field BuildStudy reads, compared exactly: a set entry's contacts must be the explicit
// entries' to the bit.
void ExpectSame(const SceneContact& a, const SceneContact& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.body, b.body);
  EXPECT_EQ(a.shape, b.shape);
  EXPECT_EQ(a.p_BoC_B, b.p_BoC_B) << a.name;
  EXPECT_EQ(a.axis_B, b.axis_B);
  EXPECT_EQ(a.radius, b.radius);
  EXPECT_EQ(a.length, b.length);
  EXPECT_EQ(a.size, b.size);
  EXPECT_EQ(a.points_B, b.points_B);
  EXPECT_EQ(a.point_names, b.point_names);
  EXPECT_EQ(a.with_plane, b.with_plane);
  EXPECT_EQ(a.plane_point_W, b.plane_point_W);
  EXPECT_EQ(a.plane_normal_W, b.plane_normal_W);
  EXPECT_EQ(a.other_body, b.other_body);
  EXPECT_EQ(a.p_OoD_O, b.p_OoD_O) << a.name;
  EXPECT_TRUE(a.other_radius == b.other_radius ||
              (std::isnan(a.other_radius) && std::isnan(b.other_radius)));  // NaN on a plane
  EXPECT_EQ(a.mu_s, b.mu_s);
  EXPECT_EQ(a.mu_k, b.mu_k);
  EXPECT_EQ(a.mu_r, b.mu_r);
  EXPECT_EQ(a.restitution, b.restitution);
  EXPECT_EQ(a.restitution_law, b.restitution_law);
  EXPECT_EQ(a.materials, b.materials);
}

void ExpectSame(const SceneContacts& a, const SceneContacts& b) {
  ASSERT_EQ(a.contacts.size(), b.contacts.size());
  for (size_t i = 0; i < a.contacts.size(); ++i) ExpectSame(a.contacts[i], b.contacts[i]);
  EXPECT_EQ(a.point_labels(), b.point_labels());
}

TEST(ContactSets, PatternGivesOnePlaneContactPerBodyAsListed) {
  const std::string plane =
      "shape: sphere, radius: R, mu_s: 0.3, mu_k: 0.2, mu_r: 0.01, "
      "plane: {point: [0, 0, 0], normal: [0, 0, 1]}";
  const SceneContacts set =
      Contacts(fmt::format("  - {{name: cloth, body: 'ball*', {}}}\n", plane));
  ExpectSame(set, Contacts(fmt::format("  - {{name: cloth_ball1, body: ball1, {0}}}\n"
                                       "  - {{name: cloth_ball2, body: ball2, {0}}}\n"
                                       "  - {{name: cloth_ball3, body: ball3, {0}}}\n",
                                       plane)));
  // A list in another order gives the bodies in scene order.
  ExpectSame(
      set, Contacts(fmt::format("  - {{name: cloth, body: [ball3, ball1, ball2], {}}}\n", plane)));
}

TEST(ContactSets, BetweenGivesEveryPairOnceWithEachBodysOwnCentre) {
  // Each pair (a, b), a before b in scene order, once; ball3 is a spherical shell, which a
  // sphere contact describes too.
  const std::string sphere = "shape: sphere, radius: R, restitution: 0.9, restitution_law: newton";
  const SceneContacts set =
      Contacts(fmt::format("  - {{name: hit, between: 'ball?', {}}}\n", sphere));
  ExpectSame(set,
             Contacts(fmt::format(
                 "  - {{name: hit_ball1_ball2, body: ball1, with: ball2, other_radius: R, {0}}}\n"
                 "  - {{name: hit_ball1_ball3, body: ball1, with: ball3, other_radius: R, {0}}}\n"
                 "  - {{name: hit_ball2_ball3, body: ball2, with: ball3, other_radius: R, {0}}}\n",
                 sphere)));
  EXPECT_EQ(set.contacts.size(), 3u);
}

TEST(ContactSets, WithPairsTakeOtherCentreOnTheOtherBodies) {
  const SceneContacts set = Contacts(
      "  - {name: tip, body: ball2, center: top, shape: sphere, radius: 0.01 m, with: [ball3, "
      "ball1], "
      "other_radius: R}\n");
  ExpectSame(set, Contacts("  - {name: tip_ball2_ball1, body: ball2, center: top, shape: sphere, "
                           "radius: 0.01 m, with: ball1, other_radius: R}\n"
                           "  - {name: tip_ball2_ball3, body: ball2, center: top, shape: sphere, "
                           "radius: 0.01 m, with: ball3, other_radius: R}\n"));
  // Body order is the pair's order: (ball2, ball1) is listed before (ball2, ball3).
  EXPECT_EQ(set.contacts[0].other_body, 0);
  EXPECT_EQ(set.contacts[0].p_BoC_B, Vec3(0, 0, 0.1));
}

TEST(ContactSets, AllAndNamesThatLookLikeSets) {
  // `all` takes every body (shape points fits any body).
  const SceneContacts all = Contacts(
      "  - {name: f, body: all, shape: points, points: [center_of_mass], plane: {normal: [0, 0, "
      "1]}}\n");
  ASSERT_EQ(all.contacts.size(), 4u);
  EXPECT_EQ(all.contacts[3].name, "f_crate");
  EXPECT_EQ(all.point_labels()[3], "f_crate");  // one point: the contact's name
  // A body named `all` or `b*` keeps its name's meaning: one contact, named as written.
  const std::string text = R"(chasles: 3
bodies:
  - {name: all, parts: [{shape: sphere, radius: 0.1 m, mass: 1 kg}]}
  - {name: b*, parts: [{shape: sphere, radius: 0.1 m, mass: 1 kg}]}
contacts:
  - {name: f, body: all, shape: sphere, radius: 0.1 m, plane: {normal: [0, 0, 1]}}
  - {name: g, body: b*, shape: sphere, radius: 0.1 m, plane: {normal: [0, 0, 1]}}
)";
  const SceneContacts c = LoadSceneText(text, "s.yaml").dynamics.contacts;
  ASSERT_EQ(c.contacts.size(), 2u);
  EXPECT_EQ(c.contacts[0].name, "f");
  EXPECT_EQ(c.contacts[0].body, 0);
  EXPECT_EQ(c.contacts[1].name, "g");
  EXPECT_EQ(c.contacts[1].body, 1);
}

TEST(ContactSets, ErrorsPointAtTheItem) {
  // Line 11 is the first contact; `body: [` begins at column 21, its items after it.
  SceneError e = ErrorOf(
      "  - {name: c, body: [ball1, 'cue*'], shape: sphere, radius: R, plane: {normal: [0, 0, "
      "1]}}\n");
  EXPECT_EQ(e.line(), 11);
  EXPECT_EQ(e.column(), 29);
  EXPECT_EQ(e.key(), "contacts[0].body[1]");
  EXPECT_THAT(e.message(), HasSubstr("the pattern 'cue*' matches no body"));

  e = ErrorOf("  - {name: c, between: all, shape: sphere, radius: R}\n");
  EXPECT_EQ(e.key(), "contacts[0].between");
  EXPECT_THAT(e.message(), HasSubstr("body 'crate' of the set has part 'part 1', a box, which a "
                                     "sphere contact does not describe"));

  e = ErrorOf("  - {name: c, between: [ball1, 'ball*'], shape: sphere, radius: R}\n");
  EXPECT_EQ(e.key(), "contacts[0].between[1]");
  EXPECT_THAT(e.message(), HasSubstr("body 'ball1' is already in the set (item 1, 'ball1')"));

  e = ErrorOf(
      "  - {name: c, body: 'ball*', with: ball2, shape: sphere, radius: R, other_radius: R}\n");
  EXPECT_EQ(e.key(), "contacts[0].with");
  EXPECT_THAT(e.message(), HasSubstr("body 'ball2' is in both 'body' and 'with'"));

  e = ErrorOf("  - {name: c, between: 'ball*', body: ball1, shape: sphere, radius: R}\n");
  EXPECT_EQ(e.key(), "contacts[0].body");

  e = ErrorOf("  - {name: c, between: 'ball*', shape: sphere, radius: R, other_radius: R}\n");
  EXPECT_EQ(e.key(), "contacts[0].other_radius");

  e = ErrorOf("  - {name: c, between: 'ball*', shape: disk, radius: R, axis: [0, 0, 1]}\n");
  EXPECT_EQ(e.key(), "contacts[0].shape");
}

TEST(ContactSets, AContactGivenTwiceNamesBothPlaces) {
  // The set's pair ball1/ball2 repeats the single entry's, which comes first (line 11, col 5).
  SceneError e = ErrorOf(
      "  - {name: k, body: ball2, shape: sphere, radius: R, with: ball1, other_radius: R}\n"
      "  - {name: h, between: [ball1, ball2, ball3], shape: sphere, radius: R}\n");
  EXPECT_EQ(e.line(), 12);
  EXPECT_EQ(e.key(), "contacts[1].between[1]");
  EXPECT_THAT(e.message(),
              HasSubstr("contact 'h_ball1_ball2' touches what contact 'k' "
                        "(s.yaml:11:5: contacts[0]) touches, the same pair of bodies"));
  // A single entry after the set's: the same, at the single entry's `with`.
  e = ErrorOf(
      "  - {name: h, between: 'ball?', shape: sphere, radius: R}\n"
      "  - {name: k, body: ball3, shape: sphere, radius: R, with: ball2, other_radius: R}\n");
  EXPECT_EQ(e.key(), "contacts[1].with");
  EXPECT_THAT(e.message(), HasSubstr("contact 'k' touches what contact 'h_ball2_ball3'"));
  // A plane: the same plane through another point, with a longer normal.
  e = ErrorOf(
      "  - {name: f, body: 'ball?', shape: sphere, radius: R, plane: {normal: [0, 0, 1]}}\n"
      "  - {name: g, body: ball2, shape: sphere, radius: R, plane: {point: [5, 5, 0], "
      "normal: [0, 0, 2]}}\n");
  EXPECT_THAT(e.message(), HasSubstr("contact 'g' touches what contact 'f_ball2' (s.yaml:11:5: "
                                     "contacts[0]) touches, the same body on the same plane"));
  // Two single entries on one pair stay allowed (two spheres of one body, say).
  EXPECT_EQ(
      Contacts(
          "  - {name: a, body: ball1, shape: sphere, radius: R, with: ball2, other_radius: R}\n"
          "  - {name: b, body: ball2, shape: sphere, radius: R, with: ball1, other_radius: R}\n")
          .contacts.size(),
      2u);
  // A name a set makes that is already taken.
  e = ErrorOf(
      "  - {name: f_ball1, body: crate, shape: box, size: [0.2, 0.2, 0.2], plane: {normal: [0, 0, "
      "1]}}\n"
      "  - {name: f, body: 'ball?', shape: sphere, radius: R, plane: {normal: [0, 0, 1]}}\n");
  EXPECT_THAT(e.message(),
              HasSubstr("the name 'f_ball1' of a contact this set stands for is already used"));
}

}  // namespace
}  // namespace chasles
