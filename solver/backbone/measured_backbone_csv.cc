#include "solver/backbone/measured_backbone_csv.h"

#include <cmath>
#include <sstream>

#include <fmt/core.h>

#include "hb/csv_cell.h"

namespace beamid::solver {
namespace {

using hb::CsvNumber;

// Value and σ, two cells; both empty when not estimated.
std::string Cell(const Estimate& e) {
  if (!e.valid) return ",";
  return CsvNumber(e.value, "{:.9g}") + "," + (std::isfinite(e.value) ? CsvNumber(e.std, "{:.3g}") : "");
}

}  // namespace

std::string MeasuredLevelsCsv(const MeasuredBackbone& measured) {
  const ExcitationLabels excitation = LabelsOf(measured.excitation_quantity);
  const std::size_t unit_at = excitation.column.rfind('_');
  const std::string excitation_std =
      excitation.column.substr(0, unit_at) + "_std" + excitation.column.substr(unit_at);
  std::ostringstream csv;
  csv << "level,control,quadrature_frequency_Hz,quadrature_frequency_std_Hz,amplitude_m,amplitude_std_m,"
         "response_amplitude,response_amplitude_std," << excitation.column << "," << excitation_std
      << ",zeta_quadrature,zeta_quadrature_std,"
         "zeta_local,zeta_local_std,zeta_half_power,zeta_half_power_std,peak_frequency_Hz,peak_frequency_std_Hz,"
         "local_natural_frequency_Hz,local_natural_frequency_std_Hz,regeneration_relative_rms,in_global_fit,flags,"
         "zeta,zeta_std\n";
  for (const auto& l : measured.levels) {
    // The flags' names, ';'-separated (the messages are in the .json).
    std::string flags;
    for (const auto& f : l.flags) {
      const std::string name(LevelFlagName(f.kind));
      if (flags.find(name) == std::string::npos) flags += (flags.empty() ? "" : ";") + name;
    }
    csv << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", hb::CsvText(l.label),
                       LevelControlText(measured.excitation_quantity, l.control), Cell(l.quadrature_frequency_hz),
                       Cell(l.quadrature_amplitude_m), Cell(l.quadrature_response_amplitude),
                       Cell(l.quadrature_force_N), Cell(l.quadrature_damping_ratio), Cell(l.local_damping_ratio),
                       Cell(l.half_power_damping_ratio), Cell(l.peak_frequency_hz),
                       Cell(l.local_natural_frequency_hz), CsvNumber(l.regeneration_relative_rms, "{:.4g}"),
                       l.in_global_fit ? 1 : 0, flags, Cell(l.damping_ratio));
  }
  return csv.str();
}

}  // namespace beamid::solver
