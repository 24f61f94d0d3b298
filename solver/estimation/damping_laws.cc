#include "solver/estimation/damping_laws.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>


namespace beamid::solver {
namespace {

constexpr const char* kLossFactor = "loss_factor";

// A law's parameters, started where mode 1 (near the steps' mean ω)
// dissipates as with the fitted η: ζ = η/2 = α/(2ω) = β·ω/2.
std::vector<LinearParameter> LawParameters(const std::string& law, double eta, double omega_rad_s) {
  const double alpha = eta * omega_rad_s, beta = eta / omega_rad_s;
  if (law == "rayleigh") return {RayleighMassDamping(0.5 * alpha), RayleighStiffnessDamping(0.5 * beta)};
  if (law == "mass_proportional") return {RayleighMassDamping(alpha)};
  if (law == "stiffness_proportional") return {RayleighStiffnessDamping(beta)};
  throw std::logic_error("unknown damping law " + law);
}

double MeanOmega_rad_s(const FitData& data) {
  double sum = 0.0;
  for (const auto& s : data.steps) sum += s.omega_rad_s;
  return data.steps.empty() ? 1.0 : sum / static_cast<double>(data.steps.size());
}

}  // namespace

std::vector<std::string> DampingLawNames() {
  return {kLossFactor, "rayleigh", "mass_proportional", "stiffness_proportional"};
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
  const DampingLawFit& fitted = laws.front();
  for (const ParameterEstimate& p : fitted.parameters) {
    if (p.name == kLossFactor) continue;
    ModelFormInterval interval{.name = p.name, .unit = p.unit, .lower_95 = p.lower_95, .upper_95 = p.upper_95};
    bool first = true;
    for (const auto& law : laws) {
      if (!law.accepted) continue;
      const auto it = std::find_if(law.parameters.begin(), law.parameters.end(),
                                   [&](const ParameterEstimate& q) { return q.name == p.name; });
      if (it == law.parameters.end()) continue;
      interval.lower_95 = first ? it->lower_95 : std::min(interval.lower_95, it->lower_95);
      interval.upper_95 = first ? it->upper_95 : std::max(interval.upper_95, it->upper_95);
      first = false;
      if (&law != &fitted && (it->value < p.lower_95 || it->value > p.upper_95)) interval.depends_on_damping_law = true;
    }
    envelope->intervals.push_back(interval);
  }
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
  refit.continuation_iterations = 0;  // a law that does not converge from the optimum is listed as failed
  for (const std::string& law : DampingLawNames()) {
    if (law == kLossFactor) continue;
    ModelStructure structure = fitted;
    structure.linear.erase(structure.linear.begin() + static_cast<std::ptrdiff_t>(loss_index - structure.law_bounds.size()));
    std::vector<double> start;
    for (std::size_t j = 0; j < parameters.size(); ++j)
      if (j != loss_index) start.push_back(parameters[j].value);
    for (LinearParameter& p : LawParameters(law, eta, MeanOmega_rad_s(data))) {
      start.push_back(p.initial);
      structure.linear.push_back(std::move(p));
    }
    DampingLawFit fit{.law = law};
    try {
      const IdentifyResult r = IdentifyWith(
          [&] { return refit.family->MakeProblem(data, structure, refit.model); }, structure, start, refit);
      fit = DampingLawFitOf(law, r.parameters, r.chi_square, r.degrees_of_freedom);
    } catch (const std::exception& e) {
      fit.status = std::string("failed: ") + e.what();
    }
    envelope.laws.push_back(std::move(fit));
  }
  JudgeDampingLaws(&envelope);
  return envelope;
}

}  // namespace beamid::solver
