// The model's residual error: what a fit leaves in the phasors beyond
// their stated uncertainties (the record's noise, the force's and the
// frequency's errors: phasor_uncertainty.h), estimated per harmonic k as
// one standard deviation ε_k relative to the response, so that
//
//   Cov_total(Y_i) = C_i + (ε_k·a_i)²·I,   a_i = |Ŷ_1| of the phasor's channel at its step
//
// (Ŷ the fitted model's phasors) holds what the fit actually missed. The
// error of every harmonic is relative to the fundamental, not to the
// harmonic itself, as measured on the paper's campaign from the
// independent simulator: relative to the fundamental, the ε one noise
// realisation gives makes every channel, harmonic and level of another
// read χ²/ν 0.80–1.16; relative to the harmonic, which is some 700 times
// smaller at 1 N than at 9 N, the low level's excess went onto the high
// level's third harmonic (χ²/ν 0.75 there) and k3's intervals were 1.5
// times too wide. ε_k is the
// method-of-moments (Paule–Mandel) estimate: the root of
//
//   Q(ε) = Σ_i r_iᵀ·(C_i + ε²·a_i²·I)⁻¹·r_i = ν_k,
//
// r_i = (Re, Im) of Ŷ_i − Y_i over harmonic k's phasors, ν_k their share of
// the fit's degrees of freedom; ε_k = 0 when Q(0) ≤ ν_k (nothing beyond the
// stated σ). Q decreases in ε, so the root is unique. Its 95 % interval is
// the Q-profile one: ε where Q equals the 97.5 % and the 2.5 % points of
// χ²(ν_k) (Viechtbauer 2007, for the between-study variance of a
// meta-analysis, the same problem).
//
// Its cause is not known from the residuals alone: the harmonic balance's
// own truncation, a damping law that is right only at the fundamental, or
// physics the model lacks. The diagnosis asks which; identify states the
// term, and its part in the parameters' intervals, on its own.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "solver/estimation/fit_data.h"

namespace beamid::solver {

// One phasor's residual r, its stated covariance C and the magnitude a
// the relative error scales.
struct ModelErrorPhasor {
  Eigen::Vector2d residual;
  Eigen::Matrix2d covariance;
  double scale = 0.0;
};

struct ModelErrorEstimate {
  double relative = 0.0;      // ε_k
  double lower_95 = 0.0;      // Q-profile interval of ε_k
  double upper_95 = 0.0;
  double chi_square = 0.0;    // Q(0): with the stated σ alone
  double degrees_of_freedom = 0.0;  // ν_k
};

// ε for one group of phasors (one harmonic). Throws std::invalid_argument
// for a non-positive degrees of freedom or a covariance that is not
// positive definite.
ModelErrorEstimate EstimateModelError(const std::vector<ModelErrorPhasor>& phasors, double degrees_of_freedom);

// ε_k for harmonics k = 1..K of a fit: `model` its phasors
// (model_phasors.h), C_i from each phasor's whitening, ν_k = n_k·ν/n (the
// fit's degrees of freedom shared in proportion to the residuals). A
// fit whose fundamental is 0 everywhere gets ε = 0.
std::vector<ModelErrorEstimate> EstimateModelErrors(const FitData& data, const std::vector<Eigen::MatrixXcd>& model,
                                                    int degrees_of_freedom);

// What the residual model error adds to the information a phasor-by-phasor
// whitening counts, for the parameters' covariance Cov = A⁻¹·(A + this)·A⁻¹:
//   Σ_i J_iᵀ·(ε_k·a_i)²·L_i⁻¹·L_i⁻ᵀ·J_i,
// J_i the whitened Jacobian's two rows of phasor i (FitData::NumResiduals'
// order), L_i⁻¹ its whitening. The error is taken as independent from
// phasor to phasor.
Eigen::MatrixXd ModelErrorInformation(const FitData& data, const std::vector<Eigen::MatrixXcd>& model,
                                      const std::vector<ModelErrorEstimate>& errors,
                                      const Eigen::MatrixXd& whitened_jacobian);

}  // namespace beamid::solver
