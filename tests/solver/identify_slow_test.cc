// Identification on a campaign from the independent time-domain simulator
// (never from the harmonic-balance model it fits): the paper's set-up, base
// physics (polynomial support), three force levels, realistic noise.
#include "solver/estimation/identification_problem.h"
#include "solver/estimation/identify.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <random>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "solver/estimation/prediction.h"
#include "solver/estimation/result_file.h"
#include "solver/estimation/result_io.h"
#include "tests/support/paper_scenario.h"
#include "tests/support/simulated_campaign.h"

namespace beamid::solver {
namespace {

constexpr double kK1 = 150.0, kK2 = 0.0, kK3 = 3e5, kC = 0.05;

const std::string kScenario = testing::PaperScenarioJson("identification test: paper set-up, base physics", R"([
  {"label": "low", "force_amplitude_N": 1.0, "frequencies_Hz": {"start": 51, "stop": 57.3, "step": 0.45}},
  {"label": "mid", "force_amplitude_N": 4.0, "frequencies_Hz": {"start": 51, "stop": 57.3, "step": 0.45}},
  {"label": "high", "force_amplitude_N": 11.0, "frequencies_Hz": {"start": 51, "stop": 57.3, "step": 0.45}}])", 7);

class IdentifyOnSimulatedCampaign : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { simulated_ = new testing::SimulatedCampaign(kScenario, "beamid_identify_slow_test"); }
  static void TearDownTestSuite() { delete simulated_; }

  static FitData Fit(std::vector<std::string> channels) {
    return MakeFitData(simulated_->campaign, simulated_->phasors, {.channels = std::move(channels)});
  }

  static testing::SimulatedCampaign* simulated_;
};

testing::SimulatedCampaign* IdentifyOnSimulatedCampaign::simulated_ = nullptr;

double Value(const IdentifyResult& r, const std::string& name) {
  for (const auto& p : r.parameters)
    if (p.name == name) return p.value;
  ADD_FAILURE() << "no parameter " << name;
  return 0.0;
}

TEST_F(IdentifyOnSimulatedCampaign, RecoversTheSupportWithinTheIssuesTolerances) {
  const FitData fit = Fit({"acc1", "acc2"});
  const IdentifyResult result = Identify(fit, PolynomialModel({.k1_Nm_rad = 100.0}), {});
  EXPECT_NEAR(Value(result, "k1"), kK1, 0.01 * kK1);
  EXPECT_NEAR(Value(result, "c"), kC, 0.05 * kC);
  EXPECT_NEAR(Value(result, "k3"), kK3, 0.10 * kK3);
  const ParameterEstimate& k2 = result.parameters[1];
  EXPECT_LE(k2.lower_95, kK2);
  EXPECT_GE(k2.upper_95, kK2);
  EXPECT_LE(k2.std, 10.0);  // measured 5.2 N·m/rad²: not by being vague
  for (const auto& p : result.parameters) std::printf("%s = %.6g ± %.3g %s\n", p.name.c_str(), p.value, p.std, p.unit.c_str());
  std::printf("reduced chi-square %.3g, %.2f s\n", result.reduced_chi_square, result.seconds);
}

TEST_F(IdentifyOnSimulatedCampaign, PredictsTheHeldOutAccelerometerAndAHiddenPosition) {
  const FitData fit = Fit({"acc1", "acc2"});
  const FitData held_out = Fit({"acc3"});
  const ModelStructure structure = PolynomialModel({.k1_Nm_rad = 100.0});
  const IdentifyResult result = Identify(fit, structure, {});
  IdentificationProblem problem(fit, structure, {});
  problem.FeasiblePoint(result.starts[result.best_start].scaled_at);
  // First harmonic against the measurement; the third against the truth
  // file's noise-free phasors, since at the low level it lies below the
  // noise floor of the measured acc3. The truth is itself a time
  // integration stopped when the response changed by `settle_change`
  // between windows (~1e-5; more on the first step, from rest, when it hit
  // settle_max_s): what is left of the transient (the lightly damped second
  // mode, near 3Ω) is of that order relative to the fundamental, so the
  // third harmonic is held to 10 % plus that floor.
  double worst_acc3 = 0.0, worst_hidden = 0.0, worst_acc3_h3 = 0.0, worst_hidden_h3 = 0.0;
  const auto truth_phasor = [](const nlohmann::json& harmonics, int k) {
    return std::complex<double>(harmonics[k - 1][0].get<double>(), harmonics[k - 1][1].get<double>());
  };
  const auto relative = [](std::complex<double> a, std::complex<double> b) { return std::abs(a - b) / std::abs(b); };
  for (int i = 0; i < problem.num_steps(); ++i) {
    const double omega = fit.steps[i].omega_rad_s;
    const Eigen::MatrixXcd y = problem.DisplacementPhasors(result.x, i, {0.57, 0.45});
    const auto& truth_step = simulated_->truth["steps"][i];
    const double settle_change = truth_step["settle_change"].get<double>();
    const auto third_harmonic_ok = [&](std::complex<double> predicted, const nlohmann::json& truth) {
      const double allowed = 0.10 * std::abs(truth_phasor(truth, 3)) + settle_change * std::abs(truth_phasor(truth, 1));
      return std::abs(predicted - truth_phasor(truth, 3)) < allowed;
    };
    worst_acc3 = std::max(worst_acc3, relative(-omega * omega * y(0, 1), held_out.steps[i].measured(0, 0)));
    const auto& acc3_truth = truth_step["channels"]["acc3"]["harmonics"];
    const std::complex<double> acc3_h3 = -9 * omega * omega * y(0, 3);
    worst_acc3_h3 = std::max(worst_acc3_h3, relative(acc3_h3, truth_phasor(acc3_truth, 3)));
    EXPECT_TRUE(third_harmonic_ok(acc3_h3, acc3_truth)) << "acc3, step " << i;
    // The truth file's noise-free displacement at 0.45 m (not in the campaign).
    const auto& hidden = truth_step["hidden"][0];
    ASSERT_DOUBLE_EQ(hidden["position_m"].get<double>(), 0.45);
    const auto& hidden_truth = hidden["displacement_m"]["harmonics"];
    worst_hidden = std::max(worst_hidden, relative(y(1, 1), truth_phasor(hidden_truth, 1)));
    worst_hidden_h3 = std::max(worst_hidden_h3, relative(y(1, 3), truth_phasor(hidden_truth, 3)));
    EXPECT_TRUE(third_harmonic_ok(y(1, 3), hidden_truth)) << "0.45 m, step " << i;
  }
  std::printf("worst error: acc3 h1 %.3f %%, h3 %.2f %%; hidden 0.45 m h1 %.3f %%, h3 %.2f %%\n", 100 * worst_acc3,
              100 * worst_acc3_h3, 100 * worst_hidden, 100 * worst_hidden_h3);
  EXPECT_LT(worst_acc3, 0.02);
  EXPECT_LT(worst_hidden, 0.02);
}

// The data, every measured and force phasor, changed by ±1e-12 relative: the
// size of the differences between machines (libm variants, FFTW's SIMD
// codelets), which must not change the best fit.
FitData PerturbedAtTheLastBits(FitData data, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (FitStep& step : data.steps) {
    for (Eigen::Index j = 0; j < step.measured.size(); ++j) step.measured(j) *= 1.0 + 1e-12 * unit(random);
    for (Eigen::Index j = 0; j < step.force_N.size(); ++j) step.force_N(j) *= 1.0 + 1e-12 * unit(random);
  }
  return data;
}

TEST_F(IdentifyOnSimulatedCampaign, FindsTheSameFitFromFarStartsWhateverTheLastBitsAndTheSeed) {
  const FitData fit = Fit({"acc1", "acc2"});
  const IdentifyResult reference = Identify(fit, PolynomialModel({.k1_Nm_rad = 100.0}), {});
  int reached = 0, tried = 0;
  double seconds = 0.0;
  for (double factor : {3.0, 1.0 / 3.0, 5.0, 1.0 / 5.0})
    for (unsigned variant : {0u, 1u, 2u})
      for (bool direct : {false, true}) {
        // The far start and eight space-filling starts over a factor 9
        // either way of it (so that the range holds the truth well inside);
        // with the direct estimate, those start around that estimate.
        IdentifyOptions far;
        far.use_direct_estimate = direct;
        far.num_starts = 8;
        far.start_spread = 9.0;
        far.seed = 1 + variant;
        const double nudge = variant == 0 ? 1.0 : 1.0 + (variant == 1 ? 1e-12 : -1e-12);
        // k2 is 0 in truth: start it at ±3 % of k3's scale instead.
        const ModelStructure start = PolynomialModel({.k1_Nm_rad = kK1 * factor * nudge,
                                                      .k2_Nm_rad2 = 3e3 * factor * nudge,
                                                      .k3_Nm_rad3 = kK3 * factor * nudge,
                                                      .c_Nms_rad = kC * factor * nudge});
        const IdentifyResult result = Identify(variant == 0 ? fit : PerturbedAtTheLastBits(fit, variant), start, far);
        const std::string where = "factor " + std::to_string(factor) + ", variant " + std::to_string(variant) +
                                  (direct ? ", with" : ", without") + " the direct estimate";
        EXPECT_NEAR(Value(result, "k1"), Value(reference, "k1"), 1e-4 * Value(reference, "k1")) << where;
        EXPECT_NEAR(Value(result, "k3"), Value(reference, "k3"), 1e-3 * Value(reference, "k3")) << where;
        EXPECT_NEAR(Value(result, "c"), Value(reference, "c"), 1e-3 * Value(reference, "c")) << where;
        // No other minimum the data cannot rule out; and most starts reach
        // the best fit (before the states were seeded on the measured
        // branch, 1 or 2 of 9 did, and on some machines none).
        EXPECT_TRUE(result.minima.decisive) << where;
        EXPECT_GE(3 * result.starts_at_best, 2 * static_cast<int>(result.starts.size())) << where;
        reached += result.starts_at_best;
        tried += static_cast<int>(result.starts.size());
        seconds += result.seconds;
      }
  std::printf("%d of %d starts reached the best fit, %.2f s per search of 9 starts\n", reached, tried,
              seconds / (tried / 9));
}

TEST_F(IdentifyOnSimulatedCampaign, BranchRepairTakesTheOldSearchOutOfItsLocalMinimum) {
  // The old search (states solved at each start's parameters, never seeded
  // on the measured branch) from a factor 3 away, as the test that failed on
  // an AVX-512 machine ran it: there its one converged start ended in a
  // local minimum with one step of the top level (55.05 Hz) on the lower
  // branch of the fold, k1 150.71, k3 323233, χ² 1.8e8 against 108. Where
  // it does, re-seeding that end point's states on the measured branch
  // lowers the misfit, and the re-run reaches the best fit.
  const FitData fit = Fit({"acc1", "acc2"});
  const IdentifyResult reference = Identify(fit, PolynomialModel({.k1_Nm_rad = 100.0}), {});
  IdentifyOptions old_search;
  old_search.use_direct_estimate = false;
  old_search.seed_states_from_measurements = false;
  old_search.num_starts = 8;
  old_search.start_spread = 9.0;
  const ModelStructure start = PolynomialModel(
      {.k1_Nm_rad = 3 * kK1, .k2_Nm_rad2 = 9e3, .k3_Nm_rad3 = 3 * kK3, .c_Nms_rad = 3 * kC});
  const IdentifyResult repaired = Identify(fit, start, old_search);
  EXPECT_NEAR(Value(repaired, "k1"), Value(reference, "k1"), 1e-4 * Value(reference, "k1"));
  EXPECT_NEAR(Value(repaired, "k3"), Value(reference, "k3"), 1e-3 * Value(reference, "k3"));
  EXPECT_NEAR(Value(repaired, "c"), Value(reference, "c"), 1e-3 * Value(reference, "c"));
  old_search.branch_repair = false;
  const IdentifyResult unrepaired = Identify(fit, start, old_search);
  int repairs = 0;
  for (const auto& s : repaired.starts) repairs += s.branch_repairs;
  std::printf("old search: %d of %zu starts converged; without branch repair k1 = %.6g (%d minima), with it "
              "k1 = %.6g after %d repair(s)\n",
              static_cast<int>(std::count_if(unrepaired.starts.begin(), unrepaired.starts.end(),
                                             [](const StartOutcome& s) { return s.success; })),
              unrepaired.starts.size(), Value(unrepaired, "k1"), static_cast<int>(unrepaired.minima.minima.size()),
              Value(repaired, "k1"), repairs);
  // Where the old search ended elsewhere, that minimum was repaired.
  if (std::abs(Value(unrepaired, "k1") - Value(reference, "k1")) > 1e-4 * Value(reference, "k1")) {
    EXPECT_GT(repairs, 0);
  }
}

// The same numbers, to the last bit, on two runs and in one process or in
// parallel worker processes (the starts are independent; which worker runs
// which must not matter).
TEST_F(IdentifyOnSimulatedCampaign, GivesIdenticalNumbersOnEveryRunAndAnyNumberOfWorkers) {
  const FitData fit = Fit({"acc1", "acc2"});
  IdentifyOptions options;
  options.num_starts = 4;
  options.num_workers = 2;
  const IdentifyResult parallel = Identify(fit, PolynomialModel({.k1_Nm_rad = 100.0}), options);
  const IdentifyResult again = Identify(fit, PolynomialModel({.k1_Nm_rad = 100.0}), options);
  options.num_workers = 1;
  const IdentifyResult serial = Identify(fit, PolynomialModel({.k1_Nm_rad = 100.0}), options);
  for (const IdentifyResult* other : {&again, &serial}) {
    ASSERT_EQ(other->parameters.size(), parallel.parameters.size());
    for (std::size_t j = 0; j < parallel.parameters.size(); ++j) {
      EXPECT_EQ(other->parameters[j].value, parallel.parameters[j].value) << parallel.parameters[j].name;
      EXPECT_EQ(other->parameters[j].std, parallel.parameters[j].std) << parallel.parameters[j].name;
    }
    EXPECT_EQ(other->chi_square, parallel.chi_square);
    EXPECT_EQ(other->best_start, parallel.best_start);
  }
}

TEST_F(IdentifyOnSimulatedCampaign, ThePapersOwnFlowOneStepTwoAccelerometers) {
  // One step of the top level near 54.2 Hz, fit on acc1 and acc2, predict acc3.
  FitData fit = Fit({"acc1", "acc2"});
  FitData held_out = Fit({"acc3"});
  std::size_t chosen = 0;
  for (std::size_t i = 0; i < fit.steps.size(); ++i)
    if (fit.steps[i].level == "high" &&
        std::abs(fit.steps[i].omega_rad_s / (2 * std::numbers::pi) - 54.2) <
            std::abs(fit.steps[chosen].omega_rad_s / (2 * std::numbers::pi) - 54.2))
      chosen = i;
  fit.steps = {fit.steps[chosen]};
  fit.levels = {"high"};
  const ModelStructure structure = PolynomialModel({.k1_Nm_rad = 100.0});
  const IdentifyResult result = Identify(fit, structure, {});
  IdentificationProblem problem(fit, structure, {});
  problem.FeasiblePoint(result.starts[result.best_start].scaled_at);
  const double omega = fit.steps[0].omega_rad_s;
  const std::complex<double> acc3 = -omega * omega * problem.DisplacementPhasors(result.x, 0, {0.57})(0, 1);
  const std::complex<double> measured = held_out.steps[chosen].measured(0, 0);
  std::printf("one step at %.2f Hz: acc3 predicted %.4g%+.4gi, measured %.4g%+.4gi\n", omega / (2 * std::numbers::pi),
              acc3.real(), acc3.imag(), measured.real(), measured.imag());
  EXPECT_LT(std::abs(acc3 - measured), 0.02 * std::abs(measured));
}

TEST_F(IdentifyOnSimulatedCampaign, PredictFromTheResultFileMatchesTheTruthWithItsBand) {
  // result.json written, read back, and the model re-solved per step at a
  // position that is in no campaign file: the truth file's 0.45 m.
  const FitData fit = Fit({"acc1", "acc2"});
  const ModelStructure structure = PolynomialModel({.k1_Nm_rad = 100.0});
  const IdentifyResult result = Identify(fit, structure, {});
  IdentificationProblem problem(fit, structure, {});
  problem.FeasiblePoint(result.starts[result.best_start].scaled_at);
  const auto file = simulated_->folder / "result.json";
  WriteResultFile(file, MakeResultFile(fit, FitData{}, problem, result, {}));
  const IdentifiedModel model = ReadIdentifiedModel(file);
  const std::vector<PredictedStep> predicted = PredictAt(model, 0.45);
  ASSERT_EQ(predicted.size(), fit.steps.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < predicted.size(); ++i) {
    ASSERT_TRUE(predicted[i].converged);
    const auto& h1 = simulated_->truth["steps"][i]["hidden"][0]["displacement_m"]["harmonics"][0];
    const std::complex<double> truth(h1[0].get<double>(), h1[1].get<double>());
    worst = std::max(worst, std::abs(predicted[i].displacement_m[1] - truth) / std::abs(truth));
    // The band is a real spread: positive, and far below the amplitude.
    EXPECT_GT(predicted[i].std_real_m[1] + predicted[i].std_imag_m[1], 0.0);
    EXPECT_LT(predicted[i].std_real_m[1] + predicted[i].std_imag_m[1], 0.05 * std::abs(truth));
  }
  EXPECT_LT(worst, 0.02);
  EXPECT_THROW(PredictAt(model, 0.8), std::invalid_argument);
  EXPECT_THROW(ReadIdentifiedModel(simulated_->folder / "missing.json"), std::invalid_argument);
}

}  // namespace
}  // namespace beamid::solver
