// What the response plots draw of measured phasors, against the closed form
// of a linear single-degree-of-freedom oscillator m ẍ + c ẋ + k x = F cos ωt:
// the receptance H(ω) = 1/(k − mω² + icω). Sensors of displacement, velocity
// and acceleration see (iω)^n H F; the plots show |X₁|, |X₁|/|F₁| (the
// channel's own quantity per unit force: (ω^n)|H|) and the phase of the
// displacement against the force, arg H, for every sensor alike — which
// crosses −90° at the undamped natural frequency √(k/m), whatever the damping.
#include <cmath>
#include <complex>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "signal/phasor_set.h"
#include "solver/report/report_curves.h"
#include "solver/report/response_plots.h"

namespace beamid::solver {
namespace {

using Complex = std::complex<double>;
constexpr double kPi = std::numbers::pi;

struct Oscillator {
  double mass_kg = 1.0;
  double natural_hz = 50.0;
  double damping_ratio = 0.03;
  double Stiffness() const { return mass_kg * std::pow(2 * kPi * natural_hz, 2); }
  double Damping() const { return 2 * damping_ratio * std::sqrt(Stiffness() * mass_kg); }
  Complex Receptance(double frequency_hz) const {
    const double w = 2 * kPi * frequency_hz;
    return 1.0 / Complex(Stiffness() - mass_kg * w * w, Damping() * w);
  }
};

constexpr double kForceN = 2.5;
const char* const kChannels[] = {"disp", "vel", "acc"};  // derivative orders 0, 1, 2
const signal::Quantity kQuantities[] = {signal::Quantity::kDisplacement, signal::Quantity::kVelocity,
                                        signal::Quantity::kAcceleration};

// Steps 45.1, 45.4, … 54.7 Hz: none at 50 Hz itself. The force phasor is
// real and positive, as the extraction references every step to it; the
// third harmonic is there, the second not (as after an extraction with H = 1
// would leave neither: absent entries must read as absent).
signal::PhasorSet Phasors(const Oscillator& oscillator, std::vector<double>& frequencies) {
  signal::PhasorSet set;
  for (int i = 0; i < 33; ++i) {
    const double f = 45.1 + 0.3 * i;
    frequencies.push_back(f);
    signal::StepPhasors step{.file = "L/step_" + std::to_string(i) + ".csv", .level = "L", .frequency_hz = f};
    step.force.channel = "force";
    step.force.harmonics = {{.harmonic = 1, .value = kForceN}};
    for (int order = 0; order <= 2; ++order) {
      signal::ChannelPhasors channel{.channel = kChannels[order], .quantity = kQuantities[order]};
      const Complex x = std::pow(Complex(0, 2 * kPi * f), order) * oscillator.Receptance(f) * kForceN;
      channel.harmonics = {{.harmonic = 1, .value = x}};
      step.responses.push_back(channel);
    }
    set.steps.push_back(step);
  }
  return set;
}

std::vector<ReportChannel> Channels() {
  std::vector<ReportChannel> channels;
  for (int order = 0; order <= 2; ++order)
    channels.push_back({.channel = kChannels[order], .derivative_order = order, .fitted = true});
  return channels;
}

TEST(ReportResponseRows, MeasuredAmplitudePerForceAndPhaseFollowTheOscillatorsClosedForm) {
  const Oscillator oscillator;
  std::vector<double> frequencies;
  const LevelCurves level = MeasuredLevelCurves(Phasors(oscillator, frequencies), Channels(), "L");
  ASSERT_EQ(level.measured.size(), frequencies.size());
  EXPECT_NEAR(level.force_amplitude_N, kForceN, 1e-12);
  for (std::size_t c = 0; c < 3; ++c) {
    const std::vector<ResponseRow> rows = MeasuredResponseRows(level, c);
    ASSERT_EQ(rows.size(), frequencies.size());
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const double f = frequencies[i], w = 2 * kPi * f;
      const Complex h = oscillator.Receptance(f);
      const double per_force = std::pow(w, static_cast<double>(c)) * std::abs(h);
      EXPECT_NEAR(rows[i][0], f, 1e-12);
      EXPECT_NEAR(rows[i][1], per_force * kForceN, 1e-9 * per_force * kForceN) << kChannels[c] << " " << f;
      EXPECT_NEAR(rows[i][2], per_force, 1e-9 * per_force) << kChannels[c] << " " << f;
      // arg H = −atan2(cω, k − mω²), in (−180°, 0°).
      const double phase =
          -std::atan2(oscillator.Damping() * w, oscillator.Stiffness() - oscillator.mass_kg * w * w) * 180.0 / kPi;
      EXPECT_NEAR(rows[i][3], phase, 1e-9) << kChannels[c] << " " << f;
      // Below resonance the displacement lags by less than 90°, above by more.
      if (f < oscillator.natural_hz) {
        EXPECT_GT(rows[i][3], -90.0) << kChannels[c] << " " << f;
      } else {
        EXPECT_LT(rows[i][3], -90.0) << kChannels[c] << " " << f;
      }
    }
    // The crossing of −90°, interpolated between the steps that bracket it,
    // lies at √(k/m) within the interpolation's error: at this damping the
    // phase is nearly linear over one 0.3 Hz step (here 49.9 … 50.2 Hz).
    int crossings = 0;
    for (std::size_t i = 1; i < rows.size(); ++i)
      if (rows[i - 1][3] > -90.0 && rows[i][3] <= -90.0) {
        ++crossings;
        const double t = (-90.0 - rows[i - 1][3]) / (rows[i][3] - rows[i - 1][3]);
        const double crossing = rows[i - 1][0] + t * (rows[i][0] - rows[i - 1][0]);
        EXPECT_NEAR(crossing, oscillator.natural_hz, 0.01) << kChannels[c];
      }
    EXPECT_EQ(crossings, 1) << kChannels[c];
  }
}

TEST(ReportResponseRows, HarmonicsTheExtractionDidNotHoldAreAbsentNotZero) {
  const Oscillator oscillator;
  std::vector<double> frequencies;
  signal::PhasorSet phasors = Phasors(oscillator, frequencies);
  // Harmonics 2 and 3 at one step of the acceleration channel only.
  phasors.steps[4].responses[2].harmonics.push_back({.harmonic = 2, .value = Complex(0.0, 0.02)});
  phasors.steps[4].responses[2].harmonics.push_back({.harmonic = 3, .value = Complex(-0.003, 0.004)});
  const LevelCurves level = MeasuredLevelCurves(phasors, Channels(), "L");
  EXPECT_NEAR(level.measured[4].higher_harmonics[2][0], 0.02, 1e-15);
  EXPECT_NEAR(level.measured[4].higher_harmonics[2][1], 0.005, 1e-15);
  EXPECT_TRUE(std::isnan(level.measured[3].higher_harmonics[2][0]));
  EXPECT_TRUE(std::isnan(level.measured[4].higher_harmonics[0][1]));
  ReportCurves curves;
  curves.channels = Channels();
  curves.levels = {level};
  EXPECT_TRUE(HasHigherHarmonics(curves, 2));
  EXPECT_FALSE(HasHigherHarmonics(curves, 0));
}

// The model's curve is drawn per unit of the level's force: a point of
// amplitude A under a level of force F is at A/F.
TEST(ReportResponseRows, TheModelCurveIsDividedByItsLevelsForce) {
  const Oscillator oscillator;
  LevelCurves level{.level = "L", .force_amplitude_N = kForceN};
  for (double f : {48.0, 50.0, 52.0}) {
    const Complex x = std::pow(Complex(0, 2 * kPi * f), 2) * oscillator.Receptance(f) * kForceN;
    level.model.push_back(
        {.frequency_hz = f, .amplitude = {std::abs(x)}, .phase_deg = {DisplacementPhaseDeg(x / kForceN, 2)}});
  }
  const std::vector<ResponseRow> rows = ModelResponseRows(level, 0);
  ASSERT_EQ(rows.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    const double w = 2 * kPi * rows[i][0];
    EXPECT_NEAR(rows[i][2], w * w * std::abs(oscillator.Receptance(rows[i][0])), 1e-9 * rows[i][2]);
  }
  EXPECT_NEAR(rows[1][3], -90.0, 1e-9);  // exactly at √(k/m)
  EXPECT_GT(rows[0][3], -90.0);
  EXPECT_LT(rows[2][3], -90.0);
}

TEST(ReportResponseRows, ThePhaseIsWrappedIntoOneTurn) {
  EXPECT_NEAR(DisplacementPhaseDeg(Complex(-1.0, 0.0), 0), 180.0, 1e-12);  // (−180°, 180°]
  EXPECT_NEAR(DisplacementPhaseDeg(Complex(0.0, 1.0), 2), -90.0, 1e-12);   // 90° − 180°
  EXPECT_NEAR(DisplacementPhaseDeg(Complex(0.0, -1.0), 2), 90.0, 1e-12);   // −90° − 180° + 360°
  EXPECT_NEAR(DisplacementPhaseDeg(Complex(1.0, 0.0), 1), -90.0, 1e-12);
}

}  // namespace
}  // namespace beamid::solver
