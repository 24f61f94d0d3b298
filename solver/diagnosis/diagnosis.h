// Diagnosis of a model-vs-recording mismatch (issue 7): fit the base model
// (polynomial support, nominal beam, its loss factor), locate where its
// residuals exceed the noise (solver/misfit_location.h), refit every
// candidate of solver/candidate_physics.h from the base optimum (Ipopt, all
// candidates and starts in parallel worker processes), and name a cause only
// when its refit is significantly better:
//   likelihood ratio  Λ = (χ²_base − χ²_cand)/s²,  s² = max(1, χ²_cand/dof),
//   p = P(χ²(q) ≥ Λ) below significance/(number of candidates) (Bonferroni),
//   and the refit removes at least min_relative_improvement of χ²_base
//   (a significant but negligible gain is not a cause); a candidate balanced
//   with more harmonics than the base is tested against the refit with those
//   harmonics and no parameters of its own (harmonic_truncation) instead of
//   χ²_base, when that fits better; and the base misfit
//   exceeds acceptable_reduced_chi_square (a base within the model's own
//   errors has nothing to explain);
// ranked by BIC = χ² + P·ln(n) (AIC = χ² + 2P also reported) and checked on
// the held-out channels. Without a significant candidate the verdict is "no
// significant discrepancy" when the base fits within the noise, else
// "unexplained" with the location's findings.
#pragma once

#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "solver/diagnosis/candidate_physics.h"
#include "solver/estimation/fit_data.h"
#include "solver/estimation/identify.h"
#include "solver/diagnosis/misfit_location.h"

namespace beamid::solver {

struct DiagnosisOptions {
  int model_harmonics = 5;          // H of the base model
  bool fit_loss_factor = true;      // the beam's η beside the support (as `beamid identify`)
  double loss_factor_start = 1e-4;
  std::vector<std::string> candidates;  // names to try (empty: the whole library)
  // Family-wise significance of naming a cause (Bonferroni over the candidates).
  double significance = 0.01;
  // Share of the base χ² a cause must remove.
  double min_relative_improvement = 0.2;
  // The base fits "within the noise" up to this reduced χ²: the model's own
  // errors (time integrator, extraction) keep it above 1 on correct physics;
  // `beamid identify` warns above the same value.
  double acceptable_reduced_chi_square = 4.0;
  int num_workers = 0;              // 0: one per hardware core
  internal::IpoptOptions ipopt;     // the base fit's
  // Each candidate refit starts at the base optimum and needs < 40
  // iterations when the candidate fits; a start that wanders is cut short.
  int refit_max_iterations = 80;
  double refit_max_cpu_seconds = 10.0;
};

// One fitted model's quality.
struct FitSummary {
  std::vector<ParameterEstimate> parameters;
  int model_harmonics = 5;
  double chi_square = 0.0;
  int degrees_of_freedom = 0;
  int num_residuals = 0;
  double reduced_chi_square = 0.0;
  double aic = 0.0;  // χ² + 2P
  double bic = 0.0;  // χ² + P·ln(n)
  // Held-out channels (NaN without): χ² of harmonics 1..K, and the relative
  // RMS error of the first harmonic over all steps, sqrt(Σ|ΔY₁|²/Σ|Y₁|²).
  double held_out_chi_square = std::numeric_limits<double>::quiet_NaN();
  double held_out_h1_relative_error = std::numeric_limits<double>::quiet_NaN();
};

struct CandidateOutcome {
  std::string name;
  std::string description;
  double signature_score = 0.0;     // match with the located misfit, 0..1
  std::vector<std::string> extra_parameters;
  bool converged = false;
  std::string status;
  FitSummary fit;
  double likelihood_ratio = 0.0;    // Λ
  int test_dof = 0;                 // q
  double p_value = 1.0;
  double residual_drop = 1.0;       // χ²_base / χ²_candidate
  bool significant = false;
  double seconds = 0.0;             // Ipopt time of its refits (all starts)
};

// Measured and modelled first harmonics of one channel at one step (the
// per-level response curves).
struct ResponsePoint {
  std::string level;
  double frequency_hz = 0.0;
  std::string channel;
  bool held_out = false;
  std::complex<double> measured;
  std::complex<double> base_model;
  std::complex<double> final_model;
};

struct DiagnosisResult {
  FitSummary base;
  std::optional<MisfitLocation> location;  // empty if locating failed
  std::string location_error;
  std::vector<CandidateOutcome> candidates;  // ranked: significant first, by BIC
  std::vector<std::string> selected;         // {"none"} when no cause is named
  std::string verdict;  // "cause named" | "no significant discrepancy" | "unexplained"
  FitSummary final_fit;                      // the selected model (the base when none)
  std::vector<std::string> final_extra_parameters;
  std::vector<ResponsePoint> response;
  std::string summary;
  double seconds = 0.0;
};

using DiagnosisProgress = std::function<void(double fraction, const std::string& what)>;

// fit: the fitted channels (harmonics 1..K). validation: held-out channels
// (may have none). located: the channels to examine with harmonics 1..5
// (beyond K); empty channels: fit's. Throws std::runtime_error when the base
// fit fails.
DiagnosisResult Diagnose(const FitData& fit, const FitData& validation, const FitData& located,
                         const DiagnosisOptions& options = {}, const DiagnosisProgress& progress = {});

nlohmann::json ToJson(const DiagnosisResult& result);
// CSV of the response curves: level, frequency, channel, held_out, then
// amplitude and phase of measured, base and final first harmonics.
std::string ResponseCsv(const DiagnosisResult& result);

}  // namespace beamid::solver
