// First-harmonic tables as acquisition systems export them: the accepted
// header and number variants read the same phasors, and every mistake is
// reported with the file and the column to fix.
#include "signal/phasor_table.h"

#include <cmath>
#include <complex>
#include <numbers>
#include <string>

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

TEST(PhasorTable, AMissingFileIsAnInputError) {
  EXPECT_THROW(ReadPhasorTable("/nonexistent/level.csv"), InputError);
}

}  // namespace
}  // namespace beamid::signal
