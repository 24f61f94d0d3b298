#include "solver/estimation/multiple_scales_problem.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <Eigen/LU>

#include "hb/option_checks.h"

namespace beamid::solver {

using hb::Complex;
using hb::MultipleScalesModel;

// Per step, the constraint S_i (2 rows, N) stacked over the whitened misfit
// r_i, and their derivatives in U_i and in the physical parameters.
struct MultipleScalesProblem::StepCache {
  Eigen::VectorXd values;
  Eigen::MatrixXd d_values_d_z;  // (2 + n) × 2
  Eigen::MatrixXd d_values_d_p;  // (2 + n) × P
};

// The model at the current parameters and, per parameter, the models of its
// difference stencil: ∂f/∂p_j ≈ center_weight·f(p) + Σ weight_k·f(model_k).
// Each model is kept as its excitations, one per step (at the fitted
// channels' positions): all of it that does not depend on U.
struct MultipleScalesProblem::ModelSet {
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

namespace {
// Relative steps of the difference quotients (see the header).
constexpr double kStateStep = 1e-6;
constexpr double kParameterStep = 1e-5;

bool IsPlainBeam(const hb::LinearAttachments& a) {
  return a.point_masses.empty() && std::isinf(a.clamp_rotational_stiffness_Nm_rad) &&
         std::isinf(a.support_translational_stiffness_N_m);
}

// Central difference of a vector function of U in Re U and Im U.
template <class Function>
Eigen::MatrixXd DifferenceInU(const Function& f, Complex u, double step) {
  const Eigen::VectorXd re = f(u + step) - f(u - step);
  const Eigen::VectorXd im = f(u + Complex(0.0, step)) - f(u - Complex(0.0, step));
  Eigen::MatrixXd d(re.size(), 2);
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

MultipleScalesProblem::MultipleScalesProblem(const FitData& data, const ModelStructure& structure,
                                             const MultipleScalesProblemOptions& options)
    : data_(data), structure_(structure), options_(options) {
  options_.Validate();
  if (!dynamic_cast<const hb::PolynomialSupportLaw*>(structure_.law.get()))
    throw std::invalid_argument("the multiple-scales model (--model ms) needs the polynomial support law");
  if (data_.num_fit_harmonics < 1 || data_.num_fit_harmonics > 3)
    throw std::invalid_argument("the multiple-scales model gives harmonics 1..3 only: fit at most 3 harmonics (got " +
                                std::to_string(data_.num_fit_harmonics) + ")");
  if (!IsPlainBeam(data_.sensor_masses))
    throw std::invalid_argument(
        "the multiple-scales model has no point masses: campaign.json gives sensor masses (mass_kg), "
        "use the harmonic-balance model (--model hb)");
  for (const FitStep& s : data_.steps)
    if (s.force_N.size() < 2)
      throw std::invalid_argument("step " + s.file + " has no force fundamental");
  num_parameters_ = structure_.NumParameters();
  scaling_ = ParameterScaling(structure_.Bounds());
  base_beam_ = data_.beam;
  base_beam_.loss_factor = options_.beam_loss_factor;
  cache_.resize(num_steps());
  state_scale_m_.assign(num_steps(), 1e-4);  // refined by FeasiblePoint
  constraint_scale_N_.assign(num_steps(), 1.0);
}

MultipleScalesProblem::~MultipleScalesProblem() = default;

std::vector<double> MultipleScalesProblem::Parameters(const Eigen::VectorXd& x) const {
  return scaling_.Physical(x);
}

Complex MultipleScalesProblem::ModalPhasor_m(const Eigen::VectorXd& x, int step) const {
  const int at = num_parameters_ + kStateSize * step;
  return Complex(x[at], x[at + 1]) * state_scale_m_[step];
}

MultipleScalesModel MultipleScalesProblem::Model(const std::vector<double>& parameters) const {
  if (static_cast<int>(parameters.size()) != num_parameters_)
    throw std::invalid_argument("MultipleScalesProblem: wrong number of parameters");
  // Ipopt evaluates within its slightly relaxed bounds; the model refuses
  // k1 < 0 and c < 0 even by 1e-12.
  std::vector<double> p(parameters);
  for (int j = 0; j < num_parameters_; ++j)
    p[j] = std::clamp(p[j], scaling_.bounds()[j].lower, scaling_.bounds()[j].upper);
  return MakeMultipleScalesModel(base_beam_, data_.force_position_m, structure_, p, options_.model);
}

const MultipleScalesProblem::ModelSet& MultipleScalesProblem::ModelsAt(const std::vector<double>& parameters) {
  if (models_ && models_->parameters == parameters) return *models_;
  models_.reset();
  std::vector<double> positions_m;
  for (const FitChannel& c : data_.channels) positions_m.push_back(c.position_m);
  auto excitations = [&](const MultipleScalesModel& model) {
    ModelSet::Steps steps;
    for (const FitStep& s : data_.steps) steps.push_back(model.AtExcitation(s.omega_rad_s, s.force_N[1], positions_m));
    return steps;
  };
  auto set = std::make_unique<ModelSet>(ModelSet{.parameters = parameters, .center = Model(parameters)});
  set->center_steps = excitations(set->center);
  for (int j = 0; j < num_parameters_; ++j) {
    const double h = kParameterStep * std::max(std::abs(parameters[j]), scaling_.scale(j));
    const bool below = parameters[j] - h < scaling_.bounds()[j].lower, above = parameters[j] + h > scaling_.bounds()[j].upper;
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

Eigen::Vector2d MultipleScalesProblem::StepConstraint(const MultipleScalesModel::Excitation& excitation, Complex u) {
  const Complex residual = excitation.SolvabilityResidual_N(u);
  return {residual.real(), residual.imag()};
}

Eigen::VectorXd MultipleScalesProblem::StepResidual(const MultipleScalesModel::Excitation& excitation, int step,
                                                    Complex u) const {
  const FitStep& s = data_.steps[step];
  const int channels = static_cast<int>(data_.channels.size());
  const int k_max = data_.num_fit_harmonics;
  Eigen::VectorXd r(2 * channels * k_max);
  for (int c = 0; c < channels; ++c) {
    const MultipleScalesModel::Harmonics h = excitation.Response(c, u);
    const Complex displacement[] = {h.h1_m, h.h2_m, h.h3_m};
    for (int k = 1; k <= k_max; ++k) {
      const Complex misfit = DerivativeFactor(data_.channels[c].derivative_order, k * s.omega_rad_s) *
                                 displacement[k - 1] -
                             s.measured(c, k - 1);
      r.segment<2>(2 * (c * k_max + k - 1)) = s.whitening[c][k - 1] * Eigen::Vector2d(misfit.real(), misfit.imag());
    }
  }
  return r;
}

void MultipleScalesProblem::Evaluate(const Eigen::VectorXd& x) {
  if (cached_x_.size() == x.size() && cached_x_ == x) return;
  const ModelSet& set = ModelsAt(Parameters(x));
  objective_ = 0.0;
  for (int i = 0; i < num_steps(); ++i) {
    StepCache& c = cache_[i];
    const Complex u = ModalPhasor_m(x, i);
    auto values = [&](const ModelSet::Steps& model, Complex uu) {
      const Eigen::VectorXd r = StepResidual(model[i], i, uu);
      Eigen::VectorXd v(kStateSize + r.size());
      v << StepConstraint(model[i], uu), r;
      return v;
    };
    c.values = values(set.center_steps, u);
    objective_ += 0.5 * c.values.tail(c.values.size() - kStateSize).squaredNorm();
    c.d_values_d_z = DifferenceInU([&](Complex uu) { return values(set.center_steps, uu); }, u,
                                   kStateStep * state_scale_m_[i]);
    c.d_values_d_p.resize(c.values.size(), num_parameters_);
    for (int j = 0; j < num_parameters_; ++j) {
      const ModelSet::Stencil& stencil = set.stencils[j];
      Eigen::VectorXd d = stencil.center_weight * c.values;
      for (std::size_t m = 0; m < stencil.models.size(); ++m) d += stencil.weights[m] * values(stencil.models[m], u);
      c.d_values_d_p.col(j) = d;
    }
  }
  cached_x_ = x;
}

Eigen::VectorXd MultipleScalesProblem::FeasiblePoint(const std::vector<double>& parameters, int* failed_steps) {
  const ModelSet& set = ModelsAt(parameters);
  const MultipleScalesModel& model = set.center;
  std::vector<Complex> states(num_steps(), Complex(0.0));
  int failures = 0;
  for (int i = 0; i < num_steps(); ++i) {
    const FitStep& s = data_.steps[i];
    std::vector<Complex> roots;
    try {
      roots = model.Solve(s.omega_rad_s, s.force_N[1]);
    } catch (const std::runtime_error&) {
      ++failures;  // an internal resonance at 2Ω or 3Ω: no steady state in this model
      continue;
    }
    if (roots.size() == 3) roots.erase(roots.begin() + 1);  // the unstable middle branch
    double best = std::numeric_limits<double>::infinity();
    for (Complex u : roots) {
      const double misfit = StepResidual(set.center_steps[i], i, u).squaredNorm();
      if (misfit < best) {
        best = misfit;
        states[i] = u;
      }
    }
  }
  double largest = 0.0;
  for (Complex u : states) largest = std::max(largest, std::abs(u));
  for (int i = 0; i < num_steps(); ++i) {
    state_scale_m_[i] = std::max(std::abs(states[i]), 1e-6 * largest + 1e-15);
    const Eigen::MatrixXd d =
        DifferenceInU([&](Complex u) -> Eigen::VectorXd { return StepConstraint(set.center_steps[i], u); }, states[i],
                      kStateStep * state_scale_m_[i]);
    // |∂S/∂U| (the rms singular value) times U's size: the force U takes.
    const double scale = d.norm() / std::sqrt(2.0) * state_scale_m_[i];
    constraint_scale_N_[i] = std::isfinite(scale) && scale > 0.0 ? scale : 1.0;
  }
  Eigen::VectorXd x(num_variables());
  scaling_.SetScaled(parameters, &x);
  for (int i = 0; i < num_steps(); ++i) {
    x[num_parameters_ + kStateSize * i] = states[i].real() / state_scale_m_[i];
    x[num_parameters_ + kStateSize * i + 1] = states[i].imag() / state_scale_m_[i];
  }
  cached_x_.resize(0);
  if (failed_steps) *failed_steps = failures;
  return x;
}

void MultipleScalesProblem::Bounds(Eigen::VectorXd* lower, Eigen::VectorXd* upper) const {
  scaling_.Bounds(num_variables(), lower, upper);
}

double MultipleScalesProblem::Objective(const Eigen::VectorXd& x) {
  Evaluate(x);
  return objective_;
}

void MultipleScalesProblem::Gradient(const Eigen::VectorXd& x, Eigen::VectorXd* gradient) {
  Evaluate(x);
  gradient->setZero(num_variables());
  for (int i = 0; i < num_steps(); ++i) {
    const StepCache& c = cache_[i];
    const int n = static_cast<int>(c.values.size()) - kStateSize;
    const Eigen::VectorXd r = c.values.tail(n);
    gradient->head(num_parameters_) += c.d_values_d_p.bottomRows(n).transpose() * r;
    gradient->segment<kStateSize>(num_parameters_ + kStateSize * i) =
        c.d_values_d_z.bottomRows(n).transpose() * r * state_scale_m_[i];
  }
  for (int j = 0; j < num_parameters_; ++j) (*gradient)[j] *= scaling_.scale(j);
}

void MultipleScalesProblem::Constraints(const Eigen::VectorXd& x, Eigen::VectorXd* constraints) {
  Evaluate(x);
  constraints->resize(num_constraints());
  for (int i = 0; i < num_steps(); ++i)
    constraints->segment<kStateSize>(kStateSize * i) = cache_[i].values.head<kStateSize>() / constraint_scale_N_[i];
}

void MultipleScalesProblem::JacobianStructure(int* rows, int* cols) const {
  int n = 0;
  for (int row = 0; row < num_constraints(); ++row) {
    const int step = row / kStateSize;
    for (int col = 0; col < num_parameters_ + kStateSize; ++col, ++n) {
      rows[n] = row;
      cols[n] = col < num_parameters_ ? col : col + kStateSize * step;
    }
  }
}

void MultipleScalesProblem::JacobianValues(const Eigen::VectorXd& x, double* values) {
  Evaluate(x);
  int n = 0;
  for (int row = 0; row < num_constraints(); ++row) {
    const int step = row / kStateSize, r = row % kStateSize;
    const StepCache& c = cache_[step];
    const double row_scale = 1.0 / constraint_scale_N_[step];
    for (int j = 0; j < num_parameters_; ++j) values[n++] = c.d_values_d_p(r, j) * scaling_.scale(j) * row_scale;
    for (int j = 0; j < kStateSize; ++j) values[n++] = c.d_values_d_z(r, j) * state_scale_m_[step] * row_scale;
  }
}

// Hessian layout (lower triangle): the parameter block row by row, then per
// step and per state row its P parameter entries and its states up to the
// diagonal.
int MultipleScalesProblem::HessianNonZeros() const {
  const int p = num_parameters_;
  return p * (p + 1) / 2 + num_steps() * (kStateSize * p + kStateSize * (kStateSize + 1) / 2);
}

void MultipleScalesProblem::HessianStructure(int* rows, int* cols) const {
  int n = 0;
  auto add = [&](int row, int col) {
    rows[n] = row;
    cols[n++] = col;
  };
  for (int r = 0; r < num_parameters_; ++r)
    for (int q = 0; q <= r; ++q) add(r, q);
  for (int row = num_parameters_; row < num_variables(); ++row) {
    const int first_state = row - (row - num_parameters_) % kStateSize;
    for (int q = 0; q < num_parameters_; ++q) add(row, q);
    for (int q = first_state; q <= row; ++q) add(row, q);
  }
}

void MultipleScalesProblem::HessianValues(const Eigen::VectorXd& x, double objective_factor,
                                          const double* /*multipliers*/, double* values) {
  Evaluate(x);
  const int p = num_parameters_;
  // Scaled residual Jacobians: J_p (shared columns) and J_z per step.
  const Eigen::VectorXd s = Eigen::Map<const Eigen::VectorXd>(scaling_.scales().data(), p);
  Eigen::MatrixXd hpp = Eigen::MatrixXd::Zero(p, p);
  int n = p * (p + 1) / 2;
  for (int i = 0; i < num_steps(); ++i) {
    const StepCache& c = cache_[i];
    const int rows = static_cast<int>(c.values.size()) - kStateSize;
    const Eigen::MatrixXd jp = c.d_values_d_p.bottomRows(rows) * s.asDiagonal();
    const Eigen::MatrixXd jz = c.d_values_d_z.bottomRows(rows) * state_scale_m_[i];
    hpp += jp.transpose() * jp;
    const Eigen::MatrixXd hzp = jz.transpose() * jp, hzz = jz.transpose() * jz;
    for (int r = 0; r < kStateSize; ++r) {
      for (int q = 0; q < p; ++q) values[n++] = objective_factor * hzp(r, q);
      for (int q = 0; q <= r; ++q) values[n++] = objective_factor * hzz(r, q);
    }
  }
  n = 0;
  for (int r = 0; r < p; ++r)
    for (int q = 0; q <= r; ++q) values[n++] = objective_factor * hpp(r, q);
}

Eigen::VectorXd MultipleScalesProblem::WeightedResiduals(const Eigen::VectorXd& x) {
  Evaluate(x);
  Eigen::VectorXd r(num_residuals());
  int offset = 0;
  for (const StepCache& c : cache_) {
    const int n = static_cast<int>(c.values.size()) - kStateSize;
    r.segment(offset, n) = c.values.tail(n);
    offset += n;
  }
  return r;
}

Eigen::MatrixXd MultipleScalesProblem::ReducedResidualJacobian(const Eigen::VectorXd& x) {
  Evaluate(x);
  Eigen::MatrixXd j(num_residuals(), num_parameters_);
  int offset = 0;
  for (const StepCache& c : cache_) {
    const int n = static_cast<int>(c.values.size()) - kStateSize;
    const Eigen::MatrixXd du_dp =
        -c.d_values_d_z.topRows<kStateSize>().partialPivLu().solve(c.d_values_d_p.topRows<kStateSize>());
    j.middleRows(offset, n) = c.d_values_d_p.bottomRows(n) + c.d_values_d_z.bottomRows(n) * du_dp;
    offset += n;
  }
  return j;
}

Eigen::MatrixXcd MultipleScalesProblem::DisplacementPhasors(const Eigen::VectorXd& x, int step,
                                                            const std::vector<double>& positions_m) {
  const MultipleScalesModel model = Model(Parameters(x));
  const FitStep& s = data_.steps[step];
  Eigen::MatrixXcd phasors(positions_m.size(), 4);
  for (std::size_t c = 0; c < positions_m.size(); ++c) {
    const MultipleScalesModel::Harmonics h =
        model.Response(positions_m[c], ModalPhasor_m(x, step), s.omega_rad_s, s.force_N[1]);
    phasors.row(c) << h.h0_m, h.h1_m, h.h2_m, h.h3_m;
  }
  return phasors;
}

}  // namespace beamid::solver
