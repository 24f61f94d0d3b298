// The response plots of `beamid report`, one figure per channel (stacked
// panels on one frequency axis, solver/report/stacked_plot.h):
//  - |X₁|, the first harmonic's amplitude (linear, or logarithmic with
//    `--log-amplitude`);
//  - |X₁|/|F₁|, the amplitude per unit force (receptance, mobility or
//    accelerance after the channel's quantity), always logarithmic: the
//    levels, whose amplitudes span decades, meet on one axis where the
//    response is linear and part where it is not;
//  - the phase of the displacement against the force (DisplacementPhaseDeg,
//    solver/report/report_curves.h), −90° at a phase resonance;
// and, where the phasors or the model hold them, a second figure with the
// amplitudes of harmonics 2 and 3 (logarithmic). Measured steps are dots,
// the model's curves lines (dashed where unstable); a diagnosis's selected
// model adds crosses at the measured steps.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "solver/diagnosis/diagnosis.h"
#include "solver/report/report_curves.h"
#include "solver/report/stacked_plot.h"

namespace beamid::solver {

struct ResponsePlotOptions {
  bool log_amplitude = false;  // |X₁| on a logarithmic axis too
};

// A diagnosis's selected model, drawn beside the base model.
struct SelectedResponse {
  std::string name;                                    // "support_friction", "a + b"
  const std::vector<ResponsePoint>* points = nullptr;  // DiagnosisResult::response
  const SelectedBackbone* backbone = nullptr;          // DiagnosisResult::final_backbone
};

// What the response figure draws of one channel of one level, a row per
// point: frequency [Hz], |X₁| [SI of the channel], |X₁|/|F₁| [SI/N], phase
// [°]. Measured: campaign order, each step's own |F₁| (the level's mean
// when the step's is unknown); model: continuation order, the level's force.
using ResponseRow = std::array<double, 4>;
std::vector<ResponseRow> MeasuredResponseRows(const LevelCurves& level, std::size_t channel);
std::vector<ResponseRow> ModelResponseRows(const LevelCurves& level, std::size_t channel);

// The panels every response figure shares: |X₁|/|F₁| on a logarithmic axis
// (`ylabel` names it with its unit) and the displacement's phase against the
// force, −180° … 180° (DisplacementPhaseDeg).
Panel PerForcePanel(const std::string& ylabel);
Panel PhasePanel();

std::string ResponsePlotSvg(const ReportCurves& curves, std::size_t channel, const SelectedResponse* selected,
                            const ResponsePlotOptions& options);

// Whether any step or model point of the channel has a finite, positive
// amplitude of harmonic 2 or 3.
bool HasHigherHarmonics(const ReportCurves& curves, std::size_t channel);
std::string HarmonicsPlotSvg(const ReportCurves& curves, std::size_t channel);

}  // namespace beamid::solver
