#include "solver/report/gnuplot_svg.h"

#include "hb/errors.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <fmt/core.h>

namespace beamid::solver {
namespace {

namespace fs = std::filesystem;

std::string ReadAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Removes a temporary folder whatever happens.
struct TempFolder {
  fs::path path;
  TempFolder() {
    static int counter = 0;
    path = fs::temp_directory_path() / fmt::format("beamid_gnuplot_{}_{}", ::getpid(), counter++);
    fs::create_directories(path);
  }
  ~TempFolder() {
    std::error_code error;
    fs::remove_all(path, error);
  }
};

}  // namespace

std::string GnuplotQuote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

std::string Datablock(const std::string& name, const std::vector<std::vector<double>>& rows) {
  std::string out = "$" + name + " << EOD\n";
  for (const auto& row : rows) {
    for (std::size_t i = 0; i < row.size(); ++i) out += fmt::format("{}{:.9g}", i ? " " : "", row[i]);
    out += '\n';
  }
  // A datablock without a single point makes gnuplot fail: give one that
  // plots nothing.
  if (rows.empty()) out += "NaN NaN\n";
  return out + "EOD\n";
}

std::string GnuplotSvg(const std::string& script, const SvgSize& size) {
  const TempFolder folder;
  const fs::path script_file = folder.path / "plot.gp";
  const fs::path svg_file = folder.path / "plot.svg";
  const fs::path error_file = folder.path / "gnuplot.err";
  {
    std::ofstream out(script_file);
    out << fmt::format("set terminal svg size {},{} dynamic enhanced font 'Helvetica,12' background '#ffffff'\n",
                       size.width_px, size.height_px)
        << "set output " << GnuplotQuote(svg_file.string()) << "\n"
        << "set encoding utf8\n"
        << script << "\nunset output\n";
  }
  const std::string command = fmt::format("gnuplot '{}' 2> '{}'", script_file.string(), error_file.string());
  const int status = std::system(command.c_str());
  if (status != 0) {
    const std::string message = ReadAll(error_file);
    if (WIFEXITED(status) && WEXITSTATUS(status) == 127)
      throw EnvironmentError("gnuplot is not installed: install the Debian package gnuplot-nox "
                               "(scripts/install-deps.sh)");
    throw EnvironmentError("gnuplot failed to draw a plot: " + message.substr(0, 2000));
  }
  std::string svg = ReadAll(svg_file);
  const std::size_t start = svg.find("<svg");
  if (start == std::string::npos) throw EnvironmentError("gnuplot wrote no SVG: " + ReadAll(error_file));
  return svg.substr(start);
}

std::string PlotText(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '_' || c == '^' || c == '@' || c == '&' || c == '{' || c == '}') out += "\\\\";
    out += c;
  }
  return out;
}

}  // namespace beamid::solver
