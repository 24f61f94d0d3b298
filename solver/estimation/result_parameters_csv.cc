#include "solver/estimation/result_parameters_csv.h"

#include <algorithm>

#include <fmt/core.h>

#include "hb/csv_cell.h"
#include "solver/estimation/damping_laws.h"

namespace beamid::solver {

std::string ResultParametersCsv(const ResultFile& file) {
  using hb::CsvNumber;
  std::string csv =
      "parameter,unit,value,std,lower_95,upper_95,std_model_error,total_lower_95,total_upper_95,total_holds\n";
  const std::string parts = file.damping_laws.empty() ? "" : TotalIntervalParts(file.damping_laws);
  for (const ResultParameter& p : file.parameters) {
    const auto& intervals = file.damping_laws.intervals;
    const auto total = std::find_if(intervals.begin(), intervals.end(),
                                    [&](const ModelFormInterval& m) { return m.name == p.name; });
    const bool has_total = total != intervals.end();
    csv += fmt::format("{},{},{},{},{},{},{},{},{},{}\n", hb::CsvText(p.name), hb::CsvText(p.unit),
                       CsvNumber(p.value, "{:.9g}"), CsvNumber(p.std, "{:.3g}"), CsvNumber(p.lower_95, "{:.9g}"),
                       CsvNumber(p.upper_95, "{:.9g}"), CsvNumber(p.std_model_error, "{:.3g}"),
                       has_total ? CsvNumber(total->lower_95, "{:.9g}") : "",
                       has_total ? CsvNumber(total->upper_95, "{:.9g}") : "", has_total ? hb::CsvText(parts) : "");
  }
  return csv;
}

}  // namespace beamid::solver
