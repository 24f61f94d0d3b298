#include "solver/cli/measured_backbone_command.h"

#include <string_view>
#include <tuple>

#include <fmt/core.h>

#include "solver/backbone/measured_backbone.h"
#include "solver/cli/cli_output.h"
#include "solver/workflow/measure_backbone.h"

namespace beamid::cli {

void RunMeasuredBackbone(const workflow::MeasureBackboneRequest& request, const GlobalOptions& global) {
  const workflow::MeasureBackboneOutcome outcome = workflow::MeasureBackbone(request, CliObserver(global));
  const solver::MeasuredBackbone& measured = outcome.measured;
  const solver::ExcitationLabels excitation = solver::LabelsOf(measured.excitation_quantity);
  const auto control = [&](const solver::LevelResonance& l) { return workflow::LevelControlText(measured, l); };
  const auto& fit = measured.fit;
  const auto& trend = measured.damping_trend;
  if (global.quiet) return;
  for (const auto& w : measured.warnings) PrintToStderr(fmt::format("beamid backbone: warning: {}\n", w));
  // A flag's note, with a space before it, next to the number it concerns.
  const auto note = [](const solver::LevelResonance& l, std::string_view quantity) {
    const std::string text = l.FlagNote(quantity);
    return text.empty() ? text : "  " + text;
  };
  if (measured.excitation_quantity != "force")
    fmt::print("  excitation: {} [{}]; X/F is the {}; {}\n", excitation.control, excitation.unit, excitation.frf,
               excitation.caveat);
  for (const auto& l : measured.levels) {
    if (!l.quadrature_frequency_hz.valid)
      fmt::print("  {:>8} ({}-controlled): no phase resonance ({}), local fit ζ {}{}\n", l.label,
                 control(l), l.quadrature_note,
                 l.local_damping_ratio.valid ? fmt::format("{:.5f}", l.local_damping_ratio.value) : std::string("not available"),
                 note(l, "local_damping_ratio"));
    else
      fmt::print("  {:>8} ({}-controlled): {:.4f} ± {:.4f} Hz{} at {:.3e} m, ζ = {} (phase resonance {:.5f} ± {:.2g}{}, "
                 "local fit {}{}, half-power {}{})\n",
                 l.label, control(l), l.quadrature_frequency_hz.value,
                 l.quadrature_frequency_hz.std, note(l, "quadrature_frequency"), l.quadrature_amplitude_m.value,
                 l.damping_ratio.valid ? fmt::format("{:.5f} ± {:.2g}", l.damping_ratio.value, l.damping_ratio.std)
                                       : std::string("not available"),
                 l.quadrature_damping_ratio.value, l.quadrature_damping_ratio.std,
                 note(l, "quadrature_damping_ratio"),
                 l.local_damping_ratio.valid ? fmt::format("{:.5f}", l.local_damping_ratio.value)
                                             : std::string("not available: too few steps near the mode"),
                 note(l, "local_damping_ratio"),
                 l.half_power_damping_ratio.valid ? fmt::format("{:.5f}", l.half_power_damping_ratio.value)
                                                  : std::string("not available"),
                 note(l, "half_power_damping_ratio"));
    if (!l.damping_ratio_note.empty()) fmt::print("           ζ: {}\n", l.damping_ratio_note);
    if (l.flags.empty()) continue;
    for (const auto& [quantity, what, estimate] :
         {std::tuple{"peak_frequency", "peak", l.peak_frequency_hz},
          std::tuple{"local_natural_frequency", "local-fit natural frequency", l.local_natural_frequency_hz}})
      if (!l.FlagNote(quantity).empty())
        fmt::print("           {} = {}{}\n", what,
                   estimate.valid ? fmt::format("{:.4f} ± {:.2g} Hz", estimate.value, estimate.std) : "none in the band",
                   note(l, quantity));
    if (!l.FlagNote("half_power_damping_ratio").empty())
      fmt::print("           ζ (half-power) = {:.3f} %{}\n", 100 * l.half_power_damping_ratio.value,
                 note(l, "half_power_damping_ratio"));
    for (const auto& f : l.flags)
      if (f.kind == solver::LevelFlagKind::kJump) fmt::print("           jump: {}  [FLAG: jump]\n", f.message);
    for (const auto& f : l.flags)
      if (f.kind == solver::LevelFlagKind::kPhaseConvention)
        fmt::print("           phase: {}  [FLAG: phase convention]\n", f.message);
    if (!l.FlagNote("regeneration_relative_rms").empty())
      fmt::print("           regeneration RMS = {:.3g} % ({}){}\n", 100 * l.regeneration_relative_rms,
                 l.regeneration_noise_relative_rms > 0
                     ? fmt::format("noise {:.3g} %", 100 * l.regeneration_noise_relative_rms)
                     : std::string("no noise given"),
                 note(l, "regeneration_relative_rms"));
    fmt::print("           {}\n", l.in_global_fit ? "flagged, kept in the cross-level fit"
                                                   : "flagged: left out of the cross-level fit and the damping trend");
  }
  if (fit.ok) fmt::print("  single-mode fit (AICc): {}, reduced χ² {:.3g}\n", fit.FormName(), fit.ReducedChiSquare());
  if (!trend.note.empty())
    fmt::print("  damping against amplitude: not judged ({})\n", trend.note);
  else
    fmt::print("  damping against amplitude: {} (ζω_n: slope {:.3g} ± {:.2g} /(s·m), {:+.1f} σ; ζ alone {}: slope "
               "{:.3g} ± {:.2g} per m, {:+.1f} σ, which a constant damper also gives where the frequency changes)\n",
               schema::NameOf(trend.verdict, solver::kDampingRateTrendNames), trend.damping_rate_slope_per_s_m,
               trend.damping_rate_slope_std_per_s_m, trend.damping_rate_z,
               schema::NameOf(trend.damping_ratio_verdict, solver::kDampingRatioTrendNames), trend.slope_per_m, trend.slope_std_per_m, trend.z);
  fmt::print("wrote {0}.json, {0}.csv and {0}_curves.csv\n", request.output);
}

}  // namespace beamid::cli
