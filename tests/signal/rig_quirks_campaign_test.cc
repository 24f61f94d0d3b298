// Campaigns with the quirks of real rigs, simulated by the independent
// time-domain simulator (hb/stepped_sine.h, docs/simulator.md) and
// extracted: the response phasors lie within 3σ of the simulator's
// noise-free truth (as transfer ratios to the excitation channel, which is
// what a test measures), and each quirk is said:
//  - the shaker stopping at 80 % of each record: cut, with a warning;
//  - 2 % amplitude creep over each record: "steady with drift" (the truth is
//    then the creep line's mean over the part analysed);
//  - 1/f drift on every sensor: no transient taken for it;
//  - a quiet accelerometer near the clamp read by a 12-bit converter on a
//    ±500 m/s² range: quantisation, no dropout, and the quantisation error
//    in its uncertainty;
//  - and a clean campaign: no note, no warning.
//  - a voltage drive whose amplifier sags near resonance: phasors per volt;
//  - base excitation: absolute accelerations per base acceleration.
#include <complex>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/LU>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hb/scenario.h"
#include "hb/stepped_sine.h"
#include "signal/phasor_set.h"
#include "tests/support/simulated_campaign.h"

namespace beamid::signal {
namespace {

using nlohmann::json;

json BaseScenario() {
  return json::parse(R"({
  "beam": {"length_m": 0.6, "width_m": 0.04, "thickness_m": 0.005, "youngs_modulus_Pa": 2.1e11,
           "density_kg_m3": 7850, "loss_factor": 0.0002},
  "support": {"polynomial": {"k1_Nm_rad": 150, "k3_Nm_rad3": 3e5, "c_Nms_rad": 0.05}},
  "excitation": {"channel": "force", "position_m": 0.57},
  "sensors": [{"channel": "acc1", "position_m": 0.1, "unit": "m/s^2"},
              {"channel": "acc2", "position_m": 0.3, "unit": "m/s^2"},
              {"channel": "acc3", "position_m": 0.57, "unit": "m/s^2"}],
  "levels": [{"label": "mid", "force_amplitude_N": 2.0, "frequencies_Hz": [53.5, 54.0, 54.5]}],
  "timing": {"sample_rate_Hz": 5120, "settle_min_s": 0.2, "settle_max_s": 12.0, "settle_tolerance": 1e-5,
             "transient_s": 0.05, "record_s": 0.5},
  "noise": {"seed": 7, "clock_offset_ppm": 25,
            "default": {"relative_rms": 0.003, "absolute": 0.002},
            "channels": {"force": {"relative_rms": 0.002, "absolute": 0.002}}}
})");
}

struct Extracted {
  std::vector<hb::SimulatedStep> truth;
  PhasorSet phasors;
};

Extracted SimulateAndExtract(const json& scenario_json, const std::string& name) {
  const hb::Scenario scenario = hb::ParseScenario(scenario_json.dump(), name + ".json");
  Extracted out{.truth = beamid::testing::SimulateSteps(scenario), .phasors = {}};
  const auto extracted = beamid::testing::WriteAndExtract(scenario, out.truth, scenario.seed, "beamid_rig_" + name);
  out.phasors = extracted.phasors;
  std::filesystem::remove_all(extracted.folder);
  return out;
}

bool Mentions(const std::vector<std::string>& lines, const std::string& text) {
  for (const auto& line : lines)
    if (line.find(text) != std::string::npos) return true;
  return false;
}

// Every sensor's fundamental against the truth scaled by truth_scale(step),
// in standard uncertainties (Mahalanobis, 2 degrees of freedom: 3σ ⇔ 9·2).
void ExpectWithinThreeSigma(const Extracted& e, const std::function<double(const StepPhasors&)>& truth_scale = {}) {
  ASSERT_EQ(e.phasors.steps.size(), e.truth.size());
  for (std::size_t s = 0; s < e.truth.size(); ++s) {
    const hb::SimulatedStep& truth = e.truth[s];
    const StepPhasors& step = e.phasors.steps[s];
    const std::complex<double> excitation = truth.channel_phasors[0](1);
    const double scale = truth_scale ? truth_scale(step) : 1.0;
    for (std::size_t c = 0; c < step.responses.size(); ++c) {
      const std::complex<double> expected =
          scale * truth.channel_phasors[c + 1](1) * std::conj(excitation) / std::abs(excitation);
      const HarmonicPhasor& h = step.responses[c].Harmonic(1);
      const Eigen::Vector2d error(h.value.real() - expected.real(), h.value.imag() - expected.imag());
      const double mahalanobis = error.dot(h.Covariance().inverse() * error);
      EXPECT_LT(mahalanobis, 2.0 * 9.0) << step.file << " " << step.responses[c].channel << ": " << h.value
                                        << " vs " << expected << " ± " << h.std_real;
    }
  }
}

TEST(RigQuirksCampaign, ACleanCampaignIsWithinThreeSigmaWithoutANoteOrWarning) {
  const Extracted e = SimulateAndExtract(BaseScenario(), "clean");
  for (const auto& step : e.phasors.steps) {
    EXPECT_TRUE(step.quality.warnings.empty()) << step.file << ": " << step.quality.warnings.front();
    EXPECT_TRUE(step.quality.notes.empty()) << step.file << ": " << step.quality.notes.front();
  }
  ExpectWithinThreeSigma(e);
}

TEST(RigQuirksCampaign, AShakerStoppingInsideTheRecordIsCutAndSaid) {
  json scenario = BaseScenario();
  scenario["timing"]["excitation_stop_fraction"] = 0.8;
  const Extracted e = SimulateAndExtract(scenario, "stop");
  for (const auto& step : e.phasors.steps) {
    EXPECT_TRUE(Mentions(step.quality.warnings, "the excitation stops before the end of the record")) << step.file;
    EXPECT_GT(step.quality.snr_db, 30.0) << step.file;
  }
  ExpectWithinThreeSigma(e);
}

TEST(RigQuirksCampaign, AmplitudeCreepIsASteadyStateWithDrift) {
  constexpr double kCreep = 0.02, kSteadyStart_s = 0.05, kRecord_s = 0.5;
  json scenario = BaseScenario();
  scenario["noise"]["amplitude_creep_relative"] = kCreep;
  const Extracted e = SimulateAndExtract(scenario, "creep");
  for (const auto& step : e.phasors.steps)
    EXPECT_TRUE(Mentions(step.quality.notes, "steady with drift")) << step.file << ": " << step.quality.settling;
  // The creep line's mean over what was analysed.
  ExpectWithinThreeSigma(e, [&](const StepPhasors& step) {
    const double middle_s = step.quality.settled_after_s + 0.5 * step.quality.analysed_duration_s;
    return 1.0 + kCreep * ((middle_s - kSteadyStart_s) / kRecord_s - 0.5);
  });
}

TEST(RigQuirksCampaign, LowFrequencyDriftIsNoTransient) {
  json scenario = BaseScenario();
  scenario["noise"]["default"]["pink_rms"] = 0.05;
  const Extracted e = SimulateAndExtract(scenario, "pink");
  for (const auto& step : e.phasors.steps) EXPECT_LT(step.quality.settled_after_s, 0.1) << step.quality.settling;
  ExpectWithinThreeSigma(e);
}

TEST(RigQuirksCampaign, AQuietQuantisedAccelerometerIsNoDropout) {
  json scenario = BaseScenario();
  scenario["sensors"].push_back({{"channel", "acc0"}, {"position_m", 0.02}, {"unit", "m/s^2"}});
  scenario["noise"]["channels"]["acc0"] = {{"relative_rms", 0.0}, {"absolute", 0.0}, {"adc_bits", 12}, {"adc_range", 500.0}};
  const Extracted e = SimulateAndExtract(scenario, "quantised");
  for (const auto& step : e.phasors.steps) {
    for (const auto& warning : step.quality.warnings) EXPECT_EQ(warning.find("dropout"), std::string::npos) << warning;
    // A few steps of the converter: said, and in the uncertainty (a bias
    // of 0.1 step here, 60σ of the noise alone).
    EXPECT_TRUE(Mentions(step.quality.warnings, "channel 'acc0' spans only")) << step.file;
  }
  ExpectWithinThreeSigma(e);
}

TEST(RigQuirksCampaign, AVoltageDriveGivesPhasorsPerVolt) {
  json scenario = BaseScenario();
  scenario["excitation"] = {{"channel", "drive"}, {"position_m", 0.57}, {"quantity", "voltage"},
                            {"amplifier_gain_N_per_V", 10.0}, {"amplifier_sag", 0.3}};
  scenario["levels"][0].erase("force_amplitude_N");
  scenario["levels"][0]["voltage_amplitude_V"] = 0.2;
  scenario["noise"]["channels"] = {{"drive", {{"relative_rms", 0.002}, {"absolute", 1e-4}}}};
  const Extracted e = SimulateAndExtract(scenario, "voltage");
  for (const auto& step : e.phasors.steps) EXPECT_EQ(step.force.quantity, Quantity::kVoltage);
  ExpectWithinThreeSigma(e);
}

TEST(RigQuirksCampaign, BaseExcitationGivesPhasorsPerBaseAcceleration) {
  json scenario = BaseScenario();
  scenario["excitation"] = {{"channel", "base"}, {"quantity", "base_acceleration"}};
  scenario["levels"][0].erase("force_amplitude_N");
  scenario["levels"][0]["base_acceleration_amplitude_m_s2"] = 1.0;
  scenario["noise"]["channels"] = {{"base", {{"relative_rms", 0.002}, {"absolute", 1e-3}}}};
  const Extracted e = SimulateAndExtract(scenario, "base");
  for (const auto& step : e.phasors.steps) EXPECT_EQ(step.force.quantity, Quantity::kBaseAcceleration);
  ExpectWithinThreeSigma(e);
}

}  // namespace
}  // namespace beamid::signal
