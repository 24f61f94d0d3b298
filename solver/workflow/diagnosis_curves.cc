#include "solver/workflow/diagnosis_curves.h"

#include <algorithm>
#include <complex>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include <fmt/core.h>

#include "hb/errors.h"
#include "solver/report/external_program.h"
#include "solver/report/gnuplot_script.h"
#include "solver/report/temp_folder.h"
#include "solver/workflow/output_file.h"

namespace beamid::workflow {
namespace {

std::string ReadWholeFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Draws PREFIX.png with gnuplot, run without a shell; the PNG is written like
// every other output (whole or not at all). Returns why it was not drawn
// (empty: drawn).
std::string DrawCurves(const std::string& script, const std::string& png) {
  std::string problem;
  try {
    const solver::TempFolder folder("gnuplot");
    const std::filesystem::path picture = folder.path() / "curves.png", messages = folder.path() / "gnuplot.err";
    const int status = solver::RunExternalProgram({.program = "gnuplot",
                                                   .debian_package = "gnuplot-nox",
                                                   .stdin_text = script,
                                                   .stdout_file = picture,
                                                   .stderr_file = messages});
    const std::string bytes = ReadWholeFile(picture);
    if (status == 0 && !bytes.empty()) WriteTextFile(png, bytes);
    else problem = fmt::format("gnuplot failed (exit status {}): {}", status, ReadWholeFile(messages).substr(0, 2000));
  } catch (const EnvironmentError& e) {
    problem = e.what();
  }
  return problem;
}

}  // namespace

std::string DiagnosisCurvesScript(const solver::DiagnosisResult& result) {
  std::vector<std::string> levels, channels;
  for (const auto& p : result.response) {
    if (std::find(levels.begin(), levels.end(), p.level) == levels.end()) levels.push_back(p.level);
    if (std::find(channels.begin(), channels.end(), p.channel) == channels.end()) channels.push_back(p.channel);
  }
  std::string script = fmt::format(
      "# Draws PREFIX.png of beamid diagnose --curves on standard output: gnuplot PREFIX.gp > PREFIX.png\n"
      "set terminal pngcairo size {},600 enhanced\nset key top left\n"
      "set xlabel 'frequency [Hz]'\nset ylabel 'first-harmonic amplitude (channel unit)'\n",
      500 * std::max<std::size_t>(channels.size(), 1));
  for (std::size_t c = 0; c < channels.size(); ++c)
    for (std::size_t l = 0; l < levels.size(); ++l) {
      std::vector<std::vector<double>> rows;  // frequency, measured, base, diagnosed
      for (const auto& p : result.response)
        if (p.level == levels[l] && p.channel == channels[c])
          rows.push_back({p.frequency_hz, std::abs(p.measured), std::abs(p.base_model), std::abs(p.final_model)});
      script += solver::Datablock(fmt::format("c{}_l{}", c, l), rows);
    }
  script += fmt::format("set multiplot layout 1,{}\n", std::max<std::size_t>(channels.size(), 1));
  for (std::size_t c = 0; c < channels.size(); ++c) {
    script += fmt::format("set title {} font ',10'\nplot ",
                          solver::GnuplotText(channels[c] + " (points: measured, dashed: base, solid: diagnosed)"));
    for (std::size_t l = 0; l < levels.size(); ++l)
      script += fmt::format("$c{0}_l{1} using 1:2 with points pt 7 lc {2} title {3}, "
                            "$c{0}_l{1} using 1:3 with lines dt 2 lc {2} notitle, "
                            "$c{0}_l{1} using 1:4 with lines dt 1 lc {2} notitle{4}",
                            c, l, l + 1, solver::GnuplotText(levels[l]), l + 1 < levels.size() ? ", \\\n  " : "\n");
  }
  return script + "unset multiplot\n";
}

std::string WriteDiagnosisCurves(const solver::DiagnosisResult& result, const std::string& prefix) {
  WriteTextFile(prefix + ".csv", solver::ResponseCsv(result));
  const std::string script = DiagnosisCurvesScript(result);
  WriteTextFile(prefix + ".gp", script);
  return DrawCurves(script, prefix + ".png");
}

}  // namespace beamid::workflow
