// The measurement artefacts of the simulator (docs/simulator.md, "Faults of
// the measurement"): a sensor's gain error, its delay and a stated position
// other than the true one, and a step recorded before it settled
// (timing.early_records), and the acquisition's clock error. Each is checked against the same scenario without
// it, simulated noise-free: the artefact must change the recording exactly as
// documented and nothing else, and truth.json must list it.
#include <cmath>
#include <complex>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hb/scenario.h"
#include "hb/stepped_sine.h"
#include "hb/time_harmonic_fit.h"
#include "tests/support/csv_text.h"
#include "tests/support/json_file.h"
#include "tests/support/simulated_campaign.h"
#include "tests/support/temp_path.h"

namespace beamid::hb {
namespace {

using Json = nlohmann::json;

constexpr double kSampleRate_Hz = 4096.0;

// Noise-free (no "noise" settings but the seed and a clock offset), short
// records, a nonlinear support (k3) strong enough for a third harmonic, and
// damped enough (ζ ≈ 3 %) that every step settles to 1e-5 within 2 s. The
// Rayleigh β damps the high modes that the force's switch-on at t = 0 sets
// ringing (with the loss factor alone they ring through every record, an RMS
// of 1.6 % of acc3's fundamental amplitude here, and the harmonic fits below would not
// compare periodic signals).
Json BaseScenario() {
  return Json::parse(R"({
  "beam": {"length_m": 0.6, "width_m": 0.04, "thickness_m": 0.005, "youngs_modulus_Pa": 2.0e11,
           "density_kg_m3": 7850, "loss_factor": 0.0002, "rayleigh_stiffness_s": 1e-5},
  "support": {"polynomial": {"k1_Nm_rad": 150, "k3_Nm_rad3": 3e5, "c_Nms_rad": 0.3}},
  "excitation": {"channel": "force", "position_m": 0.57},
  "sensors": [{"channel": "acc3", "position_m": 0.57},
              {"channel": "acc1", "position_m": 0.1},
              {"channel": "acc2", "position_m": 0.3}],
  "levels": [{"label": "only", "force_amplitude_N": 4.0, "frequencies_Hz": [53.0, 54.0, 55.0]}],
  "timing": {"sample_rate_Hz": 4096, "settle_min_s": 0.1, "settle_max_s": 2.0, "settle_tolerance": 1e-5,
             "transient_s": 0.05, "record_s": 0.5},
  "noise": {"seed": 5, "clock_offset_ppm": 25}
})");
}

std::vector<SimulatedStep> Simulate(const Json& scenario) {
  return beamid::testing::SimulateSteps(ParseScenario(scenario.dump(), "artefacts.json"));
}

// Harmonics 0..5 of one recorded column over the step's steady part, by a
// least-squares fit at the step's true frequency (phase origin: the first
// steady sample; only ratios between channels are compared).
Eigen::VectorXcd FittedPhasors(const SimulatedStep& step, Eigen::Index column) {
  const double omega = 2.0 * std::numbers::pi * step.frequency_hz;
  TimeHarmonicFit fit(kTruthHarmonics, 1);
  for (Eigen::Index n = step.transient_samples; n < step.recording.rows(); ++n) {
    const double value = step.recording(n, column);
    fit.Add(omega * static_cast<double>(n - step.transient_samples) / kSampleRate_Hz, std::span<const double>(&value, 1));
  }
  return fit.Solve()[0];
}

// A folder removed when the test ends.
struct TempFolder {
  std::filesystem::path path;
  explicit TempFolder(const std::string& name) : path(beamid::testing::UniqueTempPath(name)) {
    std::filesystem::remove_all(path);
  }
  ~TempFolder() { std::filesystem::remove_all(path); }
};

// gain_error_relative: the channel records (1 + g) times what it recorded
// without it, before any noise; every other channel and the truth (the beam's
// true motion) are untouched, and campaign.json does not know it.
TEST(SimulatorMeasurementArtefacts, AGainErrorScalesItsChannelAndNothingElse) {
  constexpr double kGain = 0.05;
  Json with_gain = BaseScenario();
  with_gain["sensors"][2]["gain_error_relative"] = kGain;
  const TempFolder folder("beamid_gain_error");
  const std::vector<SimulatedStep> plain = Simulate(BaseScenario());
  const std::vector<SimulatedStep> gained =
      beamid::testing::SimulateInto(ParseScenario(with_gain.dump(), "gain.json"), folder.path);
  ASSERT_EQ(plain.size(), gained.size());
  for (std::size_t i = 0; i < plain.size(); ++i) {
    SCOPED_TRACE("step " + std::to_string(i));
    const Eigen::MatrixXd& a = plain[i].recording;
    const Eigen::MatrixXd& b = gained[i].recording;
    ASSERT_EQ(a.rows(), b.rows());
    const double peak = a.col(3).cwiseAbs().maxCoeff();
    EXPECT_LT((b.col(3) - (1.0 + kGain) * a.col(3)).cwiseAbs().maxCoeff(), 1e-14 * peak);
    EXPECT_EQ(b.leftCols(3), a.leftCols(3));  // force, acc3, acc1: bit for bit
    // The truth is the beam's motion, not what the miscalibrated sensor says.
    EXPECT_EQ(gained[i].channel_phasors[3], plain[i].channel_phasors[3]);
  }
  // The written CSV (9 significant digits) reads 5 % high.
  const auto columns = beamid::testing::ReadCsvColumns(folder.path / gained[1].file);
  const Eigen::MatrixXd& truth = plain[1].recording;
  const double peak = truth.col(3).cwiseAbs().maxCoeff();
  int compared = 0;
  for (Eigen::Index n = 0; n < truth.rows(); ++n) {
    if (std::abs(truth(n, 3)) < 0.2 * peak) continue;  // the ratio is ill-conditioned near zero crossings
    ASSERT_NEAR(columns.at(4).at(static_cast<std::size_t>(n)) / truth(n, 3), 1.0 + kGain, 1e-7) << "sample " << n;
    ++compared;
  }
  EXPECT_GT(compared, truth.rows() / 2);

  const Json campaign = beamid::testing::ReadJsonFile(folder.path / "campaign.json");
  EXPECT_EQ(campaign.dump().find("gain"), std::string::npos);
  const Json artefacts = beamid::testing::ReadJsonFile(folder.path / "truth.json").at("measurement_artefacts");
  EXPECT_EQ(artefacts.at("sensors").at(2).at("channel"), "acc2");
  EXPECT_EQ(artefacts.at("sensors").at(2).at("gain_error_relative").get<double>(), kGain);
  EXPECT_EQ(artefacts.at("sensors").at(1).at("gain_error_relative").get<double>(), 0.0);
  EXPECT_TRUE(artefacts.at("early_records").empty());
}

// delay_s: the channel records the signal at t − τ, so each harmonic k of its
// recording is the undelayed one times e^{−ikωτ}. Twins of acc3 at the same
// point are delayed by 0.2 ms (8.2 integration steps: the interpolation
// between steps) and by 10 µs (less than one step), and a velocity sensor's
// twin by 0.2 ms; at 54 and 60 Hz.
TEST(SimulatorMeasurementArtefacts, ADelayedChannelLagsByOmegaTauAtEveryHarmonic) {
  Json scenario = BaseScenario();
  scenario["sensors"] = Json::parse(R"([{"channel": "acc3", "position_m": 0.57},
                                        {"channel": "acc3_late", "position_m": 0.57, "delay_s": 2e-4},
                                        {"channel": "acc3_short", "position_m": 0.57, "delay_s": 1e-5},
                                        {"channel": "vel3", "position_m": 0.57, "quantity": "velocity"},
                                        {"channel": "vel3_late", "position_m": 0.57, "quantity": "velocity",
                                         "delay_s": 2e-4}])");
  scenario["levels"][0]["frequencies_Hz"] = {54.0, 60.0};
  struct Twin {
    Eigen::Index plain, delayed;
    double delay_s;
  };
  const Twin twins[] = {{1, 2, 2e-4}, {1, 3, 1e-5}, {4, 5, 2e-4}};
  const std::vector<SimulatedStep> steps = Simulate(scenario);
  ASSERT_EQ(steps.size(), 2u);
  for (const SimulatedStep& step : steps) {
    SCOPED_TRACE(std::to_string(step.nominal_frequency_hz) + " Hz");
    const double omega = 2.0 * std::numbers::pi * step.frequency_hz;
    for (const Twin& twin : twins) {
      SCOPED_TRACE("column " + std::to_string(twin.delayed) + ", delay " + std::to_string(twin.delay_s) + " s");
      const Eigen::VectorXcd plain = FittedPhasors(step, twin.plain);
      const Eigen::VectorXcd delayed = FittedPhasors(step, twin.delayed);
      const std::complex<double> lag1 = std::polar(1.0, -omega * twin.delay_s);
      // The requirement is 10⁻⁴; the cubic interpolation between integration
      // steps gives 2·10⁻⁹, so the bound 10⁻⁶ also refuses a linear one (3·10⁻⁵).
      EXPECT_LT(std::abs(delayed(1) - plain(1) * lag1), 1e-6 * std::abs(plain(1)));
      // The 3rd harmonic lags by 3ωτ (noise-free, it is resolved even where
      // it is small: at 60 Hz 2·10⁻⁵ of the fundamental at acc3, 8·10⁻⁶ at vel3).
      ASSERT_GT(std::abs(plain(3)), 1e-6 * std::abs(plain(1)));
      const double phase3 = std::arg(delayed(3) / plain(3));
      EXPECT_NEAR(phase3, -3.0 * omega * twin.delay_s, 1e-3);
      EXPECT_NEAR(std::abs(delayed(3)) / std::abs(plain(3)), 1.0, 1e-3);
      // The truth is the motion of the point, the same for both.
      for (Eigen::Index k = 1; k <= kTruthHarmonics; ++k)
        EXPECT_LT(std::abs(step.channel_phasors[twin.delayed](k) - step.channel_phasors[twin.plain](k)),
                  1e-12 * std::abs(step.channel_phasors[twin.plain](1)));
    }
  }
}

// With base excitation an accelerometer records the absolute acceleration,
// the beam's relative one plus the base's a_b: the delay applies to the sum.
TEST(SimulatorMeasurementArtefacts, ADelayedAccelerometerOnAMovingBaseLagsByOmegaTau) {
  Json scenario = BaseScenario();
  scenario["excitation"] = Json::parse(R"({"channel": "base", "quantity": "base_acceleration"})");
  scenario["sensors"] = Json::parse(R"([{"channel": "acc2", "position_m": 0.3},
                                        {"channel": "acc2_late", "position_m": 0.3, "delay_s": 2e-4}])");
  scenario["levels"] = Json::parse(R"([{"label": "only", "base_acceleration_amplitude_m_s2": 1.0, "frequencies_Hz": [54.0]}])");
  const SimulatedStep step = Simulate(scenario).at(0);
  const double omega = 2.0 * std::numbers::pi * step.frequency_hz;
  const Eigen::VectorXcd plain = FittedPhasors(step, 1), delayed = FittedPhasors(step, 2);
  EXPECT_LT(std::abs(delayed(1) - plain(1) * std::polar(1.0, -omega * 2e-4)), 1e-4 * std::abs(plain(1)));
}

// stated_position_m: campaign.json says where the test plan put the sensor;
// the beam is measured where it is, so the recording is that of a scenario
// with the sensor at position_m, and not that of one with it where stated.
TEST(SimulatorMeasurementArtefacts, AStatedPositionGoesToTheCampaignAndTheBeamIsMeasuredWhereTheSensorIs) {
  constexpr double kTrue_m = 0.1, kStated_m = 0.11;
  Json misplaced = BaseScenario();
  misplaced["sensors"][1]["stated_position_m"] = kStated_m;
  misplaced["levels"][0]["frequencies_Hz"] = {54.0};
  Json at_true = misplaced, at_stated = misplaced;
  at_true["sensors"][1].erase("stated_position_m");
  at_stated["sensors"][1].erase("stated_position_m");
  at_stated["sensors"][1]["position_m"] = kStated_m;

  const TempFolder folder("beamid_stated_position");
  const SimulatedStep step =
      beamid::testing::SimulateInto(ParseScenario(misplaced.dump(), "stated.json"), folder.path).at(0);
  const SimulatedStep truly_there = Simulate(at_true).at(0);
  const SimulatedStep where_stated = Simulate(at_stated).at(0);
  EXPECT_EQ(step.recording, truly_there.recording);
  // 10 mm from the clamp at x = 0.1 m moves the amplitude by about 20 %.
  const double measured = std::abs(FittedPhasors(step, 2)(1)), stated = std::abs(FittedPhasors(where_stated, 2)(1));
  EXPECT_GT(std::abs(stated / measured - 1.0), 0.05);

  const Json campaign = beamid::testing::ReadJsonFile(folder.path / "campaign.json");
  EXPECT_EQ(campaign.at("sensors").at(1).at("channel"), "acc1");
  EXPECT_EQ(campaign.at("sensors").at(1).at("position_m").get<double>(), kStated_m);
  EXPECT_EQ(campaign.at("sensors").at(2).at("position_m").get<double>(), 0.3);
  const Json sensor = beamid::testing::ReadJsonFile(folder.path / "truth.json").at("measurement_artefacts").at("sensors").at(1);
  EXPECT_EQ(sensor.at("channel"), "acc1");
  EXPECT_EQ(sensor.at("position_m").get<double>(), kTrue_m);
  EXPECT_EQ(sensor.at("stated_position_m").get<double>(), kStated_m);
}

// Relative change of a column's fundamental between the first and the second
// half of the step's steady part.
double HalfToHalfChange(const SimulatedStep& step, Eigen::Index column) {
  const double omega = 2.0 * std::numbers::pi * step.frequency_hz;
  const Eigen::Index start = step.transient_samples, half = (step.recording.rows() - start) / 2;
  std::complex<double> fundamental[2];
  for (int h = 0; h < 2; ++h) {
    TimeHarmonicFit fit(kTruthHarmonics, 1);
    for (Eigen::Index n = start + h * half; n < start + (h + 1) * half; ++n) {
      const double value = step.recording(n, column);
      fit.Add(omega * static_cast<double>(n - start) / kSampleRate_Hz, std::span<const double>(&value, 1));
    }
    fundamental[h] = fit.Solve()[0](1);
  }
  return std::abs(fundamental[1] - fundamental[0]) / std::abs(fundamental[1]);
}

// timing.early_records: the named step is recorded settle_s after its
// frequency change, with its transient still in it; the steps before it are
// untouched, it is listed in truth.json, and the sweep goes on from where
// its record ended (the next step settles again).
TEST(SimulatorMeasurementArtefacts, AnEarlyRecordHoldsTheTransientAndTheSweepGoesOn) {
  constexpr double kSettle_s = 0.05;
  Json early = BaseScenario();
  early["timing"]["early_records"] = Json::parse(R"([{"level": "only", "frequency_Hz": 54.0, "settle_s": 0.05}])");
  const TempFolder folder("beamid_early_record");
  const std::vector<SimulatedStep> settled = Simulate(BaseScenario());
  const std::vector<SimulatedStep> steps = beamid::testing::SimulateInto(ParseScenario(early.dump(), "early.json"), folder.path);
  ASSERT_EQ(steps.size(), 3u);

  EXPECT_EQ(steps[0].recording, settled[0].recording);  // before the early record: bit for bit
  EXPECT_FALSE(steps[0].early_record_settle_s.has_value());

  // The early record: its file starts 0.05 s after the frequency change
  // (the settled one after more than settle_min_s = 0.1 s) and differs from
  // the settled record from its first sample on; its fundamental still
  // changes by percents within the record, the settled one's by < 1e-4.
  const SimulatedStep& cut = steps[1];
  ASSERT_TRUE(cut.early_record_settle_s.has_value());
  EXPECT_EQ(*cut.early_record_settle_s, kSettle_s);
  EXPECT_FALSE(cut.settled);
  EXPECT_EQ(cut.transient_samples, settled[1].transient_samples);
  EXPECT_DOUBLE_EQ(cut.settle_s, (std::lround(kSettle_s * kSampleRate_Hz) + cut.transient_samples) / kSampleRate_Hz);
  EXPECT_GT(settled[1].settle_s, cut.settle_s + 0.05);
  const double peak = settled[1].recording.col(1).cwiseAbs().maxCoeff();
  EXPECT_GT((cut.recording.topRows(20).col(1) - settled[1].recording.topRows(20).col(1)).cwiseAbs().maxCoeff(),
            0.01 * peak);
  EXPECT_GT(HalfToHalfChange(cut, 1), 0.01);
  EXPECT_LT(HalfToHalfChange(settled[1], 1), 1e-3);

  // The next step starts from the early record's end and settles again: its
  // steady record is the settled sweep's to the settling tolerance.
  EXPECT_TRUE(steps[2].settled);
  EXPECT_FALSE(steps[2].early_record_settle_s.has_value());
  const std::complex<double> next = steps[2].channel_phasors[1](1), reference = settled[2].channel_phasors[1](1);
  EXPECT_NE(steps[2].recording, settled[2].recording);
  EXPECT_LT(std::abs(next - reference), 1e-3 * std::abs(reference));

  const Json truth = beamid::testing::ReadJsonFile(folder.path / "truth.json");
  EXPECT_EQ(truth.at("steps").at(1).at("early_record_settle_s").get<double>(), kSettle_s);
  EXPECT_FALSE(truth.at("steps").at(1).at("settled").get<bool>());
  EXPECT_FALSE(truth.at("steps").at(0).contains("early_record_settle_s"));
  EXPECT_FALSE(truth.at("steps").at(2).contains("early_record_settle_s"));
  const Json& listed = truth.at("measurement_artefacts").at("early_records");
  ASSERT_EQ(listed.size(), 1u);
  EXPECT_EQ(listed.at(0).at("file"), "only/step_001.csv");
  EXPECT_EQ(listed.at(0).at("level"), "only");
  EXPECT_EQ(listed.at(0).at("nominal_frequency_Hz").get<double>(), 54.0);
  EXPECT_EQ(listed.at(0).at("settle_s").get<double>(), kSettle_s);
}

// settle_s counts from the frequency change to the file's first sample: early
// records of every step at settle_s give the recordings of a settling rule
// that integrates exactly settle_s + transient_s before the steady part.
TEST(SimulatorMeasurementArtefacts, AnEarlyRecordStartsItsFileSettleSecondsAfterTheFrequencyChange) {
  Json early = BaseScenario();
  // 0.0625 s is 256 samples; with transient_s (205 samples) 461 = round(0.1125 s · 4096 Hz).
  early["timing"]["early_records"] = Json::parse(R"([{"level": "only", "frequency_Hz": 53.0, "settle_s": 0.0625},
                                                     {"level": "only", "frequency_Hz": 54.0, "settle_s": 0.0625},
                                                     {"level": "only", "frequency_Hz": 55.0, "settle_s": 0.0625}])");
  Json fixed = BaseScenario();
  fixed["timing"]["settle_min_s"] = 0.1125;
  fixed["timing"]["settle_max_s"] = 0.1125;
  const std::vector<SimulatedStep> a = Simulate(early), b = Simulate(fixed);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    SCOPED_TRACE("step " + std::to_string(i));
    EXPECT_EQ(a[i].recording, b[i].recording);
    EXPECT_EQ(a[i].settle_s, b[i].settle_s);
  }
}

// timing.daq_clock_error_relative: the acquisition samples at f_s·(1 + ε)
// and its files say f_s, so every frequency the extraction reads from them is
// the true one/(1 + ε); the amplitudes (m/s², not clock-based) are those of
// the same beam without the fault, campaign.json states f_s, and truth.json
// lists ε. ε = 0.5 %: a wrong 1 − ε (instead of 1/(1 + ε)) misses by ε² =
// 2.5·10⁻⁵, far beyond the tolerance below (4σ of the frequency estimates,
// ~2·10⁻⁷ relative).
TEST(SimulatorMeasurementArtefacts, AFastAcquisitionClockReadsEveryFrequencyOneOverOnePlusEpsilonLow) {
  constexpr double kClockError = 0.005;
  // A little noise: the extraction looks for the steady state above a noise floor.
  Json base = BaseScenario();
  base["noise"]["default"] = {{"relative_rms", 1e-4}};
  Json fast = base;
  fast["timing"]["daq_clock_error_relative"] = kClockError;
  const TempFolder plain_folder("beamid_daq_clock_plain"), fast_folder("beamid_daq_clock_fast");
  const std::vector<SimulatedStep> plain =
      beamid::testing::SimulateInto(ParseScenario(base.dump(), "plain.json"), plain_folder.path);
  const std::vector<SimulatedStep> clocked =
      beamid::testing::SimulateInto(ParseScenario(fast.dump(), "clock.json"), fast_folder.path);
  const beamid::testing::ExtractedCampaign a = beamid::testing::ExtractFolder(plain_folder.path);
  const beamid::testing::ExtractedCampaign b = beamid::testing::ExtractFolder(fast_folder.path);
  ASSERT_EQ(a.phasors.steps.size(), 3u);
  ASSERT_EQ(b.phasors.steps.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    SCOPED_TRACE("step " + std::to_string(i));
    // The same beam driven at the same true frequency...
    EXPECT_EQ(clocked[i].frequency_hz, plain[i].frequency_hz);
    // ...sampled as many times per record, but faster.
    EXPECT_EQ(clocked[i].recording.rows(), plain[i].recording.rows());
    const double read = b.phasors.steps[i].frequency_hz, unfaulted = a.phasors.steps[i].frequency_hz;
    std::printf("%.6f Hz read (± %.1e), %.6f Hz without the fault, ratio − 1/(1 + ε) = %.2e\n", read,
                b.phasors.steps[i].frequency_std_hz, unfaulted, read / unfaulted - 1.0 / (1.0 + kClockError));
    // To 4σ of the extraction's frequency estimates (~4·10⁻⁸ relative each).
    const double sigma_read = b.phasors.steps[i].frequency_std_hz / read;
    const double sigma_unfaulted = a.phasors.steps[i].frequency_std_hz / unfaulted;
    ASSERT_GT(sigma_read, 0.0);
    ASSERT_LT(sigma_read, 1e-6);
    EXPECT_NEAR(read / unfaulted, 1.0 / (1.0 + kClockError), 4.0 * std::hypot(sigma_read, sigma_unfaulted));
    EXPECT_NEAR(unfaulted / plain[i].frequency_hz, 1.0, 4.0 * sigma_unfaulted);
    for (std::size_t c = 0; c < b.phasors.steps[i].responses.size(); ++c) {
      SCOPED_TRACE(b.phasors.steps[i].responses[c].channel);
      // What the extraction reads is the beam's true amplitude (a clock in
      // it, through the ω² of an acceleration, would move it by 2ε = 10⁻²)...
      const double read_amplitude = b.phasors.steps[i].responses[c].Harmonic(1).Amplitude();
      const double true_amplitude = std::abs(clocked[i].channel_phasors[c + 1](1));
      std::printf("  %s: read/true amplitude − 1 = %.2e, true with/without the fault − 1 = %.2e\n",
                  b.phasors.steps[i].responses[c].channel.c_str(), read_amplitude / true_amplitude - 1.0,
                  true_amplitude / std::abs(plain[i].channel_phasors[c + 1](1)) - 1.0);
      EXPECT_NEAR(read_amplitude / true_amplitude, 1.0, 1e-5);
      // ...and the beam's motion is the unfaulted one's, both settled to
      // 10⁻⁵ between windows.
      EXPECT_NEAR(true_amplitude / std::abs(plain[i].channel_phasors[c + 1](1)), 1.0, 1e-5);
    }
  }
  // The files label the samples at the stated rate.
  const auto columns = beamid::testing::ReadCsvColumns(fast_folder.path / clocked[1].file);
  EXPECT_DOUBLE_EQ(columns.at(0).at(100), 100.0 / kSampleRate_Hz);
  const Json campaign = beamid::testing::ReadJsonFile(fast_folder.path / "campaign.json");
  EXPECT_EQ(campaign.at("sample_rate_Hz").get<double>(), kSampleRate_Hz);
  EXPECT_EQ(campaign.dump().find("clock"), std::string::npos);
  const Json truth = beamid::testing::ReadJsonFile(fast_folder.path / "truth.json");
  EXPECT_EQ(truth.at("measurement_artefacts").at("daq_clock_error_relative").get<double>(), kClockError);
  EXPECT_FALSE(beamid::testing::ReadJsonFile(plain_folder.path / "truth.json").contains("measurement_artefacts"));
}

}  // namespace
}  // namespace beamid::hb
