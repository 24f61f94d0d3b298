#include "solver/report/measured_backbone_summary.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/core.h>

#include "solver/report/uncertain_number.h"

namespace beamid::solver {
namespace {

bool Defined(const Estimate& e) { return e.valid && std::isfinite(e.value); }

// Why a level has no ζ: every estimator failed; the half-power one says
// why it did, the local fit lacks steps near the mode.
std::string WhyNoDampingRatio(const LevelResonance& l) {
  return l.half_power_note.empty() ? "too few steps near the mode" : l.half_power_note;
}

}  // namespace

std::string FlagWords(const LevelResonance& level) {
  std::vector<std::pair<LevelFlagKind, int>> kinds;
  for (const auto& f : level.flags) {
    const auto seen = std::find_if(kinds.begin(), kinds.end(), [&](const auto& k) { return k.first == f.kind; });
    if (seen == kinds.end())
      kinds.push_back({f.kind, 1});
    else
      ++seen->second;
  }
  std::string words;
  for (const auto& [kind, count] : kinds) {
    std::string name(LevelFlagName(kind));
    std::replace(name.begin(), name.end(), '_', ' ');
    words += fmt::format("{}[{}{}]", words.empty() ? "" : " ", name, count > 1 ? fmt::format(" ×{}", count) : "");
  }
  if (!level.in_global_fit) words += std::string(words.empty() ? "" : " ") + "[left out of the fit]";
  return words;
}

std::vector<std::string> LevelSummaryLines(const MeasuredBackbone& measured) {
  std::vector<std::string> lines;
  for (const auto& l : measured.levels) {
    std::string line = fmt::format("  {:>8} ({}-controlled): ", l.label,
                                   LevelControlText(measured.excitation_quantity, l.control));
    if (Defined(l.quadrature_frequency_hz)) {
      line += "f = " + WithUncertainty(l.quadrature_frequency_hz.value, l.quadrature_frequency_hz.std, "Hz");
      line += Defined(l.quadrature_amplitude_m) ? fmt::format(" at {:.4g} mm", 1e3 * l.quadrature_amplitude_m.value)
                                                : " at an amplitude not estimated";
    } else {
      line += "phase resonance not estimated (" +
              (l.quadrature_note.empty() ? std::string("no quadrature crossing") : l.quadrature_note) + ")";
    }
    line += ", ζ = " + (Defined(l.damping_ratio)
                            ? WithUncertainty(100 * l.damping_ratio.value, 100 * l.damping_ratio.std) + " %"
                            : "not estimated (" + WhyNoDampingRatio(l) + ")");
    if (Defined(l.free_decay_damping_ratio))
      line += ", free decay ζ = " +
              WithUncertainty(100 * l.free_decay_damping_ratio.value, 100 * l.free_decay_damping_ratio.std) + " %";
    const std::string flags = FlagWords(l);
    lines.push_back(flags.empty() ? line : line + "  " + flags);
  }
  return lines;
}

std::vector<std::string> CrossLevelSummaryLines(const MeasuredBackbone& measured) {
  std::vector<std::string> lines;
  const SingleModeFit& fit = measured.fit;
  lines.push_back(fit.ok ? fmt::format("  single-mode fit (AICc): {}, reduced χ² {}", fit.FormName(),
                                       NumberOrWhyNot(fit.ReducedChiSquare(), "{:.3g}", "no degrees of freedom left"))
                         : "  single-mode fit across levels: not made (too few points near the mode)");
  const DampingTrend& t = measured.damping_trend;
  const std::string why_not = "the fit gives no σ for it";
  if (!t.note.empty())
    lines.push_back("  damping against amplitude: not judged (" + t.note + ")");
  else if (t.verdict == Trend::kNotJudged)
    lines.push_back("  damping against amplitude: not judged (no single-mode fit across levels)");
  else
    lines.push_back(fmt::format(
        "  damping against amplitude: {} (ζω_n: slope {} /(s·m), {}; ζ alone {}: slope {} per m, {}, which a "
        "constant damper also gives where the frequency changes)",
        schema::NameOf(t.verdict, kDampingRateTrendNames),
        UncertainOrWhyNot(t.damping_rate_slope_per_s_m, t.damping_rate_slope_std_per_s_m, why_not),
        NumberOrWhyNot(t.damping_rate_z, "{:+.1f} σ", why_not),
        schema::NameOf(t.damping_ratio_verdict, kDampingRatioTrendNames),
        UncertainOrWhyNot(t.slope_per_m, t.slope_std_per_m, why_not), NumberOrWhyNot(t.z, "{:+.1f} σ", why_not)));
  return lines;
}

}  // namespace beamid::solver
