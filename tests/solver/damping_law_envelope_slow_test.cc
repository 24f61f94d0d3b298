// The model-form intervals over the beam's damping laws: the
// paper's set-up simulated ONCE by the independent time-domain simulator
// with a beam whose damping is Rayleigh (C = α·M + β·K), or modal with
// unrelated ratios per mode, or the loss factor the fit assumes; then
// independent realisations of the measurement noise, each identified as
// `beamid identify` does (k1, k2, k3, c, η) and refitted under the other
// damping laws (solver/estimation/damping_laws.h).
//
// What must hold: on the Rayleigh and modal beams the fit that assumes a
// loss factor puts c outside its own 95 % interval in most realisations (the
// problem), the data reject the loss factor, and k1, k3 and c lie inside
// their model-form intervals in ≥ 85 % of the realisations (the coverage
// test's bar); on the loss-factor beam the loss factor is accepted and the
// model-form intervals cover as well.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hb/scenario.h"
#include "signal/campaign.h"
#include "solver/estimation/damping_laws.h"
#include "solver/estimation/identify.h"
#include "tests/support/simulated_campaign.h"
#include "tests/support/temp_path.h"

namespace beamid::solver {
namespace {

constexpr int kRealisations = 8;
constexpr double kMinCoverage = 0.85;

// An example scenario with 15 steps per level over the resonance (as the
// coverage test's), its own damping kept, and a distorted force (2 % second,
// 1 % third harmonic).
hb::Scenario LeanScenario(const std::string& file_name) {
  nlohmann::json scenario = beamid::testing::LeanExample(file_name);
  scenario["excitation"]["distortion"] = {{{"harmonic", 2}, {"amplitude_ratio", 0.02}, {"phase_rad", 0.4}},
                                          {{"harmonic", 3}, {"amplitude_ratio", 0.01}, {"phase_rad", -1.1}}};
  return hb::ParseScenario(scenario.dump(), file_name + ", 15 steps per level, distorted force");
}

// The scenario's campaign, simulated into a temporary folder and read back;
// *steps: the simulated steps, for noise realisations of it.
signal::Campaign Simulate(const hb::Scenario& scenario, std::vector<hb::SimulatedStep>* steps) {
  const std::filesystem::path folder = beamid::testing::UniqueTempPath("beamid_damping_law_test");
  std::filesystem::remove_all(folder);
  *steps = beamid::testing::SimulateInto(scenario, folder);
  const signal::Campaign campaign = signal::ReadCampaign(folder);
  std::filesystem::remove_all(folder);
  return campaign;
}

ModelStructure PolynomialWithLossFactor() {
  ModelStructure structure = PolynomialModel({.k1_Nm_rad = 100.0});
  structure.linear.push_back(LossFactor(1e-4));
  return structure;
}

struct Tally {
  int loss_factor_c_covered = 0;   // the loss-factor fit's own 95 % interval of c
  int loss_factor_accepted = 0;
  int k1_covered = 0, k3_covered = 0, c_covered = 0;  // by the model-form intervals
  int answer_c_covered = 0;  // by the 95 % interval of the law the answer is (AnswerLaw)
  // The widest model-form interval over the realisations, relative to the truth.
  double k1_widest = 0.0, k3_widest = 0.0, c_widest = 0.0;
};

bool Covers(const DampingLawEnvelope& envelope, const std::string& name, double truth, double* widest) {
  for (const auto& i : envelope.intervals)
    if (i.name == name) {
      *widest = std::max(*widest, (i.upper_95 - i.lower_95) / truth);
      return i.lower_95 <= truth && truth <= i.upper_95;
    }
  ADD_FAILURE() << "no model-form interval for " << name;
  return false;
}

Tally RunRealisations(const std::string& file_name) {
  const hb::Scenario scenario = LeanScenario(file_name);
  std::vector<hb::SimulatedStep> steps;
  const signal::Campaign campaign = Simulate(scenario, &steps);
  const ModelStructure structure = PolynomialWithLossFactor();
  const IdentifyOptions options;
  Tally tally;
  for (int r = 0; r < kRealisations; ++r) {
    const FitData fit = MakeFitData(campaign, beamid::testing::MeasureAgain(scenario, steps, campaign, 2000 + r),
                                    {.channels = {"acc1", "acc2"}});
    const IdentifyResult result = Identify(fit, structure, options);
    const DampingLawEnvelope envelope = FitDampingLaws(fit, structure, result, options);
    EXPECT_EQ(envelope.laws.size(), DampingLawNames().size());
    for (const auto& law : envelope.laws) EXPECT_TRUE(law.converged) << file_name << " " << law.law << ": " << law.status;
    const ParameterEstimate& c = result.parameters[3];
    tally.loss_factor_c_covered += c.lower_95 <= 0.05 && 0.05 <= c.upper_95;
    tally.loss_factor_accepted += envelope.laws.front().accepted;
    tally.k1_covered += Covers(envelope, "k1", 150.0, &tally.k1_widest);
    tally.k3_covered += Covers(envelope, "k3", 3e5, &tally.k3_widest);
    tally.c_covered += Covers(envelope, "c", 0.05, &tally.c_widest);
    const DampingLawFit* answer = AnswerLaw(envelope);
    if (answer == nullptr) {
      ADD_FAILURE() << "no answer law";
      continue;
    }
    for (const auto& p : answer->parameters)
      if (p.name == "c") tally.answer_c_covered += p.lower_95 <= 0.05 && 0.05 <= p.upper_95;
  }
  std::printf("%s: loss-factor fit's c covered %d/%d, loss factor accepted %d/%d; model-form covers k1 %d, k3 %d, c %d "
              "of %d; the answer's c covered %d; widest model-form interval / truth: k1 %.3g, k3 %.3g, c %.3g\n",
              file_name.c_str(), tally.loss_factor_c_covered, kRealisations, tally.loss_factor_accepted, kRealisations,
              tally.k1_covered, tally.k3_covered, tally.c_covered, kRealisations, tally.answer_c_covered,
              tally.k1_widest, tally.k3_widest, tally.c_widest);
  return tally;
}

void ExpectModelFormCoverage(const Tally& t) {
  EXPECT_GE(t.k1_covered, kMinCoverage * kRealisations);
  EXPECT_GE(t.k3_covered, kMinCoverage * kRealisations);
  EXPECT_GE(t.c_covered, kMinCoverage * kRealisations);
  // Not by being vague: the widest model-form interval over the realisations
  // at most about twice what these campaigns give (measured, as a share of
  // the truth: k1 7.9e-5 to 9.1e-5, k3 7.8e-4 to 8.5e-4, c 0.0093 to 0.0124).
  EXPECT_LE(t.k1_widest, 2e-4);
  EXPECT_LE(t.k3_widest, 2e-3);
  EXPECT_LE(t.c_widest, 0.025);
  // The headline numbers (the accepted law's) hold the truth, not just the envelope.
  EXPECT_GE(t.answer_c_covered, kMinCoverage * kRealisations);
}

TEST(DampingLawEnvelope, ARayleighBeamRejectsTheLossFactorAndTheModelFormIntervalsCoverTheTruth) {
  const Tally t = RunRealisations("paper_rayleigh_damping.json");
  EXPECT_LE(t.loss_factor_c_covered, kRealisations / 2) << "the loss-factor fit alone should not cover c";
  EXPECT_LE(t.loss_factor_accepted, kRealisations / 4);
  ExpectModelFormCoverage(t);
}

TEST(DampingLawEnvelope, AModallyDampedBeamRejectsTheLossFactorAndTheModelFormIntervalsCoverTheTruth) {
  const Tally t = RunRealisations("paper_modal_damping.json");
  EXPECT_LE(t.loss_factor_c_covered, kRealisations / 2) << "the loss-factor fit alone should not cover c";
  EXPECT_LE(t.loss_factor_accepted, kRealisations / 4);
  ExpectModelFormCoverage(t);
}

TEST(DampingLawEnvelope, ALossFactorBeamKeepsTheLossFactorAndTheModelFormIntervalsCoverTheTruth) {
  const Tally t = RunRealisations("paper_base.json");
  EXPECT_GE(t.loss_factor_accepted, kRealisations - 1);
  ExpectModelFormCoverage(t);
}

// The truncation's shift is one Gauss–Newton step at H + 4 harmonics from
// the optimum at H: to first order, a full refit at H + 4. Checked against
// that refit where truncation moves the fit most, 3 harmonics balanced for
// 3 fitted.
TEST(DampingLawEnvelope, TheTruncationShiftIsAFullRefitWithMoreHarmonicsToFirstOrder) {
  const hb::Scenario scenario = beamid::testing::LeanPaperBase();
  std::vector<hb::SimulatedStep> steps;
  const signal::Campaign campaign = Simulate(scenario, &steps);
  const FitData fit = MakeFitData(campaign, beamid::testing::MeasureAgain(scenario, steps, campaign, 2100),
                                  {.channels = {"acc1", "acc2"}});
  const ModelStructure structure = PolynomialWithLossFactor();
  IdentifyOptions options;
  options.model.num_harmonics = 3;
  const IdentifyResult result = Identify(fit, structure, options);
  const DampingLawEnvelope envelope = FitDampingLaws(fit, structure, result, options);
  ASSERT_TRUE(envelope.truncation.has_value());
  ASSERT_TRUE(envelope.truncation->converged) << envelope.truncation->status;
  EXPECT_EQ(envelope.truncation->refit_harmonics, 7);

  ModelStructure at_optimum = structure;
  std::vector<double> values;
  for (const auto& p : result.parameters) values.push_back(p.value);
  at_optimum.SetValues(values);
  IdentifyOptions more = options;
  more.model.num_harmonics = 7;
  more.use_direct_estimate = false;
  const IdentifyResult refit = Identify(fit, at_optimum, more);
  for (std::size_t j = 0; j < result.parameters.size(); ++j) {
    const ParameterEstimate& p = result.parameters[j];
    const double step = envelope.truncation->parameters[j].value - p.value;
    const double full = refit.parameters[j].value - p.value;
    std::printf("  %-12s σ %.3g: shift by the step %.4g, by the full refit %.4g\n", p.name.c_str(), p.std, step,
                full);
    EXPECT_NEAR(step, full, 0.1 * std::abs(full) + 0.01 * p.std) << p.name;
  }
}

}  // namespace
}  // namespace beamid::solver
