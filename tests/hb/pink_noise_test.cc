// ChannelNoise::pink_rms (docs/simulator.md, hb/internal/pink_noise.h): the
// drift added to a channel has exactly the RMS asked, no mean, and a power
// spectrum falling as 1/f from 1/T to f_s/2; it is the scenario's seed's
// alone, and in a campaign it is in the channel's written unit.
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hb/internal/real_fft.h"
#include "hb/noise.h"
#include "hb/scenario.h"
#include "hb/stepped_sine.h"
#include "tests/support/csv_text.h"
#include "tests/support/json_file.h"
#include "tests/support/simulated_campaign.h"
#include "tests/support/temp_path.h"

namespace beamid::hb {
namespace {

constexpr int kSamples = 4096;
constexpr double kPinkRms = 0.5;

Eigen::VectorXd Drift(MeasurementNoise& noise) {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(kSamples);
  noise.Apply({.pink_rms = kPinkRms}, x);
  return x;
}

TEST(PinkNoise, HasTheAskedRmsNoMeanAndAOneOverFSpectrum) {
  MeasurementNoise noise(11);
  constexpr int kRealisations = 16;
  const int harmonics = kSamples / 2 - 1;
  Eigen::VectorXd power = Eigen::VectorXd::Zero(harmonics + 1);
  internal::RealFft fft(kSamples);
  for (int r = 0; r < kRealisations; ++r) {
    const Eigen::VectorXd x = Drift(noise);
    EXPECT_NEAR(std::sqrt(x.squaredNorm() / kSamples), kPinkRms, 1e-12);
    EXPECT_NEAR(x.mean(), 0.0, 1e-12);
    Eigen::VectorXcd phasors;
    fft.Forward(x, harmonics, &phasors);
    power += phasors.cwiseAbs2();
  }
  // Equal widths, a low band and a high one: 1/f gives Σ1/k over 1..32
  // against Σ1/k over 1000..1031, a ratio of about 130 (white noise: 1).
  const double low = power.segment(1, 32).sum();
  const double high = power.segment(1000, 32).sum();
  EXPECT_GT(low / high, 50.0);
  EXPECT_LT(low / high, 400.0);
  // The slope of the mean power per bin over octaves 4..2047: −1.
  std::vector<double> log_f, log_p;
  for (int start = 4; start < harmonics; start *= 2) {
    const int end = std::min(2 * start, harmonics + 1);
    log_f.push_back(std::log(0.5 * (start + end - 1)));
    log_p.push_back(std::log(power.segment(start, end - start).mean()));
  }
  const Eigen::Map<const Eigen::VectorXd> lf(log_f.data(), static_cast<Eigen::Index>(log_f.size()));
  const Eigen::Map<const Eigen::VectorXd> lp(log_p.data(), static_cast<Eigen::Index>(log_p.size()));
  const Eigen::VectorXd df = lf.array() - lf.mean(), dp = lp.array() - lp.mean();
  const double slope = df.dot(dp) / df.squaredNorm();
  EXPECT_NEAR(slope, -1.0, 0.15);
  // The lowest bin (1/T) is populated, not left out.
  EXPECT_GT(power(1), power(2) * 0.2);
}

TEST(PinkNoise, IsTheSeedsAlone) {
  MeasurementNoise a(3), b(3), c(4);
  const Eigen::VectorXd xa = Drift(a), xb = Drift(b), xc = Drift(c);
  EXPECT_EQ(xa, xb);
  EXPECT_GT((xa - xc).norm(), 1.0);
}

// In a campaign: the acc3 column (unit g) minus the noise-free signal has the
// asked RMS in g; a channel without drift is written noise-free.
TEST(PinkNoise, IsAddedInTheChannelsWrittenUnit) {
  const std::string text = R"({
  "beam": {"length_m": 0.6, "width_m": 0.04, "thickness_m": 0.005, "youngs_modulus_Pa": 2.0e11,
           "density_kg_m3": 7850, "loss_factor": 0.0002},
  "support": {"polynomial": {"k1_Nm_rad": 150, "c_Nms_rad": 0.1}},
  "excitation": {"channel": "force", "position_m": 0.57},
  "sensors": [{"channel": "acc3", "position_m": 0.57, "unit": "g"}],
  "levels": [{"label": "only", "force_amplitude_N": 1.0, "frequencies_Hz": [52.0]}],
  "timing": {"sample_rate_Hz": 4096, "settle_min_s": 0.1, "settle_max_s": 0.5, "settle_tolerance": 1e-4,
             "transient_s": 0.05, "record_s": 0.5},
  "noise": {"seed": 2, "channels": {"acc3": {"pink_rms": 0.01}}}
})";
  const std::filesystem::path directory = beamid::testing::UniqueTempPath("beamid_pink");
  std::filesystem::remove_all(directory);
  const SimulatedStep clean = beamid::testing::SimulateInto(ParseScenario(text, "pink.json"), directory).back();
  ASSERT_EQ(beamid::testing::ReadCsvHeader(directory / clean.file), "time_s,force,acc3");
  const auto columns = beamid::testing::ReadCsvColumns(directory / clean.file);
  const std::vector<double>& force = columns.at(1);
  const std::vector<double>& acc3 = columns.at(2);
  double force_error = 0.0, drift_squares = 0.0;
  Eigen::Index n = 0;
  for (; n < static_cast<Eigen::Index>(force.size()); ++n) {
    const size_t i = static_cast<size_t>(n);
    force_error = std::max(force_error, std::abs(force[i] - clean.recording(n, 0)));
    const double drift_g = acc3[i] - clean.recording(n, 1) / 9.80665;
    drift_squares += drift_g * drift_g;
  }
  ASSERT_EQ(n, clean.recording.rows());
  EXPECT_LT(force_error, 1e-8);
  EXPECT_NEAR(std::sqrt(drift_squares / static_cast<double>(n)), 0.01, 1e-6);
  const nlohmann::json truth = beamid::testing::ReadJsonFile(directory / "truth.json");
  EXPECT_EQ(truth.at("noise").at("channels").at("acc3").at("pink_rms").get<double>(), 0.01);
  EXPECT_FALSE(truth.at("noise").at("default").contains("pink_rms"));
  std::filesystem::remove_all(directory);
}

}  // namespace
}  // namespace beamid::hb
