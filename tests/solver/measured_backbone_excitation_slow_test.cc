// The measured backbone of a test driven by something other than a force,
// from the independent simulator (docs/simulator.md):
//  - a voltage drive through an amplifier of constant gain gives the same
//    natural frequency and damping ratio as the force drive of the same rig
//    (within their σ), labelled per volt, with the caveat that a sagging
//    amplifier would bias them;
//  - a base excitation is analysed on the motion relative to the base per
//    −a_b: the natural frequency of the lowest level is the structure's
//    (within its σ of the force-driven one) and the phase runs the
//    receptance's way (no phase-convention flag).
// A slow test although it takes seconds: the simulator's settling runs 30x
// longer under AddressSanitizer (2 minutes a test), and the backbone's code
// runs there in the other measured-backbone tests.
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hb/errors.h"
#include "hb/scenario.h"
#include "signal/first_harmonic_level.h"
#include "solver/backbone/measured_backbone.h"
#include "solver/backbone/measured_backbone_io.h"
#include "tests/support/simulated_campaign.h"

namespace beamid::solver {
namespace {

using nlohmann::json;

json Scenario() {
  return json::parse(R"({
  "beam": {"length_m": 0.6, "width_m": 0.04, "thickness_m": 0.005, "youngs_modulus_Pa": 2.1e11,
           "density_kg_m3": 7850, "loss_factor": 0.0002},
  "support": {"polynomial": {"k1_Nm_rad": 150, "k3_Nm_rad3": 3e5, "c_Nms_rad": 0.05}},
  "excitation": {"channel": "force", "position_m": 0.57},
  "sensors": [{"channel": "acc3", "position_m": 0.57, "unit": "m/s^2"}],
  "levels": [{"label": "low", "force_amplitude_N": 0.02,
              "frequencies_Hz": {"start": 52.4, "stop": 54.8, "step": 0.2}},
             {"label": "mid", "force_amplitude_N": 0.06,
              "frequencies_Hz": {"start": 52.4, "stop": 54.8, "step": 0.2}}],
  "timing": {"sample_rate_Hz": 5120, "settle_min_s": 0.2, "settle_max_s": 12.0, "settle_tolerance": 1e-5,
             "transient_s": 0.05, "record_s": 0.5},
  "noise": {"seed": 3, "default": {"relative_rms": 0.002, "absolute": 0.0002},
            "channels": {"force": {"relative_rms": 0.002, "absolute": 0.00005}}}
})");
}

MeasuredBackbone Analyse(const json& scenario_json, const std::string& name) {
  const hb::Scenario scenario = hb::ParseScenario(scenario_json.dump(), name);
  const auto extracted = beamid::testing::WriteAndExtract(scenario, beamid::testing::SimulateSteps(scenario),
                                                          scenario.seed, "beamid_bb_" + name);
  std::filesystem::remove_all(extracted.folder);
  return AnalyseMeasuredBackbone(signal::FirstHarmonicLevels(extracted.phasors, "acc3", name));
}

bool Flagged(const LevelResonance& level, LevelFlagKind kind) {
  for (const auto& flag : level.flags)
    if (flag.kind == kind) return true;
  return false;
}

void ExpectSameWithinSigma(const Estimate& a, const Estimate& b, const std::string& what) {
  ASSERT_TRUE(a.valid && b.valid) << what;
  EXPECT_LT(std::abs(a.value - b.value), 3.0 * std::hypot(a.std, b.std)) << what << ": " << a.value << " ± " << a.std
                                                                          << " vs " << b.value << " ± " << b.std;
}

TEST(MeasuredBackboneExcitation, AVoltageDriveGivesTheForceDrivesNumbersLabelledPerVolt) {
  const MeasuredBackbone force = Analyse(Scenario(), "force");
  json voltage = Scenario();
  voltage["excitation"] = {{"channel", "drive"}, {"position_m", 0.57}, {"quantity", "voltage"},
                           {"amplifier_gain_N_per_V", 4.0}};
  voltage["levels"][0].erase("force_amplitude_N");
  voltage["levels"][0]["voltage_amplitude_V"] = 0.005;
  voltage["levels"][1].erase("force_amplitude_N");
  voltage["levels"][1]["voltage_amplitude_V"] = 0.015;
  voltage["noise"]["channels"] = {{"drive", {{"relative_rms", 0.002}, {"absolute", 0.0000125}}}};
  const MeasuredBackbone per_volt = Analyse(voltage, "voltage");
  EXPECT_EQ(force.excitation_quantity, "force");
  EXPECT_EQ(per_volt.excitation_quantity, "voltage");
  for (std::size_t l = 0; l < 2; ++l) {
    ExpectSameWithinSigma(per_volt.levels[l].quadrature_frequency_hz, force.levels[l].quadrature_frequency_hz, "f_n");
    ExpectSameWithinSigma(per_volt.levels[l].damping_ratio, force.levels[l].damping_ratio, "ζ");
  }
  MeasuredBackboneFile file;
  file.channel = "acc";  // the reader refuses an unnamed channel and quantity
  file.response_quantity = "acceleration";
  file.excitation_quantity = per_volt.excitation_quantity;
  const std::string text = MeasuredBackboneFileToJson(file);
  EXPECT_NE(text.find("displacement per drive voltage [m/V]"), std::string::npos);
  EXPECT_EQ(MeasuredBackboneFileFromJson(text, "bb.json").excitation_quantity, "voltage");
  EXPECT_NE(LabelsOf("voltage").caveat.find("biases f_n and ζ"), std::string::npos);
  EXPECT_EQ(LabelsOf("voltage").column, "voltage_V");
}

TEST(MeasuredBackboneExcitation, ABaseExcitationIsAnalysedRelativeToTheBase) {
  const MeasuredBackbone force = Analyse(Scenario(), "force");
  json base = Scenario();
  base["excitation"] = {{"channel", "base"}, {"quantity", "base_acceleration"}};
  base["levels"][0].erase("force_amplitude_N");
  base["levels"][0]["base_acceleration_amplitude_m_s2"] = 0.02;
  base["levels"][1].erase("force_amplitude_N");
  base["levels"][1]["base_acceleration_amplitude_m_s2"] = 0.06;
  base["noise"]["channels"] = {{"base", {{"relative_rms", 0.002}, {"absolute", 0.00005}}}};
  const MeasuredBackbone relative = Analyse(base, "base");
  EXPECT_EQ(relative.excitation_quantity, "base_acceleration");
  for (const auto& level : relative.levels) {
    EXPECT_FALSE(Flagged(level, LevelFlagKind::kPhaseConvention)) << level.label;
    EXPECT_GT(level.damping_ratio.value, 0.0) << level.label;
  }
  // The lowest levels of both (0.02 N, 0.02 m/s²) are linear to well within
  // their σ: the same mode.
  ExpectSameWithinSigma(relative.levels[0].quadrature_frequency_hz, force.levels[0].quadrature_frequency_hz, "f_n");
  EXPECT_THROW(LabelsOf("pressure"), beamid::InputError);
}

}  // namespace
}  // namespace beamid::solver
