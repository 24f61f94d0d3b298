// The report's plots read at a glance: in every SVG gnuplot draws for the
// page, no legend entry (its sample and its text) lies over a data point or
// a curve vertex, or inside any panel's plotting area; the response figure
// of each channel has its amplitude, |X/F| and phase panels and the
// harmonics figure where harmonics 2 and 3 are held; and the residual map's
// colour scale is centred at one standard uncertainty — a cell at 1 σ is
// the neutral colour whatever the largest residual, below it blue, above red.
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
// GCC 12 reports a false -Wmaybe-uninitialized inside std::regex's compiler
// when built with the sanitizers (GCC PR 105562).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <regex>
#pragma GCC diagnostic pop
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "solver/report/html_report.h"
#include "tests/support/sample_report.h"

namespace beamid::solver {
namespace {

using ::testing::HasSubstr;

struct Point {
  double x = 0, y = 0;
};
struct Box {
  double left = 1e300, top = 1e300, right = -1e300, bottom = -1e300;
  bool Empty() const { return right < left; }
  void Add(double x, double y) {
    left = std::min(left, x), right = std::max(right, x), top = std::min(top, y), bottom = std::max(bottom, y);
  }
  bool Contains(const Point& p) const { return p.x >= left && p.x <= right && p.y >= top && p.y <= bottom; }
  bool Intersects(const Box& b) const { return left < b.right && b.left < right && top < b.bottom && b.top < bottom; }
};

// The <g id="gnuplot_plot_…"> elements of one SVG: gnuplot draws each plot
// item in one, titled by the item's legend text (or by its own id when the
// item has no legend entry).
struct PlotGroup {
  std::string title;
  std::string body;
  bool Keyed() const { return title.rfind("gnuplot_plot_", 0) != 0; }
};

std::vector<PlotGroup> PlotGroups(const std::string& svg, std::string* outside) {
  std::vector<PlotGroup> groups;
  const std::string open = "<g id=\"gnuplot_plot_";
  std::size_t at = 0, copied = 0;
  while ((at = svg.find(open, at)) != std::string::npos) {
    *outside += svg.substr(copied, at - copied);
    // The group's end: its matching </g>.
    int depth = 1;  // inside the group's own <g>
    std::size_t end = at;
    do {
      const std::size_t next_open = svg.find("<g", end + 1), next_close = svg.find("</g>", end + 1);
      if (next_close == std::string::npos) break;
      if (next_open != std::string::npos && next_open < next_close) {
        ++depth;
        end = next_open;
      } else {
        --depth;
        end = next_close;
      }
    } while (depth > 0);
    const std::size_t title_at = svg.find("<title>", at) + 7;
    groups.push_back({svg.substr(title_at, svg.find("</title>", title_at) - title_at), svg.substr(at, end + 4 - at)});
    at = copied = end + 4;
  }
  *outside += svg.substr(copied);
  return groups;
}

// The "x,y" pairs of a path's d or a polygon's points (letters between them
// are the path's commands).
void AddPairs(const std::string& coordinates, std::vector<Point>& points) {
  const char* at = coordinates.c_str();
  const char* end = at + coordinates.size();
  while (at < end) {
    if (!(std::isdigit(static_cast<unsigned char>(*at)) || *at == '-' || *at == '.')) {
      ++at;
      continue;
    }
    char* after = nullptr;
    const double x = std::strtod(at, &after);
    if (after >= end || *after != ',') {  // a lone number (a path's h or v length): not a vertex
      at = after;
      continue;
    }
    const double y = std::strtod(after + 1, &after);
    points.push_back({x, y});
    at = after;
  }
}

// The text of every attribute `name='...'` in `body` (written without a
// regular expression: a path of a long curve is thousands of characters).
std::vector<std::string> Attributes(const std::string& body, const std::string& name) {
  std::vector<std::string> values;
  const std::string open = name + "'";
  for (std::size_t at = body.find(open); at != std::string::npos; at = body.find(open, at + 1)) {
    const std::size_t start = at + open.size(), stop = body.find('\'', start);
    values.push_back(body.substr(start, stop - start));
  }
  return values;
}

// Every vertex a group draws: path and polygon coordinates and point markers.
std::vector<Point> Vertices(const std::string& body) {
  std::vector<Point> points;
  for (const auto& d : Attributes(body, " d=")) AddPairs(d, points);
  for (const auto& p : Attributes(body, "points = ")) AddPairs(p, points);
  for (const auto& t : Attributes(body, "transform=")) {  // <use xlink:href='#gpPt..' transform='translate(x,y) ..'
    if (t.rfind("translate(", 0) != 0) continue;
    AddPairs(t.substr(10, t.find(')') - 10), points);
  }
  return points;
}

// A legend entry's text: anchored at translate(x, y) (baseline), drawn to the
// left of x (text-anchor end) or right of it; a generous 7.5 px a character.
void AddTexts(const std::string& body, Box& box) {
  static const std::regex text(
      R"re(<g transform="translate\(([-\d.]+),([-\d.]+)\)"[^>]*text-anchor="(\w+)">\s*<text><tspan[^>]*>([^<]*)</tspan>)re");
  for (std::sregex_iterator m(body.begin(), body.end(), text), end; m != end; ++m) {
    const double x = std::stod((*m)[1]), y = std::stod((*m)[2]);
    const double width = 7.5 * static_cast<double>((*m)[4].length());
    const std::string anchor = (*m)[3];
    const double left = anchor == "end" ? x - width : anchor == "middle" ? x - width / 2 : x;
    box.Add(left, y - 12);
    box.Add(left + width, y + 4);
  }
}

// The plotting areas: the closed axis-aligned rectangles gnuplot draws as
// each panel's border (outside the plot groups).
std::vector<Box> Borders(const std::string& outside) {
  std::vector<Box> borders;
  static const std::regex rectangle(
      R"re(d='M([-\d.]+),([-\d.]+) L([-\d.]+),([-\d.]+) L([-\d.]+),([-\d.]+) L([-\d.]+),([-\d.]+) L([-\d.]+),([-\d.]+) Z)re");
  for (std::sregex_iterator m(outside.begin(), outside.end(), rectangle), end; m != end; ++m) {
    Box b;
    for (int i = 1; i <= 10; i += 2) b.Add(std::stod((*m)[i]), std::stod((*m)[i + 1]));
    const bool drawn = std::any_of(borders.begin(), borders.end(), [&](const Box& o) {  // gnuplot draws each twice
      return std::abs(o.left - b.left) < 0.01 && std::abs(o.top - b.top) < 0.01 && std::abs(o.right - b.right) < 0.01 &&
             std::abs(o.bottom - b.bottom) < 0.01;
    });
    if (!drawn && b.right - b.left > 50 && b.bottom - b.top > 50) borders.push_back(b);
  }
  return borders;
}

std::vector<std::pair<std::string, std::string>> Figures(const std::string& page) {
  std::vector<std::pair<std::string, std::string>> figures;
  static const std::regex figure(R"re(<figure class="plot" id="([^"]*)">)re");
  for (std::sregex_iterator m(page.begin(), page.end(), figure), end; m != end; ++m) {
    const std::size_t start = page.find("<svg", m->position());
    figures.push_back({(*m)[1], page.substr(start, page.find("</svg>", start) + 6 - start)});
  }
  return figures;
}

TEST(HtmlReportPlots, NoLegendEntryLiesOverADataPointOrInsideAPlottingArea) {
  const std::string page = HtmlReport(testing::SampleReportInput(), testing::SampleReportCurves());
  const auto figures = Figures(page);
  std::vector<std::string> ids;
  for (const auto& [id, svg] : figures) {
    ids.push_back(id);
    std::string outside;
    const std::vector<PlotGroup> groups = PlotGroups(svg, &outside);
    Box key;
    std::vector<Point> data;
    int entries = 0;
    for (const auto& g : groups) {
      if (g.Keyed()) {
        ++entries;
        for (const auto& p : Vertices(g.body)) key.Add(p.x, p.y);
        AddTexts(g.body, key);
      } else {
        const auto v = Vertices(g.body);
        data.insert(data.end(), v.begin(), v.end());
      }
    }
    const std::vector<Box> borders = Borders(outside);
    ASSERT_FALSE(borders.empty()) << id;
    EXPECT_GT(data.size(), 10u) << id << ": the test found no data to check";
    if (id == "residual-map") {
      EXPECT_EQ(entries, 0) << "the residual map has a colour box, no legend";
      continue;
    }
    ASSERT_GT(entries, 0) << id;
    ASSERT_FALSE(key.Empty()) << id;
    for (const auto& b : borders)
      EXPECT_FALSE(key.Intersects(b)) << id << ": the legend [" << key.left << ", " << key.top << ", " << key.right
                                      << ", " << key.bottom << "] overlaps a plotting area [" << b.left << ", " << b.top
                                      << ", " << b.right << ", " << b.bottom << "]";
    int covered = 0;
    for (const auto& p : data) covered += key.Contains(p) ? 1 : 0;
    EXPECT_EQ(covered, 0) << id << ": data vertices under the legend";
    // And the legend's samples lie on the canvas (a column too many would run off its right edge).
    const double width = std::stod(svg.substr(svg.find("viewBox=\"0 0 ") + 13));
    for (const auto& g : groups) {
      if (!g.Keyed()) continue;
      for (const auto& p : Vertices(g.body)) EXPECT_LE(p.x, width) << id << ": legend " << g.title;
    }
  }
  EXPECT_THAT(ids, ::testing::ElementsAre("frc-acc1", "harmonics-acc1", "frc-acc3", "harmonics-acc3", "backbone-plot",
                                          "damping-plot", "time-high", "residual-map"));
}

TEST(HtmlReportPlots, EachChannelsResponseHasAmplitudePerForceAndPhasePanelsOnOneAxis) {
  const std::string page = HtmlReport(testing::SampleReportInput(), testing::SampleReportCurves());
  for (const auto& [id, svg] : Figures(page)) {
    std::string outside;
    PlotGroups(svg, &outside);
    const std::vector<Box> borders = Borders(outside);
    if (id.rfind("frc-", 0) == 0) {
      EXPECT_THAT(svg, HasSubstr("|X₁| [m/s²]"));
      EXPECT_THAT(svg, HasSubstr("|X₁|/|F₁| [m/s²/N]"));
      EXPECT_THAT(svg, HasSubstr("phase [°]"));
      ASSERT_EQ(borders.size(), 3u) << id;
      for (const auto& b : borders) {  // stacked on one frequency axis
        EXPECT_NEAR(b.left, borders[0].left, 0.01) << id;
        EXPECT_NEAR(b.right, borders[0].right, 0.01) << id;
      }
    } else if (id.rfind("harmonics-", 0) == 0) {
      EXPECT_EQ(borders.size(), 2u) << id << ": harmonics 2 and 3";
    }
  }
}

// The colour of each cell of a one-row residual map, left to right.
std::vector<std::array<int, 3>> CellColours(const ResidualMap& map) {
  ReportCurves curves = testing::SampleReportCurves();
  curves.residuals = map;
  const std::string page = HtmlReport(testing::SampleReportInput(), curves);
  std::string svg;
  for (const auto& [id, s] : Figures(page))
    if (id == "residual-map") svg = s;
  // The map's cells are the plot's polygons (the colour box's gradient is drawn outside it).
  std::string outside, cells_svg;
  for (const auto& g : PlotGroups(svg, &outside)) cells_svg += g.body;
  static const std::regex cell(R"re(<polygon fill = 'rgb\(\s*(\d+),\s*(\d+),\s*(\d+)\)' points = '([-\d.]+),)re");
  std::vector<std::pair<double, std::array<int, 3>>> cells;
  for (std::sregex_iterator m(cells_svg.begin(), cells_svg.end(), cell), end; m != end; ++m)
    cells.push_back({std::stod((*m)[4]), {std::stoi((*m)[1]), std::stoi((*m)[2]), std::stoi((*m)[3])}});
  std::sort(cells.begin(), cells.end());
  std::vector<std::array<int, 3>> colours;
  for (const auto& c : cells) colours.push_back(c.second);
  return colours;
}

TEST(HtmlReportPlots, TheResidualMapsNeutralColourIsOneStandardUncertainty) {
  for (const double largest : {3.0, 100.0}) {
    ResidualMap map;
    map.rows = {"acc1 h1"};
    map.step_level = {"low", "low", "low", "high", "high"};
    map.step_frequency_hz = {1, 2, 3, 4, 5};
    map.whitened_norm.resize(1, 5);
    map.whitened_norm << 0.05, 0.5, 1.0, 2.0, largest;
    const auto colours = CellColours(map);
    ASSERT_EQ(colours.size(), 5u) << largest;
    const auto& neutral = colours[2];
    // 1 σ: a light grey, no hue.
    EXPECT_GE(std::min({neutral[0], neutral[1], neutral[2]}), 235) << largest;
    EXPECT_LE(std::max({neutral[0], neutral[1], neutral[2]}) - std::min({neutral[0], neutral[1], neutral[2]}), 3)
        << largest;
    // Below: blue, within the noise; above: red, a misfit.
    for (int i : {0, 1}) EXPECT_GT(colours[i][2], colours[i][0] + 20) << largest << " cell " << i;
    for (int i : {3, 4}) EXPECT_GT(colours[i][0], colours[i][2] + 20) << largest << " cell " << i;
    // Further from 1 σ, further from neutral.
    EXPECT_LT(colours[0][0], colours[1][0]) << largest;
    EXPECT_LT(colours[4][2], colours[3][2]) << largest;
  }
}

}  // namespace
}  // namespace beamid::solver
