#include "solver/estimation/prediction_csv.h"

#include <cmath>
#include <numbers>

#include <fmt/core.h>

#include "hb/csv_cell.h"

namespace beamid::solver {
namespace {

double Degrees(std::complex<double> z) { return std::arg(z) * 180 / std::numbers::pi; }

// The amplitude columns' unit as a name's suffix: the channel's own ("g",
// "mm/s" as "mm_s", "m/s^2" as "m_s2"), else the SI unit of the file's
// compared_quantity ("acceleration_m_s2": "m_s2").
std::string UnitInName(const std::string& compared_quantity, const CsvChannelUnit& unit) {
  if (unit.unit.empty()) return compared_quantity.substr(compared_quantity.find('_') + 1);
  std::string name;
  for (const char c : unit.unit)
    if (c != '^') name += c == '/' ? '_' : c;
  return name;
}

}  // namespace

std::string PredictionCsv(const PredictionFile& file, const CsvChannelUnit& compared_unit) {
  using hb::CsvNumber;
  const bool compared = !file.compared_channel.empty();
  std::string csv =
      "level,file,frequency_Hz,converged,k,displacement_amplitude_m,displacement_phase_deg,displacement_std_real_m,"
      "displacement_std_imag_m,acceleration_amplitude_m_s2,acceleration_phase_deg";
  if (compared)
    csv += fmt::format(",channel,measured_amplitude_{0},measured_phase_deg,predicted_amplitude_{0},predicted_phase_deg,"
                       "relative_error",
                       UnitInName(file.compared_quantity, compared_unit));
  csv += "\n";
  for (const PredictionStep& step : file.steps)
    for (const PredictionHarmonic& h : step.harmonics) {
      csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{}", hb::CsvText(step.level), hb::CsvText(step.file),
                         CsvNumber(step.frequency_hz, "{:.9g}"), step.converged ? "yes" : "no", h.k,
                         CsvNumber(std::abs(h.displacement_m), "{:.9g}"), CsvNumber(Degrees(h.displacement_m), "{:.6f}"),
                         CsvNumber(h.displacement_std_real_m, "{:.3g}"), CsvNumber(h.displacement_std_imag_m, "{:.3g}"),
                         CsvNumber(h.acceleration_amplitude_m_s2, "{:.9g}"),
                         CsvNumber(Degrees(h.acceleration_m_s2), "{:.6f}"));
      if (compared) {
        const double scale = 1.0 / compared_unit.to_si_factor;
        csv += h.compared ? fmt::format(",{},{},{},{},{},{}", hb::CsvText(file.compared_channel),
                                        CsvNumber(std::abs(h.measured) * scale, "{:.9g}"),
                                        CsvNumber(Degrees(h.measured), "{:.6f}"),
                                        CsvNumber(std::abs(h.predicted) * scale, "{:.9g}"),
                                        CsvNumber(Degrees(h.predicted), "{:.6f}"), CsvNumber(h.relative_error, "{:.4g}"))
                          : "," + hb::CsvText(file.compared_channel) + ",,,,,";
      }
      csv += "\n";
    }
  return csv;
}

}  // namespace beamid::solver
