#include "solver/report/level_frf_plot.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include <fmt/core.h>

#include "solver/report/gnuplot_script.h"
#include "solver/report/report_curves.h"
#include "solver/report/response_plots.h"
#include "solver/report/uncertain_number.h"

namespace beamid::solver {
namespace {

using Rows = std::vector<std::vector<double>>;

// The displacement's phase against the force in degrees, as every response figure gives it.
double PhaseDeg(double phase_rad) { return DisplacementPhaseDeg(std::polar(1.0, phase_rad), 0); }

// A curve's rows (frequency, value), a blank row wherever the value is not
// finite or, for a phase, wraps by more than half a turn, so that gnuplot
// draws no line across the gap.
Rows CurveRows(const std::vector<LevelFrfPoint>& points, bool phase) {
  Rows rows;
  double previous = NAN;
  for (const auto& p : points) {
    const double value = phase ? PhaseDeg(p.phase_rad) : p.receptance_m_N;
    const bool defined = std::isfinite(p.frequency_hz) && std::isfinite(value) && (phase || value > 0);
    if (!defined || (phase && std::abs(value - previous) > 180.0)) {
      if (!rows.empty() && !rows.back().empty()) rows.push_back({});
    }
    if (defined) rows.push_back({p.frequency_hz, value});
    previous = defined ? value : NAN;
  }
  return rows;
}

}  // namespace

StackedPlot LevelFrfPlot(const LevelResonance& level, const ExcitationLabels& excitation) {
  const std::string unit = UnitSymbol(excitation.unit);
  StackedPlot plot{.title = "level " + level.label + ": first harmonic", .xlabel = "frequency [Hz]"};
  Panel per_force =
      PerForcePanel("|X/F| [m/" + (unit.find('/') == std::string::npos ? unit : "(" + unit + ")") + "]");
  Panel phase = PhasePanel();
  const auto add = [&](const std::string& block, int column, bool on_phase, const std::string& style,
                       const std::string& title) {
    per_force.items.push_back({"$" + block + " using 1:2", style});
    if (on_phase) phase.items.push_back({"$" + block + " using 1:" + std::to_string(column), style});
    plot.keys.push_back({style, title});
  };

  Rows measured;
  double low = INFINITY, high = -INFINITY;
  for (const auto& p : level.measured_frf) {
    measured.push_back({p.frequency_hz, p.receptance_m_N, PhaseDeg(p.phase_rad)});
    low = std::min(low, p.frequency_hz), high = std::max(high, p.frequency_hz);
  }
  // The measured band, not gnuplot's rounding of it to whole tics.
  const double margin = 0.01 * (high - low);
  if (high > low) plot.x_settings = fmt::format("set xrange [{:.9g}:{:.9g}]\n", low - margin, high + margin);
  plot.datablocks += Datablock("measured", measured);
  add("measured", 3, true, std::string("with points pt 7 ps 0.7 lc rgb '") + SeriesColour(0) + "'", "measured steps");

  if (!level.fit_frf.empty()) {
    plot.datablocks += Datablock("fit", CurveRows(level.fit_frf, false)) +
                       Datablock("fit_phase", CurveRows(level.fit_frf, true));
    const std::string line = "with lines lw 2 lc rgb '#2050a0'";
    per_force.items.push_back({"$fit using 1:2", line});
    phase.items.push_back({"$fit_phase using 1:2", line});
    plot.keys.push_back({line, "single-mode fit across levels"});
  }

  const Estimate& peak_f = level.peak_frequency_hz;
  const Estimate& peak = level.peak_receptance_m_N;
  if (peak_f.valid && peak.valid) {
    plot.datablocks += Datablock("peak", {{peak_f.value, peak.value}});
    add("peak", 2, false, "with points pt 9 ps 1.8 lc rgb 'black'", "peak");
    Rows half_power;
    for (const Estimate* f : {&level.half_power_lower_frequency_hz, &level.half_power_upper_frequency_hz})
      if (f->valid) half_power.push_back({f->value, peak.value / std::sqrt(2.0)});
    if (!half_power.empty()) {
      plot.datablocks += Datablock("half_power", half_power);
      add("half_power", 2, false, "with points pt 13 ps 1.6 lc rgb '#7030a0'", "half-power points (peak/√2)");
    }
  }

  // The phase resonance at ±90°, on the side the measured phase passes (+90°
  // where the mode's shape has the other sign at the sensor).
  const Estimate& quadrature = level.quadrature_frequency_hz;
  if (quadrature.valid && std::isfinite(quadrature.value) && !measured.empty()) {
    const auto nearest = std::min_element(measured.begin(), measured.end(), [&](const auto& a, const auto& b) {
      return std::abs(a[0] - quadrature.value) < std::abs(b[0] - quadrature.value);
    });
    plot.datablocks += Datablock("quadrature", {{quadrature.value, (*nearest)[2] > 0 ? 90.0 : -90.0}});
    const std::string style = "with points pt 5 ps 1.4 lc rgb 'black'";
    phase.items.push_back({"$quadrature using 1:2", style});
    plot.keys.push_back({style, "phase resonance"});
  }

  // Each jump from the step before it to the step after, in run order (the
  // order `jumps` counts the steps in).
  Rows jumps;
  const auto size = static_cast<int>(level.measured_frf.size());
  for (const auto& j : level.jumps) {
    if (j.from_step < 0 || j.to_step < 0 || j.from_step >= size || j.to_step >= size) continue;
    for (int step : {j.from_step, j.to_step}) jumps.push_back(measured[static_cast<std::size_t>(step)]);
    jumps.push_back({});
  }
  if (!jumps.empty()) {
    plot.datablocks += Datablock("jumps", jumps);
    add("jumps", 3, true, "with linespoints lw 2 dt 2 pt 6 ps 1.6 lc rgb '#a50f15'", "jump of the sweep");
  }
  plot.panels = {per_force, phase};
  return plot;
}

std::string LevelFrfPlotSvg(const LevelResonance& level, const ExcitationLabels& excitation) {
  if (level.measured_frf.empty()) return "";
  return StackedPlotSvg(LevelFrfPlot(level, excitation));
}

}  // namespace beamid::solver
