// Identification of the support (and optional linear parameters) from a
// whole stepped-sine campaign: a direct linear least-squares estimate from
// the reconstructed support, then Ipopt on the constrained program of the
// chosen model family (solver/estimation/model_family.h) from that estimate and from a
// space-filling set of further starts (in parallel), then the Gauss–Newton
// covariance in the reduced parameter space:
//     Cov(p) = s²·A⁻¹·B·A⁻¹,  A = JᵀJ,  J = dr/dp along the constraint manifold,
//     B = A + what errors shared by a step's phasors add (shared_step_errors.h;
//         B = A when the phasors' errors are independent, as under the relative floor),
//     s² = max(1, χ²/(n − P))  (the scatter is trusted only when it is worse
//                               than the stated phasor uncertainties);
// with calibrated phasor σ (PhasorUncertainty::kPropagated) s² = 1 and B
// holds the residual model error instead, estimated per harmonic from
// what the fit leaves beyond those σ (model_error.h).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "solver/estimation/fit_data.h"
#include "solver/estimation/fit_problem.h"
#include "solver/estimation/fit_verdict.h"
#include "solver/estimation/ipopt_options.h"
#include "solver/estimation/model_family.h"
#include "solver/estimation/model_options.h"
#include "solver/estimation/model_structure.h"
#include "solver/estimation/multistart.h"
#include "solver/estimation/support_reconstruction.h"

namespace beamid::solver {

struct IdentifyOptions {
  // The model to fit: its family (exact harmonic balance by default) and
  // what the family is told about it.
  const ModelFamily* family = &HarmonicBalanceFamily();
  ModelOptions model;
  IpoptOptions ipopt;
  // The first start (the direct estimate, or the caller's own start: the
  // one a single-start fit rests on, which from a factor 3 away may need ~400
  // iterations) and the branch repairs run for at least this many
  // iterations; the further starts are exploratory and keep
  // ipopt.max_iterations (a start on another branch of the response stalls
  // rather than converges), as do the diagnosis's refits, cut short on
  // purpose (0 here). An iteration count, not a time limit, so that
  // the answer does not depend on the machine or its load.
  int first_start_min_iterations = 1000;
  // Further starts besides the direct estimate (0: only that one).
  int num_starts = 0;
  // Space-filling starts cover [value/spread, value·spread] around the direct
  // estimate for positive parameters and ±spread·|value| for signed ones.
  double start_spread = 3.0;
  // Worker processes that run the starts in parallel; 0: one per hardware
  // core.
  int num_workers = 0;
  unsigned seed = 1;
  // Start from the structure's own values instead of the direct estimate
  // (the direct estimate needs a polynomial law).
  bool use_direct_estimate = true;
  double decisive_chi_square_gap = kDecisiveChiSquareGap;  // solver/multistart.h
  // Seed every start's states at the rotation the data show (else only at
  // the harmonic-balance solution of the start's parameters). Off for refits
  // from a neighbouring fit, and to compare with the old search.
  bool seed_states_from_measurements = true;
  // Re-seed the best end point's states on the measured branch and re-run
  // the fit if that lowers the misfit (a step converged on the other branch
  // of a fold).
  bool branch_repair = true;
  // When no start converged, the best end point goes on for this many more
  // iterations (a model that misses the data slows Ipopt near the optimum);
  // 0: fail at once (the diagnosis's refits, which a cap cuts on purpose).
  int continuation_iterations = 3000;
  // When no start converged even so (a polynomial law only): continuation in
  // the parameters from the linear fit — k2 = k3 = 0 first, then their range
  // opened in steps of ×kLinearContinuationWidening, each fit from the one
  // before (solver/estimation/identify.cc). Off for refits that are cut
  // short on purpose, as continuation_iterations.
  bool linear_continuation = true;
  // When no start converged: Gauss–Newton steps in the parameters from the
  // best end point, each with the balance solved, until χ² could fall by at
  // most 0.1·max(1, χ²/ν) (the point is then within a third of a σ of the
  // linearised optimum; solver/estimation/gauss_newton_polish.h). For refits from a neighbouring
  // optimum whose balance is non-smooth, where Ipopt circles the optimum
  // without meeting its tolerance (the damping-law refits).
  bool polish_end_point = false;

  // Throws InputError naming the field, its value and the allowed range
  // (model and ipopt included).
  void Validate() const;
};

struct ParameterEstimate {
  std::string name;
  std::string unit;
  double value = 0.0;
  double std = 0.0;
  double lower_95 = 0.0;
  double upper_95 = 0.0;
  // The part of std the residual model error adds (model_error.h):
  // std² = statistical² + std_model_error²; 0 when it is not estimated.
  double std_model_error = 0.0;
};

struct IdentifyResult {
  std::vector<ParameterEstimate> parameters;
  Eigen::MatrixXd covariance;
  Eigen::MatrixXd correlation;
  double chi_square = 0.0;
  int degrees_of_freedom = 0;
  double reduced_chi_square = 0.0;
  // The residual model error ε_k of harmonics 1..K, estimated when the
  // phasors' σ are calibrated (PhasorUncertainty::kPropagated; empty
  // otherwise) and propagated into the covariance on its own.
  std::vector<ModelErrorEstimate> model_errors;
  DirectEstimate direct;
  std::vector<StartOutcome> starts;   // [0]: from the direct estimate
  int best_start = 0;
  int starts_at_best = 0;             // starts that reached the best fit
  // Every distinct minimum the converged starts reached, best first, and
  // whether the data decide between the best two.
  MinimaSummary minima;
  std::vector<std::string> warnings;
  FitVerdict verdict;                 // within the noise, or "run beamid diagnose"
  Eigen::VectorXd x;                  // optimiser variables at the best fit
  double seconds = 0.0;
};

using ProgressCallback = std::function<void(double fraction, const std::string& what)>;
// Makes a fresh problem (each parallel start owns one).
using ProblemFactory = std::function<std::unique_ptr<FitProblem>()>;

// The model of options.family, started from the direct estimate of the
// polynomial law. Throws InputError (or std::invalid_argument) for data the
// family cannot hold, before any start.
IdentifyResult Identify(const FitData& data, const ModelStructure& structure, const IdentifyOptions& options,
                        const ProgressCallback& progress = {});

// Any model: starts at `first` (physical parameters, structure order) and
// around it; the structure gives names, units and bounds.
IdentifyResult IdentifyWith(const ProblemFactory& make_problem, const ModelStructure& structure,
                            const std::vector<double>& first, const IdentifyOptions& options,
                            const ProgressCallback& progress = {});

}  // namespace beamid::solver
