// noise.amplitude_creep_relative (docs/simulator.md): every response channel
// of the written CSV is the noise-free signal times 1 + creep·(t/T − 1/2)
// over the steady record (0 at its first sample, 1 at its last), the
// transient continuing the line; the excitation channel is untouched, and
// the record-mean amplitude is the truth.
#include <cmath>
#include <complex>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hb/scenario.h"
#include "hb/stepped_sine.h"
#include "hb/time_harmonic_fit.h"
#include "tests/support/csv_text.h"
#include "tests/support/simulated_campaign.h"
#include "tests/support/temp_path.h"

namespace beamid::hb {
namespace {

constexpr double kCreep = 0.02;

const std::string kScenario = R"({
  "beam": {"length_m": 0.6, "width_m": 0.04, "thickness_m": 0.005, "youngs_modulus_Pa": 2.0e11,
           "density_kg_m3": 7850, "loss_factor": 0.0002},
  "support": {"polynomial": {"k1_Nm_rad": 150, "k3_Nm_rad3": 3e5, "c_Nms_rad": 0.1}},
  "excitation": {"channel": "force", "position_m": 0.57},
  "sensors": [{"channel": "acc3", "position_m": 0.57, "unit": "g"},
              {"channel": "vel1", "position_m": 0.1, "quantity": "velocity", "unit": "mm/s"}],
  "levels": [{"label": "only", "force_amplitude_N": 2.0, "frequencies_Hz": [54.0]}],
  "timing": {"sample_rate_Hz": 4096, "settle_min_s": 0.1, "settle_max_s": 1.0, "settle_tolerance": 1e-4,
             "transient_s": 0.05, "record_s": 0.5},
  "noise": {"seed": 5, "amplitude_creep_relative": 0.02}
})";

TEST(AmplitudeCreep, ResponseChannelsCreepLinearlyAboutTheTruthAndTheForceDoesNot) {
  const std::filesystem::path directory = beamid::testing::UniqueTempPath("beamid_creep");
  std::filesystem::remove_all(directory);
  const SimulatedStep clean = beamid::testing::SimulateInto(ParseScenario(kScenario, "creep.json"), directory).back();
  const auto columns = beamid::testing::ReadCsvColumns(directory / clean.file);
  std::filesystem::remove_all(directory);
  const Eigen::Index rows = clean.recording.rows();
  ASSERT_EQ(static_cast<Eigen::Index>(columns.at(0).size()), rows);
  const int steady = clean.transient_samples;
  ASSERT_GT(steady, 0);
  const double span = static_cast<double>(rows - 1 - steady);
  const std::vector<double> to_si{1.0, 9.80665, 1e-3};  // force N, acc3 g, vel1 mm/s

  for (int c = 0; c < 3; ++c) {
    SCOPED_TRACE("column " + std::to_string(c));
    const double peak = clean.recording.col(c).cwiseAbs().maxCoeff();
    int compared = 0;
    for (Eigen::Index n = 0; n < rows; ++n) {
      const double truth = clean.recording(n, c);
      if (std::abs(truth) < 0.2 * peak) continue;  // the ratio is ill-conditioned near zero crossings
      const double expected_scale = c == 0 ? 1.0 : 1.0 + kCreep * ((n - steady) / span - 0.5);
      // The CSV holds 9 significant digits.
      ASSERT_NEAR(columns[c + 1][n] * to_si[c] / truth, expected_scale, 1e-7) << "sample " << n;
      ++compared;
    }
    EXPECT_GT(compared, rows / 2);
  }

  // Over the steady record the creep averages out: the fitted fundamental is
  // the truth's (a linear ramp of zero mean leaks only ~creep/(ωT) into it).
  const double omega = 2.0 * std::numbers::pi * clean.frequency_hz;
  TimeHarmonicFit fit(1, 2);
  for (Eigen::Index n = steady; n < rows; ++n) {
    const double values[2] = {columns[1][n], columns[2][n] * 9.80665};
    fit.Add(omega * static_cast<double>(n - steady) / 4096.0, std::span<const double>(values, 2));
  }
  const std::vector<Eigen::VectorXcd> phasors = fit.Solve();
  const double gain = std::abs(phasors[1](1)) / std::abs(phasors[0](1));
  const double truth_gain = std::abs(clean.channel_phasors[1](1)) / std::abs(clean.channel_phasors[0](1));
  EXPECT_NEAR(gain / truth_gain, 1.0, 2e-4);
  // Without the creep correction (the end of the record) it would be off by 1 %.
  EXPECT_GT(kCreep / 2, 50 * std::abs(gain / truth_gain - 1.0));
}

}  // namespace
}  // namespace beamid::hb
