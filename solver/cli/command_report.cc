// beamid report: one self-contained HTML page (inline SVG plots by gnuplot)
// of an identification result or a diagnosis: parameters with intervals,
// frequency response curves, backbone, prediction at the held-out sensor,
// residual map, diagnosis summary; or of a measured backbone on its own
// (the .json of `beamid backbone --measured`: levels, flags, fit, trend).
#include <algorithm>
#include <chrono>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "hb/errors.h"
#include "hb/strict_json.h"
#include "hb/text_file.h"
#include "signal/campaign.h"
#include "signal/campaign_extractor.h"
#include "signal/campaign_identity.h"
#include "solver/cli/cli_output.h"
#include "solver/workflow/output_file.h"
#include "solver/cli/command_registry.h"
#include "solver/workflow/output_paths.h"
#include "solver/report/html_report.h"
#include "solver/report/html_screenshot.h"
#include "solver/report/measured_backbone_report.h"
#include "solver/report/report_curves.h"
#include "solver/report/report_input.h"

namespace beamid::cli {
namespace {

struct ReportOptions {
  std::string input_file;
  std::string campaign_folder;
  std::string output = "report.html";
  std::string screenshot;
};

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

void Screenshot(const ReportOptions& options, const GlobalOptions& global) {
  if (options.screenshot.empty()) return;
  Progress progress("report: screenshot", global);
  solver::ScreenshotHtml(options.output, options.screenshot);
  progress.Done();
  // The path is printed even with --quiet: it was asked for.
  fmt::print("screenshot: {}\n", options.screenshot);
}

void RunReport(const ReportOptions& options, const GlobalOptions& global) {
  workflow::OutputPaths paths;
  paths.Input(options.input_file).InputFolder(options.campaign_folder).Output("-o", options.output);
  if (!options.screenshot.empty()) paths.Output("--screenshot", options.screenshot);
  paths.Check();
  const auto start = std::chrono::steady_clock::now();
  if (IsMeasuredBackboneFile(options.input_file)) {
    if (!options.campaign_folder.empty())
      throw std::invalid_argument("report: " + options.input_file +
                                  " is a measured backbone, which needs no campaign: leave out --campaign");
    std::string html;
    {
      Progress progress("report: plots", global);
      html = solver::MeasuredBackboneHtmlReport(solver::ReadMeasuredBackboneFile(options.input_file), options.input_file);
    }
    workflow::WriteTextFile(options.output, html);
    if (!global.quiet)
      fmt::print("wrote {} ({:.0f} kB, measured backbone)\n", options.output, html.size() / 1e3);
    Screenshot(options, global);
    return;
  }
  const solver::ReportInput input = solver::LoadReportInput(
      options.input_file,
      options.campaign_folder.empty() ? std::nullopt : std::optional<std::filesystem::path>(options.campaign_folder));
  // What the input names (its result file, the campaign it was fitted on)
  // is read too: known only now, checked before any work.
  paths.Input(input.result_file).InputFolder(input.campaign_folder).Check();
  const signal::Campaign campaign = ReadCampaignAndWarn("report", input.campaign_folder, global);
  // A --campaign of the same layout would put the result's curves over
  // another campaign's recordings.
  signal::RequireDerivedFrom({.file = input.result_file.string(),
                              .sha256 = input.result.campaign.sha256,
                              .name = input.result.campaign.name},
                             campaign,
                             options.campaign_folder.empty()
                                 ? "the campaign changed since it was identified: identify it again"
                                 : "give with --campaign the campaign the result was identified from (or leave "
                                   "--campaign out to use the one the result names)");
  signal::PhasorSet phasors;
  {
    // The phasors as `beamid identify` extracted them.
    Progress progress("report: extract", global);
    signal::ExtractOptions extract;
    extract.estimator.num_harmonics = std::max(5, input.result.model.num_fit_harmonics);
    extract.progress = [&](std::size_t done, std::size_t total, const signal::StepPhasors&) {
      progress.Update(static_cast<double>(done) / total);
    };
    phasors = signal::ExtractCampaign(campaign, extract);
  }
  solver::ReportCurves curves;
  {
    Progress progress("report: model curves", global);
    curves = solver::ComputeReportCurves(input.result, campaign, phasors, {},
                                         [&](double fraction, const std::string& what) { progress.Update(fraction, what); });
  }
  std::string html;
  {
    Progress progress("report: plots", global);
    html = solver::HtmlReport(input, curves);
  }
  workflow::WriteTextFile(options.output, html);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!global.quiet) {
    std::size_t plots = 0;
    for (std::size_t at = html.find("<svg"); at != std::string::npos; at = html.find("<svg", at + 1)) ++plots;
    fmt::print("wrote {} ({:.0f} kB, {} plots) in {:.1f} s\n", options.output, html.size() / 1e3, plots, seconds);
  }
  Screenshot(options, global);
}

BEAMID_REGISTER_COMMAND("report", [](CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<ReportOptions>();
  CLI::App* sub = app.add_subcommand(
      "report",
      "Write one self-contained HTML page of a result or diagnosis: parameters with intervals, frequency\n"
      "response curves, backbone, prediction at the held-out sensor, residual map (plots by gnuplot).\n"
      "Example: beamid report result.json -o report.html --screenshot report.png\n"
      "Example: beamid report out/measured.json -o measured.html   (a measured backbone on its own)");
  sub->add_option("input", options->input_file,
                  "result.json of 'beamid identify', diagnosis.json of 'beamid diagnose', or the .json of "
                  "'beamid backbone --measured' (rendered on its own: levels, flags, fit, damping trend)")
      ->required();
  sub->add_option("--campaign", options->campaign_folder,
                  "Campaign folder (default: the one recorded in result.json)")
      ->check(NonEmptyPath());
  sub->add_option("-o,--output", options->output, "HTML file to write")->capture_default_str();
  sub->add_option("--screenshot", options->screenshot,
                  "Also render the page in headless Chromium to this PNG and print its path")
      ->check(NonEmptyPath());
  sub->callback([options, &global] { RunReport(*options, global); });
});

}  // namespace
}  // namespace beamid::cli
