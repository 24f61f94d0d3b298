#include "solver/estimation/multiple_scales_problem.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include <Eigen/LU>

#include "hb/option_checks.h"

namespace beamid::solver {

using hb::Complex;
using hb::MultipleScalesModel;

namespace {
// Relative steps of the difference quotients (see the header).
constexpr double kStateStep = 1e-6;
constexpr double kParameterStep = 1e-5;
constexpr int kStateSize = 2;  // Re U, Im U

bool IsPlainBeam(const hb::LinearAttachments& a) {
  return a.point_masses.empty() && std::isinf(a.clamp_rotational_stiffness_Nm_rad) &&
         std::isinf(a.support_translational_stiffness_N_m);
}

// Central difference of a vector function of U in Re U and Im U.
template <class Function>
auto DifferenceInU(const Function& f, Complex u, double step) {
  using Vector = decltype(f(u));
  const Vector re = f(u + step) - f(u - step);
  const Vector im = f(u + Complex(0.0, step)) - f(u - Complex(0.0, step));
  Eigen::Matrix<typename Vector::Scalar, Eigen::Dynamic, Eigen::Dynamic> d(re.size(), 2);
  d.col(0) = re / (2.0 * step);
  d.col(1) = im / (2.0 * step);
  return d;
}
}  // namespace

MultipleScalesModel MakeMultipleScalesModel(const hb::BeamProperties& beam, double force_position_m,
                                            const ModelStructure& structure, const std::vector<double>& parameters,
                                            const hb::MultipleScalesOptions& options) {
  if (!dynamic_cast<const hb::PolynomialSupportLaw*>(structure.law.get()))
    throw std::invalid_argument("the multiple-scales model (--model ms) needs the polynomial support law");
  if (static_cast<int>(parameters.size()) != structure.NumParameters())
    throw std::invalid_argument("multiple-scales model: wrong number of parameters");
  const int num_law = static_cast<int>(structure.law_bounds.size());
  hb::LinearBeamModel linear{.beam = beam};
  for (std::size_t j = 0; j < structure.linear.size(); ++j) structure.linear[j].apply(linear, parameters[num_law + j]);
  if (!IsPlainBeam(linear.attachments))
    throw std::invalid_argument("the multiple-scales model is a plain beam: a linear parameter that adds "
                                "attachments needs the harmonic-balance model (--model hb)");
  const hb::PolynomialSupportLaw::Coefficients law{.k1_Nm_rad = parameters[0], .k2_Nm_rad2 = parameters[1],
                                                   .k3_Nm_rad3 = parameters[2], .c_Nms_rad = parameters[3]};
  return MultipleScalesModel(linear.beam, law, force_position_m, options);
}

void MultipleScalesProblemOptions::Validate() const {
  // The readers' range of η (docs/architecture.md).
  if (!(beam_loss_factor >= 0.0 && beam_loss_factor < 1.0))
    option_checks::Refuse("MultipleScalesProblemOptions.beam_loss_factor",
                          option_checks::FormatValue(beam_loss_factor), "in [0, 1)");
  model.Validate();
}

namespace {

class MultipleScalesStep final : public StepModel {
 public:
  MultipleScalesStep(const FitData& data, const ModelStructure& structure, const MultipleScalesProblemOptions& options)
      : data_(data), structure_(structure), options_(options) {
    options_.Validate();
    if (!dynamic_cast<const hb::PolynomialSupportLaw*>(structure_.law.get()))
      throw std::invalid_argument("the multiple-scales model (--model ms) needs the polynomial support law");
    if (data_.num_fit_harmonics < 1 || data_.num_fit_harmonics > 3)
      throw std::invalid_argument(
          "the multiple-scales model gives harmonics 1..3 only: fit at most 3 harmonics (got " +
          std::to_string(data_.num_fit_harmonics) + ")");
    if (!IsPlainBeam(data_.sensor_masses))
      throw std::invalid_argument(
          "the multiple-scales model has no point masses: campaign.json gives sensor masses (mass_kg), "
          "use the harmonic-balance model (--model hb)");
    for (const FitStep& s : data_.steps)
      if (s.force_N.size() < 2) throw std::invalid_argument("step " + s.file + " has no force fundamental");
    num_parameters_ = structure_.NumParameters();
    bounds_ = structure_.Bounds();
    base_beam_ = data_.beam;
    base_beam_.loss_factor = options_.beam_loss_factor;
    for (const FitChannel& c : data_.channels) positions_m_.push_back(c.position_m);
  }

  int state_size() const override { return kStateSize; }
  double TypicalStateSize() const override { return 1e-4; }
  int num_model_harmonics() const override { return 3; }

  void SetParameters(const std::vector<double>& parameters) override { set_ = &ModelsAt(parameters); }

  void Evaluate(int step, const Eigen::VectorXd& z, double state_scale, Values* v) override {
    const Complex u(z[0], z[1]);
    const ModelSet& set = *set_;
    auto balance = [&](const ModelSet::Steps& model, Complex uu) -> Eigen::VectorXd {
      return Balance(model[step], uu);
    };
    auto sensors = [&](const ModelSet::Steps& model, Complex uu) -> Eigen::VectorXcd {
      return Sensors(model[step], uu);
    };
    v->balance = balance(set.center_steps, u);
    v->sensors = sensors(set.center_steps, u);
    const double h = kStateStep * state_scale;
    v->balance_d_state = DifferenceInU([&](Complex uu) { return balance(set.center_steps, uu); }, u, h);
    v->sensors_d_state = DifferenceInU([&](Complex uu) { return sensors(set.center_steps, uu); }, u, h);
    v->balance_d_parameters.resize(kStateSize, num_parameters_);
    v->sensors_d_parameters.resize(v->sensors.size(), num_parameters_);
    for (int j = 0; j < num_parameters_; ++j) {
      const ModelSet::Stencil& stencil = set.stencils[j];
      Eigen::VectorXd d_balance = stencil.center_weight * v->balance;
      Eigen::VectorXcd d_sensors = stencil.center_weight * v->sensors;
      for (std::size_t m = 0; m < stencil.models.size(); ++m) {
        d_balance += stencil.weights[m] * balance(stencil.models[m], u);
        d_sensors += stencil.weights[m] * sensors(stencil.models[m], u);
      }
      v->balance_d_parameters.col(j) = d_balance;
      v->sensors_d_parameters.col(j) = d_sensors;
    }
  }

  std::vector<Eigen::VectorXd> SolveStates(const std::vector<double>& parameters, int* failed_steps,
                                           std::vector<Eigen::VectorXd>* /*measured: not from the data*/) override {
    SetParameters(parameters);
    const ModelSet& set = *set_;
    std::vector<Eigen::VectorXd> states;
    int failures = 0;
    for (int i = 0; i < static_cast<int>(data_.steps.size()); ++i) {
      const FitStep& s = data_.steps[i];
      Complex state(0.0);
      std::vector<Complex> roots;
      try {
        roots = set.center.Solve(s.omega_rad_s, s.force_N[1]);
      } catch (const std::runtime_error&) {
        ++failures;  // an internal resonance at 2Ω or 3Ω: no steady state in this model
      }
      if (roots.size() == 3) roots.erase(roots.begin() + 1);  // the unstable middle branch
      double best = std::numeric_limits<double>::infinity();
      for (Complex u : roots) {
        const double misfit = WhitenedMisfit(data_, i, Sensors(set.center_steps[i], u)).squaredNorm();
        if (misfit < best) {
          best = misfit;
          state = u;
        }
      }
      states.push_back(Eigen::Vector2d(state.real(), state.imag()));
    }
    if (failed_steps) *failed_steps = failures;
    return states;
  }

  // |∂S/∂U| (the rms singular value) times U's size: the force U takes.
  Eigen::VectorXd BalanceScale(int step, const Eigen::VectorXd& z, double state_scale) override {
    const Eigen::MatrixXd d = DifferenceInU(
        [&](Complex u) -> Eigen::VectorXd { return Balance(set_->center_steps[step], u); }, Complex(z[0], z[1]),
        kStateStep * state_scale);
    const double scale = d.norm() / std::sqrt(2.0) * state_scale;
    return Eigen::VectorXd::Constant(kStateSize, std::isfinite(scale) && scale > 0.0 ? scale : 1.0);
  }

  Eigen::MatrixXcd DisplacementPhasors(const std::vector<double>& parameters, int step, const Eigen::VectorXd& z,
                                       const std::vector<double>& positions_m) override {
    const MultipleScalesModel model = Model(parameters);
    const FitStep& s = data_.steps[step];
    Eigen::MatrixXcd phasors(positions_m.size(), 4);
    for (std::size_t c = 0; c < positions_m.size(); ++c) {
      const MultipleScalesModel::Harmonics h =
          model.Response(positions_m[c], Complex(z[0], z[1]), s.omega_rad_s, s.force_N[1]);
      phasors.row(c) << h.h0_m, h.h1_m, h.h2_m, h.h3_m;
    }
    return phasors;
  }

  Eigen::VectorXcd StepState(const Eigen::VectorXd& z) const override {
    return Eigen::VectorXcd::Constant(1, Complex(z[0], z[1]));
  }

 private:
  // The model at the current parameters and, per parameter, the models of its
  // difference stencil: ∂f/∂p_j ≈ center_weight·f(p) + Σ weight_k·f(model_k).
  // Each model is kept as its excitations, one per step (at the fitted
  // channels' positions): all of it that does not depend on U.
  struct ModelSet {
    using Steps = std::vector<MultipleScalesModel::Excitation>;
    struct Stencil {
      double center_weight = 0.0;
      std::vector<Steps> models;
      std::vector<double> weights;
    };
    std::vector<double> parameters;
    MultipleScalesModel center;
    Steps center_steps;
    std::vector<Stencil> stencils;
  };

  static Eigen::VectorXd Balance(const MultipleScalesModel::Excitation& excitation, Complex u) {
    const Complex residual = excitation.SolvabilityResidual_N(u);
    return Eigen::Vector2d(residual.real(), residual.imag());
  }

  // h1..h3 at the fitted channels, harmonics 1..K (entry c·K + k − 1).
  Eigen::VectorXcd Sensors(const MultipleScalesModel::Excitation& excitation, Complex u) const {
    const int channels = static_cast<int>(data_.channels.size()), k_max = data_.num_fit_harmonics;
    Eigen::VectorXcd y(channels * k_max);
    for (int c = 0; c < channels; ++c) {
      const MultipleScalesModel::Harmonics h = excitation.Response(c, u);
      const Complex displacement[] = {h.h1_m, h.h2_m, h.h3_m};
      for (int k = 1; k <= k_max; ++k) y[c * k_max + k - 1] = displacement[k - 1];
    }
    return y;
  }

  MultipleScalesModel Model(const std::vector<double>& parameters) const {
    if (static_cast<int>(parameters.size()) != num_parameters_)
      throw std::invalid_argument("MultipleScalesProblem: wrong number of parameters");
    // Ipopt evaluates within its slightly relaxed bounds; the model refuses
    // k1 < 0 and c < 0 even by 1e-12.
    std::vector<double> p(parameters);
    for (int j = 0; j < num_parameters_; ++j) p[j] = std::clamp(p[j], bounds_[j].lower, bounds_[j].upper);
    return MakeMultipleScalesModel(base_beam_, data_.force_position_m, structure_, p, options_.model);
  }

  const ModelSet& ModelsAt(const std::vector<double>& parameters) {
    if (models_ && models_->parameters == parameters) return *models_;
    models_.reset();
    auto excitations = [&](const MultipleScalesModel& model) {
      ModelSet::Steps steps;
      for (const FitStep& s : data_.steps)
        steps.push_back(model.AtExcitation(s.omega_rad_s, s.force_N[1], positions_m_));
      return steps;
    };
    auto set = std::make_unique<ModelSet>(ModelSet{.parameters = parameters, .center = Model(parameters)});
    set->center_steps = excitations(set->center);
    for (int j = 0; j < num_parameters_; ++j) {
      const double h = kParameterStep * std::max(std::abs(parameters[j]), bounds_[j].typical);
      const bool below = parameters[j] - h < bounds_[j].lower, above = parameters[j] + h > bounds_[j].upper;
      // Second-order one-sided stencils where the central one would leave the
      // bounds (the model may not exist there), central otherwise.
      ModelSet::Stencil stencil;
      std::vector<double> offsets;
      if (below && !above) {
        stencil.center_weight = -3.0 / (2.0 * h);
        offsets = {h, 2.0 * h};
        stencil.weights = {4.0 / (2.0 * h), -1.0 / (2.0 * h)};
      } else if (above && !below) {
        stencil.center_weight = 3.0 / (2.0 * h);
        offsets = {-h, -2.0 * h};
        stencil.weights = {-4.0 / (2.0 * h), 1.0 / (2.0 * h)};
      } else {
        offsets = {h, -h};
        stencil.weights = {1.0 / (2.0 * h), -1.0 / (2.0 * h)};
      }
      for (double offset : offsets) {
        std::vector<double> nudged = parameters;
        nudged[j] += offset;
        stencil.models.push_back(excitations(Model(nudged)));
      }
      set->stencils.push_back(std::move(stencil));
    }
    models_ = std::move(set);
    return *models_;
  }

  const FitData& data_;
  const ModelStructure& structure_;
  MultipleScalesProblemOptions options_;
  int num_parameters_ = 0;
  std::vector<ParameterBounds> bounds_;
  hb::BeamProperties base_beam_;
  std::vector<double> positions_m_;
  std::unique_ptr<ModelSet> models_;
  const ModelSet* set_ = nullptr;  // at the parameters last set
};

}  // namespace

MultipleScalesProblem::MultipleScalesProblem(const FitData& data, const ModelStructure& structure,
                                             const MultipleScalesProblemOptions& options)
    : SteppedFitProblem(data, structure, [&](const FitData& d, const ModelStructure& s) {
        return std::make_unique<MultipleScalesStep>(d, s, options);
      }) {}

}  // namespace beamid::solver
