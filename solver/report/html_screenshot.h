// A screenshot of an HTML file by headless Chromium (Debian package
// chromium), to check what a report shows: Chromium is run without a shell
// (solver/report/external_program.h), with --screenshot=<absolute PNG path>
// as one argument, the page as a percent-encoded file:// URL, no network
// services of its own and a fresh profile in a temporary folder, removed
// afterwards. Throws EnvironmentError when no Chromium is installed or it
// writes no image.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace beamid::solver {

struct ScreenshotOptions {
  int width_px = 1600;
  int height_px = 4200;  // the whole report at this width
  double timeout_s = 180.0;  // a browser that hangs is stopped
};

// The Chromium executable on PATH (chromium, chromium-browser), if any.
std::optional<std::filesystem::path> FindChromium();

// "file://" and the absolute, normalised path with every byte but
// A-Z a-z 0-9 - . _ ~ / percent-encoded (a ' " # ? % or space in a folder
// name stays part of the path).
std::string FileUrl(const std::filesystem::path& file);

void ScreenshotHtml(const std::filesystem::path& html_file, const std::filesystem::path& png_file,
                    const ScreenshotOptions& options = {});

}  // namespace beamid::solver
