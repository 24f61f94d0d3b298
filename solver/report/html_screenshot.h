// A screenshot of an HTML file by headless Chromium (Debian package
// chromium), to check what a report shows: Chromium is run without a shell
// (solver/report/external_program.h), with --screenshot=<absolute PNG path>
// as one argument, the page as a percent-encoded file:// URL, no network
// services of its own and a fresh profile in a temporary folder, removed
// afterwards. Throws EnvironmentError when no Chromium is installed or it
// writes no image.
//
// The whole page is captured: Chromium first lays out a copy of the page
// (in the temporary folder) with a short script of beamid's own that writes
// the page's size into the DOM it dumps (MeasurePage), and the screenshot's
// window is then that tall.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace beamid::solver {

struct ScreenshotOptions {
  int width_px = 1000;       // the page's text column is at most 1000 px wide
  int height_px = 0;         // 0: the page's own height at this width (MeasurePage)
  double timeout_s = 180.0;  // a browser that hangs is stopped
};

// The page as Chromium lays it out in a window `width_px` wide [CSS px]:
// the document's scroll width and client width (scroll_width > client_width:
// the page scrolls sideways), its full height, and the bottom edge of its
// last <section> (0 when it has none).
struct PageLayout {
  int scroll_width = 0, client_width = 0, scroll_height = 0, last_section_bottom = 0;
};
PageLayout MeasurePage(const std::filesystem::path& html_file, int width_px, double timeout_s = 180.0);

// Screenshots are at most this tall (a runaway page is cut, not rendered whole).
constexpr int kMaxScreenshotHeightPx = 30000;

// The Chromium executable on PATH (chromium, chromium-browser), if any.
std::optional<std::filesystem::path> FindChromium();

// "file://" and the absolute, normalised path with every byte but
// A-Z a-z 0-9 - . _ ~ / percent-encoded (a ' " # ? % or space in a folder
// name stays part of the path).
std::string FileUrl(const std::filesystem::path& file);

void ScreenshotHtml(const std::filesystem::path& html_file, const std::filesystem::path& png_file,
                    const ScreenshotOptions& options = {});

}  // namespace beamid::solver
