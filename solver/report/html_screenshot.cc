#include "solver/report/html_screenshot.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string_view>
#include <vector>

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

namespace {

// What Chromium said last, for an error message.
std::string LogTail(const fs::path& log) {
  const std::string message = ReadWholeFile(log);
  return message.substr(message.size() > 2000 ? message.size() - 2000 : 0);
}

fs::path RequireChromium() {
  const auto chromium = FindChromium();
  if (!chromium)
    throw EnvironmentError("no Chromium for the screenshot: install the Debian package chromium "
                           "(scripts/install-deps.sh)");
  return *chromium;
}

std::vector<std::string> ChromiumArguments(const TempFolder& profile, int width_px, int height_px) {
  return {"--headless",
          "--no-sandbox",  // Chromium refuses to run as root (CI containers) without it
          "--disable-gpu",
          "--hide-scrollbars",
          "--no-first-run",
          "--mute-audio",
          "--disable-background-networking",
          "--disable-component-update",
          "--disable-sync",
          "--user-data-dir=" + (profile.path() / "profile").string(),
          fmt::format("--window-size={},{}", width_px, height_px)};
}

// beamid's own probe: the layout's numbers as an attribute of <html>, which
// --dump-dom prints.
constexpr const char* kLayoutProbe = R"(<script>(function () {
  const e = document.documentElement;
  const sections = document.querySelectorAll('section');
  const last = sections.length ? sections[sections.length - 1].getBoundingClientRect().bottom + window.scrollY : 0;
  e.setAttribute('data-beamid-layout', [e.scrollWidth, e.clientWidth, e.scrollHeight, Math.ceil(last)].join(' '));
})();</script>)";

}  // namespace

PageLayout MeasurePage(const fs::path& html_file, int width_px, double timeout_s) {
  const fs::path chromium = RequireChromium();
  std::string page = ReadWholeFile(html_file);
  const std::size_t end = page.rfind("</body>");
  page.insert(end == std::string::npos ? page.size() : end, kLayoutProbe);
  const TempFolder folder("chromium");
  const fs::path probe = folder.path() / "probe.html";
  {
    std::ofstream out(probe, std::ios::binary);
    out << page;
    if (!out) throw EnvironmentError("cannot write the layout probe " + probe.string());
  }
  std::vector<std::string> arguments = ChromiumArguments(folder, width_px, 1000);
  arguments.push_back("--dump-dom");
  arguments.push_back(FileUrl(probe));
  const fs::path dom = folder.path() / "dom.html", log = folder.path() / "chromium.log";
  const int status = RunExternalProgram({.program = chromium.string(),
                                         .arguments = arguments,
                                         .debian_package = "chromium",
                                         .stdout_file = dom,
                                         .stderr_file = log,
                                         .timeout_s = timeout_s});
  const std::string text = ReadWholeFile(dom);
  const std::string key = "data-beamid-layout=\"";
  const std::size_t at = text.find(key);
  PageLayout layout;
  std::istringstream numbers(at == std::string::npos ? "" : text.substr(at + key.size(), 80));
  if (status != 0 ||
      !(numbers >> layout.scroll_width >> layout.client_width >> layout.scroll_height >> layout.last_section_bottom)) {
    throw EnvironmentError(
        fmt::format("Chromium did not lay out {} (exit status {}): {}", html_file.string(), status, LogTail(log)));
  }
  return layout;
}

void ScreenshotHtml(const fs::path& html_file, const fs::path& png_file, const ScreenshotOptions& options) {
  const fs::path chromium = RequireChromium();
  const int height_px = options.height_px > 0
                            ? options.height_px
                            : std::clamp(MeasurePage(html_file, options.width_px, options.timeout_s).scroll_height, 1,
                                         kMaxScreenshotHeightPx);
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
  std::vector<std::string> arguments = ChromiumArguments(profile, options.width_px, height_px);
  arguments.push_back("--screenshot=" + png.string());
  arguments.push_back(FileUrl(html_file));
  const int status = RunExternalProgram({
      .program = chromium.string(),
      .arguments = arguments,
      .debian_package = "chromium",
      .stderr_file = log,
      .timeout_s = options.timeout_s,
  });
  const bool written = device || (fs::is_regular_file(png, error) && fs::file_size(png, error) > 0 &&
                                  (!existed || fs::last_write_time(png, error) != before));
  if (status != 0 || !written) {
    throw EnvironmentError(fmt::format("Chromium wrote no screenshot {} (exit status {}): {}", png_file.string(),
                                       status, LogTail(log)));
  }
}

}  // namespace beamid::solver
