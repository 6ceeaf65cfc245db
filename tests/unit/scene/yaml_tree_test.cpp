#include "scene/internal/yaml_tree.h"

#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/scene/scene_error.h"

namespace chasles::scene_internal {
namespace {

/// "LINE:COL MESSAGE" of the SceneError ParseYaml throws, or "ok".
std::string Error(const std::string& text) {
  try {
    ParseYaml(text, "s.yaml");
  } catch (const SceneError& e) {
    return std::to_string(e.line()) + ":" + std::to_string(e.column()) + " " + e.message();
  }
  return "ok";
}

TEST(YamlTree, OneDocumentOnly) {
  EXPECT_TRUE(ParseYaml("a: 1\n", "s.yaml").Root().IsMap());
  EXPECT_TRUE(ParseYaml("---\na: 1\n...\n", "s.yaml").Root().IsMap());
  EXPECT_FALSE(ParseYaml("", "s.yaml").Root().IsDefined());
  EXPECT_FALSE(ParseYaml("# only a comment\n", "s.yaml").Root().IsDefined());
  EXPECT_EQ(Error("a: 1\n# note\n---\nb: 2\n"),
            "3:1 a second YAML document starts here; a scene file holds one document (remove "
            "this '---' and what follows, or put it in its own file)");
  // An empty second document ("---" alone at the end) is a second document too.
  EXPECT_THAT(Error("a: 1\n---\n"), ::testing::StartsWith("2:1 a second YAML document"));
}

TEST(YamlTree, SyntaxErrorsNameTheirPlace) {
  // A lone ',' (yaml-cpp 0.7's LoadAll never returned on it) is an error at once, at its place.
  for (const char* text : {",", ",\nbodies: []\n", "# c\n  ,\n---\na: 1\n"}) {
    EXPECT_THAT(Error(text), ::testing::HasSubstr("this is not valid YAML: ")) << text;
  }
  EXPECT_THAT(Error("# c\n  ,\n"), ::testing::StartsWith("2:3 this is not valid YAML"));
  EXPECT_EQ(Error("a: 1\n b: 2\n"),
            "2:3 this is not valid YAML: mapping values are not allowed in this context");
  // The context points back to where the construct started.
  EXPECT_EQ(Error("x: 1\na:\n  - 1\n  b: 2\n"),
            "4:3 this is not valid YAML: did not find expected '-' indicator (while parsing a "
            "block collection that starts at line 3, column 3); check this line's indentation "
            "against the lines above it");
  EXPECT_THAT(Error("a: [1, 2\n"), ::testing::StartsWith("2:1 this is not valid YAML"));
  // A control character is the reader's error, at its byte.
  EXPECT_THAT(Error("a: 1\nb: x\x01y\n"),
              ::testing::StartsWith("2:5 this is not valid YAML: control characters"));
}

TEST(YamlTree, ColumnsCountBytesAfterAByteOrderMark) {
  // 'é' is two bytes, '日' three: the column of x counts them as such (5 + 6).
  const YamlDocument d = ParseYaml("\xC3\xA9\xE6\x97\xA5: [1, x]\nb: \"q\"\n", "s.yaml");
  const YamlNode x = d.Root()["\xC3\xA9\xE6\x97\xA5"][1];
  EXPECT_EQ(x.Scalar(), "x");
  EXPECT_EQ(x.Mark().line, 0);
  EXPECT_EQ(x.Mark().column, 11);
  EXPECT_EQ(x.Mark().pos, 11u);
  const YamlNode q = d.Root()["b"];
  EXPECT_EQ(q.Mark().line, 1);
  EXPECT_EQ(q.Mark().column, 3);  // the opening quote
  EXPECT_EQ(q.Mark().pos, 17u);   // line 1 starts at byte 14
  EXPECT_TRUE(q.Quoted());
  // A byte-order mark is not counted.
  const YamlDocument bom = ParseYaml(
      "\xEF\xBB\xBF"
      "a: 1\nb: 2\n",
      "s.yaml");
  EXPECT_EQ(bom.Root()["a"].Mark().column, 3);
  EXPECT_EQ(bom.Root()["b"].Mark().pos, 8u);
  EXPECT_EQ(bom.Root().Mark().column, 0);
  // Places after a multi-byte character on an earlier line are unaffected.
  EXPECT_EQ(ParseYaml("t: \xC3\xA9\nu: v\n", "s.yaml").Root()["u"].Mark().pos, 9u);
}

TEST(YamlTree, NullsScalarsAndStyles) {
  const YamlDocument d = ParseYaml(
      "a:\nb: ~\nc: null\nd: \"null\"\ne: !!str null\nf: 'x'\ng: [1, {h: 2}]\ni:\n  - 3\n",
      "s.yaml");
  const YamlNode r = d.Root();
  EXPECT_TRUE(r["a"].IsNull());
  EXPECT_TRUE(r["b"].IsNull());
  EXPECT_TRUE(r["c"].IsNull());
  EXPECT_EQ(r["c"].Scalar(), "");
  EXPECT_TRUE(r["d"].IsScalar());  // quoted: a string
  EXPECT_EQ(r["d"].Scalar(), "null");
  EXPECT_TRUE(r["e"].IsScalar());  // tagged: a string
  EXPECT_TRUE(r["f"].Quoted());
  EXPECT_FALSE(r["b"].Quoted());
  EXPECT_TRUE(r["g"].Flow());
  EXPECT_TRUE(r["g"][1].Flow());
  EXPECT_FALSE(r["i"].Flow());
  EXPECT_EQ(r["g"].size(), 2u);
  EXPECT_EQ(r["g"][1]["h"].Scalar(), "2");
  EXPECT_FALSE(r["g"][2].IsDefined());
  EXPECT_FALSE(r["nope"].IsDefined());
  EXPECT_FALSE(r["g"]["h"].IsDefined());  // a key of a list
  EXPECT_FALSE(r["a"][size_t{0}].IsDefined());
  EXPECT_EQ(r.size(), 8u);
  std::string keys;
  for (const auto& kv : r) keys += std::string(kv.first.Scalar());
  EXPECT_EQ(keys, "abcdefgi");
}

TEST(YamlTree, AliasesShareTheirAnchorsNode) {
  const YamlDocument d = ParseYaml("a: &r 0.1 m\nb: *r\nc: &l [1, 2]\nd: *l\n", "s.yaml");
  EXPECT_EQ(d.Root()["b"].Scalar(), "0.1 m");
  EXPECT_EQ(d.Root()["d"][1].Scalar(), "2");
  EXPECT_EQ(Error("a: *r\n"),
            "1:4 this is not valid YAML: the alias *r names no anchor &r defined before it");
  // A container's anchor is known once it is complete: it cannot contain itself.
  EXPECT_THAT(Error("a: &l [1, *l]\n"), ::testing::StartsWith("1:11 this is not valid YAML"));
}

TEST(YamlTree, NestingIsBounded) {
  const auto nested = [](int n) { return std::string(n, '[') + std::string(n, ']'); };
  EXPECT_TRUE(ParseYaml(nested(1000), "s.yaml").Root().IsSequence());
  EXPECT_EQ(Error(nested(1001)),
            "1:1001 this YAML nests lists and mappings more than 1000 levels deep; a scene needs "
            "a few");
}

TEST(YamlTree, BooleansOfYaml11) {
  const YamlDocument d = ParseYaml(
      "[true, True, TRUE, yes, Yes, YES, on, On, ON, y, Y, false, False, FALSE, no, No, NO, off, "
      "Off, OFF, n, N, tRUE, 1, 0, \"\", [x]]",
      "s.yaml");
  const YamlNode r = d.Root();
  for (size_t i = 0; i < 22; ++i) {
    bool b = i >= 11;
    ASSERT_TRUE(DecodeBool(r[i], b)) << i;
    EXPECT_EQ(b, i < 11) << i;
  }
  for (size_t i = 22; i < r.size(); ++i) {
    bool b = false;
    EXPECT_FALSE(DecodeBool(r[i], b)) << i;
  }
}

TEST(YamlTree, DocumentsBuiltByHand) {
  YamlDocument d;
  const auto seq = d.AddSequence({d.AddScalar("1"), d.AddNull()});
  d.SetRoot(d.AddMap({{d.AddScalar("k"), seq}}));
  EXPECT_EQ(d.Root()["k"][size_t{0}].Scalar(), "1");
  EXPECT_TRUE(d.Root()["k"][1].IsNull());
  EXPECT_EQ(d.Root()["k"].Mark().line, -1);
}

}  // namespace
}  // namespace chasles::scene_internal
