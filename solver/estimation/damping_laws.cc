#include "solver/estimation/damping_laws.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include <Eigen/QR>

#include "solver/estimation/fit_problem.h"

namespace beamid::solver {
namespace {

constexpr const char* kLossFactor = "loss_factor";
constexpr int kTruncationHarmonics = 4;  // H' = H + 4
constexpr int kLawRefitIterations = 25;

// A law's parameters, started where mode 1 (near the steps' mean ω)
// dissipates as with the fitted η: η_m = η, ζ = η/2 = α/(2ω) = β·ω/2.
std::vector<LinearParameter> LawParameters(const std::string& law, double eta, double omega_rad_s) {
  const double alpha = eta * omega_rad_s, beta = eta / omega_rad_s;
  if (law == "modal_loss_factor") return {ModalLossFactor(eta)};
  if (law == "rayleigh") return {RayleighMassDamping(0.5 * alpha), RayleighStiffnessDamping(0.5 * beta)};
  if (law == "mass_proportional") return {RayleighMassDamping(alpha)};
  if (law == "stiffness_proportional") return {RayleighStiffnessDamping(beta)};
  throw std::logic_error("unknown damping law " + law);
}

std::vector<double> ValuesOf(const std::vector<ParameterEstimate>& parameters) {
  std::vector<double> values;
  for (const auto& p : parameters) values.push_back(p.value);
  return values;
}

const ParameterEstimate* Find(const std::vector<ParameterEstimate>& parameters, const std::string& name) {
  const auto it = std::find_if(parameters.begin(), parameters.end(),
                               [&](const ParameterEstimate& q) { return q.name == name; });
  return it == parameters.end() ? nullptr : &*it;
}

// The optimum at H moved by one Gauss–Newton step of the fit balanced with
// H' harmonics: Δp = −J⁺·r, r and J the whitened residuals and their reduced
// Jacobian at (p̂, the balance at H'). At p̂, Jᵀr at H is zero, so the step
// answers the harmonics H + 1..H' alone, to first order. A full refit from
// p̂ is no better and far dearer: a friction model's ran 611 iterations
// (93 s) from its new harmonics at 0.
TruncationRefit TruncationStep(const FitData& data, const ModelStructure& fitted,
                               const std::vector<ParameterEstimate>& parameters, const IdentifyOptions& options) {
  TruncationRefit t{.model_harmonics = options.model.num_harmonics,
                    .refit_harmonics = options.model.num_harmonics + kTruncationHarmonics,
                    .parameters = parameters};
  try {
    ModelOptions more = options.model;
    more.num_harmonics = t.refit_harmonics;
    const std::unique_ptr<FitProblem> problem = options.family->MakeProblem(data, fitted, more);
    int failed_steps = 0;
    const Eigen::VectorXd x = problem->FeasiblePoint(ValuesOf(parameters), &failed_steps);
    if (failed_steps > 0) {
      t.status = "failed: the balance with " + std::to_string(t.refit_harmonics) + " harmonics did not converge at " +
                 std::to_string(failed_steps) + " step(s)";
      return t;
    }
    const Eigen::VectorXd step =
        problem->ReducedResidualJacobian(x).completeOrthogonalDecomposition().solve(-problem->WeightedResiduals(x));
    for (std::size_t j = 0; j < t.parameters.size(); ++j) {
      ParameterEstimate& p = t.parameters[j];
      const double shift = step[static_cast<Eigen::Index>(j)];
      p.value += shift;
      p.lower_95 += shift;
      p.upper_95 += shift;
    }
    t.converged = step.allFinite();
    t.status = t.converged ? "solved" : "failed: the step is not finite";
  } catch (const std::exception& e) {
    t.status = std::string("failed: ") + e.what();
  }
  return t;
}

}  // namespace

std::vector<std::string> DampingLawNames() {
  return {kLossFactor, "modal_loss_factor", "rayleigh", "mass_proportional", "stiffness_proportional"};
}

DampingLawFit DampingLawFitOf(const std::string& law, const std::vector<ParameterEstimate>& parameters,
                              double chi_square, int degrees_of_freedom) {
  return {.law = law,
          .converged = true,
          .status = "solved",
          .parameters = parameters,
          .chi_square = chi_square,
          .reduced_chi_square = chi_square / std::max(1, degrees_of_freedom)};
}

const DampingLawFit* AnswerLaw(const DampingLawEnvelope& envelope) {
  if (envelope.laws.empty()) return nullptr;
  if (envelope.laws.front().accepted) return &envelope.laws.front();
  const DampingLawFit* answer = nullptr;
  for (const auto& law : envelope.laws)
    if (law.accepted && (answer == nullptr || law.chi_square < answer->chi_square)) answer = &law;
  return answer;
}

void JudgeDampingLaws(DampingLawEnvelope* envelope) {
  auto& laws = envelope->laws;
  envelope->intervals.clear();
  if (laws.empty()) return;
  const DampingLawFit* best = nullptr;
  for (const auto& law : laws)
    if (law.converged && (best == nullptr || law.chi_square < best->chi_square)) best = &law;
  if (best == nullptr) return;
  const double scale = std::max(1.0, best->reduced_chi_square);  // s² = max(1, χ²_best/ν)
  for (auto& law : laws)
    law.accepted = law.converged && (law.chi_square - best->chi_square) / scale <= kDecisiveChiSquare;
  const DampingLawFit* answer = AnswerLaw(*envelope);
  const bool truncation_refitted = envelope->truncation && envelope->truncation->converged;
  for (const ParameterEstimate& p : laws.front().parameters) {
    if (p.name == kLossFactor) continue;
    const ParameterEstimate* own = Find(answer->parameters, p.name);
    if (own == nullptr) continue;
    ModelFormInterval interval{.name = p.name,
                               .unit = p.unit,
                               .statistical_lower_95 = own->lower_95,
                               .statistical_upper_95 = own->upper_95,
                               .damping_law_lower_95 = own->lower_95,
                               .damping_law_upper_95 = own->upper_95};
    for (const auto& law : laws) {
      const ParameterEstimate* q = law.accepted ? Find(law.parameters, p.name) : nullptr;
      if (q == nullptr) continue;
      interval.damping_law_lower_95 = std::min(interval.damping_law_lower_95, q->lower_95);
      interval.damping_law_upper_95 = std::max(interval.damping_law_upper_95, q->upper_95);
      if (q->value < p.lower_95 || q->value > p.upper_95) interval.depends_on_damping_law = true;
    }
    if (const ParameterEstimate* q = truncation_refitted ? Find(envelope->truncation->parameters, p.name) : nullptr) {
      interval.truncation_shift = q->value - p.value;
      interval.depends_on_truncation = q->value < p.lower_95 || q->value > p.upper_95;
    }
    const double shift = std::abs(interval.truncation_shift);
    interval.lower_95 = interval.damping_law_lower_95 - shift;
    interval.upper_95 = interval.damping_law_upper_95 + shift;
    envelope->intervals.push_back(interval);
  }
}

double ModelFormInterval::WidthRatio() const {
  const double statistical = statistical_upper_95 - statistical_lower_95;
  return statistical > 0.0 ? (upper_95 - lower_95) / statistical : std::numeric_limits<double>::infinity();
}

std::string TotalIntervalParts(const DampingLawEnvelope& envelope) {
  std::string laws;
  for (const auto& law : envelope.laws)
    if (law.accepted) laws += (laws.empty() ? "" : ", ") + law.law;
  std::string parts = "the statistical part (with the residual model error where the weighting estimates it), the "
                      "accepted damping laws (" + laws + ")";
  const auto& t = envelope.truncation;
  if (!t) return parts + "; the harmonic truncation was not refitted";
  if (!t->converged)
    return parts + "; NOT the harmonic truncation: its refit with " + std::to_string(t->refit_harmonics) +
           " harmonics " + t->status;
  return parts + ", the harmonic truncation (" + std::to_string(t->model_harmonics) + " → " +
         std::to_string(t->refit_harmonics) + " harmonics)";
}

DampingLawEnvelope FitDampingLaws(const FitData& data, const ModelStructure& fitted, const IdentifyResult& result,
                                  const IdentifyOptions& options) {
  return FitDampingLaws(data, fitted, result.parameters, result.chi_square, result.degrees_of_freedom, options);
}

DampingLawEnvelope FitDampingLaws(const FitData& data, const ModelStructure& fitted,
                                  const std::vector<ParameterEstimate>& parameters, double chi_square,
                                  int degrees_of_freedom, const IdentifyOptions& options) {
  DampingLawEnvelope envelope;
  const auto names = fitted.Names();
  const auto loss = std::find(names.begin(), names.end(), kLossFactor);
  if (loss == names.end() || parameters.size() != names.size()) return envelope;
  const std::size_t loss_index = static_cast<std::size_t>(loss - names.begin());
  envelope.laws.push_back(DampingLawFitOf(kLossFactor, parameters, chi_square, degrees_of_freedom));

  // ζ from η alone would start every law at no damping when the fit put all
  // of it in c; a small floor lets the refit move.
  const double eta = std::max(parameters[loss_index].value, 1e-5);
  IdentifyOptions refit = options;
  refit.num_starts = 0;
  refit.num_workers = 1;
  refit.continuation_iterations = 0;  // a law that does not converge from the optimum is listed as failed,
  refit.polish_end_point = true;      // unless its end point is stationary (a kinked law's balance)
  // From the fitted optimum a law converges in a few iterations or circles
  // its optimum without meeting the tolerance (a kinked law's balance with
  // 21 harmonics: 80 iterations, 12–16 s each, where the polish takes < 1 s).
  refit.ipopt.max_iterations = std::min(refit.ipopt.max_iterations, kLawRefitIterations);
  for (const std::string& law : DampingLawNames()) {
    if (law == kLossFactor) continue;
    ModelStructure structure = fitted;
    structure.linear.erase(structure.linear.begin() + static_cast<std::ptrdiff_t>(loss_index - structure.law_bounds.size()));
    std::vector<double> start = ValuesOf(parameters);
    start.erase(start.begin() + static_cast<std::ptrdiff_t>(loss_index));
    for (LinearParameter& p : LawParameters(law, eta, data.MeanOmega_rad_s())) {
      start.push_back(p.initial);
      structure.linear.push_back(std::move(p));
    }
    DampingLawFit fit{.law = law};
    try {
      const IdentifyResult r = IdentifyWith(
          [&] { return refit.family->MakeProblem(data, structure, refit.model); }, structure, start, refit);
      fit = DampingLawFitOf(law, r.parameters, r.chi_square, r.degrees_of_freedom);
      fit.status = r.starts[static_cast<std::size_t>(r.best_start)].status;  // "solved", or how it stopped
    } catch (const std::exception& e) {
      fit.status = std::string("failed: ") + e.what();
    }
    envelope.laws.push_back(std::move(fit));
  }
  envelope.truncation = TruncationStep(data, fitted, parameters, options);
  JudgeDampingLaws(&envelope);
  return envelope;
}

}  // namespace beamid::solver
