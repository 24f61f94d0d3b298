// Spikes are judged while the excitation runs (signal/recording_validator.h):
// a shaker switched off shocks the structure, and that shock and the ring-down
// after it are no corrupted samples; the same sample while the shaker drives
// is one.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "signal/recording_validator.h"

namespace beamid::signal {
namespace {

constexpr double kRateHz = 2000.0;
constexpr double kFrequencyHz = 50.0;
const std::vector<std::string> kChannels{"force", "acc"};

// 2 s: the force runs for the first 1.2 s; the response rings down after it.
Eigen::MatrixXd StoppedRecord() {
  const int n = 4000, stop = 2400;
  Eigen::MatrixXd x(n, 2);
  for (int i = 0; i < n; ++i) {
    const double t = i / kRateHz, phase = 2.0 * std::numbers::pi * kFrequencyHz * t;
    const double driven = i < stop ? 1.0 : 0.0;
    x(i, 0) = driven * std::sin(phase) + 1e-4 * std::cos(7.3 * phase);
    x(i, 1) = 3.0 * std::cos(phase) * (i < stop ? 1.0 : std::exp(-2.0 * (t - stop / kRateHz)));
  }
  return x;
}

bool HasSpike(const std::vector<QualityFinding>& findings, const std::string& channel) {
  return std::any_of(findings.begin(), findings.end(), [&](const QualityFinding& f) {
    return f.channel == channel && f.problem.find("spike") != std::string::npos;
  });
}

TEST(SpikesInDrivenSpan, TheShockOfAShakerSwitchedOffIsNoSpike) {
  Eigen::MatrixXd x = StoppedRecord();
  x(2410, 1) = 90.0;  // the switch-off shock: 30 times the steady amplitude
  x(2411, 1) = -60.0;
  const auto findings = CheckChannels(x, kChannels, kRateHz, 0.0, kFrequencyHz, "step.csv", {});
  EXPECT_FALSE(HasSpike(findings, "acc"));
  EXPECT_FALSE(HasSpike(findings, "force"));
}

TEST(SpikesInDrivenSpan, TheSameSampleWhileTheShakerDrivesIsASpike) {
  Eigen::MatrixXd x = StoppedRecord();
  x(1000, 1) = 90.0;
  const auto findings = CheckChannels(x, kChannels, kRateHz, 0.0, kFrequencyHz, "step.csv", {});
  EXPECT_TRUE(HasSpike(findings, "acc"));
  EXPECT_FALSE(HasSpike(findings, "force"));
}

}  // namespace
}  // namespace beamid::signal
