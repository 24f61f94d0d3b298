// The workflows of a model file and of measured tables called directly,
// without the program: a model's backbone and response curves
// (examples/paper_setup/model.json) and the measured backbone of the demo's
// phasor tables (examples/phasor_tables/) hold what a direct library call
// finds and what was written, and a bad request is refused with
// an InputError naming the field before any work. Run from the source folder
// (as ctest does).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hb/backbone_file.h"
#include "hb/frc_file.h"
#include "signal/phasor_table.h"
#include "solver/backbone/measured_backbone.h"
#include "solver/backbone/measured_backbone_io.h"
#include "solver/report/measured_backbone_report.h"
#include "solver/workflow/measure_backbone.h"
#include "solver/workflow/trace_model_backbone.h"
#include "solver/workflow/trace_response_curves.h"
#include "solver/workflow/write_report.h"
#include "tests/support/expect_refused.h"
#include "tests/support/file_bytes.h"
#include "tests/support/temp_path.h"

namespace {

namespace fs = std::filesystem;
using beamid::testing::InputErrorOf;
using beamid::testing::ReadFile;
using ::testing::HasSubstr;
namespace solver = beamid::solver;
namespace workflow = beamid::workflow;

const std::vector<std::string> kTables = {"examples/phasor_tables/low.csv", "examples/phasor_tables/mid.csv",
                                          "examples/phasor_tables/high.csv"};

class BackboneWorkflows : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    out_ = beamid::testing::UniqueTempPath("beamid_backbone_workflow");
    fs::remove_all(out_);
    fs::create_directories(out_);
  }
  static void TearDownTestSuite() { fs::remove_all(out_); }
  static inline fs::path out_;
};

TEST_F(BackboneWorkflows, AModelsBackboneIsTracedWrittenAndReturned) {
  const workflow::TraceBackboneRequest request{.model_file = "examples/paper_setup/model.json",
                                               .min_theta_rad = 1e-4,
                                               .max_theta_rad = 1e-2,
                                               .points = 6,
                                               .harmonics = 3,
                                               .output = (out_ / "model").string()};
  std::vector<std::string> tasks;
  const workflow::TraceBackboneOutcome outcome = workflow::TraceModelBackbone(
      request, {.begin = [&](const std::string& task) { tasks.push_back(task); }});
  EXPECT_EQ(tasks, std::vector<std::string>{"backbone"});
  ASSERT_TRUE(outcome.Complete()) << outcome.summary.message;
  ASSERT_EQ(outcome.summary.points.size(), 6u);
  ASSERT_EQ(outcome.file.points.size(), 6u);
  EXPECT_EQ(outcome.file.harmonics, 3);
  // The paper's support stiffens (k3 > 0): the resonance rises with the amplitude.
  EXPECT_GT(outcome.file.points.back().frequency_hz, outcome.file.points.front().frequency_hz);
  EXPECT_DOUBLE_EQ(outcome.file.points.front().theta_amplitude_rad, 1e-4);
  // What the outcome holds is what was written.
  EXPECT_EQ(ReadFile(request.output + ".json"), beamid::hb::BackboneFileToJson(outcome.file));
  EXPECT_EQ(ReadFile(request.output + ".csv"), beamid::hb::BackboneFileToCsv(outcome.file));
}

TEST_F(BackboneWorkflows, ABadModelBackboneRequestIsRefusedNamingTheField) {
  workflow::TraceBackboneRequest request{.model_file = "examples/paper_setup/model.json",
                                         .min_theta_rad = 1e-2,
                                         .max_theta_rad = 1e-3,
                                         .output = (out_ / "refused").string()};
  EXPECT_THAT(InputErrorOf([&] { workflow::TraceModelBackbone(request); }),
              AllOf(HasSubstr("--min-theta-rad"), HasSubstr("--max-theta-rad")));
  EXPECT_FALSE(fs::exists(request.output + ".json"));
  request.min_theta_rad = 1e-5;
  request.points = 1;
  EXPECT_THAT(InputErrorOf([&] { request.Validate(); }), AllOf(HasSubstr("--points"), HasSubstr("must be")));
  request.points = 10;
  request.model_file.clear();
  EXPECT_THAT(InputErrorOf([&] { request.Validate(); }), HasSubstr("model file"));
  // PREFIX.json may not replace the model (Validate only checks: nothing is written).
  request.model_file = "examples/paper_setup/model.json";
  request.output = "examples/paper_setup/model";
  EXPECT_THAT(InputErrorOf([&] { request.Validate(); }), HasSubstr("-o"));
}

TEST_F(BackboneWorkflows, TheMeasuredBackboneOfTablesIsWhatADirectAnalysisFindsAndIsWritten) {
  const workflow::MeasureBackboneRequest request{.inputs = kTables, .output = (out_ / "measured").string()};
  const workflow::MeasureBackboneOutcome outcome = workflow::MeasureBackbone(request);

  std::vector<beamid::signal::FirstHarmonicLevel> levels;
  for (const auto& table : kTables) levels.push_back(beamid::signal::ReadPhasorTable(table));
  const solver::MeasuredBackbone direct = solver::AnalyseMeasuredBackbone(levels);

  EXPECT_EQ(outcome.channel, levels.front().channel);
  EXPECT_TRUE(outcome.model_backbone.empty());  // no result file
  ASSERT_EQ(outcome.measured.levels.size(), 3u);
  ASSERT_EQ(direct.levels.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(outcome.measured.levels[i].label, direct.levels[i].label);
    EXPECT_EQ(outcome.measured.levels[i].quadrature_frequency_hz.value, direct.levels[i].quadrature_frequency_hz.value);
    EXPECT_EQ(outcome.measured.levels[i].damping_ratio.value, direct.levels[i].damping_ratio.value);
  }
  EXPECT_EQ(outcome.measured.fit.FormName(), direct.fit.FormName());
  EXPECT_EQ(outcome.measured.damping_trend.verdict, direct.damping_trend.verdict);

  const solver::MeasuredBackboneFile written = solver::ReadMeasuredBackboneFile(request.output + ".json");
  EXPECT_EQ(written.inputs, kTables);
  ASSERT_EQ(written.levels.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_EQ(written.levels[i].quadrature_frequency_hz.value, direct.levels[i].quadrature_frequency_hz.value);
  // One row per level under the header.
  std::istringstream csv(ReadFile(request.output + ".csv"));
  int rows = 0;
  for (std::string line; std::getline(csv, line);) ++rows;
  EXPECT_EQ(rows, 4);
  EXPECT_TRUE(fs::exists(request.output + "_curves.csv"));
}

// The demo's tables with their force columns renamed a drive voltage: the
// same numbers, now per volt, and the levels read as voltage-controlled.
TEST_F(BackboneWorkflows, TablesDrivenByAVoltageGiveAVoltageControlledBackbone) {
  std::vector<std::string> voltage_tables;
  for (const auto& table : kTables) {
    std::string text = ReadFile(table);
    const std::string force = "force [N],force_std [N]";
    ASSERT_NE(text.find(force), std::string::npos) << table;
    text.replace(text.find(force), force.size(), "voltage [V],voltage_std [V]");
    voltage_tables.push_back((out_ / fs::path(table).filename()).string());
    beamid::testing::WriteFile(voltage_tables.back(), text);
  }
  const auto forced = workflow::MeasureBackbone({.inputs = kTables, .output = (out_ / "forced").string()});
  const auto driven = workflow::MeasureBackbone({.inputs = voltage_tables, .output = (out_ / "driven").string()});
  EXPECT_EQ(forced.measured.excitation_quantity, "force");
  EXPECT_EQ(driven.measured.excitation_quantity, "voltage");
  ASSERT_EQ(driven.measured.levels.size(), forced.measured.levels.size());
  for (std::size_t i = 0; i < forced.measured.levels.size(); ++i)
    EXPECT_EQ(driven.measured.levels[i].quadrature_frequency_hz.value,
              forced.measured.levels[i].quadrature_frequency_hz.value);
  EXPECT_EQ(solver::ReadMeasuredBackboneFile((out_ / "driven.json").string()).excitation_quantity, "voltage");
  EXPECT_THAT(ReadFile(out_ / "driven.csv"), HasSubstr(",voltage_V,voltage_std_V,"));
}

TEST_F(BackboneWorkflows, TheReportOfAMeasuredBackboneIsTheLibrarysPage) {
  const workflow::MeasureBackboneRequest measure{.inputs = kTables, .output = (out_ / "for_report").string()};
  workflow::MeasureBackbone(measure);
  const workflow::ReportRequest request{.input_file = measure.output + ".json",
                                        .output = (out_ / "report.html").string()};
  std::vector<std::string> tasks;
  const workflow::ReportOutcome outcome =
      workflow::WriteReport(request, {.begin = [&](const std::string& task) { tasks.push_back(task); }});
  EXPECT_EQ(tasks, std::vector<std::string>{"report: plots"});
  EXPECT_TRUE(outcome.measured_backbone);
  const std::string page = ReadFile(request.output);
  EXPECT_EQ(outcome.html_bytes, page.size());
  EXPECT_EQ(page, solver::MeasuredBackboneHtmlReport(solver::ReadMeasuredBackboneFile(request.input_file),
                                                     request.input_file));
  // No screenshot asked for: none taken.
  workflow::ScreenshotReport(request);
  EXPECT_FALSE(fs::exists(out_ / "report.png"));

  // A measured backbone needs no campaign: one given is a slip.
  workflow::ReportRequest with_campaign = request;
  with_campaign.campaign_folder = (out_ / "a_campaign").string();
  with_campaign.output = (out_ / "refused.html").string();
  try {
    workflow::WriteReport(with_campaign);
    ADD_FAILURE() << "accepted a campaign for a measured backbone";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("--campaign"));
  }
  EXPECT_FALSE(fs::exists(with_campaign.output));
}

TEST_F(BackboneWorkflows, ABadMeasuredBackboneRequestIsRefusedNamingTheField) {
  workflow::MeasureBackboneRequest request{.output = (out_ / "refused_measured").string()};
  EXPECT_THAT(InputErrorOf([&] { workflow::MeasureBackbone(request); }), AllOf(HasSubstr("--measured"), HasSubstr("Fix:")));
  request.inputs = kTables;
  request.position_m = std::nan("");
  EXPECT_THAT(InputErrorOf([&] { request.Validate(); }), HasSubstr("--position-m"));
  request.position_m = -1.0;  // not given
  request.output = kTables[1];
  EXPECT_THAT(InputErrorOf([&] { request.Validate(); }), AllOf(HasSubstr("-o"), HasSubstr("input")));
  EXPECT_FALSE(fs::exists(out_ / "refused_measured.json"));
}

TEST_F(BackboneWorkflows, ResponseCurvesAreTracedPerLevelWrittenAndReturned) {
  const workflow::FrcRequest request{.model_file = "examples/paper_setup/model.json",
                                     .force_levels_N = {0.5, 2.0},
                                     .from_hz = 50.0,
                                     .to_hz = 58.0,
                                     .harmonics = 3,
                                     .max_points = 400,
                                     .output = (out_ / "frc").string()};
  std::vector<std::string> tasks;
  std::vector<double> levels_told;
  const workflow::FrcOutcome outcome = workflow::TraceResponseCurves(
      request, {.begin = [&](const std::string& task) { tasks.push_back(task); }},
      [&](const workflow::FrcLevelSummary& level) { levels_told.push_back(level.force_N); });
  EXPECT_EQ(tasks, (std::vector<std::string>{"frc: level 1/2 (0.5 N)", "frc: level 2/2 (2 N)"}));
  EXPECT_EQ(levels_told, (std::vector<double>{0.5, 2.0}));
  ASSERT_TRUE(outcome.Incomplete().empty()) << outcome.Incomplete();
  ASSERT_EQ(outcome.levels.size(), 2u);
  ASSERT_EQ(outcome.file.curves.size(), 2u);
  for (std::size_t l = 0; l < 2; ++l) {
    EXPECT_EQ(outcome.levels[l].num_points, outcome.file.curves[l].points.size());
    EXPECT_TRUE(outcome.levels[l].complete);
    // The peak lies inside the band.
    EXPECT_GT(outcome.levels[l].peak_frequency_hz, 50.0);
    EXPECT_LT(outcome.levels[l].peak_frequency_hz, 58.0);
  }
  // Four times the force: a larger peak, and on the stiffening support a higher one.
  EXPECT_GT(outcome.levels[1].peak_theta_rad, outcome.levels[0].peak_theta_rad);
  EXPECT_GT(outcome.levels[1].peak_frequency_hz, outcome.levels[0].peak_frequency_hz);
  EXPECT_EQ(ReadFile(request.output + ".json"), beamid::hb::FrcFileToJson(outcome.file));
  EXPECT_EQ(ReadFile(request.output + ".csv"), beamid::hb::FrcFileToCsv(outcome.file));

  // A curve cut at 5 points is written and told, not thrown.
  workflow::FrcRequest cut = request;
  cut.force_levels_N = {1.0};
  cut.max_points = 5;
  cut.output = (out_ / "frc_cut").string();
  const workflow::FrcOutcome stopped = workflow::TraceResponseCurves(cut);
  EXPECT_THAT(stopped.Incomplete(), HasSubstr("the curve at 1 N stopped early"));
  EXPECT_TRUE(fs::exists(cut.output + ".json"));

  workflow::FrcRequest refused = request;
  refused.force_levels_N = {0.5, -1.0};
  EXPECT_THAT(InputErrorOf([&] { refused.Validate(); }), AllOf(HasSubstr("--force-N"), HasSubstr("must be")));
  refused = request;
  refused.max_points = 1;
  EXPECT_THAT(InputErrorOf([&] { refused.Validate(); }), AllOf(HasSubstr("--max-points"), HasSubstr("must be")));
}

}  // namespace
