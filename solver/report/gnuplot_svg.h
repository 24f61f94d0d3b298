// Plots for the HTML report, drawn by gnuplot (Debian package gnuplot-nox)
// with its SVG terminal: a script (datablocks inline, "$name << EOD") goes
// in, the SVG text comes out without its XML prolog, ready to be inlined in
// HTML. A missing gnuplot or a failing script is a std::runtime_error that
// quotes gnuplot's own message.
#pragma once

#include <string>
#include <vector>

namespace beamid::solver {

struct SvgSize {
  int width_px = 760;
  int height_px = 420;
};

// `script` draws one plot; terminal and output are set here.
std::string GnuplotSvg(const std::string& script, const SvgSize& size = {});

// A gnuplot datablock: "$name << EOD\n<rows>EOD\n" from rows of numbers; an
// empty row ends a line segment (gnuplot breaks lines at blank lines).
std::string Datablock(const std::string& name, const std::vector<std::vector<double>>& rows);

// A string quoted for gnuplot ('...' with quotes doubled).
std::string GnuplotQuote(const std::string& text);

// Text shown literally by gnuplot's enhanced mode, which takes _ ^ @ & { }
// for markup (a channel named acc_2 would print a subscript).
std::string PlotText(const std::string& text);

}  // namespace beamid::solver
