// Every options struct of hb refuses a value out of its range where it is
// used, with an InputError that names the field, so that a library caller
// is as protected as the command line.
#include <cmath>
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "hb/backbone.h"
#include "hb/continuation.h"
#include "hb/errors.h"
#include "hb/fe_beam.h"
#include "hb/harmonic_balance.h"
#include "hb/linear_beam.h"
#include "hb/multiple_scales.h"
#include "hb/support_law.h"
#include "hb/time_simulator.h"
#include "tests/support/paper_setup.h"

#include "tests/support/expect_refused.h"

namespace beamid::hb {
namespace {

using testing::kForcePosition_m;
using testing::PaperBeam;

using beamid::testing::ExpectRefused;

const PolynomialSupportLaw kLaw({.k1_Nm_rad = 150.0, .k3_Nm_rad3 = 1e6, .c_Nms_rad = 0.02});

LinearBeam Linear() { return LinearBeam({.beam = PaperBeam()}, kForcePosition_m); }

TEST(OptionsValidation, DefaultsAreValid) {
  EXPECT_NO_THROW(HarmonicBalanceOptions{}.Validate());
  EXPECT_NO_THROW((ContinuationOptions{.omega_start_rad_s = 300.0, .omega_end_rad_s = 400.0}.Validate()));
  EXPECT_NO_THROW(TimeSimulatorOptions{}.Validate());
  EXPECT_NO_THROW(FeBeamOptions{}.Validate());
  EXPECT_NO_THROW(LinearBeamOptions{}.Validate());
  EXPECT_NO_THROW(BackboneOptions{}.Validate());
  EXPECT_NO_THROW(MultipleScalesOptions{}.Validate());
}

TEST(OptionsValidation, HarmonicBalanceRefusesEachFieldOutOfRange) {
  const LinearBeam linear = Linear();
  auto refused = [&](const HarmonicBalanceOptions& options, const std::string& field) {
    ExpectRefused([&] { HarmonicBalance(linear, kLaw, options); }, field);
  };
  refused({.num_harmonics = 0}, "num_harmonics = 0: must be 1 … 50");
  refused({.num_harmonics = 51}, "num_harmonics = 51");
  refused({.num_harmonics = 5, .num_time_samples = 11}, "num_time_samples");
  refused({.tolerance = 0.0}, "tolerance");
  refused({.tolerance = std::nan("")}, "tolerance");
  refused({.max_iterations = 0}, "max_iterations");
  EXPECT_NO_THROW(HarmonicBalance(linear, kLaw, {.num_harmonics = 50}));
}

TEST(OptionsValidation, ContinuationRefusesEachFieldOutOfRange) {
  const LinearBeam linear = Linear();
  const HarmonicBalance balance(linear, kLaw, {.num_harmonics = 3});
  Eigen::VectorXcd force = Eigen::VectorXcd::Zero(4);
  force[1] = 1.0;
  const ContinuationOptions valid{.omega_start_rad_s = 300.0, .omega_end_rad_s = 400.0};
  auto refused = [&](auto change, const std::string& field) {
    ContinuationOptions options = valid;
    change(options);
    ExpectRefused([&] { TraceFrequencyResponse(balance, force, options); }, field);
  };
  refused([](ContinuationOptions& o) { o.omega_start_rad_s = 0.0; }, "omega_start_rad_s");
  refused([](ContinuationOptions& o) { o.omega_end_rad_s = -1.0; }, "omega_end_rad_s");
  refused([](ContinuationOptions& o) { o.omega_end_rad_s = o.omega_start_rad_s; }, "omega_end_rad_s");
  refused([](ContinuationOptions& o) { o.max_points = 0; }, "max_points");
  refused([](ContinuationOptions& o) { o.min_step = 0.0; }, "min_step");
  refused([](ContinuationOptions& o) { o.max_step = 1e-7; }, "max_step");
  refused([](ContinuationOptions& o) { o.initial_step = 1.0; }, "initial_step");
  refused([](ContinuationOptions& o) { o.target_iterations = 0; }, "target_iterations");
  refused([](ContinuationOptions& o) { o.max_iterations = 0; }, "max_iterations");
  refused([](ContinuationOptions& o) { o.tolerance = -1e-9; }, "tolerance");
}

TEST(OptionsValidation, TimeSimulatorAndMeshRefuseEachFieldOutOfRange) {
  TimeSimulatorModel model;
  model.force_position_m = kForcePosition_m;
  model.output_positions_m = {0.3};
  auto refused = [&](const TimeSimulatorOptions& options, const std::string& field) {
    ExpectRefused([&] { TimeSimulator(model, kLaw, options); }, field);
  };
  refused({.time_step_s = 0.0}, "time_step_s");
  refused({.time_step_s = 1e-9}, "time_step_s");
  refused({.damping_reference_rad_s = -1.0}, "damping_reference_rad_s");
  refused({.mesh = {.min_elements = 0}}, "min_elements");
  refused({.max_newton_iterations = 0}, "max_newton_iterations");
  ExpectRefused([] { FeBeam(PaperBeam(), LinearAttachments{}, {}, {.min_elements = 2001}); }, "min_elements");
}

TEST(OptionsValidation, LinearBeamRefusesANonPositiveFrequency) {
  ExpectRefused([] { LinearBeam({.beam = PaperBeam()}, kForcePosition_m, {.max_frequency_hz = 0.0}); },
                "max_frequency_hz");
  ExpectRefused([] { LinearBeam({.beam = PaperBeam()}, kForcePosition_m, {.max_frequency_hz = INFINITY}); },
                "max_frequency_hz");
}

TEST(OptionsValidation, BackboneRefusesEachFieldOutOfRange) {
  const LinearBeam linear = Linear();
  const HarmonicBalance balance(linear, kLaw, {.num_harmonics = 3});
  Eigen::VectorXcd shape = Eigen::VectorXcd::Zero(4);
  shape[1] = 1.0;
  auto refused = [&](const BackboneOptions& options, const std::string& field) {
    ExpectRefused([&] { TraceBackbone(balance, options, shape); }, field);
  };
  refused({.min_theta_amplitude_rad = 0.0}, "min_theta_amplitude_rad");
  refused({.min_theta_amplitude_rad = 1e-3, .max_theta_amplitude_rad = 1e-3}, "max_theta_amplitude_rad");
  refused({.num_points = 1}, "num_points");
}

TEST(OptionsValidation, MultipleScalesRefusesAnUnknownHarmonicFrequency) {
  ExpectRefused(
      [] {
        MultipleScalesModel(PaperBeam(), {.k1_Nm_rad = 150.0}, kForcePosition_m,
                            {.harmonic_frequency = static_cast<MultipleScalesHarmonicFrequency>(7)});
      },
      "harmonic_frequency");
}

}  // namespace
}  // namespace beamid::hb
