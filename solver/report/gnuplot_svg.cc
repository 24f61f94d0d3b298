#include "solver/report/gnuplot_svg.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/core.h>

#include "hb/errors.h"
#include "solver/report/external_program.h"
#include "solver/report/temp_folder.h"

namespace beamid::solver {
namespace {

namespace fs = std::filesystem;

}  // namespace

std::string GnuplotSvg(const std::string& script, const SvgSize& size) {
  const TempFolder folder("gnuplot");
  const fs::path svg_file = folder.path() / "plot.svg";
  const fs::path error_file = folder.path() / "gnuplot.err";
  // No `set output`: the SVG goes to standard output.
  const std::string full_script =
      fmt::format("set terminal svg size {},{} dynamic enhanced font 'Helvetica,12' background '#ffffff'\n"
                  "set encoding utf8\n",
                  size.width_px, size.height_px) +
      script + "\n";
  const int status = RunExternalProgram({.program = "gnuplot",
                                         .debian_package = "gnuplot-nox",
                                         .stdin_text = full_script,
                                         .stdout_file = svg_file,
                                         .stderr_file = error_file});
  if (status != 0)
    throw EnvironmentError(fmt::format("gnuplot failed to draw a plot (exit status {}): {}", status,
                                       ReadWholeFile(error_file).substr(0, 2000)));
  std::string svg = ReadWholeFile(svg_file);
  const std::size_t start = svg.find("<svg");
  if (start == std::string::npos)
    throw EnvironmentError("gnuplot wrote no SVG: " + ReadWholeFile(error_file).substr(0, 2000));
  return svg.substr(start);
}

}  // namespace beamid::solver
