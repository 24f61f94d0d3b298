// diagnosis.json (solver/diagnosis/diagnosis_io.h): everything the writer
// writes reads back to the same struct, bit for bit (NaN included), and the
// text read and written again is the same text; a file of the first layout
// (before beamid_version, response, extra_parameter_names) still reads; a
// damaged file is refused naming the file, the field and the fix. Also the
// worker processes' record of a candidate refit, which must carry every
// double exactly for the diagnosis to be the same with any number of workers.
#include "solver/diagnosis/diagnosis_io.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <functional>
#include <limits>
#include <random>

#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hb/errors.h"
#include "tests/support/same_value.h"
#include "tests/support/schema_checks.h"
#include "tests/support/temp_path.h"

namespace beamid::solver {
namespace {

using beamid::testing::Same;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Same double: same bits, so that NaN equals NaN and -0 differs from 0.
// ---------------------------------------------------------------- a file with every field set

FitSummary Fit(double seed, const std::vector<std::string>& names) {
  FitSummary s;
  for (std::size_t j = 0; j < names.size(); ++j)
    s.parameters.push_back({.name = names[j],
                            .unit = "unit_" + names[j],
                            .value = seed * (j + 1.3) / 7.0,
                            .std = seed * 1e-3 / (j + 3.0),
                            .lower_95 = seed * (j + 1.1) / 7.0,
                            .upper_95 = seed * (j + 1.7) / 7.0});
  s.model_harmonics = 3 + static_cast<int>(seed) % 7;
  s.chi_square = seed * 123.456789;
  s.degrees_of_freedom = 150 + static_cast<int>(seed);
  s.num_residuals = 160 + static_cast<int>(seed);
  s.reduced_chi_square = s.chi_square / s.degrees_of_freedom;
  s.aic = s.chi_square + 2.0 / 3.0;
  s.bic = s.chi_square + std::log(161.0) / 3.0;
  s.held_out_chi_square = seed * 9.87654321e3;
  s.held_out_h1_relative_error = 1.0 / (seed + 11.0);
  s.held_out_num_residuals = 90 + static_cast<int>(seed);
  return s;
}

MisfitLocation Location() {
  MisfitLocation m;
  m.chi2 = 4321.0987654;
  m.dof = 147;
  m.p_value = 1.234e-300;
  m.significant = true;
  m.num_groups_tested = 2;
  m.groups.push_back({.channel = "acc1", .harmonic = 3, .level = "high", .part = ResidualPart::kInPhase,
                      .band = FrequencyBand::kNearResonance, .chi2 = 91.5 / 7.0, .dof = 9, .p_value = 0.1 / 3.0,
                      .adjusted_p_value = 0.7 / 3.0, .significant = false, .excess_chi2 = 4.0 / 7.0,
                      .growth_exponent = kNaN});
  m.groups.push_back({.channel = "", .harmonic = 0, .level = "", .part = ResidualPart::kBoth, .band = FrequencyBand::kAll,
                      .chi2 = 1e5 / 3.0, .dof = 300, .p_value = 5e-310, .adjusted_p_value = 1e-308,
                      .significant = true, .excess_chi2 = 1e5 / 3.0 - 300.0, .growth_exponent = 2.0 / 3.0});
  m.in_phase_fraction = 0.1 / 3.0;
  m.near_resonance_fraction = 0.2 / 3.0;
  m.fundamental_fraction = 0.4 / 3.0;
  m.even_harmonic_fraction = 0.5 / 3.0;
  m.beyond_fitted_fraction = 0.7 / 3.0;
  m.harmonic_excess_chi2 = {1.0 / 3.0, 2.0 / 7.0, kNaN, 0.0, -0.0};
  m.channel_excess_chi2 = {10.0 / 3.0, 20.0 / 7.0};
  m.level_growth_exponent = 2.0 / 9.0;
  m.level_misfit_amplitude = {1e-7 / 3.0, 2e-7 / 3.0};
  m.level_response_amplitude = {3.0 / 11.0, 5.0 / 11.0};
  LoopStep step{.level = "mid",
                .omega_rad_s = 2.0 * 3.141592653589793 * 52.75 + 1e-9,
                .theta_amplitude_rad = 1e-3 / 3.0,
                .theta_std_rad = 1e-6 / 7.0,
                .moment_amplitude_Nm = 0.3 / 7.0,
                .dissipated_energy_J = 1e-5 / 3.0,
                .dissipated_energy_std_J = 1e-7 / 3.0,
                .viscous_energy_J = 0.9e-5 / 7.0,
                .equivalent_damping_Nms_rad = 0.05 / 3.0,
                .equivalent_damping_std_Nms_rad = 0.001 / 3.0,
                .moment_harmonic_ratio = 0.02 / 3.0,
                .elastic_harmonic_chi2 = 17.0 / 3.0,
                .hysteretic_harmonic_chi2 = 19.0 / 7.0,
                .harmonic_dof = 4,
                .theta_even_fraction = 0.003 / 7.0,
                .moment_even_fraction = 0.004 / 7.0};
  m.loops.steps = {step, step};
  m.loops.steps[1].level = "high";
  m.loops.steps[1].omega_rad_s = 2.0 * 3.141592653589793 * 53.5 / 3.0;
  m.loops.num_steps_used = 2;
  m.loops.area_exponent = 2.0 + 1.0 / 3.0;
  m.loops.area_exponent_std = kNaN;
  m.loops.viscous_chi2 = 33.0 / 7.0;
  m.loops.viscous_dof = 1;
  m.loops.viscous_p_value = 0.03 / 7.0;
  m.loops.mean_equivalent_damping_Nms_rad = 0.05 / 7.0;
  m.loops.damping_ratio_high_to_low = 1.5 / 7.0;
  m.loops.elastic_harmonic_chi2 = 41.0 / 3.0;
  m.loops.hysteretic_harmonic_chi2 = 43.0 / 3.0;
  m.loops.harmonic_dof = 8;
  m.loops.elastic_harmonic_p_value = 1e-4 / 3.0;
  m.loops.hysteretic_harmonic_p_value = 2e-4 / 3.0;
  m.loops.max_moment_harmonic_ratio = 0.07 / 3.0;
  m.loops.theta_even_chi2 = 5.0 / 3.0;
  m.loops.theta_even_dof = 6;
  m.loops.theta_even_p_value = 0.9 / 7.0;
  m.loops.dissipation_not_viscous = true;
  m.loops.non_elliptic = false;
  m.loops.hysteretic_shape = true;
  m.loops.asymmetric = false;
  m.findings = {"The base model misses acc1, harmonic 3 (\"in phase\").", "Second, with ünïcode: χ² and θ."};
  return m;
}

DiagnosisFile FullFile(bool with_location) {
  DiagnosisFile file;
  DiagnosisResult& r = file.diagnosis;
  // Not in alphabetical order: the model's order must survive.
  r.base = Fit(1.0, {"k1", "k3", "c", "loss_factor"});
  r.base.held_out_chi_square = kNaN;  // no held-out channel
  r.base.held_out_h1_relative_error = kNaN;
  if (with_location) r.location = Location();
  else r.location_error = "the reference beam has no support law";
  CandidateOutcome friction{.name = "support_friction",
                            .description = "Jenkins element in parallel",
                            .signature_score = 0.8 / 3.0,
                            .extra_parameters = {"jenkins_stiffness", "jenkins_slip_moment"},
                            .status = RefitStatus::kRefitted,
                            .fit = Fit(2.0, {"k1", "k3", "c", "loss_factor", "jenkins_stiffness",
                                             "jenkins_slip_moment"}),
                            .likelihood_ratio = 4.3e4 / 3.0,
                            .test_dof = 2,
                            .p_value = 0.0,
                            .residual_drop = 4.3e4 / 7.0,
                            .significant = true,
                            .seconds = 12.0 / 7.0};
  CandidateOutcome failed{.name = "added_mass",
                          .description = "a point mass",
                          .signature_score = 0.1 / 7.0,
                          .extra_parameters = {"added_mass_position", "added_mass"},
                          .status = RefitStatus::kFailed,
                          .status_message = "Ipopt stopped",
                          .fit = {},
                          .likelihood_ratio = 0.0,
                          .test_dof = 2,
                          .p_value = 1.0,
                          .residual_drop = 1.0,
                          .significant = false,
                          .seconds = 0.5 / 3.0};
  CandidateOutcome truncation{.name = "harmonic_truncation",
                              .description = "the balance with 2H+1 harmonics",
                              .signature_score = 0.0,
                              .extra_parameters = {},
                              .status = RefitStatus::kRefitted,
                              .fit = Fit(3.0, {"k1", "k3", "c", "loss_factor"}),
                              .likelihood_ratio = 5.0 / 3.0,
                              .test_dof = 1,
                              .p_value = 0.2 / 3.0,
                              .residual_drop = 1.01 / 3.0,
                              .significant = false,
                              .seconds = 3.0 / 7.0};
  r.candidates = {friction, failed, truncation};
  CandidateOutcome pair = truncation;
  pair.name = "support_friction + harmonic_truncation";
  pair.rig_check = "inspect the rod contact; and analyse with more harmonics";
  pair.extra_parameters = {"jenkins_stiffness", "jenkins_slip_moment"};
  r.combinations = {pair};
  r.selected = {"support_friction"};
  r.verdict = DiagnosisVerdict::kCauseNamed;
  r.ranked_by = RankedBy::kHeldOutChannels;
  r.blame = Blame::kModel;
  r.recording_findings = {"step 3 of \"high\": cut before it settled"};
  r.rest_within_noise = false;  // not the default
  r.suggestion = MeasurementSuggestion{.first = "added_mass",
                                       .second = "modulus_error",
                                       .positions = {{.position_m = 0.015, .expected_chi_square_difference = 1.0 / 3.0},
                                                     {.position_m = 0.45, .expected_chi_square_difference = 47.0 / 3.0}},
                                       .best = {.position_m = 0.45, .expected_chi_square_difference = 47.0 / 3.0},
                                       .current_expected = 2.0 / 7.0,
                                       .levels = {{.level = "low", .share = 0.25}, {.level = "high", .share = 0.75}},
                                       .focus_low_hz = 53.25,
                                       .focus_high_hz = 54.75,
                                       .text = "add an accelerometer at x = 0.450 m"};
  r.final_fit = friction.fit;
  r.final_extra_parameters = friction.extra_parameters;
  // The selected model under two damping laws; the reader judges them again.
  r.final_damping_laws.laws.push_back(DampingLawFitOf("loss_factor", friction.fit.parameters, 27.0 / 7.0, 11));
  std::vector<ParameterEstimate> rayleigh = friction.fit.parameters;
  for (ParameterEstimate& p : rayleigh) {
    p.value *= 1.0 + 1.0 / 3.0e3;
    p.upper_95 += p.std;
  }
  rayleigh.push_back({.name = "rayleigh_mass_1_s", .unit = "1/s", .value = 0.1 / 3.0, .std = 1e-3 / 7.0,
                      .lower_95 = 0.1 / 3.0 - 2e-3 / 7.0, .upper_95 = 0.1 / 3.0 + 2e-3 / 7.0});
  r.final_damping_laws.laws.push_back(DampingLawFitOf("rayleigh", rayleigh, 25.0 / 7.0, 10));
  r.final_damping_laws.laws.push_back({.law = "mass_proportional", .status = "failed: Ipopt stopped"});
  JudgeDampingLaws(&r.final_damping_laws);
  r.response.push_back({.level = "low", .frequency_hz = 51.75, .channel = "acc1", .held_out = false,
                        .measured = {-0.5 / 3.0, 1.0 / 7.0}, .base_model = {-0.51 / 3.0, 1.01 / 7.0},
                        .final_model = {-0.501 / 3.0, 1.001 / 7.0},
                        .base_misfit_sigma = {31.0 / 7.0, 2.0 / 3.0, std::nan("")},
                        .final_misfit_sigma = {0.9 / 7.0, 1e-300, 0.0}});
  r.response.push_back({.level = "high", .frequency_hz = 56.0 / 3.0 * 3.0 + 1e-12, .channel = "acc3",
                        .held_out = true, .measured = {2.0 / 3.0, -0.0}, .base_model = {1e-300, -1e-300},
                        .final_model = {2.0 / 3.0, 5e-324}});
  r.final_backbone = {.channel = "acc1", .position_m = 0.3 / 7.0};
  r.final_backbone.points = {{.amplitude_m = 1e-5 / 3.0, .frequency_hz = 53.0 + 1.0 / 7.0},
                             {.amplitude_m = 2e-4 / 3.0, .frequency_hz = 55.0 / 3.0 * 3.0}};
  r.summary = "Base model: reduced chi-square 27.3. Missing physics: support_friction.";
  r.seconds = 61.0 / 7.0;
  file.campaign_folder = "campaigns/friction";
  file.campaign_name = "concealed friction";
  file.campaign_sha256 = "9f86d081884c7d659a2feaa0c55ad015a3bf4f1b2b0b822cd15d6c15b0f00a08";
  file.result_file = "runs/identify/result.json";
  file.embedded_result_json =
      R"({"format":"beamid-result/1","parameters":{"k1":{"value":120.5}},"fit":{"chi_square":null}})";
  file.beamid_version = "9.8.7-test";
  file.phasor_uncertainty = PhasorUncertainty::kPropagated;
  return file;
}

// ---------------------------------------------------------------- comparison of every field

void ExpectSameFit(const FitSummary& a, const FitSummary& b, const std::string& where) {
  SCOPED_TRACE(where);
  ASSERT_EQ(a.parameters.size(), b.parameters.size());
  for (std::size_t j = 0; j < a.parameters.size(); ++j) {
    EXPECT_EQ(a.parameters[j].name, b.parameters[j].name);
    EXPECT_EQ(a.parameters[j].unit, b.parameters[j].unit);
    EXPECT_TRUE(Same(a.parameters[j].value, b.parameters[j].value));
    EXPECT_TRUE(Same(a.parameters[j].std, b.parameters[j].std));
    EXPECT_TRUE(Same(a.parameters[j].lower_95, b.parameters[j].lower_95));
    EXPECT_TRUE(Same(a.parameters[j].upper_95, b.parameters[j].upper_95));
  }
  EXPECT_EQ(a.model_harmonics, b.model_harmonics);
  EXPECT_TRUE(Same(a.chi_square, b.chi_square));
  EXPECT_EQ(a.degrees_of_freedom, b.degrees_of_freedom);
  EXPECT_EQ(a.num_residuals, b.num_residuals);
  EXPECT_TRUE(Same(a.reduced_chi_square, b.reduced_chi_square));
  EXPECT_TRUE(Same(a.aic, b.aic));
  EXPECT_TRUE(Same(a.bic, b.bic));
  EXPECT_TRUE(Same(a.held_out_chi_square, b.held_out_chi_square));
  EXPECT_TRUE(Same(a.held_out_h1_relative_error, b.held_out_h1_relative_error));
  EXPECT_EQ(a.held_out_num_residuals, b.held_out_num_residuals);
}

void ExpectSameNumbers(const std::vector<double>& a, const std::vector<double>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_TRUE(Same(a[i], b[i])) << "element " << i;
}

void ExpectSameLoops(const LoopEvidence& a, const LoopEvidence& b) {
  ASSERT_EQ(a.steps.size(), b.steps.size());
  for (std::size_t i = 0; i < a.steps.size(); ++i) {
    const LoopStep &x = a.steps[i], &y = b.steps[i];
    EXPECT_EQ(x.level, y.level);
    EXPECT_TRUE(Same(x.omega_rad_s, y.omega_rad_s));
    EXPECT_TRUE(Same(x.theta_amplitude_rad, y.theta_amplitude_rad));
    EXPECT_TRUE(Same(x.theta_std_rad, y.theta_std_rad));
    EXPECT_TRUE(Same(x.moment_amplitude_Nm, y.moment_amplitude_Nm));
    EXPECT_TRUE(Same(x.dissipated_energy_J, y.dissipated_energy_J));
    EXPECT_TRUE(Same(x.dissipated_energy_std_J, y.dissipated_energy_std_J));
    EXPECT_TRUE(Same(x.viscous_energy_J, y.viscous_energy_J));
    EXPECT_TRUE(Same(x.equivalent_damping_Nms_rad, y.equivalent_damping_Nms_rad));
    EXPECT_TRUE(Same(x.equivalent_damping_std_Nms_rad, y.equivalent_damping_std_Nms_rad));
    EXPECT_TRUE(Same(x.moment_harmonic_ratio, y.moment_harmonic_ratio));
    EXPECT_TRUE(Same(x.elastic_harmonic_chi2, y.elastic_harmonic_chi2));
    EXPECT_TRUE(Same(x.hysteretic_harmonic_chi2, y.hysteretic_harmonic_chi2));
    EXPECT_EQ(x.harmonic_dof, y.harmonic_dof);
    EXPECT_TRUE(Same(x.theta_even_fraction, y.theta_even_fraction));
    EXPECT_TRUE(Same(x.moment_even_fraction, y.moment_even_fraction));
  }
  EXPECT_EQ(a.num_steps_used, b.num_steps_used);
  EXPECT_TRUE(Same(a.area_exponent, b.area_exponent));
  EXPECT_TRUE(Same(a.area_exponent_std, b.area_exponent_std));
  EXPECT_TRUE(Same(a.viscous_chi2, b.viscous_chi2));
  EXPECT_EQ(a.viscous_dof, b.viscous_dof);
  EXPECT_TRUE(Same(a.viscous_p_value, b.viscous_p_value));
  EXPECT_TRUE(Same(a.mean_equivalent_damping_Nms_rad, b.mean_equivalent_damping_Nms_rad));
  EXPECT_TRUE(Same(a.damping_ratio_high_to_low, b.damping_ratio_high_to_low));
  EXPECT_TRUE(Same(a.elastic_harmonic_chi2, b.elastic_harmonic_chi2));
  EXPECT_TRUE(Same(a.hysteretic_harmonic_chi2, b.hysteretic_harmonic_chi2));
  EXPECT_EQ(a.harmonic_dof, b.harmonic_dof);
  EXPECT_TRUE(Same(a.elastic_harmonic_p_value, b.elastic_harmonic_p_value));
  EXPECT_TRUE(Same(a.hysteretic_harmonic_p_value, b.hysteretic_harmonic_p_value));
  EXPECT_TRUE(Same(a.max_moment_harmonic_ratio, b.max_moment_harmonic_ratio));
  EXPECT_TRUE(Same(a.theta_even_chi2, b.theta_even_chi2));
  EXPECT_EQ(a.theta_even_dof, b.theta_even_dof);
  EXPECT_TRUE(Same(a.theta_even_p_value, b.theta_even_p_value));
  EXPECT_EQ(a.dissipation_not_viscous, b.dissipation_not_viscous);
  EXPECT_EQ(a.non_elliptic, b.non_elliptic);
  EXPECT_EQ(a.hysteretic_shape, b.hysteretic_shape);
  EXPECT_EQ(a.asymmetric, b.asymmetric);
}

void ExpectSameLocation(const MisfitLocation& a, const MisfitLocation& b) {
  EXPECT_TRUE(Same(a.chi2, b.chi2));
  EXPECT_EQ(a.dof, b.dof);
  EXPECT_TRUE(Same(a.p_value, b.p_value));
  EXPECT_EQ(a.significant, b.significant);
  EXPECT_EQ(a.num_groups_tested, b.num_groups_tested);
  ASSERT_EQ(a.groups.size(), b.groups.size());
  for (std::size_t i = 0; i < a.groups.size(); ++i) {
    const MisfitGroupTest &x = a.groups[i], &y = b.groups[i];
    EXPECT_EQ(x.channel, y.channel);
    EXPECT_EQ(x.harmonic, y.harmonic);
    EXPECT_EQ(x.level, y.level);
    EXPECT_EQ(x.part, y.part);
    EXPECT_EQ(x.band, y.band);
    EXPECT_TRUE(Same(x.chi2, y.chi2));
    EXPECT_EQ(x.dof, y.dof);
    EXPECT_TRUE(Same(x.p_value, y.p_value));
    EXPECT_TRUE(Same(x.adjusted_p_value, y.adjusted_p_value));
    EXPECT_EQ(x.significant, y.significant);
    EXPECT_TRUE(Same(x.excess_chi2, y.excess_chi2));
    EXPECT_TRUE(Same(x.growth_exponent, y.growth_exponent));
  }
  EXPECT_TRUE(Same(a.in_phase_fraction, b.in_phase_fraction));
  EXPECT_TRUE(Same(a.near_resonance_fraction, b.near_resonance_fraction));
  EXPECT_TRUE(Same(a.fundamental_fraction, b.fundamental_fraction));
  EXPECT_TRUE(Same(a.even_harmonic_fraction, b.even_harmonic_fraction));
  EXPECT_TRUE(Same(a.beyond_fitted_fraction, b.beyond_fitted_fraction));
  ExpectSameNumbers(a.harmonic_excess_chi2, b.harmonic_excess_chi2);
  ExpectSameNumbers(a.channel_excess_chi2, b.channel_excess_chi2);
  EXPECT_TRUE(Same(a.level_growth_exponent, b.level_growth_exponent));
  ExpectSameNumbers(a.level_misfit_amplitude, b.level_misfit_amplitude);
  ExpectSameNumbers(a.level_response_amplitude, b.level_response_amplitude);
  ExpectSameLoops(a.loops, b.loops);
  EXPECT_EQ(a.findings, b.findings);
}

void ExpectSameCandidates(const std::vector<CandidateOutcome>& xs, const std::vector<CandidateOutcome>& ys) {
  ASSERT_EQ(xs.size(), ys.size());
  for (std::size_t i = 0; i < xs.size(); ++i) {
    const CandidateOutcome &c = xs[i], &d = ys[i];
    SCOPED_TRACE(c.name);
    EXPECT_EQ(c.name, d.name);
    EXPECT_EQ(c.description, d.description);
    EXPECT_EQ(c.rig_check, d.rig_check);
    EXPECT_TRUE(Same(c.signature_score, d.signature_score));
    EXPECT_EQ(c.extra_parameters, d.extra_parameters);
    EXPECT_EQ(c.status, d.status);
    EXPECT_EQ(c.status_message, d.status_message);
    ExpectSameFit(c.fit, d.fit, "candidate fit");
    EXPECT_TRUE(Same(c.likelihood_ratio, d.likelihood_ratio));
    EXPECT_EQ(c.test_dof, d.test_dof);
    EXPECT_TRUE(Same(c.p_value, d.p_value));
    EXPECT_TRUE(Same(c.residual_drop, d.residual_drop));
    EXPECT_EQ(c.significant, d.significant);
    EXPECT_TRUE(Same(c.seconds, d.seconds));
  }
}

void ExpectSameFile(const DiagnosisFile& a, const DiagnosisFile& b) {
  EXPECT_EQ(a.campaign_folder, b.campaign_folder);
  EXPECT_EQ(a.campaign_name, b.campaign_name);
  EXPECT_EQ(a.campaign_sha256, b.campaign_sha256);
  EXPECT_EQ(a.result_file, b.result_file);
  EXPECT_EQ(a.embedded_result_json, b.embedded_result_json);
  EXPECT_EQ(a.beamid_version, b.beamid_version);
  EXPECT_EQ(a.phasor_uncertainty, b.phasor_uncertainty);
  const DiagnosisResult &x = a.diagnosis, &y = b.diagnosis;
  ExpectSameFit(x.base, y.base, "base");
  ASSERT_EQ(x.location.has_value(), y.location.has_value());
  if (x.location) ExpectSameLocation(*x.location, *y.location);
  EXPECT_EQ(x.location_error, y.location_error);
  ExpectSameCandidates(x.candidates, y.candidates);
  ExpectSameCandidates(x.combinations, y.combinations);
  EXPECT_EQ(x.selected, y.selected);
  EXPECT_EQ(x.verdict, y.verdict);
  EXPECT_EQ(x.ranked_by, y.ranked_by);
  EXPECT_EQ(x.blame, y.blame);
  EXPECT_EQ(x.recording_findings, y.recording_findings);
  EXPECT_EQ(x.rest_within_noise, y.rest_within_noise);
  ASSERT_EQ(x.suggestion.has_value(), y.suggestion.has_value());
  if (x.suggestion) {
    const MeasurementSuggestion &m = *x.suggestion, &n = *y.suggestion;
    EXPECT_EQ(m.first, n.first);
    EXPECT_EQ(m.second, n.second);
    ASSERT_EQ(m.positions.size(), n.positions.size());
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
      EXPECT_TRUE(Same(m.positions[i].position_m, n.positions[i].position_m));
      EXPECT_TRUE(Same(m.positions[i].expected_chi_square_difference, n.positions[i].expected_chi_square_difference));
    }
    EXPECT_TRUE(Same(m.best.position_m, n.best.position_m));
    EXPECT_TRUE(Same(m.best.expected_chi_square_difference, n.best.expected_chi_square_difference));
    EXPECT_TRUE(Same(m.current_expected, n.current_expected));
    ASSERT_EQ(m.levels.size(), n.levels.size());
    for (std::size_t i = 0; i < m.levels.size(); ++i) {
      EXPECT_EQ(m.levels[i].level, n.levels[i].level);
      EXPECT_TRUE(Same(m.levels[i].share, n.levels[i].share));
    }
    EXPECT_TRUE(Same(m.focus_low_hz, n.focus_low_hz));
    EXPECT_TRUE(Same(m.focus_high_hz, n.focus_high_hz));
    EXPECT_EQ(m.text, n.text);
  }
  ExpectSameFit(x.final_fit, y.final_fit, "final");
  EXPECT_EQ(x.final_extra_parameters, y.final_extra_parameters);
  const DampingLawEnvelope &xl = x.final_damping_laws, &yl = y.final_damping_laws;
  ASSERT_EQ(xl.laws.size(), yl.laws.size());
  for (std::size_t i = 0; i < xl.laws.size(); ++i) {
    EXPECT_EQ(xl.laws[i].law, yl.laws[i].law);
    EXPECT_EQ(xl.laws[i].converged, yl.laws[i].converged);
    EXPECT_EQ(xl.laws[i].status, yl.laws[i].status);
    EXPECT_EQ(xl.laws[i].accepted, yl.laws[i].accepted);
    EXPECT_TRUE(Same(xl.laws[i].chi_square, yl.laws[i].chi_square));
    ASSERT_EQ(xl.laws[i].parameters.size(), yl.laws[i].parameters.size());
    for (std::size_t j = 0; j < xl.laws[i].parameters.size(); ++j) {
      EXPECT_EQ(xl.laws[i].parameters[j].name, yl.laws[i].parameters[j].name);
      EXPECT_TRUE(Same(xl.laws[i].parameters[j].value, yl.laws[i].parameters[j].value));
      EXPECT_TRUE(Same(xl.laws[i].parameters[j].upper_95, yl.laws[i].parameters[j].upper_95));
    }
  }
  ASSERT_EQ(xl.intervals.size(), yl.intervals.size());
  for (std::size_t i = 0; i < xl.intervals.size(); ++i) {
    EXPECT_EQ(xl.intervals[i].name, yl.intervals[i].name);
    EXPECT_TRUE(Same(xl.intervals[i].lower_95, yl.intervals[i].lower_95));
    EXPECT_TRUE(Same(xl.intervals[i].upper_95, yl.intervals[i].upper_95));
    EXPECT_EQ(xl.intervals[i].depends_on_damping_law, yl.intervals[i].depends_on_damping_law);
  }
  ASSERT_EQ(x.response.size(), y.response.size());
  for (std::size_t i = 0; i < x.response.size(); ++i) {
    const ResponsePoint &p = x.response[i], &q = y.response[i];
    EXPECT_EQ(p.level, q.level);
    EXPECT_TRUE(Same(p.frequency_hz, q.frequency_hz));
    EXPECT_EQ(p.channel, q.channel);
    EXPECT_EQ(p.held_out, q.held_out);
    for (const auto& [u, v] : {std::pair{p.measured, q.measured}, std::pair{p.base_model, q.base_model},
                               std::pair{p.final_model, q.final_model}}) {
      EXPECT_TRUE(Same(u.real(), v.real()));
      EXPECT_TRUE(Same(u.imag(), v.imag()));
    }
    ExpectSameNumbers(p.base_misfit_sigma, q.base_misfit_sigma);
    ExpectSameNumbers(p.final_misfit_sigma, q.final_misfit_sigma);
  }
  EXPECT_EQ(x.final_backbone.channel, y.final_backbone.channel);
  EXPECT_TRUE(Same(x.final_backbone.position_m, y.final_backbone.position_m));
  EXPECT_EQ(x.final_backbone.error, y.final_backbone.error);
  ASSERT_EQ(x.final_backbone.points.size(), y.final_backbone.points.size());
  for (std::size_t i = 0; i < x.final_backbone.points.size(); ++i) {
    EXPECT_TRUE(Same(x.final_backbone.points[i].amplitude_m, y.final_backbone.points[i].amplitude_m));
    EXPECT_TRUE(Same(x.final_backbone.points[i].frequency_hz, y.final_backbone.points[i].frequency_hz));
  }
  EXPECT_EQ(x.summary, y.summary);
  EXPECT_TRUE(Same(x.seconds, y.seconds));
}

// ---------------------------------------------------------------- round trips

TEST(DiagnosisFile, EveryFieldSurvivesTheRoundTrip) {
  for (bool with_location : {true, false}) {
    SCOPED_TRACE(with_location ? "with a location" : "locating failed");
    const DiagnosisFile written = FullFile(with_location);
    const std::string text = DiagnosisFileToJson(written);
    const DiagnosisFile read = DiagnosisFileFromJson(text, "diagnosis.json");
    ExpectSameFile(written, read);
    // Text → struct → text is the same text.
    EXPECT_EQ(DiagnosisFileToJson(read), text);
  }
}

// How many failures a check reports, without failing this test.
int FailuresOf(const std::function<void()>& check) {
  ::testing::TestPartResultArray results;
  {
    const ::testing::ScopedFakeTestPartResultReporter reporter(
        ::testing::ScopedFakeTestPartResultReporter::INTERCEPT_ONLY_CURRENT_THREAD, &results);
    check();
  }
  return results.size();
}

// The comparison itself must see a difference (else the round trip above
// would pass on anything): one ulp of one ω, two parameters swapped.
TEST(DiagnosisFile, TheComparisonSeesAChangedField) {
  const DiagnosisFile file = FullFile(true);
  EXPECT_EQ(FailuresOf([&] { ExpectSameFile(file, file); }), 0);
  DiagnosisFile changed = file;
  double& omega = changed.diagnosis.location->loops.steps[1].omega_rad_s;
  omega = std::nextafter(omega, 0.0);
  EXPECT_EQ(FailuresOf([&] { ExpectSameFile(file, changed); }), 1);
  changed = file;
  std::swap(changed.diagnosis.base.parameters[0], changed.diagnosis.base.parameters[1]);
  EXPECT_GE(FailuresOf([&] { ExpectSameFile(file, changed); }), 2);
  changed = file;
  changed.diagnosis.final_extra_parameters.pop_back();
  EXPECT_EQ(FailuresOf([&] { ExpectSameFile(file, changed); }), 1);
  changed = file;
  changed.phasor_uncertainty = PhasorUncertainty::kRelativeFloor;
  EXPECT_EQ(FailuresOf([&] { ExpectSameFile(file, changed); }), 1);
  changed = file;
  double& upper = changed.diagnosis.final_damping_laws.intervals[0].upper_95;
  upper = std::nextafter(upper, 2.0 * upper);
  EXPECT_EQ(FailuresOf([&] { ExpectSameFile(file, changed); }), 1);
}

TEST(DiagnosisFile, WritesTheLayoutTheReportReads) {
  const nlohmann::json j = nlohmann::json::parse(DiagnosisFileToJson(FullFile(true)));
  EXPECT_EQ(j["format"], "beamid-diagnosis/1");
  EXPECT_EQ(j["beamid_version"], "9.8.7-test");
  EXPECT_EQ(j["campaign"]["folder"], "campaigns/friction");
  EXPECT_EQ(j["campaign"]["name"], "concealed friction");
  EXPECT_EQ(j["campaign_sha256"], "9f86d081884c7d659a2feaa0c55ad015a3bf4f1b2b0b822cd15d6c15b0f00a08");
  EXPECT_EQ(j["phasor_uncertainty"], "propagated");
  EXPECT_EQ(j["result_file"], "runs/identify/result.json");
  EXPECT_EQ(j["result"]["format"], "beamid-result/1");
  EXPECT_EQ(j["selected"], nlohmann::json::array({"support_friction"}));
  EXPECT_EQ(j["final"]["extension"], j["selected"]);
  EXPECT_TRUE(j["base"]["held_out_chi_square"].is_null());  // NaN
  EXPECT_EQ(j["base"]["parameters"]["k3"]["unit"], "unit_k3");
  const auto& friction = j["candidates"][0];
  EXPECT_EQ(friction["score"].get<double>(), 0.8 / 3.0);
  EXPECT_EQ(friction["residual_before"].get<double>(), 123.456789);
  EXPECT_EQ(friction["residual_after"].get<double>(), 2.0 * 123.456789);
  EXPECT_EQ(friction["extra_parameters"].size(), 2u);
  EXPECT_EQ(friction["extra_parameters"]["jenkins_slip_moment"]["ci95"].size(), 2u);
  EXPECT_TRUE(j["candidates"][1]["residual_after"].is_null());  // the failed refit
  EXPECT_EQ(j["location"]["loops"]["steps"][0]["frequency_hz"].get<double>(),
            (2.0 * 3.141592653589793 * 52.75 + 1e-9) / (2.0 * 3.141592653589793));
  EXPECT_FALSE(j["location"].contains("error"));
  EXPECT_EQ(j["response"].size(), 2u);
  // Locating failed: the location is the error alone, as before.
  const nlohmann::json failed = nlohmann::json::parse(DiagnosisFileToJson(FullFile(false)));
  EXPECT_EQ(failed["location"], nlohmann::json({{"error", "the reference beam has no support law"}}));
}

TEST(DiagnosisFile, WritesAndReadsAFile) {
  const std::filesystem::path path = testing::UniqueTempPath("diagnosis") / "out.json";
  std::filesystem::create_directories(path.parent_path());
  const DiagnosisFile written = FullFile(true);
  WriteDiagnosisFile(path, written);
  ExpectSameFile(written, ReadDiagnosisFile(path));
  std::filesystem::remove_all(path.parent_path());
}

// Doubles of every magnitude: nlohmann writes digits that read back to the
// same bits (a worker's refit and the file rely on it).
TEST(DiagnosisFile, DoublesOfAnyBitPatternReadBackExactly) {
  std::mt19937_64 rng(7);
  DiagnosisFile file = FullFile(false);
  std::vector<double> values = {0.0, -0.0, 5e-324, -5e-324, 2.2250738585072014e-308, 1.7976931348623157e308,
                                0.1, 1.0 / 3.0, 9007199254740993.0, 1e23, 123456789012345678.0};
  while (values.size() < 4000) {
    const double v = std::bit_cast<double>(rng());
    if (std::isfinite(v)) values.push_back(v);
  }
  file.diagnosis.response.clear();
  for (std::size_t i = 0; i + 1 < values.size(); i += 2)
    // A frequency must be positive (the reader refuses others); the phasors take any bits.
    file.diagnosis.response.push_back({.level = "l", .frequency_hz = 53.5, .channel = "c", .held_out = false,
                                       .measured = {values[i], values[i + 1]}, .base_model = {}, .final_model = {}});
  const DiagnosisFile read = DiagnosisFileFromJson(DiagnosisFileToJson(file), "random.json");
  ASSERT_EQ(read.diagnosis.response.size(), file.diagnosis.response.size());
  for (std::size_t i = 0; i < read.diagnosis.response.size(); ++i) {
    EXPECT_TRUE(Same(read.diagnosis.response[i].measured.real(), values[2 * i]));
    EXPECT_TRUE(Same(read.diagnosis.response[i].measured.imag(), values[2 * i + 1]));
  }

  CandidateRefit refit{.chi_square = values[7], .seconds = values[8]};
  refit.values.assign(values.begin(), values.begin() + 100);
  refit.std.assign(values.begin() + 100, values.begin() + 200);
  refit.scaled_at.assign(values.begin() + 200, values.begin() + 300);
  refit.x.assign(values.begin() + 300, values.end());
  // JSON has no non-finite numbers; the record keeps them by name.
  refit.x.push_back(std::numeric_limits<double>::infinity());
  refit.x.push_back(-std::numeric_limits<double>::infinity());
  refit.x.push_back(kNaN);
  const CandidateRefit back = CandidateRefitFromText(CandidateRefitToText(refit));
  EXPECT_TRUE(Same(back.chi_square, refit.chi_square));
  EXPECT_TRUE(Same(back.seconds, refit.seconds));
  ExpectSameNumbers(back.values, refit.values);
  ExpectSameNumbers(back.std, refit.std);
  ExpectSameNumbers(back.scaled_at, refit.scaled_at);
  ExpectSameNumbers(back.x, refit.x);
  EXPECT_THROW(CandidateRefitFromText(R"({"chi_square": 1.0})"), std::runtime_error);
  EXPECT_THROW(CandidateRefitFromText("{\"chi_square\": \"many\", \"seconds\": 1, \"values\": [], \"std\": [], "
                                      "\"scaled_at\": [], \"x\": []}"),
               std::runtime_error);
}

// The declaration's generic checks (tests/support/schema_checks.h) on files
// with every field set: the text survives reading and writing, and every
// number out of range, integer, boolean, choice, required field and unknown
// key is refused naming its path. Without a location, the file holds its
// error alone.
TEST(DiagnosisFile, TheDeclarationHolds) {
  for (bool with_location : {true, false}) {
    SCOPED_TRACE(with_location ? "with a location" : "locating failed");
    testing::ExpectDeclarationHolds(
        {.fields = DiagnosisFileFields(),
         .sample = DiagnosisFileToJson(FullFile(with_location)),
         .read = [](const std::string& text) { DiagnosisFileFromJson(text, "run/diagnosis.json"); },
         .rewrite = [](const std::string& text) {
           return DiagnosisFileToJson(DiagnosisFileFromJson(text, "run/diagnosis.json"));
         }});
  }
}

std::string SeedText(const std::string& name) {
  const std::string path = "tests/fuzz/seeds/diagnosis_json_fuzzer/" + name;
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(in) << path << " is missing (the test runs from the source folder)";
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A file that `beamid diagnose` wrote before the refit status was a choice
// (the fuzzer's first seed, from a real run: "converged" and "status":
// "solved" or "not refitted: why") reads as refitted or not refitted with
// the why; the same run in today's layout ("refit": "refitted") is written
// again byte for byte.
TEST(DiagnosisFile, AFileOfTheEarlierWriterReadsAndTodaysLayoutIsWrittenAgainTheSame) {
  const DiagnosisFile earlier = DiagnosisFileFromJson(SeedText("diagnosis.json"), "diagnosis.json");
  EXPECT_EQ(earlier.diagnosis.verdict, DiagnosisVerdict::kNoSignificantDiscrepancy);
  EXPECT_EQ(earlier.diagnosis.blame, Blame::kNone);
  int refitted = 0, not_refitted = 0;
  for (const auto& c : earlier.diagnosis.candidates) {
    refitted += c.Refitted();
    if (c.status != RefitStatus::kNotRefitted) continue;
    ++not_refitted;
    EXPECT_EQ(c.status_message, "the base model already fits within the noise") << c.name;
  }
  EXPECT_EQ(refitted, 10);  // "solved" in the file
  EXPECT_EQ(not_refitted, 3);
  const std::string text = SeedText("diagnosis_current.json");
  const DiagnosisFile today = DiagnosisFileFromJson(text, "diagnosis_current.json");
  EXPECT_EQ(DiagnosisFileToJson(today), text);
  EXPECT_EQ(DiagnosisFileToJson(earlier), text);  // the same run, whichever layout it was read from
}

// ---------------------------------------------------------------- the first layout

// As `beamid diagnose` wrote it before beamid_version: keys sorted, the
// result named by "result", no response, no extra_parameter_names, loop
// steps with frequency_hz only.
constexpr const char* kFirstLayout = R"json({
 "base": {"aic": 40.5, "bic": 45.25, "chi_square": 36.5, "degrees_of_freedom": 160,
          "held_out_chi_square": null, "held_out_h1_relative_error": null, "model_harmonics": 5,
          "num_residuals": 162, "parameters": {"c": {"ci95": [0.01, 0.03], "std": 0.005, "unit": "N*m*s/rad", "value": 0.02},
          "k1": {"ci95": [119.0, 121.0], "std": 0.5, "unit": "N*m/rad", "value": 120.0}},
          "reduced_chi_square": 0.228125},
 "campaign": {"folder": "out/clamp", "name": "clamp"},
 "candidates": [
  {"converged": true, "description": "rotational spring at x = 0",
   "extra_parameters": {"clamp_compliance": {"ci95": [9.0e-5, 1.1e-4], "std": 5.0e-6, "unit": "rad/(N*m)", "value": 1.0e-4}},
   "fit": {"aic": 12.0, "bic": 14.0, "chi_square": 6.0, "degrees_of_freedom": 159, "held_out_chi_square": 3.5,
           "held_out_h1_relative_error": 0.00096, "model_harmonics": 5, "num_residuals": 162,
           "parameters": {"clamp_compliance": {"ci95": [9.0e-5, 1.1e-4], "std": 5.0e-6, "unit": "rad/(N*m)", "value": 1.0e-4}},
           "reduced_chi_square": 0.0377},
   "likelihood_ratio": 30.5, "name": "clamp_compliance", "p_value": 1e-8, "residual_after": 6.0,
   "residual_before": 36.5, "residual_drop": 6.083, "score": 0.75, "seconds": 2.5, "significant": true,
   "status": "solved", "test_dof": 1},
  {"converged": false, "description": "a point mass", "extra_parameters": {},
   "fit": {"aic": 0, "bic": 0, "chi_square": 0, "degrees_of_freedom": 0, "held_out_chi_square": null,
           "held_out_h1_relative_error": null, "model_harmonics": 5, "num_residuals": 0, "parameters": {},
           "reduced_chi_square": 0},
   "likelihood_ratio": 0, "name": "added_mass", "p_value": 1, "residual_after": null, "residual_before": 36.5,
   "residual_drop": 1, "score": 0.1, "seconds": 0.25, "significant": false, "status": "failed: stopped", "test_dof": 2}],
 "final": {"extension": ["clamp_compliance"],
           "fit": {"aic": 12.0, "bic": 14.0, "chi_square": 6.0, "degrees_of_freedom": 159, "held_out_chi_square": 3.5,
                   "held_out_h1_relative_error": 0.00096, "model_harmonics": 5, "num_residuals": 162,
                   "parameters": {}, "reduced_chi_square": 0.0377}},
 "format": "beamid-diagnosis/1",
 "location": {"beyond_fitted_fraction": 0.0, "channel_excess_chi2": [10.0, 2.0], "chi2": 400.0, "dof": 158,
   "even_harmonic_fraction": 0.0, "findings": ["acc1 misses its fundamental."], "fundamental_fraction": 0.9,
   "groups": [{"adjusted_p_value": 0.001, "band": "all", "channel": "acc1", "chi2": 50.0, "dof": 18,
               "excess_chi2": 32.0, "growth_exponent": null, "harmonic": 1, "level": "", "p_value": 0.0001,
               "part": "both", "significant": true}],
   "harmonic_excess_chi2": [12.0, 0.0, 0.0], "in_phase_fraction": 0.8, "level_growth_exponent": 1.0,
   "level_misfit_amplitude": [0.1, 0.2], "level_response_amplitude": [1.0, 2.0],
   "loops": {"area_exponent": null, "area_exponent_std": null, "asymmetric": false, "damping_ratio_high_to_low": 1.0,
     "dissipation_not_viscous": false, "elastic_harmonic_chi2": 2.0, "elastic_harmonic_p_value": 0.7,
     "harmonic_dof": 4, "hysteretic_harmonic_chi2": 3.0, "hysteretic_harmonic_p_value": 0.5,
     "hysteretic_shape": false, "max_moment_harmonic_ratio": 0.01, "mean_equivalent_damping_Nms_rad": 0.02,
     "non_elliptic": false, "num_steps_used": 1,
     "steps": [{"dissipated_energy_J": 1e-6, "dissipated_energy_std_J": 1e-8, "elastic_harmonic_chi2": 0.5,
                "equivalent_damping_Nms_rad": 0.02, "equivalent_damping_std_Nms_rad": 0.001, "frequency_hz": 52.0,
                "harmonic_dof": 4, "hysteretic_harmonic_chi2": 0.25, "level": "low", "moment_amplitude_Nm": 0.1,
                "moment_even_fraction": 0.001, "moment_harmonic_ratio": 0.002, "theta_amplitude_rad": 0.001,
                "theta_even_fraction": 0.003, "theta_std_rad": 1e-6, "viscous_energy_J": 1e-6}],
     "theta_even_chi2": 1.0, "theta_even_dof": 2, "theta_even_p_value": 0.6, "viscous_chi2": 0.0,
     "viscous_dof": 0, "viscous_p_value": 1.0},
   "near_resonance_fraction": 0.7, "num_groups_tested": 1, "p_value": 1e-20, "significant": true},
 "result": "result.json",
 "seconds": 10.5,
 "selected": ["clamp_compliance"],
 "summary": "Missing physics: clamp_compliance.",
 "verdict": "cause named"
})json";

TEST(DiagnosisFile, ReadsTheFirstLayout) {
  const DiagnosisFile file = DiagnosisFileFromJson(kFirstLayout, "old/diagnosis.json");
  EXPECT_EQ(file.beamid_version, "");
  EXPECT_EQ(file.campaign_folder, "out/clamp");
  EXPECT_EQ(file.campaign_name, "clamp");
  EXPECT_EQ(file.campaign_sha256, "");
  EXPECT_EQ(file.phasor_uncertainty, PhasorUncertainty::kRelativeFloor);  // weighed so before the key
  EXPECT_EQ(file.result_file, "result.json");
  EXPECT_EQ(file.embedded_result_json, "");
  const DiagnosisResult& r = file.diagnosis;
  EXPECT_EQ(r.verdict, DiagnosisVerdict::kCauseNamed);
  EXPECT_EQ(r.selected, std::vector<std::string>{"clamp_compliance"});
  ASSERT_EQ(r.base.parameters.size(), 2u);
  EXPECT_EQ(r.base.parameters[1].name, "k1");
  EXPECT_EQ(r.base.parameters[1].unit, "N*m/rad");
  EXPECT_EQ(r.base.parameters[1].value, 120.0);
  EXPECT_EQ(r.base.parameters[1].lower_95, 119.0);
  EXPECT_EQ(r.base.parameters[1].upper_95, 121.0);
  EXPECT_TRUE(std::isnan(r.base.held_out_chi_square));
  EXPECT_EQ(r.base.num_residuals, 162);
  ASSERT_EQ(r.candidates.size(), 2u);
  EXPECT_EQ(r.candidates[0].extra_parameters, std::vector<std::string>{"clamp_compliance"});
  EXPECT_EQ(r.candidates[0].fit.held_out_h1_relative_error, 0.00096);
  EXPECT_TRUE(r.candidates[0].significant);
  EXPECT_EQ(r.candidates[0].status, RefitStatus::kRefitted);
  EXPECT_EQ(r.candidates[1].status, RefitStatus::kFailed);
  EXPECT_EQ(r.candidates[1].status_message, "stopped");
  EXPECT_TRUE(r.candidates[1].extra_parameters.empty());
  EXPECT_EQ(r.final_fit.chi_square, 6.0);
  EXPECT_EQ(r.final_extra_parameters, std::vector<std::string>{"clamp_compliance"});
  ASSERT_TRUE(r.location.has_value());
  EXPECT_EQ(r.location->findings, std::vector<std::string>{"acc1 misses its fundamental."});
  ASSERT_EQ(r.location->groups.size(), 1u);
  EXPECT_TRUE(std::isnan(r.location->groups[0].growth_exponent));
  EXPECT_EQ(r.location->groups[0].dof, 18);
  ASSERT_EQ(r.location->loops.steps.size(), 1u);
  EXPECT_DOUBLE_EQ(r.location->loops.steps[0].omega_rad_s, 2.0 * 3.141592653589793 * 52.0);
  EXPECT_TRUE(std::isnan(r.location->loops.area_exponent));
  EXPECT_TRUE(r.response.empty());
  EXPECT_EQ(r.seconds, 10.5);
}

TEST(DiagnosisFile, KeepsAnEmbeddedResultAsItsText) {
  nlohmann::json j = nlohmann::json::parse(kFirstLayout);
  j["result"] = {{"format", "beamid-result/1"}, {"parameters", {{"k1", {{"value", 120.25}}}}}};
  const DiagnosisFile file = DiagnosisFileFromJson(j.dump(), "embedded.json");
  EXPECT_EQ(file.result_file, "");
  EXPECT_EQ(nlohmann::json::parse(file.embedded_result_json), j["result"]);
  // The path may also be given as result_file.
  j.erase("result");
  j["result_file"] = "identify/result.json";
  EXPECT_EQ(DiagnosisFileFromJson(j.dump(), "named.json").result_file, "identify/result.json");
}

// ---------------------------------------------------------------- refusals

// The message names the file, the field and the fix.
void ExpectRefused(const nlohmann::json& j, const std::string& source, const std::string& field) {
  try {
    DiagnosisFileFromJson(j.dump(), source);
    ADD_FAILURE() << "accepted a file with a bad " << field;
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(source), std::string::npos) << message;
    EXPECT_NE(message.find("\"" + field + "\""), std::string::npos) << message;
    EXPECT_NE(message.find("Fix:"), std::string::npos) << message;
  }
}

TEST(DiagnosisFile, RefusesAMissingField) {
  const nlohmann::json good = nlohmann::json::parse(DiagnosisFileToJson(FullFile(true)));
  nlohmann::json j = good;
  j["base"].erase("bic");
  ExpectRefused(j, "run/diagnosis.json", "base.bic");
  j = good;
  j["candidates"][1]["fit"].erase("chi_square");
  ExpectRefused(j, "run/diagnosis.json", "candidates[1].fit.chi_square");
  j = good;
  j["location"]["loops"]["steps"][1].erase("theta_std_rad");
  ExpectRefused(j, "run/diagnosis.json", "location.loops.steps[1].theta_std_rad");
  j = good;
  j.erase("verdict");
  ExpectRefused(j, "run/diagnosis.json", "verdict");
}

TEST(DiagnosisFile, RefusesAnotherFormat) {
  nlohmann::json j = nlohmann::json::parse(DiagnosisFileToJson(FullFile(true)));
  j["format"] = "beamid-result/1";
  ExpectRefused(j, "result.json", "format");
  j.erase("format");
  ExpectRefused(j, "result.json", "format");
}

TEST(DiagnosisFile, RefusesAWrongType) {
  const nlohmann::json good = nlohmann::json::parse(DiagnosisFileToJson(FullFile(true)));
  nlohmann::json j = good;
  j["candidates"][0]["test_dof"] = "two";
  ExpectRefused(j, "d.json", "candidates[0].test_dof");
  j = good;
  j["candidates"][2]["test_dof"] = 1.5;
  ExpectRefused(j, "d.json", "candidates[2].test_dof");
  j = good;
  j["base"]["parameters"]["k3"]["value"] = "12";
  ExpectRefused(j, "d.json", "base.parameters.k3.value");
  j = good;
  j["location"]["significant"] = 1;
  ExpectRefused(j, "d.json", "location.significant");
  j = good;
  j["response"][0]["measured"] = {1.0};
  ExpectRefused(j, "d.json", "response[0].measured");
  j = good;
  j["result"] = 3;
  ExpectRefused(j, "d.json", "result");
  j = good;
  j["candidates"] = nlohmann::json::object();
  ExpectRefused(j, "d.json", "candidates");
}

// A misspelt key is not skipped: the value the writer meant would be lost.
TEST(DiagnosisFile, RefusesAnUnknownField) {
  const nlohmann::json good = nlohmann::json::parse(DiagnosisFileToJson(FullFile(true)));
  nlohmann::json j = good;
  j["candidates"][0]["p_valeu"] = 0.5;
  ExpectRefused(j, "d.json", "candidates[0].p_valeu");
  j = good;
  j["location"]["loops"]["steps"][0]["omega_hz"] = 52.0;
  ExpectRefused(j, "d.json", "location.loops.steps[0].omega_hz");
  j = good;
  j["verdicts"] = "unexplained";
  ExpectRefused(j, "d.json", "verdicts");
}

// The outcomes travel by name: a name the diagnosis does not give is refused.
TEST(DiagnosisFile, RefusesAnOutcomeItDoesNotName) {
  const nlohmann::json good = nlohmann::json::parse(DiagnosisFileToJson(FullFile(true)));
  const nlohmann::json read_back =
      nlohmann::json::parse(DiagnosisFileToJson(DiagnosisFileFromJson(good.dump(), "d.json")));
  EXPECT_EQ(read_back["verdict"], "cause named");
  EXPECT_EQ(read_back["ranked_by"], "held-out channels");
  EXPECT_EQ(read_back["blame"], "the model");
  for (const char* key : {"verdict", "ranked_by", "blame"}) {
    nlohmann::json j = good;
    j[key] = "the weather";
    ExpectRefused(j, "d.json", key);
  }
  nlohmann::json j = good;
  j["blame"] = "";  // nothing named: nobody to blame
  EXPECT_EQ(DiagnosisFileFromJson(j.dump(), "d.json").diagnosis.blame, Blame::kNone);
}

TEST(DiagnosisFile, RefusesWhatIsNotADiagnosis) {
  // A number beyond double range.
  DiagnosisFile file = FullFile(true);
  file.diagnosis.seconds = 12345.5;
  std::string text = DiagnosisFileToJson(file);
  const std::size_t at = text.find("12345.5");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 7, "1e400");
  EXPECT_THROW(DiagnosisFileFromJson(text, "huge.json"), InputError);

  EXPECT_THROW(DiagnosisFileFromJson("{\"format\": ", "cut.json"), InputError);
  EXPECT_THROW(DiagnosisFileFromJson("[1, 2]", "array.json"), InputError);
  const std::filesystem::path missing = testing::UniqueTempPath("no_such_diagnosis") / "diagnosis.json";
  try {
    ReadDiagnosisFile(missing);
    ADD_FAILURE() << "read a missing file";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace beamid::solver
