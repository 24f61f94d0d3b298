// The robust fit (solver/estimation/robust_fit.h). The outlier test on
// hand-made chi-square vectors against the distribution it assumes (one far
// in the tail is found; draws from χ²(d) raise an alarm at most at the
// family-wise rate; a uniformly inflated set is the model's, not outliers);
// and the refit on a small campaign from the independent time-domain
// simulator (never from the harmonic-balance model it fits), base physics,
// whose FitData are corrupted after extraction: one glitching step is found
// and left out, and the robust fit's 95 % intervals hold the simulator's
// truth again; the clean campaign is left alone; a misfit spread over many
// steps is declined.
#include "solver/estimation/robust_fit.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <fstream>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "solver/estimation/identify.h"
#include "solver/estimation/model_family.h"
#include "tests/support/paper_scenario.h"
#include "tests/support/simulated_campaign.h"

namespace beamid::solver {
namespace {

// ---------------------------------------------------------------------------
// FindOutlyingSteps on hand-made chi-squares.

// num_steps steps of 2 channels × 3 harmonics (d = 12 residuals per step).
FitData HandMadeData(int num_steps) {
  FitData data;
  data.channels = {{.channel = "acc1", .position_m = 0.1}, {.channel = "acc2", .position_m = 0.3}};
  data.num_fit_harmonics = 3;
  data.levels = {"low"};
  for (int i = 0; i < num_steps; ++i)
    data.steps.push_back({.level = i % 2 == 0 ? "low" : "high",
                          .file = "step" + std::to_string(i) + ".csv",
                          .omega_rad_s = 2.0 * std::numbers::pi * (50.0 + 0.01 * i)});
  return data;
}

constexpr int kDof = 12;

std::vector<double> ChiSquareDraws(std::mt19937& rng, int n, double dof) {
  std::chi_squared_distribution<double> chi2(dof);
  std::vector<double> out(static_cast<std::size_t>(n));
  for (auto& x : out) x = chi2(rng);
  return out;
}

TEST(FindOutlyingSteps, FindsTheOneStepFarInTheTail) {
  const FitData data = HandMadeData(60);
  std::mt19937 rng(3);
  std::vector<double> chi_squares = ChiSquareDraws(rng, 60, kDof);
  // P(χ²(12) ≥ 150) ≈ 1e-25, far below α/N = 1.7e-5.
  chi_squares[37] = 150.0;
  const std::vector<OutlyingStep> found = FindOutlyingSteps(data, chi_squares, {});
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].step, 37);
  EXPECT_EQ(found[0].file, "step37.csv");
  EXPECT_EQ(found[0].level, "high");
  EXPECT_NEAR(found[0].frequency_hz, 50.37, 1e-9);
  EXPECT_EQ(found[0].chi_square, 150.0);
  EXPECT_EQ(found[0].num_residuals, kDof);
  EXPECT_LT(found[0].tail_probability, 1e-3 / 60);
  EXPECT_GT(found[0].tail_probability, 0.0);
  EXPECT_FALSE(found[0].unsettled);
}

TEST(FindOutlyingSteps, TheLimitIsTheChiSquareTailAtAlphaOverTheNumberOfSteps) {
  // 60 steps at χ² = 11 (below the median of χ²(12), 11.34: the robust scale
  // stays 1) and one at x: an outlier when P(χ²(12) ≥ x) < 1e-3/60 = 1.67e-5,
  // i.e. x > 43.78. The tails, from the Poisson sum e^{−x/2}Σ_{j<6}(x/2)^j/j!:
  // P(≥ 40) = 7.2e-5, P(≥ 43) = 2.26e-5, P(≥ 45) = 1.03e-5.
  const FitData data = HandMadeData(60);
  std::vector<double> chi_squares(60, 11.0);
  for (double x : {30.0, 40.0, 43.0}) {
    chi_squares[12] = x;
    EXPECT_TRUE(FindOutlyingSteps(data, chi_squares, {}).empty()) << x;
  }
  chi_squares[12] = 45.0;
  const std::vector<OutlyingStep> found = FindOutlyingSteps(data, chi_squares, {});
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].step, 12);
  EXPECT_NEAR(found[0].tail_probability, 1.0305007e-5, 1e-9);
  // At α = 0.01 the limit is 1.67e-4: 40 is then an outlier, 30 (P = 2.8e-3) not.
  chi_squares[12] = 40.0;
  EXPECT_EQ(FindOutlyingSteps(data, chi_squares, {.outlier_probability = 0.01}).size(), 1u);
  chi_squares[12] = 30.0;
  EXPECT_TRUE(FindOutlyingSteps(data, chi_squares, {.outlier_probability = 0.01}).empty());
}

TEST(FindOutlyingSteps, DrawsFromTheAssumedDistributionRaiseAnAlarmAtMostAtTheFamilyWiseRate) {
  // 100 draws of 200 steps: α = 1e-3 family-wise, so ~0.1 draws with an
  // alarm are expected. A test without the Bonferroni correction would
  // alarm in ~18 % of the draws, one with d = C·K = 6 in all.
  const FitData data = HandMadeData(200);
  std::mt19937 rng(20240611);
  int clean = 0;
  for (int draw = 0; draw < 100; ++draw)
    if (FindOutlyingSteps(data, ChiSquareDraws(rng, 200, kDof), {}).empty()) ++clean;
  std::printf("%d of 100 draws without an outlier\n", clean);
  EXPECT_GE(clean, 98);
}

TEST(FindOutlyingSteps, AUniformlyInflatedSetIsNotOutlyingButItsOwnOutlierStillIs) {
  // Every step 50× its noise: a model that misses everywhere. The robust
  // scale s² = median χ²_i / median χ²(d) absorbs it.
  const FitData data = HandMadeData(80);
  std::mt19937 rng(7);
  int clean = 0;
  for (int draw = 0; draw < 20; ++draw) {
    std::vector<double> chi_squares = ChiSquareDraws(rng, 80, kDof);
    for (auto& x : chi_squares) x *= 50.0;
    if (FindOutlyingSteps(data, chi_squares, {}).empty()) ++clean;
    // One step 30× beyond the rest (χ²/s² ≈ 360) is still found.
    chi_squares[5] = 50.0 * 360.0;
    const std::vector<OutlyingStep> found = FindOutlyingSteps(data, chi_squares, {});
    ASSERT_EQ(found.size(), 1u) << "draw " << draw;
    EXPECT_EQ(found[0].step, 5);
  }
  EXPECT_EQ(clean, 20);
}

TEST(WithoutSteps, KeepsTheOtherStepsInOrderAndEverythingElse) {
  FitData data = HandMadeData(6);
  data.num_fit_harmonics = 2;
  data.force_position_m = 0.57;
  const FitData out = WithoutSteps(data, {4, 1});
  ASSERT_EQ(out.steps.size(), 4u);
  const std::vector<std::string> files{"step0.csv", "step2.csv", "step3.csv", "step5.csv"};
  for (std::size_t i = 0; i < files.size(); ++i) EXPECT_EQ(out.steps[i].file, files[i]);
  EXPECT_EQ(out.num_fit_harmonics, 2);
  EXPECT_EQ(out.force_position_m, 0.57);
  EXPECT_EQ(out.channels.size(), 2u);
  EXPECT_EQ(WithoutSteps(data, {}).steps.size(), 6u);
}

// identify --validate predicts the held-out channels with the robust fit's
// model, which holds no state at a left-out step (it crashed on the step
// count before): the held-out data lose the same steps, and only when the
// robust fit was applied.
TEST(WithoutLeftOutSteps, TheHeldOutChannelsLoseTheStepsTheRobustFitLeftOut) {
  const FitData held_out = HandMadeData(5);
  RobustFitResult robust;
  robust.outliers = {OutlyingStep{.step = 3}, OutlyingStep{.step = 0}};
  EXPECT_EQ(WithoutLeftOutSteps(held_out, robust).steps.size(), 5u);  // found, not applied: all kept
  robust.applied = true;
  const FitData out = WithoutLeftOutSteps(held_out, robust);
  ASSERT_EQ(out.steps.size(), 3u);
  const std::vector<std::string> files{"step1.csv", "step2.csv", "step4.csv"};
  for (std::size_t i = 0; i < files.size(); ++i) EXPECT_EQ(out.steps[i].file, files[i]);
  EXPECT_TRUE(WithoutLeftOutSteps(FitData{}, robust).steps.empty());
}

// ---------------------------------------------------------------------------
// RobustRefit on a simulated campaign: the paper's set-up, base physics,
// 1 N and 9 N, nine steps each over the resonance, 0.4 s records.

const std::vector<std::string> kNames{"k1", "k2", "k3", "c", "loss_factor"};

class RobustRefitOnSimulatedCampaign : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const std::string scenario = testing::PaperScenarioJson("robust fit test: base physics", R"([
      {"label": "low", "force_amplitude_N": 1.0, "frequencies_Hz": {"start": 51, "stop": 57, "step": 0.75}},
      {"label": "high", "force_amplitude_N": 9.0, "frequencies_Hz": {"start": 51, "stop": 57, "step": 0.75}}])", 5);
    const testing::ExtractedCampaign extracted =
        testing::SimulateCampaign(nlohmann::json::parse(scenario), "beamid_robust_fit_test");
    std::ifstream truth_file(extracted.folder / "truth.json");
    const nlohmann::json truth = nlohmann::json::parse(truth_file);
    const auto& law = truth["support_law"]["polynomial"];
    truth_ = new std::vector<double>{law["k1_Nm_rad"].get<double>(), law["k2_Nm_rad2"].get<double>(),
                                     law["k3_Nm_rad3"].get<double>(), law["c_Nms_rad"].get<double>(),
                                     truth["beam"]["loss_factor"].get<double>()};
    clean_ = new FitData(extracted.Fit({"acc1", "acc2"}));
    std::filesystem::remove_all(extracted.folder);
    clean_fit_ = new IdentifyResult(Identify(*clean_, Structure(), Options()));
  }
  static void TearDownTestSuite() {
    delete clean_fit_;
    delete clean_;
    delete truth_;
  }

  // As `beamid identify` fits: the polynomial law and the beam's loss factor.
  static ModelStructure Structure() {
    ModelStructure structure = PolynomialModel({.k1_Nm_rad = 100.0});
    structure.linear.push_back(LossFactor(1e-4));
    return structure;
  }
  static IdentifyOptions Options() {
    IdentifyOptions options;
    options.num_workers = 1;
    return options;
  }

  // The step of `level` nearest `frequency_hz`.
  static int StepAt(const FitData& data, const std::string& level, double frequency_hz) {
    int best = -1;
    for (int i = 0; i < static_cast<int>(data.steps.size()); ++i)
      if (data.steps[i].level == level &&
          (best < 0 || std::abs(data.steps[i].omega_rad_s - 2 * std::numbers::pi * frequency_hz) <
                           std::abs(data.steps[best].omega_rad_s - 2 * std::numbers::pi * frequency_hz)))
        best = i;
    return best;
  }

  // k1, k3, c (the parameters the data determine) inside their 95 % intervals.
  static bool CoversTheTruth(const IdentifyResult& r, std::string* which = nullptr) {
    bool all = true;
    for (std::size_t j : {0u, 2u, 3u}) {
      const ParameterEstimate& p = r.parameters[j];
      const bool covered = p.lower_95 <= (*truth_)[j] && (*truth_)[j] <= p.upper_95;
      if (!covered && which) *which += p.name + " ";
      all = all && covered;
    }
    return all;
  }

  // ... and no wider than the data allow: each standard uncertainty within
  // about four times the clean fit's (k1 0.004 %, k3 0.024 %, c 0.34 % of the truth).
  static bool Tight(const IdentifyResult& r, std::string* which = nullptr) {
    constexpr double kMaxRelativeStd[] = {2e-4, 0.0, 1e-3, 1.5e-2};
    bool all = true;
    for (std::size_t j : {0u, 2u, 3u}) {
      const ParameterEstimate& p = r.parameters[j];
      const bool tight = std::isfinite(p.std) && p.std <= kMaxRelativeStd[j] * std::abs((*truth_)[j]);
      if (!tight && which) *which += p.name + " ± " + std::to_string(p.std) + " ";
      all = all && tight;
    }
    return all;
  }

  static void Print(const char* what, const IdentifyResult& r) {
    std::printf("%s: reduced chi-square %.3g;", what, r.reduced_chi_square);
    for (const auto& p : r.parameters) std::printf(" %s %.6g ± %.2g", p.name.c_str(), p.value, p.std);
    std::printf("\n");
  }

  static std::vector<double>* truth_;
  static FitData* clean_;
  static IdentifyResult* clean_fit_;
};

std::vector<double>* RobustRefitOnSimulatedCampaign::truth_ = nullptr;
FitData* RobustRefitOnSimulatedCampaign::clean_ = nullptr;
IdentifyResult* RobustRefitOnSimulatedCampaign::clean_fit_ = nullptr;

TEST_F(RobustRefitOnSimulatedCampaign, TheCleanFitCoversTheTruth) {
  // The premise of the tests below.
  ASSERT_EQ(clean_->steps.size(), 18u);
  ASSERT_EQ(clean_fit_->parameters.size(), kNames.size());
  for (std::size_t j = 0; j < kNames.size(); ++j) ASSERT_EQ(clean_fit_->parameters[j].name, kNames[j]);
  Print("clean", *clean_fit_);
  std::string which;
  EXPECT_TRUE(CoversTheTruth(*clean_fit_, &which)) << which;
  std::string wide;
  EXPECT_TRUE(Tight(*clean_fit_, &wide)) << wide;
  EXPECT_LT(clean_fit_->reduced_chi_square, 2.0);
}

TEST_F(RobustRefitOnSimulatedCampaign, StepChiSquaresAreEachStepsShareOfTheFit) {
  // Per step, χ²_i recomputed from the model's displacement phasors (the
  // channels measure acceleration: Y = (ikω)²·U), the measured phasors and
  // the whitening; their sum is the fit's χ².
  const std::unique_ptr<FitProblem> problem = HarmonicBalanceFamily().MakeProblem(*clean_, Structure(), Options().model);
  problem->FeasiblePoint(clean_fit_->starts[clean_fit_->best_start].scaled_at);
  const std::vector<double> chi_squares = StepChiSquares(*problem, clean_fit_->x);
  ASSERT_EQ(chi_squares.size(), clean_->steps.size());
  const std::vector<double> positions{clean_->channels[0].position_m, clean_->channels[1].position_m};
  double sum = 0.0;
  for (std::size_t i = 0; i < clean_->steps.size(); ++i) {
    const FitStep& s = clean_->steps[i];
    const Eigen::MatrixXcd u = problem->DisplacementPhasors(clean_fit_->x, static_cast<int>(i), positions);
    double expected = 0.0;
    for (int c = 0; c < 2; ++c)
      for (int k = 1; k <= clean_->num_fit_harmonics; ++k) {
        const std::complex<double> r = DerivativeFactor(2, k * s.omega_rad_s) * u(c, k) - s.measured(c, k - 1);
        expected += (s.whitening[c][k - 1] * Eigen::Vector2d(r.real(), r.imag())).squaredNorm();
      }
    EXPECT_NEAR(chi_squares[i], expected, 1e-6 * expected + 1e-12) << "step " << i;
    sum += chi_squares[i];
  }
  EXPECT_NEAR(sum, clean_fit_->chi_square, 1e-6 * clean_fit_->chi_square);
}

TEST_F(RobustRefitOnSimulatedCampaign, OnTheCleanCampaignNothingIsLeftOut) {
  const RobustFitResult robust = RobustRefit(*clean_, Structure(), *clean_fit_, Options());
  EXPECT_FALSE(robust.applied);
  EXPECT_TRUE(robust.outliers.empty());
  EXPECT_EQ(robust.data.steps.size(), clean_->steps.size());
  ASSERT_EQ(robust.fit.parameters.size(), clean_fit_->parameters.size());
  for (std::size_t j = 0; j < clean_fit_->parameters.size(); ++j) {
    EXPECT_EQ(robust.fit.parameters[j].value, clean_fit_->parameters[j].value) << kNames[j];
    EXPECT_EQ(robust.fit.parameters[j].std, clean_fit_->parameters[j].std) << kNames[j];
  }
  EXPECT_EQ(robust.fit.chi_square, clean_fit_->chi_square);
}

// A glitch of the recording, not physics: acc1 of one 9 N step reads off at
// every harmonic (by `factor`: 1 % high, or 2° late).
struct Glitch {
  double frequency_hz;
  std::complex<double> factor;
};

void ExpectTheGlitchFoundAndLeftOut(const FitData& clean, const Glitch& glitch, const ModelStructure& structure,
                                    const IdentifyOptions& options,
                                    const std::function<bool(const IdentifyResult&, std::string*)>& covers,
                                    const std::function<bool(const IdentifyResult&, std::string*)>& tight,
                                    int bad) {
  FitData glitched = clean;
  glitched.steps[bad].measured.row(0) *= glitch.factor;
  const IdentifyResult ordinary = Identify(glitched, structure, options);
  std::string pulled;
  const bool covered = covers(ordinary, &pulled);
  std::printf("ordinary fit with the glitch: reduced chi-square %.3g, outside their 95 %% intervals: %s\n",
              ordinary.reduced_chi_square, pulled.c_str());
  EXPECT_TRUE(!covered || ordinary.reduced_chi_square > 2.0) << "the glitch did not pull the ordinary fit";

  const RobustFitResult robust = RobustRefit(glitched, structure, ordinary, options);
  std::printf("robust: %s\n", robust.note.c_str());
  EXPECT_TRUE(robust.applied);
  ASSERT_EQ(robust.outliers.size(), 1u);
  EXPECT_EQ(robust.outliers[0].step, bad);
  EXPECT_EQ(robust.outliers[0].file, glitched.steps[bad].file);
  EXPECT_EQ(robust.outliers[0].level, "high");
  EXPECT_NEAR(robust.outliers[0].frequency_hz, glitched.steps[bad].omega_rad_s / (2 * std::numbers::pi), 1e-9);
  EXPECT_EQ(robust.outliers[0].num_residuals, 12);
  ASSERT_EQ(robust.data.steps.size(), glitched.steps.size() - 1);
  for (const auto& s : robust.data.steps) EXPECT_NE(s.file, glitched.steps[bad].file);
  EXPECT_NE(robust.note.find("left out 1 outlying step"), std::string::npos) << robust.note;
  std::string which;
  EXPECT_TRUE(covers(robust.fit, &which)) << "outside their 95 % intervals: " << which;
  std::string wide;
  EXPECT_TRUE(tight(robust.fit, &wide)) << "wider than the data allow: " << wide;
  EXPECT_LT(robust.fit.reduced_chi_square, 2.0);
}

TEST_F(RobustRefitOnSimulatedCampaign, OneGlitchingStepIsFoundLeftOutAndTheTruthCoveredAgain) {
  for (const Glitch& glitch : {Glitch{53.25, 1.01}, Glitch{56.25, std::polar(1.0, 2.0 * std::numbers::pi / 180.0)}}) {
    SCOPED_TRACE("glitch at " + std::to_string(glitch.frequency_hz) + " Hz");
    const int bad = StepAt(*clean_, "high", glitch.frequency_hz);
    ASSERT_GE(bad, 0);
    ExpectTheGlitchFoundAndLeftOut(*clean_, glitch, Structure(), Options(), CoversTheTruth, Tight, bad);
  }
}

// PRODUCT BUG (reported, robust_fit.cc RobustRefit): a 3 % glitch at the 9 N
// step nearest the resonance pulls the ordinary fit so far that five clean
// neighbours also miss beyond the noise there; RobustRefit counts them all
// against max_outlier_fraction before leaving out the worst one, and
// declines. Left out alone, that step leaves a fit within the noise with no
// further outlier (reduced chi-square 0.02). Enable once fixed.
TEST_F(RobustRefitOnSimulatedCampaign, AStrongGlitchNearTheResonanceIsLeftOutNotDeclined) {
  const int bad = StepAt(*clean_, "high", 54.75);
  ASSERT_GE(bad, 0);
  ExpectTheGlitchFoundAndLeftOut(*clean_, {54.75, 1.03}, Structure(), Options(), CoversTheTruth, Tight, bad);
}

TEST_F(RobustRefitOnSimulatedCampaign, AMisfitSpreadOverManyStepsIsDeclined) {
  // A third of the steps (both levels) read 3 % high on acc1.
  FitData spread = *clean_;
  for (std::size_t i = 0; i < spread.steps.size(); i += 3) spread.steps[i].measured.row(0) *= 1.03;
  const IdentifyResult ordinary = Identify(spread, Structure(), Options());
  const RobustFitResult robust = RobustRefit(spread, Structure(), ordinary, Options());
  std::printf("note: %s\n", robust.note.c_str());
  EXPECT_FALSE(robust.applied);
  EXPECT_GT(robust.outliers.size(), 1u);
  EXPECT_NE(robust.note.find("the model's"), std::string::npos) << robust.note;
  EXPECT_NE(robust.note.find("no step was left out"), std::string::npos) << robust.note;
  EXPECT_EQ(robust.data.steps.size(), spread.steps.size());
  ASSERT_EQ(robust.fit.parameters.size(), ordinary.parameters.size());
  for (std::size_t j = 0; j < ordinary.parameters.size(); ++j)
    EXPECT_EQ(robust.fit.parameters[j].value, ordinary.parameters[j].value) << kNames[j];
  EXPECT_EQ(robust.fit.chi_square, ordinary.chi_square);
}

}  // namespace
}  // namespace beamid::solver
