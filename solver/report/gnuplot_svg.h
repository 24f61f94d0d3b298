// Plots for the HTML report, drawn by gnuplot (Debian package gnuplot-nox)
// with its SVG terminal: a script (datablocks inline, texts through
// GnuplotText, solver/report/gnuplot_script.h) goes to gnuplot's standard
// input, the SVG comes back on its standard output, without its XML prolog,
// ready to be inlined in HTML. No path and no shell are involved. A missing
// gnuplot or a failing script is an EnvironmentError that quotes gnuplot's
// own message.
#pragma once

#include <string>

#include "solver/report/gnuplot_script.h"

namespace beamid::solver {

struct SvgSize {
  int width_px = 760;
  int height_px = 420;
};

// `script` draws one plot; terminal and output are set here.
std::string GnuplotSvg(const std::string& script, const SvgSize& size = {});

}  // namespace beamid::solver
