// Identification with the seed's multiple-scales model (`--model ms`) on a
// campaign from the independent time-domain simulator: the paper's set-up,
// base physics, three small force levels around the first resonance (where
// the model's ordering holds), realistic noise.
#include <cmath>
#include <cstdio>
#include <numbers>

#include <gtest/gtest.h>

#include "solver/estimation/identify.h"
#include "solver/estimation/multiple_scales_problem.h"
#include "solver/estimation/prediction.h"
#include "solver/estimation/result_file.h"
#include "solver/estimation/result_io.h"
#include "tests/support/paper_scenario.h"
#include "tests/support/simulated_campaign.h"

namespace beamid::solver {
namespace {

constexpr double kK1 = 150.0, kK3 = 3e5, kC = 0.05, kLossFactor = 2e-4;

// Tolerances from the model's own error, which grows as a² (hb/ tests:
// multiple_scales_vs_hb). At this campaign's top level (|θ1| ≤ 1.7 mrad) the
// cubic part of the support stiffness is ¾·k3·θ²/k1 ≈ 0.4 % of k1, and the
// seed's first-harmonic error is below the 0.5 % that the seed model is required to meet at
// small amplitude. So k1 can absorb at most a tenth of that 0.4 % (0.04 %),
// and c (the height of the resonance peak, ∝ 1/c) at most the 0.5 %; the
// noise adds ~0.002 % (k1) and ~0.01 % (c). k3 is the issue's 10 % (at small
// amplitude it is poorly determined by either model).
constexpr double kK1Tolerance = 0.001;
constexpr double kCTolerance = 0.01;
constexpr double kK3Tolerance = 0.10;
// MS and HB fitted to the same data: their k1 differ by the model error only.
constexpr double kK1Agreement = 0.0005;
constexpr double kPredictionTolerance = 0.02;  // required: held-out first harmonic within 2 %

const std::string kScenario = testing::PaperScenarioJson("multiple-scales identification test: small amplitudes", R"([
  {"label": "low", "force_amplitude_N": 0.25, "frequencies_Hz": {"start": 52.6, "stop": 55.6, "step": 0.5}},
  {"label": "mid", "force_amplitude_N": 0.5, "frequencies_Hz": {"start": 52.6, "stop": 55.6, "step": 0.5}},
  {"label": "high", "force_amplitude_N": 1.0, "frequencies_Hz": {"start": 52.6, "stop": 55.6, "step": 0.5}}])", 11);

IdentifyOptions KnownLossFactor() {
  IdentifyOptions options;
  options.model.beam_loss_factor = kLossFactor;  // from a separate test of the beam
  return options;
}

IdentifyOptions MultipleScales(IdentifyOptions options) {
  options.family = &MultipleScalesFamily();
  return options;
}

double Value(const IdentifyResult& r, const std::string& name) {
  for (const auto& p : r.parameters)
    if (p.name == name) return p.value;
  ADD_FAILURE() << "no parameter " << name;
  return 0.0;
}

void Print(const char* model, const IdentifyResult& r) {
  std::printf("%s:", model);
  for (const auto& p : r.parameters) std::printf("  %s = %.6g ± %.3g", p.name.c_str(), p.value, p.std);
  std::printf("  (reduced chi-square %.3g, %.3f s)\n", r.reduced_chi_square, r.seconds);
}

class MultipleScalesIdentification : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    simulated_ = new testing::SimulatedCampaign(kScenario, "beamid_ms_identify_slow_test");
    fit_ = new FitData(Fit({"acc1", "acc2"}));
    ms_ = new IdentifyResult(Identify(*fit_, PolynomialModel({.k1_Nm_rad = 100.0}), MultipleScales(KnownLossFactor())));
    hb_ = new IdentifyResult(Identify(*fit_, PolynomialModel({.k1_Nm_rad = 100.0}), KnownLossFactor()));
    Print("multiple scales", *ms_);
    Print("harmonic balance", *hb_);
  }
  static void TearDownTestSuite() {
    delete hb_;
    delete ms_;
    delete fit_;
    delete simulated_;
  }

  static FitData Fit(std::vector<std::string> channels) {
    return MakeFitData(simulated_->campaign, simulated_->phasors, {.channels = std::move(channels)});
  }
  static std::complex<double> HiddenTruth(std::size_t step) {
    const auto& hidden = simulated_->truth["steps"][step]["hidden"][0];
    EXPECT_DOUBLE_EQ(hidden["position_m"].get<double>(), 0.45);
    const auto& h1 = hidden["displacement_m"]["harmonics"][0];
    return {h1[0].get<double>(), h1[1].get<double>()};
  }

  static testing::SimulatedCampaign* simulated_;
  static FitData* fit_;
  static IdentifyResult* ms_;
  static IdentifyResult* hb_;
};

testing::SimulatedCampaign* MultipleScalesIdentification::simulated_ = nullptr;
FitData* MultipleScalesIdentification::fit_ = nullptr;
IdentifyResult* MultipleScalesIdentification::ms_ = nullptr;
IdentifyResult* MultipleScalesIdentification::hb_ = nullptr;

TEST_F(MultipleScalesIdentification, RecoversK1AndCAndAgreesWithHarmonicBalance) {
  EXPECT_NEAR(Value(*ms_, "k1"), kK1, kK1Tolerance * kK1);
  EXPECT_NEAR(Value(*ms_, "c"), kC, kCTolerance * kC);
  EXPECT_NEAR(Value(*ms_, "k3"), kK3, kK3Tolerance * kK3);
  EXPECT_NEAR(Value(*ms_, "k1"), Value(*hb_, "k1"), kK1Agreement * Value(*hb_, "k1"));
}

TEST_F(MultipleScalesIdentification, PredictsTheHeldOutChannelAndAHiddenPositionFromTheResultFile) {
  const ModelStructure structure = PolynomialModel({.k1_Nm_rad = 100.0});
  MultipleScalesProblem problem(*fit_, structure, {.beam_loss_factor = kLossFactor});
  problem.FeasiblePoint(ms_->starts[ms_->best_start].scaled_at);
  FitData fit_with_loss = *fit_;
  fit_with_loss.beam.loss_factor = kLossFactor;
  const ResultFile report = MakeResultFile(fit_with_loss, Fit({"acc3"}), problem, *ms_, {.family = &MultipleScalesFamily()});
  EXPECT_EQ(report.model.kind, ModelKind::kMultipleScales);
  EXPECT_EQ(report.model.num_harmonics, 3);
  ASSERT_EQ(report.validation.size(), 1u);
  ASSERT_EQ(report.validation[0].channel, "acc3");
  const double worst_acc3 = report.validation[0].worst_h1_relative_error;
  EXPECT_LT(worst_acc3, kPredictionTolerance);

  const auto file = simulated_->folder / "ms_result.json";
  WriteResultFile(file, report);
  const IdentifiedModel model = ReadIdentifiedModel(file);
  EXPECT_EQ(model.family, &MultipleScalesFamily());
  const std::vector<PredictedStep> predicted = PredictAt(model, 0.45);
  ASSERT_EQ(predicted.size(), fit_->steps.size());
  double worst_hidden = 0.0;
  for (std::size_t i = 0; i < predicted.size(); ++i) {
    ASSERT_TRUE(predicted[i].converged);
    ASSERT_EQ(predicted[i].displacement_m.size(), 4);
    const std::complex<double> truth = HiddenTruth(i);
    worst_hidden = std::max(worst_hidden, std::abs(predicted[i].displacement_m[1] - truth) / std::abs(truth));
    EXPECT_GT(predicted[i].std_real_m[1] + predicted[i].std_imag_m[1], 0.0);
  }
  std::printf("multiple scales, worst first-harmonic error: acc3 %.3f %%, hidden 0.45 m %.3f %%\n", 100 * worst_acc3,
              100 * worst_hidden);
  EXPECT_LT(worst_hidden, kPredictionTolerance);
}

TEST_F(MultipleScalesIdentification, ThePapersOwnFlowOneStepTwoAccelerometers) {
  // One step of the top level near 54.2 Hz, fit on acc1 and acc2, predict acc3.
  FitData fit = *fit_;
  const FitData held_out = Fit({"acc3"});
  std::size_t chosen = 0;
  auto distance = [&](std::size_t i) { return std::abs(fit.steps[i].omega_rad_s / (2 * std::numbers::pi) - 54.2); };
  for (std::size_t i = 0; i < fit.steps.size(); ++i)
    if (fit.steps[i].level == "high" && (fit.steps[chosen].level != "high" || distance(i) < distance(chosen)))
      chosen = i;
  fit.steps = {fit.steps[chosen]};
  fit.levels = {"high"};
  const ModelStructure structure = PolynomialModel({.k1_Nm_rad = 100.0});
  const IdentifyResult result = Identify(fit, structure, MultipleScales(KnownLossFactor()));
  MultipleScalesProblem problem(fit, structure, {.beam_loss_factor = kLossFactor});
  problem.FeasiblePoint(result.starts[result.best_start].scaled_at);
  const double omega = fit.steps[0].omega_rad_s;
  const std::complex<double> acc3 = -omega * omega * problem.DisplacementPhasors(result.x, 0, {0.57})(0, 1);
  const std::complex<double> measured = held_out.steps[chosen].measured(0, 0);
  std::printf("multiple scales, one step at %.2f Hz: acc3 predicted %.4g%+.4gi, measured %.4g%+.4gi\n",
              omega / (2 * std::numbers::pi), acc3.real(), acc3.imag(), measured.real(), measured.imag());
  EXPECT_LT(std::abs(acc3 - measured), kPredictionTolerance * std::abs(measured));
}

}  // namespace
}  // namespace beamid::solver
