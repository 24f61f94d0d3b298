// The model-free measured backbone on campaigns of the independent
// time-domain simulator (hb/stepped_sine): the paper's set-up with the base
// physics and with a concealed Jenkins friction element, 3 force levels ×
// 15 steps around the resonance each, simulated once for the whole binary.
// The measured backbone is compared with the harmonic-balance backbone of the
// TRUE parameters (an independent method: nothing of it enters the analysis),
// and first-harmonic tables written from the campaign's phasors in an
// acquisition system's variants must give the same results.
#include "solver/backbone/measured_backbone.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "hb/campaign_writer.h"
#include "hb/scenario.h"
#include "hb/stepped_sine.h"
#include "signal/campaign.h"
#include "signal/campaign_extractor.h"
#include "signal/first_harmonic_level.h"
#include "signal/phasor_table.h"
#include "signal/quantity_conversion.h"
#include "solver/estimation/sensor_backbone.h"
#include "tests/support/temp_path.h"

namespace beamid::solver {
namespace {

constexpr double kSensorPosition_m = 0.3;  // acc2: near the first mode's largest motion
constexpr double kAgreementSigmas = 3.0;   // a measured point within 3 σ of the true backbone
constexpr double kTrendSigmas = 3.0;       // a significant damping trend

std::string Scenario(const std::string& support, const std::string& timing) {
  return R"({
  "name": "measured backbone test",
  "beam": {"length_m": 0.6, "width_m": 0.04, "thickness_m": 0.005, "youngs_modulus_Pa": 2.1e11,
           "density_kg_m3": 7850, "loss_factor": 0.0002},
  "support": )" + support + R"(,
  "excitation": {"channel": "force", "position_m": 0.57},
  "sensors": [{"channel": "acc2", "position_m": 0.3}, {"channel": "acc3", "position_m": 0.57}],
  "levels": [{"label": "low", "force_amplitude_N": 1.0, "frequencies_Hz": {"start": 52.0, "stop": 56.2, "step": 0.3}},
             {"label": "mid", "force_amplitude_N": 4.0, "frequencies_Hz": {"start": 52.0, "stop": 56.2, "step": 0.3}},
             {"label": "high", "force_amplitude_N": 9.0, "frequencies_Hz": {"start": 52.0, "stop": 56.2, "step": 0.3}}],
  "timing": )" + timing + R"(,
  "noise": {"seed": 11, "clock_offset_ppm": 25,
            "default": {"relative_rms": 0.003, "absolute": 0.005, "adc_bits": 24, "adc_range": 500},
            "channels": {"force": {"relative_rms": 0.002, "absolute": 0.002, "adc_bits": 24, "adc_range": 50}}}
})";
}

const std::string kBaseSupport =
    R"({"polynomial": {"k1_Nm_rad": 150, "k2_Nm_rad2": 0, "k3_Nm_rad3": 3e5, "c_Nms_rad": 0.05}})";
const std::string kFrictionSupport =
    R"({"polynomial": {"k1_Nm_rad": 100, "k2_Nm_rad2": 0, "k3_Nm_rad3": 3e5, "c_Nms_rad": 0.05},
        "jenkins": {"stiffness_Nm_rad": 50, "slip_moment_Nm": 0.15}})";
const std::string kBaseTiming =
    R"({"sample_rate_Hz": 5120, "settle_min_s": 0.2, "settle_max_s": 4.0, "transient_s": 0.05, "record_s": 0.4})";
const std::string kFrictionTiming =
    R"({"sample_rate_Hz": 5120, "max_time_step_s": 9.765625e-06, "settle_min_s": 0.5, "settle_max_s": 4.0,
        "settle_tolerance": 0.0005, "transient_s": 0.05, "record_s": 0.4})";

struct SimulatedCase {
  hb::Scenario scenario;
  std::vector<signal::FirstHarmonicLevel> levels;  // acc2
  MeasuredBackbone measured;
  std::vector<SensorBackbonePoint> truth_backbone;
};

SimulatedCase Simulate(const std::string& support, const std::string& timing, const std::filesystem::path& folder) {
  SimulatedCase c{.scenario = hb::ParseScenario(Scenario(support, timing), "measured_backbone_slow_test scenario")};
  std::filesystem::remove_all(folder);
  {
    hb::SteppedSineSimulation simulation(c.scenario);
    hb::CampaignWriter writer(simulation, folder);
    simulation.Run([&](const hb::SimulatedStep& step) { writer.Write(step); });
    writer.Finish();
  }
  signal::ExtractOptions extract;
  extract.estimator.num_harmonics = 3;
  const signal::PhasorSet phasors = signal::ExtractCampaign(signal::ReadCampaign(folder), extract);
  std::filesystem::remove_all(folder);
  c.levels = signal::FirstHarmonicLevels(phasors, "acc2", "campaign");
  c.measured = AnalyseMeasuredBackbone(c.levels);
  const auto law = c.scenario.MakeSupportLaw();
  c.truth_backbone = ModelBackboneAtSensor({.beam = c.scenario.beam, .attachments = c.scenario.TrueAttachments()}, *law,
                                           c.scenario.force_position_m, kSensorPosition_m,
                                           {.min_theta_amplitude_rad = 1e-4, .max_theta_amplitude_rad = 2e-2, .num_points = 120});
  return c;
}

class MeasuredBackboneOnSimulatedCampaigns : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const auto folder = beamid::testing::UniqueTempPath("beamid_measured_backbone_slow_test");
    base_ = new SimulatedCase(Simulate(kBaseSupport, kBaseTiming, folder.string() + "_base"));
    friction_ = new SimulatedCase(Simulate(kFrictionSupport, kFrictionTiming, folder.string() + "_friction"));
  }
  static void TearDownTestSuite() {
    delete base_;
    delete friction_;
  }
  static SimulatedCase* base_;
  static SimulatedCase* friction_;
};

SimulatedCase* MeasuredBackboneOnSimulatedCampaigns::base_ = nullptr;
SimulatedCase* MeasuredBackboneOnSimulatedCampaigns::friction_ = nullptr;

void Print(const char* name, const MeasuredBackbone& m) {
  for (const auto& l : m.levels)
    std::printf(
        "%s %-4s (%s-controlled): f_q = %.4f ± %.4f Hz at |X_d| = %.4e ± %.1e m; zeta: quadrature %.5f ± %.5f, "
        "local %.5f ± %.5f (chi2_r %.3g), half-power %.5f ± %.5f; regeneration rms %.2f %%\n",
        name, l.label.c_str(), std::string(LevelControlName(l.control)).c_str(), l.quadrature_frequency_hz.value,
        l.quadrature_frequency_hz.std, l.quadrature_amplitude_m.value, l.quadrature_amplitude_m.std,
        l.quadrature_damping_ratio.value, l.quadrature_damping_ratio.std, l.local_damping_ratio.value,
        l.local_damping_ratio.std, l.local_reduced_chi_square, l.half_power_damping_ratio.value, l.half_power_damping_ratio.std,
        100 * l.regeneration_relative_rms);
  for (const auto& l : m.levels)
    for (const auto& f : l.flags)
      std::printf("%s %-4s flag %s: %s%s\n", name, l.label.c_str(), std::string(LevelFlagName(f.kind)).c_str(),
                  f.message.c_str(), l.in_global_fit ? "" : " (left out of the fit)");
  std::printf("%s global fit: %s, reduced chi-square %.3g; damping slope %.4g ± %.3g /m (z = %.2f, %s); damping "
              "rate slope %.4g ± %.3g /(s m) (z = %.2f): %s\n",
              name, m.fit.FormName().c_str(), m.fit.ReducedChiSquare(), m.damping_trend.slope_per_m,
              m.damping_trend.slope_std_per_m, m.damping_trend.z, std::string(schema::NameOf(m.damping_trend.damping_ratio_verdict, kDampingRatioTrendNames)).c_str(),
              m.damping_trend.damping_rate_slope_per_s_m, m.damping_trend.damping_rate_slope_std_per_s_m,
              m.damping_trend.damping_rate_z, std::string(schema::NameOf(m.damping_trend.verdict, kDampingRateTrendNames)).c_str());
  // The best candidate of the other family, to see how close the choice was.
  const BackboneModelCandidate* other = nullptr;
  const bool chosen_power = m.fit.frequency_exponent > 0 || m.fit.damping_exponent > 0;
  for (const auto& c : m.candidates)
    if ((c.frequency_exponent > 0 || c.damping_exponent > 0) != chosen_power && (!other || c.aicc < other->aicc)) other = &c;
  if (other)
    std::printf("%s best %s candidate: %s, AICc %+.1f from the chosen\n", name, chosen_power ? "polynomial" : "power-law",
                other->form.c_str(), other->aicc - m.fit.aicc);
}

// Measured phase resonance against the true model's backbone at the same amplitude, in σ.
void ExpectAgreementWithTrueBackbone(const char* name, const SimulatedCase& c) {
  Print(name, c.measured);
  for (const auto& l : c.measured.levels) {
    ASSERT_TRUE(l.quadrature_frequency_hz.valid) << name << " " << l.label;
    const double a = l.quadrature_amplitude_m.value;
    const double f_true = BackboneFrequencyAt_hz(c.truth_backbone, a);
    ASSERT_TRUE(std::isfinite(f_true)) << name << " " << l.label << ": amplitude " << a << " outside the model backbone";
    const double slope = (BackboneFrequencyAt_hz(c.truth_backbone, 1.01 * a) - BackboneFrequencyAt_hz(c.truth_backbone, 0.99 * a)) /
                         (0.02 * a);
    const double sigma = std::hypot(l.quadrature_frequency_hz.std, slope * l.quadrature_amplitude_m.std);
    const double z = (l.quadrature_frequency_hz.value - f_true) / sigma;
    std::printf("%s %-4s: measured %.4f Hz, true backbone %.4f Hz at that amplitude: %+.2f σ (σ = %.4f Hz); local fit %.4f ± %.4f Hz\n", name,
                l.label.c_str(), l.quadrature_frequency_hz.value, f_true, z, sigma, l.local_natural_frequency_hz.value, l.local_natural_frequency_hz.std);
    EXPECT_LT(std::abs(z), kAgreementSigmas) << name << " level " << l.label;
  }
}

TEST_F(MeasuredBackboneOnSimulatedCampaigns, BaseBackboneAgreesWithTheTrueModelsBackbone) {
  ExpectAgreementWithTrueBackbone("base", *base_);
}

TEST_F(MeasuredBackboneOnSimulatedCampaigns, FrictionBackboneAgreesWithTheTrueModelsBackbone) {
  ExpectAgreementWithTrueBackbone("friction", *friction_);
}

TEST_F(MeasuredBackboneOnSimulatedCampaigns, FrictionDampingRisesWithAmplitudeBaseDampingDoesNot) {
  EXPECT_GT(friction_->measured.damping_trend.z, kTrendSigmas);
  EXPECT_EQ(friction_->measured.damping_trend.verdict, Trend::kRises);
  EXPECT_LT(base_->measured.damping_trend.z, kTrendSigmas);
  EXPECT_NE(base_->measured.damping_trend.verdict, Trend::kRises);
}

// A level written as an acquisition system's table: response converted to
// `quantity` and scaled to `unit_si` per written unit, phase in degrees or
// radians, optional polar uncertainties, `;` with decimal commas or `,`.
std::string WriteTable(const signal::FirstHarmonicLevel& level, signal::Quantity quantity, const std::string& header,
                       double unit_si, bool degrees, bool uncertainties, bool decimal_comma) {
  std::ostringstream out;
  out << header << "\n";
  const char separator = decimal_comma ? ';' : ',';
  const double phase_unit = degrees ? 180 / std::numbers::pi : 1.0;
  for (const auto& p : level.points) {
    const auto x = signal::ConvertHarmonic(p.response, level.response_quantity, quantity, 2 * std::numbers::pi * p.frequency_hz);
    const double phase = std::arg(x.value / p.force.value);
    std::ostringstream cells;
    cells.precision(12);
    cells << p.frequency_hz << separator << std::abs(p.force.value) << separator << x.Amplitude() / unit_si << separator
          << phase * phase_unit;
    if (uncertainties)
      cells << separator << p.force.std_real << separator << x.AmplitudeStd() / unit_si << separator
            << x.PhaseStdRad() * phase_unit << separator << p.frequency_std_hz;
    std::string row = cells.str();
    if (decimal_comma)
      for (auto& c : row)
        if (c == '.') c = ',';
    out << row << "\n";
  }
  return out.str();
}

// The same curve as a response-controlled test would give it near a linear
// mode: every step scaled so that the displacement amplitude is the peak's
// (G = F/X unchanged), as a controller holding the response would.
signal::FirstHarmonicLevel HeldAtItsPeak(signal::FirstHarmonicLevel level) {
  for (auto& p : level.points)
    p.response = signal::ConvertHarmonic(p.response, level.response_quantity, signal::Quantity::kDisplacement,
                                         2 * std::numbers::pi * p.frequency_hz);
  level.response_quantity = signal::Quantity::kDisplacement;
  double peak = 0;
  for (const auto& p : level.points) peak = std::max(peak, p.response.Amplitude());
  for (auto& p : level.points) {
    const double s = peak / p.response.Amplitude();
    p.force.value *= s;
    p.force.SetCovariance(s * s * p.force.Covariance());
    p.response.value *= s;
    p.response.SetCovariance(s * s * p.response.Covariance());
  }
  return level;
}

void ExpectSameEstimate(const Estimate& table, const Estimate& campaign, double std_tolerance, const std::string& what) {
  ASSERT_TRUE(table.valid && campaign.valid) << what;
  // The weights of the fits differ a little (polar uncertainties): a small fraction of σ.
  EXPECT_NEAR(table.value, campaign.value, 0.05 * campaign.std) << what;
  EXPECT_NEAR(table.std, campaign.std, std_tolerance * campaign.std) << what;
}

TEST_F(MeasuredBackboneOnSimulatedCampaigns, TablesInAcquisitionSystemVariantsGiveTheCampaignsResults) {
  constexpr double kG = 9.80665;
  std::vector<signal::FirstHarmonicLevel> comma_g, velocity;
  for (const auto& level : base_->levels) {
    comma_g.push_back(signal::ParsePhasorTable(
        WriteTable(level, signal::Quantity::kAcceleration,
                   "Frequency [Hz];Force [N];Acceleration [g];Phase [deg];Force_std [N];Acceleration_std [g];Phase_std [deg];Frequency_std [Hz]",
                   kG, true, true, true),
        level.label + "_g.csv", level.label));
    velocity.push_back(signal::ParsePhasorTable(
        WriteTable(level, signal::Quantity::kVelocity, "freq_Hz,F_amp_N,vel_mm_s,phase_rad,std_F_N,std_vel_mm_s,std_phase_rad,std_freq_Hz",
                   1e-3, false, true, false),
        level.label + "_vel.csv", level.label));
  }
  const MeasuredBackbone from_comma_g = AnalyseMeasuredBackbone(comma_g);
  const MeasuredBackbone from_velocity = AnalyseMeasuredBackbone(velocity);
  // Polar uncertainties lose a little of the Re/Im correlation of the extracted phasors: stds agree to 10 %.
  constexpr double kStdTolerance = 0.10;
  for (std::size_t l = 0; l < base_->levels.size(); ++l) {
    const auto& c = base_->measured.levels[l];
    for (const auto* t : {&from_comma_g.levels[l], &from_velocity.levels[l]}) {
      ExpectSameEstimate(t->quadrature_frequency_hz, c.quadrature_frequency_hz, kStdTolerance, c.label + " frequency");
      ExpectSameEstimate(t->quadrature_amplitude_m, c.quadrature_amplitude_m, kStdTolerance, c.label + " amplitude");
      ExpectSameEstimate(t->quadrature_damping_ratio, c.quadrature_damping_ratio, kStdTolerance, c.label + " zeta");
      ExpectSameEstimate(t->local_damping_ratio, c.local_damping_ratio, kStdTolerance, c.label + " local zeta");
    }
  }
  EXPECT_EQ(from_velocity.damping_trend.verdict, base_->measured.damping_trend.verdict);

  // Response-controlled, displacement in mm, no uncertainty columns.
  const signal::FirstHarmonicLevel held = HeldAtItsPeak(base_->levels.front());
  const MeasuredBackbone from_held = AnalyseMeasuredBackbone({signal::ParsePhasorTable(
      WriteTable(held, signal::Quantity::kDisplacement, "frequency,force [N],displacement [mm],phase (rad)", 1e-3, false,
                 false, false),
      "held.csv", "held")});
  const LevelResonance& h = from_held.levels.front();
  const LevelResonance& c = base_->measured.levels.front();
  EXPECT_EQ(h.control, LevelControl::kResponse);
  EXPECT_EQ(c.control, LevelControl::kForce);
  std::printf("response-controlled low level: %.4f ± %.4f Hz, zeta %.5f ± %.5f (campaign %.4f ± %.4f Hz, %.5f ± %.5f)\n",
              h.quadrature_frequency_hz.value, h.quadrature_frequency_hz.std, h.quadrature_damping_ratio.value,
              h.quadrature_damping_ratio.std, c.quadrature_frequency_hz.value, c.quadrature_frequency_hz.std,
              c.quadrature_damping_ratio.value, c.quadrature_damping_ratio.std);
  EXPECT_NEAR(h.quadrature_frequency_hz.value, c.quadrature_frequency_hz.value,
              3 * std::hypot(h.quadrature_frequency_hz.std, c.quadrature_frequency_hz.std));
  // Without uncertainty columns the σ comes from the fit's scatter; a broken
  // fit (terms the held level cannot tell apart) shows as a σ of many Hz.
  constexpr double kHeldRelativeStd = 1e-4;
  EXPECT_LT(h.quadrature_frequency_hz.std, kHeldRelativeStd * c.quadrature_frequency_hz.value);
  EXPECT_NEAR(h.local_damping_ratio.value, c.local_damping_ratio.value,
              3 * std::hypot(h.local_damping_ratio.std, c.local_damping_ratio.std));
}

}  // namespace
}  // namespace beamid::solver
