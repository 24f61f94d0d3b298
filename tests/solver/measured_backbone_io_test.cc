// The file of `beamid backbone --measured` (solver/backbone/
// measured_backbone_io.h): every field the writer writes reads back to the
// same struct, bit for bit (NaN included), and the text read and written
// again is the same text; a file as beamid wrote it before the struct (keys
// sorted, no struct behind it) reads; a damaged file is refused naming the
// file, the field and the fix.
#include "solver/backbone/measured_backbone_io.h"

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

// Same double: same bits, so that NaN equals NaN and -0 differs from 0.
Estimate Est(double value, double std) { return {.value = value, .std = std, .valid = true}; }

LevelResonance Level(int k) {
  const double s = k + 1.0;
  LevelResonance l;
  l.label = "level_" + std::to_string(k);
  l.control = k == 0 ? LevelControl::kForce : k == 1 ? LevelControl::kResponse : LevelControl::kNeither;
  l.num_points = 17 + k;
  l.num_fit_points = 9 + k;
  l.quadrature_frequency_hz = Est(31.234567890123 * s, 1.1e-3 * s);
  l.quadrature_amplitude_m = Est(2.345678e-4 * s, 3.1e-7 * s);
  l.quadrature_response_amplitude = Est(0.456789 * s, 4.1e-4 * s);
  l.quadrature_force_N = Est(0.5678901 * s, 5.1e-4 * s);
  l.quadrature_damping_ratio = Est(6.789e-3 * s, 7.1e-5 * s);
  l.quadrature_after_jump = k == 1;
  l.quadrature_note = "note " + std::to_string(k);
  l.peak_frequency_hz = Est(31.3 * s, 2.2e-3 * s);
  l.peak_receptance_m_N = Est(4.4e-4 * s, kNaN);  // a std that could not be computed
  l.peak_amplitude_m = k == 2 ? Estimate{} : Est(2.4e-4 * s, 3.3e-7 * s);
  l.half_power_damping_ratio = k == 1 ? Estimate{} : Est(7.7e-3 * s, 8.8e-5 * s);
  l.half_power_note = k == 1 ? "too few steps above half power" : "";
  l.half_power_lower_frequency_hz = k == 1 ? Estimate{} : Est(30.9 * s, 1.5e-3 * s);
  l.half_power_upper_frequency_hz = k == 1 ? Estimate{} : Est(31.7 * s, 1.6e-3 * s);
  l.half_power_natural_frequency_hz = k == 1 ? Estimate{} : Est(31.31 * s, 1.7e-3 * s);
  if (k == 2)
    l.jumps = {{.from_step = 7, .to_step = 8, .from_frequency_hz = 31.5, .to_frequency_hz = 31.6, .up_sweep = false,
                .receptance_ratio = 2.25, .phase_change_rad = 1.25, .miss_over_predicted = 17.5}};
  l.damping_ratio = k == 2 ? Estimate{} : Est(6.8e-3 * s, 9.1e-4 * s);
  l.damping_ratio_note = k == 1 ? "the estimators part" : "";
  l.local_natural_frequency_hz = Est(31.1 * s, 9.9e-4 * s);
  l.local_damping_ratio = Est(6.6e-3 * s, 6.1e-5 * s);
  l.local_reduced_chi_square = 1.0123 * s;
  l.regeneration_relative_rms = 0.0123 * s;
  l.regeneration_max_relative = 0.0345 * s;
  l.regeneration_reduced_chi_square = k == 2 ? kNaN : 0.987 * s;
  // Not the reader's defaults (0, no flags, in the fit), so that a field the writer forgets fails.
  l.regeneration_noise_relative_rms = 0.0021 * s;
  if (k != 0)
    l.flags = {{.kind = LevelFlagKind::kDampingNotPositive, .quantity = "half_power_damping_ratio", .message = "ζ -0.14 %"},
               {.kind = k == 1 ? LevelFlagKind::kPeakOutsideBand : LevelFlagKind::kJump,
                .quantity = "peak_frequency",
                .message = "flag " + std::to_string(k)}};
  l.in_global_fit = k == 0;
  return l;
}

MeasuredBackboneFile Filled() {
  MeasuredBackboneFile f;
  f.beamid_version = "9.8.7";
  f.inputs = {"campaigns/a", "campaigns/b.csv"};
  f.channel = "acc3";
  f.response_quantity = "acceleration";
  for (int k = 0; k < 3; ++k) f.levels.push_back(Level(k));
  auto& fit = f.single_mode_fit;
  fit.form = "power law (alpha 1.5, beta 0.75), A(a)";
  fit.frequency_degree = 2;
  fit.damping_degree = 1;
  fit.frequency_exponent = 1.5;
  fit.damping_exponent = 0.75;
  fit.amplitude_dependent_modal_constant = true;
  fit.residual_receptance_m_N = -1.234e-7;
  fit.reference_amplitude_m = 2.5e-4;
  fit.parameters = {1.1, -2.2, 3.3e-2, 3.9e4, -1.2e3, 0.45, 0.067};
  fit.reduced_chi_square = 1.0456;
  fit.candidates = {{.frequency_degree = 1,
                     .damping_degree = 0,
                     .aicc = 123.25,
                     .reduced_chi_square = 1.5,
                     .frequency_exponent = 0.0,
                     .damping_exponent = 0.0,
                     .amplitude_dependent_modal_constant = false,
                     .form = "polynomial P=1 Q=0"},
                    {.frequency_degree = 2,
                     .damping_degree = 1,
                     .aicc = 99.125,
                     .reduced_chi_square = 1.0456,
                     .frequency_exponent = 1.5,
                     .damping_exponent = 0.75,
                     .amplitude_dependent_modal_constant = true,
                     .form = "power law"}};
  for (int k = 0; k < 3; ++k)
    fit.curve.push_back({.amplitude_m = 1e-4 * (k + 1),
                         .frequency_hz = 31.0 + 0.1 * k,
                         .frequency_std_hz = 1e-3 * (k + 2),
                         .damping_ratio = 6e-3 + 1e-4 * k,
                         .damping_ratio_std = 5e-5 * (k + 3)});
  f.damping_trend = {.amplitude_m = 3.3e-4,
                     .slope_per_m = 4.4,
                     .slope_std_per_m = 0.55,
                     .z = 8.0,
                     .damping_rate_slope_per_s_m = 1.5e3,
                     .damping_rate_slope_std_per_s_m = 7.5e2,
                     .damping_rate_z = 2.0,
                     .verdict = Trend::kNone,
                     .damping_ratio_verdict = Trend::kRises};
  f.model_backbone = {{.amplitude_m = 1e-5, .frequency_hz = 31.5}, {.amplitude_m = 2e-5, .frequency_hz = kNaN}};
  f.warnings = {"first warning", "second warning"};
  return f;
}

void ExpectSameEstimate(const Estimate& a, const Estimate& b, const std::string& what) {
  SCOPED_TRACE(what);
  EXPECT_EQ(a.valid, b.valid);
  EXPECT_TRUE(Same(a.value, b.value));
  EXPECT_TRUE(Same(a.std, b.std));
}

void ExpectSame(const MeasuredBackboneFile& a, const MeasuredBackboneFile& b) {
  EXPECT_EQ(a.beamid_version, b.beamid_version);
  EXPECT_EQ(a.inputs, b.inputs);
  EXPECT_EQ(a.channel, b.channel);
  EXPECT_EQ(a.response_quantity, b.response_quantity);
  ASSERT_EQ(a.levels.size(), b.levels.size());
  for (std::size_t i = 0; i < a.levels.size(); ++i) {
    SCOPED_TRACE("level " + std::to_string(i));
    const auto& x = a.levels[i];
    const auto& y = b.levels[i];
    EXPECT_EQ(x.label, y.label);
    EXPECT_EQ(x.control, y.control);
    EXPECT_EQ(x.num_points, y.num_points);
    EXPECT_EQ(x.num_fit_points, y.num_fit_points);
    ExpectSameEstimate(x.quadrature_frequency_hz, y.quadrature_frequency_hz, "quadrature_frequency_hz");
    ExpectSameEstimate(x.quadrature_amplitude_m, y.quadrature_amplitude_m, "quadrature_amplitude_m");
    ExpectSameEstimate(x.quadrature_response_amplitude, y.quadrature_response_amplitude, "response_amplitude");
    ExpectSameEstimate(x.quadrature_force_N, y.quadrature_force_N, "quadrature_force_N");
    ExpectSameEstimate(x.quadrature_damping_ratio, y.quadrature_damping_ratio, "quadrature_damping_ratio");
    EXPECT_EQ(x.quadrature_after_jump, y.quadrature_after_jump);
    EXPECT_EQ(x.quadrature_note, y.quadrature_note);
    ExpectSameEstimate(x.peak_frequency_hz, y.peak_frequency_hz, "peak_frequency_hz");
    ExpectSameEstimate(x.peak_receptance_m_N, y.peak_receptance_m_N, "peak_receptance_m_N");
    ExpectSameEstimate(x.peak_amplitude_m, y.peak_amplitude_m, "peak_amplitude_m");
    ExpectSameEstimate(x.half_power_damping_ratio, y.half_power_damping_ratio, "half_power_damping_ratio");
    EXPECT_EQ(x.half_power_note, y.half_power_note);
    ExpectSameEstimate(x.half_power_lower_frequency_hz, y.half_power_lower_frequency_hz, "half_power_lower");
    ExpectSameEstimate(x.half_power_upper_frequency_hz, y.half_power_upper_frequency_hz, "half_power_upper");
    ExpectSameEstimate(x.half_power_natural_frequency_hz, y.half_power_natural_frequency_hz, "half_power_natural");
    ASSERT_EQ(x.jumps.size(), y.jumps.size());
    for (std::size_t k = 0; k < x.jumps.size(); ++k) {
      EXPECT_EQ(x.jumps[k].from_step, y.jumps[k].from_step);
      EXPECT_EQ(x.jumps[k].to_step, y.jumps[k].to_step);
      EXPECT_TRUE(Same(x.jumps[k].from_frequency_hz, y.jumps[k].from_frequency_hz));
      EXPECT_TRUE(Same(x.jumps[k].to_frequency_hz, y.jumps[k].to_frequency_hz));
      EXPECT_EQ(x.jumps[k].up_sweep, y.jumps[k].up_sweep);
      EXPECT_TRUE(Same(x.jumps[k].receptance_ratio, y.jumps[k].receptance_ratio));
      EXPECT_TRUE(Same(x.jumps[k].phase_change_rad, y.jumps[k].phase_change_rad));
      EXPECT_TRUE(Same(x.jumps[k].miss_over_predicted, y.jumps[k].miss_over_predicted));
    }
    ExpectSameEstimate(x.damping_ratio, y.damping_ratio, "damping_ratio");
    EXPECT_EQ(x.damping_ratio_note, y.damping_ratio_note);
    ExpectSameEstimate(x.local_natural_frequency_hz, y.local_natural_frequency_hz, "local_natural_frequency_hz");
    ExpectSameEstimate(x.local_damping_ratio, y.local_damping_ratio, "local_damping_ratio");
    EXPECT_TRUE(Same(x.local_reduced_chi_square, y.local_reduced_chi_square));
    EXPECT_TRUE(Same(x.regeneration_relative_rms, y.regeneration_relative_rms));
    EXPECT_TRUE(Same(x.regeneration_max_relative, y.regeneration_max_relative));
    EXPECT_TRUE(Same(x.regeneration_reduced_chi_square, y.regeneration_reduced_chi_square));
    EXPECT_TRUE(Same(x.regeneration_noise_relative_rms, y.regeneration_noise_relative_rms));
    ASSERT_EQ(x.flags.size(), y.flags.size());
    for (std::size_t k = 0; k < x.flags.size(); ++k) {
      EXPECT_EQ(x.flags[k].kind, y.flags[k].kind);
      EXPECT_EQ(x.flags[k].quantity, y.flags[k].quantity);
      EXPECT_EQ(x.flags[k].message, y.flags[k].message);
    }
    EXPECT_EQ(x.in_global_fit, y.in_global_fit);
  }
  const auto& f = a.single_mode_fit;
  const auto& g = b.single_mode_fit;
  EXPECT_EQ(f.form, g.form);
  EXPECT_EQ(f.frequency_degree, g.frequency_degree);
  EXPECT_EQ(f.damping_degree, g.damping_degree);
  EXPECT_TRUE(Same(f.frequency_exponent, g.frequency_exponent));
  EXPECT_TRUE(Same(f.damping_exponent, g.damping_exponent));
  EXPECT_EQ(f.amplitude_dependent_modal_constant, g.amplitude_dependent_modal_constant);
  EXPECT_TRUE(Same(f.residual_receptance_m_N, g.residual_receptance_m_N));
  EXPECT_TRUE(Same(f.reference_amplitude_m, g.reference_amplitude_m));
  ASSERT_EQ(f.parameters.size(), g.parameters.size());
  for (std::size_t i = 0; i < f.parameters.size(); ++i) EXPECT_TRUE(Same(f.parameters[i], g.parameters[i]));
  EXPECT_TRUE(Same(f.reduced_chi_square, g.reduced_chi_square));
  ASSERT_EQ(f.candidates.size(), g.candidates.size());
  for (std::size_t i = 0; i < f.candidates.size(); ++i) {
    const auto& x = f.candidates[i];
    const auto& y = g.candidates[i];
    EXPECT_EQ(x.form, y.form);
    EXPECT_EQ(x.frequency_degree, y.frequency_degree);
    EXPECT_EQ(x.damping_degree, y.damping_degree);
    EXPECT_TRUE(Same(x.frequency_exponent, y.frequency_exponent));
    EXPECT_TRUE(Same(x.damping_exponent, y.damping_exponent));
    EXPECT_EQ(x.amplitude_dependent_modal_constant, y.amplitude_dependent_modal_constant);
    EXPECT_TRUE(Same(x.aicc, y.aicc));
    EXPECT_TRUE(Same(x.reduced_chi_square, y.reduced_chi_square));
  }
  ASSERT_EQ(f.curve.size(), g.curve.size());
  for (std::size_t i = 0; i < f.curve.size(); ++i) {
    EXPECT_TRUE(Same(f.curve[i].amplitude_m, g.curve[i].amplitude_m));
    EXPECT_TRUE(Same(f.curve[i].frequency_hz, g.curve[i].frequency_hz));
    EXPECT_TRUE(Same(f.curve[i].frequency_std_hz, g.curve[i].frequency_std_hz));
    EXPECT_TRUE(Same(f.curve[i].damping_ratio, g.curve[i].damping_ratio));
    EXPECT_TRUE(Same(f.curve[i].damping_ratio_std, g.curve[i].damping_ratio_std));
  }
  EXPECT_TRUE(Same(a.damping_trend.amplitude_m, b.damping_trend.amplitude_m));
  EXPECT_TRUE(Same(a.damping_trend.slope_per_m, b.damping_trend.slope_per_m));
  EXPECT_TRUE(Same(a.damping_trend.slope_std_per_m, b.damping_trend.slope_std_per_m));
  EXPECT_TRUE(Same(a.damping_trend.z, b.damping_trend.z));
  EXPECT_EQ(a.damping_trend.verdict, b.damping_trend.verdict);
  EXPECT_TRUE(Same(a.damping_trend.damping_rate_slope_per_s_m, b.damping_trend.damping_rate_slope_per_s_m));
  EXPECT_TRUE(Same(a.damping_trend.damping_rate_slope_std_per_s_m, b.damping_trend.damping_rate_slope_std_per_s_m));
  EXPECT_TRUE(Same(a.damping_trend.damping_rate_z, b.damping_trend.damping_rate_z));
  EXPECT_EQ(a.damping_trend.damping_ratio_verdict, b.damping_trend.damping_ratio_verdict);
  ASSERT_EQ(a.model_backbone.size(), b.model_backbone.size());
  for (std::size_t i = 0; i < a.model_backbone.size(); ++i) {
    EXPECT_TRUE(Same(a.model_backbone[i].amplitude_m, b.model_backbone[i].amplitude_m));
    EXPECT_TRUE(Same(a.model_backbone[i].frequency_hz, b.model_backbone[i].frequency_hz));
  }
  EXPECT_EQ(a.warnings, b.warnings);
}

TEST(MeasuredBackboneFile, EveryFieldSurvivesTheTextAndBackAndTheTextIsStable) {
  const MeasuredBackboneFile original = Filled();
  const std::string text = MeasuredBackboneFileToJson(original);
  const MeasuredBackboneFile read = MeasuredBackboneFileFromJson(text, "b.json");
  ExpectSame(original, read);
  EXPECT_EQ(MeasuredBackboneFileToJson(read), text);
  EXPECT_THAT(text, HasSubstr("\"format\": \"beamid-measured-backbone/1\""));
  EXPECT_THAT(text, HasSubstr("\"beamid_version\": \"9.8.7\""));
  EXPECT_THAT(text, HasSubstr("\"frequency_Hz\": null"));  // NaN of the model backbone
  EXPECT_THAT(text, HasSubstr("\"displacement_amplitude_m\": null"));  // an estimate not made
}

TEST(MeasuredBackboneFile, WrittenFileReadsBack) {
  const std::filesystem::path path = testing::UniqueTempPath("backbone.json");
  WriteMeasuredBackboneFile(path, Filled());
  ExpectSame(Filled(), ReadMeasuredBackboneFile(path));
  std::filesystem::remove(path);
  const std::string message = InputErrorOf([&] { ReadMeasuredBackboneFile(path); });
  EXPECT_THAT(message, HasSubstr(path.string()));
  EXPECT_THAT(message, HasSubstr("measured backbone file"));
}

// As the inline writer of `beamid backbone --measured` wrote it before the
// struct: keys sorted, no beamid_version (the oldest files).
constexpr const char* kEarlierFile = R"({
 "amplitude": "first-harmonic displacement amplitude at the sensor [m]",
 "channel": "acc3",
 "damping_trend": {"amplitude_m": 0.0003, "slope_per_m": 2.5, "slope_std_per_m": 1.25, "verdict": "no significant trend", "z": 2.0},
 "format": "beamid-measured-backbone/1",
 "inputs": ["camp"],
 "levels": [
  {"control": "force", "half_power": {"damping_ratio": null, "note": "no half-power points"},
   "label": "low",
   "local_fit": {"damping_ratio": {"std": 0.0001, "value": 0.005}, "natural_frequency_Hz": {"std": 0.01, "value": 30.5}, "reduced_chi_square": 1.1},
   "num_fit_points": 3, "num_points": 5,
   "peak": {"displacement_amplitude_m": {"std": 1e-06, "value": 0.0002}, "frequency_Hz": {"std": 0.02, "value": 30.6}, "receptance_m_N": null},
   "phase_resonance": {"after_jump": false, "damping_ratio": {"std": 0.0002, "value": 0.0051}, "displacement_amplitude_m": {"std": 2e-06, "value": 0.00021},
     "force_N": {"std": 0.001, "value": 0.1}, "frequency_Hz": {"std": 0.03, "value": 30.55}, "note": "", "response_amplitude": {"std": 0.01, "value": 7.7}},
   "regeneration": {"max_relative": 0.02, "reduced_chi_square": null, "relative_rms": 0.01}}
 ],
 "model_backbone": [{"amplitude_m": 1e-05, "frequency_Hz": 31.0}],
 "response_quantity": "acceleration",
 "single_mode_fit": {
  "amplitude_dependent_modal_constant": false,
  "candidates": [{"aicc": 12.5, "amplitude_dependent_modal_constant": false, "damping_degree": 0, "damping_exponent": 0.0, "form": "P=1 Q=0", "frequency_degree": 1, "frequency_exponent": 0.0, "reduced_chi_square": 1.2}],
  "curve": [{"amplitude_m": 0.0002, "damping_ratio": 0.005, "damping_ratio_std": 0.0001, "frequency_Hz": 30.5, "frequency_std_Hz": 0.01}],
  "damping_degree": 0, "damping_exponent": 0.0, "form": "P=1 Q=0", "frequency_degree": 1, "frequency_exponent": 0.0,
  "model": "any description", "parameter_order": "Re A0, Im A0, [A2], wn^2 terms, zeta*wn terms",
  "parameters": [1.0, 0.0, 36000.0, 1500.0, 1.9],
  "reduced_chi_square": 1.2, "reference_amplitude_m": 0.0002, "residual_receptance_m_N": 0.0
 },
 "warnings": []
})";

TEST(MeasuredBackboneFile, AFileInTheEarlierLayoutReads) {
  const MeasuredBackboneFile f = MeasuredBackboneFileFromJson(kEarlierFile, "old.json");
  EXPECT_EQ(f.beamid_version, "");
  EXPECT_EQ(f.inputs, std::vector<std::string>{"camp"});
  EXPECT_EQ(f.channel, "acc3");
  ASSERT_EQ(f.levels.size(), 1u);
  const LevelResonance& l = f.levels[0];
  EXPECT_EQ(l.label, "low");
  EXPECT_EQ(l.control, LevelControl::kForce);
  EXPECT_EQ(l.num_points, 5);
  EXPECT_TRUE(l.quadrature_frequency_hz.valid);
  EXPECT_EQ(l.quadrature_frequency_hz.value, 30.55);
  EXPECT_EQ(l.quadrature_response_amplitude.value, 7.7);
  EXPECT_FALSE(l.peak_receptance_m_N.valid);
  EXPECT_FALSE(l.half_power_damping_ratio.valid);
  EXPECT_EQ(l.half_power_note, "no half-power points");
  EXPECT_TRUE(std::isnan(l.regeneration_reduced_chi_square));
  // Before the flags: none, in the fit, no noise figure.
  EXPECT_TRUE(l.flags.empty());
  EXPECT_TRUE(l.in_global_fit);
  EXPECT_EQ(l.regeneration_noise_relative_rms, 0.0);
  EXPECT_EQ(f.single_mode_fit.parameters.size(), 5u);
  EXPECT_EQ(f.single_mode_fit.parameters[2], 36000.0);
  ASSERT_EQ(f.single_mode_fit.curve.size(), 1u);
  EXPECT_EQ(f.single_mode_fit.curve[0].frequency_std_hz, 0.01);
  // Before the damping rate, the one verdict was on ζ: the damping rate is not judged.
  EXPECT_EQ(f.damping_trend.verdict, Trend::kNotJudged);
  EXPECT_EQ(f.damping_trend.damping_ratio_verdict, Trend::kNone);
  ASSERT_EQ(f.model_backbone.size(), 1u);
  EXPECT_EQ(f.model_backbone[0].frequency_hz, 31.0);
}

// The text of Filled() with one change.
std::string Damaged(const std::function<void(nlohmann::json&)>& damage) {
  nlohmann::json j = nlohmann::json::parse(MeasuredBackboneFileToJson(Filled()));
  damage(j);
  return j.dump();
}

TEST(MeasuredBackboneFile, AMissingFieldIsRefusedNamingTheFileAndTheField) {
  const std::string message = InputErrorOf([] {
    MeasuredBackboneFileFromJson(Damaged([](nlohmann::json& j) { j["levels"][1]["peak"].erase("frequency_Hz"); }),
                                 "out/b.json");
  });
  EXPECT_THAT(message, HasSubstr("out/b.json: field \"levels[1].peak.frequency_Hz\" is missing"));
  EXPECT_THAT(message, HasSubstr("Fix: "));
  const std::string trend = InputErrorOf([] {
    MeasuredBackboneFileFromJson(Damaged([](nlohmann::json& j) { j.erase("damping_trend"); }), "out/b.json");
  });
  EXPECT_THAT(trend, HasSubstr("out/b.json: field \"damping_trend\" is missing"));
}

TEST(MeasuredBackboneFile, AWrongFormatIsRefusedNamingTheFile) {
  const std::string message = InputErrorOf([] {
    MeasuredBackboneFileFromJson(Damaged([](nlohmann::json& j) { j["format"] = "beamid-result/1"; }), "r.json");
  });
  EXPECT_THAT(message, HasSubstr("r.json: field \"format\" is \"beamid-result/1\""));
  EXPECT_THAT(message, HasSubstr("Fix: "));
  EXPECT_THAT(InputErrorOf([] { MeasuredBackboneFileFromJson("[1, 2]", "list.json"); }), HasSubstr("list.json: not a"));
  EXPECT_THAT(InputErrorOf([] { MeasuredBackboneFileFromJson("{\"format\": ", "cut.json"); }),
              HasSubstr("cut.json: not valid JSON"));
}

TEST(MeasuredBackboneFile, AFieldOfTheWrongTypeIsRefusedNamingTheFileAndTheField) {
  struct Case {
    std::function<void(nlohmann::json&)> damage;
    const char* field;
    const char* problem;
  };
  const Case cases[] = {
      {[](nlohmann::json& j) { j["single_mode_fit"]["frequency_degree"] = "two"; },
       "single_mode_fit.frequency_degree", "must be an integer"},
      {[](nlohmann::json& j) { j["levels"][0]["phase_resonance"]["force_N"] = 3.0; }, "levels[0].phase_resonance.force_N",
       "must be an object"},
      {[](nlohmann::json& j) { j["levels"][2]["control"] = "voltage"; }, "levels[2].control", "is \"voltage\""},
      {[](nlohmann::json& j) { j["single_mode_fit"]["curve"][1]["damping_ratio"] = true; },
       "single_mode_fit.curve[1].damping_ratio", "must be a number"},
      {[](nlohmann::json& j) { j["warnings"] = "none"; }, "warnings", "must be an array"},
      {[](nlohmann::json& j) { j["damping_trend"]["slope"] = 1.0; }, "damping_trend.slope", "is not a field"},
      {[](nlohmann::json& j) { j["levels"][1]["flags"][0]["kind"] = "odd"; }, "levels[1].flags[0].kind", "is \"odd\""},
      {[](nlohmann::json& j) { j["levels"][1]["flags"][1].erase("message"); }, "levels[1].flags[1].message",
       "is missing"},
      {[](nlohmann::json& j) { j["levels"][0]["in_global_fit"] = 1; }, "levels[0].in_global_fit", "must be true or false"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.field);
    const std::string message = InputErrorOf([&] { MeasuredBackboneFileFromJson(Damaged(c.damage), "out/b.json"); });
    EXPECT_THAT(message, HasSubstr("out/b.json: field \"" + std::string(c.field) + "\" " + c.problem));
    EXPECT_THAT(message, HasSubstr("Fix: "));
  }
}

TEST(MeasuredBackboneFile, TheDeclarationHoldsForEveryField) {
  // The checks damage the first level: it gets the jumps and flags of the others.
  MeasuredBackboneFile sample = Filled();
  sample.levels[0].jumps = sample.levels[2].jumps;
  sample.levels[0].flags = sample.levels[1].flags;
  beamid::testing::ExpectDeclarationHolds({
      .fields = MeasuredBackboneFileFields(),
      .sample = MeasuredBackboneFileToJson(sample),
      .read = [](const std::string& text) { MeasuredBackboneFileFromJson(text, "x.json"); },
      .rewrite = [](const std::string& text) {
        return MeasuredBackboneFileToJson(MeasuredBackboneFileFromJson(text, "x.json"));
      },
  });
}

}  // namespace
}  // namespace beamid::solver
