#include "solver/report/html_screenshot.h"

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string_view>

#include <fmt/core.h>

#include "hb/errors.h"
#include "solver/report/external_program.h"
#include "solver/report/temp_folder.h"

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

std::string FileUrl(const fs::path& file) {
  std::string url = "file://";
  for (const char c : fs::absolute(file).lexically_normal().string()) {
    const auto byte = static_cast<unsigned char>(c);
    const bool plain = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' ||
                       c == '.' || c == '_' || c == '~' || c == '/';
    url += plain ? std::string(1, c) : fmt::format("%{:02X}", byte);
  }
  return url;
}

void ScreenshotHtml(const fs::path& html_file, const fs::path& png_file, const ScreenshotOptions& options) {
  const auto chromium = FindChromium();
  if (!chromium)
    throw EnvironmentError("no Chromium for the screenshot: install the Debian package chromium "
                           "(scripts/install-deps.sh)");
  std::error_code error;
  const fs::path png = fs::absolute(png_file).lexically_normal();
  if (png.has_parent_path()) fs::create_directories(png.parent_path(), error);
  // The target is not removed first (the command has refused any target
  // that is one of its inputs, but a file must not vanish before Chromium
  // writes): a screenshot is recognised by its new modification time. A
  // character device (/dev/null) is written in place and not inspected.
  const bool device = fs::is_character_file(png, error);
  const auto before = fs::last_write_time(png, error);
  const bool existed = !error;
  const TempFolder profile("chromium");
  const fs::path log = profile.path() / "chromium.log";
  const int status = RunExternalProgram({
      .program = chromium->string(),
      .arguments = {"--headless", "--no-sandbox",  // Chromium refuses to run as root (CI containers) without it
                    "--disable-gpu", "--hide-scrollbars", "--no-first-run", "--mute-audio",
                    "--disable-background-networking", "--disable-component-update", "--disable-sync",
                    "--user-data-dir=" + (profile.path() / "profile").string(),
                    fmt::format("--window-size={},{}", options.width_px, options.height_px),
                    "--screenshot=" + png.string(), FileUrl(html_file)},
      .debian_package = "chromium",
      .stderr_file = log,
      .timeout_s = options.timeout_s,
  });
  const bool written = device || (fs::is_regular_file(png, error) && fs::file_size(png, error) > 0 &&
                                  (!existed || fs::last_write_time(png, error) != before));
  if (status != 0 || !written) {
    std::ifstream in(log);
    std::ostringstream text;
    text << in.rdbuf();
    const std::string message = text.str();
    throw EnvironmentError(fmt::format("Chromium wrote no screenshot {} (exit status {}): {}", png_file.string(),
                                       status, message.substr(message.size() > 2000 ? message.size() - 2000 : 0)));
  }
}

}  // namespace beamid::solver
