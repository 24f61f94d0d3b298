// The time-domain simulator against independent references: the exact
// dynamic-stiffness beam (hb/linear_beam.h) for linear steady states, its own
// result at half the time step, and the closed-form energy a Jenkins element
// dissipates per cycle.
#include "hb/time_simulator.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "hb/linear_beam.h"
#include "hb/support_law.h"
#include "hb/time_harmonic_fit.h"

namespace beamid::hb {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kReceptanceTolerance = 5e-3;   // 0.5 %
constexpr double kTimeStepTolerance = 1e-3;     // 0.1 %
constexpr int kHarmonics = 5;

const std::vector<double> kSensors{0.100, 0.300, 0.570};

TimeSimulatorModel PaperModel(double loss_factor) {
  TimeSimulatorModel model;
  model.beam.loss_factor = loss_factor;
  model.force_position_m = 0.570;
  model.output_positions_m = kSensors;
  return model;
}

struct SteadyState {
  std::vector<Eigen::VectorXcd> acceleration;  // per sensor, X_0..X_5 [m/s²]
  Eigen::VectorXcd theta;                      // X_0..X_5 [rad]
  double max_moment_Nm = 0.0;
  double loop_area_J = 0.0;        // ∮ M dθ over the last fitted period
  double theta_range_rad = 0.0;    // θ_max − θ_min over that period
  double slider_travel_rad = 0.0;  // range of the law's first state over it
};

// Drives F(t) = F·cos ωt from rest for settle_s, then fits `periods` periods
// sampled at every time step (phasors referenced to the force, phase 0).
SteadyState Simulate(TimeSimulator& sim, double force_N, double frequency_hz, double settle_s, int periods = 4) {
  const double omega = 2 * kPi * frequency_hz;
  const double dt = sim.time_step_s();
  sim.Reset(force_N);
  long step = 0;
  auto advance = [&] {
    ++step;
    sim.Advance(force_N * std::cos(omega * dt * static_cast<double>(step)));
  };
  const long settle_steps = std::lround(settle_s / dt);
  while (step < settle_steps) advance();
  TimeHarmonicFit fit(kHarmonics, static_cast<int>(kSensors.size()) + 1);
  Eigen::VectorXd y(kSensors.size()), v(kSensors.size()), a(kSensors.size());
  SteadyState out;
  const long fit_steps = std::lround(periods / (frequency_hz * dt));
  const long last_period_start = fit_steps - std::lround(1.0 / (frequency_hz * dt));
  double theta_min = 1e300, theta_max = -1e300, slider_min = 1e300, slider_max = -1e300;
  for (long i = 0; i < fit_steps; ++i) {
    const double theta_before = sim.SupportRotation_rad(), moment_before = sim.SupportMoment_Nm();
    advance();
    sim.Outputs(y, v, a);
    std::vector<double> values(a.data(), a.data() + a.size());
    values.push_back(sim.SupportRotation_rad());
    fit.Add(omega * dt * static_cast<double>(step), values);
    out.max_moment_Nm = std::max(out.max_moment_Nm, std::abs(sim.SupportMoment_Nm()));
    if (i >= last_period_start) {
      out.loop_area_J += 0.5 * (moment_before + sim.SupportMoment_Nm()) * (sim.SupportRotation_rad() - theta_before);
      theta_min = std::min(theta_min, sim.SupportRotation_rad());
      theta_max = std::max(theta_max, sim.SupportRotation_rad());
      if (!sim.state().law_state.empty()) {
        slider_min = std::min(slider_min, sim.state().law_state[0]);
        slider_max = std::max(slider_max, sim.state().law_state[0]);
      }
    }
  }
  auto phasors = fit.Solve();
  out.theta = phasors.back();
  phasors.pop_back();
  out.acceleration = std::move(phasors);
  out.theta_range_rad = theta_max - theta_min;
  out.slider_travel_rad = sim.state().law_state.empty() ? 0.0 : slider_max - slider_min;
  return out;
}

double RelativeError(std::complex<double> value, std::complex<double> reference) {
  return std::abs(value - reference) / std::abs(reference);
}

// Simulated fundamental accelerations against −ω²·(exact receptance).
void ExpectMatchesExactReceptance(const SteadyState& simulated, const LinearBeam& exact, double frequency_hz,
                                  double force_N) {
  const double omega = 2 * kPi * frequency_hz;
  const BeamDeflection deflection = exact.RespondToForce(omega);
  for (size_t s = 0; s < kSensors.size(); ++s) {
    const std::complex<double> expected = -omega * omega * force_N * deflection.Displacement_m(kSensors[s]);
    EXPECT_LT(RelativeError(simulated.acceleration[s](1), expected), kReceptanceTolerance)
        << "sensor at " << kSensors[s] << " m, " << frequency_hz << " Hz: simulated " << simulated.acceleration[s](1)
        << ", exact " << expected;
  }
  EXPECT_LT(RelativeError(simulated.theta(1), force_N * deflection.SupportRotation_rad()), kReceptanceTolerance);
}

TEST(TimeSimulatorTest, LinearSteadyStateMatchesExactReceptance) {
  // Structural damping matches E(1 + iη) exactly at ω_ref, so each frequency
  // sets ω_ref = ω; the support dashpot c is the same in both models.
  const double eta = 0.004, k1 = 150.0, c = 0.05;
  const PolynomialSupportLaw law({.k1_Nm_rad = k1, .c_Nms_rad = c});
  const LinearBeam exact(
      LinearBeamModel{.beam = PaperModel(eta).beam, .support_stiffness_Nm_rad = k1, .support_damping_Nms_rad = c},
      0.570);
  for (double frequency_hz : {30.0, 53.0, 54.2, 120.0, 260.0}) {
    SCOPED_TRACE(frequency_hz);
    TimeSimulator sim(PaperModel(eta), law, {.damping_reference_rad_s = 2 * kPi * frequency_hz});
    ExpectMatchesExactReceptance(Simulate(sim, 1.0, frequency_hz, 3.0), exact, frequency_hz, 1.0);
  }
}

TEST(TimeSimulatorTest, LinearSteadyStateWithAttachmentsMatchesExactReceptance) {
  // Clamp compliance, a laterally soft support and point masses; no material
  // damping (the dashpot alone), which both models represent identically.
  TimeSimulatorModel model = PaperModel(0.0);
  model.attachments.clamp_rotational_stiffness_Nm_rad = 3.0e4;
  model.attachments.support_translational_stiffness_N_m = 2.0e5;
  model.attachments.point_masses = {{0.570, 0.025}, {0.100, 0.012}};
  const double k1 = 150.0, c = 0.08;
  const PolynomialSupportLaw law({.k1_Nm_rad = k1, .c_Nms_rad = c});
  const LinearBeam exact(LinearBeamModel{.beam = model.beam,
                                         .attachments = model.attachments,
                                         .support_stiffness_Nm_rad = k1,
                                         .support_damping_Nms_rad = c},
                         0.570);
  const double f1_hz = exact.NaturalFrequencies_rad_s(1)[0] / (2 * kPi);
  for (double frequency_hz : {0.8 * f1_hz, f1_hz, 1.5 * f1_hz}) {
    SCOPED_TRACE(frequency_hz);
    TimeSimulator sim(model, law);
    ExpectMatchesExactReceptance(Simulate(sim, 1.0, frequency_hz, 3.0), exact, frequency_hz, 1.0);
  }
}

TEST(TimeSimulatorTest, RayleighDampedSteadyStateMatchesExactReceptance) {
  // C = α·M + β·K on the beam and its point masses against the exact beam's
  // ρA(ω² − iαω), m(ω² − iαω) and EI(1 + iβω); heavy enough damping that
  // leaving it out of the exact beam misses by far more than the tolerance.
  TimeSimulatorModel model = PaperModel(0.0);
  model.beam.rayleigh_mass_1_s = 2.0;
  model.beam.rayleigh_stiffness_s = 2e-6;
  model.attachments.point_masses = {{0.570, 0.025}, {0.300, 0.012}};
  const double k1 = 150.0, c = 0.02;
  const PolynomialSupportLaw law({.k1_Nm_rad = k1, .c_Nms_rad = c});
  LinearBeamModel exact_model{
      .beam = model.beam, .attachments = model.attachments, .support_stiffness_Nm_rad = k1, .support_damping_Nms_rad = c};
  const LinearBeam exact(exact_model, 0.570);
  exact_model.beam.rayleigh_mass_1_s = exact_model.beam.rayleigh_stiffness_s = 0.0;
  const LinearBeam without_rayleigh(exact_model, 0.570);
  const double f1_hz = exact.NaturalFrequencies_rad_s(1)[0] / (2 * kPi);
  for (double frequency_hz : {0.8 * f1_hz, f1_hz, 1.5 * f1_hz, 260.0}) {
    SCOPED_TRACE(frequency_hz);
    TimeSimulator sim(model, law);
    const SteadyState simulated = Simulate(sim, 1.0, frequency_hz, 3.0);
    ExpectMatchesExactReceptance(simulated, exact, frequency_hz, 1.0);
    if (frequency_hz == f1_hz) {
      const double omega = 2 * kPi * frequency_hz;
      EXPECT_GT(RelativeError(simulated.theta(1), without_rayleigh.RespondToForce(omega).SupportRotation_rad()),
                10 * kReceptanceTolerance);
    }
  }
}

TEST(TimeSimulatorTest, ModalDampingRatiosOfTwoModesActAsTheRayleighDampingThatGivesThem) {
  // ζ₁, ζ₂ given per mode; the Rayleigh α, β with the same ratios at ω₁, ω₂
  // (ζ_j = α/(2ω_j) + β·ω_j/2) in the exact beam. The modes are the beam's
  // without the support law, which here has no stiffness (a pinned end), so
  // they are the exact beam's; the third and higher modes differ (ζ₂ against
  // Rayleigh's), which near mode 1 is far below the tolerance.
  TimeSimulatorModel model = PaperModel(0.0);
  model.modal_damping_ratios = {1e-2, 5e-3};  // heavy: settled within the 3 s
  const PolynomialSupportLaw law({.k1_Nm_rad = 0.0});
  LinearBeamModel exact_model{.beam = model.beam};
  const std::vector<double> w = LinearBeam(exact_model, 0.570).NaturalFrequencies_rad_s(2);
  const double z1 = model.modal_damping_ratios[0], z2 = model.modal_damping_ratios[1];
  exact_model.beam.rayleigh_stiffness_s = 2.0 * (z2 * w[1] - z1 * w[0]) / (w[1] * w[1] - w[0] * w[0]);
  exact_model.beam.rayleigh_mass_1_s = 2.0 * z1 * w[0] - exact_model.beam.rayleigh_stiffness_s * w[0] * w[0];
  ASSERT_GT(exact_model.beam.rayleigh_mass_1_s, 0.0);
  ASSERT_GT(exact_model.beam.rayleigh_stiffness_s, 0.0);
  const LinearBeam exact(exact_model, 0.570);
  const double f1_hz = w[0] / (2 * kPi);
  for (double frequency_hz : {0.9 * f1_hz, f1_hz, 1.1 * f1_hz}) {
    SCOPED_TRACE(frequency_hz);
    TimeSimulator sim(model, law);
    ExpectMatchesExactReceptance(Simulate(sim, 1.0, frequency_hz, 3.0), exact, frequency_hz, 1.0);
  }
}

TEST(TimeSimulatorTest, RejectsAModalDampingRatioOutsideZeroToOne) {
  TimeSimulatorModel model = PaperModel(0.0);
  model.modal_damping_ratios = {1e-3, 1.5};
  EXPECT_THROW(TimeSimulator(model, PolynomialSupportLaw({.k1_Nm_rad = 150.0})), std::invalid_argument);
}

TEST(TimeSimulatorTest, HalvingTheTimeStepChangesHarmonicsLessThanTolerance) {
  // A strongly nonlinear polynomial support with even and odd terms, driven
  // below resonance (a single stable branch).
  const PolynomialSupportLaw law({.k1_Nm_rad = 150.0, .k2_Nm_rad2 = 2.0e4, .k3_Nm_rad3 = 3.0e7, .c_Nms_rad = 0.05});
  const double force_N = 10.0, frequency_hz = 50.0;
  TimeSimulator coarse(PaperModel(0.004), law, {.time_step_s = 1.0 / 51200.0});  // the default
  TimeSimulator fine(PaperModel(0.004), law, {.time_step_s = 1.0 / 102400.0});
  const SteadyState a = Simulate(coarse, force_N, frequency_hz, 5);
  const SteadyState b = Simulate(fine, force_N, frequency_hz, 5);
  // The test is only meaningful if the support is really nonlinear.
  ASSERT_GT(std::abs(b.theta(3)), 1e-3 * std::abs(b.theta(1)));
  ASSERT_GT(std::abs(b.theta(2)), 1e-3 * std::abs(b.theta(1)));
  for (size_t s = 0; s < kSensors.size(); ++s) {
    for (int k = 1; k <= kHarmonics; ++k) {
      // Harmonics below 0.1 % of the fundamental are judged against 1e-3 of it.
      const double scale = std::max(std::abs(b.acceleration[s](k)), 1e-3 * std::abs(b.acceleration[s](1)));
      EXPECT_LT(std::abs(a.acceleration[s](k) - b.acceleration[s](k)) / scale, kTimeStepTolerance)
          << "sensor " << s << ", harmonic " << k << ": " << a.acceleration[s](k) << " vs " << b.acceleration[s](k);
    }
  }
}

TEST(TimeSimulatorTest, JenkinsSticksAtLowLevelAndSlipsAtHighLevel) {
  const double stiffness = 150.0, slip_moment = 0.02;
  const JenkinsSupportLaw law({.stiffness_Nm_rad = stiffness, .slip_moment_Nm = slip_moment});
  // 50 Hz is 1024 steps of the default Δt, so the last period's loop closes;
  // η = 2 % lets the start-up transient die out within the settling time.
  const double frequency_hz = 50.0, eta = 0.02;
  TimeSimulator sim(PaperModel(eta), law, {.damping_reference_rad_s = 2 * kPi * frequency_hz});

  // Low level: sticks, so the beam is the linear one with k1 = k_t and no loss.
  const double low_N = 0.05;
  const SteadyState low = Simulate(sim, low_N, frequency_hz, 3.0);
  EXPECT_LT(low.max_moment_Nm, slip_moment);
  EXPECT_EQ(low.slider_travel_rad, 0.0);
  EXPECT_NEAR(low.loop_area_J, 0.0, 1e-3 * slip_moment * low.theta_range_rad);
  const LinearBeam stuck(LinearBeamModel{.beam = PaperModel(eta).beam, .support_stiffness_Nm_rad = stiffness}, 0.570);
  ExpectMatchesExactReceptance(low, stuck, frequency_hz, low_N);

  // High level: slips every cycle; the moment saturates at M_slip and the
  // loop encloses the Coulomb energy 2·M_slip·(Δθ − 2·M_slip/k_t).
  const double high_N = 2.0;
  const SteadyState high = Simulate(sim, high_N, frequency_hz, 3.0);
  EXPECT_NEAR(high.max_moment_Nm, slip_moment, 1e-12);
  EXPECT_GT(high.slider_travel_rad, 0.0);
  const double coulomb_J = 2 * slip_moment * (high.theta_range_rad - 2 * slip_moment / stiffness);
  ASSERT_GT(coulomb_J, 0.0);
  EXPECT_NEAR(high.loop_area_J / coulomb_J, 1.0, 1e-2);
  // And the response per newton is no longer the stuck beam's.
  const double omega = 2 * kPi * frequency_hz;
  const std::complex<double> stuck_per_N = -omega * omega * stuck.RespondToForce(omega).Displacement_m(0.570);
  EXPECT_GT(RelativeError(high.acceleration[2](1) / high_N, stuck_per_N), 0.05);
}

TEST(TimeSimulatorTest, SavedStateReplaysTheSameTrajectory) {
  const JenkinsSupportLaw law({.stiffness_Nm_rad = 150.0, .slip_moment_Nm = 0.02});
  TimeSimulator sim(PaperModel(0.004), law);
  sim.Reset(1.0);
  for (int i = 0; i < 2000; ++i) sim.Advance(std::cos(0.01 * i));
  const TimeSimulator::State saved = sim.state();
  auto run = [&] {
    for (int i = 0; i < 500; ++i) sim.Advance(std::sin(0.02 * i));
    return sim.SupportRotation_rad();
  };
  const double first = run();
  sim.set_state(saved);
  EXPECT_EQ(run(), first);
}

TEST(TimeSimulatorTest, RejectsForceAtConstrainedPoint) {
  TimeSimulatorModel model = PaperModel(0.0);
  model.force_position_m = 0.6;
  EXPECT_THROW(TimeSimulator(model, PolynomialSupportLaw({.k1_Nm_rad = 1.0})), std::invalid_argument);
}

}  // namespace
}  // namespace beamid::hb
