#include "solver/report/html_report.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "solver/report/diagnosis_residual_map.h"
#include "solver/report/gnuplot_script.h"
#include "solver/report/gnuplot_svg.h"
#include "solver/report/held_out_summary.h"
#include "solver/report/html_escape.h"
#include "solver/report/html_page.h"
#include "solver/report/report_outcome.h"
#include "solver/report/response_plots.h"
#include "solver/report/stacked_plot.h"
#include "solver/report/uncertain_number.h"

namespace beamid::solver {
namespace {

using Rows = std::vector<std::vector<double>>;

// A statistic (χ², p, a score): no uncertainty, six significant digits.
std::string Number(double value) { return fmt::format("{:.6g}", value); }

// value ± σ for a table cell: a narrow column breaks it after the ±, never
// inside a number or before the ±.
std::string UncertainCell(double value, double sigma, const std::string& unit = "") {
  std::string text = HtmlEscape(WithUncertainty(value, sigma, unit));
  for (std::size_t at; (at = text.find(" ± ")) != std::string::npos;) text.replace(at, 4, "&nbsp;± ");
  return text;
}

// A unit column: the unit's symbols, "—" for a dimensionless one.
std::string UnitCell(const std::string& unit) {
  const std::string symbol = UnitSymbol(unit);
  return symbol.empty() ? "—" : HtmlEscape(symbol);
}

// A standard uncertainty's cell: "not available" rather than a 0 that
// would read as exact.
std::string SigmaCell(const UncertainFormat& format, double sigma) {
  return format.has_sigma() ? format.Format(sigma) : "not available";
}

// The model a diagnosis selected, as its file holds it: its first harmonic
// at every measured step of every channel (DiagnosisResult::response).
std::optional<SelectedResponse> SelectedModelOf(const ReportInput& input, const IdentificationOutcome& outcome) {
  if (!input.diagnosis || !outcome.diagnosis) return std::nullopt;
  const DiagnosisResult& d = input.diagnosis->diagnosis;
  const DiagnosisVerdict verdict = outcome.diagnosis->verdict;
  const bool named = verdict == DiagnosisVerdict::kCauseNamed || verdict == DiagnosisVerdict::kCombinationNamed;
  if (!named || d.response.empty()) return std::nullopt;
  std::string name;
  for (const auto& s : outcome.diagnosis->selected) name += (name.empty() ? "" : " + ") + s;
  return SelectedResponse{.name = name, .points = &d.response, .backbone = &d.final_backbone};
}

// The steps the recording makes doubtful: cut before they settled (the
// extraction's flag) or left out by the robust fit; empty when none.
std::string RecordingSection(const ReportCurves& curves, const ResultFile& result) {
  std::string items;
  for (const auto& level : curves.levels)
    for (const auto& m : level.measured)
      if (!m.flag.empty())
        items += fmt::format("<li>{} {:.4g} Hz (<code>{}</code>): {}</li>", HtmlEscape(level.level), m.frequency_hz,
                             HtmlEscape(m.file), HtmlEscape(m.flag));
  std::string html;
  if (!items.empty())
    html += "<p>Flagged steps (circled on the response curves):</p><ul>" + items + "</ul>\n";
  if (result.robust_fit) {
    html += "<p>Robust fit: " + HtmlEscape(result.robust_fit->note) + "</p>\n";
    if (result.robust_fit->applied) {
      html += "<table><tr><th>parameter</th><th>without the outliers (reported)</th><th>with them</th></tr>\n";
      for (std::size_t j = 0; j < result.parameters.size() && j < result.robust_fit->ordinary_parameters.size(); ++j) {
        // Both at the reported value's uncertainty, so that they compare digit by digit.
        const UncertainFormat format(result.parameters[j].value, result.parameters[j].std);
        html += "<tr><td>" + HtmlEscape(result.parameters[j].name) + "</td><td>" +
                format.Format(result.parameters[j].value) + "</td><td>" +
                format.Format(result.robust_fit->ordinary_parameters[j].value) + "</td></tr>\n";
      }
      html += "</table>\n";
    }
  }
  return html.empty() ? html : "<section id=\"recording\"><h2>The recording</h2>\n" + html + "</section>\n";
}

std::string BackbonePlotSvg(const ReportCurves& curves, const SelectedResponse* selected) {
  const std::size_t c = static_cast<std::size_t>(curves.reference_channel);
  const ReportChannel& ch = curves.channels[c];
  Rows frc, backbone, resonance, selected_backbone;
  if (selected && selected->backbone && selected->backbone->channel == ch.channel)
    for (const auto& p : selected->backbone->points)
      selected_backbone.push_back(
          {p.frequency_hz, p.amplitude_m * std::pow(2 * std::numbers::pi * p.frequency_hz, ch.derivative_order)});
  for (const auto& level : curves.levels) {
    for (const auto& p : level.model) frc.push_back({p.frequency_hz, p.amplitude[c]});
    frc.push_back({});
  }
  for (const auto& p : curves.backbone) backbone.push_back({p.frequency_hz, p.amplitude});
  // Error bars and bands of two standard uncertainties.
  for (const auto& p : curves.phase_resonance)
    resonance.push_back({p.frequency_hz, p.amplitude, 2 * p.frequency_std_hz, 2 * p.amplitude_std});
  // The fit's band in frequency, as a closed polygon: up one edge, down the other.
  Rows single_mode, band;
  const auto& fit = curves.measured_mode.fit;
  for (const auto& p : fit) {
    single_mode.push_back({p.frequency_hz, p.amplitude});
    band.push_back({p.frequency_hz - 2 * p.frequency_std_hz, p.amplitude});
  }
  for (auto p = fit.rbegin(); p != fit.rend(); ++p) band.push_back({p->frequency_hz + 2 * p->frequency_std_hz, p->amplitude});
  StackedPlot plot{.title = fmt::format("backbone at {} (x = {:.3f} m)", ch.channel, ch.position_m),
                   .xlabel = "frequency [Hz]",
                   .datablocks = Datablock("frc", frc) + Datablock("bb", backbone) + Datablock("pr", resonance) +
                                 Datablock("sm", single_mode) + Datablock("band", band)};
  Panel panel{.settings = "set ylabel " + GnuplotText("|X₁| [" + UnitSymbol(ch.si_unit) + "]") + "\n",
              .height_px = 330};
  const std::string grey = "with lines lw 1 lc rgb '#aaaaaa'", black = "with lines lw 2.5 lc rgb '#000000'";
  panel.items = {{"$frc", grey}, {"$bb", black}};
  plot.keys = {{grey, "model FRCs"},
               {black, selected ? "base model's backbone (phase resonance at this sensor)"
                                : "model backbone (phase resonance at this sensor)"}};
  if (!selected_backbone.empty()) {
    const std::string blue = "with lines lw 2.5 lc rgb '#1f77b4'";
    plot.datablocks += Datablock("sel", selected_backbone);
    panel.items.push_back({"$sel", blue});
    plot.keys.push_back({blue, "backbone of the selected model (" + selected->name + ")"});
  }
  if (!single_mode.empty()) {
    const std::string fill = "with filledcurves closed lc rgb '#f4b6b6' fs transparent solid 0.5";
    const std::string dashed = "with lines lw 1.5 dt 2 lc rgb '#d62728'";
    panel.items.push_back({"$band", fill});
    panel.items.push_back({"$sm using 1:2", dashed});
    plot.keys.push_back({dashed, "measured: one nonlinear mode fitted across levels"});
    plot.keys.push_back({fill, "its ±2σ band"});
  }
  const std::string bars = "with xyerrorbars pt 13 ps 1.6 lw 1.5 lc rgb '#d62728'";
  panel.items.push_back({"$pr using 1:2:3:4", bars});
  plot.keys.push_back({bars, "measured phase resonance ±2σ"});
  plot.panels = {panel};
  return StackedPlotSvg(plot);
}

// Damping ratio against amplitude, model-free: each level's three estimates
// and the single-nonlinear-mode fit's ζ(a).
std::string DampingPlotSvg(const ReportCurves& curves) {
  const ReportChannel& ch = curves.channels[static_cast<std::size_t>(curves.reference_channel)];
  const MeasuredNonlinearMode& mode = curves.measured_mode;
  Rows quadrature, local, half_power, fit;
  for (const auto& p : mode.damping) {
    if (std::isfinite(p.quadrature)) quadrature.push_back({p.amplitude, p.quadrature, 2 * p.quadrature_std});
    if (std::isfinite(p.local)) local.push_back({p.amplitude, p.local, 2 * p.local_std});
    if (std::isfinite(p.half_power)) half_power.push_back({p.amplitude, p.half_power, 2 * p.half_power_std});
  }
  for (const auto& p : mode.fit)
    fit.push_back({p.amplitude, p.damping_ratio, p.damping_ratio - 2 * p.damping_ratio_std,
                   p.damping_ratio + 2 * p.damping_ratio_std});
  StackedPlot plot{.title = fmt::format("damping against amplitude at {} (model-free)", ch.channel),
                   .xlabel = "|X₁| at phase resonance [" + UnitSymbol(ch.si_unit) + "]",
                   .datablocks = Datablock("q", quadrature) + Datablock("l", local) + Datablock("h", half_power) +
                                 Datablock("f", fit)};
  Panel panel{.settings = "set ylabel 'damping ratio ζ'\n", .height_px = 300};
  auto add = [&](bool any, const std::string& source, const std::string& style, const std::string& title) {
    if (!any) return;
    panel.items.push_back({source, style});
    if (!title.empty()) plot.keys.push_back({style, title});
  };
  add(!fit.empty(), "$f using 1:3:4", "with filledcurves lc rgb '#f4b6b6' fs transparent solid 0.5", "");
  add(!fit.empty(), "$f using 1:2", "with lines lw 1.5 dt 2 lc rgb '#d62728'",
      "one nonlinear mode fitted across levels ±2σ");
  add(!quadrature.empty(), "$q", "with yerrorbars pt 13 ps 1.4 lc rgb '#d62728'", "quadrature point");
  add(!local.empty(), "$l", "with yerrorbars pt 7 ps 0.9 lc rgb '#1f77b4'", "local single-mode fit");
  add(!half_power.empty(), "$h", "with yerrorbars pt 5 ps 0.9 lc rgb '#2ca02c'", "half-power");
  plot.panels = {panel};
  return StackedPlotSvg(plot);
}

std::string Warnings(const std::vector<std::string>& warnings) {
  std::string html;
  for (const auto& w : warnings) html += "<p class=\"warning\">warning: " + HtmlEscape(w) + "</p>\n";
  return html;
}

// Each level's measured phase resonance against the model's backbone.
std::string ResonanceTable(const ReportCurves& curves) {
  const ReportChannel& ch = curves.channels[static_cast<std::size_t>(curves.reference_channel)];
  std::string html = fmt::format(
      "<table class=\"resonance\"><tr><th>level</th><th>phase resonance [Hz]</th><th>|X₁| [{}]</th>"
      "<th>damping ratio ζ</th><th>model backbone there [Hz]</th><th>measured − model</th></tr>\n",
      HtmlEscape(UnitSymbol(ch.si_unit)));
  // A level's note is a sentence: below the table, where it has the page's width.
  std::string notes;
  for (const auto& p : curves.phase_resonance) {
    // The model's frequency at the measured one's decimal place.
    const UncertainFormat frequency(p.frequency_hz, p.frequency_std_hz);
    html += fmt::format(
        "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td class=\"z\">{}</td></tr>\n",
        HtmlEscape(p.level) + (p.note.empty() ? "" : "&nbsp;*"), UncertainCell(p.frequency_hz, p.frequency_std_hz),
        UncertainCell(p.amplitude, p.amplitude_std), UncertainCell(p.damping_ratio, p.damping_ratio_std),
        std::isfinite(p.model_frequency_hz) ? frequency.Format(p.model_frequency_hz) : "outside its range",
        std::isfinite(p.z) ? fmt::format("{:+.2f} σ", p.z) : "");
    if (!p.note.empty()) notes += "<li>" + HtmlEscape(p.level) + ": " + HtmlEscape(p.note) + "</li>";
  }
  return html + "</table>\n" + (notes.empty() ? "" : "<ul class=\"notes\">" + notes + "</ul>\n");
}

std::string TimePlotSvg(const TimeHistory& history, const std::string& channel) {
  Rows rows;
  for (std::size_t n = 0; n < history.time_s.size(); ++n)
    rows.push_back({1e3 * history.time_s[n], history.predicted[n], history.predicted_std[n], history.measured[n]});
  StackedPlot plot{.title = fmt::format("{} (held out), level {}, {:.3f} Hz: one period of the steady state", channel,
                                        history.level, history.frequency_hz),
                   .xlabel = "time [ms]",
                   .datablocks = Datablock("t", rows),
                   .x_settings = "set autoscale xfix\n"};  // one period, edge to edge
  const std::string band = "with filledcurves fc rgb '#c6dbef'", predicted = "with lines lw 2 lc rgb '#1f77b4'",
                    measured = "with lines lw 2 dt 2 lc rgb '#d62728'";
  plot.panels = {
      {.settings = "set ylabel 'acceleration [m/s²]'\n",
       .items = {{"$t using 1:($2-2*$3):($2+2*$3)", band}, {"$t using 1:2", predicted}, {"$t using 1:4", measured}},
       .height_px = 280}};
  plot.keys = {{band, "prediction ±2σ"}, {predicted, "predicted"}, {measured, "measured (harmonics of the recording)"}};
  return StackedPlotSvg(plot);
}

// The colour scale is logarithmic and centred at one standard uncertainty:
// |residual|/σ = 1 is the neutral colour, blue below (within the noise), red
// above (a misfit), symmetric in decades about 1. `largest`: a residual the
// scale must reach besides the map's own (another map's, so that two maps
// share one scale).
std::string ResidualPlot(const ResidualMap& map, double largest = 1.0) {
  const Eigen::Index rows = map.whitened_norm.rows(), steps = map.whitened_norm.cols();
  for (Eigen::Index r = 0; r < rows; ++r)
    for (Eigen::Index i = 0; i < steps; ++i)
      if (std::isfinite(map.whitened_norm(r, i))) largest = std::max(largest, map.whitened_norm(r, i));
  const int decades = std::clamp(static_cast<int>(std::ceil(std::log10(largest) - 1e-9)), 1, 3);
  const double top = std::pow(10.0, decades), bottom = 1.0 / top;
  // One filled box per cell (an image needs a grid of at least 2 × 2: one
  // fitted channel and harmonic would show nothing); a step without a state
  // (NaN) stays blank.
  Rows data;
  for (Eigen::Index r = 0; r < rows; ++r)
    for (Eigen::Index i = 0; i < steps; ++i)
      data.push_back(
          {static_cast<double>(i), static_cast<double>(r), std::clamp(map.whitened_norm(r, i), bottom, top)});
  std::string ytics, xtics, arrows, cbtics;
  for (Eigen::Index r = 0; r < rows; ++r)
    ytics += fmt::format("{}{} {}", r ? ", " : "", GnuplotText(map.rows[r], GnuplotTextUse::kTicLabel), r);
  std::size_t start = 0;
  for (std::size_t i = 1; i <= map.step_level.size(); ++i) {
    if (i < map.step_level.size() && map.step_level[i] == map.step_level[start]) continue;
    xtics += fmt::format("{}{} {}", xtics.empty() ? "" : ", ", GnuplotText(map.step_level[start], GnuplotTextUse::kTicLabel),
                         0.5 * (start + i - 1));
    if (i < map.step_level.size())
      arrows +=
          fmt::format("set arrow from {0}, graph 0 to {0}, graph 1 nohead lc rgb '#444444' lw 2 front\n", i - 0.5);
    start = i;
  }
  for (int d = -decades; d <= decades; ++d)
    cbtics +=
        fmt::format("{}'{}{}' {:g}", d == -decades ? "" : ", ", d == 0 ? "1 σ" : fmt::format("{:g}", std::pow(10.0, d)),
                    d < 0   ? " (noise)"
                    : d > 0 ? " (misfit)"
                            : "",
                    std::pow(10.0, d));
  return fmt::format(
             "set title 'whitened residual |L^{{-1}}(Y_{{model}} - Y_{{measured}})| per channel, harmonic and step'\n"
             "set xlabel 'steps (by level, in campaign order)'\nset ytics ({})\nset xtics ({})\n"
             "set logscale cb\nset cbrange [{:g}:{:g}]\nset cbtics ({})\n"
             "set cblabel '|residual| / σ'\n"
             "set palette defined (0 '#4393c3', 0.25 '#92c5de', 0.5 '#f7f7f7', 0.75 '#f4a582', 1 '#b2182b')\n"
             "set lmargin 10\nset rmargin 16\n"
             "set xrange [-0.5:{}]\nset yrange [-0.5:{}]\n{}",
             ytics, xtics, bottom, top, cbtics, steps - 0.5, rows - 0.5, arrows) +
         Datablock("r", data) +
         "plot $r using 1:2:(0.5):(0.5):3 with boxxyerror fs solid 1.0 noborder lc palette notitle\n";
}

// What the table's total intervals hold, under it.
std::string IntervalParts(const DampingLawEnvelope& envelope) {
  if (envelope.intervals.empty()) return "";
  return "<p class=\"interval-parts\">The total 95 % intervals hold " + HtmlEscape(TotalIntervalParts(envelope)) +
         ".</p>\n";
}

// With the damping laws refitted: a column of the total interval (the
// envelope over the laws the data accept, widened by the harmonic
// truncation's shift), flagged where it depends on the law or the truncation.
// With `base`: a last column of the base fit's value of each parameter, blank
// for those the base model lacks (a diagnosis's selected model).
// (result.json's parameters and a damping law's fit hold the same fields.)
template <typename Parameter>
std::string ParameterRows(const std::vector<Parameter>& parameters, const std::vector<ModelFormInterval>& intervals,
                          const std::vector<ParameterEstimate>* base = nullptr) {
  std::string html =
      "<table class=\"parameters\"><tr><th>parameter</th><th>value</th><th>standard uncertainty</th>"
      "<th>95 % interval</th>" +
      std::string(intervals.empty() ? "" : "<th>total 95 % (damping laws, harmonic truncation)</th>") +
      "<th>unit</th>" +
      std::string(base == nullptr ? "" : "<th>base fit (rejected)</th>") + "</tr>\n";
  for (const auto& p : parameters) {
    // Every number of the row at the decimal place of the value's σ.
    const UncertainFormat format(p.value, p.std);
    std::string model_form, base_value;
    if (!intervals.empty()) {
      const auto i = std::find_if(intervals.begin(), intervals.end(), [&](const auto& m) { return m.name == p.name; });
      model_form = i == intervals.end()
                       ? "<td>(a damping parameter)</td>"
                       : fmt::format("<td>{} … {}{}{}</td>", format.Format(i->lower_95), format.Format(i->upper_95),
                                     i->depends_on_damping_law ? " <b>[depends on the damping law]</b>" : "",
                                     i->depends_on_truncation ? " <b>[depends on the harmonic truncation]</b>" : "");
    }
    if (base != nullptr) {
      const auto b = std::find_if(base->begin(), base->end(), [&](const auto& q) { return q.name == p.name; });
      base_value = "<td>" + (b == base->end() ? std::string() : UncertainCell(b->value, b->std)) + "</td>";
    }
    html += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td>{} … {}</td>{}<td>{}</td>{}</tr>\n",
                        HtmlEscape(p.name), format.Format(p.value), SigmaCell(format, p.std),
                        format.Format(p.lower_95), format.Format(p.upper_95), model_form, UnitCell(p.unit),
                        base_value);
  }
  return html + "</table>\n";
}

// The selected model's parameters, the answer, with the base fit's value of
// each beside it, and their model-form intervals over the beam damping laws
// when the diagnosis refitted the selected model under them.
std::string SelectedParameterTable(const DiagnosisResult& d) {
  return ParameterRows(d.final_fit.parameters, d.final_damping_laws.intervals, &d.base.parameters) +
         IntervalParts(d.final_damping_laws);
}

// The held-out channels' first harmonic at every step: measured, the base
// model and the selected one, per level (DiagnosisResult::response).
std::string HeldOutSelectedPlotSvg(const SelectedResponse& selected, const ReportCurves& curves,
                                   const std::string& channel, const std::vector<std::string>& levels) {
  std::string unit = "the channel quantity, SI";
  for (const auto& ch : curves.channels)
    if (ch.channel == channel) unit = UnitSymbol(ch.si_unit);
  StackedPlot plot{.title = "held-out " + channel + ": measured, base model and selected model (" + selected.name + ")",
                   .xlabel = "frequency [Hz]"};
  Panel panel{.settings = "set ylabel " + GnuplotText("|X₁| [" + unit + "]") + "\n", .height_px = 300};
  for (std::size_t l = 0; l < levels.size(); ++l) {
    Rows rows;
    for (const auto& p : *selected.points)
      if (p.level == levels[l] && p.channel == channel)
        rows.push_back({p.frequency_hz, std::abs(p.measured), std::abs(p.base_model), std::abs(p.final_model)});
    std::sort(rows.begin(), rows.end());
    plot.datablocks += Datablock(fmt::format("h{}", l), rows);
    const std::string c = SeriesColour(l);
    const std::string dots = "with points pt 7 ps 0.7 lc rgb '" + c + "'",
                      base = "with lines lw 1 dt 2 lc rgb '" + c + "'",
                      crosses = "with linespoints pt 2 lw 1.5 lc rgb '" + c + "'";
    panel.items.push_back({fmt::format("$h{} using 1:2", l), dots});
    panel.items.push_back({fmt::format("$h{} using 1:3", l), base});
    panel.items.push_back({fmt::format("$h{} using 1:4", l), crosses});
    plot.keys.push_back({dots, "measured " + levels[l]});
    plot.keys.push_back({base, "base model " + levels[l]});
    plot.keys.push_back({crosses, "selected model " + levels[l]});
  }
  plot.panels = {panel};
  return StackedPlotSvg(plot);
}

// The answer first: the parameters under the damping law the data accept;
// when they reject the loss factor the fit assumed, its parameters follow.
std::string ParameterTable(const ResultFile& result, const IdentificationOutcome& outcome) {
  const auto& laws = result.damping_laws.laws;
  const auto& intervals = result.damping_laws.intervals;
  const auto answer = std::find_if(laws.begin(), laws.end(),
                                   [&](const DampingLawFit& law) { return law.law == outcome.answer_damping_law; });
  if (!outcome.assumed_damping_law_rejected || answer == laws.end())
    return ParameterRows(result.parameters, intervals) + IntervalParts(result.damping_laws);
  return fmt::format("<p class=\"answer\"><b>The data reject the loss factor the fit assumes</b>; they accept the "
                     "<b>{}</b> damping law (reduced χ² {} against {}), whose parameters are the answer:</p>\n",
                     HtmlEscape(outcome.answer_damping_law), Number(outcome.answer_reduced_chi_square),
                     Number(outcome.reduced_chi_square)) +
         ParameterRows(answer->parameters, intervals) + IntervalParts(result.damping_laws) +
         "<p>Under the rejected loss factor (for comparison only):</p>\n" + ParameterRows(result.parameters, {});
}

// What a test engineer reads of a diagnosis (diagnosis.json of `beamid
// diagnose`): the verdict, the findings, only the residual groups that stand
// out of the noise, and one row per candidate; the full statistics stay in
// the JSON file.
std::string DiagnosisSection(const DiagnosisResult& diagnosis, const DiagnosisOutcome& stated) {
  std::string html = "<section id=\"diagnosis\"><h2>Diagnosis</h2>\n";
  std::string selected;
  for (const auto& name : stated.selected) selected += (selected.empty() ? "" : ", ") + HtmlEscape(name);
  html += "<p class=\"diagnosis-verdict\"><b>Verdict:</b> " + HtmlEscape(ToString(stated.verdict)) +
          (stated.blame == Blame::kNone ? ""
                                         : " — to blame: <b>" + HtmlEscape(ToString(stated.blame)) + "</b>") +
          (stated.ranked_by == RankedBy::kNone ? "" : " (ranked by " + HtmlEscape(ToString(stated.ranked_by)) + ")") +
          "</p>\n";
  // An engineer checks the recording before the model: its findings first.
  std::string recording;
  for (const auto& c : diagnosis.candidates)
    if (c.measurement && stated.blame == Blame::kRecording && !stated.selected.empty() &&
        c.name == stated.selected.front())
      recording += "<li>" + HtmlEscape(c.name) + ": " + HtmlEscape(c.rig_check) + "</li>";
  for (const auto& f : diagnosis.recording_findings) recording += "<li>" + HtmlEscape(f) + "</li>";
  if (!recording.empty()) html += "<h3>The recording</h3>\n<ul class=\"warning\">" + recording + "</ul>\n";
  html += "<p class=\"diagnosis-selected\"><b>Selected:</b> " + selected + "</p>\n";
  html += std::string("<p class=\"diagnosis-rest\">") +
          (stated.rest_within_noise ? "What the diagnosis leaves of the misfit lies within the noise."
                                    : "Part of the misfit remains beyond the noise after the diagnosis.") +
          "</p>\n";
  html += "<p class=\"diagnosis-summary\">" + HtmlEscape(diagnosis.summary) + "</p>\n";
  if (!diagnosis.location) {
    html += "<p class=\"warning\">The misfit could not be located: " + HtmlEscape(diagnosis.location_error) + "</p>\n";
  } else {
    const MisfitLocation& location = *diagnosis.location;
    if (!location.findings.empty()) {
      html += "<h3>Where the misfit sits</h3>\n<ul>";
      for (const auto& finding : location.findings) html += "<li>" + HtmlEscape(finding) + "</li>";
      html += "</ul>\n";
    }
    std::string rows;
    int significant = 0;
    for (const auto& g : location.groups) {
      if (!g.significant) continue;
      ++significant;
      rows += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
                          g.channel.empty() ? "all" : HtmlEscape(g.channel),
                          g.harmonic == 0 ? std::string("all") : std::to_string(g.harmonic),
                          g.level.empty() ? "all" : HtmlEscape(g.level), ToString(g.part), ToString(g.band),
                          Number(g.chi2), g.dof, Number(g.adjusted_p_value));
    }
    html += fmt::format("<h3>Residual groups beyond the noise ({} of {})</h3>\n", significant, location.groups.size());
    if (significant > 0)
      html += "<table><tr><th>channel</th><th>harmonic</th><th>level</th><th>part</th><th>band</th><th>χ²</th>"
              "<th>dof</th><th>adjusted p</th></tr>\n" + rows + "</table>\n";
  }
  html += "<h3>Candidates, each refitted: faults of the recording and missing physics, best first</h3>\n<table><tr><th>candidate</th><th>kind</th><th>signature score</th>"
          "<th>χ² before</th><th>χ² after</th><th>drop</th><th>p</th><th>significant</th>"
          "<th>extra parameters ± standard uncertainty</th></tr>\n";
  for (const auto& c : diagnosis.candidates) {
    std::string extra;
    for (const auto& p : c.fit.parameters) {
      if (std::find(c.extra_parameters.begin(), c.extra_parameters.end(), p.name) == c.extra_parameters.end()) continue;
      // A refit that did not move a parameter off its base value leaves it
      // undetermined (its std is that of a flat direction): say so.
      const bool determined = std::isfinite(p.std) && p.std < 100 * std::abs(p.value);
      const std::string symbol = UnitSymbol(p.unit);
      const std::string unit = symbol.empty() ? "" : " " + HtmlEscape(symbol);
      extra += fmt::format("{}{} = {}", extra.empty() ? "" : "<br>", HtmlEscape(p.name),
                           determined ? UncertainCell(p.value, p.std, p.unit)
                                      : Number(p.value) + unit + " (not determined by these data)");
    }
    // Without a refit there is no χ² after, drop or p: the row says why instead.
    const std::string outcome =
        c.Refitted() ? "<td>" + Number(c.fit.chi_square) + "</td><td>" + Number(c.residual_drop) + "</td><td>" +
                           Number(c.p_value) + "</td><td>" + (c.significant ? "yes" : "no") + "</td>"
                     : "<td colspan=\"4\">" +
                           std::string(c.status == RefitStatus::kNotRefitted ? "not refitted" : "refit failed") +
                           (c.status_message.empty() ? "" : ": " + HtmlEscape(c.status_message)) + "</td>";
    html += "<tr><td>" + HtmlEscape(c.name) + "</td><td>" + (c.measurement ? "recording" : "physics") + "</td><td>" +
            Number(c.signature_score) + "</td><td>" + Number(diagnosis.base.chi_square) + "</td>" + outcome + "<td>" +
            extra + "</td></tr>\n";
  }
  html += "</table>\n";
  return html + "</section>\n";
}

// What the selected model's backbone adds to the backbone figure's caption.
std::string SelectedBackboneCaption(const SelectedResponse* selected, const ReportCurves& curves) {
  if (!selected || !selected->backbone || selected->backbone->empty()) return "";
  const SelectedBackbone& b = *selected->backbone;
  if (!b.error.empty()) return " The selected model's backbone could not be traced: " + HtmlEscape(b.error) + ".";
  if (b.channel != curves.channels[static_cast<std::size_t>(curves.reference_channel)].channel)
    return " The selected model's backbone was traced at " + HtmlEscape(b.channel) + ", not at this sensor.";
  return " Blue: the backbone of the model the diagnosis selected (" + HtmlEscape(selected->name) +
         "), beside the base model's (black).";
}

constexpr SvgSize kResidualMapSize{.width_px = 760, .height_px = 360};
constexpr const char* kResidualMapScale =
    "on a logarithmic colour scale centred at 1 σ (white): blue cells lie within the noise, red ones beyond it "
    "point at what the model misses";

// The identified model's map; after a diagnosis that named a cause, the base
// model's and the selected model's (diagnosis.json), so that the cause's
// effect shows cell by cell.
std::string ResidualMaps(const ReportCurves& curves, const ReportInput& input, const std::optional<SelectedResponse>& selected) {
  if (selected) {
    const ResidualMap before = DiagnosisResidualMap(*selected->points, DiagnosedModel::kBase);
    const ResidualMap after = DiagnosisResidualMap(*selected->points, DiagnosedModel::kSelected);
    if (!before.rows.empty() && !after.rows.empty()) {
      // One colour scale for both: a cell's colour compares across the maps.
      const auto finite = [](const ResidualMap& map) {
        return map.whitened_norm.unaryExpr([](double v) { return std::isfinite(v) ? v : 0.0; }).maxCoeff();
      };
      const double largest = std::max(finite(before), finite(after));
      return PlotFigure("residual-map", GnuplotSvg(ResidualPlot(before, largest), kResidualMapSize),
                    fmt::format("Before: the base model the diagnosis refitted (χ² {} on the map; {} in its fit). Per "
                                "fitted channel, harmonic and step the misfit in units of its standard uncertainty σ, {}.",
                                Number(SumOfSquares(before)), Number(input.diagnosis->diagnosis.base.chi_square),
                                kResidualMapScale)) +
             PlotFigure("residual-map-selected", GnuplotSvg(ResidualPlot(after, largest), kResidualMapSize),
                    fmt::format("After: the selected model ({}), against the data it was fitted to (χ² {} on the "
                                "map; {} in its fit), on the same colour scale: what stays red, the cause does not explain.",
                                HtmlEscape(selected->name), Number(SumOfSquares(after)),
                                Number(input.diagnosis->diagnosis.final_fit.chi_square)));
    }
  }
  return PlotFigure("residual-map", GnuplotSvg(ResidualPlot(curves.residuals), kResidualMapSize),
                std::string("Per fitted channel, harmonic and step: the misfit in units of its standard uncertainty "
                            "σ, ") + kResidualMapScale + ".");
}

}  // namespace

std::string HtmlReport(const ReportInput& input, const ReportCurves& curves, const HtmlReportOptions& options) {
  const ResultFile& result = input.result;
  // What the page states, once: its text below reads it, and the page embeds it.
  const IdentificationOutcome outcome = OutcomeOf(input, curves);
  std::string title = "beamid report";
  if (!result.campaign.name.empty()) title += ": " + result.campaign.name;
  std::string fit_channels;
  for (const auto& channel : result.model.fit_channels)
    fit_channels += (fit_channels.empty() ? "" : ", ") + HtmlEscape(channel);
  std::string html = HtmlPageHead(title);
  html += fmt::format("<p>Result <code>{}</code>, campaign <code>{}</code>; model {} ({}); support law {}; fitted "
                      "channels {}, harmonics 1..{}; reduced χ² = {} (χ² {} over {} degrees of freedom).</p>\n",
                      HtmlEscape(input.result_file.string()), HtmlEscape(input.campaign_folder.string()),
                      schema::NameOf(outcome.model_kind, kModelKindNames),
                      HtmlEscape(FindModelFamily(outcome.model_kind).Description()), HtmlEscape(outcome.support_law),
                      fit_channels, result.model.num_fit_harmonics,
                      Number(outcome.reduced_chi_square), Number(outcome.chi_square), outcome.degrees_of_freedom);
  html += fmt::format("<p class=\"fit-verdict\"><b>{}</b> (reduced χ² {}, at most {:g} allowed){}</p>\n",
                      outcome.fit_within_noise ? "The model fits within the noise"
                                               : "The model misfits beyond the noise",
                      Number(outcome.reduced_chi_square), kMisfitReducedChiSquare,
                      outcome.fit_within_noise ? "."
                                               : ": it lacks some physics or the recordings hold a fault; "
                                                 "<code>beamid diagnose</code> tells which.");
  if (input.diagnosis) html += DiagnosisSection(input.diagnosis->diagnosis, *outcome.diagnosis);

  const std::optional<SelectedResponse> selected = SelectedModelOf(input, outcome);
  if (selected)
    html += "<section id=\"selected\"><h2>The selected model: " + HtmlEscape(selected->name) + "</h2>\n" +
            SelectedParameterTable(input.diagnosis->diagnosis) + "</section>\n";
  html += std::string("<section id=\"parameters\"><h2>") +
          (selected ? "The base model's fit (identify), which the diagnosis rejects" : "Identified parameters") +
          "</h2>\n" + ParameterTable(result, outcome);
  for (const auto& v : outcome.held_out)
    html += fmt::format("<p class=\"held-out\">Held-out {}: {}.</p>\n", HtmlEscape(v.channel),
                        HtmlEscape(HeldOutSummary(v.steps, v.worst_h1_relative_error, v.measurable_steps_h1,
                                                  v.worst_h3_relative_error, v.measurable_steps_h3)));
  html += Warnings(result.warnings) + "</section>\n";
  html += RecordingSection(curves, result);

  html += "<section id=\"frc\"><h2>Frequency response curves</h2>\n";
  for (std::size_t c = 0; c < curves.channels.size(); ++c) {
    html +=
        PlotFigure("frc-" + curves.channels[c].channel,
               ResponsePlotSvg(curves, c, selected ? &*selected : nullptr, {.log_amplitude = options.log_amplitude}),
               "First harmonic of " + HtmlEscape(curves.channels[c].channel) + ": its amplitude |X₁| (" +
                   (options.log_amplitude ? "logarithmic" : "linear") +
                   " axis), the amplitude per unit force |X₁|/|F₁| (logarithmic: the levels meet where the "
                   "response is linear and part where it is not) and the phase of the displacement against "
                   "the force (−90° at phase resonance). Measured steps (dots) and the identified model under "
                   "each level's mean force (harmonic balance and continuation; solid stable, dashed unstable)" +
                   (selected ? "; crosses: the model the diagnosis selected (" + HtmlEscape(selected->name) +
                                   "), at each measured step, beside the base model it replaces."
                             : std::string(".")));
    if (HasHigherHarmonics(curves, c))
      html += PlotFigure("harmonics-" + curves.channels[c].channel, HarmonicsPlotSvg(curves, c),
                     "Harmonics 2 and 3 of " + HtmlEscape(curves.channels[c].channel) +
                         " (logarithmic axes): measured at every step (dots) and the identified model's (lines). "
                         "A symmetric support makes mostly odd harmonics; an even one points at asymmetry.");
  }
  for (const auto& level : curves.levels)
    if (!level.model_complete)
      html += "<p class=\"warning\">The model curve of level " + HtmlEscape(level.level) +
              " stopped early: " + HtmlEscape(level.model_message) + "</p>\n";
  html += "</section>\n";

  html += "<section id=\"backbone\"><h2>Backbone</h2>\n" +
          PlotFigure("backbone-plot", BackbonePlotSvg(curves, selected ? &*selected : nullptr),
                 "The model's backbone as this sensor sees it (its first harmonic in quadrature with the force) "
                 "and each level's measured phase resonance with ±2σ bars, from the model-free analysis of "
                 "<code>beamid backbone --measured</code> (the step nearest quadrature moved there along one "
                 "nonlinear mode; on a level that jumps before quadrature, from the branch before the jump)." +
                     SelectedBackboneCaption(selected ? &*selected : nullptr, curves)) +
          (curves.phase_resonance.empty() ? "<p>No level crosses phase resonance.</p>\n" : ResonanceTable(curves)) +
          Warnings(curves.phase_resonance_warnings);
  if (!curves.measured_mode.damping.empty()) {
    const MeasuredNonlinearMode& mode = curves.measured_mode;
    // The verdict in the measured backbone's own words (kDampingRateTrendNames).
    std::string trend;
    if (outcome.damping_trend != Trend::kNotJudged)
      trend = fmt::format("The damping rate ζω_n against amplitude {}{} ({:+.1f} σ){}",
                          outcome.damping_trend == Trend::kNone ? "is " : "",
                          schema::NameOf(outcome.damping_trend, kDampingRateTrendNames), outcome.damping_trend_z,
                          outcome.damping_trend == Trend::kRises
                              ? ": dissipation that grows faster than a viscous damper's, as friction's does."
                              : ".");
    html += PlotFigure("damping-plot", DampingPlotSvg(curves),
                   "The measured damping ratio of each level by three estimators (±2σ), and the single nonlinear "
                   "mode fitted across levels (" +
                       HtmlEscape(mode.fit_form) + "). " + trend);
  }
  html += "</section>\n";

  html += "<section id=\"prediction\"><h2>Prediction at the held-out sensor</h2>\n";
  if (selected) {
    std::vector<std::string> held_out, levels;
    for (const auto& p : *selected->points) {
      if (p.held_out && std::find(held_out.begin(), held_out.end(), p.channel) == held_out.end())
        held_out.push_back(p.channel);
      if (std::find(levels.begin(), levels.end(), p.level) == levels.end()) levels.push_back(p.level);
    }
    for (const auto& channel : held_out)
      html += PlotFigure("held-out-selected-" + channel, HeldOutSelectedPlotSvg(*selected, curves, channel, levels),
                     "First-harmonic amplitude at the held-out " + HtmlEscape(channel) +
                         " at every step: measured, predicted by the base model and by the selected model (" +
                         HtmlEscape(selected->name) + "); neither fitted this channel.");
  }
  if (curves.time_histories.empty())
    html += "<p>This result has no held-out channel (identify with <code>--validate CHANNEL</code>).</p>\n";
  for (const auto& history : curves.time_histories)
    html += PlotFigure("time-" + history.level, TimePlotSvg(history, curves.held_out_channel),
                   "Steady-state acceleration at " + HtmlEscape(curves.held_out_channel) + ", level " +
                       HtmlEscape(history.level) +
                       ": predicted by the identified model (band: ±2 standard "
                       "uncertainties from the parameter covariance) and measured.");
  html += "</section>\n";

  html += "<section id=\"residuals\"><h2>Residual map</h2>\n" + ResidualMaps(curves, input, selected) + "</section>\n";
  return ScrollableTables(html) + ReportDataBlock(ToJson(outcome)) + "</body>\n</html>\n";
}

}  // namespace beamid::solver
