// A prediction (solver/estimation/prediction_io.h) as a CSV table a
// spreadsheet opens (`beamid predict --csv FILE`, docs/result-format.md):
// one row per step and harmonic k with the model's displacement (amplitude,
// phase, σ of its real and imaginary parts) and acceleration at the
// position; with a compared campaign sensor, its measured and the predicted
// amplitude and phase in the sensor's quantity and in the unit its recordings
// use (campaign.json's: an accelerometer recorded in g is compared in g),
// and their relative error. Phases in degrees, beamid's convention (docs/
// fourier-convention.md). Cells not computed are empty (hb/csv_cell.h).
#pragma once

#include <string>

#include "solver/estimation/prediction_io.h"

namespace beamid::solver {

// The compared channel's unit as its recordings give it; "" for SI.
struct CsvChannelUnit {
  std::string unit;           // "g", "mm/s", ...
  double to_si_factor = 1.0;  // SI value = factor · value in `unit`
};

std::string PredictionCsv(const PredictionFile& file, const CsvChannelUnit& compared_unit = {});

}  // namespace beamid::solver
