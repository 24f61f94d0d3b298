// The flags of the measured backbone (solver/backbone/measured_backbone.h):
// on the closed-form receptance of a 1-DOF oscillator (known f_n and ζ,
// displacement over force, sampled densely across the peak, with seeded
// noise of the stated σ) no level is flagged and ζ lies within its stated σ;
// cutting the peak off the band flags peak_outside_band; negative damping
// flags damping_not_positive; 30 % noise against a stated 0.2 % flags
// regeneration_beyond_noise; a flagged level stays out of the cross-level fit
// unless the options keep it. And `beamid backbone --measured` refuses an -o
// that is one of its input tables before reading anything.
#include "solver/backbone/measured_backbone.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hb/errors.h"
#include "tests/support/expect_refused.h"
#include "tests/support/temp_path.h"

namespace beamid::solver {
namespace {

using ::testing::HasSubstr;

constexpr double kNaturalFrequency_hz = 50.0;
constexpr double kDampingRatio = 0.01;
constexpr double kStatedRelativeStd = 2e-3;  // σ of the response phasor, relative to |X|
constexpr double kSigmas = 3.0;

struct Oscillator {
  double damping_ratio = kDampingRatio;
  // A second mode (0: none) of this frequency and the same modal mass and damping.
  double second_mode_hz = 0.0;
  std::complex<double> Receptance(double f_hz) const {
    auto mode = [&](double fn) {
      const double wn = 2 * std::numbers::pi * fn, w = 2 * std::numbers::pi * f_hz;
      return 1.0 / std::complex<double>(wn * wn - w * w, 2 * damping_ratio * wn * w);  // m = 1 kg
    };
    return mode(kNaturalFrequency_hz) + (second_mode_hz > 0 ? mode(second_mode_hz) : 0.0);
  }
};

// A force-controlled level in displacement: X = H·F (+ seeded noise of
// relative σ `actual_noise`), stated σ kStatedRelativeStd·|X| per component / √2.
signal::FirstHarmonicLevel Level(const std::string& label, const Oscillator& oscillator, double force_N, double f_start,
                                 double f_stop, double actual_noise, unsigned seed) {
  std::mt19937 random(seed);
  std::normal_distribution<double> normal;
  signal::FirstHarmonicLevel level{.label = label, .source = label + ".csv", .channel = "disp",
                                   .response_quantity = signal::Quantity::kDisplacement};
  const int n = static_cast<int>(std::lround((f_stop - f_start) / 0.1));
  for (int i = 0; i <= n; ++i) {
    const double f = f_start + 0.1 * i;
    signal::FirstHarmonicPoint p{.frequency_hz = f};
    p.force.value = force_N;
    std::complex<double> x = oscillator.Receptance(f) * force_N;
    const double sigma = kStatedRelativeStd * std::abs(x) / std::sqrt(2.0);
    x += std::abs(x) * actual_noise / std::sqrt(2.0) * std::complex<double>(normal(random), normal(random));
    p.response.value = x;
    p.response.std_real = p.response.std_imag = sigma;
    level.points.push_back(p);
  }
  return level;
}

signal::FirstHarmonicLevel Clean(const std::string& label, double force_N, unsigned seed) {
  return Level(label, {}, force_N, 47.0, 53.0, kStatedRelativeStd, seed);
}

std::string Flags(const LevelResonance& l) {
  std::string text;
  for (const auto& f : l.flags) text += std::string(LevelFlagName(f.kind)) + " (" + f.quantity + "): " + f.message + "\n";
  return text;
}

void ExpectWithin(const Estimate& e, double truth, const std::string& what) {
  ASSERT_TRUE(e.valid) << what;
  EXPECT_GT(e.std, 0.0) << what;
  EXPECT_LE(std::abs(e.value - truth), kSigmas * e.std) << what << ": " << e.value << " ± " << e.std;
}

TEST(MeasuredBackboneFlags, ASingleModeAcrossItsPeakIsNotFlaggedAndGivesItsDamping) {
  const MeasuredBackbone result = AnalyseMeasuredBackbone({Clean("low", 1.0, 1), Clean("high", 2.0, 2)});
  ASSERT_TRUE(result.fit.ok);
  for (const auto& l : result.levels) {
    SCOPED_TRACE(l.label);
    EXPECT_TRUE(l.flags.empty()) << Flags(l);
    EXPECT_TRUE(l.in_global_fit);
    ExpectWithin(l.quadrature_damping_ratio, kDampingRatio, "phase-resonance ζ");
    ExpectWithin(l.local_damping_ratio, kDampingRatio, "local-fit ζ");
    ExpectWithin(l.half_power_damping_ratio, kDampingRatio, "half-power ζ");
    ExpectWithin(l.peak_frequency_hz, kNaturalFrequency_hz * std::sqrt(1 - 2 * kDampingRatio * kDampingRatio),
                 "peak of |X/F|");
    ExpectWithin(l.quadrature_frequency_hz, kNaturalFrequency_hz, "phase resonance");
    // The noise the phasors state (relative to the clean |X|), as the level's regeneration allowance.
    EXPECT_NEAR(l.regeneration_noise_relative_rms, kStatedRelativeStd, 1e-2 * kStatedRelativeStd);
    EXPECT_LT(l.regeneration_relative_rms, kRegenerationNoiseFactor * kStatedRelativeStd);
  }
  for (const auto& w : result.warnings) EXPECT_THAT(w, ::testing::Not(HasSubstr("flagged"))) << w;
}

TEST(MeasuredBackboneFlags, APeakAboveTheBandIsFlagged) {
  // 40 … 48.5 Hz: the band ends three half-power bandwidths below f_n.
  const MeasuredBackbone result =
      AnalyseMeasuredBackbone({Level("cut", {}, 1.0, 40.0, 48.5, kStatedRelativeStd, 3)});
  ASSERT_EQ(result.levels.size(), 1u);
  const LevelResonance& l = result.levels[0];
  EXPECT_TRUE(l.HasFlag(LevelFlagKind::kPeakOutsideBand)) << Flags(l);
  EXPECT_FALSE(l.HasFlag(LevelFlagKind::kDampingNotPositive)) << Flags(l);
  EXPECT_THAT(Flags(l), HasSubstr("48.5 Hz"));
  // The same sweep across the peak is not.
  EXPECT_FALSE(AnalyseMeasuredBackbone({Level("whole", {}, 1.0, 40.0, 55.0, kStatedRelativeStd, 3)})
                   .levels[0]
                   .HasFlag(LevelFlagKind::kPeakOutsideBand));
}

TEST(MeasuredBackboneFlags, NegativeDampingIsFlaggedNextToItsNumber) {
  const MeasuredBackbone result =
      AnalyseMeasuredBackbone({Level("unstable", {.damping_ratio = -kDampingRatio}, 1.0, 47.0, 53.0, 0.0, 4)});
  const LevelResonance& l = result.levels[0];
  ASSERT_TRUE(l.HasFlag(LevelFlagKind::kDampingNotPositive)) << Flags(l);
  ASSERT_TRUE(l.quadrature_damping_ratio.valid);
  EXPECT_LT(l.quadrature_damping_ratio.value, 0.0);
  EXPECT_EQ(l.FlagNote("quadrature_damping_ratio"), "[FLAG: not positive]");
  EXPECT_THAT(Flags(l), HasSubstr("phase-resonance damping ratio is -1"));
  EXPECT_EQ(l.FlagNote("regeneration_relative_rms").find("not positive"), std::string::npos);
}

TEST(MeasuredBackboneFlags, ANoisyLevelIsFlaggedAndLeftOutOfTheCrossLevelFitUnlessKept) {
  const std::vector<signal::FirstHarmonicLevel> levels = {
      Clean("low", 1.0, 5), Level("noisy", {}, 1.5, 47.0, 53.0, 0.3, 6), Clean("high", 2.0, 7)};
  const MeasuredBackbone result = AnalyseMeasuredBackbone(levels);
  ASSERT_TRUE(result.fit.ok);
  const LevelResonance& noisy = result.levels[1];
  EXPECT_TRUE(noisy.HasFlag(LevelFlagKind::kRegenerationBeyondNoise)) << Flags(noisy);
  EXPECT_GT(noisy.regeneration_relative_rms, 0.1);
  EXPECT_FALSE(noisy.in_global_fit);
  int fitted_points = 0;
  for (const auto& l : result.levels) {
    if (&l == &noisy) continue;
    EXPECT_TRUE(l.flags.empty()) << l.label << ": " << Flags(l);
    EXPECT_TRUE(l.in_global_fit) << l.label;
    fitted_points += l.num_fit_points;
  }
  // Only the clean levels' points are in the cross-level fit, which then gives ζ.
  EXPECT_EQ(result.fit.num_residuals, 2 * fitted_points);
  const double a = 0.5 * (result.min_amplitude_m + result.max_amplitude_m);
  EXPECT_LE(std::abs(result.fit.DampingRatio(a) - kDampingRatio), kSigmas * result.fit.DampingRatioStd(a));
  EXPECT_TRUE(std::any_of(result.warnings.begin(), result.warnings.end(), [](const std::string& w) {
    return w.find("level 'noisy' is flagged") != std::string::npos && w.find("left out") != std::string::npos;
  }));

  const MeasuredBackbone kept = AnalyseMeasuredBackbone(levels, {.keep_flagged_levels_in_fit = true});
  EXPECT_TRUE(kept.levels[1].HasFlag(LevelFlagKind::kRegenerationBeyondNoise)) << Flags(kept.levels[1]);
  int all_points = 0;
  for (const auto& l : kept.levels) {
    EXPECT_TRUE(l.in_global_fit) << l.label;
    all_points += l.num_fit_points;
  }
  EXPECT_EQ(kept.fit.num_residuals, 2 * all_points);
}

// A flagged level kept in the fit changes the fit, not the damping trend's
// verdict, which is the one judged with the flagged levels left out; with
// fewer than two clean levels there is no verdict, and the note says why.
TEST(MeasuredBackboneFlags, TheDampingTrendIsJudgedOnlyOnLevelsThatPassed) {
  const std::vector<signal::FirstHarmonicLevel> levels = {
      Clean("low", 1.0, 5), Level("noisy", {}, 1.5, 47.0, 53.0, 0.3, 6), Clean("high", 2.0, 7)};
  const MeasuredBackbone left_out = AnalyseMeasuredBackbone(levels);
  const MeasuredBackbone kept = AnalyseMeasuredBackbone(levels, {.keep_flagged_levels_in_fit = true});
  ASSERT_TRUE(kept.levels[1].in_global_fit);
  ASSERT_NE(left_out.damping_trend.verdict, Trend::kNotJudged);
  EXPECT_EQ(kept.damping_trend.verdict, left_out.damping_trend.verdict);
  EXPECT_EQ(kept.damping_trend.damping_ratio_verdict, left_out.damping_trend.damping_ratio_verdict);
  EXPECT_EQ(kept.damping_trend.damping_rate_z, left_out.damping_trend.damping_rate_z);
  EXPECT_EQ(kept.damping_trend.note, "");
  // The fit itself does hold the flagged level.
  EXPECT_NE(kept.fit.num_residuals, left_out.fit.num_residuals);

  const MeasuredBackbone one_clean = AnalyseMeasuredBackbone({levels[0], levels[1]});
  EXPECT_EQ(one_clean.damping_trend.verdict, Trend::kNotJudged);
  EXPECT_EQ(one_clean.damping_trend.damping_ratio_verdict, Trend::kNotJudged);
  EXPECT_THAT(one_clean.damping_trend.note, HasSubstr("not enough clean levels: 1 of 2 passed their checks"));
}

TEST(MeasuredBackboneFlags, TwoModesInTheWindowAreBeyondOneModesRegeneration) {
  const MeasuredBackbone result =
      AnalyseMeasuredBackbone({Level("two modes", {.second_mode_hz = 51.0}, 1.0, 47.0, 54.0, kStatedRelativeStd, 8)});
  EXPECT_TRUE(result.levels[0].HasFlag(LevelFlagKind::kRegenerationBeyondNoise)) << Flags(result.levels[0]);
}

TEST(MeasuredBackboneFlags, TheRegenerationThresholdIsValidated) {
  for (double bad : {0.0, -0.1, std::nan("")}) {
    const std::string message = beamid::testing::InputErrorOf(
        [&] { MeasuredBackboneOptions{.max_regeneration_relative_rms = bad}.Validate(); });
    EXPECT_THAT(message, HasSubstr("max_regeneration_relative_rms"));
  }
}

TEST(MeasuredBackboneCommand, RefusesAnOutputThatIsAnInputTableBeforeReadingIt) {
  const std::filesystem::path program = BEAMID_EXECUTABLE;  // tests/CMakeLists.txt
  const auto folder = beamid::testing::UniqueTempPath("measured_backbone_flags_test");
  std::filesystem::create_directories(folder);
  // Not a valid table: were it read first, the error would be about its columns.
  const auto table = folder / "high.csv";
  std::ofstream(table) << "not a table\n";
  const auto log = folder / "run.log";
  for (const std::string& output : {table.string(), (folder / "." / "high.csv").string(), (folder / "high").string()}) {
    SCOPED_TRACE(output);
    const std::string command = program.string() + " backbone --measured " + table.string() + " -o " + output +
                                " > " + log.string() + " 2>&1";
    const int status = std::system(command.c_str());
    std::stringstream text;
    text << std::ifstream(log).rdbuf();
    EXPECT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 2) << text.str();
    EXPECT_THAT(text.str(), HasSubstr("is also an input of this command"));
  }
  std::stringstream content;
  content << std::ifstream(table).rdbuf();
  EXPECT_EQ(content.str(), "not a table\n");
  std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace beamid::solver
