// Two independent models of the same physics must agree at a strongly
// nonlinear level: the time-domain finite-element simulation (through the
// production stepped-sine path, hb/stepped_sine.h) and the exact harmonic
// balance of the continuous beam (hb/harmonic_balance.h). Required: harmonics
// at each sensor within 1 % on the first and 5 % on the third, for the
// polynomial law and for the Jenkins element.
#include <cmath>
#include <algorithm>
#include <iostream>
#include <complex>
#include <numbers>
#include <optional>

#include <gtest/gtest.h>

#include "hb/harmonic_balance.h"
#include "hb/linear_beam.h"
#include "hb/scenario.h"
#include "hb/stepped_sine.h"

namespace beamid::hb {
namespace {

constexpr double kFirstHarmonicTolerance = 0.01;
constexpr double kThirdHarmonicTolerance = 0.05;

// One step, no noise, settled far below the fit's accuracy. No material
// damping (η = 0): the support dashpot is the only loss, identical in both.
// settle_tolerance: the floor of the window-to-window change is ~1e-6 for a
// smooth law (harmonics above the 5th that the settling fit leaves out) and
// ~1e-4 with friction (stick-slip instants fall between time steps); 10 s of
// settling is ~19 decay times of the first mode anyway.
Scenario OneStep(const PolynomialSupportLaw::Coefficients& polynomial,
                 std::optional<JenkinsSupportLaw::Parameters_> jenkins, double force_N, double frequency_hz,
                 double settle_tolerance, double one_sided_stiffness_Nm_rad = 0.0) {
  Scenario s;
  s.beam.loss_factor = 0.0;
  s.nominal_beam = s.beam;
  s.polynomial = polynomial;
  s.jenkins = jenkins;
  s.one_sided_stiffness_Nm_rad = one_sided_stiffness_Nm_rad;
  s.sensors = {{.channel = "acc1", .position_m = 0.100},
               {.channel = "acc2", .position_m = 0.300},
               {.channel = "acc3", .position_m = 0.570}};
  s.levels = {{.label = "strong", .force_amplitude_N = force_N, .frequencies_hz = {frequency_hz}}};
  s.timing.settle_min_s = 10.0;
  s.timing.settle_max_s = 20.0;
  s.timing.settle_tolerance = settle_tolerance;
  s.timing.record_s = 1.0;
  s.timing.max_time_step_s = 1.0 / 51200.0;
  return s;
}

// Returns the harmonic-balance fundamental of θ.
std::complex<double> ExpectSimulatorMatchesHarmonicBalance(const Scenario& scenario,
                                                           const HarmonicBalanceOptions& hb_options,
                                                           double min_third_to_first,
                                                           std::vector<int> harmonics = {1, 3}) {
  const ScenarioLevel& level = scenario.levels.front();
  const double omega = 2 * std::numbers::pi * level.frequencies_hz.front();

  SimulatedStep simulated;
  SteppedSineSimulation simulation(scenario);
  simulation.Run([&](const SimulatedStep& step) { simulated = step; });
  EXPECT_TRUE(simulated.settled) << "last window change " << simulated.settle_change;

  // Harmonic balance, continued in force from the linear solution.
  const LinearBeam beam(LinearBeamModel{.beam = scenario.beam, .attachments = scenario.TrueAttachments()},
                        scenario.force_position_m);
  const auto law = scenario.MakeSupportLaw();
  const HarmonicBalance hb(beam, *law, hb_options);
  Eigen::VectorXcd force = Eigen::VectorXcd::Zero(hb_options.num_harmonics + 1);
  HarmonicBalanceSolution solution;
  Eigen::VectorXd z;
  constexpr int kRamp = 6;
  for (int i = 1; i <= kRamp; ++i) {
    force(1) = level.force_amplitude_N * i / kRamp;
    solution = hb.Solve(omega, force, z);
    if (!solution.converged) {
      ADD_FAILURE() << "harmonic balance did not converge at " << force(1).real() << " N";
      return {};
    }
    z = HarmonicBalance::ToReal(solution.theta_rad);
  }
  std::vector<double> positions;
  for (const ScenarioSensor& s : scenario.sensors) positions.push_back(s.position_m);
  const Eigen::MatrixXcd displacement = hb.Displacements(solution, force, positions);

  // The level must really be nonlinear for the test to mean anything: the
  // third harmonic of the direct accelerometer is a sizeable part of it.
  EXPECT_GT(9 * std::abs(displacement(2, 3)), min_third_to_first * std::abs(displacement(2, 1)));
  double worst[4] = {0, 0, 0, 0};
  for (size_t s = 0; s < positions.size(); ++s) {
    for (int k : harmonics) {
      const std::complex<double> expected = -std::pow(k * omega, 2) * displacement(static_cast<Eigen::Index>(s), k);
      const std::complex<double> value = simulated.channel_phasors[s + 1](k);
      const double tolerance = k == 1 ? kFirstHarmonicTolerance : kThirdHarmonicTolerance;
      worst[k] = std::max(worst[k], std::abs(value - expected) / std::abs(expected));
      EXPECT_LT(std::abs(value - expected), tolerance * std::abs(expected))
          << scenario.sensors[s].channel << " harmonic " << k << ": simulated " << value << ", harmonic balance "
          << expected;
    }
  }
  std::cout << "worst relative difference at the sensors: harmonic 1 " << worst[1] << ", harmonic 3 " << worst[3]
            << " (harmonic 2 " << worst[2] << ")\n";
  for (int k : harmonics) {
    const double tolerance = k == 1 ? kFirstHarmonicTolerance : kThirdHarmonicTolerance;
    EXPECT_LT(std::abs(simulated.support_rotation_phasors(k) - solution.theta_rad(k)),
              tolerance * std::abs(solution.theta_rad(k)))
        << "theta harmonic " << k;
  }
  return solution.theta_rad(1);
}

TEST(TimeSimulatorHarmonicBalanceTest, PolynomialLawAtStrongLevel) {
  // The paper example's support at its top force, just below the hardened
  // resonance (a single stable branch): θ ≈ 8 mrad, (3/4)·k3·θ² ≈ 0.1·k1,
  // and the third harmonic is near the second mode (168 Hz).
  const Scenario scenario = OneStep({.k1_Nm_rad = 150.0, .k3_Nm_rad3 = 3.0e5, .c_Nms_rad = 0.05}, std::nullopt,
                                    11.0, 53.5, 1e-5);
  ExpectSimulatorMatchesHarmonicBalance(scenario, {.num_harmonics = 9}, 0.02);
}

TEST(TimeSimulatorHarmonicBalanceTest, JenkinsElementSlipping) {
  // The friction example: k1 = 100 plus a Jenkins element (50 N·m/rad, slips
  // at 0.15 N·m), driven hard enough to slip on every cycle.
  const Scenario scenario = OneStep({.k1_Nm_rad = 100.0, .k3_Nm_rad3 = 3.0e5, .c_Nms_rad = 0.05},
                                    JenkinsSupportLaw::Parameters_{.stiffness_Nm_rad = 50.0, .slip_moment_Nm = 0.15},
                                    11.0, 53.0, 1e-3);
  const std::complex<double> theta =
      ExpectSimulatorMatchesHarmonicBalance(scenario, {.num_harmonics = 15, .num_time_samples = 512}, 0.02);
  // Slipping: the stuck spring alone would exceed the slip moment 1.5 times over.
  EXPECT_GT(50.0 * std::abs(theta), 1.5 * 0.15);
}

TEST(TimeSimulatorHarmonicBalanceTest, OneSidedStiffnessMakesEvenHarmonics) {
  // An asymmetric support: 40 N·m/rad more stiffness for positive rotation
  // than for negative. Its even harmonics (absent from a symmetric law) agree
  // between the two methods like the odd ones. Settling floor ~1e-3: the
  // kink at θ = 0 falls between time steps, as friction's slip instants do.
  const Scenario scenario = OneStep({.k1_Nm_rad = 130.0, .k3_Nm_rad3 = 3.0e5, .c_Nms_rad = 0.05}, std::nullopt, 11.0,
                                    53.5, 1e-3, 40.0);
  ExpectSimulatorMatchesHarmonicBalance(scenario, {.num_harmonics = 15, .num_time_samples = 512}, 0.02, {1, 2, 3});
}

}  // namespace
}  // namespace beamid::hb
