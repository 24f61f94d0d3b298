#include "hb/multiple_scales.h"

#include "hb/errors.h"
#include "hb/option_checks.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

namespace beamid::hb {
namespace {

// Within this relative distance of ω0 the non-resonant receptance (a
// difference of two large numbers) is interpolated from both sides.
constexpr double kResonanceGuard = 1e-4;

// Positive real roots of c3·s³ + c2·s² + c1·s + c0 with c0 < 0 < c3: the
// cubic is split into monotone pieces at its critical points and each piece
// with a sign change is bisected. Robust where the roots nearly merge (fold).
std::vector<double> PositiveCubicRoots(double c3, double c2, double c1, double c0) {
  auto p = [&](double s) { return ((c3 * s + c2) * s + c1) * s + c0; };
  std::vector<double> breaks = {0.0};
  const double qa = 3.0 * c3, qb = 2.0 * c2, qc = c1;
  const double discriminant = qb * qb - 4.0 * qa * qc;
  if (discriminant > 0.0) {
    const double q = -0.5 * (qb + std::copysign(std::sqrt(discriminant), qb));
    for (double s : {q / qa, q != 0.0 ? qc / q : 0.0})
      if (s > 0.0) breaks.push_back(s);
    std::sort(breaks.begin(), breaks.end());
  }
  double upper = std::max(breaks.back(), std::cbrt(std::abs(c0) / c3));
  if (c1 > 0.0) upper = std::max(upper, std::abs(c0) / c1);
  while (p(upper) <= 0.0) upper *= 2.0;
  breaks.push_back(upper);
  std::vector<double> roots;
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
    double a = breaks[i], b = breaks[i + 1];
    double fa = p(a);
    const double fb = p(b);
    if (fa == 0.0 && a > 0.0) roots.push_back(a);
    if ((fa > 0.0) == (fb > 0.0) || fa == 0.0) continue;
    for (int iteration = 0; iteration < 400; ++iteration) {
      const double m = 0.5 * (a + b);
      if (m == a || m == b) break;
      const double fm = p(m);
      if ((fm > 0.0) == (fa > 0.0)) {
        a = m;
        fa = fm;
      } else {
        b = m;
      }
    }
    roots.push_back(0.5 * (a + b));
  }
  return roots;
}

}  // namespace

void MultipleScalesOptions::Validate() const {
  if (harmonic_frequency != MultipleScalesHarmonicFrequency::kExcitation &&
      harmonic_frequency != MultipleScalesHarmonicFrequency::kNatural)
    option_checks::Refuse("MultipleScalesOptions.harmonic_frequency",
                          option_checks::FormatValue(static_cast<int>(harmonic_frequency)), "kExcitation or kNatural");
}

MultipleScalesModel::MultipleScalesModel(const BeamProperties& beam,
                                         const PolynomialSupportLaw::Coefficients& support,
                                         double force_position_m, const Options& options)
    : beam_(beam),
      support_(support),
      force_position_m_(force_position_m),
      options_(options),
      closed_form_(beam, support.k1_Nm_rad) {
  options.Validate();
  for (double value : {support.k2_Nm_rad2, support.k3_Nm_rad3, support.c_Nms_rad})
    if (!std::isfinite(value))
      throw std::invalid_argument("multiple-scales model: the support coefficients k2, k3 and c must be finite");
  if (support.c_Nms_rad < 0.0)
    throw std::invalid_argument("multiple-scales model: the support damping c must be >= 0 N*m*s/rad");
  if (!(force_position_m >= 0.0 && force_position_m <= beam.length_m))
    throw std::invalid_argument("multiple-scales model: the force position " + std::to_string(force_position_m) +
                                " m lies outside the beam [0, " + std::to_string(beam.length_m) + "] m");
  if (beam.rayleigh_mass_1_s != 0.0 || beam.rayleigh_stiffness_s != 0.0)
    throw std::invalid_argument(
        "multiple-scales model: the beam's Rayleigh damping is not modelled (its loss factor is); use the "
        "harmonic-balance model");
  mode_ = closed_form_.ModeShape(0);
  omega0_rad_s_ = closed_form_.NaturalFrequencies_rad_s(1).front();
  modal_mass_kg_ = beam.MassPerLength_kg_m() * mode_.SquareIntegral(0);
  // One mode at its driving harmonic, where a modal loss factor is the loss
  // factor (hb/matched_modal_loss.h).
  modal_loss_stiffness_N_m_ =
      (beam.loss_factor + beam.modal_loss_factor) * beam.BendingStiffness_Nm2() * mode_.SquareIntegral(2);
  support_slope_per_m_ = mode_.Value(beam.length_m, 1);
  mode_at_force_ = mode_.Value(force_position_m);
  static_rotation_per_moment_rad_Nm_ = closed_form_.RotationPerEndMoment_rad_Nm(0.0);
}

double MultipleScalesModel::HarmonicBase_rad_s(double omega_rad_s) const {
  if (!(std::isfinite(omega_rad_s) && omega_rad_s > 0.0))
    throw std::invalid_argument("multiple-scales model: the excitation frequency must be a positive number of rad/s");
  return options_.harmonic_frequency == HarmonicFrequency::kExcitation ? omega_rad_s : omega0_rad_s_;
}

Complex MultipleScalesModel::ModalDynamicStiffness_N_m(double omega_rad_s) const {
  const double w0 = omega0_rad_s_;
  const double detuning = options_.harmonic_frequency == HarmonicFrequency::kExcitation
                              ? w0 * w0 - omega_rad_s * omega_rad_s
                              : 2.0 * w0 * (w0 - omega_rad_s);
  return {modal_mass_kg_ * detuning, modal_loss_stiffness_N_m_};
}

double MultipleScalesModel::CubicCoefficient_N_m3(double omega_rad_s) const {
  const double base = HarmonicBase_rad_s(omega_rad_s);
  const double g2 = closed_form_.RotationPerEndMoment_rad_Nm(2.0 * base);
  const double k2 = support_.k2_Nm_rad2;
  const double slope2 = support_slope_per_m_ * support_slope_per_m_;
  const double gamma =
      (2.0 * k2 * k2 * (2.0 * static_rotation_per_moment_rad_Nm_ + g2) - 3.0 * support_.k3_Nm_rad3) * slope2 * slope2;
  if (!std::isfinite(gamma))
    throw NumericalError("multiple-scales model: 2*Omega = " + std::to_string(2.0 * base) +
                             " rad/s is a natural frequency of the linear beam (internal resonance)");
  return gamma;
}

MultipleScalesModel::LinearCoupling MultipleScalesModel::Coupling(double omega_rad_s, Complex force_phasor_N) const {
  const Complex damper(0.0, HarmonicBase_rad_s(omega_rad_s) * support_.c_Nms_rad);  // iΩ·C
  if (options_.harmonic_frequency == HarmonicFrequency::kNatural) return {damper, 1.0, 0.0};
  const double rest_compliance = NonResonantMoment_m_Nm(beam_.length_m, omega_rad_s, 1);  // G_rest,θM
  const Complex damping = damper / (1.0 + damper * rest_compliance);
  return {damping, 1.0 - damping * rest_compliance,
          force_phasor_N * NonResonantForce_m_N(beam_.length_m, omega_rad_s, 1)};
}

Complex MultipleScalesModel::DamperFactor(double harmonic_omega_rad_s) const {
  if (options_.harmonic_frequency == HarmonicFrequency::kNatural || support_.c_Nms_rad == 0.0) return 1.0;
  // Unit end moment with the damper: θ = G·(1 − iω·C·θ), so G_C = G/(1 + iω·C·G).
  const Complex damper(0.0, harmonic_omega_rad_s * support_.c_Nms_rad);
  return 1.0 / (1.0 + damper * closed_form_.RotationPerEndMoment_rad_Nm(harmonic_omega_rad_s));
}

Complex MultipleScalesModel::SecondHarmonicCompliance_rad_Nm(double omega_rad_s) const {
  const double second = 2.0 * HarmonicBase_rad_s(omega_rad_s);
  const Complex compliance = closed_form_.RotationPerEndMoment_rad_Nm(second) * DamperFactor(second);
  if (!std::isfinite(std::abs(compliance)))
    throw NumericalError("multiple-scales model: 2*Omega = " + std::to_string(second) +
                             " rad/s is a natural frequency of the linear beam (internal resonance)");
  return compliance;
}

Complex MultipleScalesModel::ForcedRotation_rad(double omega_rad_s, Complex force_phasor_N) const {
  return Coupling(omega_rad_s, force_phasor_N).forced_rotation_rad;
}

MultipleScalesModel::Excitation MultipleScalesModel::AtExcitation(double omega_rad_s, Complex force_phasor_N,
                                                                  const std::vector<double>& positions_m) const {
  for (double x : positions_m)
    if (!(x >= 0.0 && x <= beam_.length_m))
      throw std::invalid_argument("multiple-scales model: the response position " + std::to_string(x) +
                                  " m lies outside the beam [0, " + std::to_string(beam_.length_m) + "] m");
  const double base = HarmonicBase_rad_s(omega_rad_s);
  const LinearCoupling coupling = Coupling(omega_rad_s, force_phasor_N);
  Excitation e;
  e.k2_ = support_.k2_Nm_rad2;
  e.k3_ = support_.k3_Nm_rad3;
  e.slope_per_m_ = support_slope_per_m_;
  e.static_compliance_rad_Nm_ = static_rotation_per_moment_rad_Nm_;
  e.force_phasor_N_ = force_phasor_N;
  e.modal_stiffness_N_m_ = ModalDynamicStiffness_N_m(omega_rad_s);
  e.modal_force_N_ = force_phasor_N * mode_at_force_;
  e.damping_Nm_rad_ = coupling.damping_Nm_rad;
  e.nonlinear_factor_ = coupling.nonlinear_factor;
  e.forced_rotation_rad_ = coupling.forced_rotation_rad;
  e.second_compliance_rad_Nm_ = SecondHarmonicCompliance_rad_Nm(omega_rad_s);
  // The seed's form takes θ1 = θ0: no forced rotation (θ_F = 0 there) and no
  // non-resonant rotation of the support moment.
  e.rest_rotation_rad_Nm_ = options_.harmonic_frequency == HarmonicFrequency::kNatural
                                ? 0.0
                                : NonResonantMoment_m_Nm(beam_.length_m, omega_rad_s, 1);
  for (double x : positions_m)
    e.positions_.push_back({.mode = mode_.Value(x),
                            .rest_force_m_N = NonResonantForce_m_N(x, base),
                            .rest_moment_m_Nm = NonResonantMoment_m_Nm(x, base),
                            .static_m_Nm = DisplacementPerEndMoment_m_Nm(x, 0.0),
                            .second_m_Nm = DisplacementPerEndMoment_m_Nm(x, 2.0 * base) * DamperFactor(2.0 * base),
                            .third_m_Nm = DisplacementPerEndMoment_m_Nm(x, 3.0 * base) * DamperFactor(3.0 * base)});
  return e;
}

Complex MultipleScalesModel::Excitation::NonlinearMoment_Nm(Complex theta0_rad) const {
  const double theta0_abs2 = std::norm(theta0_rad);
  const double theta_static = -k2_ * theta0_abs2 * static_compliance_rad_Nm_ / 2.0;
  const Complex theta2 = -k2_ * theta0_rad * theta0_rad * second_compliance_rad_Nm_ / 2.0;
  return 0.75 * k3_ * theta0_abs2 * theta0_rad + 2.0 * k2_ * (theta0_rad * theta_static + std::conj(theta0_rad) * theta2 / 2.0);
}

Complex MultipleScalesModel::Excitation::SupportMomentFirstHarmonic_Nm(Complex modal_phasor_m) const {
  const Complex theta0 = modal_phasor_m * slope_per_m_;
  return damping_Nm_rad_ * (theta0 + forced_rotation_rad_) + nonlinear_factor_ * NonlinearMoment_Nm(theta0);
}

Complex MultipleScalesModel::Excitation::SolvabilityResidual_N(Complex modal_phasor_m) const {
  return modal_stiffness_N_m_ * modal_phasor_m - modal_force_N_ +
         slope_per_m_ * SupportMomentFirstHarmonic_Nm(modal_phasor_m);
}

Complex MultipleScalesModel::Excitation::FirstHarmonicRotation_rad(Complex modal_phasor_m) const {
  return modal_phasor_m * slope_per_m_ + forced_rotation_rad_ -
         SupportMomentFirstHarmonic_Nm(modal_phasor_m) * rest_rotation_rad_Nm_;
}

MultipleScalesModel::Harmonics MultipleScalesModel::Excitation::Response(int position_index,
                                                                         Complex modal_phasor_m) const {
  const AtPosition& at = positions_.at(position_index);
  const Complex u = modal_phasor_m;
  const Complex moment1 = SupportMomentFirstHarmonic_Nm(u);
  const Complex theta1 = u * slope_per_m_ + forced_rotation_rad_ - moment1 * rest_rotation_rad_Nm_;
  Harmonics h;
  h.h0_m = -(k2_ / 2.0) * std::norm(theta1) * at.static_m_Nm;
  h.h1_m = u * at.mode + force_phasor_N_ * at.rest_force_m_N - moment1 * at.rest_moment_m_Nm;
  h.h2_m = -(k2_ / 2.0) * theta1 * theta1 * at.second_m_Nm;
  h.h3_m = -(theta1 * theta1 * theta1 / 4.0) * (k3_ - 2.0 * k2_ * k2_ * second_compliance_rad_Nm_) * at.third_m_Nm;
  return h;
}

Complex MultipleScalesModel::SupportMomentFirstHarmonic_Nm(Complex modal_phasor_m, double omega_rad_s,
                                                          Complex force_phasor_N) const {
  return AtExcitation(omega_rad_s, force_phasor_N).SupportMomentFirstHarmonic_Nm(modal_phasor_m);
}

Complex MultipleScalesModel::SolvabilityResidual_N(Complex modal_phasor_m, double omega_rad_s,
                                                  Complex force_phasor_N) const {
  return AtExcitation(omega_rad_s, force_phasor_N).SolvabilityResidual_N(modal_phasor_m);
}

std::vector<Complex> MultipleScalesModel::Solve(double omega_rad_s, Complex force_phasor_N) const {
  if (!std::isfinite(std::abs(force_phasor_N)))
    throw std::invalid_argument("multiple-scales model: the force phasor must be finite");
  const LinearCoupling coupling = Coupling(omega_rad_s, force_phasor_N);
  const double slope = support_slope_per_m_;
  // (α − β·a²)·U = f with
  const Complex alpha = ModalDynamicStiffness_N_m(omega_rad_s) + coupling.damping_Nm_rad * slope * slope;
  const double slope4 = slope * slope * slope * slope;
  const Complex gamma = (2.0 * support_.k2_Nm_rad2 * support_.k2_Nm_rad2 *
                             (2.0 * static_rotation_per_moment_rad_Nm_ + SecondHarmonicCompliance_rad_Nm(omega_rad_s)) -
                         3.0 * support_.k3_Nm_rad3) *
                        slope4;
  const Complex beta = coupling.nonlinear_factor * gamma / 4.0;
  const Complex force_modal =
      force_phasor_N * mode_at_force_ - slope * coupling.damping_Nm_rad * coupling.forced_rotation_rad;
  if (force_modal == 0.0) return {Complex(0.0)};
  // |α − β·s|²·s = |f|², s = a²: a cubic in s.
  const double f2 = std::norm(force_modal);
  std::vector<double> squares;
  if (beta == 0.0) {
    if (std::norm(alpha) == 0.0)
      throw NumericalError("multiple-scales model: undamped linear beam forced at its natural frequency");
    squares.push_back(f2 / std::norm(alpha));
  } else {
    squares = PositiveCubicRoots(std::norm(beta), -2.0 * (alpha * std::conj(beta)).real(), std::norm(alpha), -f2);
  }
  std::vector<Complex> solutions;
  for (double s : squares) solutions.push_back(force_modal / (alpha - beta * s));
  std::sort(solutions.begin(), solutions.end(), [](Complex x, Complex y) { return std::abs(x) < std::abs(y); });
  return solutions;
}

std::vector<MultipleScalesModel::SweepPoint> MultipleScalesModel::Sweep(const std::vector<double>& omegas_rad_s,
                                                                        Complex force_phasor_N) const {
  std::vector<SweepPoint> points;
  points.reserve(omegas_rad_s.size());
  for (double omega : omegas_rad_s) points.push_back({omega, Solve(omega, force_phasor_N)});
  return points;
}

double MultipleScalesModel::DisplacementPerEndMoment_m_Nm(double position_m, double omega_rad_s) const {
  const double value = closed_form_.EndMomentShape(omega_rad_s).Value(position_m) / beam_.BendingStiffness_Nm2();
  if (!std::isfinite(value))
    throw NumericalError("multiple-scales model: " + std::to_string(omega_rad_s) +
                             " rad/s is a natural frequency of the linear beam (internal resonance)");
  return value;
}

namespace {

// f(Ω) − (modal term), evaluated away from ω0 and interpolated across it.
double SmoothThroughResonance(const std::function<double(double)>& rest, double omega, double omega0) {
  const double relative = omega / omega0 - 1.0;
  if (std::abs(relative) >= kResonanceGuard) return rest(omega);
  const double below = rest(omega0 * (1.0 - kResonanceGuard));
  const double above = rest(omega0 * (1.0 + kResonanceGuard));
  const double t = 0.5 * (relative / kResonanceGuard + 1.0);
  return (1.0 - t) * below + t * above;
}

}  // namespace

double MultipleScalesModel::NonResonantForce_m_N(double position_m, double omega_rad_s, int derivative) const {
  const double ei = beam_.BendingStiffness_Nm2();
  const double mode_x = mode_.Value(position_m, derivative);
  auto rest = [&](double omega) {
    const double exact = closed_form_.PointForceShape(omega, force_position_m_).Value(position_m, derivative) / ei;
    return exact - mode_x * mode_at_force_ / (modal_mass_kg_ * (omega0_rad_s_ * omega0_rad_s_ - omega * omega));
  };
  return SmoothThroughResonance(rest, omega_rad_s, omega0_rad_s_);
}

double MultipleScalesModel::NonResonantMoment_m_Nm(double position_m, double omega_rad_s, int derivative) const {
  const double ei = beam_.BendingStiffness_Nm2();
  const double mode_x = mode_.Value(position_m, derivative);
  auto rest = [&](double omega) {
    const double exact = closed_form_.EndMomentShape(omega).Value(position_m, derivative) / ei;
    if (!std::isfinite(exact))
      throw NumericalError("multiple-scales model: " + std::to_string(omega) +
                               " rad/s is a natural frequency of the linear beam (internal resonance)");
    return exact -
           mode_x * support_slope_per_m_ / (modal_mass_kg_ * (omega0_rad_s_ * omega0_rad_s_ - omega * omega));
  };
  return SmoothThroughResonance(rest, omega_rad_s, omega0_rad_s_);
}

Complex MultipleScalesModel::FirstHarmonicRotation_rad(Complex modal_phasor_m, double omega_rad_s,
                                                       Complex force_phasor_N) const {
  return AtExcitation(omega_rad_s, force_phasor_N).FirstHarmonicRotation_rad(modal_phasor_m);
}

MultipleScalesModel::Harmonics MultipleScalesModel::Response(double position_m, Complex modal_phasor_m,
                                                             double omega_rad_s, Complex force_phasor_N) const {
  return AtExcitation(omega_rad_s, force_phasor_N, {position_m}).Response(0, modal_phasor_m);
}

double MultipleScalesModel::Backbone_rad_s(double amplitude_m) const {
  if (!(amplitude_m >= 0.0 && std::isfinite(amplitude_m)))
    throw std::invalid_argument("multiple-scales model: the backbone amplitude must be a finite number >= 0 m");
  const double w0 = omega0_rad_s_;
  const double shift = amplitude_m * amplitude_m / (4.0 * modal_mass_kg_);
  if (options_.harmonic_frequency == HarmonicFrequency::kNatural)
    return w0 - CubicCoefficient_N_m3(w0) * shift / (2.0 * w0);  // 2ω0·(ω0 − Ω) = Γ·a²/4
  double omega = w0;
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double square = w0 * w0 - CubicCoefficient_N_m3(omega) * shift;
    if (!(square > 0.0))
      throw NumericalError("multiple-scales model: no backbone frequency at amplitude " +
                               std::to_string(amplitude_m) + " m (softening beyond the model's range)");
    const double next = std::sqrt(square);
    if (std::abs(next - omega) <= 1e-14 * w0) return next;
    omega = next;
  }
  throw NumericalError("multiple-scales model: the backbone fixed point did not converge at amplitude " +
                           std::to_string(amplitude_m) + " m");
}

}  // namespace beamid::hb
