#include "solver/report/html_screenshot.h"

#include "hb/errors.h"

#include <cstdlib>
#include <stdexcept>
#include <string_view>

#include <fmt/core.h>

namespace beamid::solver {

namespace fs = std::filesystem;

std::optional<fs::path> FindChromium() {
  const char* path = std::getenv("PATH");
  if (!path) return std::nullopt;
  for (const char* name : {"chromium", "chromium-browser"}) {
    std::string_view rest = path;
    while (!rest.empty()) {
      const std::size_t colon = rest.find(':');
      const fs::path candidate = fs::path(std::string(rest.substr(0, colon))) / name;
      std::error_code error;
      if (fs::is_regular_file(candidate, error)) return candidate;
      rest.remove_prefix(colon == std::string_view::npos ? rest.size() : colon + 1);
    }
  }
  return std::nullopt;
}

void ScreenshotHtml(const fs::path& html_file, const fs::path& png_file, const ScreenshotOptions& options) {
  const auto chromium = FindChromium();
  if (!chromium)
    throw EnvironmentError("no Chromium for the screenshot: install the Debian package chromium "
                             "(scripts/install-deps.sh)");
  std::error_code error;
  if (png_file.has_parent_path()) fs::create_directories(png_file.parent_path(), error);
  // The target is not removed first (the command has refused any target
  // that is one of its inputs, but a file must not vanish before Chromium
  // writes): a screenshot is recognised by its new modification time. A
  // character device (/dev/null) is written in place and not inspected.
  const bool device = fs::is_character_file(png_file, error);
  const auto before = fs::last_write_time(png_file, error);
  const bool existed = !error;
  // --no-sandbox: Chromium refuses to run as root (CI containers) without it.
  const std::string command = fmt::format(
      "'{}' --headless --no-sandbox --disable-gpu --hide-scrollbars --no-first-run --mute-audio "
      "--window-size={},{} --screenshot='{}' 'file://{}' > /dev/null 2>&1",
      chromium->string(), options.width_px, options.height_px, fs::absolute(png_file).string(),
      fs::absolute(html_file).string());
  const int status = std::system(command.c_str());
  const bool written = device || (fs::is_regular_file(png_file, error) && fs::file_size(png_file, error) > 0 &&
                                  (!existed || fs::last_write_time(png_file, error) != before));
  if (status != 0 || !written)
    throw EnvironmentError(fmt::format("Chromium wrote no screenshot {} (exit status {})", png_file.string(), status));
}

}  // namespace beamid::solver
