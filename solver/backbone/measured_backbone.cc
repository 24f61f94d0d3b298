#include "solver/backbone/measured_backbone.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <tuple>

#include <fmt/core.h>

#include <Eigen/Cholesky>
#include <Eigen/QR>

#include "hb/errors.h"
#include "hb/option_checks.h"
#include "signal/quantity_conversion.h"
#include "solver/backbone/phase_convention.h"

namespace beamid::solver {
namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;
constexpr int kInputsPerPoint = 5;  // ω, Re F, Im F, Re X_d, Im X_d

using PointCovariance = Eigen::Matrix<double, kInputsPerPoint, kInputsPerPoint>;

// One level sorted by frequency, the response as displacement. The raw
// vector holds every point's inputs, then any extra inputs a computation
// appends (a modal constant). Their covariance is block diagonal and kept
// as its blocks: one per point (ω, F and X_d are independent) and one for
// the extras. (Dense, it was (5n)² doubles: 800 MB for a level of 2000
// steps.)
struct LevelData {
  Eigen::VectorXd raw;
  std::vector<PointCovariance> point_covariance;
  Eigen::MatrixXd extra_covariance;  // of raw's entries after the points
  int order = 2;  // derivative order of the response quantity
  // The response's relative noise estimated from the sweep when the table
  // states none (0 when it does).
  double noise_from_sweep_relative_rms = 0.0;
  // The frequency-sorted index of each step, in the campaign's (run) order.
  std::vector<int> sorted_index_of_run;
  int size() const { return static_cast<int>(point_covariance.size()); }
  double OmegaVariance(int i) const { return point_covariance[i](0, 0); }
  Eigen::Matrix2d ForceCovariance(int i) const { return point_covariance[i].block<2, 2>(1, 1); }
  Eigen::Matrix2d DispCovariance(int i) const { return point_covariance[i].block<2, 2>(3, 3); }
};

struct PointView {
  double omega;
  std::complex<double> force, disp;
  std::complex<double> G() const { return force / disp; }
  double H() const { return std::abs(disp / force); }
};

PointView At(const Eigen::VectorXd& raw, int i) {
  const double* r = raw.data() + kInputsPerPoint * i;
  return {r[0], {r[1], r[2]}, {r[3], r[4]}};
}

// Steps a sweep needs before its own scatter says anything about its noise.
constexpr int kMinStepsForSweepNoise = 7;

// A table that states no uncertainty still has noise, and without a σ every
// difference between steps would read as physics (a jump, a flag, a σ of
// zero). Along a branch of one mode the inverse receptance G = F/X_d is
// nearly straight in ω² (A·G = ω_n² − ω² + 2iω·ζω_n), so a step's departure
// from the chord through its neighbours, e = G_i − (w₋G_{i−1} + w₊G_{i+1}),
// is noise: with relative noise r on X_d (E|δX|² = r²|X|²),
// E|e|² = r²(|G_i|² + w₋²|G_{i−1}|² + w₊²|G_{i+1}|²) =: r²·D_i, and |e|²/D_i
// is r² times a unit exponential variable, whose median is ln 2. The
// median over the sweep ignores the few steps where the curve bends (the
// top of a fold, a jump). Every response then gets that σ, as the table's
// own would have been used.
void EstimateNoiseFromSweepIfNoneStated(LevelData& data) {
  const int n = data.size();
  for (int i = 0; i < n; ++i)
    if (data.point_covariance[i].trace() > 0) return;
  if (n < kMinStepsForSweepNoise) return;
  std::vector<double> normalised;
  for (int i = 1; i + 1 < n; ++i) {
    const PointView a = At(data.raw, i - 1), b = At(data.raw, i), c = At(data.raw, i + 1);
    const double xa = a.omega * a.omega, xb = b.omega * b.omega, xc = c.omega * c.omega;
    if (!(xa < xb && xb < xc)) continue;
    const double w_before = (xc - xb) / (xc - xa), w_after = (xb - xa) / (xc - xa);
    const std::complex<double> e = b.G() - (w_before * a.G() + w_after * c.G());
    const double d = std::norm(b.G()) + w_before * w_before * std::norm(a.G()) + w_after * w_after * std::norm(c.G());
    if (d > 0 && std::isfinite(std::norm(e) / d)) normalised.push_back(std::norm(e) / d);
  }
  if (normalised.size() < 3) return;
  auto middle = normalised.begin() + normalised.size() / 2;
  std::nth_element(normalised.begin(), middle, normalised.end());
  const double relative = std::sqrt(*middle / std::log(2.0));
  if (!(relative > 0)) return;
  data.noise_from_sweep_relative_rms = relative;
  for (int i = 0; i < n; ++i) {
    const double variance = 0.5 * std::pow(relative * std::abs(At(data.raw, i).disp), 2);
    data.point_covariance[i].block<2, 2>(3, 3) = variance * Eigen::Matrix2d::Identity();
  }
}

LevelData MakeLevelData(const signal::FirstHarmonicLevel& level) {
  const int n = static_cast<int>(level.points.size());
  std::vector<int> run_of_sorted(n);
  for (int i = 0; i < n; ++i) run_of_sorted[i] = i;
  std::stable_sort(run_of_sorted.begin(), run_of_sorted.end(), [&](int a, int b) {
    return level.points[a].frequency_hz < level.points[b].frequency_hz;
  });
  LevelData data;
  data.sorted_index_of_run.resize(n);
  for (int i = 0; i < n; ++i) data.sorted_index_of_run[run_of_sorted[i]] = i;
  data.order = signal::DerivativeOrder(level.response_quantity);
  data.raw.resize(kInputsPerPoint * n);
  data.point_covariance.assign(n, PointCovariance::Zero());
  for (int i = 0; i < n; ++i) {
    const auto& p = level.points[run_of_sorted[i]];
    const double omega = kTwoPi * p.frequency_hz;
    const signal::HarmonicPhasor disp =
        signal::ConvertHarmonic(p.response, level.response_quantity, signal::Quantity::kDisplacement, omega);
    const int o = kInputsPerPoint * i;
    data.raw.segment(o, kInputsPerPoint) << omega, p.force.value.real(), p.force.value.imag(), disp.value.real(),
        disp.value.imag();
    data.point_covariance[i](0, 0) = std::pow(kTwoPi * p.frequency_std_hz, 2);
    data.point_covariance[i].block<2, 2>(1, 1) = p.force.Covariance();
    data.point_covariance[i].block<2, 2>(3, 3) = disp.Covariance();
  }
  EstimateNoiseFromSweepIfNoneStated(data);
  return data;
}

// Values and standard uncertainties of f(raw), linearised about the level's
// raw inputs (central differences, one input at a time perturbed in place:
// a copy per input would make a level of n steps cost n² in time). Only
// the points first…last (all by default) and the extra inputs can change f:
// the caller says so, since a number from a few steps around the peak does
// not depend on the other steps.
std::vector<Estimate> Propagate(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f, const LevelData& data,
                                int first = 0, int last = -1) {
  if (last < 0) last = data.size() - 1;
  const Eigen::VectorXd value = f(data.raw);
  const int m = static_cast<int>(value.size());
  Eigen::VectorXd x = data.raw;
  const auto column = [&](int j, double variance) -> Eigen::VectorXd {
    const double sigma = std::sqrt(variance);
    if (sigma == 0.0) return Eigen::VectorXd::Zero(m);  // exact input: no contribution
    const double h = 1e-3 * sigma, original = x[j];
    x[j] = original + h;
    const Eigen::VectorXd plus = f(x);
    x[j] = original - h;
    const Eigen::VectorXd minus = f(x);
    x[j] = original;
    return (plus - minus) / (2 * h);
  };
  Eigen::MatrixXd covariance = Eigen::MatrixXd::Zero(m, m);
  Eigen::MatrixXd jacobian(m, kInputsPerPoint);
  for (int i = std::max(0, first); i <= std::min(last, data.size() - 1); ++i) {
    for (int c = 0; c < kInputsPerPoint; ++c)
      jacobian.col(c) = column(kInputsPerPoint * i + c, data.point_covariance[i](c, c));
    covariance += jacobian * data.point_covariance[i] * jacobian.transpose();
  }
  const int extras = static_cast<int>(data.extra_covariance.rows());
  if (extras > 0) {
    Eigen::MatrixXd extra_jacobian(m, extras);
    for (int c = 0; c < extras; ++c)
      extra_jacobian.col(c) = column(kInputsPerPoint * data.size() + c, data.extra_covariance(c, c));
    covariance += extra_jacobian * data.extra_covariance * extra_jacobian.transpose();
  }
  std::vector<Estimate> out;
  for (int k = 0; k < value.size(); ++k)
    out.push_back({value[k], std::sqrt(std::max(0.0, covariance(k, k))), std::isfinite(value[k])});
  return out;
}

// Covariance of G = F/X_d from those of F and X_d (independent).
Eigen::Matrix2d InverseReceptanceCovariance(const LevelData& data, int i) {
  const PointView p = At(data.raw, i);
  auto real_matrix = [](std::complex<double> c) {
    Eigen::Matrix2d m;
    m << c.real(), -c.imag(), c.imag(), c.real();
    return m;
  };
  const Eigen::Matrix2d d_force = real_matrix(1.0 / p.disp);
  const Eigen::Matrix2d d_disp = real_matrix(-p.force / (p.disp * p.disp));
  return d_force * data.ForceCovariance(i) * d_force.transpose() + d_disp * data.DispCovariance(i) * d_disp.transpose();
}

// Phase-resonance point from the step k nearest quadrature: frequency [Hz],
// |X_d|, |F|, ζ. The last three raw inputs are Re A, Im A at the step's
// amplitude and the other modes' share R. Each step is a point of the
// backbone at its own (modal) amplitude a' = |X_d − R·F|: with
// A·G' = D = ω_n² − ω² + 2iω·ζω_n (G' = F/(X_d − R·F)), the sensor is in
// quadrature with the force where Re(A/D) + R = 0, i.e. with Δ = ω_n² − ω_q²
// and E = 2ω_q·ζω_n, Re A·Δ + Im A·E + R·(Δ² + E²) = 0 — a small move near
// quadrature, where Re G is small. The sensor's amplitude there is
// a'·|1 + R·D_q/A|. Interpolating Re G in ω² between the two bracketing
// steps instead is biased by the curvature of the backbone when the amplitude
// changes much between them (the far side of a hardening peak), and
// impossible across a jump.
Eigen::VectorXd QuadratureFrom(const Eigen::VectorXd& raw, int k) {
  const PointView p = At(raw, k);
  const std::complex<double> modal_constant(raw[raw.size() - 3], raw[raw.size() - 2]);
  const double residual = raw[raw.size() - 1];
  const std::complex<double> modal_disp = p.disp - residual * p.force;
  const std::complex<double> ag = modal_constant * p.force / modal_disp;
  const double omega_n_sq = p.omega * p.omega + ag.real();
  const double zeta_omega_n = ag.imag() / (2 * p.omega);
  double delta = 0.0, w2 = omega_n_sq;
  for (int iteration = 0; iteration < 4; ++iteration) {
    const double e = 2 * std::sqrt(w2) * zeta_omega_n;
    delta = -(modal_constant.imag() * e + residual * (delta * delta + e * e)) / modal_constant.real();
    w2 = omega_n_sq - delta;
  }
  const std::complex<double> d_q(delta, 2 * std::sqrt(w2) * zeta_omega_n);
  Eigen::VectorXd out(4);
  out << std::sqrt(w2) / kTwoPi, std::abs(modal_disp) * std::abs(1.0 + residual * d_q / modal_constant), std::abs(p.force),
      zeta_omega_n / std::sqrt(omega_n_sq);
  return out;
}

// The detected jump between frequency-sorted steps i and j, or null.
const SweepJump* JumpBetween(const LevelData& data, const std::vector<SweepJump>& jumps, int i, int j) {
  for (const auto& jump : jumps) {
    const int a = data.sorted_index_of_run[jump.from_step], b = data.sorted_index_of_run[jump.to_step];
    if ((a == i && b == j) || (a == j && b == i)) return &jump;
  }
  return nullptr;
}

// `modal_fit` gives A(a): the global fit, or the most linear level's local fit.
// A crossing of quadrature across a jump is no measured phase resonance. When
// the sweep dropped off the upper branch there (a hardening up-sweep, a
// softening down-sweep), the upper branch ends at its fold, next to its
// phase resonance: that last step before the jump is moved to quadrature by
// the single-mode model at its own amplitude, as any step is. When the sweep
// jumped up onto the upper branch (a hardening down-sweep), it landed far
// before resonance (phase short of −90°) and left it the way it came: no
// phase resonance was measured.
void FindQuadrature(const LevelData& data, const SingleModeFit& modal_fit, const SingleModeFit& local_fit,
                    LevelResonance& out) {
  const int n = data.size();
  int best = -1;
  double best_h = 0.0;
  for (int i = 0; i + 1 < n; ++i) {
    const PointView a = At(data.raw, i), b = At(data.raw, i + 1);
    if ((a.G().real() > 0) == (b.G().real() > 0)) continue;
    // Among several crossings (noise far from the mode), the one of largest response.
    const double h = std::max(a.H(), b.H());
    if (h > best_h) best_h = h, best = i;
  }
  if (best < 0) {
    out.quadrature_note = "the response never crosses quadrature with the force: widen the sweep";
    return;
  }
  const int i = best, j = best + 1;
  int k = std::abs(At(data.raw, i).G().real()) / std::abs(At(data.raw, i).G()) <
                  std::abs(At(data.raw, j).G().real()) / std::abs(At(data.raw, j).G())
              ? i
              : j;
  if (const SweepJump* jump = JumpBetween(data, out.jumps, i, j)) {
    if (jump->receptance_ratio >= 1.0) {
      out.quadrature_note = "the response crosses quadrature with the force only across a jump up onto the upper "
                            "branch (fold) of the sweep: the phase resonance was not measured (sweep the other way, or "
                            "control the response)";
      return;
    }
    k = data.sorted_index_of_run[jump->from_step];
    out.quadrature_note = "the response crosses quadrature across a drop off the upper branch (fold): the phase "
                          "resonance is taken at the last step before the drop, moved to quadrature by the "
                          "single-mode model";
  }
  if (!modal_fit.ok) {
    out.quadrature_note = "too few points near the mode for the modal constant";
    return;
  }
  // The modal constant at the step's amplitude as two more inputs, with their
  // covariance: where the step lies far from the amplitudes that pin A(a)
  // down (the top of a folding curve), that is the extrapolation's
  // uncertainty. Then R, with its σ and its covariance with A (the fit moved
  // A with R: R takes part of the peak's height, A the rest, and ζ reads A).
  const double residual = modal_fit.residual_receptance_m_N;
  const double step_amplitude = std::abs(At(data.raw, k).disp - residual * At(data.raw, k).force);
  const std::complex<double> modal_constant = modal_fit.ModalConstantAt(step_amplitude);
  LevelData with_constant = data;
  const int n_raw = static_cast<int>(data.raw.size());
  with_constant.raw.conservativeResize(n_raw + 3);
  with_constant.raw.tail(3) << modal_constant.real(), modal_constant.imag(), residual;
  with_constant.extra_covariance = Eigen::MatrixXd::Zero(3, 3);
  with_constant.extra_covariance.block(0, 0, 2, 2) = modal_fit.ModalConstantCovariance(step_amplitude);
  const Eigen::Vector2d with_residual = modal_fit.ModalConstantResidualCovariance(step_amplitude);
  with_constant.extra_covariance.block(0, 2, 2, 1) = with_residual;
  with_constant.extra_covariance.block(2, 0, 1, 2) = with_residual.transpose();
  with_constant.extra_covariance(2, 2) = std::pow(modal_fit.residual_receptance_std_m_N, 2);
  const auto e = Propagate([&](const Eigen::VectorXd& raw) { return QuadratureFrom(raw, k); }, with_constant, k, k);
  out.quadrature_frequency_hz = e[0];
  // Beyond the noise: how far this level strays from one nonlinear mode
  // (from the fit across levels when the level has too few points near the
  // mode for its own).
  const double model_residual_rad2_s2 =
      local_fit.ok ? local_fit.backbone_residual_rms_rad2_s2 : modal_fit.backbone_residual_rms_rad2_s2;
  const double model_std_hz = model_residual_rad2_s2 / (2 * kTwoPi * e[0].value) / kTwoPi;
  out.quadrature_frequency_hz.std = std::hypot(e[0].std, model_std_hz);
  out.quadrature_amplitude_m = e[1];
  out.quadrature_force_N = e[2];
  out.quadrature_damping_ratio = e[3];
  const double scale = std::pow(kTwoPi * e[0].value, data.order);
  out.quadrature_response_amplitude = {e[1].value * scale, e[1].std * scale, true};
}

// The steps as the campaign took them, for the jump detection.
std::vector<SweepPoint> SweepPointsInRunOrder(const LevelData& data) {
  std::vector<SweepPoint> points;
  for (int s : data.sorted_index_of_run) {
    const PointView p = At(data.raw, s);
    points.push_back({.frequency_hz = p.omega / kTwoPi,
                      .inverse_receptance_N_m = p.G(),
                      .inverse_receptance_std_N_m = std::sqrt(InverseReceptanceCovariance(data, s).trace())});
  }
  return points;
}

int PeakIndex(const Eigen::VectorXd& raw, int n) {
  int best = 0;
  for (int i = 1; i < n; ++i)
    if (At(raw, i).H() > At(raw, best).H()) best = i;
  return best;
}

// x = ω² spans a fraction ~ζ of its value across a peak (2.5·10⁵ ± 10³ at
// 80 Hz, ζ = 0.002): a quadratic in raw ω² is the difference of terms 10⁸
// times larger than the curvature it must find. Both fits below work in
// u = (x − centre)/half_width instead, where u, u² are of order one.
struct CentredAxis {
  double centre = 0, half_width = 1;
  double U(double x) const { return (x - centre) / half_width; }
  double X(double u) const { return centre + half_width * u; }
};

CentredAxis AxisOver(double x_first, double x_last) {
  const double half_width = 0.5 * std::abs(x_last - x_first);
  return {.centre = 0.5 * (x_first + x_last), .half_width = half_width > 0 ? half_width : 1.0};
}

// The quadratic through three points (u, y): y = c0 + c1·u + c2·u².
Eigen::Vector3d Quadratic(const double u[3], const double y[3]) {
  Eigen::Matrix3d m;
  for (int k = 0; k < 3; ++k) m.row(k) << 1.0, u[k], u[k] * u[k];
  return m.colPivHouseholderQr().solve(Eigen::Vector3d(y[0], y[1], y[2]));
}

// The top of the peak: the steps [first, last] around the largest, m, whose
// |X_d/F| is at least 1/√2 of it (at least m − 1 … m + 1).
std::pair<int, int> PeakTop(const Eigen::VectorXd& raw, int n, int m) {
  const double top = At(raw, m).H() / std::sqrt(2.0);
  int first = m - 1, last = m + 1;
  while (first > 0 && At(raw, first - 1).H() >= top) --first;
  while (last + 1 < n && At(raw, last + 1).H() >= top) ++last;
  return {first, last};
}

// Peak frequency [Hz], |X_d/F| and |X_d| there, then the half-power ζ, the
// half-power frequencies [Hz] and the natural frequency [Hz] they give (NaN
// if not available). For one mode 1/|H|² is a quadratic in ω² exactly,
// ((ω_n² − ω²)² + (2ζω_nω)²)/A², so the peak is the vertex of the quadratic
// fitted to the steps of the top (PeakTop) and each half-power crossing is
// solved on the quadratic through the three steps around it: exact for one
// linear mode whatever the steps' spacing, and three steps per side are
// enough. Where the top does not bend like a peak (noise on a flat top, a
// vertex outside it) there is no peak: all NaN, rather than a number from
// the highest step that its σ would not describe. From the crossings ω₁²,
// ω₂² and the vertex ω_p² = ω_n²(1 − 2ζ²), r = (ω₂² − ω₁²)/(4ω_p²) =
// ζ√(1 − ζ²)/(1 − 2ζ²) exactly, so ζ² = (1 − 1/√(1 + 4r²))/2 (the usual
// ζ ≈ r is off by 1.5 ζ² relative).
Eigen::VectorXd PeakAndHalfPower(const Eigen::VectorXd& raw, int n, int m, std::pair<int, int> top) {
  auto x_of = [&](int i) { return At(raw, i).omega * At(raw, i).omega; };
  auto y_of = [&](int i) { return 1.0 / (At(raw, i).H() * At(raw, i).H()); };
  // The vertex of the quadratic fitted (relative weights) to every step of
  // the top: three steps alone, when two lie close together, turn noise into
  // a vertex anywhere.
  const int count = top.second - top.first + 1;
  const CentredAxis top_axis = AxisOver(x_of(top.first), x_of(top.second));
  Eigen::MatrixXd basis(count, 3);
  Eigen::VectorXd y(count), a(count);
  for (int k = 0; k < count; ++k) {
    const int i = top.first + k;
    const double weight = 1 / y_of(i), u = top_axis.U(x_of(i));
    basis.row(k) << weight, weight * u, weight * u * u;
    y[k] = 1.0;
    a[k] = weight * std::abs(At(raw, i).disp);
  }
  const auto qr = basis.colPivHouseholderQr();
  const Eigen::Vector3d peak = qr.solve(y), amplitude = qr.solve(a);
  const double u_peak = -peak[1] / (2 * peak[2]);
  const double y_peak = peak[0] + peak[1] * u_peak + peak[2] * u_peak * u_peak;
  if (!(peak[2] > 0 && u_peak >= -1 && u_peak <= 1))
    return Eigen::VectorXd::Constant(7, std::numeric_limits<double>::quiet_NaN());
  const double x_peak = top_axis.X(u_peak);
  const double level = 2 * y_peak;
  // The crossing of the level on one side (step −1 below the vertex, +1
  // above), bracketed by the vertex or the last step above the level and the
  // first step below it. The step nearest the vertex may itself lie outside
  // the half-power band when the steps are coarse.
  auto crossing = [&](int step) {
    int near = m;
    while ((x_of(near) - x_peak) * step < 0) {
      if (near + step < 0 || near + step >= n) return std::numeric_limits<double>::quiet_NaN();
      near += step;
    }
    double x_in = x_peak, y_in = y_peak;
    int out = near;
    while (y_of(out) <= level) {
      x_in = x_of(out), y_in = y_of(out);
      if (out + step < 0 || out + step >= n) return std::numeric_limits<double>::quiet_NaN();
      out += step;
    }
    // Three steps around the crossing: out − 2·step, out − step, out (or the
    // nearest three inside the sweep).
    int c = out - step;
    if (c - step < 0 || c - step >= n) c = out;
    if (c + step < 0 || c + step >= n) c = out - step;
    const CentredAxis axis = AxisOver(x_of(c - step), x_of(c + step));
    double us[3], ys[3];
    for (int k = -1; k <= 1; ++k) {
      us[k + 1] = axis.U(x_of(c + k * step));
      ys[k + 1] = y_of(c + k * step) / level;
    }
    // In units of the level, the crossing is where the quadratic is 1.
    const Eigen::Vector3d q = Quadratic(us, ys);
    const double disc = q[1] * q[1] - 4 * q[2] * (q[0] - 1);
    const double lo = std::min(axis.U(x_in), axis.U(x_of(out))), hi = std::max(axis.U(x_in), axis.U(x_of(out)));
    // Both roots without cancellation (the quadratic is nearly straight
    // between close steps): h = −(c1 + sign(c1)·√disc)/2, roots h/c2 and (c0 − 1)/h.
    if (disc >= 0) {
      const double h = -0.5 * (q[1] + std::copysign(std::sqrt(disc), q[1]));
      for (double root : {q[2] != 0 ? h / q[2] : NAN, h != 0 ? (q[0] - 1) / h : NAN})
        if (root >= lo && root <= hi) return std::sqrt(axis.X(root));
    }
    // Not one mode's shape there: linear interpolation.
    return std::sqrt(x_in + (level - y_in) / (y_of(out) - y_in) * (x_of(out) - x_in));
  };
  const double w1 = crossing(-1), w2 = crossing(+1);
  const double r = (w2 * w2 - w1 * w1) / (4 * x_peak);
  const double zeta = std::sqrt(0.5 * (1 - 1 / std::sqrt(1 + 4 * r * r)));
  Eigen::VectorXd out(7);
  out << std::sqrt(x_peak) / kTwoPi, 1 / std::sqrt(y_peak),
      amplitude[0] + amplitude[1] * u_peak + amplitude[2] * u_peak * u_peak, std::copysign(zeta, r), w1 / kTwoPi,
      w2 / kTwoPi, std::sqrt(x_peak / (1 - 2 * zeta * zeta)) / kTwoPi;
  return out;
}

void FindPeakAndHalfPower(const LevelData& data, LevelResonance& out) {
  const int n = data.size();
  const int m = PeakIndex(data.raw, n);
  if (m == 0 || m == n - 1) {
    out.half_power_note = "the largest response is at the end of the sweep: no peak, no half-power points";
    return;
  }
  const auto top = PeakTop(data.raw, n, m);
  const auto f = [&](const Eigen::VectorXd& raw) { return PeakAndHalfPower(raw, n, m, top); };
  // The steps it reads: the top, and three around each crossing (or, without
  // one, every step to the sweep's end on that side).
  const Eigen::VectorXd value = f(data.raw);
  int first = top.first, last = top.second;
  if (std::isfinite(value[4]))
    while (first > 0 && At(data.raw, first).omega > kTwoPi * value[4]) --first;
  else
    first = 0;
  if (std::isfinite(value[5]))
    while (last + 1 < n && At(data.raw, last).omega < kTwoPi * value[5]) ++last;
  else
    last = n - 1;
  const auto e = Propagate(f, data, first - 2, last + 2);
  out.peak_frequency_hz = e[0];
  out.peak_receptance_m_N = e[1];
  out.peak_amplitude_m = e[2];
  out.half_power_damping_ratio = e[3];
  out.half_power_lower_frequency_hz = e[4];
  out.half_power_upper_frequency_hz = e[5];
  out.half_power_natural_frequency_hz = e[6];
  if (!e[0].valid) {
    out.half_power_note = "the steps at the top of the curve do not bend like one peak (noise on a flat top, or "
                          "steps too far apart): no peak, no half-power points";
  } else if (!e[3].valid) {
    out.half_power_note = fmt::format("the response does not fall to 1/√2 of its peak {} the peak: widen the sweep",
                                      !e[4].valid && !e[5].valid ? "on either side of"
                                      : !e[4].valid             ? "below"
                                                                : "above");
    out.half_power_natural_frequency_hz = {};
  }
  if (out.quadrature_after_jump) {
    // One side of the peak lies on the other branch of a fold, and its
    // largest step is the fold's edge (where an up-sweep dropped off, or a
    // down-sweep landed), not the top of a curve: a vertex fitted there is
    // no peak frequency.
    out.peak_frequency_hz.valid = false;
    out.half_power_damping_ratio.valid = false;
    out.half_power_lower_frequency_hz.valid = out.half_power_upper_frequency_hz.valid = false;
    out.half_power_natural_frequency_hz.valid = false;
    out.half_power_note = "the sweep jumped (a folded curve): its largest step is the fold's edge and one side of "
                          "it lies on another branch, no peak frequency or half-power estimate";
  }
}

LevelControl DetectControl(const LevelData& data, double tolerance) {
  double f_min = INFINITY, f_max = 0, x_min = INFINITY, x_max = 0;
  for (int i = 0; i < data.size(); ++i) {
    const PointView p = At(data.raw, i);
    const double x = std::abs(p.disp) * std::pow(p.omega, data.order);
    f_min = std::min(f_min, std::abs(p.force));
    f_max = std::max(f_max, std::abs(p.force));
    x_min = std::min(x_min, x);
    x_max = std::max(x_max, x);
  }
  if (f_max / f_min - 1 <= tolerance) return LevelControl::kForce;
  if (x_max / x_min - 1 <= tolerance) return LevelControl::kResponse;
  return LevelControl::kNeither;
}

std::vector<SingleModePoint> FitPoints(const LevelData& data, double window) {
  const int n = data.size();
  const double peak = At(data.raw, PeakIndex(data.raw, n)).H();
  std::vector<SingleModePoint> points;
  for (int i = 0; i < n; ++i) {
    const PointView p = At(data.raw, i);
    if (p.H() < window * peak) continue;
    // a = |X_d| and G = F/X_d share X_d's noise.
    const Eigen::Vector2d amplitude_gradient = Eigen::Vector2d(p.disp.real(), p.disp.imag()) / std::abs(p.disp);
    const std::complex<double> d_disp = -p.force / (p.disp * p.disp);
    Eigen::Matrix2d g_of_disp;
    g_of_disp << d_disp.real(), -d_disp.imag(), d_disp.imag(), d_disp.real();
    const Eigen::Vector2d disp_amplitude = data.DispCovariance(i) * amplitude_gradient;
    points.push_back({.omega_rad_s = p.omega,
                      .omega_std_rad_s = std::sqrt(data.OmegaVariance(i)),
                      .inverse_receptance_N_m = p.G(),
                      .inverse_receptance_covariance = InverseReceptanceCovariance(data, i),
                      .amplitude_m = std::abs(p.disp),
                      .amplitude_variance_m2 = amplitude_gradient.dot(disp_amplitude),
                      .amplitude_inverse_receptance_covariance = g_of_disp * disp_amplitude});
  }
  return points;
}

SingleModeFitOptions LocalFitForm(const std::vector<SingleModePoint>& points, double tolerance) {
  double a_min = INFINITY, a_max = 0;
  for (const auto& p : points) a_min = std::min(a_min, p.amplitude_m), a_max = std::max(a_max, p.amplitude_m);
  // A level held at one amplitude cannot tell how ω_n and ζ change with it.
  const int degree = a_max / a_min - 1 > tolerance ? 1 : 0;
  return {.frequency_degree = 2 * degree, .damping_degree = degree, .reference_amplitude_m = a_max};
}

SingleModeFit LocalFit(const std::vector<SingleModePoint>& points, double tolerance, double residual) {
  SingleModeFitOptions form = LocalFitForm(points, tolerance);
  form.residual_receptance_m_N = residual;
  return FitSingleMode(points, form);
}

// LevelResonance::free_decay: the ring-down of the step nearest the phase
// resonance, else the peak, else the largest response.
void TakeFreeDecay(const signal::FirstHarmonicLevel& level, LevelResonance& out) {
  const double centre_hz = out.quadrature_frequency_hz.valid ? out.quadrature_frequency_hz.value
                           : out.peak_frequency_hz.valid    ? out.peak_frequency_hz.value
                                                            : NAN;
  const signal::FirstHarmonicPoint* chosen = nullptr;
  const auto distance = [&](const signal::FirstHarmonicPoint& p) {
    return std::isfinite(centre_hz) ? std::abs(p.frequency_hz - centre_hz) : -std::abs(p.response.value / p.force.value);
  };
  for (const signal::FirstHarmonicPoint& p : level.points)
    if (!p.free_decay.empty() && (!chosen || distance(p) < distance(*chosen))) chosen = &p;
  if (!chosen) return;
  out.free_decay = chosen->free_decay;
  out.free_decay_step_frequency_hz = chosen->frequency_hz;
  const signal::DecayPoint& first = chosen->free_decay.front();
  out.free_decay_damping_ratio = {.value = first.damping_ratio, .std = first.damping_ratio_std, .valid = true};
}

void EvaluateLocalFit(const SingleModeFit& fit, LevelResonance& out) {
  if (!fit.ok) return;
  const double a = out.quadrature_amplitude_m.valid ? out.quadrature_amplitude_m.value : fit.reference_amplitude_m;
  out.local_natural_frequency_hz = {fit.NaturalFrequency_rad_s(a) / kTwoPi, fit.NaturalFrequencyStd_rad_s(a) / kTwoPi,
                                    true};
  out.local_damping_ratio = {fit.DampingRatio(a), fit.DampingRatioStd(a), true};
  out.local_reduced_chi_square = fit.ReducedChiSquare();
}

// The amplitude a ∈ (0, a_max] with a·|D(a, ω)| = |A·F| closest to `measured`
// (several on a folded curve); NaN if there is none.
double SolveAmplitude(const SingleModeFit& fit, double omega, double force_amplitude, double a_max, double measured) {
  auto g = [&](double a) {
    return a * std::abs(fit.DynamicTerm(a, omega)) - std::abs(fit.ModalConstantAt(a)) * force_amplitude;
  };
  constexpr int kGrid = 400;
  double best = std::numeric_limits<double>::quiet_NaN();
  double lo = 0.0, g_lo = g(0.0);
  for (int k = 1; k <= kGrid; ++k) {
    const double hi = a_max * k / kGrid, g_hi = g(hi);
    if ((g_lo <= 0) != (g_hi <= 0)) {
      double x0 = lo, x1 = hi, g0 = g_lo;
      for (int it = 0; it < 60; ++it) {
        const double xm = 0.5 * (x0 + x1), gm = g(xm);
        if ((gm <= 0) == (g0 <= 0)) x0 = xm, g0 = gm;
        else x1 = xm;
      }
      const double root = 0.5 * (x0 + x1);
      if (!(std::abs(root - measured) >= std::abs(best - measured))) best = root;
    }
    lo = hi;
    g_lo = g_hi;
  }
  return best;
}

// The fit's step in place of the measured one, X_d = F·(A/D + R): the
// response from the measured force (force-controlled or neither; on the
// branch nearest the measured amplitude) or the force from the measured
// response (response-controlled, at the modal amplitude it shows).
PointView ModelPoint(const SingleModeFit& fit, const PointView& p, LevelControl control, double a_max) {
  const double residual = fit.residual_receptance_m_N;
  PointView model = p;
  if (control == LevelControl::kResponse) {
    const double a = std::abs(p.disp - residual * p.force);
    model.force = p.disp / (fit.ModalConstantAt(a) / fit.DynamicTerm(a, p.omega) + residual);
  } else {
    const double a = SolveAmplitude(fit, p.omega, std::abs(p.force), 2 * a_max, std::abs(p.disp - residual * p.force));
    model.disp = (fit.ModalConstantAt(a) / fit.DynamicTerm(a, p.omega) + residual) * p.force;
  }
  return model;
}

// The fit regenerates the level, step by step, as the test ran it
// (ModelPoint). At the last step before a jump, on the branch that ends at
// the fold, the force-controlled reading is singular: a fold's frequency
// moves with the parameters far faster than any amplitude on the curve, and
// a fit whose fold lies one step short of the measured one puts that step on
// the other branch (a 100 % miss, the level's whole RMS, on a 3 % noise
// table whose parameters hold their truth). There the fit is read as it was
// fitted, at the measured amplitude: the force it needs to hold the step, as
// for a response-controlled level. (Not the step after the jump: it lands on
// a branch far from its fold, and near the top of the upper branch, where
// |D| is small, the force reading magnified a sound fit's error to 65-83 %.)
void Regenerate(const SingleModeFit& fit, const LevelData& data, const std::vector<SweepJump>& jumps, double window,
                double a_max, LevelResonance& out) {
  std::vector<bool> before_jump(data.size(), false);
  for (const auto& jump : jumps) before_jump[data.sorted_index_of_run[jump.from_step]] = true;
  // The fitted points (FitPoints' window).
  const double peak = At(data.raw, PeakIndex(data.raw, data.size())).H();
  double sum_sq = 0, worst = 0, chi_square = 0, noise_sq = 0;
  int count = 0;
  for (int i = 0; i < data.size(); ++i) {
    const PointView p = At(data.raw, i);
    if (p.H() < window * peak) continue;
    const bool response = out.control == LevelControl::kResponse || before_jump[i];
    const PointView model = ModelPoint(fit, p, response ? LevelControl::kResponse : out.control, a_max);
    const std::complex<double> predicted = response ? model.force : model.disp;
    const std::complex<double> measured = response ? p.force : p.disp;
    const Eigen::Matrix2d covariance = response ? data.ForceCovariance(i) : data.DispCovariance(i);
    const std::complex<double> error = predicted - measured;
    const double relative = std::abs(error) / std::abs(measured);
    sum_sq += relative * relative;
    // The relative error variance the noise of F and X_d alone gives (either way round).
    noise_sq += data.ForceCovariance(i).trace() / std::norm(p.force) + data.DispCovariance(i).trace() / std::norm(p.disp);
    worst = std::max(worst, std::isfinite(relative) ? relative : INFINITY);
    if (covariance.trace() > 0) {
      const Eigen::Vector2d e(error.real(), error.imag());
      chi_square += e.dot(covariance.ldlt().solve(e));
    }
    ++count;
  }
  out.regeneration_relative_rms = count ? std::sqrt(sum_sq / count) : 0.0;
  out.regeneration_max_relative = worst;
  out.regeneration_reduced_chi_square = count ? chi_square / (2 * count) : 0.0;
  out.regeneration_noise_relative_rms = count ? std::sqrt(noise_sq / count) : 0.0;
}

// The steps as the page draws them, in the campaign's (run) order.
std::vector<LevelFrfPoint> MeasuredFrf(const LevelData& data) {
  std::vector<LevelFrfPoint> points;
  for (int s : data.sorted_index_of_run) {
    const PointView p = At(data.raw, s);
    points.push_back(
        {.frequency_hz = p.omega / kTwoPi, .receptance_m_N = p.H(), .phase_rad = std::arg(p.disp / p.force)});
  }
  return points;
}

// Points of the fit's curve between two frequency-sorted steps; at most
// about this many in all, however many steps the level has.
constexpr int kFitFrfPoints = 400;

// The fit's X_d/F at and between the frequency-sorted steps, the force (or,
// response-controlled, the modal amplitude) interpolated between them, each
// point on the branch nearest the measured amplitude (as Regenerate does),
// so that the curve of a folded level follows the branch the sweep was on.
std::vector<LevelFrfPoint> FitFrf(const SingleModeFit& fit, const LevelData& data, LevelControl control,
                                  double a_max) {
  const int n = data.size();
  const int subdivisions = std::max(1, kFitFrfPoints / std::max(1, n - 1));
  const double residual = fit.residual_receptance_m_N;
  std::vector<LevelFrfPoint> curve;
  for (int i = 0; i < n; ++i) {
    const PointView a = At(data.raw, i), b = At(data.raw, std::min(i + 1, n - 1));
    for (int k = 0; k < (i + 1 < n ? subdivisions : 1); ++k) {
      const double t = static_cast<double>(k) / subdivisions;
      const double omega = a.omega + t * (b.omega - a.omega);
      const std::complex<double> force = a.force + t * (b.force - a.force);
      const double measured =
          (1 - t) * std::abs(a.disp - residual * a.force) + t * std::abs(b.disp - residual * b.force);
      const double amplitude = control == LevelControl::kResponse
                                   ? measured
                                   : SolveAmplitude(fit, omega, std::abs(force), 2 * a_max, measured);
      const std::complex<double> receptance =
          fit.ModalConstantAt(amplitude) / fit.DynamicTerm(amplitude, omega) + residual;
      curve.push_back(
          {.frequency_hz = omega / kTwoPi, .receptance_m_N = std::abs(receptance), .phase_rad = std::arg(receptance)});
    }
  }
  return curve;
}

// The peak and half-power estimators read |X_d/F| as one linear mode's
// (1/|X_d/F|² a quadratic in ω²). Along a force-controlled nonlinear curve
// the amplitude, and with it ω_n(a), changes from step to step, and another
// mode's share R skews the peak: no noise, so the propagated σ does not see
// it (on a hardening level below its fold, stepped coarsely, the peak came
// out 145 mHz, 8 σ, low at 0.3 % noise). The same estimators, at the same
// steps, read on a fit's noise-free curve, whose peak and whose ζ and ω_n
// at the peak's amplitude are known: their departure there is the method's
// bias on this level (NaN where it cannot be read).
struct LinearModeBias {
  double peak_frequency_hz = NAN, half_power_damping_ratio = NAN, half_power_natural_frequency_hz = NAN;
};

LinearModeBias PredictLinearModeBias(const SingleModeFit& fit, const LevelData& data, double a_max,
                                     LevelControl control) {
  const int n = data.size();
  Eigen::VectorXd raw = data.raw;
  for (int i = 0; i < n; ++i) {
    const PointView model = ModelPoint(fit, At(data.raw, i), control, a_max);
    raw.segment(kInputsPerPoint * i + 1, 4) << model.force.real(), model.force.imag(), model.disp.real(),
        model.disp.imag();
  }
  // The steps the estimator read on the measured curve: two steps of nearly
  // equal height at the top swap places between the two curves, and a
  // vertex fitted to other steps has another bias.
  const int m = PeakIndex(data.raw, n);
  if (m == 0 || m == n - 1) return {};
  const Eigen::VectorXd read = PeakAndHalfPower(raw, n, m, PeakTop(data.raw, n, m));
  const double a = read[2];
  if (!std::isfinite(read[0]) || !(a > 0)) return {};
  // The model's own peak at that amplitude (golden section about ω_n(a)).
  const double omega_n = fit.NaturalFrequency_rad_s(a), zeta = fit.DampingRatio(a);
  const auto receptance = [&](double w) {
    return std::abs(fit.ModalConstantAt(a) / fit.DynamicTerm(a, w) + fit.residual_receptance_m_N);
  };
  const double golden = (std::sqrt(5.0) - 1) / 2, width = 4 * std::clamp(std::abs(zeta), 1e-6, 0.2);
  double lo = omega_n * (1 - width), hi = omega_n * (1 + width);
  for (int iteration = 0; iteration < 100; ++iteration) {
    const double w1 = hi - golden * (hi - lo), w2 = lo + golden * (hi - lo);
    if (receptance(w1) < receptance(w2))
      lo = w1;
    else
      hi = w2;
  }
  return {.peak_frequency_hz = read[0] - 0.5 * (lo + hi) / kTwoPi,
          .half_power_damping_ratio = read[3] - zeta,
          .half_power_natural_frequency_hz = read[6] - omega_n / kTwoPi};
}

// The predicted biases' standard uncertainties: the fit's parameters and R,
// with their covariance, propagated to first order (R fitted to noise on a
// linear mode predicts a skew that is not there).
LinearModeBias LinearModeBiasStd(const SingleModeFit& fit, const LevelData& data, double a_max,
                                 LevelControl control) {
  const int k = static_cast<int>(fit.parameters.size());
  Eigen::MatrixXd covariance = Eigen::MatrixXd::Zero(k + 1, k + 1);
  covariance.topLeftCorner(k, k) = fit.covariance;
  if (fit.residual_covariance.size() == k) {
    covariance.block(0, k, k, 1) = fit.residual_covariance;
    covariance.block(k, 0, 1, k) = fit.residual_covariance.transpose();
  }
  covariance(k, k) = std::pow(fit.residual_receptance_std_m_N, 2);
  const auto read = [&](const SingleModeFit& f) {
    const LinearModeBias b = PredictLinearModeBias(f, data, a_max, control);
    return Eigen::Vector3d(b.peak_frequency_hz, b.half_power_damping_ratio, b.half_power_natural_frequency_hz);
  };
  Eigen::MatrixXd jacobian = Eigen::MatrixXd::Zero(3, k + 1);
  for (int j = 0; j <= k; ++j) {
    const double h = 1e-3 * std::sqrt(covariance(j, j));
    if (!(h > 0)) continue;
    SingleModeFit plus = fit, minus = fit;
    if (j < k) {
      plus.parameters[j] += h;
      minus.parameters[j] -= h;
    } else {
      plus.residual_receptance_m_N += h;
      minus.residual_receptance_m_N -= h;
    }
    jacobian.col(j) = (read(plus) - read(minus)) / (2 * h);
  }
  const Eigen::Matrix3d bias_covariance = jacobian * covariance * jacobian.transpose();
  return {.peak_frequency_hz = std::sqrt(bias_covariance(0, 0)),
          .half_power_damping_ratio = std::sqrt(bias_covariance(1, 1)),
          .half_power_natural_frequency_hz = std::sqrt(bias_covariance(2, 2))};
}

// Below this fraction of the number a predicted bias is the arithmetic's
// rounding (the half-power ζ differences terms 1/ζ² larger than itself: 10⁸
// at ζ = 10⁻⁴), not the curve's; it matters on an exact table, whose σ is 0.
constexpr double kBiasRounding = 1e-7;

// Where a linear-mode estimator's predicted bias is established (beyond
// twice its own uncertainty, as estimators part beyond their noise in the
// level's ζ) and exceeds the estimate's σ, the number is flagged where it is
// shown (and a flagged ζ stays out of the level's ζ), never hidden inside a
// σ widened to cover it.
// (The prediction's uncertainty, `bias_std`, costs a regeneration per
// parameter: it is asked for only where a bias beyond σ is predicted.)
void FlagNonlinearCurve(const LinearModeBias& bias, const std::function<LinearModeBias()>& bias_std,
                        std::string_view source, LevelResonance& r) {
  std::optional<LinearModeBias> uncertainty;
  for (const auto& [estimate, predicted, member, quantity, what, unit, scale] :
       {std::tuple{&r.peak_frequency_hz, bias.peak_frequency_hz, &LinearModeBias::peak_frequency_hz,
                   "peak_frequency", "peak frequency", "Hz", 1.0},
        std::tuple{&r.half_power_damping_ratio, bias.half_power_damping_ratio,
                   &LinearModeBias::half_power_damping_ratio, "half_power_damping_ratio", "half-power ζ", "%", 100.0},
        std::tuple{&r.half_power_natural_frequency_hz, bias.half_power_natural_frequency_hz,
                   &LinearModeBias::half_power_natural_frequency_hz, "half_power_natural_frequency",
                   "half-power natural frequency", "Hz", 1.0}}) {
    if (!(estimate->valid && std::abs(predicted) > estimate->std &&
          std::abs(predicted) > kBiasRounding * std::abs(estimate->value)))
      continue;
    if (!uncertainty) uncertainty = bias_std();
    const double predicted_std = (*uncertainty).*member;
    if (std::abs(predicted) > 2 * (std::isfinite(predicted_std) ? predicted_std : 0.0))
      r.flags.push_back(
          {.kind = LevelFlagKind::kNonlinearCurve,
           .quantity = quantity,
           .message = fmt::format("the curve is not one linear mode's (the amplitude changes along it, or another "
                                  "mode's share skews it): the {} is biased by {:+.3g} {} (predicted from {}, ± "
                                  "{:.2g}), beyond its σ of {:.2g} {}{}",
                                  what, scale * predicted, unit, source, scale * predicted_std,
                                  scale * estimate->std, unit,
                                  estimate == &r.half_power_damping_ratio ? "; not in the level's ζ" : "")});
  }
}

bool FlaggedNonlinear(const LevelResonance& r, std::string_view quantity) {
  return std::any_of(r.flags.begin(), r.flags.end(), [&](const LevelFlag& f) {
    return f.kind == LevelFlagKind::kNonlinearCurve && f.quantity == quantity;
  });
}

// The steps between the half-power frequencies (−1 without both).
int StepsInHalfPowerBand(const LevelData& data, const LevelResonance& r) {
  if (!r.half_power_lower_frequency_hz.valid || !r.half_power_upper_frequency_hz.valid) return -1;
  int count = 0;
  for (int i = 0; i < data.size(); ++i) {
    const double f_hz = At(data.raw, i).omega / kTwoPi;
    if (f_hz >= r.half_power_lower_frequency_hz.value && f_hz <= r.half_power_upper_frequency_hz.value) ++count;
  }
  return count;
}

bool HalfPowerTooCoarse(const LevelData& data, const LevelResonance& r) {
  const int steps = StepsInHalfPowerBand(data, r);
  return steps >= 0 && steps < kMinStepsInHalfPowerBand;
}

// A number of a message in `format`, or words where it is not finite: a
// step of no response or no force makes a ratio or a relative error
// infinite, and a person reads no "nan".
std::string FiniteOr(double x, std::string_view format) {
  return std::isfinite(x) ? fmt::format(fmt::runtime(format), x)
                          : "not estimated (a step of no response or no force)";
}

std::string Percent(double fraction) { return FiniteOr(100 * fraction, "{:.3g} %"); }

// The drop off the upper branch when the phase resonance, moved to
// quadrature from the last step before it, lands past the step after it:
// where the sweep found that branch gone (a fold at 3 % noise put it 0.4 Hz
// past its truth, its ζ five times the truth's). Null otherwise.
const SweepJump* QuadraturePastTheDrop(const LevelResonance& r) {
  if (!r.quadrature_after_jump || !r.quadrature_frequency_hz.valid) return nullptr;
  for (const auto& jump : r.jumps) {
    if (!(jump.receptance_ratio < 1.0)) continue;
    const double onward = jump.to_frequency_hz - jump.from_frequency_hz;
    if ((r.quadrature_frequency_hz.value - jump.to_frequency_hz) * onward > 0) return &jump;
  }
  return nullptr;
}

// LevelResonance::damping_ratio from the three estimators; a half-power ζ
// read between steps too coarse for it, or on a curve that is not one linear
// mode's, stays out (flagged where it is shown) rather than widening the
// level's σ to cover it.
void CombineDampingRatios(const LevelData& data, LevelResonance& r) {
  const std::tuple<const Estimate*, const char*> estimators[] = {{&r.quadrature_damping_ratio, "phase resonance"},
                                                                 {&r.local_damping_ratio, "local fit"},
                                                                 {&r.half_power_damping_ratio, "half-power"}};
  const bool half_power_flagged = HalfPowerTooCoarse(data, r) || FlaggedNonlinear(r, "half_power_damping_ratio");
  const bool quadrature_flagged = QuadraturePastTheDrop(r) != nullptr;
  const auto usable = [&](const Estimate* e) {
    return e->valid && std::isfinite(e->value) && !(e == &r.half_power_damping_ratio && half_power_flagged) &&
           !(e == &r.quadrature_damping_ratio && quadrature_flagged);
  };
  const Estimate* primary = nullptr;
  const char* primary_name = "";
  for (const auto& [e, name] : estimators)
    if (usable(e) && !primary) primary = e, primary_name = name;
  if (!primary) return;
  double spread = 0.0;
  bool beyond_noise = false;
  std::string values;
  for (const auto& [e, name] : estimators) {
    if (!usable(e)) continue;
    const double difference = std::abs(e->value - primary->value);
    spread = std::max(spread, difference);
    const double noise = std::hypot(e->std, primary->std);
    if (e != primary && !(difference <= 2 * noise)) beyond_noise = true;
    values += fmt::format("{}{} {:.3g} % ± {}", values.empty() ? "" : ", ", name, 100 * e->value,
                          FiniteOr(100 * e->std, "{:.2g} %"));
  }
  const double std = std::isfinite(primary->std) ? std::hypot(primary->std, spread) : spread;
  // hypot rounds: make sure the stated σ covers the spread exactly.
  r.damping_ratio = {.value = primary->value, .std = std::max(std, spread), .valid = true};
  if (beyond_noise)
    r.damping_ratio_note = fmt::format(
        "the estimators part by more than their noise ({}): the σ covers their spread. Trust the {} one{}", values,
        primary_name,
        primary == &r.quadrature_damping_ratio
            ? " (at the phase resonance, with the modal constant A(a) of the fit across levels); the local fit "
              "assumes one modal constant along the curve, half-power a constant amplitude (and one mode)"
            : ": the phase resonance was not available");
}


// Where the level's own curve puts its resonance against the backbone the
// cross-level fit draws, at the level's amplitude: what a person checks
// against the test's log (the order the levels ran in, the temperature).
std::string OffBackboneMessage(const SingleModeFit& cross_level_fit, const LevelResonance& r, double allowed) {
  std::string where;
  if (r.local_natural_frequency_hz.valid && r.quadrature_amplitude_m.valid) {
    const double a = r.quadrature_amplitude_m.value;
    where = fmt::format(" (its natural frequency {:.6g} Hz, the backbone's {:.6g} Hz at its amplitude)",
                        r.local_natural_frequency_hz.value, cross_level_fit.NaturalFrequency_rad_s(a) / kTwoPi);
  }
  return fmt::format("the cross-level fit misses the level by {} RMS, beyond the {} its noise allows, while its own "
                     "single-mode curve holds it within {}: the level lies off the backbone the others draw{} — "
                     "drift over the test (the beam warming, a contact bedding in) or a level in another state; "
                     "it stays in the cross-level fit, its own numbers stand",
                     Percent(r.regeneration_relative_rms), Percent(allowed), Percent(r.own_curve_relative_rms), where);
}

// The relative RMS regeneration error a level's noise allows (LevelFlagKind::kRegenerationBeyondNoise).
double RegenerationAllowed(const MeasuredBackboneOptions& options, const LevelResonance& r) {
  return std::max(options.max_regeneration_relative_rms, kRegenerationNoiseFactor * r.regeneration_noise_relative_rms);
}

// The checks of LevelResonance::flags on one level's numbers.
void FlagLevel(const LevelData& data, const SingleModeFit* cross_level_fit, const MeasuredBackboneOptions& options,
               LevelResonance& r) {
  const auto add = [&](LevelFlagKind kind, std::string quantity, std::string message) {
    r.flags.push_back({.kind = kind, .quantity = std::move(quantity), .message = std::move(message)});
  };
  for (const auto& [estimate, quantity, name] :
       {std::tuple{&r.quadrature_damping_ratio, "quadrature_damping_ratio", "phase-resonance"},
        std::tuple{&r.local_damping_ratio, "local_damping_ratio", "local-fit"},
        std::tuple{&r.half_power_damping_ratio, "half_power_damping_ratio", "half-power"},
        std::tuple{&r.free_decay_damping_ratio, "free_decay_damping_ratio", "free-decay"}})
    if (estimate->valid && !(estimate->value > 0.0))
      add(LevelFlagKind::kDampingNotPositive, quantity,
          fmt::format("the {} damping ratio is {:.3g} % (± {}): not positive, no physical damping", name,
                      100 * estimate->value, FiniteOr(100 * estimate->std, "{:.2g} %")));
  const int n = data.size();
  const double f_min = At(data.raw, 0).omega / kTwoPi, f_max = At(data.raw, n - 1).omega / kTwoPi;
  const int m = PeakIndex(data.raw, n);
  if (m == 0 || m == n - 1)
    add(LevelFlagKind::kPeakOutsideBand, "peak_frequency",
        fmt::format("the largest response is at the sweep's {} ({:.6g} Hz): the peak lies outside the measured band "
                    "{:.6g} … {:.6g} Hz",
                    m == 0 ? "start" : "end", At(data.raw, m).omega / kTwoPi, f_min, f_max));
  for (const auto& [estimate, quantity, name] :
       {std::tuple{&r.peak_frequency_hz, "peak_frequency", "peak"},
        std::tuple{&r.quadrature_frequency_hz, "quadrature_frequency", "phase-resonance"},
        std::tuple{&r.local_natural_frequency_hz, "local_natural_frequency", "local-fit natural"}})
    if (estimate->valid && !(estimate->value >= f_min && estimate->value <= f_max))
      add(LevelFlagKind::kPeakOutsideBand, quantity,
          fmt::format("the {} frequency {:.6g} Hz lies outside the measured band {:.6g} … {:.6g} Hz", name,
                      estimate->value, f_min, f_max));
  if (const SweepJump* drop = QuadraturePastTheDrop(r))
    for (const char* quantity : {"quadrature_frequency", "quadrature_damping_ratio"})
      add(LevelFlagKind::kPeakOutsideBand, quantity,
          fmt::format("the phase resonance, moved to quadrature from the last step before the drop ({:.6g} Hz), "
                      "lands at {:.6g} Hz, past the step after it ({:.6g} Hz) where the sweep found the upper branch "
                      "gone: an extrapolation the data do not hold (its ζ left out of the level's ζ); step more "
                      "finely before the drop, or control the response",
                      drop->from_frequency_hz, r.quadrature_frequency_hz.value, drop->to_frequency_hz));
  if (HalfPowerTooCoarse(data, r))
    add(LevelFlagKind::kCoarseSteps, "half_power_damping_ratio",
        fmt::format("steps coarser than the resonance: {} step(s) between the half-power frequencies {:.6g} and "
                    "{:.6g} Hz, {} needed: half-power unreliable (left out of the level's ζ); step more finely "
                    "across the peak",
                    StepsInHalfPowerBand(data, r), r.half_power_lower_frequency_hz.value,
                    r.half_power_upper_frequency_hz.value, kMinStepsInHalfPowerBand));
  for (const auto& jump : r.jumps)
    add(LevelFlagKind::kJump, "sweep",
        fmt::format("the response jumps between the steps at {:.6g} and {:.6g} Hz ({}-sweep): |X/F| × {}, phase "
                    "{}; one smooth single-mode curve does not join them (a fold): the peak is the fold's edge, "
                    "the half-power points lie on two branches",
                    jump.from_frequency_hz, jump.to_frequency_hz, jump.up_sweep ? "up" : "down",
                    FiniteOr(jump.receptance_ratio, "{:.3g}"),
                    FiniteOr(jump.phase_change_rad * 180 / std::numbers::pi, "{:+.0f}°")));
  if (cross_level_fit) {
    const double allowed = RegenerationAllowed(options, r);
    if (r.regeneration_relative_rms <= allowed) return;
    if (r.own_curve_relative_rms > 0 && r.own_curve_relative_rms <= allowed) {
      add(LevelFlagKind::kOffBackbone, "regeneration_relative_rms", OffBackboneMessage(*cross_level_fit, r, allowed));
      return;
    }
    add(LevelFlagKind::kRegenerationBeyondNoise, "regeneration_relative_rms",
        r.regeneration_noise_relative_rms > 0
            ? fmt::format("the single-mode fit misses the level by {} RMS; its noise allows {} (the larger of {} × "
                          "the noise's {} and {})",
                          Percent(r.regeneration_relative_rms), Percent(allowed), kRegenerationNoiseFactor,
                          Percent(r.regeneration_noise_relative_rms), Percent(options.max_regeneration_relative_rms))
            : fmt::format("the single-mode fit misses the level by {} RMS, more than {} (the level gives no noise)",
                          Percent(r.regeneration_relative_rms), Percent(allowed)));
  }
}

// The global single-nonlinear-mode fit: every form of ω_n²(a) and ζω_n(a)
// (polynomial degrees, Iwan-like power laws) with A constant or A(a), by AICc.
void ChooseGlobalFit(const std::vector<SingleModePoint>& points, double reference_amplitude_m, double residual,
                     const MeasuredBackboneOptions& options, MeasuredBackbone& result) {
  constexpr double kPowerLaw = 1.0;  // "choose the exponent"
  double a_min = INFINITY, a_max = 0;
  for (const auto& p : points) a_min = std::min(a_min, p.amplitude_m), a_max = std::max(a_max, p.amplitude_m);
  // Levels held at one amplitude cannot tell how anything changes with it.
  const bool spans = a_max / a_min - 1 > options.constant_tolerance;
  std::vector<std::pair<int, double>> frequency_forms, damping_forms;  // (degree, exponent)
  for (int p = 0; p <= (spans ? options.max_frequency_degree : 0); ++p) frequency_forms.push_back({p, 0.0});
  for (int q = 0; q <= (spans ? options.max_damping_degree : 0); ++q) damping_forms.push_back({q, 0.0});
  if (options.try_power_laws && spans) {
    frequency_forms.push_back({1, kPowerLaw});
    damping_forms.push_back({1, kPowerLaw});
  }
  for (bool varying : {false, true}) {
    if (varying && !(options.try_amplitude_dependent_modal_constant && spans)) continue;
    for (const auto& [p, alpha] : frequency_forms)
      for (const auto& [q, beta] : damping_forms) {
        const SingleModeFit fit = FitSingleModeChoosingExponents(points, {.frequency_degree = p,
                                                                          .damping_degree = q,
                                                                          .frequency_exponent = alpha,
                                                                          .damping_exponent = beta,
                                                                          .amplitude_dependent_modal_constant = varying,
                                                                          .residual_receptance_m_N = residual,
                                                                          .reference_amplitude_m = reference_amplitude_m});
        if (!fit.ok) continue;
        result.candidates.push_back({.frequency_degree = fit.frequency_degree,
                                     .damping_degree = fit.damping_degree,
                                     .aicc = fit.aicc,
                                     .reduced_chi_square = fit.ReducedChiSquare(),
                                     .frequency_exponent = fit.frequency_exponent,
                                     .damping_exponent = fit.damping_exponent,
                                     .amplitude_dependent_modal_constant = varying,
                                     .form = fit.FormName()});
        if (!result.fit.ok || fit.aicc < result.fit.aicc) result.fit = fit;
      }
  }
}

}  // namespace

ExcitationLabels LabelsOf(std::string_view excitation_quantity) {
  if (excitation_quantity == "force")
    return {.control = "force", .unit = "N", .column = "force_N", .frf = "receptance [m/N]"};
  if (excitation_quantity == "voltage")
    return {.control = "voltage",
            .unit = "V",
            .column = "voltage_V",
            .frf = "displacement per drive voltage [m/V] (the amplifier's and shaker's gain included: not a receptance)",
            .caveat = "an amplifier whose gain changes near resonance (the shaker's back EMF) biases f_n and ζ; "
                      "measure the force at the drive point to remove it"};
  if (excitation_quantity == "base_acceleration")
    return {.control = "base acceleration",
            .unit = "m/s^2",
            .column = "minus_base_acceleration_m_s2",
            .frf = "displacement relative to the base per base acceleration [s^2] (the response less the base's own "
                   "motion, per −a_b: a transmissibility's resonant part)",
            .caveat = "f_n and ζ are the mode's (the base's own motion is taken out)"};
  throw InputError("excitation quantity '" + std::string(excitation_quantity) +
                   "' is none of force, voltage, base_acceleration");
}

std::string LevelControlText(std::string_view excitation_quantity, LevelControl control) {
  return control == LevelControl::kForce ? LabelsOf(excitation_quantity).control
                                         : std::string(LevelControlName(control));
}

std::string_view LevelControlName(LevelControl control) {
  switch (control) {
    case LevelControl::kForce: return "force";
    case LevelControl::kResponse: return "response";
    case LevelControl::kNeither: return "neither";
  }
  return "";
}

std::string_view LevelFlagName(LevelFlagKind kind) {
  switch (kind) {
    case LevelFlagKind::kDampingNotPositive: return "damping_not_positive";
    case LevelFlagKind::kPeakOutsideBand: return "peak_outside_band";
    case LevelFlagKind::kRegenerationBeyondNoise: return "regeneration_beyond_noise";
    case LevelFlagKind::kJump: return "jump";
    case LevelFlagKind::kPhaseConvention: return "phase_convention";
    case LevelFlagKind::kCoarseSteps: return "coarse_steps";
    case LevelFlagKind::kOffBackbone: return "off_backbone";
    case LevelFlagKind::kNonlinearCurve: return "nonlinear_curve";
  }
  return "";
}

LevelFlagKind LevelFlagKindFromName(std::string_view name) {
  for (LevelFlagKind kind :
       {LevelFlagKind::kDampingNotPositive, LevelFlagKind::kPeakOutsideBand, LevelFlagKind::kRegenerationBeyondNoise,
        LevelFlagKind::kJump, LevelFlagKind::kPhaseConvention, LevelFlagKind::kCoarseSteps, LevelFlagKind::kOffBackbone,
        LevelFlagKind::kNonlinearCurve})
    if (name == LevelFlagName(kind)) return kind;
  throw InputError("unknown level flag \"" + std::string(name) +
                   "\": give damping_not_positive, peak_outside_band, regeneration_beyond_noise, jump, "
                   "phase_convention, coarse_steps, off_backbone or nonlinear_curve");
}

bool LevelResonance::HasFlag(LevelFlagKind kind) const {
  return std::any_of(flags.begin(), flags.end(), [&](const LevelFlag& f) { return f.kind == kind; });
}

std::string LevelResonance::FlagNote(std::string_view quantity) const {
  // Each kind once, with its count when repeated (a noisy sweep jumps hundreds of times).
  std::vector<std::pair<std::string_view, int>> kinds;
  for (const auto& f : flags) {
    if (f.quantity != quantity) continue;
    const std::string_view what = f.kind == LevelFlagKind::kDampingNotPositive ? "not positive"
                                  : f.kind == LevelFlagKind::kPeakOutsideBand  ? "outside the measured band"
                                  : f.kind == LevelFlagKind::kJump             ? "jump"
                                  : f.kind == LevelFlagKind::kPhaseConvention  ? "phase convention"
                                  : f.kind == LevelFlagKind::kCoarseSteps      ? "steps coarser than the resonance"
                                  : f.kind == LevelFlagKind::kOffBackbone      ? "off the backbone"
                                  : f.kind == LevelFlagKind::kNonlinearCurve   ? "not one linear mode's curve"
                                                                               : "beyond the noise";
    const auto seen = std::find_if(kinds.begin(), kinds.end(), [&](const auto& k) { return k.first == what; });
    if (seen == kinds.end())
      kinds.push_back({what, 1});
    else
      ++seen->second;
  }
  std::string note;
  for (const auto& [what, count] : kinds)
    note += (note.empty() ? "[FLAG: " : "; ") + std::string(what) + (count > 1 ? fmt::format(" ×{}", count) : "");
  return note.empty() ? note : note + "]";
}

void MeasuredBackboneOptions::Validate() const {
  using namespace option_checks;
  if (!(fit_window > 0.0 && fit_window <= 1.0))
    Refuse("MeasuredBackboneOptions.fit_window", FormatValue(fit_window), "above 0 and at most 1");
  RequirePositive("MeasuredBackboneOptions.constant_tolerance", constant_tolerance);
  jumps.Validate();
  RequireAtLeast("MeasuredBackboneOptions.max_frequency_degree", max_frequency_degree, 0);
  RequireAtLeast("MeasuredBackboneOptions.max_damping_degree", max_damping_degree, 0);
  RequirePositive("MeasuredBackboneOptions.trend_significance", trend_significance);
  RequirePositive("MeasuredBackboneOptions.max_regeneration_relative_rms", max_regeneration_relative_rms);
}

namespace {

// Where the other modes' share R comes from: the cross-level fit (one
// backbone for all levels), or the levels' own curves with one R between
// them, when the levels do not lie on one backbone.
enum class ResidualFrom { kCrossLevelFit, kLevelsOwnCurves };

// The analysis with the levels of `in_fit` in the cross-level fit (all levels
// are analysed, regenerated and flagged).

MeasuredBackbone Analyse(const std::vector<signal::FirstHarmonicLevel>& levels, const MeasuredBackboneOptions& options,
                         const std::vector<bool>& in_fit, ResidualFrom residual_from = ResidualFrom::kCrossLevelFit) {
  MeasuredBackbone result;
  result.response_quantity = signal::QuantityName(levels.front().response_quantity);
  result.excitation_quantity = signal::QuantityName(levels.front().excitation_quantity);
  std::vector<LevelData> data;
  std::vector<SingleModePoint> all_points;
  std::vector<SingleModeFit> local_fits;
  std::vector<std::vector<SingleModePoint>> level_points;
  for (const auto& level : levels) {
    if (level.response_quantity == signal::Quantity::kForce)
      throw std::invalid_argument(level.source + ": level '" + level.label + "': the response is a force");
    if (level.excitation_quantity != levels.front().excitation_quantity)
      throw std::invalid_argument(level.source + ": level '" + level.label + "' is driven by a " +
                                  std::string(signal::QuantityName(level.excitation_quantity)) + ", level '" +
                                  levels.front().label + "' by a " + result.excitation_quantity +
                                  ": give the levels of one test");
    if (level.response_quantity != levels.front().response_quantity)
      throw std::invalid_argument(level.source + ": level '" + level.label + "' holds a " +
                                  std::string(signal::QuantityName(level.response_quantity)) + ", level '" +
                                  levels.front().label + "' a " + result.response_quantity +
                                  ": give the levels of one sensor, in one quantity");
    if (level.points.size() < 3)
      throw std::invalid_argument(level.source + ": level '" + level.label + "' has " +
                                  std::to_string(level.points.size()) + " steps; at least 3 are needed");
    data.push_back(MakeLevelData(level));
    level_points.push_back(FitPoints(data.back(), options.fit_window));
  }
  for (std::size_t l = 0; l < level_points.size(); ++l)
    if (in_fit[l]) all_points.insert(all_points.end(), level_points[l].begin(), level_points[l].end());
  result.min_amplitude_m = INFINITY;
  for (const auto& p : all_points) {
    result.min_amplitude_m = std::min(result.min_amplitude_m, p.amplitude_m);
    result.max_amplitude_m = std::max(result.max_amplitude_m, p.amplitude_m);
  }
  // The other modes' share R, once for all levels (it does not depend on
  // amplitude): first with the most flexible polynomial form, then again with
  // the form chosen with it (R and the form bias each other's choice).
  // R's σ, from the same points that gave it, goes into every fit's
  // covariance that uses it: taken as exact, a spurious R of 1 % of the peak
  // (noise) moved a linear level's natural frequency by 6 of its σ.
  double residual = 0.0, residual_std = 0.0;
  if (options.estimate_residual && residual_from == ResidualFrom::kLevelsOwnCurves) {
    std::vector<std::vector<SingleModePoint>> groups;
    std::vector<SingleModeFitOptions> forms;
    for (std::size_t l = 0; l < level_points.size(); ++l) {
      if (!in_fit[l]) continue;
      groups.push_back(level_points[l]);
      forms.push_back(LocalFitForm(level_points[l], options.constant_tolerance));
    }
    residual = FitResidualReceptance(groups, forms);
    residual_std = ResidualReceptanceStd(groups, forms, residual);
  } else if (options.estimate_residual) {
    const bool spans = result.max_amplitude_m / result.min_amplitude_m - 1 > options.constant_tolerance;
    residual = FitResidualReceptance(all_points, {.frequency_degree = spans ? options.max_frequency_degree : 0,
                                                  .damping_degree = spans ? options.max_damping_degree : 0,
                                                  .amplitude_dependent_modal_constant =
                                                      spans && options.try_amplitude_dependent_modal_constant,
                                                  .reference_amplitude_m = result.max_amplitude_m});
    ChooseGlobalFit(all_points, result.max_amplitude_m, residual, options, result);
    if (result.fit.ok) {
      const SingleModeFitOptions form = result.fit.Form();
      residual = FitResidualReceptance(all_points, form);
      residual_std = ResidualReceptanceStd({all_points}, {form}, residual);
    }
    result.fit = SingleModeFit();
    result.candidates.clear();
  }
  for (const auto& points : level_points) {
    local_fits.push_back(LocalFit(points, options.constant_tolerance, residual));
    IncludeResidualUncertainty(local_fits.back(), points, residual_std);
  }
  ChooseGlobalFit(all_points, result.max_amplitude_m, residual, options, result);
  IncludeResidualUncertainty(result.fit, all_points, residual_std);
  if (!result.fit.ok) result.warnings.push_back("too few points near the mode for a single-mode fit across levels");

  // A(a) for the phase resonances: from the global fit, which sees every
  // level (the amplitudes at which each is pinned down by points on both
  // sides of a resonance); without one, from the most linear level's local fit.
  int linear_level = -1;
  for (std::size_t l = 0; l < levels.size(); ++l) {
    if (!local_fits[l].ok) continue;
    if (linear_level < 0 || local_fits[l].reference_amplitude_m < local_fits[linear_level].reference_amplitude_m)
      linear_level = static_cast<int>(l);
  }
  for (std::size_t l = 0; l < levels.size(); ++l) {
    LevelResonance r;
    r.label = levels[l].label;
    r.num_points = data[l].size();
    r.num_fit_points = static_cast<int>(level_points[l].size());
    r.noise_from_sweep_relative_rms = data[l].noise_from_sweep_relative_rms;
    r.control = DetectControl(data[l], options.constant_tolerance);
    const SingleModeFit& modal_fit = result.fit.ok ? result.fit : linear_level >= 0 ? local_fits[linear_level] : local_fits[l];
    r.jumps = DetectSweepJumps(SweepPointsInRunOrder(data[l]), options.jumps);
    r.quadrature_after_jump = !r.jumps.empty();
    FindQuadrature(data[l], modal_fit, local_fits[l], r);
    FindPeakAndHalfPower(data[l], r);
    TakeFreeDecay(levels[l], r);
    EvaluateLocalFit(local_fits[l], r);
    if (!r.quadrature_note.empty()) result.warnings.push_back("level '" + r.label + "': " + r.quadrature_note);
    if (r.noise_from_sweep_relative_rms > 0)
      result.warnings.push_back(fmt::format(
          "level '{}' states no uncertainty: its noise, {} of the response, is estimated from the sweep's scatter "
          "about a smooth curve and used for every σ, flag and jump",
          r.label, Percent(r.noise_from_sweep_relative_rms)));
    if (result.fit.ok) Regenerate(result.fit, data[l], r.jumps, options.fit_window, result.max_amplitude_m, r);
    if (local_fits[l].ok) {
      LevelResonance own{.control = r.control};
      Regenerate(local_fits[l], data[l], r.jumps, options.fit_window, result.max_amplitude_m, own);
      r.own_curve_relative_rms = own.regeneration_relative_rms;
    }
    // The linear-mode estimators' bias read on the fit that regenerates the
    // level more closely, within what its noise allows: the cross-level
    // fit's curve, or the level's own (off a drifting backbone the
    // cross-level fit reads the drift as a nonlinearity the level lacks; a
    // fit that misses the level predicts nothing about its curve).
    const double allowed = RegenerationAllowed(options, r);
    const bool cross_level_holds = result.fit.ok && r.regeneration_relative_rms <= allowed;
    const bool own_holds = local_fits[l].ok && r.own_curve_relative_rms <= allowed;
    const SingleModeFit* holds =
        cross_level_holds && !(own_holds && r.own_curve_relative_rms < r.regeneration_relative_rms) ? &result.fit
        : own_holds                                                                                   ? &local_fits[l]
                                                                                                      : nullptr;
    if (holds && r.peak_frequency_hz.valid)
      FlagNonlinearCurve(PredictLinearModeBias(*holds, data[l], result.max_amplitude_m, r.control),
                         [&] { return LinearModeBiasStd(*holds, data[l], result.max_amplitude_m, r.control); },
                         holds == &result.fit ? "the cross-level fit" : "the level's own curve", r);
    CombineDampingRatios(data[l], r);
    FlagLevel(data[l], result.fit.ok ? &result.fit : nullptr, options, r);
    std::vector<ReceptancePoint> receptances;
    for (int i = 0; i < data[l].size(); ++i) {
      const PointView p = At(data[l].raw, i);
      receptances.push_back({.omega_rad_s = p.omega, .receptance_m_N = p.disp / p.force});
    }
    const PhaseConventionCheck phase = CheckPhaseConvention(receptances, levels[l].response_quantity, options.fit_window);
    if (!phase.message.empty())
      r.flags.push_back({.kind = LevelFlagKind::kPhaseConvention, .quantity = "phase", .message = phase.message});
    r.in_global_fit = in_fit[l];
    result.levels.push_back(std::move(r));
  }
  if (!result.fit.ok) return result;

  // Damping trend: ζω_n linear in a, the frequency and A(a) as chosen.
  SingleModeFit linear = FitSingleModeChoosingExponents(
      all_points, {.frequency_degree = result.fit.frequency_degree,
                   .damping_degree = 1,
                   .frequency_exponent = result.fit.frequency_exponent,
                   .amplitude_dependent_modal_constant = result.fit.amplitude_dependent_modal_constant,
                   .residual_receptance_m_N = result.fit.residual_receptance_m_N,
                   .reference_amplitude_m = result.max_amplitude_m});
  IncludeResidualUncertainty(linear, all_points, residual_std);
  if (linear.ok) {
    DampingTrend& trend = result.damping_trend;
    trend.amplitude_m = 0.5 * (result.min_amplitude_m + result.max_amplitude_m);
    trend.slope_per_m = linear.DampingSlope_per_m(trend.amplitude_m);
    trend.slope_std_per_m = linear.DampingSlopeStd_per_m(trend.amplitude_m);
    trend.z = trend.slope_per_m / trend.slope_std_per_m;
    const auto judged = [&](double z) {
      return z > options.trend_significance ? Trend::kRises : z < -options.trend_significance ? Trend::kFalls : Trend::kNone;
    };
    trend.damping_ratio_verdict = judged(trend.z);
    // ζω_n = q0 + q1·a/a_ref: its slope is q1/a_ref, the last parameter.
    const int q1 = static_cast<int>(linear.parameters.size()) - 1;
    trend.damping_rate_slope_per_s_m = linear.parameters[q1] / linear.reference_amplitude_m;
    trend.damping_rate_slope_std_per_s_m = std::sqrt(linear.covariance(q1, q1)) / linear.reference_amplitude_m;
    trend.damping_rate_z = trend.damping_rate_slope_per_s_m / trend.damping_rate_slope_std_per_s_m;
    trend.verdict = judged(trend.damping_rate_z);
  }
  return result;
}

// Coarse steps, or a curve not one linear mode's, spoil one estimator, not
// the level's points; a level off the backbone is sound by its own curve.
bool PassedItsChecks(const LevelResonance& level) {
  return std::all_of(level.flags.begin(), level.flags.end(), [](const LevelFlag& f) {
    return f.kind == LevelFlagKind::kCoarseSteps || f.kind == LevelFlagKind::kNonlinearCurve ||
           f.kind == LevelFlagKind::kOffBackbone;
  });
}

// What the page draws of each level (LevelResonance::measured_frf,
// fit_frf), from the fit the levels' exclusion ended with: once, not in
// each of its passes.
void AddFrequencyResponses(const std::vector<signal::FirstHarmonicLevel>& levels, MeasuredBackbone& result) {
  for (std::size_t l = 0; l < levels.size(); ++l) {
    const LevelData data = MakeLevelData(levels[l]);
    LevelResonance& r = result.levels[l];
    r.measured_frf = MeasuredFrf(data);
    if (result.fit.ok) r.fit_frf = FitFrf(result.fit, data, r.control, result.max_amplitude_m);
  }
}

// A trend is a verdict on the damping only where the levels it reads passed
// their checks; the exclusion leaves in the fit only such levels, unless no
// level would be left.
void WithholdTrendWithoutCleanLevels(MeasuredBackbone& result) {
  const auto clean = std::count_if(result.levels.begin(), result.levels.end(),
                                   [](const LevelResonance& l) { return l.in_global_fit && PassedItsChecks(l); });
  if (clean >= kMinCleanLevelsForTrend) return;
  result.damping_trend.verdict = result.damping_trend.damping_ratio_verdict = Trend::kNotJudged;
  result.damping_trend.note =
      fmt::format("not enough clean levels: {} of {} passed their checks, {} needed; no damping trend is judged",
                  clean, result.levels.size(), kMinCleanLevelsForTrend);
}

// Once for the set: the levels disagree with each other, not one of them
// with its own curve.
void WarnOfLevelsOffTheBackbone(MeasuredBackbone& result) {
  std::vector<std::string> labels;
  for (const auto& level : result.levels)
    if (level.HasFlag(LevelFlagKind::kOffBackbone)) labels.push_back("'" + level.label + "'");
  if (labels.empty()) return;
  result.warnings.push_back(fmt::format(
      "the levels do not lie on one backbone: {} of {} ({}) sit off the one the cross-level fit draws by more than "
      "their noise, while each one's own single-mode curve holds it — drift over the test (temperature, a contact "
      "bedding in) or levels run in another state; the backbone and the damping trend average over them, each "
      "level's own numbers stand; compare the levels' natural frequencies with the order they were run in",
      labels.size(), result.levels.size(), fmt::join(labels, ", ")));
}

// Each kind's first message, and how many more there are: a noisy sweep
// jumps hundreds of times, and every message is in the level's flags.
std::string FlagSummary(const LevelResonance& level) {
  std::string text;
  for (std::size_t i = 0; i < level.flags.size(); ++i) {
    const LevelFlag& f = level.flags[i];
    const auto same_kind = [&](const LevelFlag& g) { return g.kind == f.kind; };
    if (std::any_of(level.flags.begin(), level.flags.begin() + static_cast<long>(i), same_kind)) continue;
    const auto count = std::count_if(level.flags.begin(), level.flags.end(), same_kind);
    text += (text.empty() ? "" : "; ") + std::string(LevelFlagName(f.kind)) + ": " + f.message +
            (count > 1 ? fmt::format(" (and {} more, in the level's flags)", count - 1) : "");
  }
  return text;
}

}  // namespace

// Flags are found with every level in the cross-level fit; then, unless the
// options keep them, flagged levels leave the fit one pass at a time: every
// level with a flag the fit does not change (damping, band), and of those
// the fit regenerates beyond their noise only the worst (a bad level bends
// the fit and so the regeneration of the good ones), until no level in the
// fit is flagged. A level left out keeps the flags it was left out for.
MeasuredBackbone AnalyseMeasuredBackbone(const std::vector<signal::FirstHarmonicLevel>& levels,
                                         const MeasuredBackboneOptions& options) {
  options.Validate();
  if (levels.empty()) throw std::invalid_argument("measured backbone: no levels to analyse");
  const std::size_t n = levels.size();
  std::vector<bool> in_fit(n, true);
  MeasuredBackbone result = Analyse(levels, options, in_fit);
  std::vector<std::vector<LevelFlag>> left_out_for(n);
  bool fit_would_be_empty = false;
  while (!options.keep_flagged_levels_in_fit) {
    std::vector<bool> next = in_fit;
    int worst = -1;
    for (std::size_t l = 0; l < n; ++l) {
      const LevelResonance& r = result.levels[l];
      if (!in_fit[l] || PassedItsChecks(r)) continue;
      if (std::any_of(r.flags.begin(), r.flags.end(), [](const LevelFlag& f) {
            return f.kind != LevelFlagKind::kRegenerationBeyondNoise && f.kind != LevelFlagKind::kCoarseSteps &&
                   f.kind != LevelFlagKind::kNonlinearCurve && f.kind != LevelFlagKind::kOffBackbone;
          }))
        next[l] = false;
      else if (worst < 0 || r.regeneration_relative_rms > result.levels[worst].regeneration_relative_rms)
        worst = static_cast<int>(l);
    }
    if (worst >= 0 && std::equal(next.begin(), next.end(), in_fit.begin())) next[worst] = false;
    if (std::equal(next.begin(), next.end(), in_fit.begin())) break;
    if (std::none_of(next.begin(), next.end(), [](bool b) { return b; })) {
      fit_would_be_empty = true;
      break;
    }
    for (std::size_t l = 0; l < n; ++l)
      if (in_fit[l] && !next[l]) left_out_for[l] = result.levels[l].flags;
    in_fit = next;
    result = Analyse(levels, options, in_fit);
  }
  // Off one backbone, the cross-level fit's R holds its misfit: R again, from
  // the levels' own curves, and every number with it.
  if (std::any_of(result.levels.begin(), result.levels.end(),
                  [](const LevelResonance& l) { return l.HasFlag(LevelFlagKind::kOffBackbone); }))
    result = Analyse(levels, options, in_fit, ResidualFrom::kLevelsOwnCurves);
  // A level left out is flagged by the last fit (the flags the fit bends may
  // have changed); only if that fit flags nothing does it keep the flags it
  // was left out for.
  for (std::size_t l = 0; l < n; ++l) {
    auto& flags = result.levels[l].flags;
    if (!flags.empty()) continue;
    for (const auto& f : left_out_for[l])
      flags.push_back({f.kind, f.quantity, f.message + " (when the level was in the cross-level fit)"});
  }
  AddFrequencyResponses(levels, result);
  if (options.keep_flagged_levels_in_fit) {
    // Flagged levels kept bend the fit, and so the regeneration flags of the
    // others: the trend is the one the exclusion would judge.
    MeasuredBackboneOptions excluding = options;
    excluding.keep_flagged_levels_in_fit = false;
    result.damping_trend = AnalyseMeasuredBackbone(levels, excluding).damping_trend;
  } else {
    WithholdTrendWithoutCleanLevels(result);
  }
  WarnOfLevelsOffTheBackbone(result);
  for (const auto& level : result.levels) {
    if (level.flags.empty()) continue;
    result.warnings.push_back(
        "level '" + level.label + "' is flagged (" + FlagSummary(level) + "): " +
        (!level.in_global_fit ? "left out of the cross-level fit and the damping trend "
                                "(--keep-flagged-levels keeps it)"
         : fit_would_be_empty ? "kept in the cross-level fit, which would otherwise hold no level"
                              : "kept in the cross-level fit"));
  }
  return result;
}

}  // namespace beamid::solver
