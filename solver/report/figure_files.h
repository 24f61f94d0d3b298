// Each plot of a report page as files of its own, for slides and papers:
// <id>.svg (gnuplot's SVG as the page inlines it, with its XML prolog) and
// <id>.png (rendered from that SVG by rsvg-convert, Debian package
// librsvg2-bin, without a shell), <id> the figure's id on the page made a
// file name (letters, digits, '-', '_' and '.'; anything else '_'; a second
// figure of the same name gets "-2"). Both are written atomically into a
// folder the caller has checked (solver/workflow/output_paths.h): a file of
// that name is replaced, the file a link points to never.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace beamid::solver {

struct FigureFile {
  std::string name;  // the file stem
  std::string svg;
};

// The page's <figure class="plot" id="..."> elements with an inline <svg>, in page order.
std::vector<FigureFile> FiguresOfPage(const std::string& html);

// PNG pixels per SVG pixel: 2 for print and high-density screens.
constexpr double kFigurePngZoom = 2.0;

// Writes folder/<name>.svg and folder/<name>.png for each figure, creating
// the folder. Throws EnvironmentError when rsvg-convert is missing or fails.
void WriteFigureFiles(const std::vector<FigureFile>& figures, const std::filesystem::path& folder);

}  // namespace beamid::solver
