// The declaration of a format (hb/json_schema.h) on a toy format that holds
// every kind of field: what it writes reads back to the same struct; the
// reader refuses, naming the path and the fix, what the declaration does not
// allow; a misspelt key is named as such rather than as a missing field; the
// field table lists every field with its unit and range.
#include "hb/json_schema.h"

#include <complex>
#include <limits>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/support/expect_refused.h"
#include "tests/support/schema_checks.h"

namespace beamid::toy {

enum class Colour { kRed, kGreen };
constexpr schema::Name<Colour> kColours[] = {{Colour::kRed, "red"}, {Colour::kGreen, "green"}};

struct Sensor {
  std::string channel;
  double position_m = 0.0;
};

struct Curve {
  double force_N = 1.0;
  std::vector<std::complex<double>> phasors;
};

struct Toy {
  std::string name = "toy";
  int harmonics = 2;
  double frequency_hz = 50.0;
  double damping = std::numeric_limits<double>::quiet_NaN();
  bool stable = true;
  Colour colour = Colour::kRed;
  std::vector<double> levels_N;
  std::vector<std::string> labels;
  std::vector<Sensor> sensors;
  std::vector<Curve> curves;
  Sensor drive;
  double amplitude = 0.0;
};

void Describe(auto& io, schema::Like<Sensor> auto& s) { io.Number("position_m", s.position_m, "m", schema::NonNegative()); }

void Describe(auto& io, schema::Like<Toy> auto& t) {
  io.Constant("format", "toy/1");
  io.Text("name", t.name, schema::TextRule::kNotEmpty);
  io.Integer("harmonics", t.harmonics, 1, 9);
  io.Number("frequency_Hz", t.frequency_hz, "Hz", schema::Positive());
  io.Number("damping", t.damping, "1", schema::Probability().OrNull(), schema::kOptional);
  io.Boolean("stable", t.stable);
  io.Choice("colour", t.colour, kColours);
  io.Numbers("levels_N", t.levels_N, "N", schema::Positive(), 4);
  io.Texts("labels", t.labels, 3, schema::TextRule::kNotEmpty);
  io.Keyed("sensors", t.sensors, &Sensor::channel, 8);
  const auto phasors = schema::Count::Exactly(static_cast<std::size_t>(t.harmonics) + 1, "harmonics + 1");
  io.List("curves", t.curves, 5, schema::Presence::kRequired, [&](auto& curve_io, auto& c) {
    curve_io.Number("force_N", c.force_N, "N", schema::Positive());
    curve_io.Phasors("phasors", c.phasors, "m", phasors);
  });
  io.Object("drive", t.drive, schema::Presence::kRequired, [](auto& drive_io, auto& d) {
    drive_io.Text("channel", d.channel);
    drive_io.Number("position_m", d.position_m, "m", schema::NonNegative());
  });
  io.Derived("amplitude", 2.0 * t.frequency_hz, "Hz");
  io.Check(t.levels_N.size() <= t.curves.size() + 1, "at most one level more than curves");
}

}  // namespace beamid::toy

namespace beamid {
namespace {

using testing::InputErrorOf;
using ::testing::HasSubstr;
using toy::Toy;

constexpr schema::Format kToy{"toy/1", "toy file", "give a toy file"};

Toy Filled() {
  Toy t;
  t.name = "a toy";
  t.harmonics = 1;
  t.damping = 0.25;
  t.stable = false;
  t.colour = toy::Colour::kGreen;
  t.levels_N = {0.5, 2.0};
  t.labels = {"low", "high"};
  t.sensors = {{"acc1", 0.1}, {"acc3", 0.45}};
  t.curves = {{0.5, {{1.0, -2.0}, {3.0, 0.5}}}, {2.0, {{0.0, 0.0}, {-1.0, 1e-9}}}};
  t.drive = {"force", 0.2};
  return t;
}

Toy Read(const std::string& text) { return schema::FromJson<Toy>(text, "t.json", kToy); }

TEST(JsonSchema, WhatIsWrittenReadsBackToTheSameStruct) {
  const Toy a = Filled();
  const Toy b = Read(schema::ToJson(a));
  EXPECT_EQ(b.name, a.name);
  EXPECT_EQ(b.harmonics, 1);
  EXPECT_EQ(b.damping, 0.25);
  EXPECT_FALSE(b.stable);
  EXPECT_EQ(b.colour, toy::Colour::kGreen);
  EXPECT_EQ(b.levels_N, a.levels_N);
  EXPECT_EQ(b.labels, a.labels);
  ASSERT_EQ(b.sensors.size(), 2u);
  EXPECT_EQ(b.sensors[1].channel, "acc3");
  EXPECT_EQ(b.sensors[1].position_m, 0.45);
  ASSERT_EQ(b.curves.size(), 2u);
  EXPECT_EQ(b.curves[1].phasors[1], std::complex<double>(-1.0, 1e-9));
  EXPECT_EQ(b.drive.channel, "force");
  // The derived value is written, not read.
  EXPECT_THAT(schema::ToJson(a), HasSubstr("\"amplitude\": 100.0"));
}

TEST(JsonSchema, AMissingOptionalNumberKeepsItsDefaultAndNullReadsAsNaN) {
  std::string text = schema::ToJson(Filled());
  text.replace(text.find("\"damping\": 0.25"), 15, "\"damping\": null");
  EXPECT_TRUE(std::isnan(Read(text).damping));
}

TEST(JsonSchema, AMisspeltKeyIsNamedAsSuchNotAsAMissingField) {
  std::string text = schema::ToJson(Filled());
  text.replace(text.find("\"stable\""), 8, "\"stabel\"");
  const std::string message = InputErrorOf([&] { Read(text); });
  EXPECT_THAT(message, HasSubstr("t.json: field \"stabel\" is not a field here"));
  EXPECT_THAT(message, HasSubstr("the fields here: format, name, harmonics"));
}

TEST(JsonSchema, ARuleBetweenFieldsIsCheckedOnReadingAndOnWriting) {
  Toy t = Filled();
  t.levels_N = {1, 2, 3, 4};
  EXPECT_THROW(schema::ToJson(t), std::logic_error);
  std::string text = schema::ToJson(Filled());
  text.replace(text.find("2.0\n ]"), 3, "2.0, 3.0, 4.0");
  EXPECT_THAT(InputErrorOf([&] { Read(text); }), HasSubstr("breaks the rule: at most one level more than curves"));
}

TEST(JsonSchema, AFixedCountFollowsTheFieldItDependsOn) {
  std::string text = schema::ToJson(Filled());
  text.replace(text.find("\"harmonics\": 1"), 14, "\"harmonics\": 2");
  const std::string message = InputErrorOf([&] { Read(text); });
  EXPECT_THAT(message, HasSubstr("curves[0].phasors\" holds 2 entries, not exactly harmonics + 1"));
  Toy t = Filled();
  t.curves[0].phasors.pop_back();
  EXPECT_THROW(schema::ToJson(t), std::logic_error);
}

TEST(JsonSchema, AKeyedNameMustBeOneLineOfText) {
  Toy t = Filled();
  t.sensors[0].channel = "acc\n1";
  EXPECT_THAT(InputErrorOf([&] { Read(schema::ToJson(t)); }), HasSubstr("control character 0x0A"));
}

TEST(JsonSchema, EveryDeclaredFieldIsCheckedByTheGenericChecks) {
  testing::ExpectDeclarationHolds({
      .fields = schema::Fields<Toy>(),
      .sample = schema::ToJson(Filled()),
      .read = [](const std::string& text) { Read(text); },
      .rewrite = [](const std::string& text) { return schema::ToJson(Read(text)); },
  });
}

TEST(JsonSchema, TheFieldTableListsEveryFieldWithUnitAndRange) {
  const std::string table = schema::FieldTable(schema::Fields<Toy>());
  EXPECT_THAT(table, HasSubstr("| `frequency_Hz` | number | Hz | > 0 | yes |"));
  EXPECT_THAT(table, HasSubstr("| `damping` | number | 1 | 0 .. 1, or null | no |"));
  EXPECT_THAT(table, HasSubstr("| `colour` | string | – | \"red\" \\| \"green\" | yes |"));
  EXPECT_THAT(table, HasSubstr("| `sensors.<name>.position_m` | number | m | ≥ 0 | yes |"));
  EXPECT_THAT(table, HasSubstr("| `curves[].phasors` | [[re, im]] | m | exactly harmonics + 1 entries | yes |"));
  EXPECT_THAT(table, HasSubstr("| `drive.channel` | string |"));
  EXPECT_THAT(table, HasSubstr("| `(file)` | rule | – | at most one level more than curves |"));
}

}  // namespace
}  // namespace beamid
