// Every options struct of solver/estimation and solver/backbone refuses a
// value out of its range where it is used, with an InputError that names the
// field. The checks run before any work, so the calls below need no data.
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hb/errors.h"
#include "solver/backbone/measured_backbone.h"
#include "solver/backbone/single_mode_fit.h"
#include "solver/estimation/fit_data.h"
#include "solver/estimation/identification_problem.h"
#include "solver/estimation/identify.h"
#include "solver/estimation/multiple_scales_problem.h"
#include "solver/estimation/nested_fit.h"

#include "tests/support/expect_refused.h"

namespace beamid::solver {
namespace {

using beamid::testing::ExpectRefused;

TEST(OptionsValidation, DefaultsAreValid) {
  EXPECT_NO_THROW(ModelOptions{}.Validate());
  EXPECT_NO_THROW(MultipleScalesProblemOptions{}.Validate());
  EXPECT_NO_THROW(FitDataOptions{}.Validate());
  EXPECT_NO_THROW(NestedFitOptions{}.Validate());
  EXPECT_NO_THROW(IpoptOptions{}.Validate());
  EXPECT_NO_THROW(IdentifyOptions{}.Validate());
  EXPECT_NO_THROW(MeasuredBackboneOptions{}.Validate());
  EXPECT_NO_THROW(SingleModeFitOptions{}.Validate());
}

TEST(OptionsValidation, FitDataRefusesEachFieldOutOfRange) {
  auto refused = [&](const FitDataOptions& options, const std::string& field) {
    ExpectRefused([&] { MakeFitData(signal::Campaign{}, signal::PhasorSet{}, options); }, field);
  };
  refused({.num_fit_harmonics = 0}, "num_fit_harmonics = 0: must be 1 … 50");
  refused({.num_fit_harmonics = 51}, "num_fit_harmonics");
  refused({.relative_uncertainty_floor = 0.0}, "relative_uncertainty_floor");
  refused({.relative_model_error = -1e-6}, "relative_model_error");
  refused({.relative_model_error = 1.0}, "relative_model_error");
  refused({.force_harmonic_family_significance = 0.0}, "force_harmonic_family_significance");
  refused({.force_harmonic_family_significance = 1.0}, "force_harmonic_family_significance");
}

TEST(OptionsValidation, FitProblemsRefuseEachFieldOutOfRange) {
  const FitData data;
  const ModelStructure structure;
  auto refused = [&](const ModelOptions& options, const std::string& field) {
    ExpectRefused([&] { IdentificationProblem(data, structure, options); }, field);
    ExpectRefused([&] { NestedFit(data, structure, {}, {.model = options}); }, field);
    ExpectRefused([&] { Identify(data, structure, {.model = options}); }, field);
  };
  refused({.num_harmonics = 0}, "ModelOptions.num_harmonics");
  refused({.num_harmonics = 51}, "ModelOptions.num_harmonics");
  refused({.num_harmonics = 5, .num_time_samples = 8}, "num_time_samples");
  refused({.beam_loss_factor = 1.0}, "ModelOptions.beam_loss_factor");

  auto refused_ms = [&](const MultipleScalesProblemOptions& options, const std::string& field) {
    ExpectRefused([&] { MultipleScalesProblem(data, structure, options); }, field);
  };
  refused_ms({.beam_loss_factor = -0.1}, "MultipleScalesProblemOptions.beam_loss_factor");
  refused_ms({.model = {.harmonic_frequency = static_cast<hb::MultipleScalesHarmonicFrequency>(9)}},
             "harmonic_frequency");

  ExpectRefused([&] { NestedFit(data, structure, {}, {.max_iterations = 0}); }, "NestedFitOptions.max_iterations");
  ExpectRefused([&] { NestedFit(data, structure, {}, {.relative_tolerance = 0.0}); },
                "NestedFitOptions.relative_tolerance");
}

TEST(OptionsValidation, IdentifyRefusesEachFieldOutOfRange) {
  const FitData data;
  const ModelStructure structure;
  auto refused = [&](auto change, const std::string& field) {
    IdentifyOptions options;
    change(options);
    ExpectRefused([&] { Identify(data, structure, options); }, field);
    options.family = &MultipleScalesFamily();
    ExpectRefused([&] { Identify(data, structure, options); }, field);
    ExpectRefused([&] { IdentifyWith([] { return std::unique_ptr<FitProblem>(); }, structure, {}, options); },
                  field);
  };
  refused([](IdentifyOptions& o) { o.num_starts = -1; }, "num_starts");
  refused([](IdentifyOptions& o) { o.num_starts = 1001; }, "num_starts");
  refused([](IdentifyOptions& o) { o.start_spread = 1.0; }, "start_spread");
  refused([](IdentifyOptions& o) { o.num_workers = -1; }, "num_workers");
  refused([](IdentifyOptions& o) { o.num_workers = 257; }, "num_workers");
  refused([](IdentifyOptions& o) { o.decisive_chi_square_gap = 0.0; }, "decisive_chi_square_gap");
  refused([](IdentifyOptions& o) { o.ipopt.max_iterations = 0; }, "IpoptOptions.max_iterations");
  refused([](IdentifyOptions& o) { o.ipopt.tolerance = 0.0; }, "IpoptOptions.tolerance");
  refused([](IdentifyOptions& o) { o.ipopt.constraint_tolerance = -1.0; }, "IpoptOptions.constraint_tolerance");
  refused([](IdentifyOptions& o) { o.ipopt.max_cpu_seconds = -1.0; }, "IpoptOptions.max_cpu_seconds");
  refused([](IdentifyOptions& o) { o.ipopt.print_level = 13; }, "IpoptOptions.print_level");
}

TEST(OptionsValidation, MeasuredBackboneRefusesEachFieldOutOfRange) {
  auto refused = [&](const MeasuredBackboneOptions& options, const std::string& field) {
    ExpectRefused([&] { AnalyseMeasuredBackbone({}, options); }, field);
  };
  refused({.fit_window = 0.0}, "fit_window");
  refused({.fit_window = 1.5}, "fit_window");
  refused({.constant_tolerance = 0.0}, "constant_tolerance");
  refused({.jumps = {.slope_factor = 0.0}}, "slope_factor");
  refused({.max_frequency_degree = -1}, "max_frequency_degree");
  refused({.max_damping_degree = -1}, "max_damping_degree");
  refused({.trend_significance = std::nan("")}, "trend_significance");
}

TEST(OptionsValidation, SingleModeFitRefusesEachFieldOutOfRange) {
  auto refused = [&](const SingleModeFitOptions& options, const std::string& field) {
    ExpectRefused([&] { FitSingleMode({}, options); }, field);
    ExpectRefused([&] { FitResidualReceptance({}, options); }, field);
    ExpectRefused([&] { FitSingleModeChoosingExponents({}, options); }, field);
  };
  refused({.frequency_degree = -1}, "frequency_degree");
  refused({.damping_degree = -1}, "damping_degree");
  refused({.frequency_exponent = -0.5}, "frequency_exponent");
  refused({.damping_exponent = INFINITY}, "damping_exponent");
  refused({.residual_receptance_m_N = std::nan("")}, "residual_receptance_m_N");
  refused({.reference_amplitude_m = 0.0}, "reference_amplitude_m");
  refused({.default_relative_std = 0.0}, "default_relative_std");
  refused({.reweighting_iterations = -1}, "reweighting_iterations");
}

}  // namespace
}  // namespace beamid::solver
