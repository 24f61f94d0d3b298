// Extraction benchmark: phasor extraction throughput (samples per second on
// one core, in-memory records), CSV load speed (MB/s, parse + validation,
// in memory and from a file in the page cache), and the wall time to extract
// a 120-step, 4-channel campaign of 1 s at 5120 Hz from disk (target < 1 s),
// on 1 and 2 threads. Records: 5 harmonics down to -60 dB, a decaying
// transient over the first 20 %, white noise at 50 dB SNR.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <string>

#include <benchmark/benchmark.h>

#include "signal/campaign.h"
#include "signal/campaign_extractor.h"
#include "signal/phasor_estimator.h"
#include "signal/recording.h"

namespace {

using namespace beamid::signal;
namespace fs = std::filesystem;

constexpr double kRateHz = 5120.0;
constexpr int kSamples = 5120;
constexpr int kSteps = 120;
constexpr int kSensors = 3;

double StepFrequency(int step) { return 45.0 + 0.1 * step; }

Eigen::MatrixXd SynthesizeStep(int step, std::mt19937& rng) {
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> phase(-std::numbers::pi, std::numbers::pi);
  const double f_hz = StepFrequency(step) * (1.0 + 25e-6);  // clock mismatch
  Eigen::MatrixXd samples(kSamples, kSensors + 1);
  for (int c = 0; c <= kSensors; ++c) {
    const double amplitude = 1.0 + c;
    double phases[6];
    for (double& p : phases) p = phase(rng);
    for (int n = 0; n < kSamples; ++n) {
      const double t = n / kRateHz;
      double x = 0.0;
      for (int k = 1; k <= 5; ++k)
        x += amplitude * std::pow(10.0, -0.75 * (k - 1)) * std::cos(2.0 * std::numbers::pi * k * f_hz * t + phases[k]);
      x += amplitude * std::exp(-t / 0.02) * std::sin(2.0 * std::numbers::pi * 61.0 * t + phases[0]);
      samples(n, c) = x + amplitude * 2.2e-3 * normal(rng);
    }
  }
  return samples;
}

std::string ToCsv(const Eigen::MatrixXd& samples) {
  std::string csv = "time_s,force,acc1,acc2,acc3\n";
  char line[160];
  for (Eigen::Index n = 0; n < samples.rows(); ++n) {
    std::snprintf(line, sizeof line, "%.9f,%.9g,%.9g,%.9g,%.9g\n", static_cast<double>(n) / kRateHz, samples(n, 0),
                  samples(n, 1), samples(n, 2), samples(n, 3));
    csv += line;
  }
  return csv;
}

// The campaign folder, written once per process.
const fs::path& CampaignFolder() {
  static const fs::path folder = [] {
    const fs::path dir = fs::temp_directory_path() / "beamid_signal_benchmark_campaign";
    fs::remove_all(dir);
    fs::create_directories(dir / "steps");
    std::string json = R"({"format": "stepped-sine-campaign/1", "name": "benchmark",
  "beam": {"length_m": 0.6, "width_m": 0.04, "thickness_m": 0.005, "youngs_modulus_Pa": 2.1e11, "density_kg_m3": 7850},
  "excitation": {"channel": "force", "position_m": 0.57, "quantity": "force", "unit": "N"},
  "sensors": [{"channel": "acc1", "position_m": 0.1, "quantity": "acceleration", "unit": "m/s^2"},
              {"channel": "acc2", "position_m": 0.3, "quantity": "acceleration", "unit": "m/s^2"},
              {"channel": "acc3", "position_m": 0.57, "quantity": "acceleration", "unit": "m/s^2"}],
  "steps": [)";
    std::mt19937 rng(4);
    for (int s = 0; s < kSteps; ++s) {
      const std::string name = "steps/step_" + std::to_string(s) + ".csv";
      std::ofstream(dir / name) << ToCsv(SynthesizeStep(s, rng));
      json += std::string(s ? ",\n" : "") + R"({"file": ")" + name + R"(", "frequency_Hz": )" +
              std::to_string(StepFrequency(s)) + R"(, "level": "mid"})";
    }
    std::ofstream(dir / "campaign.json") << json << "]}\n";
    return dir;
  }();
  return folder;
}

void BM_PhasorExtraction(benchmark::State& state) {
  const Campaign campaign = ReadCampaign(CampaignFolder());
  const Recording recording = ReadRecording(campaign, campaign.steps[10]);
  for (auto _ : state) {
    StepPhasors step = EstimateStepPhasors(recording, campaign, campaign.steps[10]);
    benchmark::DoNotOptimize(step);
  }
  state.SetItemsProcessed(state.iterations() * recording.samples.size());
  state.counters["samples_per_s"] =
      benchmark::Counter(static_cast<double>(recording.samples.size()), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_PhasorExtraction)->Unit(benchmark::kMillisecond);

void BM_CsvParse(benchmark::State& state) {
  const Campaign campaign = ReadCampaign(CampaignFolder());
  std::ifstream in(campaign.StepPath(campaign.steps[0]));
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  for (auto _ : state) {
    Recording recording = ParseRecording(text, campaign, campaign.steps[0], "bench.csv");
    benchmark::DoNotOptimize(recording);
  }
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(text.size()));
}
BENCHMARK(BM_CsvParse)->Unit(benchmark::kMillisecond);

void BM_CsvReadFile(benchmark::State& state) {
  const Campaign campaign = ReadCampaign(CampaignFolder());
  const auto size = static_cast<std::int64_t>(fs::file_size(campaign.StepPath(campaign.steps[0])));
  for (auto _ : state) {
    Recording recording = ReadRecording(campaign, campaign.steps[0]);
    benchmark::DoNotOptimize(recording);
  }
  state.SetBytesProcessed(state.iterations() * size);
}
BENCHMARK(BM_CsvReadFile)->Unit(benchmark::kMillisecond);

// 120 steps × 4 channels × 1 s at 5120 Hz, from disk, all of beamid extract
// except writing the output.
void BM_ExtractCampaignFromDisk(benchmark::State& state) {
  const fs::path folder = CampaignFolder();
  ExtractOptions options;
  options.num_threads = static_cast<int>(state.range(0));
  for (auto _ : state) {
    PhasorSet set = ExtractCampaign(ReadCampaign(folder), options);
    benchmark::DoNotOptimize(set);
  }
  state.counters["steps"] = kSteps;
}
BENCHMARK(BM_ExtractCampaignFromDisk)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);

}  // namespace
