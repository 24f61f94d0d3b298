#include "solver/estimation/sensor_backbone.h"

#include "hb/errors.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "hb/harmonic_balance.h"

namespace beamid::solver {

std::vector<SensorBackbonePoint> ModelBackboneAtSensor(const hb::LinearBeamModel& beam, const hb::SupportLaw& law,
                                                       double force_position_m, double sensor_position_m,
                                                       const hb::BackboneOptions& options, int num_harmonics) {
  hb::LinearBeamModel linearised = beam;
  linearised.support_stiffness_Nm_rad = law.InitialStiffness_Nm_rad();
  const double f_guess_hz =
      hb::LinearBeam(linearised, force_position_m).NaturalFrequencies_rad_s(1)[0] / (2 * std::numbers::pi);
  // Segments sized for harmonic H of a resonance that may rise by half (as `beamid backbone`).
  const hb::LinearBeam linear(beam, force_position_m, {.max_frequency_hz = 1.5 * (num_harmonics + 1) * 1.5 * f_guess_hz});
  const hb::HarmonicBalance balance(linear, law, {.num_harmonics = num_harmonics});
  const hb::BackboneSummary summary = hb::TraceBackbone(balance, options);
  if (summary.points.empty()) throw NumericalError("model backbone: " + summary.message);
  std::vector<SensorBackbonePoint> out;
  for (const auto& p : summary.points) {
    // From θ's phase resonance at this force to the sensor's: secant steps on
    // ω of cos(arg Y_1 − arg F), each a Newton solve from the last solution.
    Eigen::VectorXcd force = Eigen::VectorXcd::Zero(2);
    force[1] = p.force_amplitude_N;
    hb::HarmonicBalanceSolution solution{.omega_rad_s = p.omega_rad_s, .theta_rad = p.theta_rad, .converged = true};
    auto quadrature = [&](const hb::HarmonicBalanceSolution& s) {
      const std::complex<double> ratio = balance.Displacements(s, force, {sensor_position_m})(0, 1) / force[1];
      return ratio.real() / std::abs(ratio);
    };
    double w0 = p.omega_rad_s, g0 = quadrature(solution);
    double w1 = w0 * (1 + 1e-5);
    for (int iteration = 0; iteration < 30 && std::abs(g0) > 1e-9; ++iteration) {
      const auto next = balance.Solve(w1, force, hb::HarmonicBalance::ToReal(solution.theta_rad));
      if (!next.converged) break;
      const double g1 = quadrature(next);
      solution = next;
      const double w2 = w1 - g1 * (w1 - w0) / (g1 - g0);
      w0 = w1, g0 = g1, w1 = w2;
    }
    if (std::abs(g0) > 1e-6) continue;  // no sensor quadrature found near this point
    const Eigen::MatrixXcd y = balance.Displacements(solution, force, {sensor_position_m});
    out.push_back({std::abs(y(0, 1)), solution.omega_rad_s / (2 * std::numbers::pi)});
  }
  if (out.empty()) throw NumericalError("model backbone: no phase resonance of the sensor found");
  return out;
}

double BackboneFrequencyAt_hz(const std::vector<SensorBackbonePoint>& backbone, double amplitude_m) {
  for (std::size_t i = 0; i + 1 < backbone.size(); ++i) {
    const auto& a = backbone[i];
    const auto& b = backbone[i + 1];
    if ((amplitude_m - a.amplitude_m) * (amplitude_m - b.amplitude_m) <= 0 && a.amplitude_m != b.amplitude_m)
      return a.frequency_hz + (amplitude_m - a.amplitude_m) / (b.amplitude_m - a.amplitude_m) * (b.frequency_hz - a.frequency_hz);
  }
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace beamid::solver
