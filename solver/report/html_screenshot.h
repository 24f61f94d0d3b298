// A screenshot of an HTML file by headless Chromium (Debian package
// chromium), to check what a report shows: `chromium --headless
// --screenshot=PNG --window-size=W,H file://...`. Throws std::runtime_error
// when no Chromium is installed or it writes no image.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace beamid::solver {

struct ScreenshotOptions {
  int width_px = 1600;
  int height_px = 4200;  // the whole report at this width
};

// The Chromium executable on PATH (chromium, chromium-browser), if any.
std::optional<std::filesystem::path> FindChromium();

void ScreenshotHtml(const std::filesystem::path& html_file, const std::filesystem::path& png_file,
                    const ScreenshotOptions& options = {});

}  // namespace beamid::solver
