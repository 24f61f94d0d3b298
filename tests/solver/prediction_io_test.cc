// The file of `beamid predict` (solver/estimation/prediction_io.h): every
// field the writer writes reads back to the same struct, bit for bit (NaN
// included), and the text read and written again is the same text; a file of
// the earlier inline writer (no "format", no "compared_quantity", keys sorted)
// reads; a damaged file is refused naming the file, the field and the fix.
#include "solver/estimation/prediction_io.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hb/errors.h"
#include "tests/support/same_value.h"
#include "tests/support/schema_checks.h"
#include "tests/support/temp_path.h"

#include "tests/support/expect_refused.h"

namespace beamid::solver {
namespace {

using beamid::testing::Same;

using beamid::testing::InputErrorOf;

using ::testing::HasSubstr;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

PredictionFile Filled() {
  PredictionFile f;
  f.beamid_version = "9.8.7";
  f.result_file = "runs/result.json";
  f.campaign_sha256 = "9f86d081884c7d659a2feaa0c55ad015a3bf4f1b2b0b822cd15d6c15b0f00a08";
  f.model_kind = ModelKind::kMultipleScales;
  f.position_m = 0.4567;
  f.compared_channel = "vel2";
  f.compared_quantity = "velocity_m_s";
  for (int i = 0; i < 2; ++i) {
    PredictionStep s;
    s.level = "level_" + std::to_string(i);
    s.file = "step_" + std::to_string(i) + ".csv";
    s.frequency_hz = 30.123456789 + i;
    s.converged = i == 0;
    for (int k = 1; k <= 3; ++k) {
      PredictionHarmonic h;
      h.k = k;
      h.displacement_m = {1.1e-4 / k + i, -2.2e-5 * k};
      h.displacement_std_real_m = 3.3e-7 * k;
      h.displacement_std_imag_m = k == 3 ? kNaN : 4.4e-7 * k;
      h.acceleration_m_s2 = {5.5 * k, -6.6 * k + i};
      h.acceleration_amplitude_m_s2 = 7.7 * k + i;
      h.compared = k < 3;  // the channel measured two harmonics
      if (h.compared) {
        h.measured = {0.011 * k, 0.022 * k + i};
        h.predicted = {0.0111 * k, 0.0219 * k + i};
        h.relative_error = 0.0123 * k + i;
      }
      s.harmonics.push_back(h);
    }
    s.time_s = {0.0, 0.01, 0.02 + i};
    s.acceleration_m_s2 = {1.5, -2.5, 0.5 * i};
    s.acceleration_std_m_s2 = {0.1, 0.2, i == 1 ? kNaN : 0.3};
    f.steps.push_back(s);
  }
  return f;
}

void ExpectSame(const PredictionFile& a, const PredictionFile& b) {
  EXPECT_EQ(a.beamid_version, b.beamid_version);
  EXPECT_EQ(a.result_file, b.result_file);
  EXPECT_EQ(a.campaign_sha256, b.campaign_sha256);
  EXPECT_EQ(a.model_kind, b.model_kind);
  EXPECT_TRUE(Same(a.position_m, b.position_m));
  EXPECT_EQ(a.compared_channel, b.compared_channel);
  EXPECT_EQ(a.compared_quantity, b.compared_quantity);
  ASSERT_EQ(a.steps.size(), b.steps.size());
  for (std::size_t i = 0; i < a.steps.size(); ++i) {
    SCOPED_TRACE("step " + std::to_string(i));
    const PredictionStep& x = a.steps[i];
    const PredictionStep& y = b.steps[i];
    EXPECT_EQ(x.level, y.level);
    EXPECT_EQ(x.file, y.file);
    EXPECT_TRUE(Same(x.frequency_hz, y.frequency_hz));
    EXPECT_EQ(x.converged, y.converged);
    ASSERT_EQ(x.harmonics.size(), y.harmonics.size());
    for (std::size_t k = 0; k < x.harmonics.size(); ++k) {
      SCOPED_TRACE("harmonic " + std::to_string(k));
      const PredictionHarmonic& g = x.harmonics[k];
      const PredictionHarmonic& h = y.harmonics[k];
      EXPECT_EQ(g.k, h.k);
      EXPECT_TRUE(Same(g.displacement_m, h.displacement_m));
      EXPECT_TRUE(Same(g.displacement_std_real_m, h.displacement_std_real_m));
      EXPECT_TRUE(Same(g.displacement_std_imag_m, h.displacement_std_imag_m));
      EXPECT_TRUE(Same(g.acceleration_m_s2, h.acceleration_m_s2));
      EXPECT_TRUE(Same(g.acceleration_amplitude_m_s2, h.acceleration_amplitude_m_s2));
      EXPECT_EQ(g.compared, h.compared);
      EXPECT_TRUE(Same(g.measured, h.measured));
      EXPECT_TRUE(Same(g.predicted, h.predicted));
      EXPECT_TRUE(Same(g.relative_error, h.relative_error));
    }
    ASSERT_EQ(x.time_s.size(), y.time_s.size());
    for (std::size_t j = 0; j < x.time_s.size(); ++j) EXPECT_TRUE(Same(x.time_s[j], y.time_s[j]));
    ASSERT_EQ(x.acceleration_m_s2.size(), y.acceleration_m_s2.size());
    for (std::size_t j = 0; j < x.acceleration_m_s2.size(); ++j)
      EXPECT_TRUE(Same(x.acceleration_m_s2[j], y.acceleration_m_s2[j]));
    ASSERT_EQ(x.acceleration_std_m_s2.size(), y.acceleration_std_m_s2.size());
    for (std::size_t j = 0; j < x.acceleration_std_m_s2.size(); ++j)
      EXPECT_TRUE(Same(x.acceleration_std_m_s2[j], y.acceleration_std_m_s2[j]));
  }
}

TEST(PredictionFile, EveryFieldSurvivesTheTextAndBackAndTheTextIsStable) {
  const PredictionFile original = Filled();
  const std::string text = PredictionFileToJson(original);
  const PredictionFile read = PredictionFileFromJson(text, "p.json");
  ExpectSame(original, read);
  EXPECT_EQ(PredictionFileToJson(read), text);
  EXPECT_THAT(text, HasSubstr("\"format\": \"beamid-prediction/1\""));
  EXPECT_THAT(text, HasSubstr("\"command\": \"predict\""));
  EXPECT_THAT(text, HasSubstr("\"beamid_version\": \"9.8.7\""));
  EXPECT_THAT(text, HasSubstr("\"campaign_sha256\": \"9f86d081"));
  EXPECT_THAT(text, HasSubstr("\"measured_velocity_m_s\""));
  EXPECT_THAT(text, HasSubstr("null"));  // the NaNs
}

TEST(PredictionFile, WithoutAComparedChannelTheTextHasNoComparison) {
  PredictionFile f = Filled();
  f.compared_channel = "";
  f.compared_quantity = "";
  for (auto& s : f.steps)
    for (auto& h : s.harmonics) {
      h.compared = false;
      h.measured = h.predicted = {};
      h.relative_error = 0.0;
    }
  const std::string text = PredictionFileToJson(f);
  EXPECT_THAT(text, ::testing::Not(HasSubstr("measured_")));
  ExpectSame(f, PredictionFileFromJson(text, "p.json"));
}

TEST(PredictionFile, WrittenFileReadsBack) {
  const std::filesystem::path path = testing::UniqueTempPath("prediction.json");
  WritePredictionFile(path, Filled());
  ExpectSame(Filled(), ReadPredictionFile(path));
  std::filesystem::remove(path);
  const std::string message = InputErrorOf([&] { ReadPredictionFile(path); });
  EXPECT_THAT(message, HasSubstr(path.string()));
  EXPECT_THAT(message, HasSubstr("prediction file"));
}

// As the inline writer of `beamid predict` wrote it before the struct.
constexpr const char* kEarlierFile = R"({
 "beamid_version": "0.9.0",
 "command": "predict",
 "compared_channel": "acc3",
 "model": "hb",
 "position_m": 0.45,
 "result": "r.json",
 "steps": [
  {"acceleration_m_s2": [1.0, -1.0], "acceleration_std_m_s2": [0.1, 0.1], "converged": true, "file": "s1.csv",
   "frequency_Hz": 30.5,
   "harmonics": [
    {"acceleration_amplitude_m_s2": 3.0, "acceleration_m_s2": [3.0, 0.0], "displacement_m": [-8e-05, 0.0],
     "displacement_std_m": [1e-07, 2e-07], "k": 1, "measured_acceleration_m_s2": [2.9, 0.1],
     "predicted_acceleration_m_s2": [3.0, 0.0], "relative_error": 0.04},
    {"acceleration_amplitude_m_s2": 0.1, "acceleration_m_s2": [0.1, 0.0], "displacement_m": [-7e-07, 0.0],
     "displacement_std_m": [1e-09, 2e-09], "k": 2}
   ],
   "level": "low", "time_s": [0.0, 0.016]}
 ]
})";

TEST(PredictionFile, AFileOfTheEarlierWriterReads) {
  const PredictionFile f = PredictionFileFromJson(kEarlierFile, "old.json");
  EXPECT_EQ(f.beamid_version, "0.9.0");
  EXPECT_EQ(f.result_file, "r.json");
  EXPECT_EQ(f.campaign_sha256, "");
  EXPECT_EQ(f.model_kind, ModelKind::kHarmonicBalance);
  EXPECT_EQ(f.position_m, 0.45);
  EXPECT_EQ(f.compared_channel, "acc3");
  EXPECT_EQ(f.compared_quantity, "acceleration_m_s2");
  ASSERT_EQ(f.steps.size(), 1u);
  ASSERT_EQ(f.steps[0].harmonics.size(), 2u);
  EXPECT_TRUE(f.steps[0].harmonics[0].compared);
  EXPECT_EQ(f.steps[0].harmonics[0].measured, std::complex<double>(2.9, 0.1));
  EXPECT_EQ(f.steps[0].harmonics[0].relative_error, 0.04);
  EXPECT_FALSE(f.steps[0].harmonics[1].compared);
  EXPECT_EQ(f.steps[0].harmonics[1].displacement_std_imag_m, 2e-09);
  EXPECT_EQ(f.steps[0].time_s, (std::vector<double>{0.0, 0.016}));
}

std::string Damaged(const std::function<void(nlohmann::json&)>& damage) {
  nlohmann::json j = nlohmann::json::parse(PredictionFileToJson(Filled()));
  damage(j);
  return j.dump();
}

TEST(PredictionFile, AMissingFieldIsRefusedNamingTheFileAndTheField) {
  const std::string message = InputErrorOf([] {
    PredictionFileFromJson(Damaged([](nlohmann::json& j) { j["steps"][1]["harmonics"][0].erase("displacement_m"); }),
                           "out/p.json");
  });
  EXPECT_THAT(message, HasSubstr("out/p.json: field \"steps[1].harmonics[0].displacement_m\" is missing"));
  EXPECT_THAT(message, HasSubstr("Fix: "));
  EXPECT_THAT(InputErrorOf([] { PredictionFileFromJson(Damaged([](nlohmann::json& j) { j.erase("position_m"); }), "p.json"); }),
              HasSubstr("p.json: field \"position_m\" is missing"));
}

TEST(PredictionFile, AWrongFormatIsRefusedNamingTheFile) {
  const std::string message = InputErrorOf([] {
    PredictionFileFromJson(Damaged([](nlohmann::json& j) { j["format"] = "beamid-result/1"; }), "r.json");
  });
  EXPECT_THAT(message, HasSubstr("r.json: field \"format\" is \"beamid-result/1\""));
  EXPECT_THAT(message, HasSubstr("Fix: "));
  EXPECT_THAT(InputErrorOf([] {
                PredictionFileFromJson(Damaged([](nlohmann::json& j) { j["command"] = "identify"; }), "i.json");
              }),
              HasSubstr("i.json: field \"command\" is \"identify\""));
  EXPECT_THAT(InputErrorOf([] { PredictionFileFromJson("[]", "list.json"); }), HasSubstr("list.json: not a"));
  EXPECT_THAT(InputErrorOf([] { PredictionFileFromJson("{", "cut.json"); }), HasSubstr("cut.json: not valid JSON"));
}

TEST(PredictionFile, AFieldOfTheWrongTypeIsRefusedNamingTheFileAndTheField) {
  struct Case {
    std::function<void(nlohmann::json&)> damage;
    const char* field;
    const char* problem;
  };
  const Case cases[] = {
      {[](nlohmann::json& j) { j["position_m"] = "0.45"; }, "position_m", "must be a number"},
      {[](nlohmann::json& j) { j["steps"][0]["converged"] = 1; }, "steps[0].converged", "must be true or false"},
      {[](nlohmann::json& j) { j["steps"][0]["harmonics"][1]["k"] = 1.5; }, "steps[0].harmonics[1].k",
       "must be an integer"},
      {[](nlohmann::json& j) { j["steps"][1]["harmonics"][0]["displacement_m"] = nlohmann::json::array({1.0}); },
       "steps[1].harmonics[0].displacement_m", "must be [re, im]"},
      {[](nlohmann::json& j) { j["steps"][1]["time_s"] = 0.0; }, "steps[1].time_s", "must be an array"},
      {[](nlohmann::json& j) { j["steps"][0]["frequency_hz"] = 1.0; }, "steps[0].frequency_hz", "is not a field"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.field);
    const std::string message = InputErrorOf([&] { PredictionFileFromJson(Damaged(c.damage), "out/p.json"); });
    EXPECT_THAT(message, HasSubstr("out/p.json: field \"" + std::string(c.field) + "\" " + c.problem));
    EXPECT_THAT(message, HasSubstr("Fix: "));
  }
}

TEST(PredictionFile, TheDeclarationHoldsForEveryField) {
  beamid::testing::ExpectDeclarationHolds({
      .fields = PredictionFileFields(),
      .sample = PredictionFileToJson(Filled()),
      .read = [](const std::string& text) { PredictionFileFromJson(text, "x.json"); },
      .rewrite = [](const std::string& text) { return PredictionFileToJson(PredictionFileFromJson(text, "x.json")); },
  });
}

TEST(PredictionFile, AComparisonMustBeWholeAndInTheFilesQuantity) {
  struct Case {
    std::function<void(nlohmann::json&)> damage;
    const char* message;
  };
  const Case cases[] = {
      // measured without its prediction and error
      {[](nlohmann::json& j) {
         j["steps"][0]["harmonics"][0].erase("predicted_velocity_m_s");
         j["steps"][0]["harmonics"][0].erase("relative_error");
       },
       "field \"steps[0].harmonics[0]\" breaks the rule: measured_<q>, predicted_<q> and relative_error are there "
       "together"},
      // another quantity than the file's compared_quantity
      {[](nlohmann::json& j) {
         auto& h = j["steps"][1]["harmonics"][1];
         h["measured_displacement_m"] = h["measured_velocity_m_s"];
         h.erase("measured_velocity_m_s");
       },
       "field \"steps[1].harmonics[1].measured_displacement_m\" is not a field here"},
      {[](nlohmann::json& j) { j["compared_quantity"] = "force_N"; },
       "field \"compared_quantity\" breaks the rule: compared_quantity is displacement_m, velocity_m_s, "
       "acceleration_m_s2 or \"\""},
      {[](nlohmann::json& j) { j["model"] = "duffing"; }, "field \"model\" is \"duffing\", not one of \"hb\", \"ms\""},
      {[](nlohmann::json& j) { j["steps"][0]["harmonics"][2]["displacement_std_m"][1] = -1e-9; },
       "field \"steps[0].harmonics[2].displacement_std_m[1]\" = -1e-09 lies outside ≥ 0"},
      {[](nlohmann::json& j) { j["steps"][0]["harmonics"][2]["k"] = 0; },
       "field \"steps[0].harmonics[2].k\" = 0 lies outside 1 .. 50"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.message);
    EXPECT_THAT(InputErrorOf([&] { PredictionFileFromJson(Damaged(c.damage), "out/p.json"); }),
                HasSubstr("out/p.json: " + std::string(c.message)));
  }
}

}  // namespace
}  // namespace beamid::solver
