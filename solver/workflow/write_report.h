// The report use case: one self-contained HTML page (inline SVG plots by
// gnuplot) of an identification result or a diagnosis, with its campaign's
// recordings (extracted again as identify did) and the model's curves; or of
// a measured backbone on its own (the .json of `beamid backbone --measured`);
// and, when asked, its screenshot. The page and the screenshot are two
// steps, so that the caller can say the page is written before the
// screenshot is taken (a missing Chromium fails only the second).
#pragma once

#include <cstddef>
#include <string>

#include "solver/workflow/run_observer.h"

namespace beamid::workflow {

struct ReportRequest {
  std::string input_file;       // result.json, diagnosis.json, or a measured backbone's .json
  std::string campaign_folder;  // "": the one the result names (none for a measured backbone)
  std::string output = "report.html";
  std::string screenshot;  // PNG of the page ("": none)
  std::string figures_folder;  // each plot as <id>.svg and <id>.png there ("": none)
  bool log_amplitude = false;  // |X1| on a logarithmic axis too (HtmlReportOptions)

  // Throws InputError naming the field (by its command-line option) and the
  // fix: an output that would replace an input (solver/workflow/
  // output_paths.h). What the input names (its result file and campaign) is
  // checked once the input is read, before any work.
  void Validate() const;
};

struct ReportOutcome {
  bool measured_backbone = false;  // the input was a measured backbone (no campaign, no model)
  std::size_t html_bytes = 0;
  std::size_t plots = 0;  // SVG plots on the page
  double seconds = 0.0;   // from the inputs read to the page written
  std::string output;
};

// Validates the request, reads the input (and the campaign), computes the
// curves and writes request.output; tasks told: "report: extract",
// "report: model curves", "report: plots" (only the last for a measured
// backbone). The screenshot is ScreenshotReport's.
ReportOutcome WriteReport(const ReportRequest& request, const RunObserver& observer = {});

// Writes each plot of the page request.output as request.figures_folder/
// <id>.svg and <id>.png (solver/report/figure_files.h; the task "report:
// figure files") and returns how many; 0 when no folder is asked for.
std::size_t WriteReportFigures(const ReportRequest& request, const RunObserver& observer = {});

// Renders request.output in headless Chromium to request.screenshot (the
// task "report: screenshot"); nothing when no screenshot is asked for.
void ScreenshotReport(const ReportRequest& request, const RunObserver& observer = {});

}  // namespace beamid::workflow
