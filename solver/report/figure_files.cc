#include "solver/report/figure_files.h"

#include <set>

#include <fmt/core.h>

#include "hb/errors.h"
#include "hb/file_stem.h"
#include "hb/text_file.h"
#include "solver/report/external_program.h"
#include "solver/report/temp_folder.h"

namespace beamid::solver {
namespace {

namespace fs = std::filesystem;

// The id as the page escaped it (solver/report/html_escape.h), back to its text.
std::string Unescaped(std::string text) {
  for (const auto& [reference, character] : {std::pair{"&lt;", "<"}, {"&gt;", ">"}, {"&quot;", "\""},
                                             {"&#39;", "'"}, {"&amp;", "&"}})
    for (std::size_t at = 0; (at = text.find(reference, at)) != std::string::npos; at += 1)
      text.replace(at, std::string(reference).size(), character);
  return text;
}

}  // namespace

std::vector<FigureFile> FiguresOfPage(const std::string& html) {
  static constexpr std::string_view kOpen = "<figure class=\"plot", kId = " id=\"";
  std::vector<FigureFile> figures;
  std::set<std::string> taken;
  for (std::size_t at = html.find(kOpen); at != std::string::npos; at = html.find(kOpen, at + 1)) {
    const std::size_t tag_end = html.find('>', at), id_at = html.find(kId, at);
    if (tag_end == std::string::npos || id_at == std::string::npos || id_at > tag_end) continue;
    const std::size_t id_start = id_at + kId.size(), id_end = html.find('"', id_start);
    const std::size_t figure_end = html.find("</figure>", at);
    const std::size_t svg_start = html.find("<svg", tag_end), svg_end = html.find("</svg>", svg_start);
    if (id_end > tag_end || svg_start > figure_end || svg_end == std::string::npos) continue;
    figures.push_back({hb::UniqueFileStem(Unescaped(html.substr(id_start, id_end - id_start)), "plot_", taken),
                       html.substr(svg_start, svg_end + 6 - svg_start)});
  }
  return figures;
}

void WriteFigureFiles(const std::vector<FigureFile>& figures, const fs::path& folder) {
  fs::create_directories(folder);
  const TempFolder scratch("figures");
  for (const FigureFile& figure : figures) {
    const std::string svg = "<?xml version=\"1.0\" encoding=\"utf-8\" standalone=\"no\"?>\n" + figure.svg + "\n";
    WriteTextFileAtomically(folder / (figure.name + ".svg"), svg);
    // rsvg-convert reads and writes files of ours only, in the scratch folder.
    const fs::path in = scratch.path() / "plot.svg", out = scratch.path() / "plot.png",
                   errors = scratch.path() / "rsvg.err";
    WriteTextFileAtomically(in, svg);
    const int status = RunExternalProgram({.program = "rsvg-convert",
                                           .arguments = {"--format=png", fmt::format("--zoom={}", kFigurePngZoom),
                                                         "--background-color=white", "--output=" + out.string(),
                                                         in.string()},
                                           .debian_package = "librsvg2-bin",
                                           .stderr_file = errors,
                                           .timeout_s = 60.0});
    if (status != 0 || !fs::exists(out))
      throw EnvironmentError(fmt::format("rsvg-convert could not draw {}.png (exit status {}): {}", figure.name, status,
                                         ReadWholeFile(errors).substr(0, 2000)));
    WriteTextFileAtomically(folder / (figure.name + ".png"), ReadWholeFile(out));
  }
}

}  // namespace beamid::solver
