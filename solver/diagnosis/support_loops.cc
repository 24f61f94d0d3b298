#include "solver/diagnosis/support_loops.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include "solver/estimation/chi_square.h"
#include "solver/diagnosis/internal/weighted_slope.h"
#include "solver/estimation/support_reconstruction.h"

namespace beamid::solver {

namespace {

using Complex = std::complex<double>;

// A loop step is used when |Θ₁| is this many σ above the noise.
constexpr double kLoopAmplitudeMinSigma = 10.0;
// A step's dissipated energy enters the area exponent when this many σ above 0.
constexpr double kLoopEnergyMinSigma = 3.0;

// The dissipated energy per cycle, W = π Σ k·Im(M_k conj Θ_k), and its σ.
void StepEnergy(const ReconstructedStep& r, int k_max, double relative_model_error, LoopStep* step) {
  // M_k = B F_k − D Θ_k: W's gradient with respect to (Re Θ_k, Im Θ_k) gives σ_W.
  double energy = 0.0, energy_var = 0.0;
  for (int k = 1; k <= k_max; ++k) {
    const Complex theta = r.theta_rad[k], moment = r.moment_Nm[k];
    energy += std::numbers::pi * k * std::imag(moment * std::conj(theta));
    const Complex driven = moment + r.rotational_stiffness_Nm_rad[k] * theta;  // B·F_k
    const double im_d = r.rotational_stiffness_Nm_rad[k].imag();
    const double d_re = driven.imag() - 2.0 * im_d * theta.real();
    const double d_im = -driven.real() - 2.0 * im_d * theta.imag();
    energy_var += std::pow(std::numbers::pi * k * r.theta_std_rad[k], 2) * (d_re * d_re + d_im * d_im);
  }
  step->dissipated_energy_J = energy;
  step->dissipated_energy_std_J = std::hypot(std::sqrt(energy_var), relative_model_error * energy);
}

// Moment harmonics beyond the linear support (k1, c), split against
// e^{ik·arg Θ₁}, and the even harmonics' shares.
void StepHarmonics(const ReconstructedStep& r, int k_max, double k1, double c, double relative_model_error,
                   LoopStep* step) {
  const double omega = r.omega_rad_s;
  double beyond2 = 0.0, theta_even2 = 0.0, theta_all2 = 0.0, moment_even2 = 0.0, moment_all2 = 0.0;
  const Complex unit = step->theta_amplitude_rad > 0.0 ? r.theta_rad[1] / step->theta_amplitude_rad : Complex(1.0);
  for (int k = 1; k <= k_max; ++k) {
    theta_all2 += std::norm(r.theta_rad[k]);
    moment_all2 += std::norm(r.moment_Nm[k]);
    if (k % 2 == 0) theta_even2 += std::norm(r.theta_rad[k]), moment_even2 += std::norm(r.moment_Nm[k]);
    if (k < 2) continue;
    const Complex linear_support(k1, k * omega * c);
    const Complex beyond = r.moment_Nm[k] - linear_support * r.theta_rad[k];
    const double sigma = std::hypot(std::abs(r.rotational_stiffness_Nm_rad[k] + linear_support) * r.theta_std_rad[k],
                                    relative_model_error * std::abs(beyond));
    const Complex rotated = beyond * std::conj(std::pow(unit, k));
    beyond2 += std::norm(beyond);
    step->elastic_harmonic_chi2 += std::pow(rotated.real() / sigma, 2);
    step->hysteretic_harmonic_chi2 += std::pow(rotated.imag() / sigma, 2);
    ++step->harmonic_dof;
  }
  step->moment_harmonic_ratio = step->moment_amplitude_Nm > 0.0 ? std::sqrt(beyond2) / step->moment_amplitude_Nm : 0.0;
  step->theta_even_fraction = theta_all2 > 0.0 ? std::sqrt(theta_even2 / theta_all2) : 0.0;
  step->moment_even_fraction = moment_all2 > 0.0 ? std::sqrt(moment_even2 / moment_all2) : 0.0;
}

// One step's loop: its energy against the viscous reference c, and its harmonics.
LoopStep MakeLoopStep(const ReconstructedStep& r, const FitStep& s, const hb::LinearBeamModel& reference_beam,
                      int k_max, double relative_model_error) {
  const double k1 = reference_beam.support_stiffness_Nm_rad, c = reference_beam.support_damping_Nms_rad;
  LoopStep step;
  step.level = s.level;
  step.omega_rad_s = r.omega_rad_s;
  step.theta_amplitude_rad = std::abs(r.theta_rad[1]);
  step.theta_std_rad = r.theta_std_rad[1];
  step.moment_amplitude_Nm = std::abs(r.moment_Nm[1]);
  StepEnergy(r, k_max, relative_model_error, &step);
  const double scale = std::numbers::pi * r.omega_rad_s * step.theta_amplitude_rad * step.theta_amplitude_rad;
  step.viscous_energy_J = c * scale;
  step.equivalent_damping_Nms_rad = scale > 0.0 ? step.dissipated_energy_J / scale : 0.0;
  step.equivalent_damping_std_Nms_rad = scale > 0.0 ? step.dissipated_energy_std_J / scale : 0.0;
  StepHarmonics(r, k_max, k1, c, relative_model_error, &step);
  return step;
}

// What the steps whose rotation stands above the noise contribute to the tests.
struct LoopSeries {
  std::vector<double> log_amplitude, log_energy, log_energy_sigma;  // steps with W above noise
  std::vector<double> damping, damping_sigma, amplitude;
};

void UseStep(const ReconstructedStep& r, const LoopStep& step, int k_max, LoopSeries* series, LoopEvidence* out) {
  ++out->num_steps_used;
  series->damping.push_back(step.equivalent_damping_Nms_rad);
  series->damping_sigma.push_back(step.equivalent_damping_std_Nms_rad);
  series->amplitude.push_back(step.theta_amplitude_rad);
  out->elastic_harmonic_chi2 += step.elastic_harmonic_chi2;
  out->hysteretic_harmonic_chi2 += step.hysteretic_harmonic_chi2;
  out->harmonic_dof += step.harmonic_dof;
  out->max_moment_harmonic_ratio = std::max(out->max_moment_harmonic_ratio, step.moment_harmonic_ratio);
  for (int k = 2; k <= k_max; k += 2) {
    out->theta_even_chi2 += std::norm(r.theta_rad[k]) / std::pow(r.theta_std_rad[k], 2);
    out->theta_even_dof += 2;
  }
  const double energy = step.dissipated_energy_J;
  if (energy >= kLoopEnergyMinSigma * step.dissipated_energy_std_J) {
    series->log_amplitude.push_back(std::log(step.theta_amplitude_rad));
    series->log_energy.push_back(std::log(energy / step.omega_rad_s));
    series->log_energy_sigma.push_back(step.dissipated_energy_std_J / energy);
  }
}

// Is the equivalent damping one constant c over the steps (a viscous damper)?
void ViscousTest(const LoopSeries& s, LoopEvidence* out) {
  if (s.damping.size() < 2) return;
  double sw = 0.0, swc = 0.0;
  for (std::size_t i = 0; i < s.damping.size(); ++i) {
    sw += 1.0 / (s.damping_sigma[i] * s.damping_sigma[i]);
    swc += s.damping[i] / (s.damping_sigma[i] * s.damping_sigma[i]);
  }
  out->mean_equivalent_damping_Nms_rad = swc / sw;
  for (std::size_t i = 0; i < s.damping.size(); ++i)
    out->viscous_chi2 += std::pow((s.damping[i] - out->mean_equivalent_damping_Nms_rad) / s.damping_sigma[i], 2);
  out->viscous_dof = static_cast<int>(s.damping.size()) - 1;
  out->viscous_p_value = ChiSquareUpperTail(out->viscous_chi2, out->viscous_dof);
  const auto [low, high] = std::minmax_element(s.amplitude.begin(), s.amplitude.end());
  out->damping_ratio_high_to_low = s.damping[high - s.amplitude.begin()] / s.damping[low - s.amplitude.begin()];
}

// The four tests at family_significance/4 each.
void DecideLoops(double family_significance, LoopEvidence* out) {
  out->elastic_harmonic_p_value = ChiSquareUpperTail(out->elastic_harmonic_chi2, out->harmonic_dof);
  out->hysteretic_harmonic_p_value = ChiSquareUpperTail(out->hysteretic_harmonic_chi2, out->harmonic_dof);
  out->theta_even_p_value = ChiSquareUpperTail(out->theta_even_chi2, out->theta_even_dof);
  const double alpha = family_significance / 4.0;
  out->dissipation_not_viscous = out->viscous_dof > 0 && out->viscous_p_value < alpha;
  out->hysteretic_shape = out->harmonic_dof > 0 && out->hysteretic_harmonic_p_value < alpha;
  out->non_elliptic = out->hysteretic_shape || (out->harmonic_dof > 0 && out->elastic_harmonic_p_value < alpha);
  out->asymmetric = out->theta_even_dof > 0 && out->theta_even_p_value < alpha;
}

}  // namespace

LoopEvidence AnalyseSupportLoops(const FitData& data, const hb::LinearBeamModel& reference_beam,
                                 double family_significance, double relative_model_error) {
  const std::vector<ReconstructedStep> reconstructed = ReconstructSupport(data, reference_beam);
  const int k_max = data.num_fit_harmonics;
  LoopEvidence out;
  LoopSeries series;
  for (std::size_t i = 0; i < reconstructed.size(); ++i) {
    LoopStep step = MakeLoopStep(reconstructed[i], data.steps[i], reference_beam, k_max, relative_model_error);
    if (step.theta_amplitude_rad >= kLoopAmplitudeMinSigma * step.theta_std_rad)
      UseStep(reconstructed[i], step, k_max, &series, &out);
    out.steps.push_back(std::move(step));
  }
  if (series.log_amplitude.size() >= 3) {
    std::tie(out.area_exponent, out.area_exponent_std) =
        internal::WeightedSlope(series.log_amplitude, series.log_energy, series.log_energy_sigma);
  }
  ViscousTest(series, &out);
  DecideLoops(family_significance, &out);
  return out;
}

}  // namespace beamid::solver
