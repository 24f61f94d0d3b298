#include "solver/report/measured_backbone_report.h"

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "solver/report/gnuplot_svg.h"
#include "solver/report/html_escape.h"
#include "solver/report/html_page.h"
#include "solver/report/level_frf_plot.h"
#include "solver/report/report_outcome.h"
#include "solver/report/stacked_plot.h"
#include "solver/report/uncertain_number.h"

namespace beamid::solver {
namespace {

using Rows = std::vector<std::vector<double>>;

// A value with its σ, rounded to it (solver/report/uncertain_number.h); the
// reason a number is missing is in the level's notes below the table.
std::string Cell(const Estimate& e, double scale) {
  if (!e.valid || !std::isfinite(e.value)) return "not estimated";
  return WithUncertainty(scale * e.value, scale * e.std);
}

// A level's flags on one quantity, in red next to its number.
std::string FlagCell(const LevelResonance& l, const std::string& quantity) {
  const std::string note = l.FlagNote(quantity);
  return note.empty() ? "" : " <span class=\"flag\">" + HtmlEscape(note) + "</span>";
}

// One quantity against amplitude [mm]: the fit's curve ±1σ and each level's
// point, the levels in the cross-level fit apart from those left out.
std::string PlotAgainstAmplitude(const MeasuredBackboneFile& file, bool frequency) {
  Rows band, in_fit, left_out;
  for (const auto& p : file.single_mode_fit.curve) {
    const double value = frequency ? p.frequency_hz : p.damping_ratio;
    const double std = frequency ? p.frequency_std_hz : p.damping_ratio_std;
    band.push_back({1e3 * p.amplitude_m, value - std, value + std, value});
  }
  for (const auto& l : file.levels) {
    const Estimate& y = frequency ? l.quadrature_frequency_hz : l.damping_ratio;
    if (!y.valid || !l.quadrature_amplitude_m.valid) continue;
    (l.in_global_fit ? in_fit : left_out).push_back({1e3 * l.quadrature_amplitude_m.value, y.value, y.std});
  }
  // The legend in a band of its own below the data (solver/report/stacked_plot.h).
  StackedPlot plot{.xlabel = "displacement amplitude at the sensor [mm]",
                   .datablocks = Datablock("band", band) + Datablock("fit", in_fit) + Datablock("out", left_out)};
  Panel panel{
      .settings = "set ylabel " + GnuplotText(frequency ? "phase-resonance frequency [Hz]" : "damping ratio ζ") + "\n",
      .height_px = 320};
  auto add = [&](const std::string& source, const std::string& style, const std::string& title) {
    panel.items.push_back({source, style});
    plot.keys.push_back({style, title});
  };
  if (!band.empty()) {
    add("$band using 1:2:3", "with filledcurves lc rgb '#c8d8f0'", "single-mode fit ±1σ");
    add("$band using 1:4", "with lines lw 2 lc rgb '#2050a0'", "single-mode fit");
  }
  if (!in_fit.empty()) add("$fit using 1:2:3", "with yerrorbars pt 7 ps 1.2 lc rgb '#c03020'", "levels in the fit");
  if (!left_out.empty())
    add("$out using 1:2:3", "with yerrorbars pt 6 ps 1.4 lc rgb '#a50f15'", "flagged levels, left out of the fit");
  if (panel.items.empty()) return "";
  plot.panels = {panel};
  return StackedPlotSvg(plot);
}

std::string LevelTable(const MeasuredBackboneFile& file, const MeasuredBackboneOutcome& outcome) {
  std::string html =
      "<table>\n<tr><th>level</th><th>control</th><th>phase resonance [Hz]</th><th>amplitude [mm]</th>"
      "<th>ζ [%] (σ covers the estimators)</th><th>ζ phase resonance [%]</th><th>ζ local fit [%]</th>"
      "<th>ζ half-power [%]</th><th>ζ free decay [%]</th><th>peak [Hz]</th><th>regeneration RMS</th><th>in the fit</th><th>flags</th></tr>\n";
  for (std::size_t i = 0; i < file.levels.size(); ++i) {
    const LevelResonance& l = file.levels[i];
    const LevelOutcome& stated = outcome.levels[i];
    std::string kinds;
    for (const auto& name : stated.flags) kinds += (kinds.empty() ? "" : ", ") + name;
    html += fmt::format(
        "<tr><td>{}</td><td>{}</td><td>{}{}</td><td>{}</td><td>{}</td><td>{}{}</td><td>{}{}</td><td>{}{}</td>"
        "<td>{}{}</td><td>{}{}</td><td>{}{}</td><td>{}</td><td class=\"flag\">{}</td></tr>\n",
        HtmlEscape(l.label),
        LevelControlText(file.excitation_quantity, l.control),
        Cell(l.quadrature_frequency_hz, 1), FlagCell(l, "quadrature_frequency"), Cell(l.quadrature_amplitude_m, 1e3),
        Cell(l.damping_ratio, 100), Cell(l.quadrature_damping_ratio, 100), FlagCell(l, "quadrature_damping_ratio"),
        Cell(l.local_damping_ratio, 100), FlagCell(l, "local_damping_ratio"), Cell(l.half_power_damping_ratio, 100),
        FlagCell(l, "half_power_damping_ratio"), Cell(l.free_decay_damping_ratio, 100),
        FlagCell(l, "free_decay_damping_ratio"), Cell(l.peak_frequency_hz, 1), FlagCell(l, "peak_frequency"),
        NumberOrWhyNot(100 * l.regeneration_relative_rms, "{:.3g} %", "the fit misses a step of no response"),
        FlagCell(l, "regeneration_relative_rms"),
        stated.in_global_fit ? "yes" : "<span class=\"flag\">no</span>", HtmlEscape(kinds));
  }
  return html + "</table>\n";
}

std::string LevelNotes(const MeasuredBackboneFile& file) {
  std::string html;
  for (const auto& l : file.levels) {
    std::string items;
    for (const auto& f : l.flags)
      items += fmt::format("<li class=\"flag\">[FLAG: {}] {}</li>\n", HtmlEscape(std::string(LevelFlagName(f.kind))),
                           HtmlEscape(f.message));
    for (const auto& j : l.jumps)
      items += fmt::format("<li>jump ({}-sweep) between steps {} and {}: {:.6g} → {:.6g} Hz, |X/F| × {}, phase "
                           "{}</li>\n",
                           j.up_sweep ? "up" : "down", j.from_step, j.to_step, j.from_frequency_hz, j.to_frequency_hz,
                           NumberOrWhyNot(j.receptance_ratio, "{:.3g}", "a step of no response"),
                           NumberOrWhyNot(j.phase_change_rad * 180 / std::numbers::pi, "{:+.0f}°",
                                          "a step of no response"));
    for (const std::string* note : {&l.quadrature_note, &l.half_power_note, &l.damping_ratio_note})
      if (!note->empty()) items += "<li>" + HtmlEscape(*note) + "</li>\n";
    if (!items.empty()) html += "<h3>" + HtmlEscape(l.label) + "</h3>\n<ul>\n" + items + "</ul>\n";
  }
  return html;
}

// Per level its measured |X/F| and phase with the fit over them, and below
// each the numbers its markers stand for, their flags beside them.
std::string LevelFrfFigures(const MeasuredBackboneFile& file) {
  const ExcitationLabels excitation = LabelsOf(file.excitation_quantity);
  std::string html;
  for (const auto& l : file.levels) {
    const std::string svg = LevelFrfPlotSvg(l, excitation);
    if (svg.empty()) continue;
    std::string caption = fmt::format(
        "Level {}: measured steps (dots){}; peak {}{}", HtmlEscape(l.label),
        l.fit_frf.empty() ? "" : " and the single-mode fit across levels (line)",
        l.peak_frequency_hz.valid ? Cell(l.peak_frequency_hz, 1) + " Hz"
                                  : "not estimated (" + HtmlEscape(l.half_power_note.empty() ? "no peak in the sweep"
                                                                                            : l.half_power_note) + ")",
        FlagCell(l, "peak_frequency"));
    if (l.quadrature_frequency_hz.valid)
      caption += fmt::format(", phase resonance {} Hz{}", Cell(l.quadrature_frequency_hz, 1),
                             FlagCell(l, "quadrature_frequency"));
    if (l.half_power_damping_ratio.valid)
      caption += fmt::format(", half-power points {} and {} Hz, ζ {} %{}", Cell(l.half_power_lower_frequency_hz, 1),
                             Cell(l.half_power_upper_frequency_hz, 1), Cell(l.half_power_damping_ratio, 100),
                             FlagCell(l, "half_power_damping_ratio"));
    else if (!l.half_power_note.empty() && l.peak_frequency_hz.valid)
      caption += ", half-power ζ not estimated (" + HtmlEscape(l.half_power_note) + ")";
    if (!l.jumps.empty())
      caption += fmt::format("; {} jump{} of the sweep (dashed){}", l.jumps.size(), l.jumps.size() == 1 ? "" : "s",
                             FlagCell(l, "sweep"));
    html += PlotFigure("frf-" + l.label, svg, caption + ".", "level-frf");
  }
  return html.empty() ? html
                      : "<section id=\"frequency-responses\"><h2>Frequency response of each level</h2>\n" + html +
                            "</section>\n";
}

}  // namespace

std::string MeasuredBackboneHtmlReport(const MeasuredBackboneFile& file, const std::string& source) {
  const std::string title = "Measured backbone";
  // What the page states, once: its text below reads it, and the page embeds it.
  const MeasuredBackboneOutcome outcome = OutcomeOf(file);
  std::string html = HtmlPageHead(title);
  std::string inputs;
  for (const auto& i : file.inputs) inputs += (inputs.empty() ? "" : ", ") + ("<code>" + HtmlEscape(i) + "</code>");
  const ExcitationLabels excitation = LabelsOf(file.excitation_quantity);
  html += fmt::format("<p>File <code>{}</code> (beamid {}), inputs {}; channel {}, response {}; excitation {} [{}]: "
                      "X/F is the {}{}.</p>\n",
                      HtmlEscape(source), HtmlEscape(file.beamid_version.empty() ? "?" : file.beamid_version), inputs,
                      HtmlEscape(file.channel.empty() ? "?" : file.channel), HtmlEscape(file.response_quantity),
                      HtmlEscape(excitation.control), HtmlEscape(excitation.unit), HtmlEscape(excitation.frf),
                      excitation.caveat.empty() ? "" : "; " + HtmlEscape(excitation.caveat));
  html += fmt::format("<section id=\"levels\"><h2>Levels</h2>\n<p>{} levels, {} flagged, {} left out of the "
                      "cross-level fit.</p>\n",
                      outcome.levels.size(), outcome.flagged_levels, outcome.left_out_levels);
  html += LevelTable(file, outcome) + LevelNotes(file) + "</section>\n" + LevelFrfFigures(file);
  const auto& t = file.damping_trend;  // the slopes; the verdicts and their z from the record
  html += "<section id=\"fit\"><h2>Cross-level single-mode fit and damping trend</h2>\n";
  html += outcome.fit_form.empty()
              ? std::string("<p>No single-mode fit across levels: too few points near the mode.</p>\n")
              : fmt::format("<p>Form: {}; reduced χ² {}.</p>\n", HtmlEscape(outcome.fit_form),
                            NumberOrWhyNot(outcome.fit_reduced_chi_square, "{:.3g}", "no degrees of freedom left"));
  const std::string no_sigma = "the fit gives no σ for it";
  if (!t.note.empty())
    html += fmt::format("<p class=\"damping-trend\">Damping against amplitude: <strong>not judged</strong>: {}.</p>\n",
                        HtmlEscape(t.note));
  else
    html += fmt::format("<p class=\"damping-trend\">Damping against amplitude: <strong>{}</strong> (ζω_n: slope "
                        "{} /(s·m), {}); ζ alone {} (slope {} per m, {}), which a constant damper also gives where "
                        "the frequency changes.</p>\n",
                        outcome.damping_rate_trend == Trend::kNotJudged
                            ? "not available"
                            : schema::NameOf(outcome.damping_rate_trend, kDampingRateTrendNames),
                        UncertainOrWhyNot(t.damping_rate_slope_per_s_m, t.damping_rate_slope_std_per_s_m, no_sigma),
                        NumberOrWhyNot(outcome.damping_rate_z, "{:+.1f} σ", no_sigma),
                        schema::NameOf(outcome.damping_ratio_trend, kDampingRatioTrendNames),
                        UncertainOrWhyNot(t.slope_per_m, t.slope_std_per_m, no_sigma),
                        NumberOrWhyNot(outcome.damping_ratio_z, "{:+.1f} σ", no_sigma));
  for (bool frequency : {true, false}) {
    const std::string svg = PlotAgainstAmplitude(file, frequency);
    if (svg.empty()) continue;
    html += PlotFigure(frequency ? "backbone-frequency" : "backbone-damping", svg, frequency ? "Backbone: each level's phase resonance (±1σ) and the "
                                    "single-mode fit across levels; open circles: flagged levels, "
                                    "left out of the fit."
                                  : "Damping ratio against amplitude: each level's ζ (its σ covers "
                                    "the three estimators) and the fit's ζ(a).");
  }
  html += "</section>\n";
  if (!file.warnings.empty()) {
    html += "<section id=\"warnings\"><h2>Warnings</h2>\n<ul>\n";
    for (const auto& w : file.warnings) html += "<li class=\"warning\">" + HtmlEscape(w) + "</li>\n";
    html += "</ul>\n</section>\n";
  }
  return ScrollableTables(html) + ReportDataBlock(ToJson(outcome)) + "</body>\n</html>\n";
}

}  // namespace beamid::solver
