#include "solver/estimation/identification_problem.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include <Eigen/LU>

#include "hb/harmonic_balance.h"
#include "solver/estimation/support_reconstruction.h"

namespace beamid::solver {

using hb::Complex;
using hb::HarmonicBalance;
using hb::LinearHarmonics;

namespace {
// Relative nudge of a linear parameter for its difference quotient.
constexpr double kLinearNudge = 1e-6;

class HarmonicBalanceStep final : public StepModel {
 public:
  HarmonicBalanceStep(const FitData& data, const ModelStructure& structure, const ModelOptions& options)
      : data_(data), structure_(structure), options_(options) {
    options_.Validate();
    if (!structure_.law) throw std::invalid_argument("the model structure has no support law");
    if (options_.num_harmonics < data_.num_fit_harmonics)
      throw std::invalid_argument("the model must hold at least the fitted harmonics");
    num_law_ = static_cast<int>(structure_.law_bounds.size());
    num_linear_ = static_cast<int>(structure_.linear.size());
    for (const auto& c : data_.channels) positions_m_.push_back(c.position_m);
    base_model_ = {.beam = data_.beam, .attachments = data_.sensor_masses};
    base_model_.beam.loss_factor = options_.beam_loss_factor;
    balance_ = std::make_unique<HarmonicBalance>(
        hb::LinearBeam(base_model_, data_.force_position_m), *structure_.law,
        hb::HarmonicBalanceOptions{.num_harmonics = options_.num_harmonics,
                                   .num_time_samples = options_.num_time_samples});
  }

  int state_size() const override { return 2 * options_.num_harmonics + 1; }
  double TypicalStateSize() const override { return 1e-3; }
  int num_model_harmonics() const override { return options_.num_harmonics; }

  void SetParameters(const std::vector<double>& p) override {
    law_values_.assign(p.begin(), p.begin() + num_law_);
    balance_->SetLawParameters(law_values_);
    UpdateLinear(std::vector<double>(p.begin() + num_law_, p.end()));
  }

  void Evaluate(int step, const Eigen::VectorXd& z, double /*state_scale*/, Values* v) override {
    const FitStep& s = data_.steps[step];
    const int h = options_.num_harmonics, m = state_size(), k_max = data_.num_fit_harmonics;
    const LinearHarmonics& linear = linear_[step];
    const Eigen::VectorXcd theta = HarmonicBalance::ToComplex(z);
    const Eigen::VectorXcd force = hb::PadHarmonics(s.force_N, h);
    balance_->Residual(z, linear, s.force_N, &v->balance, &v->balance_d_state);
    v->balance_d_parameters.resize(m, num_law_ + num_linear_);
    if (num_law_ > 0) v->balance_d_parameters.leftCols(num_law_) = balance_->ParameterJacobian(z, s.omega_rad_s);
    v->sensors = Sensors(step, theta, linear);
    v->sensors_d_parameters = Eigen::MatrixXcd::Zero(v->sensors.size(), num_law_ + num_linear_);
    for (int j = 0; j < num_linear_; ++j) {
      const LinearHarmonics& nudged = linear_nudged_[j][step];
      Eigen::VectorXcd d_balance(h + 1);
      for (int k = 0; k <= h; ++k)
        d_balance[k] = ((nudged.rotational_stiffness[k] - linear.rotational_stiffness[k]) * theta[k] -
                        (nudged.blocked_moment_per_force[k] - linear.blocked_moment_per_force[k]) * force[k]) /
                       linear_step_[j];
      d_balance[0] = d_balance[0].real();
      v->balance_d_parameters.col(num_law_ + j) = HarmonicBalance::ToReal(d_balance);
      v->sensors_d_parameters.col(num_law_ + j) = (Sensors(step, theta, nudged) - v->sensors) / linear_step_[j];
    }
    // Only Re/Im Θ_k of the fitted harmonics enter, through b.
    v->sensors_d_state = Eigen::MatrixXcd::Zero(v->sensors.size(), m);
    for (int c = 0; c < static_cast<int>(data_.channels.size()); ++c)
      for (int k = 1; k <= k_max; ++k) {
        const Complex b = linear.displacement_per_rotation(c, k);
        v->sensors_d_state(c * k_max + k - 1, 2 * k - 1) = b;
        v->sensors_d_state(c * k_max + k - 1, 2 * k) = Complex(0.0, 1.0) * b;
      }
  }

  // The gradient of μᵀR (w.r.t. p_law, z) differenced; the linear
  // parameters enter R as D(p_l)·Θ − B(p_l)·F: a cross term with z only.
  bool BalanceCurvature(int step, const Eigen::VectorXd& z, double state_scale, const Eigen::VectorXd& mu,
                        Eigen::MatrixXd* second) override {
    if (!options_.constraint_curvature) return false;
    const FitStep& s = data_.steps[step];
    const int m = state_size(), p = num_law_ + num_linear_, h = options_.num_harmonics;
    const std::vector<double> law = law_values_;
    auto gradient = [&](const Eigen::VectorXd& zz, const std::vector<double>& nudged_law) {
      balance_->SetLawParameters(nudged_law);
      Eigen::VectorXd r;
      Eigen::MatrixXd jz;
      balance_->Residual(zz, linear_[step], s.force_N, &r, &jz);
      Eigen::VectorXd g(num_law_ + m);
      g.head(num_law_) = balance_->ParameterJacobian(zz, s.omega_rad_s).transpose() * mu;
      g.tail(m) = jz.transpose() * mu;
      return g;
    };
    Eigen::MatrixXd differenced = Eigen::MatrixXd::Zero(num_law_ + m, num_law_ + m);
    for (int j = 0; j < num_law_ + m; ++j) {
      const bool is_law = j < num_law_;
      const double nudge = 1e-6 * (is_law ? structure_.law_bounds[j].typical : state_scale);
      Eigen::VectorXd z_up = z, z_down = z;
      std::vector<double> law_up = law, law_down = law;
      if (is_law) {
        law_up[j] += nudge;
        law_down[j] -= nudge;
      } else {
        z_up[j - num_law_] += nudge;
        z_down[j - num_law_] -= nudge;
      }
      differenced.col(j) = (gradient(z_up, law_up) - gradient(z_down, law_down)) / (2.0 * nudge);
    }
    balance_->SetLawParameters(law);
    differenced = 0.5 * (differenced + differenced.transpose()).eval();
    *second = Eigen::MatrixXd::Zero(p + m, p + m);
    second->topLeftCorner(num_law_, num_law_) = differenced.topLeftCorner(num_law_, num_law_);
    second->block(p, 0, m, num_law_) = differenced.bottomLeftCorner(m, num_law_);
    second->bottomRightCorner(m, m) = differenced.bottomRightCorner(m, m);
    for (int j = 0; j < num_linear_; ++j) {
      const LinearHarmonics& nudged = linear_nudged_[j][step];
      Eigen::VectorXd column = Eigen::VectorXd::Zero(m);
      for (int k = 0; k <= h; ++k) {
        const Complex d = (nudged.rotational_stiffness[k] - linear_[step].rotational_stiffness[k]) / linear_step_[j];
        if (k == 0) {
          column[0] = d.real() * mu[0];
          continue;
        }
        // ∂/∂(Re Θ, Im Θ) of μ_re·Re(dΘ) + μ_im·Im(dΘ).
        column[2 * k - 1] = d.real() * mu[2 * k - 1] + d.imag() * mu[2 * k];
        column[2 * k] = -d.imag() * mu[2 * k - 1] + d.real() * mu[2 * k];
      }
      second->block(p, num_law_ + j, m, 1) = column;
    }
    return true;
  }

  std::vector<Eigen::VectorXd> SolveStates(const std::vector<double>& parameters, int* failed_steps,
                                           std::vector<Eigen::VectorXd>* measured) override {
    const std::vector<ReconstructedStep> rotations = MeasuredRotations(parameters);
    std::vector<Eigen::VectorXd> states = FeasibleStates(parameters, rotations, failed_steps);
    if (measured && !rotations.empty()) {
      // The feasible state keeps the harmonics the sensors do not resolve
      // (0 and above K); the measured ones replace the rest.
      measured->clear();
      for (int i = 0; i < static_cast<int>(states.size()); ++i) {
        Eigen::VectorXcd theta = HarmonicBalance::ToComplex(states[i]);
        const Eigen::VectorXcd& m = rotations[i].theta_rad;
        for (Eigen::Index k = 1; k < std::min<Eigen::Index>(m.size(), theta.size()); ++k) theta[k] = m[k];
        measured->push_back(HarmonicBalance::ToReal(theta));
      }
    }
    return states;
  }

  // Each harmonic's row by the moment its own stiffness D(kω) takes: D is
  // huge near the clamped–clamped frequencies of a high harmonic, and an
  // unscaled row there would dominate the constraint violation.
  Eigen::VectorXd BalanceScale(int step, const Eigen::VectorXd& /*z*/, double state_scale) override {
    const double k_law = balance_->law().InitialStiffness_Nm_rad();
    Eigen::VectorXd scale(state_size());
    for (int k = 0; k <= options_.num_harmonics; ++k) {
      const double row = state_scale * std::max(std::abs(linear_[step].rotational_stiffness[k]), k_law + 1.0);
      scale[k == 0 ? 0 : 2 * k - 1] = row;
      if (k > 0) scale[2 * k] = row;
    }
    return scale;
  }

  Eigen::MatrixXcd DisplacementPhasors(const std::vector<double>& p, int step, const Eigen::VectorXd& z,
                                       const std::vector<double>& positions_m) override {
    hb::LinearBeamModel model = base_model_;
    for (int j = 0; j < num_linear_; ++j) structure_.linear[j].apply(model, p[num_law_ + j]);
    const hb::LinearBeam beam(model, data_.force_position_m);
    const FitStep& s = data_.steps[step];
    const LinearHarmonics linear =
        hb::ComputeLinearHarmonics(beam, s.omega_rad_s, options_.num_harmonics, positions_m);
    const Eigen::VectorXcd theta = HarmonicBalance::ToComplex(z);
    const Eigen::VectorXcd force = hb::PadHarmonics(s.force_N, options_.num_harmonics);
    return linear.displacement_per_force * force.asDiagonal() + linear.displacement_per_rotation * theta.asDiagonal();
  }

  Eigen::VectorXcd StepState(const Eigen::VectorXd& z) const override { return HarmonicBalance::ToComplex(z); }

 private:
  // Y at the fitted channels, harmonics 1..K (entry c·K + k − 1).
  Eigen::VectorXcd Sensors(int step, const Eigen::VectorXcd& theta, const LinearHarmonics& linear) const {
    const Eigen::VectorXcd force = hb::PadHarmonics(data_.steps[step].force_N, options_.num_harmonics);
    const int channels = static_cast<int>(data_.channels.size()), k_max = data_.num_fit_harmonics;
    Eigen::VectorXcd y(channels * k_max);
    for (int c = 0; c < channels; ++c)
      for (int k = 1; k <= k_max; ++k)
        y[c * k_max + k - 1] =
            linear.displacement_per_force(c, k) * force[k] + linear.displacement_per_rotation(c, k) * theta[k];
    return y;
  }

  // The linear part per step at these linear parameters, and at each
  // parameter nudged for the difference quotients.
  void UpdateLinear(const std::vector<double>& linear_values) {
    if (linear_valid_ && linear_values == linear_values_) return;
    linear_values_ = linear_values;
    const double max_hz = [&] {
      double m = 0.0;
      for (const auto& s : data_.steps) m = std::max(m, s.omega_rad_s);
      return 1.5 * (options_.num_harmonics + 1) * m / (2.0 * 3.141592653589793);
    }();
    auto build = [&](const std::vector<double>& values) {
      hb::LinearBeamModel model = base_model_;
      for (int j = 0; j < num_linear_; ++j) structure_.linear[j].apply(model, values[j]);
      const hb::LinearBeam beam(model, data_.force_position_m, {.max_frequency_hz = std::max(max_hz, 100.0)});
      std::vector<LinearHarmonics> per_step;
      for (const auto& s : data_.steps)
        per_step.push_back(hb::ComputeLinearHarmonics(beam, s.omega_rad_s, options_.num_harmonics, positions_m_));
      return per_step;
    };
    linear_ = build(linear_values);
    linear_nudged_.assign(num_linear_, {});
    linear_step_.assign(num_linear_, 0.0);
    for (int j = 0; j < num_linear_; ++j) {
      std::vector<double> nudged = linear_values;
      linear_step_[j] = kLinearNudge * std::max(std::abs(linear_values[j]), structure_.linear[j].bounds.typical);
      nudged[j] += linear_step_[j];
      linear_nudged_[j] = build(nudged);
    }
    linear_valid_ = true;
  }

  // The support rotation the measurements show through the exact linear
  // beam with these linear parameters (solver/support_reconstruction.h;
  // empty when too few channels reconstruct it).
  std::vector<ReconstructedStep> MeasuredRotations(const std::vector<double>& parameters) const {
    try {
      ModelStructure current = structure_;
      current.SetValues(parameters);
      return ReconstructSupport(data_, current.ApplyLinear(base_model_));
    } catch (const std::exception&) {
      return {};  // too few channels to reconstruct: the sweep alone decides
    }
  }

  // Newton on every step's balance, started at `measured` where it is
  // given, else warm-started along each sweep, else at the linear response
  // (which failed steps keep).
  std::vector<Eigen::VectorXd> FeasibleStates(const std::vector<double>& parameters,
                                              const std::vector<ReconstructedStep>& measured, int* failed_steps) {
    SetParameters(parameters);
    const int h = options_.num_harmonics;
    const double k_law = balance_->law().InitialStiffness_Nm_rad();
    const double c_law = balance_->law().InitialDamping_Nms_rad();
    // Newton started at the support rotation the measurements show lands on
    // the branch the test was on, whatever branch a sweep with far-off
    // parameters would have followed.
    const int num_steps = static_cast<int>(data_.steps.size());
    std::vector<Eigen::VectorXd> states(num_steps);
    int failures = 0;
    Eigen::VectorXd previous;
    std::string previous_level;
    for (int i = 0; i < num_steps; ++i) {
      const FitStep& s = data_.steps[i];
      const LinearHarmonics& linear = linear_[i];
      // Linear guess with the law's small-amplitude stiffness.
      Eigen::VectorXcd theta(h + 1);
      const Eigen::VectorXcd force = hb::PadHarmonics(s.force_N, h);
      for (int k = 0; k <= h; ++k)
        theta[k] = linear.blocked_moment_per_force[k] * force[k] /
                   (linear.rotational_stiffness[k] + Complex(k_law, k * s.omega_rad_s * c_law));
      const Eigen::VectorXd linear_guess = HarmonicBalance::ToReal(theta);
      auto newton = [&](Eigen::VectorXd z) -> std::optional<Eigen::VectorXd> {
        Eigen::VectorXd r;
        Eigen::MatrixXd j;
        for (int iteration = 0; iteration < 60; ++iteration) {
          balance_->Residual(z, linear, s.force_N, &r, &j);
          const Eigen::VectorXd step = j.partialPivLu().solve(-r);
          if (!step.allFinite()) return std::nullopt;
          // Damped: never move |θ| by more than its own size at once.
          const double limit = std::max(z.norm(), 1e-9);
          z += step.norm() > limit ? Eigen::VectorXd(step * (limit / step.norm())) : step;
          if (step.norm() <= 1e-11 * (z.norm() + 1e-15)) return z;
        }
        return std::nullopt;
      };
      std::optional<Eigen::VectorXd> solution;
      if (!measured.empty()) {
        Eigen::VectorXcd theta_measured = Eigen::VectorXcd::Zero(h + 1);
        const Eigen::VectorXcd& m = measured[i].theta_rad;
        for (Eigen::Index k = 1; k < std::min<Eigen::Index>(m.size(), h + 1); ++k) theta_measured[k] = m[k];
        solution = newton(HarmonicBalance::ToReal(theta_measured));
      }
      if (!solution && previous.size() && s.level == previous_level) solution = newton(previous);
      if (!solution) solution = newton(linear_guess);
      if (!solution) {
        ++failures;
        solution = linear_guess;
      }
      states[i] = *solution;
      previous = *solution;
      previous_level = s.level;
    }
    if (failed_steps) *failed_steps = failures;
    return states;
  }

  const FitData& data_;
  const ModelStructure& structure_;
  ModelOptions options_;
  int num_law_ = 0, num_linear_ = 0;
  std::vector<double> positions_m_;
  hb::LinearBeamModel base_model_;
  std::unique_ptr<HarmonicBalance> balance_;

  std::vector<double> law_values_;  // as last set
  std::vector<double> linear_values_;
  bool linear_valid_ = false;
  std::vector<LinearHarmonics> linear_;
  std::vector<std::vector<LinearHarmonics>> linear_nudged_;  // [parameter][step]
  std::vector<double> linear_step_;
};

}  // namespace

IdentificationProblem::IdentificationProblem(const FitData& data, const ModelStructure& structure,
                                             const ModelOptions& options)
    : SteppedFitProblem(data, structure, [&](const FitData& d, const ModelStructure& s) {
        return std::make_unique<HarmonicBalanceStep>(d, s, options);
      }) {}

}  // namespace beamid::solver
