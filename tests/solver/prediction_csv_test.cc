// A prediction as CSV (solver/estimation/prediction_csv.h): a row per step
// and harmonic, as wide as the header; the compared sensor's amplitudes in
// the unit its recordings use; empty cells where nothing was compared.
#include "solver/estimation/prediction_csv.h"

#include <complex>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/csv_text.h"

namespace beamid::solver {
namespace {

using beamid::testing::Cells;
using beamid::testing::G9;
using beamid::testing::Lines;

constexpr double kStandardGravity = 9.80665;

PredictionFile File() {
  PredictionFile file{.position_m = 0.57, .compared_channel = "acc3", .compared_quantity = "acceleration_m_s2"};
  for (int s = 0; s < 2; ++s) {
    PredictionStep& step = file.steps.emplace_back();
    step.level = "low";
    step.file = "step_00" + std::to_string(s) + ".csv";
    step.frequency_hz = 53.5 + s;
    step.converged = s == 0;
    for (int k = 1; k <= 3; ++k) {
      PredictionHarmonic& h = step.harmonics.emplace_back();
      h.k = k;
      h.displacement_m = std::polar(1e-4 / k, -0.5 * k);
      h.displacement_std_real_m = 1e-7;
      h.displacement_std_imag_m = 2e-7;
      h.acceleration_m_s2 = -std::pow(k * 2 * std::numbers::pi * step.frequency_hz, 2) * h.displacement_m;
      h.acceleration_amplitude_m_s2 = std::abs(h.acceleration_m_s2);
      h.compared = k <= 2;  // the channel measured two harmonics
      h.measured = std::polar(19.6133 / k, 1.0);
      h.predicted = std::polar(19.0 / k, 1.1);
      h.relative_error = std::abs(h.predicted - h.measured) / std::abs(h.measured);
    }
  }
  return file;
}

TEST(PredictionCsv, TheComparedSensorIsInTheUnitOfItsRecordings) {
  const PredictionFile file = File();
  const std::vector<std::string> lines = Lines(PredictionCsv(file, {.unit = "g", .to_si_factor = kStandardGravity}));
  ASSERT_EQ(lines.size(), 1u + 2 * 3);
  const std::vector<std::string> header = Cells(lines[0]);
  EXPECT_EQ(header[12], "measured_amplitude_g");
  EXPECT_EQ(header[14], "predicted_amplitude_g");
  const std::vector<std::string> first = Cells(lines[1]);
  ASSERT_EQ(first.size(), header.size());
  EXPECT_EQ(first[0], "low");
  EXPECT_EQ(first[3], "yes");
  EXPECT_EQ(first[5], G9(1e-4));
  EXPECT_EQ(first[6], "-28.647890");  // -0.5 rad
  EXPECT_EQ(first[12], G9(19.6133 / kStandardGravity));  // 2 g
  EXPECT_EQ(first[13], "57.295780");                      // 1 rad
  EXPECT_EQ(first[14], G9(19.0 / kStandardGravity));
  const std::vector<std::string> third_harmonic = Cells(lines[3]);
  ASSERT_EQ(third_harmonic.size(), header.size());
  EXPECT_EQ(third_harmonic[4], "3");
  EXPECT_EQ(third_harmonic[11], "acc3");
  EXPECT_EQ(third_harmonic[12], "");  // not measured
  EXPECT_EQ(Cells(lines[4])[3], "no");  // the second step did not converge
}

TEST(PredictionCsv, WithoutAUnitOfItsOwnTheColumnsAreSiAndWithoutASensorThereAreNone) {
  PredictionFile file = File();
  EXPECT_EQ(Cells(Lines(PredictionCsv(file))[0])[12], "measured_amplitude_m_s2");
  EXPECT_EQ(Cells(Lines(PredictionCsv(file, {.unit = "m/s^2"}))[0])[12], "measured_amplitude_m_s2");
  file.compared_channel.clear();
  file.compared_quantity.clear();
  for (const std::string& line : Lines(PredictionCsv(file))) EXPECT_EQ(Cells(line).size(), 11u) << line;
}

}  // namespace
}  // namespace beamid::solver
