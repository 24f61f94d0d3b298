// A record whose excitation stops before it ends, from the independent
// time-domain simulator (hb/stepped_sine): a clamped–pinned beam whose
// support adds nothing (k1 = 0, no damper) and whose first mode has the
// modal damping ratio ζ = 0.003, so the truth is that ratio exactly. The
// steady-state estimators of the measured backbone, read on the driven
// part, and the free decay after the stop (signal/free_decay.h) must each
// hold it within three of their stated σ, the decay's ringing frequency the
// mode's damped one, and the shaker's switch-off must not refuse a step;
// the only flag is the half-power natural frequency's, which the other
// modes' share skews beyond its σ.
// The record rings down for 2.8 s after 1.2 s of steady drive.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "hb/scenario.h"
#include "signal/campaign.h"
#include "signal/campaign_extractor.h"
#include "signal/first_harmonic_level.h"
#include "signal/phasor_set_io.h"
#include "solver/backbone/measured_backbone.h"
#include "tests/support/simulated_campaign.h"
#include "tests/support/temp_path.h"

namespace beamid::solver {
namespace {

constexpr double kZeta = 0.003;
constexpr double kSigmas = 3.0;

const char* const kScenario = R"({
  "name": "free decay test",
  "beam": {"length_m": 0.6, "width_m": 0.04, "thickness_m": 0.005, "youngs_modulus_Pa": 2.1e11,
           "density_kg_m3": 7850, "loss_factor": 0},
  "support": {"polynomial": {"k1_Nm_rad": 0, "k2_Nm_rad2": 0, "k3_Nm_rad3": 0, "c_Nms_rad": 0}},
  "damping": {"modal_damping_ratios": [0.003]},
  "excitation": {"channel": "force", "position_m": 0.57},
  "sensors": [{"channel": "acc2", "position_m": 0.3}, {"channel": "acc3", "position_m": 0.57}],
  "levels": [{"label": "only", "force_amplitude_N": 0.5, "frequencies_Hz": {"start": 50.25, "stop": 51.35, "step": 0.05}}],
  "timing": {"sample_rate_Hz": 5120, "settle_min_s": 0.5, "settle_max_s": 10.0, "settle_tolerance": 1e-5,
             "transient_s": 0.05, "record_s": 4.0, "excitation_stop_fraction": 0.3},
  "noise": {"seed": 3, "default": {"relative_rms": 0.002, "absolute": 0.002, "adc_bits": 24, "adc_range": 500},
            "channels": {"force": {"relative_rms": 0.002, "absolute": 0.0005, "adc_bits": 24, "adc_range": 50}}}
})";

// The clamped–pinned Euler–Bernoulli beam's first natural frequency: λ₁ = 3.92660231 (tan λ = tanh λ).
double ClampedPinnedFirstFrequency_hz(const hb::Scenario& s) {
  const auto& b = s.beam;
  const double ei = b.youngs_modulus_Pa * b.width_m * std::pow(b.thickness_m, 3) / 12.0;
  const double rho_a = b.density_kg_m3 * b.width_m * b.thickness_m;
  const double lambda = 3.92660231;
  return lambda * lambda / (2.0 * std::numbers::pi * b.length_m * b.length_m) * std::sqrt(ei / rho_a);
}

TEST(FreeDecayOnASimulatedCampaign, SteadyStateAndDecayDampingHoldTheModalRatio) {
  const hb::Scenario scenario = hb::ParseScenario(kScenario, "free decay scenario");
  const auto folder = beamid::testing::UniqueTempPath("beamid_free_decay");
  std::filesystem::remove_all(folder);
  beamid::testing::SimulateInto(scenario, folder);
  const signal::PhasorSet phasors = signal::ExtractCampaign(signal::ReadCampaign(folder), {});
  // The phasors file keeps every ring-down.
  signal::WritePhasorSetJson(phasors, folder / "phasors.json");
  const signal::PhasorSet read = signal::ReadPhasorSetJson(folder / "phasors.json");
  std::filesystem::remove_all(folder);

  ASSERT_TRUE(phasors.skipped.empty()) << phasors.skipped.front().reason;
  ASSERT_EQ(phasors.steps.size(), 23u);
  ASSERT_EQ(read.steps.size(), phasors.steps.size());
  const double f1 = ClampedPinnedFirstFrequency_hz(scenario);
  const double f_d = f1 * std::sqrt(1.0 - kZeta * kZeta);
  double sum_z2 = 0.0;
  int windows = 0, beyond = 0;
  for (std::size_t s = 0; s < phasors.steps.size(); ++s) {
    const signal::StepPhasors& step = phasors.steps[s];
    SCOPED_TRACE(step.file);
    for (const std::string& w : step.quality.warnings) EXPECT_EQ(w.find("spike"), std::string::npos) << w;
    // Both responses ring down in every step, acc3 (3 cm from the pin)
    // with more of the higher modes the switch-off starts beside the first.
    ASSERT_EQ(step.free_decays.size(), 2u);
    ASSERT_EQ(read.steps[s].free_decays.size(), step.free_decays.size());
    for (std::size_t c = 0; c < step.free_decays.size(); ++c) {
      const signal::FreeDecay& decay = step.free_decays[c];
      EXPECT_EQ(read.steps[s].free_decays[c].points.size(), decay.points.size());
      EXPECT_EQ(read.steps[s].free_decays[c].points.front().damping_ratio, decay.points.front().damping_ratio);
      ASSERT_GE(decay.points.size(), 5u) << decay.channel;
      for (const signal::DecayPoint& p : decay.points) {
        const double z = (p.damping_ratio - kZeta) / p.damping_ratio_std;
        sum_z2 += z * z;
        beyond += std::abs(z) > kSigmas;
        ++windows;
        // The FE model's first frequency lies within 1e-5 of the closed form's.
        EXPECT_LT(std::abs(p.frequency_hz - f_d), kSigmas * p.frequency_std_hz + 1e-5 * f1) << decay.channel;
      }
    }
  }
  // Each window's ζ within its σ as often as a σ promises: the higher modes
  // left in the residual are counted as noise, not hidden.
  const double rms_z = std::sqrt(sum_z2 / windows);
  std::printf("%d windows: rms z %.3f, %d beyond 3 σ\n", windows, rms_z, beyond);
  EXPECT_GT(windows, 500);
  EXPECT_LT(rms_z, 1.25);
  EXPECT_LE(beyond, windows / 100);

  const auto levels = signal::FirstHarmonicLevels(phasors, "acc2", "campaign");
  const MeasuredBackbone measured = AnalyseMeasuredBackbone(levels);
  ASSERT_EQ(measured.levels.size(), 1u);
  const LevelResonance& l = measured.levels.front();
  std::printf("f1 %.5f Hz; ζ: phase resonance %.6f ± %.2g, local %.6f ± %.2g, half-power %.6f ± %.2g, free decay "
              "%.6f ± %.2g (step %.3f Hz, %zu windows)\n",
              f1, l.quadrature_damping_ratio.value, l.quadrature_damping_ratio.std, l.local_damping_ratio.value,
              l.local_damping_ratio.std, l.half_power_damping_ratio.value, l.half_power_damping_ratio.std,
              l.free_decay_damping_ratio.value, l.free_decay_damping_ratio.std, l.free_decay_step_frequency_hz,
              l.free_decay.size());
  for (const Estimate* e : {&l.quadrature_damping_ratio, &l.local_damping_ratio, &l.half_power_damping_ratio,
                            &l.free_decay_damping_ratio}) {
    ASSERT_TRUE(e->valid);
    EXPECT_LT(std::abs(e->value - kZeta), kSigmas * e->std) << e->value << " ± " << e->std;
  }
  // The ring-down of the step nearest the phase resonance.
  for (const signal::FirstHarmonicPoint& p : levels.front().points)
    EXPECT_LE(std::abs(l.free_decay_step_frequency_hz - l.quadrature_frequency_hz.value),
              std::abs(p.frequency_hz - l.quadrature_frequency_hz.value) + 1e-12);
  // The flags: the half-power natural frequency, which the other modes'
  // share at the sensor skews (predicted +0.12 mHz ± 0.02; it lies +0.16 mHz,
  // 17 σ, off the mode's), and rightly so: it misses the mode's by more
  // than its σ allows. The same skew of the peak frequency is predicted at
  // +0.028 mHz ± 0.012, at the flag's threshold of twice its uncertainty:
  // one processor's floating point puts it above, another's below, so it
  // may be flagged too, as a frequency's skew and never as a ζ's (every ζ
  // meets the truth, above).
  ASSERT_FALSE(l.flags.empty());
  for (const LevelFlag& flag : l.flags) {
    EXPECT_EQ(flag.kind, LevelFlagKind::kNonlinearCurve) << flag.message;
    EXPECT_TRUE(flag.quantity == "half_power_natural_frequency" || flag.quantity == "peak_frequency")
        << flag.message;
  }
  EXPECT_TRUE(std::any_of(l.flags.begin(), l.flags.end(),
                          [](const LevelFlag& f) { return f.quantity == "half_power_natural_frequency"; }));
  EXPECT_GT(std::abs(l.half_power_natural_frequency_hz.value - f1), kSigmas * l.half_power_natural_frequency_hz.std);
}

}  // namespace
}  // namespace beamid::solver
