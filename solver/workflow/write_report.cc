#include "solver/workflow/write_report.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "hb/errors.h"
#include "hb/strict_json.h"
#include "hb/text_file.h"
#include "signal/campaign.h"
#include "signal/campaign_extractor.h"
#include "signal/campaign_identity.h"
#include "solver/backbone/measured_backbone_io.h"
#include "solver/report/figure_files.h"
#include "solver/report/html_report.h"
#include "solver/report/html_screenshot.h"
#include "solver/report/measured_backbone_report.h"
#include "solver/report/report_curves.h"
#include "solver/report/report_input.h"
#include "solver/workflow/campaign_input.h"
#include "solver/workflow/output_file.h"
#include "solver/workflow/output_paths.h"

namespace beamid::workflow {
namespace {

// Whether the input is the .json of `beamid backbone --measured` (its
// "format"), which needs no model and no campaign.
bool IsMeasuredBackboneFile(const std::string& path) {
  if (std::filesystem::path(path).extension() != ".json" || !std::filesystem::is_regular_file(path)) return false;
  const std::string text =
      ReadTextFile(path, "report input", "give a result.json, a diagnosis.json or a measured backbone .json");
  nlohmann::json json;
  try {
    json = ParseStrictJson<nlohmann::json>(text, path, "see docs/report.md");
  } catch (const InputError&) {
    return false;  // not one: the reader of a result or diagnosis names what is wrong
  }
  return json.is_object() && json.contains("format") && json["format"] == solver::kMeasuredBackboneFormat;
}

OutputPaths Paths(const ReportRequest& request) {
  OutputPaths paths;
  paths.Input(request.input_file).InputFolder(request.campaign_folder).Output("-o", request.output);
  if (!request.screenshot.empty()) paths.Output("--screenshot", request.screenshot);
  if (!request.figures_folder.empty()) paths.OutputFolder("--figures", request.figures_folder);
  return paths;
}

}  // namespace

void ReportRequest::Validate() const { Paths(*this).Check(); }

ReportOutcome WriteReport(const ReportRequest& request, const RunObserver& observer) {
  OutputPaths paths = Paths(request);
  paths.Check();
  const auto start = std::chrono::steady_clock::now();
  ReportOutcome out{.output = request.output};
  std::string html;
  if (IsMeasuredBackboneFile(request.input_file)) {
    if (!request.campaign_folder.empty())
      throw std::invalid_argument("report: " + request.input_file +
                                  " is a measured backbone, which needs no campaign: leave out --campaign");
    {
      ObservedTask progress(observer, "report: plots");
      html = solver::MeasuredBackboneHtmlReport(solver::ReadMeasuredBackboneFile(request.input_file),
                                                request.input_file);
    }
    WriteTextFile(request.output, html);
    out.measured_backbone = true;
  } else {
    const solver::ReportInput input = solver::LoadReportInput(
        request.input_file, request.campaign_folder.empty()
                                ? std::nullopt
                                : std::optional<std::filesystem::path>(request.campaign_folder));
    // What the input names (its result file, the campaign it was fitted on)
    // is read too: known only now, checked before any work.
    paths.Input(input.result_file).InputFolder(input.campaign_folder).Check();
    const signal::Campaign campaign = ReadCampaignAndWarn("report", input.campaign_folder, observer);
    // A --campaign of the same layout would put the result's curves over
    // another campaign's recordings.
    signal::RequireDerivedFrom({.file = input.result_file.string(),
                                .sha256 = input.result.campaign.sha256,
                                .name = input.result.campaign.name},
                               campaign,
                               request.campaign_folder.empty()
                                   ? "the campaign changed since it was identified: identify it again"
                                   : "give with --campaign the campaign the result was identified from (or leave "
                                     "--campaign out to use the one the result names)");
    signal::PhasorSet phasors;
    {
      // The phasors as `beamid identify` extracted them.
      ObservedTask progress(observer, "report: extract");
      signal::ExtractOptions extract;
      extract.estimator.num_harmonics = std::max(5, input.result.model.num_fit_harmonics);
      extract.progress = [&](std::size_t done, std::size_t total, const signal::StepPhasors&) {
        progress.Update(static_cast<double>(done) / total);
      };
      phasors = signal::ExtractCampaign(campaign, extract);
    }
    solver::ReportCurves curves;
    {
      ObservedTask progress(observer, "report: model curves");
      curves = solver::ComputeReportCurves(
          input.result, campaign, phasors, {},
          [&](double fraction, const std::string& what) { progress.Update(fraction, what); });
    }
    {
      ObservedTask progress(observer, "report: plots");
      html = solver::HtmlReport(input, curves, {.log_amplitude = request.log_amplitude});
    }
    WriteTextFile(request.output, html);
    for (std::size_t at = html.find("<svg"); at != std::string::npos; at = html.find("<svg", at + 1)) ++out.plots;
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.html_bytes = html.size();
  return out;
}

std::size_t WriteReportFigures(const ReportRequest& request, const RunObserver& observer) {
  if (request.figures_folder.empty()) return 0;
  ObservedTask progress(observer, "report: figure files");
  const std::vector<solver::FigureFile> figures =
      solver::FiguresOfPage(ReadTextFile(request.output, "report page", "write the page first"));
  solver::WriteFigureFiles(figures, request.figures_folder);
  return figures.size();
}

void ScreenshotReport(const ReportRequest& request, const RunObserver& observer) {
  if (request.screenshot.empty()) return;
  ObservedTask progress(observer, "report: screenshot");
  solver::ScreenshotHtml(request.output, request.screenshot);
}

}  // namespace beamid::workflow
