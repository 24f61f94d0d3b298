// The identify, diagnose and predict workflows called directly, without the
// program: on a small simulated campaign (3 steps, made once for the suite)
// the outcome holds what a direct library call finds and what was written,
// the observer is told the tasks in order, and a bad request is refused with
// an InputError naming the field before any work.
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "solver/diagnosis/diagnosis_candidates_csv.h"
#include "solver/diagnosis/diagnosis_io.h"
#include "solver/estimation/identify.h"
#include "solver/estimation/model_structure.h"
#include "solver/estimation/prediction.h"
#include "solver/estimation/prediction_io.h"
#include "solver/estimation/result_io.h"
#include "solver/workflow/diagnose_campaign.h"
#include "solver/workflow/identify_campaign.h"
#include "solver/workflow/predict_campaign.h"
#include "tests/support/expect_refused.h"
#include "tests/support/file_bytes.h"
#include "tests/support/paper_scenario.h"
#include "tests/support/simulated_campaign.h"

namespace {

namespace fs = std::filesystem;
using beamid::testing::InputErrorOf;
using beamid::testing::ReadFile;
using ::testing::HasSubstr;
namespace solver = beamid::solver;
namespace workflow = beamid::workflow;

class Workflows : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    campaign_ = new beamid::testing::SimulatedCampaign(
        beamid::testing::PaperScenarioJson("workflow test", R"([
          {"label": "low", "force_amplitude_N": 0.5, "frequencies_Hz": {"start": 53.6, "stop": 54.6, "step": 0.5}}])",
                                           3),
        "beamid_workflow_test");
    out_ = beamid::testing::UniqueTempPath("beamid_workflow_out");
    fs::remove_all(out_);
    fs::create_directories(out_);
  }
  static void TearDownTestSuite() {
    delete campaign_;
    fs::remove_all(out_);
  }

  // The fit the tests run: two channels, one held out, no outlier test and
  // no damping-law refits (both compared elsewhere), one start.
  static workflow::IdentifyRequest Request(const std::string& output) {
    return {.campaign_folder = campaign_->folder.string(),
            .fit_channels = std::vector<std::string>{"acc1", "acc2"},
            .validate_channels = {"acc3"},
            .damping_envelope = false,
            .robust = false,
            .output = (out_ / output).string()};
  }

  static inline beamid::testing::SimulatedCampaign* campaign_ = nullptr;
  static inline fs::path out_;
};

TEST_F(Workflows, IdentifyCampaignFindsWhatADirectIdentifyFindsAndWritesIt) {
  const workflow::IdentifyRequest request = Request("result.json");
  const workflow::IdentifyOutcome outcome = workflow::IdentifyCampaign(request);

  // The same fit by hand: the campaign's phasors weighed as the workflow
  // does by default (propagated), the polynomial support with the beam's
  // loss factor fitted, H = 5.
  const solver::FitData fit = solver::MakeFitData(
      campaign_->campaign, campaign_->phasors,
      {.channels = {"acc1", "acc2"}, .num_fit_harmonics = 3, .uncertainty = solver::PhasorUncertainty::kPropagated});
  solver::ModelStructure structure = solver::PolynomialModel({.k1_Nm_rad = 100.0});
  structure.linear.push_back(solver::LossFactor(1e-4));
  solver::IdentifyOptions options;
  options.model.num_harmonics = 5;
  const solver::IdentifyResult direct = solver::Identify(fit, structure, options);

  ASSERT_EQ(outcome.Result().parameters.size(), direct.parameters.size());
  for (std::size_t j = 0; j < direct.parameters.size(); ++j) {
    EXPECT_EQ(outcome.Result().parameters[j].name, direct.parameters[j].name);
    EXPECT_EQ(outcome.Result().parameters[j].value, direct.parameters[j].value) << direct.parameters[j].name;
    EXPECT_EQ(outcome.Result().parameters[j].std, direct.parameters[j].std) << direct.parameters[j].name;
  }
  EXPECT_EQ(outcome.Result().chi_square, direct.chi_square);
  EXPECT_EQ(outcome.WithinNoise(), direct.verdict.within_noise);
  EXPECT_EQ(outcome.Result().verdict.text, direct.verdict.text);
  EXPECT_EQ(outcome.fit.steps.size(), campaign_->campaign.steps.size());
  EXPECT_EQ(outcome.family, &solver::HarmonicBalanceFamily());
  EXPECT_TRUE(outcome.damping_laws.laws.empty());  // not asked for

  // What the outcome holds is what was written: the parameters and the held-out channel.
  const solver::ResultFile written = solver::ReadResultFile(request.output);
  ASSERT_EQ(written.parameters.size(), direct.parameters.size());
  for (std::size_t j = 0; j < direct.parameters.size(); ++j)
    EXPECT_EQ(written.parameters[j].value, direct.parameters[j].value) << direct.parameters[j].name;
  ASSERT_EQ(outcome.result_file.validation.size(), 1u);
  EXPECT_EQ(outcome.result_file.validation[0].channel, "acc3");
  ASSERT_EQ(written.validation.size(), 1u);
  EXPECT_EQ(written.validation[0].channel, "acc3");
}

TEST_F(Workflows, TheObserverIsToldEachTaskInOrderWithItsProgress) {
  std::vector<std::string> events;
  double lowest = 1.0, highest = 0.0;
  const workflow::RunObserver observer{
      .begin = [&](const std::string& task) { events.push_back("begin " + task); },
      .progress =
          [&](double fraction, const std::string&) {
            lowest = std::min(lowest, fraction);
            highest = std::max(highest, fraction);
          },
      .end = [&] { events.push_back("end"); },
      .warning = [&](const std::string& source, const std::string& text) { events.push_back(source + ": " + text); },
      .note = {}};
  workflow::IdentifyCampaign(Request("observed.json"), observer);
  EXPECT_EQ(events, (std::vector<std::string>{"begin extract", "end", "begin identify", "end"}));
  EXPECT_GE(lowest, 0.0);
  EXPECT_LE(highest, 1.0);
  EXPECT_GT(highest, 0.0);
}

TEST_F(Workflows, AnEmptyChannelListIsRefusedNamingItBeforeAnyWork) {
  workflow::IdentifyRequest request = Request("empty_list.json");
  request.fit_channels = std::vector<std::string>{};
  EXPECT_THAT(InputErrorOf([&] { workflow::IdentifyCampaign(request); }),
              AllOf(HasSubstr("--fit"), HasSubstr("empty"), HasSubstr("Fix:")));
  EXPECT_FALSE(fs::exists(request.output));

  workflow::DiagnoseRequest diagnose{.campaign_folder = campaign_->folder.string(),
                                     .fit_channels = std::vector<std::string>{},
                                     .output = (out_ / "empty_list_diagnosis.json").string()};
  EXPECT_THAT(InputErrorOf([&] { workflow::DiagnoseCampaign(diagnose); }),
              AllOf(HasSubstr("--fit"), HasSubstr("empty")));
  EXPECT_FALSE(fs::exists(diagnose.output));
}

TEST_F(Workflows, AMissingCampaignFolderIsRefusedNamingIt) {
  workflow::IdentifyRequest request = Request("missing.json");
  request.campaign_folder = (out_ / "no_such_campaign").string();
  EXPECT_THAT(InputErrorOf([&] { workflow::IdentifyCampaign(request); }), HasSubstr(request.campaign_folder));
  EXPECT_FALSE(fs::exists(request.output));

  const workflow::DiagnoseRequest diagnose{.campaign_folder = request.campaign_folder,
                                           .output = (out_ / "missing_diagnosis.json").string()};
  EXPECT_THAT(InputErrorOf([&] { workflow::DiagnoseCampaign(diagnose); }), HasSubstr(request.campaign_folder));
}

TEST_F(Workflows, ARequestOutOfRangeOrAgainstItsInputsIsRefusedNamingTheField) {
  workflow::IdentifyRequest request = Request("refused.json");
  request.fit_harmonics = 6;  // the model holds 5
  EXPECT_THAT(InputErrorOf([&] { request.Validate(); }), AllOf(HasSubstr("--fit-harmonics 6"), HasSubstr("-H 5")));
  request = Request("refused.json");
  request.harmonics = 0;
  EXPECT_THAT(InputErrorOf([&] { request.Validate(); }), AllOf(HasSubstr("-H"), HasSubstr("must be")));
  request = Request("refused.json");
  request.model = "fem";
  EXPECT_THAT(InputErrorOf([&] { request.Validate(); }), AllOf(HasSubstr("'fem'"), HasSubstr("hb")));
  // An output inside the campaign would mix a result into the recordings.
  request = Request("refused.json");
  request.output = (campaign_->folder / "result.json").string();
  EXPECT_THAT(InputErrorOf([&] { request.Validate(); }), HasSubstr("-o"));
  EXPECT_FALSE(fs::exists(request.output));

  workflow::DiagnoseRequest diagnose{.campaign_folder = campaign_->folder.string(),
                                     .candidates = {"support_friction", "gravity"},
                                     .output = (out_ / "refused_diagnosis.json").string()};
  EXPECT_THAT(InputErrorOf([&] { diagnose.Validate(); }),
              AllOf(HasSubstr("--candidates"), HasSubstr("'gravity'"), HasSubstr("support_friction")));
  diagnose.candidates = {};
  diagnose.significance = 0.9;
  EXPECT_THAT(InputErrorOf([&] { diagnose.Validate(); }), AllOf(HasSubstr("--significance"), HasSubstr("must be")));
}

TEST_F(Workflows, DiagnoseCampaignReturnsTheDiagnosisItWrites) {
  const workflow::DiagnoseRequest request{.campaign_folder = campaign_->folder.string(),
                                          .fit_channels = std::vector<std::string>{"acc1", "acc2"},
                                          .validate_channels = {"acc3"},
                                          .candidates = {"support_friction"},
                                          .phasor_uncertainty = solver::PhasorUncertainty::kPropagated,
                                          .recording_check = false,
                                          .output = (out_ / "diagnosis.json").string(),
                                          .csv_output = (out_ / "candidates.csv").string()};
  const workflow::DiagnoseOutcome outcome = workflow::DiagnoseCampaign(request);
  EXPECT_EQ(ReadFile(out_ / "candidates.csv"), solver::DiagnosisCandidatesCsv(outcome.diagnosis));
  EXPECT_EQ(outcome.num_steps, campaign_->campaign.steps.size());
  EXPECT_TRUE(outcome.curves_problem.empty());  // no curves asked for
  EXPECT_FALSE(fs::exists(out_ / "diagnosis.png"));
  const solver::DiagnosisFile written = solver::ReadDiagnosisFile(request.output);
  EXPECT_EQ(written.diagnosis.verdict, outcome.diagnosis.verdict);
  EXPECT_EQ(written.diagnosis.summary, outcome.diagnosis.summary);
  EXPECT_EQ(written.diagnosis.base.chi_square, outcome.diagnosis.base.chi_square);
  EXPECT_EQ(written.campaign_sha256, campaign_->campaign.sha256);
  EXPECT_EQ(written.phasor_uncertainty, solver::PhasorUncertainty::kPropagated);  // as the fit weighed the phasors
  // Only the asked candidate was tried.
  for (const auto& c : outcome.diagnosis.candidates) EXPECT_EQ(c.name, "support_friction");
}

TEST_F(Workflows, PredictCampaignPredictsWhatADirectPredictionFindsAndComparesTheSensorThere) {
  const workflow::IdentifyRequest identify = Request("for_prediction.json");
  workflow::IdentifyCampaign(identify);
  const workflow::PredictRequest request{.result_file = identify.output,
                                         .campaign_folder = campaign_->folder.string(),
                                         .position_m = 0.57,  // acc3
                                         .output = (out_ / "prediction.json").string()};
  std::vector<std::string> tasks;
  const workflow::PredictOutcome outcome =
      workflow::PredictCampaign(request, {.begin = [&](const std::string& task) { tasks.push_back(task); }});
  EXPECT_EQ(tasks, std::vector<std::string>{"predict"});

  const std::vector<solver::PredictedStep> direct =
      solver::PredictAt(solver::ToIdentifiedModel(solver::ReadResultFile(identify.output)), 0.57);
  ASSERT_EQ(outcome.num_steps, direct.size());
  ASSERT_EQ(outcome.file.steps.size(), direct.size());
  EXPECT_EQ(outcome.family, &solver::HarmonicBalanceFamily());
  for (std::size_t i = 0; i < direct.size(); ++i) {
    EXPECT_EQ(outcome.file.steps[i].file, direct[i].file);
    ASSERT_FALSE(outcome.file.steps[i].harmonics.empty());
    EXPECT_EQ(outcome.file.steps[i].harmonics[0].displacement_m, direct[i].displacement_m[1]);
  }
  EXPECT_TRUE(outcome.Unconverged().empty());
  // acc3 sits at x: compared, with the worst first-harmonic error of the steps.
  EXPECT_EQ(outcome.file.compared_channel, "acc3");
  double worst = 0.0;
  for (const auto& step : outcome.file.steps) {
    ASSERT_TRUE(step.harmonics[0].compared);
    worst = std::max(worst, step.harmonics[0].relative_error);
  }
  EXPECT_EQ(outcome.worst_h1_relative_error, worst);
  EXPECT_GT(worst, 0.0);
  const solver::PredictionFile written = solver::ReadPredictionFile(request.output);
  EXPECT_EQ(written.compared_channel, "acc3");
  ASSERT_EQ(written.steps.size(), direct.size());
  EXPECT_EQ(written.steps[0].harmonics[0].displacement_m, direct[0].displacement_m[1]);

  // Off the beam's range, and an output that is the result itself: refused.
  workflow::PredictRequest refused = request;
  refused.position_m = -0.1;
  EXPECT_THAT(InputErrorOf([&] { refused.Validate(); }), AllOf(HasSubstr("--x"), HasSubstr("must be")));
  refused = request;
  refused.output = identify.output;
  EXPECT_THAT(InputErrorOf([&] { workflow::PredictCampaign(refused); }), HasSubstr("-o"));
}

}  // namespace
