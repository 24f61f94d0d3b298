#include "solver/report/response_plots.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include <fmt/core.h>

#include "solver/report/gnuplot_script.h"
#include "solver/report/stacked_plot.h"
#include "solver/report/uncertain_number.h"

namespace beamid::solver {
namespace {

using Rows = std::vector<std::vector<double>>;

double At(const std::vector<double>& values, std::size_t i) { return i < values.size() ? values[i] : NAN; }

double HigherAt(const std::vector<std::vector<double>>& values, std::size_t channel, int k) {
  if (channel >= values.size() || k - 2 >= static_cast<int>(values[channel].size())) return NAN;
  return values[channel][static_cast<std::size_t>(k - 2)];
}

std::string LevelLabel(const LevelCurves& level) {
  return fmt::format("{} ({:.3g} N)", level.level, level.force_amplitude_N);
}

// The model's points split into a stable and an unstable set of line
// segments (a blank row ends a segment; a switch point belongs to both so
// that the curve stays connected). `row(i)` gives point i's columns; a phase
// that wraps past ±180° also ends a segment (`wrap_column`, or -1).
void SplitByStability(const LevelCurves& level, const std::function<std::vector<double>(std::size_t)>& row,
                      int wrap_column, Rows& stable, Rows& unstable) {
  for (std::size_t i = 0; i < level.model.size(); ++i) {
    const std::vector<double> r = row(i);
    const bool is_stable = level.model[i].stable;
    Rows& mine = is_stable ? stable : unstable;
    Rows& other = is_stable ? unstable : stable;
    if (i > 0) {
      const std::vector<double> previous = row(i - 1);
      const bool wraps = wrap_column >= 0 && std::abs(r[wrap_column] - previous[wrap_column]) > 180.0;
      if (wraps) {
        mine.push_back({});
        if (level.model[i - 1].stable != is_stable) other.push_back({});
      } else if (level.model[i - 1].stable != is_stable) {
        other.push_back(r);
        other.push_back({});
        mine.push_back(previous);
      }
    }
    mine.push_back(r);
  }
}

// The frequency range every panel shares: the measured steps and the model's curves.
std::string FrequencyRange(const ReportCurves& curves) {
  double low = 1e300, high = -1e300;
  for (const auto& level : curves.levels) {
    for (const auto& m : level.measured) low = std::min(low, m.frequency_hz), high = std::max(high, m.frequency_hz);
    for (const auto& p : level.model) low = std::min(low, p.frequency_hz), high = std::max(high, p.frequency_hz);
  }
  if (!(high > low)) return "";
  const double margin = 0.01 * (high - low);
  return fmt::format("set xrange [{:.9g}:{:.9g}]\n", low - margin, high + margin);
}

// The selected model's points of one level and channel, in frequency order:
// frequency, |X₁|, |X₁|/|F₁| (the level's force), phase.
Rows SelectedRows(const SelectedResponse& selected, const LevelCurves& level, const ReportChannel& channel) {
  Rows rows;
  for (const auto& p : *selected.points)
    if (p.level == level.level && p.channel == channel.channel)
      rows.push_back({p.frequency_hz, std::abs(p.final_model), std::abs(p.final_model) / level.force_amplitude_N,
                      DisplacementPhaseDeg(p.final_model, channel.derivative_order)});
  std::sort(rows.begin(), rows.end());
  return rows;
}

std::string AxisUnit(const ReportChannel& ch) { return UnitSymbol(ch.si_unit); }

}  // namespace

std::vector<ResponseRow> MeasuredResponseRows(const LevelCurves& level, std::size_t channel) {
  std::vector<ResponseRow> rows;
  for (const auto& m : level.measured) {
    const double amplitude = At(m.amplitude, channel);
    const double force =
        std::isfinite(m.force_amplitude_N) && m.force_amplitude_N > 0 ? m.force_amplitude_N : level.force_amplitude_N;
    rows.push_back({m.frequency_hz, amplitude, amplitude / force, At(m.phase_deg, channel)});
  }
  return rows;
}

std::vector<ResponseRow> ModelResponseRows(const LevelCurves& level, std::size_t channel) {
  std::vector<ResponseRow> rows;
  for (const auto& p : level.model) {
    const double amplitude = At(p.amplitude, channel);
    rows.push_back({p.frequency_hz, amplitude, amplitude / level.force_amplitude_N, At(p.phase_deg, channel)});
  }
  return rows;
}

Panel PerForcePanel(const std::string& ylabel) {
  return {.settings = "set ylabel " + GnuplotText(ylabel) + "\nset logscale y\nset format y '%g'\n", .height_px = 210};
}

Panel PhasePanel() {
  return {.settings = "set ylabel 'phase [°]'\nset yrange [-180:180]\nset ytics -180,90,180\n", .height_px = 150};
}

std::string ResponsePlotSvg(const ReportCurves& curves, std::size_t channel, const SelectedResponse* selected,
                            const ResponsePlotOptions& options) {
  const ReportChannel& ch = curves.channels[channel];
  const std::string unit = AxisUnit(ch);
  StackedPlot plot{.title = fmt::format("{} at x = {:.3f} m ({}): first harmonic", ch.channel, ch.position_m,
                                        ch.fitted ? "fitted" : "held out"),
                   .xlabel = "frequency [Hz]",
                   .x_settings = FrequencyRange(curves)};
  Panel amplitude{.settings = "set ylabel " + GnuplotText(fmt::format("|X₁| [{}]", unit)) + "\n" +
                              (options.log_amplitude ? "set logscale y\nset format y '%g'\n" : ""),
                  .height_px = 210};
  Panel per_force = PerForcePanel(fmt::format("|X₁|/|F₁| [{}/N]", unit));
  Panel phase = PhasePanel();
  Rows flagged;
  bool any_unstable = false, any_phase = false;
  for (std::size_t l = 0; l < curves.levels.size(); ++l) {
    const LevelCurves& level = curves.levels[l];
    const std::vector<ResponseRow> model = ModelResponseRows(level, channel);
    Rows stable, unstable, phase_stable, phase_unstable, measured;
    SplitByStability(
        level, [&](std::size_t i) { return std::vector<double>(model[i].begin(), model[i].end()); }, -1, stable,
        unstable);
    SplitByStability(
        level,
        [&](std::size_t i) {
          return std::vector<double>{model[i][0], model[i][3]};
        },
        1, phase_stable, phase_unstable);
    for (const auto& r : MeasuredResponseRows(level, channel)) {
      measured.push_back({r[0], r[1], r[2], r[3]});
      any_phase = any_phase || std::isfinite(r[3]);
    }
    for (const auto& r : model) any_phase = any_phase || std::isfinite(r[3]);
    for (std::size_t i = 0; i < level.measured.size(); ++i)
      if (!level.measured[i].flag.empty()) flagged.push_back(measured[i]);
    any_unstable = any_unstable || !unstable.empty();
    const std::string c = SeriesColour(l);
    plot.datablocks += Datablock(fmt::format("s{}", l), stable) + Datablock(fmt::format("u{}", l), unstable) +
                       Datablock(fmt::format("ps{}", l), phase_stable) +
                       Datablock(fmt::format("pu{}", l), phase_unstable) + Datablock(fmt::format("m{}", l), measured);
    const std::string solid = "with lines lw 2 lc rgb '" + c + "'";
    const std::string dashed = "with lines lw 2 dt 2 lc rgb '" + c + "'";
    const std::string dots = "with points pt 7 ps 0.7 lc rgb '" + c + "'";
    for (int column : {2, 3}) {
      Panel& panel = column == 2 ? amplitude : per_force;
      panel.items.push_back({fmt::format("$s{} using 1:{}", l, column), solid});
      panel.items.push_back({fmt::format("$u{} using 1:{}", l, column), dashed});
      panel.items.push_back({fmt::format("$m{} using 1:{}", l, column), dots});
    }
    phase.items.push_back({fmt::format("$ps{} using 1:2", l), solid});
    phase.items.push_back({fmt::format("$pu{} using 1:2", l), dashed});
    phase.items.push_back({fmt::format("$m{} using 1:4", l), dots});
    plot.keys.push_back({solid, (selected ? "base model " : "model ") + LevelLabel(level)});
    plot.keys.push_back({dots, "measured " + LevelLabel(level)});
    if (selected) {
      const Rows points = SelectedRows(*selected, level, ch);
      if (points.empty()) continue;
      plot.datablocks += Datablock(fmt::format("x{}", l), points);
      const std::string crosses = "with linespoints pt 2 ps 0.9 lw 1 lc rgb '" + c + "'";
      amplitude.items.push_back({fmt::format("$x{} using 1:2", l), crosses});
      per_force.items.push_back({fmt::format("$x{} using 1:3", l), crosses});
      phase.items.push_back({fmt::format("$x{} using 1:4", l), crosses});
      plot.keys.push_back({crosses, "selected model (" + selected->name + ") " + level.level});
    }
  }
  if (any_unstable) plot.keys.push_back({"with lines lw 2 dt 2 lc rgb '#555555'", "model, unstable branch"});
  if (!flagged.empty()) {
    plot.datablocks += Datablock("flagged", flagged);
    const std::string circle = "with points pt 6 ps 2.2 lw 2 lc rgb 'black'";
    amplitude.items.push_back({"$flagged using 1:2", circle});
    per_force.items.push_back({"$flagged using 1:3", circle});
    phase.items.push_back({"$flagged using 1:4", circle});
    plot.keys.push_back({circle, "flagged step (see the recording section)"});
  }
  plot.panels = {amplitude, per_force};
  if (any_phase) plot.panels.push_back(phase);
  return StackedPlotSvg(plot);
}

bool HasHigherHarmonics(const ReportCurves& curves, std::size_t channel) {
  for (const auto& level : curves.levels)
    for (int k = 2; k <= kReportHarmonics; ++k) {
      for (const auto& m : level.measured)
        if (HigherAt(m.higher_harmonics, channel, k) > 0) return true;
      for (const auto& p : level.model)
        if (HigherAt(p.higher_harmonics, channel, k) > 0) return true;
    }
  return false;
}

std::string HarmonicsPlotSvg(const ReportCurves& curves, std::size_t channel) {
  const ReportChannel& ch = curves.channels[channel];
  StackedPlot plot{.title = fmt::format("{} at x = {:.3f} m: harmonics 2 and 3", ch.channel, ch.position_m),
                   .xlabel = "frequency [Hz]",
                   .x_settings = FrequencyRange(curves)};
  for (int k = 2; k <= kReportHarmonics; ++k) {
    Panel panel{.settings = "set ylabel " + GnuplotText(fmt::format("|X{}| [{}]", k == 2 ? "₂" : "₃", AxisUnit(ch))) +
                            "\nset logscale y\nset format y '%g'\n",
                .height_px = 170};
    bool any = false;
    for (std::size_t l = 0; l < curves.levels.size(); ++l) {
      const LevelCurves& level = curves.levels[l];
      Rows stable, unstable, measured;
      SplitByStability(
          level,
          [&](std::size_t i) {
            return std::vector<double>{level.model[i].frequency_hz,
                                       HigherAt(level.model[i].higher_harmonics, channel, k)};
          },
          -1, stable, unstable);
      for (const auto& m : level.measured) {
        const double a = HigherAt(m.higher_harmonics, channel, k);
        measured.push_back({m.frequency_hz, a});
        any = any || a > 0;
      }
      for (const auto& p : level.model) any = any || HigherAt(p.higher_harmonics, channel, k) > 0;
      const std::string c = SeriesColour(l);
      const std::string name = fmt::format("h{}l{}", k, l);
      plot.datablocks +=
          Datablock("s" + name, stable) + Datablock("u" + name, unstable) + Datablock("m" + name, measured);
      panel.items.push_back({"$s" + name, "with lines lw 2 lc rgb '" + c + "'"});
      panel.items.push_back({"$u" + name, "with lines lw 2 dt 2 lc rgb '" + c + "'"});
      panel.items.push_back({"$m" + name, "with points pt 7 ps 0.7 lc rgb '" + c + "'"});
    }
    if (any) plot.panels.push_back(std::move(panel));
  }
  for (std::size_t l = 0; l < curves.levels.size(); ++l) {
    plot.keys.push_back(
        {fmt::format("with lines lw 2 lc rgb '{}'", SeriesColour(l)), "model " + LevelLabel(curves.levels[l])});
    plot.keys.push_back({fmt::format("with points pt 7 ps 0.7 lc rgb '{}'", SeriesColour(l)),
                         "measured " + LevelLabel(curves.levels[l])});
  }
  return StackedPlotSvg(plot);
}

}  // namespace beamid::solver
