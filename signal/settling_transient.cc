#include "signal/settling_transient.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include <Eigen/Eigenvalues>

#include "hb/option_checks.h"
#include "signal/internal/harmonic_basis.h"

namespace beamid::signal {
namespace {

using Complex = std::complex<double>;

// The search covers beats up to kMaxBeatBins/T: the noise floor ignores the
// 3 bins next to f, farther ringing is in the floor already and leaks into
// X_1 as little as any noise. Decay rates up to kMaxDecayPerRecord/T: faster
// ringing is gone within the record's first tenth, where the steady-state
// detection cuts it.
constexpr double kMaxBeatBins = 4.0;
constexpr double kMaxDecayPerRecord = 12.0;
// A coarse grid, then three finer ones around its best point, each with a
// fifth of the spacing before.
constexpr int kBeatSteps = 20;
constexpr int kDecaySteps = 24;
constexpr int kRefineSteps = 10;
// Independent cells of that grid for the look-elsewhere correction: about a
// bin of beat on each side of f per cell, and decays within a record's
// inverse of each other, ~2·4·4; taken as 32 (the false-alarm rate on settled
// records is measured by the tests).
constexpr double kIndependentCells = 32.0;
constexpr double kRankTolerance = 1e-9;
constexpr double kNodeFraction = 0.1;

// Upper-tail normal quantile: the z with P(N(0,1) ≥ z) = tail, by Newton.
double NormalUpperQuantile(double tail) {
  double z = 3.0;
  for (int i = 0; i < 50; ++i) {
    const double f = 0.5 * std::erfc(z / std::numbers::sqrt2) - tail;
    const double density = std::exp(-0.5 * z * z) / std::sqrt(2.0 * std::numbers::pi);
    const double step = f / density;
    z += step;
    if (std::abs(step) < 1e-12) break;
  }
  return z;
}

// χ²(dof) quantile at an upper tail, by the Wilson–Hilferty cube-root
// normal approximation (solver/ holds the exact one; signal/ does not
// depend on it).
double ChiSquareUpperQuantile(double tail, double dof) {
  const double z = NormalUpperQuantile(tail);
  const double a = 2.0 / (9.0 * dof);
  return dof * std::pow(1.0 - a + z * std::sqrt(a), 3.0);
}

// Σ_c w_c·|projection of z_c on the ringing columns|², the columns
// e^{(−σ ± iν)τ_j} made orthogonal to the constant (the fit's X_1 is free) by
// modified Gram–Schmidt; a column that adds nothing (ν = 0) is dropped.
double BasebandDrop(const Eigen::MatrixXcd& baseband, const Eigen::VectorXd& weights, const Eigen::VectorXd& tau,
                    double decay, double beat) {
  const Eigen::Index m = baseband.rows();
  Eigen::MatrixXcd q(m, 3);
  q.col(0).setConstant(1.0 / std::sqrt(static_cast<double>(m)));
  int rank = 1;
  for (const double sign : {1.0, -1.0}) {
    if (sign < 0.0 && beat == 0.0) break;
    // The blocks are evenly spaced: e^{sτ_j} = e^{sτ_0}·(e^{sΔτ})^j.
    Eigen::VectorXcd column(m);
    const Complex s(-decay, sign * beat);
    const Complex ratio = m > 1 ? std::exp(s * (tau(1) - tau(0))) : Complex(1.0);
    column(0) = std::exp(s * tau(0));
    for (Eigen::Index j = 1; j < m; ++j) column(j) = column(j - 1) * ratio;
    const double norm = column.norm();
    for (int r = 0; r < rank; ++r) column -= q.col(r) * q.col(r).dot(column);
    if (column.norm() <= 1e-6 * norm) continue;
    q.col(rank++) = column / column.norm();
  }
  double drop = 0.0;
  for (Eigen::Index c = 0; c < baseband.cols(); ++c) {
    if (weights(c) == 0.0) continue;
    for (int r = 1; r < rank; ++r) drop += weights(c) * std::norm(q.col(r).dot(baseband.col(c)));
  }
  return drop;
}

// Pseudo-inverse of a normal matrix and its rank: near ν = 0, σ = 0 the
// ringing and the fundamental are almost the same columns.
Eigen::MatrixXd PseudoInverse(const Eigen::MatrixXd& normal, int& rank) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(normal);
  const Eigen::VectorXd& values = eigen.eigenvalues();
  Eigen::VectorXd inverse_values = Eigen::VectorXd::Zero(values.size());
  rank = 0;
  for (Eigen::Index i = 0; i < values.size(); ++i)
    if (values(i) > kRankTolerance * values.maxCoeff()) {
      inverse_values(i) = 1.0 / values(i);
      ++rank;
    }
  return eigen.eigenvectors() * inverse_values.asDiagonal() * eigen.eigenvectors().transpose();
}

}  // namespace

void SettlingTransientOptions::Validate() const {
  option_checks::RequireInRange("SettlingTransientOptions.false_alarm", false_alarm, 1e-12, 0.5);
}

SettlingTransient RemoveSettlingTransient(const Eigen::Ref<const Eigen::MatrixXd>& samples, double sample_rate_hz,
                                          const std::vector<bool>& judged, HarmonicFit& fit,
                                          const SettlingTransientOptions& options) {
  options.Validate();
  SettlingTransient result;
  const int n = static_cast<int>(samples.rows());
  const Eigen::Index num_channels = samples.cols();
  const double f = fit.frequency_hz;
  const int period = static_cast<int>(std::lround(sample_rate_hz / f));
  const int num_blocks = period > 0 ? n / period : 0;
  if (num_blocks < 8) return result;  // too few cycles to tell ringing from the response

  const internal::HarmonicBasis basis(n, sample_rate_hz, f, fit.num_harmonics);
  const Eigen::MatrixXd residual = samples - basis.matrix() * basis.Solve(samples);

  // One-period averages of the residual brought to baseband: the ringing's
  // components at ω ± ν become e^{(−σ ± iν)τ}, everything else averages out.
  const double omega = basis.omega_rad_s();
  Eigen::MatrixXcd baseband = Eigen::MatrixXcd::Zero(num_blocks, num_channels);
  Eigen::VectorXd block_tau(num_blocks);
  for (int j = 0; j < num_blocks; ++j) {
    block_tau(j) = basis.Tau_s(j * period + 0.5 * (period - 1));
    for (int i = j * period; i < (j + 1) * period; ++i) {
      const Complex turn = std::polar(1.0 / period, -omega * basis.Tau_s(i));
      for (Eigen::Index c = 0; c < num_channels; ++c) baseband(j, c) += residual(i, c) * turn;
    }
  }
  Eigen::VectorXd weights = Eigen::VectorXd::Zero(num_channels);
  int num_judged = 0;
  for (Eigen::Index c = 0; c < num_channels; ++c) {
    const double noise = fit.channels[static_cast<std::size_t>(c)].noise_variance(0);
    if (c < static_cast<Eigen::Index>(judged.size()) && judged[static_cast<std::size_t>(c)] && noise > 0.0) {
      weights(c) = 1.0 / noise;
      ++num_judged;
    }
  }
  if (num_judged == 0) return result;

  const double duration_s = n / sample_rate_hz;
  const double max_beat = 2.0 * std::numbers::pi * kMaxBeatBins / duration_s;
  const double max_decay = kMaxDecayPerRecord / duration_s;
  double best = -1.0, best_decay = 0.0, best_beat = 0.0;
  auto search = [&](double beat_lo, double beat_hi, int beat_steps, double decay_lo, double decay_hi,
                    int decay_steps) {
    beat_lo = std::max(0.0, beat_lo), beat_hi = std::min(max_beat, beat_hi);
    decay_lo = std::max(0.0, decay_lo), decay_hi = std::min(max_decay, decay_hi);
    for (int b = 0; b <= beat_steps; ++b)
      for (int d = 0; d <= decay_steps; ++d) {
        const double beat = beat_lo + (beat_hi - beat_lo) * b / beat_steps;
        const double decay = decay_lo + (decay_hi - decay_lo) * d / decay_steps;
        if (beat == 0.0 && decay == 0.0) continue;  // the response itself
        const double drop = BasebandDrop(baseband, weights, block_tau, decay, beat);
        if (drop > best) best = drop, best_decay = decay, best_beat = beat;
      }
  };
  search(0.0, max_beat, kBeatSteps, 0.0, max_decay, kDecaySteps);
  for (double beat_step = max_beat / kBeatSteps, decay_step = max_decay / kDecaySteps; beat_step > 0.02 * max_beat / kBeatSteps;
       beat_step /= kRefineSteps / 2.0, decay_step /= kRefineSteps / 2.0)
    search(best_beat - beat_step, best_beat + beat_step, kRefineSteps, best_decay - decay_step,
           best_decay + decay_step, kRefineSteps);

  // The joint fit on every sample at the best (σ, ν).
  const int num_ringing = best_beat > 0.0 ? 4 : 2;
  const Eigen::Index p = basis.matrix().cols();
  Eigen::MatrixXd design(n, p + num_ringing);
  design.leftCols(p) = basis.matrix();
  for (int i = 0; i < n; ++i) {
    const double tau = basis.Tau_s(i), envelope = std::exp(-best_decay * tau);
    design(i, p) = envelope * std::cos((omega + best_beat) * tau);
    design(i, p + 1) = envelope * std::sin((omega + best_beat) * tau);
    if (num_ringing == 4) {
      design(i, p + 2) = envelope * std::cos((omega - best_beat) * tau);
      design(i, p + 3) = envelope * std::sin((omega - best_beat) * tau);
    }
  }
  int rank = 0;
  const Eigen::MatrixXd inverse_normal = PseudoInverse(design.transpose() * design, rank);
  const Eigen::MatrixXd coefficients = inverse_normal * (design.transpose() * samples);
  const Eigen::MatrixXd joint_residual = samples - design * coefficients;

  // A ringing the record cannot tell from the response (no decay and
  // hardly a beat over the record: the columns nearly repeat the
  // fundamental's) is not removed: the split between the two would be the
  // pseudo-inverse's choice, not the data's.
  const int ringing_rank = rank - static_cast<int>(p);
  if (rank < design.cols()) return result;
  double drop = 0.0;
  for (Eigen::Index c = 0; c < num_channels; ++c)
    drop += weights(c) * (residual.col(c).squaredNorm() - joint_residual.col(c).squaredNorm());
  result.decay_rate_per_s = best_decay;
  result.beat_hz = best_beat / (2.0 * std::numbers::pi);
  result.chi_square_drop = drop;
  result.threshold = ChiSquareUpperQuantile(options.false_alarm / kIndependentCells,
                                            static_cast<double>(ringing_rank * num_judged));
  if (drop <= result.threshold) return result;

  const double tau_start = basis.Tau_s(0);
  // The size is told against each channel's own fundamental, among the
  // channels not near a node (there even a faint ringing is "large").
  double largest_fundamental = 0.0;
  for (Eigen::Index c = 0; c < num_channels; ++c)
    if (weights(c) > 0.0)
      largest_fundamental = std::max(largest_fundamental, std::abs(fit.channels[static_cast<std::size_t>(c)].phasors(0)));
  // σ and ν were estimated too: their errors move the ringing, and with it
  // the phasors, most where the ringing is large. Each channel's covariance
  // is the nonlinear fit's (variable projection), with the ringing's
  // derivatives ∂/∂σ = −τ·ring and ∂/∂ν among the columns; ν, σ taken per
  // channel, which can only widen it.
  std::vector<Eigen::MatrixXd> inverse_normals(static_cast<std::size_t>(num_channels));
  for (Eigen::Index c = 0; c < num_channels; ++c) {
    if (weights(c) == 0.0) continue;  // the reference and the channels nobody uses keep their fit
    const Eigen::VectorXd column = coefficients.col(c);
    const Eigen::VectorXd ring = design.rightCols(num_ringing) * column.tail(num_ringing);
    Eigen::MatrixXd design_c(n, design.cols() + 2);
    design_c.leftCols(design.cols()) = design;
    for (int i = 0; i < n; ++i) {
      const double tau = basis.Tau_s(i);
      design_c(i, design.cols()) = -tau * ring(i);
      double beat_derivative = -column(p) * design(i, p + 1) + column(p + 1) * design(i, p);
      if (num_ringing == 4) beat_derivative += column(p + 2) * design(i, p + 3) - column(p + 3) * design(i, p + 2);
      design_c(i, design.cols() + 1) = tau * beat_derivative;
    }
    int rank_c = 0;
    Eigen::MatrixXd& inverse = inverse_normals[static_cast<std::size_t>(c)];
    inverse = PseudoInverse(design_c.transpose() * design_c, rank_c);
    // Separating a ringing that beats less than once over the record costs
    // the fundamental 10–300 times its variance (measured on the
    // simulator's campaigns), which the covariance holds; where the columns
    // are no longer independent the split would be the pseudo-inverse's.
    if (rank_c < design.cols()) return result;
  }

  result.removed = true;
  for (Eigen::Index c = 0; c < num_channels; ++c) {
    if (weights(c) == 0.0) continue;
    ChannelFit& channel = fit.channels[static_cast<std::size_t>(c)];
    const Eigen::VectorXd column = coefficients.col(c);
    channel.mean = column(0);
    channel.residual_rms = std::sqrt(joint_residual.col(c).squaredNorm() / n);
    const Eigen::MatrixXd& inverse_normal_c = inverse_normals[static_cast<std::size_t>(c)];
    for (int k = 1; k <= fit.num_harmonics; ++k) {
      channel.phasors(k - 1) = internal::HarmonicBasis::Phasor(column, k);
      Eigen::Matrix2d covariance = inverse_normal_c.block<2, 2>(2 * k - 1, 2 * k - 1);
      covariance(0, 1) = covariance(1, 0) = -covariance(0, 1);
      // The floor is the one read before the ringing was removed, whose
      // leakage keeps it wide (these phasors' rms z reads ~0.83): Student's
      // factor (harmonic_fit.h) would only widen it further.
      channel.covariances[static_cast<std::size_t>(k - 1)] = channel.noise_variance(k - 1) * covariance;
    }
    if (std::abs(channel.phasors(0)) < kNodeFraction * largest_fundamental) continue;
    // The ringing's complex amplitude in the fundamental's band at the start.
    Complex start = Complex(column(p), -column(p + 1)) * std::exp(Complex(-best_decay, best_beat) * tau_start);
    if (num_ringing == 4)
      start += Complex(column(p + 2), -column(p + 3)) * std::exp(Complex(-best_decay, -best_beat) * tau_start);
    const double relative = std::abs(start) / std::abs(channel.phasors(0));
    if (relative > result.amplitude_relative) {
      result.amplitude_relative = relative;
      result.channel = static_cast<std::size_t>(c);
    }
  }
  return result;
}

}  // namespace beamid::signal
