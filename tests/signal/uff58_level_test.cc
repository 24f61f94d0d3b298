// A stepped sine's result as a frequency-domain system exports it, a
// universal file of spectra and frequency responses (signal/uff58_level.h),
// written here by the test's own writer from the example tables: it reads
// the phasors of the table, and the measured backbone of the files equals
// the table's; what it cannot read is refused naming the fix.
#include "signal/uff58_level.h"

#include <cmath>
#include <complex>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "signal/input_error.h"
#include "signal/phasor_table.h"
#include "solver/backbone/measured_backbone.h"
#include "solver/workflow/measure_backbone.h"
#include "tests/signal/uff58_writer.h"
#include "tests/support/file_bytes.h"
#include "tests/support/temp_path.h"

namespace beamid::signal {
namespace {

using beamid::testing::UffChannel;
using beamid::testing::UffDataset58;
using beamid::testing::UffEncoding;

constexpr double kStandardGravity = 9.80665;

// The table's phasors without their stated σ (a universal file states none).
FirstHarmonicLevel TableLevel(const std::string& name) {
  const FirstHarmonicLevel table = ReadPhasorTable("examples/phasor_tables/" + name + ".csv");
  FirstHarmonicLevel level = table;
  level.points.clear();
  for (const auto& p : table.points) {
    FirstHarmonicPoint bare{.frequency_hz = p.frequency_hz};
    bare.force.value = p.force.value;
    bare.response.value = p.response.value;
    level.points.push_back(bare);
  }
  return level;
}

enum class Response { kFrequencyResponse, kSpectrum };

// The level as a universal file: the force's spectrum and the response's
// frequency response (X/F) or spectrum, both turned by a phase the reader
// must take out, at uneven frequencies (each before its point), the
// response in g.
std::string Universal(const FirstHarmonicLevel& level, Response response, UffEncoding encoding) {
  const std::complex<double> turn = std::polar(1.0, 0.7);  // the analyser's own phase reference
  UffChannel force{.id_line1 = "Force", .node = 1, .direction = 3, .function_type = 12, .ordinate_type = 0,
                   .spacing = 0, .ordinate_data_type = 13, .unit = "N", .abscissa_unit = "Hz",
                   .abscissa_data_type = 18};
  UffChannel acc{.id_line1 = "acc2", .node = 2, .direction = 3, .spacing = 0, .ordinate_data_type = 12, .unit = "g",
                 .abscissa_unit = "Hz", .abscissa_data_type = 18};
  const bool single = encoding == UffEncoding::kAsciiSingle;
  force.ordinate_type = acc.ordinate_type = single ? 5 : 6;
  acc.function_type = response == Response::kFrequencyResponse ? 4 : 12;
  if (response == Response::kFrequencyResponse) acc.denominator_data_type = 13, acc.denominator_unit = "N";
  for (const auto& p : level.points) {
    const std::complex<double> f = p.force.value * turn, x = p.response.value * turn / kStandardGravity;
    const std::complex<double> y = response == Response::kFrequencyResponse ? x / f : x;
    force.values.insert(force.values.end(), {p.frequency_hz, f.real(), f.imag()});
    acc.values.insert(acc.values.end(), {p.frequency_hz, y.real(), y.imag()});
  }
  force.declared_values = acc.declared_values = static_cast<int>(level.points.size());
  return beamid::testing::Uff151Header() + UffDataset58(force, encoding) + UffDataset58(acc, encoding);
}

FirstHarmonicLevel Read(const std::string& text, const std::string& label = "high") {
  return FirstHarmonicLevelFromUff58(ParseUff58(text, label + ".uff", Uff58Functions::kFrequencyFunctions),
                                     label + ".uff", label);
}

void ExpectSamePhasors(const FirstHarmonicLevel& read, const FirstHarmonicLevel& table, double tolerance) {
  ASSERT_EQ(read.points.size(), table.points.size());
  EXPECT_EQ(read.response_quantity, Quantity::kAcceleration);
  EXPECT_EQ(read.excitation_quantity, Quantity::kForce);
  for (std::size_t i = 0; i < table.points.size(); ++i) {
    const auto& a = read.points[i];
    const auto& b = table.points[i];
    EXPECT_NEAR(a.frequency_hz, b.frequency_hz, tolerance * b.frequency_hz);
    EXPECT_DOUBLE_EQ(a.force.value.imag(), 0.0);  // the force is the reference again
    EXPECT_NEAR(a.force.value.real(), b.force.value.real(), tolerance * std::abs(b.force.value));
    EXPECT_NEAR(std::abs(a.response.value - b.response.value), 0.0, tolerance * std::abs(b.response.value)) << i;
  }
}

TEST(Uff58Level, AFrequencyResponseAndTheForceSpectrumReadTheTablesPhasors) {
  const FirstHarmonicLevel table = TableLevel("high");
  const FirstHarmonicLevel level = Read(Universal(table, Response::kFrequencyResponse, UffEncoding::kAsciiDouble));
  EXPECT_EQ(level.label, "high");
  EXPECT_EQ(level.channel, "acc2");
  ExpectSamePhasors(level, table, 1e-11);  // 13 digits of %20.12E
}

TEST(Uff58Level, TwoSpectraInSinglePrecisionOrBinaryReadTheSame) {
  const FirstHarmonicLevel table = TableLevel("mid");
  ExpectSamePhasors(Read(Universal(table, Response::kSpectrum, UffEncoding::kAsciiSingle), "mid"), table, 2e-5);
  ExpectSamePhasors(Read(Universal(table, Response::kSpectrum, UffEncoding::kBinaryBigDouble), "mid"), table, 1e-15);
}

// The measured backbone of the universal files is the table's: the phasors
// agree to the last bits the analyser's phase turn leaves (10⁻¹⁶), and the
// numbers to 10⁻⁴ of their σ, their σ to 10⁻³ (the searches inside the fits
// stop at their tolerances, which the last bits move: measured 1.7·10⁻⁶ σ
// and 1.1·10⁻⁴).
TEST(Uff58Level, TheMeasuredBackboneOfTheFilesIsTheTables) {
  std::vector<FirstHarmonicLevel> tables, files;
  for (const char* name : {"low", "mid", "high"}) {
    tables.push_back(TableLevel(name));
    files.push_back(Read(Universal(tables.back(), Response::kFrequencyResponse, UffEncoding::kBinaryLittleDouble),
                         name));
  }
  const solver::MeasuredBackbone from_tables = solver::AnalyseMeasuredBackbone(tables);
  const solver::MeasuredBackbone from_files = solver::AnalyseMeasuredBackbone(files);
  ASSERT_EQ(from_files.levels.size(), 3u);
  for (std::size_t l = 0; l < 3; ++l) {
    const auto& a = from_files.levels[l];
    const auto& b = from_tables.levels[l];
    ASSERT_TRUE(b.quadrature_frequency_hz.valid);
    for (const auto& [x, y] : {std::pair{a.quadrature_frequency_hz, b.quadrature_frequency_hz},
                               std::pair{a.damping_ratio, b.damping_ratio},
                               std::pair{a.local_natural_frequency_hz, b.local_natural_frequency_hz}}) {
      ASSERT_TRUE(x.valid && y.valid);
      EXPECT_NEAR(x.value, y.value, 1e-4 * y.std);
      EXPECT_NEAR(x.std, y.std, 1e-3 * y.std);
    }
    EXPECT_EQ(a.flags.size(), b.flags.size());
  }
  // `backbone --measured low.uff mid.uff high.uff` reads them as these levels.
  const std::filesystem::path folder = beamid::testing::UniqueTempPath("beamid_uff_levels");
  std::filesystem::create_directories(folder);
  workflow::MeasureBackboneRequest request{.output = (folder / "measured").string()};
  for (const FirstHarmonicLevel& level : tables) {
    const std::filesystem::path file = folder / (level.label + ".uff");
    beamid::testing::WriteFile(file, Universal(level, Response::kFrequencyResponse, UffEncoding::kBinaryLittleDouble));
    request.inputs.push_back(file.string());
  }
  // And `--uff` writes them back as universal files of its own (signal/uff58_export.h).
  request.uff_folder = (folder / "written").string();
  const workflow::MeasureBackboneOutcome outcome = workflow::MeasureBackbone(request);
  ASSERT_EQ(outcome.measured.levels.size(), 3u);
  for (std::size_t l = 0; l < 3; ++l) {
    EXPECT_EQ(outcome.measured.levels[l].label, tables[l].label);
    EXPECT_EQ(outcome.measured.levels[l].quadrature_frequency_hz.value, from_files.levels[l].quadrature_frequency_hz.value);
    const FirstHarmonicLevel written = ReadUff58Level(folder / "written" / (tables[l].label + ".uff"));
    ASSERT_EQ(written.points.size(), tables[l].points.size());
    EXPECT_NEAR(std::abs(written.points[3].response.value - tables[l].points[3].response.value), 0.0,
                1e-11 * std::abs(tables[l].points[3].response.value));
  }
  // The folder is an output: not one that holds an input.
  request.uff_folder = folder.string();
  EXPECT_THROW(workflow::MeasureBackbone(request), InputError);
  std::filesystem::remove_all(folder);
}

void ExpectRefused(const std::string& text, const std::vector<std::string>& words) {
  try {
    Read(text);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    for (const auto& word : words) EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
  }
}

TEST(Uff58Level, WhatItCannotReadIsRefusedNamingTheFix) {
  const FirstHarmonicLevel table = TableLevel("low");
  std::string text = Universal(table, Response::kFrequencyResponse, UffEncoding::kAsciiDouble);
  // The frequency response alone: no force to say the level.
  const std::size_t second = text.find("    -1\n    58\n", text.find("    58\n") + 1);
  ExpectRefused(beamid::testing::Uff151Header() + text.substr(second),
                {"high.uff", "no force spectrum beside dataset 58 number 1 ('acc2')", "force's spectrum"});
  // A time history is one step's recording, not a level.
  UffChannel time{.id_line1 = "acc1", .dx = 1e-3, .values = std::vector<double>(64, 0.5)};
  ExpectRefused(UffDataset58(time, UffEncoding::kAsciiDouble), {"no spectrum or frequency response", "campaign folder"});
  // Steps of the force and of the response that differ.
  UffChannel force{.id_line1 = "Force", .function_type = 12, .ordinate_type = 6, .spacing = 1,
                   .ordinate_data_type = 13, .unit = "N", .abscissa_unit = "Hz", .abscissa_data_type = 18,
                   .x_min = 50.0, .dx = 0.25, .values = {1, 0, 1, 0, 1, 0}};
  UffChannel acc = force;
  acc.id_line1 = "acc2";
  acc.ordinate_data_type = 12;
  acc.unit = "m/s^2";
  acc.x_min = 50.5;
  force.declared_values = acc.declared_values = 3;
  ExpectRefused(UffDataset58(force, UffEncoding::kAsciiDouble) + UffDataset58(acc, UffEncoding::kAsciiDouble),
                {"step 1", "50.5 Hz", "same positive frequencies"});
  // A response in a unit of another quantity.
  acc.x_min = 50.0;
  acc.unit = "mm";
  acc.ordinate_data_type = 12;
  ExpectRefused(UffDataset58(force, UffEncoding::kAsciiDouble) + UffDataset58(acc, UffEncoding::kAsciiDouble),
                {"'acc2'", "unit 'mm'", "m/s^2"});
}

}  // namespace
}  // namespace beamid::signal
