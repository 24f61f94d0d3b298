// result.json (solver/estimation/result_io.h): every field of a ResultFile
// survives the text and back (a NaN as null), a file in the layout of the
// writer before the typed result still reads, and a broken file is refused
// with an InputError naming the file and the field.
#include "solver/estimation/result_io.h"

#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <numbers>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hb/errors.h"
#include "solver/estimation/prediction.h"
#include "tests/support/same_value.h"
#include "tests/support/schema_checks.h"
#include "tests/support/temp_path.h"

namespace beamid::solver {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using Complex = std::complex<double>;
using Json = nlohmann::ordered_json;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Distinct numbers from a seed, so that a field read into its neighbour shows.
double Distinct(int seed) { return 1.0 + seed * 0.1234567 + seed * seed * 1e-5; }

Eigen::VectorXcd Phasors(int count, int seed) {
  Eigen::VectorXcd out(count);
  for (int i = 0; i < count; ++i) out[i] = Complex(Distinct(seed + 2 * i) * 1e-3, -Distinct(seed + 2 * i + 1) * 1e-4);
  return out;
}

ResultFit Fit(int num_parameters) {
  ResultFit f{.chi_square = 412.5,
              .degrees_of_freedom = 377,
              .reduced_chi_square = 412.5 / 377,
              .seconds = 12.75,
              .best_start = 1,
              .starts_at_best = 2,
              .second_minimum_chi_square_gap = 16.25,
              .minimum_decisive = false,
              .direct_estimate = {.k1_Nm_rad = 149.1,
                                  .k2_Nm_rad2 = -12.5,
                                  .k3_Nm_rad3 = 2.9e5,
                                  .c_Nms_rad = 0.049,
                                  .relative_residual = kNaN},
              .model_errors = {{.relative = 3.5e-5, .lower_95 = 1.25e-5, .upper_95 = 5.5e-5, .chi_square = 530.5,
                                .degrees_of_freedom = 478.25},
                               {.degrees_of_freedom = 478.25}}};
  for (int s = 0; s < 3; ++s) {
    ResultStart start{.objective = 206.25 + s,
                      .converged = s != 2,
                      .iterations = 41 + s,
                      .status = s == 2 ? "failed: the worker process died" : "Solve_Succeeded",
                      .states_seeded = s == 0 ? StartRoute::kMeasuredStates : StartRoute::kFeasibleStates,
                      .branch_repairs = s};
    for (int p = 0; p < num_parameters; ++p) {
      start.start.push_back(Distinct(10 * s + p));
      if (s != 2) start.parameters.push_back(Distinct(10 * s + p + 5));  // a failed start ended nowhere
    }
    if (s == 2) start.objective = kNaN;
    f.starts.push_back(start);
  }
  f.minima = {{.parameters = f.starts[1].parameters, .chi_square = 412.5, .num_starts = 2},
              {.parameters = f.starts[0].parameters, .chi_square = 428.75, .num_starts = 1}};
  return f;
}

// Harmonic balance, with a held-out channel, sensor masses and a fitted
// loss factor; names deliberately not in alphabetical order.
ResultFile HarmonicBalanceResult() {
  ResultFile r;
  r.beamid_version = "9.8.7";
  r.campaign = {.folder = "campaigns/base",
                .name = "paper beam, \"three\" levels",
                .absolute_folder = "/data/campaigns/base",
                .sha256 = "9f86d081884c7d659a2feaa0c55ad015a3bf4f1b2b0b822cd15d6c15b0f00a08"};
  r.model = {.kind = ModelKind::kHarmonicBalance,
             .law = "polynomial",
             .beam = {.length_m = 0.61,
                      .width_m = 0.041,
                      .thickness_m = 0.0051,
                      .youngs_modulus_Pa = 2.05e11,
                      .density_kg_m3 = 7830.5,
                      .loss_factor = 3.2e-4},
             .force_position_m = 0.571,
             .sensor_masses = {{.position_m = 0.1, .mass_kg = 0.005}, {.position_m = 0.33, .mass_kg = 0.0047}},
             .fit_channels = {"acc2", "acc1"},
             .num_fit_harmonics = 3,
             .num_harmonics = 7,
             .phasor_uncertainty = PhasorUncertainty::kPropagated};
  r.parameters = {{.name = "k1", .unit = "N*m/rad", .value = 150.43, .std = 0.21, .lower_95 = 150.02, .upper_95 = 150.84,
                   .std_model_error = 0.0625},
                  {.name = "k2", .unit = "N*m/rad^2", .value = -31.5, .std = 40.5, .lower_95 = -110.9, .upper_95 = 47.9},
                  {.name = "k3", .unit = "N*m/rad^3", .value = 3.01e5, .std = 1.1e3, .lower_95 = 2.99e5, .upper_95 = 3.03e5},
                  {.name = "c", .unit = "N*m*s/rad", .value = 0.0502, .std = 1.5e-4, .lower_95 = 0.0499, .upper_95 = 0.0505},
                  {.name = "loss_factor", .unit = "1", .value = 2.1e-4, .std = kNaN, .lower_95 = kNaN, .upper_95 = kNaN}};
  r.linear_parameters = {"loss_factor"};
  r.covariance.resize(5, 5);
  r.correlation.resize(5, 5);
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) {
      r.covariance(i, j) = Distinct(i * 5 + j) * 1e-3 * (i == j ? 10 : 1);
      r.correlation(i, j) = i == j ? 1.0 : -0.01 * (i * 5 + j);
    }
  r.correlation(4, 4) = kNaN;
  r.fit = Fit(5);
  r.warnings = {"k2 is not identifiable from these data: its standard uncertainty (40.5) exceeds its value",
                "the data do not decide between two fits"};
  const std::vector<std::string> levels = {"mid", "low"};
  for (int c = 0; c < 2; ++c) {
    ChannelQuality q{.channel = r.model.fit_channels[c]};
    for (int k = 0; k < 3; ++k) {
      std::vector<LevelQuality> per_level;
      for (int l = 0; l < 2; ++l)
        per_level.push_back({.level = levels[l],
                             .relative_rms_error = (c == 1 && k == 2 && l == 1) ? kNaN : Distinct(100 + 10 * c + 3 * k + l),
                             .chi_square = Distinct(200 + 10 * c + 3 * k + l),
                             .num_steps = 4 + c + k + l,
                             .relative_std = {.noise = Distinct(300 + 10 * c + 3 * k + l),
                                              .force = Distinct(400 + 10 * c + 3 * k + l),
                                              .frequency = Distinct(500 + 10 * c + 3 * k + l),
                                              .model_error = Distinct(600 + 10 * c + 3 * k + l)}});
      q.harmonics.push_back(per_level);
    }
    r.quality.push_back(q);
  }
  for (const std::string channel : {"acc4", "acc3"}) {
    HeldOutChannel v{.channel = channel,
                     .position_m = channel == "acc4" ? 0.52 : 0.45,
                     .worst_h1_relative_error = 0.0123,
                     .worst_h3_relative_error = 0.21,
                     .measurable_relative_std = 0.01,
                     .measurable_steps_h1 = 7,
                     .measurable_steps_h3 = 5};
    for (int i = 0; i < 2; ++i) {
      HeldOutStep step{.level = levels[i], .file = levels[i] + "/step_00" + std::to_string(i) + ".csv",
                       .frequency_hz = 53.25 + i};
      for (int k = 0; k < 3; ++k)
        step.harmonics.push_back({.relative_error = Distinct(300 + 3 * i + k),
                                  .measured_relative_std = Distinct(400 + 3 * i + k) * 1e-3,
                                  .predicted = Phasors(1, 500 + 3 * i + k)[0],
                                  .measured = Phasors(1, 600 + 3 * i + k)[0]});
      v.steps.push_back(step);
    }
    r.validation.push_back(v);
  }
  r.validation[1].steps[1].harmonics[2].predicted = Complex(kNaN, 0.5);  // a step the model did not solve
  r.damping_laws.laws = {
      DampingLawFitOf("loss_factor", {{.name = "k1", .unit = "N*m/rad", .value = 150.5, .std = 0.25, .lower_95 = 150.0,
                                       .upper_95 = 151.0}},
                      40.0, 20),
      DampingLawFitOf("rayleigh", {{.name = "k1", .unit = "N*m/rad", .value = 151.5, .std = 0.5, .lower_95 = 150.5,
                                    .upper_95 = 152.5}},
                      41.0, 19),
      {.law = "mass_proportional", .status = "failed: restoration phase failed"}};
  JudgeDampingLaws(&r.damping_laws);
  r.robust_fit = ResultRobustFit{
      .applied = true,
      .note = "left out 1 outlying step(s) and refitted",
      .outliers = {{.step = -1, .level = "high", .file = "high/step_020.csv", .frequency_hz = 55.0 + 1.0 / 3.0,
                    .chi_square = 1234.5 / 7.0, .num_residuals = 12, .tail_probability = 1e-300 / 3.0,
                    .unsettled = true}},
      .ordinary_parameters = {{.name = "k1", .unit = "N*m/rad", .value = 150.0 / 7.0, .std = 0.25 / 3.0,
                               .lower_95 = 149.0, .upper_95 = 151.0}},
      .ordinary_chi_square = 9876.5 / 3.0,
      .ordinary_degrees_of_freedom = 1183};
  r.unsettled_steps = {{.level = "high", .file = "high/step_020.csv", .frequency_hz = 55.0 / 3.0,
                        .change_relative = 0.0151 / 7.0}};
  for (int i = 0; i < 3; ++i)
    r.steps.push_back({.level = levels[i % 2],
                       .file = "level " + std::to_string(i) + "/step.csv",
                       .frequency_hz = 52.0 + 0.45 * i,
                       .force_N = Phasors(8, 700 + 20 * i),
                       .state = Phasors(8, 800 + 20 * i)});
  return r;
}

// Multiple scales: no held-out channel, no recorded absolute folder or
// version, no linear parameter.
ResultFile MultipleScalesResult() {
  ResultFile r;
  r.campaign = {.folder = "ms campaign", .name = "small forces"};
  r.model = {.kind = ModelKind::kMultipleScales,
             .law = "polynomial",
             .beam = {.length_m = 0.6, .width_m = 0.04, .thickness_m = 0.005, .youngs_modulus_Pa = 2.1e11,
                      .density_kg_m3 = 7850.0, .loss_factor = 2e-4},
             .force_position_m = 0.57,
             .fit_channels = {"acc1", "acc2"},
             .num_fit_harmonics = 2,
             .num_harmonics = 3};
  r.parameters = {{.name = "k1", .unit = "N*m/rad", .value = 151.5, .std = 0.5, .lower_95 = 150.52, .upper_95 = 152.48},
                  {.name = "k2", .unit = "N*m/rad^2", .value = 0.25, .std = 3.5, .lower_95 = -6.61, .upper_95 = 7.11},
                  {.name = "k3", .unit = "N*m/rad^3", .value = 2.95e5, .std = 4e3, .lower_95 = 2.87e5, .upper_95 = 3.03e5},
                  {.name = "c", .unit = "N*m*s/rad", .value = 0.051, .std = 2e-4, .lower_95 = 0.0506, .upper_95 = 0.0514}};
  r.covariance = Eigen::MatrixXd::Identity(4, 4) * 0.25;
  r.covariance(0, 3) = r.covariance(3, 0) = -1.5e-3;
  r.correlation = Eigen::MatrixXd::Identity(4, 4);
  r.correlation(0, 3) = r.correlation(3, 0) = -0.375;
  r.fit = Fit(4);
  ChannelQuality q{.channel = "acc1"};
  q.harmonics = {{{.level = "low", .relative_rms_error = 0.003, .chi_square = 9.5, .num_steps = 3}},
                 {{.level = "low", .relative_rms_error = 0.25, .chi_square = 2.5, .num_steps = 3}}};
  r.quality = {q};
  for (int i = 0; i < 3; ++i)
    r.steps.push_back({.level = "low",
                       .file = "low/step_" + std::to_string(i) + ".csv",
                       .frequency_hz = 53.6 + 0.5 * i,
                       .force_N = Phasors(4, 900 + 10 * i),
                       .state = Eigen::VectorXcd::Constant(1, Complex(Distinct(950 + i) * 1e-4, -Distinct(960 + i) * 1e-5))});
  return r;
}

using beamid::testing::Same;

// Every field, NaN equal to NaN.
void ExpectSame(const ResultFile& a, const ResultFile& b) {
  EXPECT_EQ(a.beamid_version, b.beamid_version);
  EXPECT_EQ(a.campaign.folder, b.campaign.folder);
  EXPECT_EQ(a.campaign.name, b.campaign.name);
  EXPECT_EQ(a.campaign.absolute_folder, b.campaign.absolute_folder);
  EXPECT_EQ(a.campaign.sha256, b.campaign.sha256);

  EXPECT_EQ(a.model.kind, b.model.kind);
  EXPECT_EQ(a.model.law, b.model.law);
  EXPECT_EQ(a.model.beam.length_m, b.model.beam.length_m);
  EXPECT_EQ(a.model.beam.width_m, b.model.beam.width_m);
  EXPECT_EQ(a.model.beam.thickness_m, b.model.beam.thickness_m);
  EXPECT_EQ(a.model.beam.youngs_modulus_Pa, b.model.beam.youngs_modulus_Pa);
  EXPECT_EQ(a.model.beam.density_kg_m3, b.model.beam.density_kg_m3);
  EXPECT_EQ(a.model.beam.loss_factor, b.model.beam.loss_factor);
  EXPECT_EQ(a.model.force_position_m, b.model.force_position_m);
  ASSERT_EQ(a.model.sensor_masses.size(), b.model.sensor_masses.size());
  for (std::size_t i = 0; i < a.model.sensor_masses.size(); ++i) {
    EXPECT_EQ(a.model.sensor_masses[i].position_m, b.model.sensor_masses[i].position_m);
    EXPECT_EQ(a.model.sensor_masses[i].mass_kg, b.model.sensor_masses[i].mass_kg);
  }
  EXPECT_EQ(a.model.fit_channels, b.model.fit_channels);
  EXPECT_EQ(a.model.num_fit_harmonics, b.model.num_fit_harmonics);
  EXPECT_EQ(a.model.num_harmonics, b.model.num_harmonics);
  EXPECT_EQ(a.model.phasor_uncertainty, b.model.phasor_uncertainty);

  ASSERT_EQ(a.parameters.size(), b.parameters.size());
  for (std::size_t i = 0; i < a.parameters.size(); ++i) {
    SCOPED_TRACE(a.parameters[i].name);
    EXPECT_EQ(a.parameters[i].name, b.parameters[i].name);
    EXPECT_EQ(a.parameters[i].unit, b.parameters[i].unit);
    EXPECT_TRUE(Same(a.parameters[i].value, b.parameters[i].value));
    EXPECT_TRUE(Same(a.parameters[i].std, b.parameters[i].std));
    EXPECT_TRUE(Same(a.parameters[i].lower_95, b.parameters[i].lower_95));
    EXPECT_TRUE(Same(a.parameters[i].upper_95, b.parameters[i].upper_95));
    EXPECT_TRUE(Same(a.parameters[i].std_model_error, b.parameters[i].std_model_error));
  }
  EXPECT_EQ(a.linear_parameters, b.linear_parameters);
  ASSERT_EQ(a.damping_laws.laws.size(), b.damping_laws.laws.size());
  for (std::size_t i = 0; i < a.damping_laws.laws.size(); ++i) {
    const DampingLawFit &x = a.damping_laws.laws[i], &y = b.damping_laws.laws[i];
    EXPECT_EQ(x.law, y.law);
    EXPECT_EQ(x.converged, y.converged);
    EXPECT_EQ(x.status, y.status);
    EXPECT_TRUE(Same(x.chi_square, y.chi_square));
    EXPECT_TRUE(Same(x.reduced_chi_square, y.reduced_chi_square));
    EXPECT_EQ(x.accepted, y.accepted);
    ASSERT_EQ(x.parameters.size(), y.parameters.size());
    for (std::size_t j = 0; j < x.parameters.size(); ++j) {
      EXPECT_EQ(x.parameters[j].name, y.parameters[j].name);
      EXPECT_TRUE(Same(x.parameters[j].value, y.parameters[j].value));
      EXPECT_TRUE(Same(x.parameters[j].upper_95, y.parameters[j].upper_95));
    }
  }
  ASSERT_EQ(a.damping_laws.intervals.size(), b.damping_laws.intervals.size());
  for (std::size_t i = 0; i < a.damping_laws.intervals.size(); ++i) {
    EXPECT_EQ(a.damping_laws.intervals[i].name, b.damping_laws.intervals[i].name);
    EXPECT_TRUE(Same(a.damping_laws.intervals[i].lower_95, b.damping_laws.intervals[i].lower_95));
    EXPECT_TRUE(Same(a.damping_laws.intervals[i].upper_95, b.damping_laws.intervals[i].upper_95));
    EXPECT_EQ(a.damping_laws.intervals[i].depends_on_damping_law, b.damping_laws.intervals[i].depends_on_damping_law);
  }
  ASSERT_EQ(a.robust_fit.has_value(), b.robust_fit.has_value());
  if (a.robust_fit) {
    const ResultRobustFit &x = *a.robust_fit, &y = *b.robust_fit;
    EXPECT_EQ(x.applied, y.applied);
    EXPECT_EQ(x.note, y.note);
    ASSERT_EQ(x.outliers.size(), y.outliers.size());
    for (std::size_t i = 0; i < x.outliers.size(); ++i) {
      EXPECT_EQ(x.outliers[i].level, y.outliers[i].level);
      EXPECT_EQ(x.outliers[i].file, y.outliers[i].file);
      EXPECT_TRUE(Same(x.outliers[i].frequency_hz, y.outliers[i].frequency_hz));
      EXPECT_TRUE(Same(x.outliers[i].chi_square, y.outliers[i].chi_square));
      EXPECT_EQ(x.outliers[i].num_residuals, y.outliers[i].num_residuals);
      EXPECT_TRUE(Same(x.outliers[i].tail_probability, y.outliers[i].tail_probability));
      EXPECT_EQ(x.outliers[i].unsettled, y.outliers[i].unsettled);
    }
    ASSERT_EQ(x.ordinary_parameters.size(), y.ordinary_parameters.size());
    for (std::size_t j = 0; j < x.ordinary_parameters.size(); ++j) {
      EXPECT_EQ(x.ordinary_parameters[j].name, y.ordinary_parameters[j].name);
      EXPECT_TRUE(Same(x.ordinary_parameters[j].value, y.ordinary_parameters[j].value));
      EXPECT_TRUE(Same(x.ordinary_parameters[j].std, y.ordinary_parameters[j].std));
    }
    EXPECT_TRUE(Same(x.ordinary_chi_square, y.ordinary_chi_square));
    EXPECT_EQ(x.ordinary_degrees_of_freedom, y.ordinary_degrees_of_freedom);
  }
  ASSERT_EQ(a.unsettled_steps.size(), b.unsettled_steps.size());
  for (std::size_t i = 0; i < a.unsettled_steps.size(); ++i) {
    EXPECT_EQ(a.unsettled_steps[i].file, b.unsettled_steps[i].file);
    EXPECT_EQ(a.unsettled_steps[i].level, b.unsettled_steps[i].level);
    EXPECT_TRUE(Same(a.unsettled_steps[i].frequency_hz, b.unsettled_steps[i].frequency_hz));
    EXPECT_TRUE(Same(a.unsettled_steps[i].change_relative, b.unsettled_steps[i].change_relative));
  }
  EXPECT_TRUE(Same(a.covariance, b.covariance));
  EXPECT_TRUE(Same(a.correlation, b.correlation));

  const ResultFit& f = a.fit;
  const ResultFit& g = b.fit;
  EXPECT_TRUE(Same(f.chi_square, g.chi_square));
  EXPECT_EQ(f.degrees_of_freedom, g.degrees_of_freedom);
  EXPECT_TRUE(Same(f.reduced_chi_square, g.reduced_chi_square));
  EXPECT_EQ(f.seconds, g.seconds);
  ASSERT_EQ(f.starts.size(), g.starts.size());
  for (std::size_t i = 0; i < f.starts.size(); ++i) {
    SCOPED_TRACE("start " + std::to_string(i));
    EXPECT_TRUE(Same(f.starts[i].start, g.starts[i].start));
    EXPECT_TRUE(Same(f.starts[i].parameters, g.starts[i].parameters));
    EXPECT_TRUE(Same(f.starts[i].objective, g.starts[i].objective));
    EXPECT_EQ(f.starts[i].converged, g.starts[i].converged);
    EXPECT_EQ(f.starts[i].iterations, g.starts[i].iterations);
    EXPECT_EQ(f.starts[i].status, g.starts[i].status);
    EXPECT_EQ(f.starts[i].states_seeded, g.starts[i].states_seeded);
    EXPECT_EQ(f.starts[i].branch_repairs, g.starts[i].branch_repairs);
  }
  EXPECT_EQ(f.best_start, g.best_start);
  EXPECT_EQ(f.starts_at_best, g.starts_at_best);
  ASSERT_EQ(f.minima.size(), g.minima.size());
  for (std::size_t i = 0; i < f.minima.size(); ++i) {
    EXPECT_TRUE(Same(f.minima[i].parameters, g.minima[i].parameters));
    EXPECT_TRUE(Same(f.minima[i].chi_square, g.minima[i].chi_square));
    EXPECT_EQ(f.minima[i].num_starts, g.minima[i].num_starts);
  }
  EXPECT_TRUE(Same(f.second_minimum_chi_square_gap, g.second_minimum_chi_square_gap));
  EXPECT_EQ(f.minimum_decisive, g.minimum_decisive);
  EXPECT_TRUE(Same(f.direct_estimate.k1_Nm_rad, g.direct_estimate.k1_Nm_rad));
  EXPECT_TRUE(Same(f.direct_estimate.k2_Nm_rad2, g.direct_estimate.k2_Nm_rad2));
  EXPECT_TRUE(Same(f.direct_estimate.k3_Nm_rad3, g.direct_estimate.k3_Nm_rad3));
  EXPECT_TRUE(Same(f.direct_estimate.c_Nms_rad, g.direct_estimate.c_Nms_rad));
  EXPECT_TRUE(Same(f.direct_estimate.relative_residual, g.direct_estimate.relative_residual));
  ASSERT_EQ(f.model_errors.size(), g.model_errors.size());
  for (std::size_t k = 0; k < f.model_errors.size(); ++k) {
    EXPECT_TRUE(Same(f.model_errors[k].relative, g.model_errors[k].relative));
    EXPECT_TRUE(Same(f.model_errors[k].lower_95, g.model_errors[k].lower_95));
    EXPECT_TRUE(Same(f.model_errors[k].upper_95, g.model_errors[k].upper_95));
    EXPECT_TRUE(Same(f.model_errors[k].chi_square, g.model_errors[k].chi_square));
    EXPECT_TRUE(Same(f.model_errors[k].degrees_of_freedom, g.model_errors[k].degrees_of_freedom));
  }
  EXPECT_EQ(a.warnings, b.warnings);

  ASSERT_EQ(a.quality.size(), b.quality.size());
  for (std::size_t c = 0; c < a.quality.size(); ++c) {
    EXPECT_EQ(a.quality[c].channel, b.quality[c].channel);
    ASSERT_EQ(a.quality[c].harmonics.size(), b.quality[c].harmonics.size());
    for (std::size_t k = 0; k < a.quality[c].harmonics.size(); ++k) {
      const auto& x = a.quality[c].harmonics[k];
      const auto& y = b.quality[c].harmonics[k];
      ASSERT_EQ(x.size(), y.size());
      for (std::size_t l = 0; l < x.size(); ++l) {
        EXPECT_EQ(x[l].level, y[l].level);
        EXPECT_TRUE(Same(x[l].relative_rms_error, y[l].relative_rms_error));
        EXPECT_TRUE(Same(x[l].chi_square, y[l].chi_square));
        EXPECT_EQ(x[l].num_steps, y[l].num_steps);
        EXPECT_EQ(x[l].relative_std.noise, y[l].relative_std.noise);
        EXPECT_EQ(x[l].relative_std.force, y[l].relative_std.force);
        EXPECT_EQ(x[l].relative_std.frequency, y[l].relative_std.frequency);
        EXPECT_EQ(x[l].relative_std.model_error, y[l].relative_std.model_error);
      }
    }
  }

  ASSERT_EQ(a.validation.size(), b.validation.size());
  for (std::size_t c = 0; c < a.validation.size(); ++c) {
    const HeldOutChannel& v = a.validation[c];
    const HeldOutChannel& w = b.validation[c];
    SCOPED_TRACE(v.channel);
    EXPECT_EQ(v.channel, w.channel);
    EXPECT_EQ(v.position_m, w.position_m);
    EXPECT_TRUE(Same(v.worst_h1_relative_error, w.worst_h1_relative_error));
    EXPECT_TRUE(Same(v.worst_h3_relative_error, w.worst_h3_relative_error));
    EXPECT_EQ(v.measurable_relative_std, w.measurable_relative_std);
    EXPECT_EQ(v.measurable_steps_h1, w.measurable_steps_h1);
    EXPECT_EQ(v.measurable_steps_h3, w.measurable_steps_h3);
    ASSERT_EQ(v.steps.size(), w.steps.size());
    for (std::size_t i = 0; i < v.steps.size(); ++i) {
      EXPECT_EQ(v.steps[i].level, w.steps[i].level);
      EXPECT_EQ(v.steps[i].file, w.steps[i].file);
      EXPECT_EQ(v.steps[i].frequency_hz, w.steps[i].frequency_hz);
      ASSERT_EQ(v.steps[i].harmonics.size(), w.steps[i].harmonics.size());
      for (std::size_t k = 0; k < v.steps[i].harmonics.size(); ++k) {
        const HeldOutHarmonic& h = v.steps[i].harmonics[k];
        const HeldOutHarmonic& e = w.steps[i].harmonics[k];
        EXPECT_TRUE(Same(h.relative_error, e.relative_error));
        EXPECT_TRUE(Same(h.measured_relative_std, e.measured_relative_std));
        EXPECT_TRUE(Same(h.predicted, e.predicted));
        EXPECT_TRUE(Same(h.measured, e.measured));
      }
    }
  }

  ASSERT_EQ(a.steps.size(), b.steps.size());
  for (std::size_t i = 0; i < a.steps.size(); ++i) {
    SCOPED_TRACE(a.steps[i].file);
    EXPECT_EQ(a.steps[i].level, b.steps[i].level);
    EXPECT_EQ(a.steps[i].file, b.steps[i].file);
    EXPECT_EQ(a.steps[i].frequency_hz, b.steps[i].frequency_hz);
    EXPECT_TRUE(Same(a.steps[i].force_N, b.steps[i].force_N));
    EXPECT_TRUE(Same(a.steps[i].state, b.steps[i].state));
  }
}

// The message of the InputError that `read` throws ("" and a failure otherwise).
std::string InputErrorOf(const std::function<void()>& read) {
  try {
    read();
  } catch (const InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not an InputError: " << e.what();
    return "";
  }
  ADD_FAILURE() << "read without complaint";
  return "";
}

// The text of `result` with one edit made to its JSON.
std::string Edited(const ResultFile& result, const std::function<void(Json&)>& edit) {
  Json j = Json::parse(ResultFileToJson(result));
  edit(j);
  return j.dump(1);
}

TEST(ResultFile, EveryFieldSurvivesTheTextAndBackAndTheTextIsStable) {
  for (const ResultFile& original : {HarmonicBalanceResult(), MultipleScalesResult()}) {
    SCOPED_TRACE(original.model.kind == ModelKind::kHarmonicBalance ? "hb" : "ms");
    const std::string text = ResultFileToJson(original);
    const ResultFile read = ResultFileFromJson(text, "memory");
    ExpectSame(original, read);
    EXPECT_EQ(ResultFileToJson(read), text);
  }
}

// The file of a real 3-step run (the fuzz seed; the tests run in the source
// folder), written by the writer before the declaration: the same text.
TEST(ResultFile, ARealRunsFileReadsAndIsWrittenBackAsTheSameText) {
  const std::string seed = "tests/fuzz/seeds/result_json_fuzzer/result.json";
  std::ifstream in(seed);
  ASSERT_TRUE(in) << seed;
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(ResultFileToJson(ResultFileFromJson(text, seed)), text);
}

TEST(ResultFile, TheDeclarationHoldsForEveryField) {
  for (const ResultFile& sample : {HarmonicBalanceResult(), MultipleScalesResult()}) {
    SCOPED_TRACE(sample.model.kind == ModelKind::kHarmonicBalance ? "hb" : "ms");
    beamid::testing::ExpectDeclarationHolds({
        .fields = ResultFileFields(),
        .sample = ResultFileToJson(sample),
        .read = [](const std::string& text) { ResultFileFromJson(text, "x.json"); },
        .rewrite = [](const std::string& text) { return ResultFileToJson(ResultFileFromJson(text, "x.json")); },
    });
  }
}

TEST(ResultFile, WritesTheVersionTheStateOfItsKindAndNullForNaN) {
  const std::string hb = ResultFileToJson(HarmonicBalanceResult());
  EXPECT_THAT(hb, HasSubstr("\"beamid_version\": \"9.8.7\""));
  EXPECT_THAT(hb, HasSubstr("\"absolute_folder\": \"/data/campaigns/base\""));
  EXPECT_THAT(hb, HasSubstr("\"campaign_sha256\": \"9f86d081"));
  EXPECT_THAT(hb, HasSubstr("\"relative_residual\": null"));
  EXPECT_THAT(hb, HasSubstr("\"theta_rad\""));
  EXPECT_THAT(hb, Not(HasSubstr("\"modal_phasor_m\"")));
  // Held-out channels in the order they were given, not sorted.
  EXPECT_LT(hb.find("\"acc4\": {"), hb.find("\"acc3\": {"));
  const std::string ms = ResultFileToJson(MultipleScalesResult());
  EXPECT_THAT(ms, HasSubstr("\"modal_phasor_m\""));
  EXPECT_THAT(ms, Not(HasSubstr("\"theta_rad\"")));
  EXPECT_THAT(ms, Not(HasSubstr("\"validation\"")));
  EXPECT_THAT(ms, Not(HasSubstr("\"beamid_version\"")));
  EXPECT_THAT(ms, Not(HasSubstr("\"absolute_folder\"")));
  EXPECT_THAT(ms, Not(HasSubstr("\"campaign_sha256\"")));
}

TEST(ResultFile, WrittenFileReadsBackAndGivesTheIdentifiedModel) {
  const std::filesystem::path file = testing::UniqueTempPath("result.json");
  const ResultFile original = HarmonicBalanceResult();
  WriteResultFile(file, original);
  ExpectSame(original, ReadResultFile(file));
  const IdentifiedModel model = ReadIdentifiedModel(file);
  std::filesystem::remove(file);
  EXPECT_EQ(model.family, &HarmonicBalanceFamily());
  EXPECT_EQ(model.num_harmonics, 7);
  EXPECT_EQ(model.beam.beam.thickness_m, 0.0051);
  ASSERT_EQ(model.beam.attachments.point_masses.size(), 2u);
  EXPECT_EQ(model.beam.attachments.point_masses[1].mass_kg, 0.0047);
  EXPECT_EQ(model.structure.Names(), (std::vector<std::string>{"k1", "k2", "k3", "c", "loss_factor"}));
  EXPECT_EQ(model.structure.Values(), (std::vector<double>{150.43, -31.5, 3.01e5, 0.0502, 2.1e-4}));
  EXPECT_TRUE(Same(model.covariance, original.covariance));
  ASSERT_EQ(model.steps.size(), 3u);
  EXPECT_DOUBLE_EQ(model.steps[2].omega_rad_s, 2 * std::numbers::pi * (52.0 + 0.9));
  EXPECT_TRUE(Same(model.steps[2].state, original.steps[2].state));
  EXPECT_TRUE(Same(model.steps[2].force_N, original.steps[2].force_N));

  const IdentifiedModel ms = ToIdentifiedModel(MultipleScalesResult());
  EXPECT_EQ(ms.family, &MultipleScalesFamily());
  EXPECT_EQ(ms.steps[1].state, MultipleScalesResult().steps[1].state);
}

// result.json as the writer before the typed result wrote it: keys sorted,
// no beamid_version, no campaign.absolute_folder (the command added it).
constexpr const char* kEarlierLayout = R"({
 "campaign": {"folder": "out/base", "name": "earlier campaign"},
 "command": "identify",
 "correlation": [[1.0, 0.5, -0.25, 0.125], [0.5, 1.0, 0.1, 0.2], [-0.25, 0.1, 1.0, 0.3], [0.125, 0.2, 0.3, 1.0]],
 "covariance": [[0.04, 1e-3, -2e-3, 1e-6], [1e-3, 2.5, 0.1, 2e-6], [-2e-3, 0.1, 1.6e5, 3e-4], [1e-6, 2e-6, 3e-4, 4e-8]],
 "fit": {"best_start": 0, "chi_square": 410.0, "degrees_of_freedom": 380,
  "direct_estimate": {"c": 0.049, "k1": 149.0, "k2": -3.0, "k3": 290000.0, "relative_residual": null},
  "minima": [{"chi_square": 410.0, "parameters": [150.1, 1.5, 301000.0, 0.0502], "starts": 1}],
  "minimum_decisive": true, "reduced_chi_square": 1.0789473684210527, "second_minimum_chi_square_gap": 0.0,
  "seconds": 3.5,
  "starts": [{"branch_repairs": 0, "converged": true, "iterations": 25, "objective": 205.0,
              "parameters": [150.1, 1.5, 301000.0, 0.0502], "start": [149.0, -3.0, 290000.0, 0.049],
              "states_seeded": "measured", "status": "Solve_Succeeded"}],
  "starts_at_best": 1},
 "format": "beamid-result/1",
 "linear_parameters": [],
 "model": {"beam": {"density_kg_m3": 7850.0, "length_m": 0.6, "loss_factor": 0.0, "thickness_m": 0.005,
                    "width_m": 0.04, "youngs_modulus_Pa": 210000000000.0},
           "fit_channels": ["acc1", "acc2"], "force_position_m": 0.57, "kind": "hb", "law": "polynomial",
           "num_fit_harmonics": 2, "num_harmonics": 3,
           "sensor_masses": [{"mass_kg": 0.005, "position_m": 0.1}]},
 "parameter_order": ["k1", "k2", "k3", "c"],
 "parameters": {"c": {"ci95": [0.0498, 0.0506], "std": 0.0002, "unit": "N*m*s/rad", "value": 0.0502},
                "k1": {"ci95": [149.7, 150.5], "std": 0.2, "unit": "N*m/rad", "value": 150.1},
                "k2": {"ci95": [-1.6, 4.6], "std": 1.58, "unit": "N*m/rad^2", "value": 1.5},
                "k3": {"ci95": [300216.0, 301784.0], "std": 400.0, "unit": "N*m/rad^3", "value": 301000.0}},
 "quality": {"acc1": {"h1": {"high": {"chi_square": 12.5, "relative_rms_error": 0.002, "steps": 1},
                             "low": {"chi_square": 3.5, "relative_rms_error": 0.004, "steps": 2}},
                      "h2": {"high": {"chi_square": 1.5, "relative_rms_error": 0.3, "steps": 1},
                             "low": {"chi_square": 0.5, "relative_rms_error": 0.6, "steps": 2}}},
             "acc2": {"h1": {"low": {"chi_square": 2.0, "relative_rms_error": 0.001, "steps": 2}},
                      "h2": {"low": {"chi_square": 1.0, "relative_rms_error": 0.5, "steps": 2}}}},
 "steps": [{"file": "low/step_000.csv", "force_N": [[0.0, 0.0], [1.0, 0.0], [0.01, -0.02], [0.0, 0.0]],
            "frequency_Hz": 53.25, "level": "low",
            "theta_rad": [[0.0, 0.0], [0.001, -0.0002], [1e-06, 1e-06], [2e-06, -1e-06]]}],
 "validation": {"acc3": {"measurable_relative_std": 0.01, "measurable_steps_h1": 1, "measurable_steps_h3": 0,
   "position_m": 0.45,
   "steps": [{"file": "low/step_000.csv", "frequency_Hz": 53.25, "level": "low",
              "h1_measured": [0.5, -0.25], "h1_measured_relative_std": 0.001, "h1_predicted": [0.502, -0.25],
              "h1_relative_error": 0.004, "h2_measured": [0.001, 0.0], "h2_measured_relative_std": 0.5,
              "h2_predicted": [0.0012, 0.0001], "h2_relative_error": 0.22}],
   "worst_h1_relative_error": 0.004, "worst_h3_relative_error": 0.0}},
 "warnings": ["the fit is worse than the phasor uncertainties allow"]
})";

TEST(ResultFile, AFileOfTheEarlierWriterStillReads) {
  const ResultFile r = ResultFileFromJson(kEarlierLayout, "earlier.json");
  EXPECT_EQ(r.beamid_version, "");
  EXPECT_EQ(r.campaign.folder, "out/base");
  EXPECT_EQ(r.campaign.name, "earlier campaign");
  EXPECT_EQ(r.campaign.absolute_folder, "");
  EXPECT_EQ(r.campaign.sha256, "");  // refused with any campaign (signal/campaign_identity.h)
  EXPECT_EQ(r.model.kind, ModelKind::kHarmonicBalance);
  EXPECT_EQ(r.model.beam.youngs_modulus_Pa, 2.1e11);
  EXPECT_EQ(r.model.fit_channels, (std::vector<std::string>{"acc1", "acc2"}));
  EXPECT_EQ(r.model.num_fit_harmonics, 2);
  // Weighed by the floor, the only weighting of its day; no σ budget.
  EXPECT_EQ(r.model.phasor_uncertainty, PhasorUncertainty::kRelativeFloor);
  EXPECT_EQ(r.quality[0].harmonics[0][0].relative_std.noise, 0.0);
  ASSERT_EQ(r.model.sensor_masses.size(), 1u);
  EXPECT_EQ(r.model.sensor_masses[0].mass_kg, 0.005);
  // The parameters in parameter_order, not in the file's (sorted) order.
  ASSERT_EQ(r.parameters.size(), 4u);
  EXPECT_EQ(r.parameters[0].name, "k1");
  EXPECT_EQ(r.parameters[3].name, "c");
  EXPECT_EQ(r.parameters[3].value, 0.0502);
  EXPECT_EQ(r.parameters[2].lower_95, 300216.0);
  EXPECT_EQ(r.parameters[1].unit, "N*m/rad^2");
  EXPECT_EQ(r.covariance(2, 1), 0.1);
  EXPECT_EQ(r.correlation(0, 3), 0.125);
  EXPECT_EQ(r.fit.degrees_of_freedom, 380);
  ASSERT_EQ(r.fit.starts.size(), 1u);
  EXPECT_EQ(r.fit.starts[0].states_seeded, StartRoute::kMeasuredStates);
  EXPECT_EQ(r.fit.starts[0].start[3], 0.049);
  EXPECT_TRUE(std::isnan(r.fit.direct_estimate.relative_residual));
  EXPECT_EQ(r.fit.direct_estimate.k3_Nm_rad3, 290000.0);
  ASSERT_EQ(r.quality.size(), 2u);
  ASSERT_EQ(r.quality[0].harmonics.size(), 2u);
  ASSERT_EQ(r.quality[0].harmonics[1].size(), 2u);
  EXPECT_EQ(r.quality[0].harmonics[1][1].level, "low");
  EXPECT_EQ(r.quality[0].harmonics[1][1].relative_rms_error, 0.6);
  EXPECT_EQ(r.quality[1].harmonics[0][0].num_steps, 2);
  ASSERT_EQ(r.validation.size(), 1u);
  EXPECT_EQ(r.validation[0].channel, "acc3");
  ASSERT_EQ(r.validation[0].steps.size(), 1u);
  ASSERT_EQ(r.validation[0].steps[0].harmonics.size(), 2u);
  EXPECT_EQ(r.validation[0].steps[0].harmonics[1].predicted, Complex(0.0012, 0.0001));
  EXPECT_EQ(r.validation[0].steps[0].harmonics[0].relative_error, 0.004);
  ASSERT_EQ(r.steps.size(), 1u);
  EXPECT_EQ(r.steps[0].state[1], Complex(0.001, -0.0002));
  EXPECT_EQ(r.steps[0].force_N[2], Complex(0.01, -0.02));
  EXPECT_EQ(r.warnings, (std::vector<std::string>{"the fit is worse than the phasor uncertainties allow"}));

  // And `beamid predict` rebuilds its model.
  const std::filesystem::path file = testing::UniqueTempPath("earlier.json");
  std::ofstream(file) << kEarlierLayout;
  const IdentifiedModel model = ReadIdentifiedModel(file);
  std::filesystem::remove(file);
  EXPECT_EQ(model.structure.Values(), (std::vector<double>{150.1, 1.5, 301000.0, 0.0502}));
  EXPECT_DOUBLE_EQ(model.steps[0].omega_rad_s, 2 * std::numbers::pi * 53.25);
}

TEST(ResultFile, FieldsAddedOverTimeMayBeAbsent) {
  // Files from before `--model ms` and the beam's loss factor.
  Json j = Json::parse(kEarlierLayout);
  j["model"].erase("kind");
  j["model"]["beam"].erase("loss_factor");
  j.erase("validation");
  const ResultFile r = ResultFileFromJson(j.dump(), "older.json");
  EXPECT_EQ(r.model.kind, ModelKind::kHarmonicBalance);
  EXPECT_EQ(r.model.beam.loss_factor, 0.0);
  EXPECT_TRUE(r.validation.empty());
}

TEST(ResultFile, AWrongFormatOrNoJsonIsRefusedNamingTheFile) {
  std::string message = InputErrorOf([] {
    ResultFileFromJson(R"({"format": "beamid-phasors/1", "steps": []})", "out/phasors.json");
  });
  EXPECT_THAT(message, HasSubstr("out/phasors.json: field \"format\" is \"beamid-phasors/1\", not \"beamid-result/1\""));
  message = InputErrorOf([] { ResultFileFromJson("[1, 2]", "list.json"); });
  EXPECT_THAT(message, HasSubstr("list.json: not a beamid result"));
  message = InputErrorOf([] { ResultFileFromJson(R"({"format": "beamid-result/1",)", "cut.json"); });
  EXPECT_THAT(message, HasSubstr("cut.json: not valid JSON"));
  const std::filesystem::path missing = testing::UniqueTempPath("no_such_result.json");
  message = InputErrorOf([&] { ReadResultFile(missing); });
  EXPECT_THAT(message, HasSubstr(missing.string()));
  EXPECT_THAT(message, HasSubstr("result file"));
}

TEST(ResultFile, AMissingFieldIsRefusedNamingTheFileAndTheField) {
  const ResultFile hb = HarmonicBalanceResult();
  const struct {
    std::function<void(Json&)> edit;
    const char* field;
  } cases[] = {
      {[](Json& j) { j["fit"].erase("chi_square"); }, "field \"fit.chi_square\" is missing"},
      {[](Json& j) { j.erase("steps"); }, "field \"steps\" is missing"},
      {[](Json& j) { j["steps"][1].erase("theta_rad"); }, "field \"steps[1].theta_rad\" is missing"},
      {[](Json& j) { j["fit"]["starts"][2].erase("status"); }, "field \"fit.starts[2].status\" is missing"},
      {[](Json& j) { j["quality"]["acc1"].erase("h2"); }, "field \"quality.acc1.h2\" is missing"},
      {[](Json& j) { j["validation"]["acc3"]["steps"][0].erase("h3_predicted"); },
       "field \"validation.acc3.steps[0].h3_predicted\" is missing"},
      {[](Json& j) { j["parameters"].erase("k3"); }, "field \"parameters\" breaks the rule: parameters holds exactly the parameters parameter_order names: it "
       "holds 4, parameter_order names 5"},
      {[](Json& j) { j["campaign"].erase("name"); }, "field \"campaign.name\" is missing"},
  };
  for (const auto& c : cases) {
    const std::string text = Edited(hb, c.edit);
    const std::string message = InputErrorOf([&] { ResultFileFromJson(text, "out/result.json"); });
    EXPECT_THAT(message, HasSubstr("out/result.json: " + std::string(c.field)));
    EXPECT_THAT(message, HasSubstr("Fix: "));
  }
}

TEST(ResultFile, AFieldOfTheWrongTypeIsRefusedNamingTheFileAndTheField) {
  const ResultFile hb = HarmonicBalanceResult();
  const struct {
    std::function<void(Json&)> edit;
    const char* message;
  } cases[] = {
      {[](Json& j) { j["model"]["num_harmonics"] = "seven"; }, "field \"model.num_harmonics\" must be an integer"},
      {[](Json& j) { j["model"]["num_fit_harmonics"] = 2.5; }, "field \"model.num_fit_harmonics\" must be an integer"},
      {[](Json& j) { j["model"]["num_fit_harmonics"] = 8; }, "field \"model.num_fit_harmonics\" breaks the rule: num_fit_harmonics <= num_harmonics: 8 > 7"},
      {[](Json& j) { j["model"]["beam"]["length_m"] = -0.6; }, "field \"model.beam.length_m\" = -0.6 lies outside > 0"},
      {[](Json& j) { j["parameters"]["k1"]["value"] = "150"; }, "field \"parameters.k1.value\" must be a number, not a string"},
      // NaN is allowed for a statistic, never for the model the prediction rebuilds.
      {[](Json& j) { j["model"]["beam"]["length_m"] = nullptr; }, "field \"model.beam.length_m\" must be a number, not null"},
      {[](Json& j) { j["fit"]["starts"][0]["converged"] = 1; }, "field \"fit.starts[0].converged\" must be true or false, not a number"},
      {[](Json& j) { j["fit"]["starts"][1]["states_seeded"] = "guessed"; },
       "field \"fit.starts[1].states_seeded\" is \"guessed\", not one of \"measured\", \"feasible\""},
      {[](Json& j) { j["model"]["kind"] = "duffing"; }, "field \"model.kind\" is \"duffing\", not one of \"hb\", \"ms\""},
      {[](Json& j) { j["warnings"] = "none"; }, "field \"warnings\" must be an array, not a string"},
      {[](Json& j) { j["quality"] = Json::array(); }, "field \"quality\" must be an object, not an array"},
      {[](Json& j) { j["covariance"].erase(4); }, "field \"covariance\" holds 4 entries, not exactly one per parameter"},
      {[](Json& j) { j["steps"][0]["force_N"][1] = Json::array({1.0}); }, "field \"steps[0].force_N[1]\" must be [re, im], not 1 numbers"},
  };
  for (const auto& c : cases) {
    const std::string text = Edited(hb, c.edit);
    const std::string message = InputErrorOf([&] { ResultFileFromJson(text, "out/result.json"); });
    EXPECT_THAT(message, HasSubstr("out/result.json: " + std::string(c.message)));
  }
  // A multiple-scales step holds one modal phasor.
  const std::string text = Edited(MultipleScalesResult(), [](Json& j) {
    j["steps"][0]["modal_phasor_m"].push_back(Json::array({1.0, 2.0}));
  });
  EXPECT_THAT(InputErrorOf([&] { ResultFileFromJson(text, "ms.json"); }),
              HasSubstr("ms.json: field \"steps[0].modal_phasor_m\" holds 2 entries, not exactly the model's state size "
                        "(theta_rad: num_harmonics + 1, modal_phasor_m: 1)"));
}

TEST(ResultFile, AModelPredictCannotRebuildIsRefusedNamingTheFileAndTheField) {
  ResultFile other_law = MultipleScalesResult();
  other_law.model.law = "jenkins";
  const std::filesystem::path file = testing::UniqueTempPath("jenkins_result.json");
  WriteResultFile(file, other_law);
  const std::string message = InputErrorOf([&] { ReadIdentifiedModel(file); });
  std::filesystem::remove(file);
  EXPECT_THAT(message, HasSubstr(file.string() + ": model.law 'jenkins': only the polynomial law can be predicted"));
  ResultFile unknown = HarmonicBalanceResult();
  unknown.linear_parameters = {"clamp_compliance"};
  EXPECT_THAT(InputErrorOf([&] { ToIdentifiedModel(unknown); }), HasSubstr("linear_parameters: "));
  // Values go to the law by position: names out of order would swap them.
  ResultFile swapped = MultipleScalesResult();
  std::swap(swapped.parameters[1], swapped.parameters[2]);
  EXPECT_THAT(InputErrorOf([&] { ToIdentifiedModel(swapped); }),
              HasSubstr("parameter_order: the polynomial law with linear_parameters takes the parameters k1, k2, k3, c"));
}

}  // namespace
}  // namespace beamid::solver
