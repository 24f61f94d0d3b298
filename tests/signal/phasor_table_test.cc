// First-harmonic tables as acquisition systems export them: the accepted
// header and number variants read the same phasors, and every mistake is
// reported with the file and the column to fix.
#include "signal/phasor_table.h"

#include <cmath>
#include <complex>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "signal/input_error.h"

namespace beamid::signal {
namespace {

constexpr double kTolerance = 1e-12;

TEST(PhasorTable, ReadsThePlainSiTable) {
  const FirstHarmonicLevel level = ParsePhasorTable(
      "# exported by some system\n"
      "frequency_Hz,force_N,acceleration_m_s2,phase_rad,coherence\n"
      "53.5,1.0,2.0,0.5,0.99\n"
      "54.0,1.1,4.0,1.5,0.99\n"
      "54.5,0.9,2.5,2.5,0.98\n",
      "plain.csv", "low");
  EXPECT_EQ(level.label, "low");
  EXPECT_EQ(level.response_quantity, Quantity::kAcceleration);
  ASSERT_EQ(level.points.size(), 3u);
  EXPECT_DOUBLE_EQ(level.points[1].frequency_hz, 54.0);
  EXPECT_DOUBLE_EQ(level.points[1].force.value.real(), 1.1);
  EXPECT_NEAR(std::abs(level.points[1].response.value - std::polar(4.0, 1.5)), 0.0, kTolerance);
}

TEST(PhasorTable, DecimalCommaDegreesAndUnitsInBracketsReadTheSame) {
  const FirstHarmonicLevel si = ParsePhasorTable(
      "frequency_Hz,force_N,velocity_m_s,phase_rad,std_phase_rad\n"
      "53.5,1.0,0.002,-0.5,0.001\n54.0,1.1,0.004,0.25,0.001\n54.5,0.9,0.0025,0.75,0.001\n",
      "si.csv", "a");
  const double deg = 180 / std::numbers::pi;
  const std::string comma = "Frequency [Hz];Force (N);Velocity [mm/s];Phase [deg];Phase_std [deg]\n53,5;1,0;2,0;" +
                            std::to_string(-0.5 * deg) + ";" + std::to_string(0.001 * deg) + "\n54,0;1,1;4,0;" +
                            std::to_string(0.25 * deg) + ";" + std::to_string(0.001 * deg) + "\n54,5;0,9;2,5;" +
                            std::to_string(0.75 * deg) + ";" + std::to_string(0.001 * deg) + "\n";
  std::string with_commas = comma;
  // std::to_string wrote '.', the system writes ','.
  for (auto& c : with_commas)
    if (c == '.') c = ',';
  const FirstHarmonicLevel other = ParsePhasorTable(with_commas, "comma.csv", "a");
  ASSERT_EQ(other.points.size(), si.points.size());
  EXPECT_EQ(other.response_quantity, Quantity::kVelocity);
  for (std::size_t i = 0; i < si.points.size(); ++i) {
    EXPECT_DOUBLE_EQ(other.points[i].frequency_hz, si.points[i].frequency_hz);
    EXPECT_NEAR(std::abs(other.points[i].response.value - si.points[i].response.value), 0.0,
                1e-6 * std::abs(si.points[i].response.value));
    EXPECT_NEAR(other.points[i].response.Covariance()(1, 1), si.points[i].response.Covariance()(1, 1),
                1e-4 * si.points[i].response.Covariance()(1, 1));
  }
}

TEST(PhasorTable, TheResponseQuantityFollowsFromTheUnit) {
  const FirstHarmonicLevel level = ParsePhasorTable(
      "f [Hz]\tF_amp [N]\tresponse [g]\tphase [deg]\n50\t1\t1\t0\n51\t1\t2\t10\n52\t1\t1\t20\n", "tab.txt", "x");
  EXPECT_EQ(level.response_quantity, Quantity::kAcceleration);
  EXPECT_NEAR(std::abs(level.points[1].response.value), 2 * 9.80665, kTolerance);
}

void ExpectError(const std::string& text, const std::vector<std::string>& words);

// The rows of a table after its header: frequency, excitation amplitude,
// response amplitude, phase [deg].
constexpr const char* kRows = "50,2,1,0\n51,2,3,40\n52,2,1,80\n";

TEST(PhasorTable, AForceIsTheDefaultExcitation) {
  for (const char* header : {"frequency_Hz,force_N,acc_g,phase_deg\n", "frequency_Hz,excitation,acc_g,phase_deg\n",
                             "frequency_Hz,input [N],acc_g,phase_deg\n"}) {
    SCOPED_TRACE(header);
    EXPECT_EQ(ParsePhasorTable(std::string(header) + kRows, "f.csv", "f").excitation_quantity, Quantity::kForce);
  }
}

TEST(PhasorTable, AVoltageDriveReadsToVoltsByNameOrUnit) {
  const FirstHarmonicLevel volts =
      ParsePhasorTable(std::string("frequency_Hz,voltage [V],acc_g,phase_deg\n") + kRows, "v.csv", "v");
  EXPECT_EQ(volts.excitation_quantity, Quantity::kVoltage);
  EXPECT_DOUBLE_EQ(volts.points[1].force.value.real(), 2.0);
  // The same drive in mV, named by its unit.
  const FirstHarmonicLevel millivolts = ParsePhasorTable(
      "frequency_Hz,excitation [mV],acc_g,phase_deg,excitation_std [mV]\n50,2000,1,0,10\n51,2000,3,40,10\n"
      "52,2000,1,80,10\n",
      "mv.csv", "mv");
  EXPECT_EQ(millivolts.excitation_quantity, Quantity::kVoltage);
  for (std::size_t i = 0; i < volts.points.size(); ++i) {
    EXPECT_NEAR(millivolts.points[i].force.value.real(), volts.points[i].force.value.real(), 1e-12);
    EXPECT_NEAR(std::abs(millivolts.points[i].response.value - volts.points[i].response.value), 0.0, 1e-12);
  }
  EXPECT_NEAR(millivolts.points[0].force.std_real, 0.01, 1e-15);
  ExpectError("frequency_Hz,voltage [N],acc_g,phase_deg\n" + std::string(kRows),
              {"column 'voltage [N]'", "unknown unit 'N'", "V, mV (for a voltage)"});
}

TEST(PhasorTable, ABaseAccelerationDriveGivesTheResponseRelativeToTheBase) {
  const FirstHarmonicLevel level =
      ParsePhasorTable(std::string("frequency_Hz,base_acceleration [g],acceleration [g],phase_deg\n") + kRows, "b.csv",
                       "b");
  EXPECT_EQ(level.excitation_quantity, Quantity::kBaseAcceleration);
  constexpr double g = 9.80665;
  const double deg = std::numbers::pi / 180;
  // Row 2: A_b = 2 g, X = 3 g at 40° from it; the level holds X − A_b per −A_b.
  const std::complex<double> absolute = std::polar(3 * g, 40 * deg);
  EXPECT_NEAR(std::abs(level.points[1].response.value - (absolute - 2 * g)), 0.0, 1e-9);
  EXPECT_NEAR(std::abs(level.points[1].force.value - (-2 * g)), 0.0, 1e-12);
  // Said by the unit of an input column too.
  EXPECT_EQ(ParsePhasorTable(std::string("frequency_Hz,input [m/s^2],acc_g,phase_deg\n") + kRows, "i.csv", "i")
                .excitation_quantity,
            Quantity::kBaseAcceleration);
  ExpectError("frequency_Hz,base_acceleration [g],velocity [mm/s],phase_deg\n" + std::string(kRows),
              {"column 'velocity [mm/s]'", "must be an acceleration", "not a velocity"});
}

void ExpectError(const std::string& text, const std::vector<std::string>& words) {
  try {
    ParsePhasorTable(text, "levels/high.csv", "high");
    ADD_FAILURE() << "no error for:\n" << text;
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("levels/high.csv"), std::string::npos) << message;
    for (const auto& word : words) EXPECT_NE(message.find(word), std::string::npos) << message << " lacks " << word;
  }
}

TEST(PhasorTable, ErrorsNameTheFileAndTheColumn) {
  ExpectError("frequency_Hz,force_N,acceleration_m_s2\n1,1,1\n2,1,1\n3,1,1\n", {"'phase'", "missing", "phase_deg"});
  ExpectError("frequency_Hz,force [N],acc_m_s2,phase_deg\n1,1,1,0\n2,nan,1,0\n3,1,1,0\n",
              {"column 'force [N]'", "line 3", "'nan'"});
  ExpectError("frequency_Hz,force_N,acceleration [furlong/s2],phase_deg\n1,1,1,0\n2,1,1,0\n3,1,1,0\n",
              {"column 'acceleration [furlong/s2]'", "unknown unit 'furlong/s2'", "m/s^2"});
  ExpectError("frequency_Hz,force_N,acc_m_s2,phase\n1,1,1,0\n2,1,1,0\n3,1,1,0\n", {"column 'phase'", "no unit"});
  ExpectError("frequency_Hz,force_N,response,phase_deg\n1,1,1,0\n2,1,1,0\n3,1,1,0\n", {"column 'response'", "quantity"});
  ExpectError("frequency_Hz,force_N,acc_m_s2,phase_deg\n1,1,1,0\n2,-1,1,0\n3,1,1,0\n", {"force_N", "not positive"});
  ExpectError("frequency_Hz,force_N,acc_m_s2,phase_deg\n1,1,1,0\n", {"3 frequency steps"});
}

// A laser vibrometer's export as its software writes it: a metadata block
// without '#', its own column names, parentheses that are part of a name,
// and the units on the row under the header.
constexpr const char* kVibrometerExport =
    "Source File Name:\tscan_0001.svd\n"
    "Signal:\tFRF Vib / Ref1, 3 averages\n"
    "Date:\t03.12.2026 21:00\n"
    "\n"
    "X-Data\tShaker Force\tLaser (M - Filtered)\tPhase Laser\tCoherence\n"
    "[Hz]\t[N]\t[mm/s]\t[°]\t\n"
    "50\t2\t1000\t0\t0.99\n51\t2\t3000\t40\t0.99\n52\t2\t1000\t80\t0.98\n";

PhasorTableOptions VibrometerLayout() {
  PhasorTableOptions options{.layout = {.lines_before_header = 4, .units_row = true, .declared_in = "the test"}};
  options.columns.Assign("frequency=X-Data");
  options.columns.Assign("excitation=2");
  options.columns.Assign("response = Laser (M - Filtered)");
  options.columns.Assign("phase=phase laser");
  return options;
}

TEST(PhasorTable, AnExportsMetadataUnitsRowAndOwnNamesReadAsTheSiTable) {
  const FirstHarmonicLevel si =
      ParsePhasorTable(std::string("frequency_Hz,force_N,velocity_m_s,phase_deg\n") + "50,2,1,0\n51,2,3,40\n52,2,1,80\n",
                       "si.csv", "a");
  const FirstHarmonicLevel exported = ParsePhasorTable(kVibrometerExport, "vib.txt", "a", VibrometerLayout());
  EXPECT_EQ(exported.response_quantity, Quantity::kVelocity);
  EXPECT_EQ(exported.excitation_quantity, Quantity::kForce);
  EXPECT_EQ(exported.channel, "Laser (M - Filtered)");
  ASSERT_EQ(exported.points.size(), si.points.size());
  for (std::size_t i = 0; i < si.points.size(); ++i) {
    EXPECT_DOUBLE_EQ(exported.points[i].frequency_hz, si.points[i].frequency_hz);
    EXPECT_NEAR(std::abs(exported.points[i].force.value - si.points[i].force.value), 0.0, kTolerance);
    EXPECT_NEAR(std::abs(exported.points[i].response.value - si.points[i].response.value), 0.0, kTolerance);
  }
}

TEST(PhasorTable, WithoutItsLayoutTheExportIsRefusedWithTheOptionsThatReadIt) {
  ExpectError(kVibrometerExport, {"'frequency': missing", "'Source File Name:'", "--column ROLE=COLUMN",
                                  "--lines-before-header"});
}

TEST(PhasorTable, AMappedColumnTakesItsRoleOverAColumnNamedForIt) {
  // The export's own "acceleration" column is another sensor's; the response is the mapped one.
  PhasorTableOptions options;
  options.columns.Assign("response=laser [m/s]");
  const FirstHarmonicLevel level = ParsePhasorTable(
      "frequency_Hz,force_N,acceleration_m_s2,laser [m/s],phase_deg\n50,2,9,1,0\n51,2,9,3,40\n52,2,9,1,80\n",
      "f.csv", "f", options);
  EXPECT_EQ(level.response_quantity, Quantity::kVelocity);
  EXPECT_NEAR(std::abs(level.points[1].response.value - std::polar(3.0, 40 * std::numbers::pi / 180)), 0.0,
              kTolerance);
}

TEST(PhasorTable, AMappingThatMissesOrCannotSayTheQuantityNamesTheFix) {
  const auto expect_error = [](const std::string& text, const std::vector<const char*>& assignments,
                               const std::vector<std::string>& words) {
    PhasorTableOptions options;
    for (const char* assignment : assignments) options.columns.Assign(assignment);
    try {
      ParsePhasorTable(text, "levels/high.csv", "high", options);
      ADD_FAILURE() << "no error for " << assignments.front();
    } catch (const InputError& e) {
      for (const auto& word : words) EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
    }
  };
  const std::string table = std::string("freq_Hz,F_N,laser,phase_deg\n") + kRows;
  expect_error(table, {"response=Laser Vib"}, {"levels/high.csv", "mapped to column 'Laser Vib'", "'laser'"});
  expect_error(table, {"response=9"}, {"mapped to column '9'", "4 columns"});
  expect_error(table, {"response=laser"}, {"column 'laser'", "quantity", "m/s"});
  expect_error(table, {"frequency=freq_Hz", "phase=1"}, {"column 'freq_Hz'", "mapped to two roles"});
  // A column mapped away from the role its name says leaves that role to be found.
  expect_error(table, {"phase=freq_Hz"}, {"column 'frequency': missing"});
  PhasorColumnMapping mapping;
  EXPECT_THROW(mapping.Assign("speed=laser"), InputError);
  EXPECT_THROW(mapping.Assign("response"), InputError);
  mapping.Assign("response=laser");
  try {
    mapping.Assign("response=3");
    ADD_FAILURE() << "a role mapped twice";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("already mapped to 'laser'"), std::string::npos) << e.what();
  }
}

TEST(PhasorTable, AMissingFileIsAnInputError) {
  EXPECT_THROW(ReadPhasorTable("/nonexistent/level.csv"), InputError);
}

}  // namespace
}  // namespace beamid::signal
