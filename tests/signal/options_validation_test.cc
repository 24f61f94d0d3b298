// Every options struct of signal refuses a value out of its range where it
// is used, with an InputError that names the field. The checks run before
// any work, so the calls below need no real recording.
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hb/errors.h"
#include "signal/campaign.h"
#include "signal/campaign_extractor.h"
#include "signal/frequency_estimator.h"
#include "signal/phasor_estimator.h"
#include "signal/recording.h"
#include "signal/recording_validator.h"
#include "signal/steady_state.h"

#include "tests/support/expect_refused.h"

namespace beamid::signal {
namespace {

using beamid::testing::ExpectRefused;

TEST(OptionsValidation, DefaultsAreValid) {
  EXPECT_NO_THROW(FrequencyEstimatorOptions{}.Validate());
  EXPECT_NO_THROW(SteadyStateOptions{}.Validate());
  EXPECT_NO_THROW(PhasorEstimatorOptions{}.Validate());
  EXPECT_NO_THROW(RecordingChecks{}.Validate());
  EXPECT_NO_THROW(ExtractOptions{}.Validate());
}

TEST(OptionsValidation, FrequencyEstimatorRefusesEachFieldOutOfRange) {
  const Eigen::VectorXd samples = Eigen::VectorXd::Zero(1024);
  auto refused = [&](const FrequencyEstimatorOptions& options, const std::string& field) {
    ExpectRefused([&] { EstimateFrequency(samples, 5120.0, 50.0, options); }, field);
  };
  refused({.num_harmonics = 0}, "num_harmonics = 0: must be 1 … 50");
  refused({.num_harmonics = 51}, "num_harmonics");
  refused({.search_band_rel = 0.0}, "search_band_rel");
  refused({.search_band_rel = 1.0}, "search_band_rel");
  refused({.max_iterations = 0}, "max_iterations");
  refused({.tolerance_rel = std::nan("")}, "tolerance_rel");
}

TEST(OptionsValidation, SteadyStateRefusesEachFieldOutOfRange) {
  const Eigen::MatrixXd samples = Eigen::MatrixXd::Zero(1024, 1);
  const std::vector<std::string> channels = {"force"};
  auto refused = [&](const SteadyStateOptions& options, const std::string& field) {
    ExpectRefused([&] { DetectSteadyState(samples, channels, 5120.0, 50.0, 3, "test.csv", options); }, field);
  };
  refused({.reference_fraction = 0.0}, "reference_fraction");
  refused({.reference_fraction = 1.5}, "reference_fraction");
  refused({.threshold = 0.0}, "threshold");
  refused({.settled_blocks = 0}, "settled_blocks");
  refused({.min_steady_periods = -1.0}, "min_steady_periods");
  refused({.max_decay_ratio = 0.5}, "max_decay_ratio");
  refused({.max_passes = 0}, "max_passes");
  refused({.relative_noise_floor = -1e-9}, "relative_noise_floor");
}

TEST(OptionsValidation, PhasorEstimatorRefusesEachFieldOutOfRange) {
  auto refused = [&](const PhasorEstimatorOptions& options, const std::string& field) {
    ExpectRefused([&] { EstimateStepPhasors(Recording{}, Campaign{}, Step{}, options); }, field);
  };
  refused({.num_harmonics = 0}, "PhasorEstimatorOptions.num_harmonics");
  refused({.num_harmonics = 51}, "PhasorEstimatorOptions.num_harmonics");
  refused({.frequency = {.max_iterations = 0}}, "FrequencyEstimatorOptions.max_iterations");
  refused({.steady_state = {.max_passes = 0}}, "SteadyStateOptions.max_passes");
  refused({.warn_snr_db = -1.0}, "warn_snr_db");
  refused({.warn_frequency_offset_rel = -0.1}, "warn_frequency_offset_rel");
  refused({.warn_transient_fraction = 2.0}, "warn_transient_fraction");
  refused({.min_force_snr = std::nan("")}, "min_force_snr");
  // The frequency estimator's own num_harmonics is replaced by H, so it is not checked.
  EXPECT_NO_THROW((PhasorEstimatorOptions{.frequency = {.num_harmonics = 0}}.Validate()));
}

TEST(OptionsValidation, RecordingChecksAreRefusedBeforeTheFileIsRead) {
  auto refused = [&](const RecordingChecks& checks, const std::string& field) {
    ExpectRefused([&] { ReadRecording(Campaign{}, Step{}, checks); }, field);
    ExpectRefused([&] { ParseRecording("time_s,force\n0,1\n", Campaign{}, Step{}, "test.csv", checks); }, field);
  };
  refused({.min_periods = 0.0}, "min_periods");
  refused({.max_time_deviation_samples = 0.0}, "max_time_deviation_samples");
  refused({.sample_rate_tolerance_rel = 1.0}, "sample_rate_tolerance_rel");
  refused({.min_run_samples = 1}, "min_run_samples");
  refused({.min_run_fraction_of_period = -0.1}, "min_run_fraction_of_period");
  refused({.max_spike_ratio = 1.0}, "max_spike_ratio");
}

TEST(OptionsValidation, ExtractCampaignRefusesEachFieldOutOfRange) {
  auto refused = [&](const ExtractOptions& options, const std::string& field) {
    ExpectRefused([&] { ExtractCampaign(Campaign{}, options); }, field);
  };
  refused({.estimator = {.num_harmonics = 60}}, "PhasorEstimatorOptions.num_harmonics = 60");
  refused({.checks = {.min_periods = -1.0}}, "RecordingChecks.min_periods");
  refused({.num_threads = -1}, "num_threads");
  refused({.num_threads = 257}, "num_threads");
}

}  // namespace
}  // namespace beamid::signal
