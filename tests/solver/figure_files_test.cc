// Each plot of a report as files of its own (solver/report/figure_files.h):
// found on the page by its figure's id, named safely whatever the id holds,
// written as the page's SVG and as a PNG whose size follows the SVG's.
#include "solver/report/figure_files.h"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "hb/errors.h"
#include "solver/workflow/measure_backbone.h"
#include "solver/workflow/write_report.h"
#include "tests/support/temp_path.h"

namespace beamid::solver {
namespace {

namespace fs = std::filesystem;

std::string Svg(int width, int height) {
  return "<svg viewBox=\"0 0 " + std::to_string(width) + " " + std::to_string(height) +
         "\" xmlns=\"http://www.w3.org/2000/svg\"><rect x=\"0\" y=\"0\" width=\"10\" height=\"10\"/></svg>";
}

TEST(FigureFiles, EachFigureWithAnIdIsFoundAndNamedSafely) {
  const std::string page =
      "<figure class=\"plot\" id=\"backbone-plot\">\n" + Svg(760, 420) + "\n<figcaption>a</figcaption>\n</figure>\n" +
      "<figure class=\"plot level-frf\" id=\"frf-../../etc/p&amp;q &quot;x&quot;\">\n" + Svg(760, 512) +
      "</figure>\n<figure class=\"plot\">" + Svg(1, 1) + "</figure>\n"  // no id: not a file
      "<figure class=\"plot\" id=\"backbone-plot\">" + Svg(2, 2) + "</figure>\n"
      "<figure class=\"plot\" id=\".hidden\"><figcaption>no plot</figcaption></figure>\n"
      "<figure class=\"plot\" id=\"-rf\">" + Svg(3, 3) + "</figure>\n";
  const std::vector<FigureFile> figures = FiguresOfPage(page);
  ASSERT_EQ(figures.size(), 4u);
  EXPECT_EQ(figures[0].name, "backbone-plot");
  EXPECT_EQ(figures[0].svg, Svg(760, 420));
  EXPECT_EQ(figures[1].name, "frf-.._.._etc_p_q__x_");
  EXPECT_EQ(figures[1].svg, Svg(760, 512));
  EXPECT_EQ(figures[2].name, "backbone-plot-2");  // a second figure of one name
  EXPECT_EQ(figures[2].svg, Svg(2, 2));
  EXPECT_EQ(figures[3].name, "plot_-rf");  // never read as an option
}

std::string Bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// A PNG's width and height from its IHDR chunk (big-endian, bytes 16..23).
std::pair<std::uint32_t, std::uint32_t> PngSize(const std::string& png) {
  const auto word = [&](std::size_t at) {
    std::uint32_t value = 0;
    for (std::size_t i = 0; i < 4; ++i) value = value << 8 | static_cast<unsigned char>(png[at + i]);
    return value;
  };
  return {word(16), word(20)};
}

// A measured backbone's page of the example tables, then its figures: one
// pair of files per plot of the page, the SVG the page's own, the PNG
// kFigurePngZoom times the SVG's size.
TEST(FigureFiles, AReportsPlotsBecomeSvgAndPngFilesOfTheirSize) {
  const fs::path root = beamid::testing::UniqueTempPath("beamid_figure_files");
  fs::remove_all(root);
  fs::create_directories(root);
  workflow::MeasureBackboneRequest measure;
  for (const char* level : {"low", "mid", "high"})
    measure.inputs.push_back(std::string("examples/phasor_tables/") + level + ".csv");
  measure.output = (root / "measured").string();
  workflow::MeasureBackbone(measure);
  const workflow::ReportRequest report{.input_file = (root / "measured.json").string(),
                                       .output = (root / "page.html").string(),
                                       .figures_folder = (root / "figures").string()};
  workflow::WriteReport(report);
  const std::string page = Bytes(root / "page.html");
  std::size_t plots = 0;
  for (std::size_t at = page.find("<figure class=\"plot"); at != std::string::npos;
       at = page.find("<figure class=\"plot", at + 1))
    ++plots;
  ASSERT_EQ(workflow::WriteReportFigures(report), plots);
  ASSERT_EQ(plots, 5u);  // three levels' responses, the backbone and the damping
  for (const char* name : {"frf-low", "frf-mid", "frf-high", "backbone-frequency", "backbone-damping"}) {
    SCOPED_TRACE(name);
    const std::string svg = Bytes(root / "figures" / (std::string(name) + ".svg"));
    ASSERT_EQ(svg.rfind("<?xml", 0), 0u);
    const std::string body = svg.substr(svg.find("<svg"), svg.rfind("</svg>") + 6 - svg.find("<svg"));
    EXPECT_NE(page.find(body), std::string::npos) << "the SVG is the page's";
    const std::size_t box = svg.find("viewBox=\"0 0 ") + 13;
    const int width = std::stoi(svg.substr(box)), height = std::stoi(svg.substr(svg.find(' ', box) + 1));
    const std::string png = Bytes(root / "figures" / (std::string(name) + ".png"));
    ASSERT_GT(png.size(), 24u);
    EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
    EXPECT_EQ(PngSize(png), std::make_pair(static_cast<std::uint32_t>(kFigurePngZoom * width),
                                           static_cast<std::uint32_t>(kFigurePngZoom * height)));
  }
  // The folder of the figures is an output: not one that holds an input, not a file.
  for (const fs::path& folder : {root, root / "page.html"}) {
    workflow::ReportRequest wrong = report;
    wrong.output = (root / "page2.html").string();
    wrong.figures_folder = folder.string();
    EXPECT_THROW(workflow::WriteReport(wrong), beamid::InputError) << folder;
  }
  fs::remove_all(root);
}

}  // namespace
}  // namespace beamid::solver
