// The one JSON parser of beamid's readers (hb/strict_json.h): a key written
// twice is refused at any depth, naming its path and the file; nesting, the
// keys of one object and the values of the text are bounded; a number beyond
// double range is refused as out of range; a syntax error names the file, its
// line and column and the fix; what is accepted reads as nlohmann would.
#include "hb/strict_json.h"

#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hb/errors.h"
#include "tests/support/expect_refused.h"

namespace beamid {
namespace {

using beamid::testing::InputErrorOf;
using ::testing::HasSubstr;

std::string Refusal(const std::string& text, const StrictJsonLimits& limits = {}) {
  return InputErrorOf([&] { ParseStrictJson(text, "dir/file.json", "see docs/x.md", limits); });
}

TEST(StrictJson, ReadsWhatNlohmannReadsInTheFilesOrder) {
  const std::string text =
      R"({"z": 1, "a": [1.5, -2, 18446744073709551615, "s", true, null, {}, []], "m": {"k": {"q": [[0.1e-3]]}}})";
  const nlohmann::ordered_json strict = ParseStrictJson(text, "f.json", "");
  EXPECT_EQ(strict, nlohmann::ordered_json::parse(text));
  EXPECT_EQ(strict.begin().key(), "z");  // the file's order, not sorted
  EXPECT_EQ(ParseStrictJson<nlohmann::json>(text, "f.json", ""), nlohmann::json::parse(text));
  EXPECT_EQ(ParseStrictJson("  42 ", "f.json", ""), nlohmann::ordered_json(42));
}

TEST(StrictJson, RefusesAKeyWrittenTwiceAtEveryDepthNamingItsPathAndTheFile) {
  const std::string root = Refusal(R"({"length_m": 0.6, "length_m": 6.0})");
  EXPECT_THAT(root, HasSubstr("dir/file.json: the key \"length_m\" is written twice"));
  EXPECT_THAT(root, HasSubstr("Fix: keep one of the two entries (see docs/x.md)"));
  const std::string deep = Refusal(R"({"a": [{"b": 1}, {"c": {"d": [0, {"k1": 1, "x": 2, "k1": 1}]}}]})");
  EXPECT_THAT(deep, HasSubstr("\"k1\" is written twice in one object (at \"a[1].c.d[1].k1\")"));
  // The same key in two objects, and the same value twice in an array, are fine.
  EXPECT_NO_THROW(ParseStrictJson(R"({"a": {"k": 1}, "b": {"k": 1}, "c": [1, 1]})", "f", ""));
  // For nlohmann::json (sorted keys) too.
  EXPECT_THROW(ParseStrictJson<nlohmann::json>(R"({"s": {"k": 1, "k": 1}})", "f", ""), InputError);
}

TEST(StrictJson, BoundsTheNestingDepth) {
  const auto nested = [](int depth) { return std::string(depth, '[') + std::string(depth, ']'); };
  EXPECT_NO_THROW(ParseStrictJson(nested(64), "f", ""));
  EXPECT_THAT(Refusal(nested(65)), HasSubstr("deeper than 64 levels"));
  // A deep text is refused at the bound, not parsed (a million levels).
  EXPECT_THAT(Refusal(nested(1'000'000)), HasSubstr("deeper than 64 levels"));
  EXPECT_THAT(Refusal(R"({"a": {"b": {"c": 1}}})", {.max_depth = 2}), HasSubstr("deeper than 2 levels (at \"a.b\")"));
}

TEST(StrictJson, BoundsTheValuesOfTheTextAndTheKeysOfAnObject) {
  EXPECT_NO_THROW(ParseStrictJson("[1, 2, 3]", "f", "", {.max_values = 4}));
  EXPECT_THAT(Refusal("[1, 2, 3, 4]", {.max_values = 4}), HasSubstr("holds more than 4 JSON values (at \"[3]\")"));
  EXPECT_NO_THROW(ParseStrictJson(R"({"a": 1, "b": 2})", "f", "", {.max_object_members = 2}));
  EXPECT_THAT(Refusal(R"({"a": 1, "b": 2, "c": 3})", {.max_object_members = 2}), HasSubstr("more than 2 keys"));
}

TEST(StrictJson, RefusesANumberBeyondDoubleRangeAsOutOfRange) {
  const std::string message = Refusal(R"({"beam": {"youngs_modulus_Pa": 1e400}})");
  EXPECT_THAT(message, HasSubstr("dir/file.json: not valid JSON (the number 1e400 (at \"beam.youngs_modulus_Pa\") ending "
                                 "at byte 36 is out of range"));
  EXPECT_THAT(Refusal("[-1e400]"), HasSubstr("out of range"));
  // An integer beyond 64 bits is a double, which holds it.
  EXPECT_NO_THROW(ParseStrictJson("[123456789012345678901234567890]", "f", ""));
}

TEST(StrictJson, ASyntaxErrorNamesTheFileLineColumnAndTheFix) {
  const std::string message = Refusal("{\n  \"a\": 1,\n  \"b\": }\n");
  EXPECT_THAT(message, HasSubstr("dir/file.json: not valid JSON (parse error at line 3, column 8"));
  EXPECT_THAT(message, HasSubstr("Fix: correct the JSON at that line and column (see docs/x.md)"));
  EXPECT_THAT(message, ::testing::Not(HasSubstr("[json.exception")));
  EXPECT_THAT(Refusal(""), HasSubstr("not valid JSON"));
  EXPECT_THAT(Refusal("{} {}"), HasSubstr("not valid JSON"));  // one value per file
  try {
    ParseStrictJson("[", "dir/file.json", "");
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "dir/file.json");
  }
}

}  // namespace
}  // namespace beamid
