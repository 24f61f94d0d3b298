#include "solver/report/stacked_plot.h"

#include <algorithm>

#include <fmt/core.h>

#include "solver/report/gnuplot_script.h"

namespace beamid::solver {
namespace {

constexpr int kTitleBand = 30;    // above the first panel
constexpr int kGap = 20;          // between panels: room for the tic labels at their ends
constexpr int kAxisBand = 46;     // below the last panel: tic labels and the x label
constexpr int kLeftMargin = 100;  // tic labels (up to 7 characters) and the y label
constexpr int kRightMargin = 24;
constexpr int kKeyRow = 18;  // one legend row at 12 pt
constexpr int kKeyPadding = 10;
constexpr double kCharWidth = 7.5;  // Helvetica 12 pt, a wide average character (a column never overflows)
constexpr int kKeySample = 90;      // the sample line and the gaps of one legend column

// Legend columns that fit the width, and the rows they take.
struct KeyLayout {
  int columns = 1, rows = 0;
};

KeyLayout LayoutKeys(const std::vector<KeyEntry>& keys, int width_px) {
  if (keys.empty()) return {};
  std::size_t longest = 0;
  for (const auto& k : keys) longest = std::max(longest, k.title.size());
  const double column_px = kCharWidth * static_cast<double>(longest) + kKeySample;
  const int columns = std::clamp(static_cast<int>((width_px - 60) / column_px), 1, 3);
  const int n = static_cast<int>(keys.size());
  return {columns, (n + columns - 1) / columns};
}

std::string Screen(double pixels_from_bottom, int height_px) {
  return fmt::format("{:.5f}", pixels_from_bottom / height_px);
}

}  // namespace

PlotScript StackedPlotScript(const StackedPlot& plot) {
  std::vector<const Panel*> panels;
  for (const auto& p : plot.panels)
    if (!p.items.empty()) panels.push_back(&p);
  const KeyLayout key = LayoutKeys(plot.keys, plot.width_px);
  const int key_band = key.rows == 0 ? 0 : key.rows * kKeyRow + 2 * kKeyPadding;
  int height = kTitleBand + kAxisBand + key_band;
  for (std::size_t i = 0; i < panels.size(); ++i) height += panels[i]->height_px + (i ? kGap : 0);

  std::string script = plot.datablocks + "$none << EOD\n-1 -1\nEOD\n";
  script += "set multiplot title " + GnuplotText(plot.title) + "\n";
  script += fmt::format("set lmargin at screen {}\nset rmargin at screen {}\n", Screen(kLeftMargin, plot.width_px),
                        Screen(plot.width_px - kRightMargin, plot.width_px));
  script += "unset key\nset grid\n" + plot.x_settings;
  int top = height - kTitleBand;  // pixels from the bottom
  for (std::size_t i = 0; i < panels.size(); ++i) {
    const Panel& panel = *panels[i];
    const bool last = i + 1 == panels.size();
    const int bottom = top - panel.height_px;
    script += fmt::format("set tmargin at screen {}\nset bmargin at screen {}\n", Screen(top, height),
                          Screen(bottom, height));
    script +=
        last ? "set format x '% h'\nset xlabel " + GnuplotText(plot.xlabel) + "\n" : "set format x ''\nunset xlabel\n";
    script += panel.settings;
    std::string command = "plot ";
    for (std::size_t j = 0; j < panel.items.size(); ++j)
      command += (j ? ", " : "") + panel.items[j].source + " " + panel.items[j].style + " notitle";
    script += command + "\n";
    // What a panel set stays with it.
    script +=
        "unset logscale y\nset autoscale y\nset ytics autofreq\nset format y '% h'\nunset ylabel\n"
        "unset label\nunset arrow\n";
    top = bottom - kGap;
  }
  if (key.rows > 0) {
    // The legend: a panel of its own, without axes, holding only key entries
    // (and one point outside its range, which gnuplot needs to draw a plot).
    script += fmt::format("set tmargin at screen {}\nset bmargin at screen 0\n", Screen(key_band, height));
    script +=
        "unset border\nunset tics\nunset xlabel\nunset ylabel\nunset grid\nset xrange [0:1]\nset yrange [0:1]\n"
        "unset logscale\n";
    script += fmt::format("set key center center maxrows {} samplen 3 spacing 1.1 noopaque nobox\n", key.rows);
    std::string command = "plot $none with points notitle";
    for (const auto& k : plot.keys) command += ", keyentry " + k.style + " title " + GnuplotText(k.title);
    script += command + "\n";
  }
  script += "unset multiplot\n";
  return {script, {.width_px = plot.width_px, .height_px = height}};
}

std::string StackedPlotSvg(const StackedPlot& plot) {
  const PlotScript s = StackedPlotScript(plot);
  return GnuplotSvg(s.script, s.size);
}

}  // namespace beamid::solver
