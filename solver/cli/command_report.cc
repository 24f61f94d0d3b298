// beamid report: one self-contained HTML page (inline SVG plots by gnuplot)
// of an identification result or a diagnosis: parameters with intervals,
// frequency response curves, backbone, prediction at the held-out sensor,
// residual map, diagnosis summary.
#include <algorithm>
#include <chrono>

#include <fmt/core.h>

#include "signal/campaign.h"
#include "signal/campaign_extractor.h"
#include "solver/cli/cli_output.h"
#include "solver/cli/command_registry.h"
#include "solver/report/html_report.h"
#include "solver/report/html_screenshot.h"
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

void RunReport(const ReportOptions& options, const GlobalOptions& global) {
  RequireWritableOutput(options.output, {options.input_file});
  if (!options.screenshot.empty()) RequireWritableOutput(options.screenshot, {options.input_file, options.output});
  const auto start = std::chrono::steady_clock::now();
  const solver::ReportInput input = solver::LoadReportInput(
      options.input_file,
      options.campaign_folder.empty() ? std::nullopt : std::optional<std::filesystem::path>(options.campaign_folder));
  const signal::Campaign campaign = signal::ReadCampaign(input.campaign_folder);
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
  WriteTextFile(options.output, html);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!global.quiet) {
    std::size_t plots = 0;
    for (std::size_t at = html.find("<svg"); at != std::string::npos; at = html.find("<svg", at + 1)) ++plots;
    fmt::print("wrote {} ({:.0f} kB, {} plots) in {:.1f} s\n", options.output, html.size() / 1e3, plots, seconds);
  }
  if (!options.screenshot.empty()) {
    Progress progress("report: screenshot", global);
    solver::ScreenshotHtml(options.output, options.screenshot);
    progress.Done();
    // The path is printed even with --quiet: it was asked for.
    fmt::print("screenshot: {}\n", options.screenshot);
  }
}

BEAMID_REGISTER_COMMAND("report", [](CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<ReportOptions>();
  CLI::App* sub = app.add_subcommand(
      "report",
      "Write one self-contained HTML page of a result or diagnosis: parameters with intervals, frequency\n"
      "response curves, backbone, prediction at the held-out sensor, residual map (plots by gnuplot).\n"
      "Example: beamid report result.json -o report.html --screenshot report.png");
  sub->add_option("input", options->input_file, "result.json of 'beamid identify' or diagnosis.json of 'beamid diagnose'")
      ->required();
  sub->add_option("--campaign", options->campaign_folder,
                  "Campaign folder (default: the one recorded in result.json)");
  sub->add_option("-o,--output", options->output, "HTML file to write")->capture_default_str();
  sub->add_option("--screenshot", options->screenshot,
                  "Also render the page in headless Chromium to this PNG and print its path");
  sub->callback([options, &global] { RunReport(*options, global); });
});

}  // namespace
}  // namespace beamid::cli
