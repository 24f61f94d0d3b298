// The paper's set-up as a scenario for the time-domain simulator, shared by
// the tests that fit simulated campaigns.
#pragma once

#include <string>

namespace beamid::testing {

// The paper's set-up as a simulation scenario: its beam (η = 2e-4) on the
// base-physics support (k1 = 150, k2 = 0, k3 = 3e5, c = 0.05), force at
// 0.57 m, acc1..acc3, the hidden position 0.45 m, noise as in a real test
// (0.3 %, 24-bit ADC, clock offset) with this seed; `levels_json` is the
// scenario's "levels" array. settle_max_s 8: near resonance a step needs
// ~5 s to settle to 1e-5; cut at 4 s every step kept a transient that moved
// the fit by 2–4 σ (docs/simulator.md, "Accuracy seen by an identification").
// A negative k3_Nm_rad3 makes the support soften instead.
inline std::string PaperScenarioJson(const std::string& name, const std::string& levels_json, int seed,
                                     double k3_Nm_rad3 = 3e5) {
  return R"({"name": ")" + name + R"(",
  "beam": {"length_m": 0.6, "width_m": 0.04, "thickness_m": 0.005, "youngs_modulus_Pa": 2.1e11,
           "density_kg_m3": 7850, "loss_factor": 0.0002},
  "support": {"polynomial": {"k1_Nm_rad": 150, "k2_Nm_rad2": 0, "k3_Nm_rad3": )" +
         std::to_string(k3_Nm_rad3) + R"(, "c_Nms_rad": 0.05}},
  "excitation": {"channel": "force", "position_m": 0.57},
  "sensors": [{"channel": "acc1", "position_m": 0.1}, {"channel": "acc2", "position_m": 0.3},
              {"channel": "acc3", "position_m": 0.57}],
  "hidden_positions_m": [0.45],
  "levels": )" + levels_json + R"(,
  "timing": {"sample_rate_Hz": 5120, "settle_min_s": 0.2, "settle_max_s": 8.0, "transient_s": 0.05, "record_s": 0.4},
  "noise": {"seed": )" + std::to_string(seed) + R"(, "clock_offset_ppm": 25,
            "default": {"relative_rms": 0.003, "absolute": 0.005, "adc_bits": 24, "adc_range": 500},
            "channels": {"force": {"relative_rms": 0.002, "absolute": 0.002, "adc_bits": 24, "adc_range": 50}}}
})";
}

}  // namespace beamid::testing
