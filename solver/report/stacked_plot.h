// The layout of every plot of `beamid report`: one or more panels stacked on
// a shared horizontal axis (amplitude, |X/F| and phase of a response; one
// panel for the backbone), and the legend in a band of its own below them,
// so that no legend box ever covers a data point or a curve. The data are
// drawn without titles; the legend is made of gnuplot `keyentry` items of
// the same styles. Each panel is placed at fixed pixel margins, so stacked
// panels line up exactly and share one frequency axis.
#pragma once

#include <string>
#include <vector>

#include "solver/report/gnuplot_svg.h"

namespace beamid::solver {

struct PlotItem {
  std::string source;  // "$m0 using 1:3": a datablock of the script, with its columns
  std::string style;   // "with points pt 7 ps 0.7 lc rgb '#1f77b4'"
};

struct KeyEntry {
  std::string style;  // as PlotItem::style
  std::string title;  // any text (a level's label): passed through GnuplotText
};

struct Panel {
  // gnuplot commands of beamid's own for this panel (ylabel through
  // GnuplotText, logscale, yrange, ytics); they are reset after the panel.
  std::string settings;
  std::vector<PlotItem> items;
  int height_px = 220;
};

struct StackedPlot {
  std::string title;          // any text
  std::string xlabel;         // any text
  std::string datablocks;     // Datablock(...) of every source
  std::string x_settings;     // "set xrange [..]\n", shared by the panels
  std::vector<Panel> panels;  // top to bottom; empty panels are left out
  std::vector<KeyEntry> keys;
  int width_px = 760;
};

struct PlotScript {
  std::string script;
  SvgSize size;
};

PlotScript StackedPlotScript(const StackedPlot& plot);

// Draws it: GnuplotSvg(script, size).
std::string StackedPlotSvg(const StackedPlot& plot);

}  // namespace beamid::solver
