// beamid report: one self-contained HTML page (inline SVG plots by gnuplot)
// of an identification result or a diagnosis: parameters with intervals,
// frequency response curves, backbone, prediction at the held-out sensor,
// residual map, diagnosis summary; or of a measured backbone on its own
// (the .json of `beamid backbone --measured`: levels, flags, fit, trend).
// The work is workflow::WriteReport and workflow::ScreenshotReport; this
// prints what they wrote.
#include <string>

#include <fmt/core.h>

#include "solver/cli/cli_output.h"
#include "solver/cli/command_registry.h"
#include "solver/workflow/write_report.h"

namespace beamid::cli {
namespace {

void RunReport(const workflow::ReportRequest& request, const GlobalOptions& global) {
  const workflow::RunObserver observer = CliObserver(global);
  const workflow::ReportOutcome outcome = workflow::WriteReport(request, observer);
  if (!global.quiet) {
    if (outcome.measured_backbone)
      fmt::print("wrote {} ({:.0f} kB, measured backbone)\n", request.output, outcome.html_bytes / 1e3);
    else
      fmt::print("wrote {} ({:.0f} kB, {} plots) in {:.1f} s\n", request.output, outcome.html_bytes / 1e3,
                 outcome.plots, outcome.seconds);
  }
  if (const std::size_t figures = workflow::WriteReportFigures(request, observer))
    fmt::print("figures: {} plots in {}, each as .svg and .png\n", figures, request.figures_folder);
  if (request.screenshot.empty()) return;
  workflow::ScreenshotReport(request, observer);
  // The path is printed even with --quiet: it was asked for.
  fmt::print("screenshot: {}\n", request.screenshot);
}

BEAMID_REGISTER_COMMAND("report", [](CLI::App& app, const GlobalOptions& global) {
  auto request = std::make_shared<workflow::ReportRequest>();
  CLI::App* sub = app.add_subcommand(
      "report",
      "Write one self-contained HTML page of a result or diagnosis: parameters with intervals, frequency\n"
      "response curves, backbone, prediction at the held-out sensor, residual map (plots by gnuplot).\n"
      "Example: beamid report result.json -o report.html --screenshot report.png --figures figures\n"
      "Example: beamid report out/measured.json -o measured.html   (a measured backbone on its own)");
  sub->add_option("input", request->input_file,
                  "result.json of 'beamid identify', diagnosis.json of 'beamid diagnose', or the .json of "
                  "'beamid backbone --measured' (rendered on its own: levels, flags, fit, damping trend)")
      ->required();
  sub->add_option("--campaign", request->campaign_folder,
                  "Campaign folder (default: the one recorded in result.json)")
      ->check(NonEmptyPath());
  sub->add_option("-o,--output", request->output, "HTML file to write")->capture_default_str();
  sub->add_flag("--log-amplitude", request->log_amplitude,
                "Draw the first-harmonic amplitude |X1| on a logarithmic axis too (|X1|/|F1| and harmonics 2, 3 "
                "always are)");
  sub->add_option("--screenshot", request->screenshot,
                  "Also render the page in headless Chromium to this PNG and print its path")
      ->check(NonEmptyPath());
  sub->add_option("--figures", request->figures_folder,
                  "Also write each plot of the page into this folder as <id>.svg and <id>.png (rsvg-convert), "
                  "for slides and papers")
      ->check(NonEmptyPath());
  sub->callback([request, &global] { RunReport(*request, global); });
});

}  // namespace
}  // namespace beamid::cli
