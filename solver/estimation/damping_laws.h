// Model-form uncertainty from the beam's damping law. The fit assumes the
// beam dissipates like a loss factor, EI(1 + iη); a real beam may follow
// Rayleigh damping C = α·M + β·K (air, joints) or any modal damping. Near
// one resonance the laws are alike, but they split the dissipation between
// the beam and the support's c differently at the harmonics, so a fit within
// the noise can still put c and k1 outside their statistical intervals when
// the law is wrong. The laws refitted here, from the fitted optimum:
//     loss_factor              η                       (the fit itself)
//     modal_loss_factor        η_m    mode j: η_m·k/k_j at harmonic k, k_j
//                                     its driving harmonic (hb/matched_modal_loss.h)
//     rayleigh                 α, β   ζ_j = α/(2ω_j) + β·ω_j/2
//     mass_proportional        α
//     stiffness_proportional   β
// (modal damping of the first two modes is Rayleigh damping: α, β follow from
// ζ₁, ζ₂ exactly). A law is accepted when it is not significantly worse
// than the best law, (χ²_law − χ²_best)/s² ≤ χ²₁(0.99) = 6.63 with
// s² = max(1, χ²_best/ν) — not merely when it fits within the noise: stated
// uncertainties are often conservative (χ²/ν ≪ 1), and a law 30 units of χ²
// worse than another is ruled out by the data even then.
// Every parameter the laws share gets a total 95 % interval, the model-form
// interval: the envelope of the accepted laws' 95 % intervals (each holds
// the statistical part and, under propagated weighting, the residual model
// error, model_error.h), widened on both sides by the harmonic truncation's
// shift |p(H') − p(H)|, p(H') the fitted law's optimum moved by one
// Gauss–Newton step of the fit with H' = H + 4 harmonics in the balance
// (its first-order refit). The shift stands for what the harmonics beyond
// H' would move too: response harmonics decay at least like 1/k² (a kink
// in the support's moment), so the ones from H + 1 to H + 4 hold about half
// of the tail or more. A parameter depends on the damping law (on the
// truncation) when an accepted law's value (the refit's value) lies outside
// the fitted law's 95 % interval.
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "solver/estimation/chi_square.h"
#include "solver/estimation/fit_data.h"
#include "solver/estimation/identify.h"
#include "solver/estimation/model_structure.h"

namespace beamid::solver {

struct DampingLawFit {
  std::string law;  // loss_factor, modal_loss_factor, rayleigh, mass_proportional, stiffness_proportional
  bool converged = false;
  // "solved", "stationary after Gauss–Newton steps …" (a balance whose
  // tolerance Ipopt could not meet), or why the refit failed
  std::string status;
  std::vector<ParameterEstimate> parameters;
  double chi_square = std::numeric_limits<double>::quiet_NaN();
  double reduced_chi_square = std::numeric_limits<double>::quiet_NaN();
  bool accepted = false;
};

// The fitted law refitted (to first order) with more harmonics in the balance.
struct TruncationRefit {
  int model_harmonics = 0;  // H of the fit
  int refit_harmonics = 0;  // H' of the refit
  bool converged = false;
  std::string status;  // "solved" or why the refit failed
  std::vector<ParameterEstimate> parameters;  // intervals moved with the values
};

struct ModelFormInterval {
  std::string name;
  std::string unit;
  double lower_95 = 0.0;  // the total interval
  double upper_95 = 0.0;
  double statistical_lower_95 = 0.0;  // the answer law's own interval
  double statistical_upper_95 = 0.0;
  double damping_law_lower_95 = 0.0;  // the envelope over the accepted laws
  double damping_law_upper_95 = 0.0;
  double truncation_shift = 0.0;  // p(H') − p(H); 0 without a converged truncation refit
  bool depends_on_damping_law = false;
  bool depends_on_truncation = false;

  // Total width over the statistical width: how much the model form adds.
  double WidthRatio() const;
};

struct DampingLawEnvelope {
  std::vector<DampingLawFit> laws;           // [0]: the fitted law (loss_factor); empty: not computed
  std::optional<TruncationRefit> truncation;  // absent: not refitted (older files)
  std::vector<ModelFormInterval> intervals;  // the parameters every law shares, in the fit's order

  bool empty() const { return laws.empty(); }  // not computed (result.json then lacks it)
};

// What the total intervals hold, for the headline that shows them: "the
// statistical part (…), the accepted damping laws (loss_factor, rayleigh),
// the harmonic truncation (5 → 9 harmonics)".
std::string TotalIntervalParts(const DampingLawEnvelope& envelope);

// The laws a damping-law envelope refits.
std::vector<std::string> DampingLawNames();

// Refits `fitted` (which must hold a "loss_factor" linear parameter; else the
// envelope is empty) under the other laws from `result`'s optimum, with
// `options`' family and model, one start each, then under its own law with
// H + 4 harmonics (one Gauss–Newton step), and judges them as above. A refit
// that stops short of Ipopt's tolerance is finished by Gauss–Newton steps
// (IdentifyOptions::polish_end_point); one that fails even so is listed
// with its status and never accepted (a failed truncation refit adds no
// shift, and the parts say so).
DampingLawEnvelope FitDampingLaws(const FitData& data, const ModelStructure& fitted, const IdentifyResult& result,
                                  const IdentifyOptions& options);
// The same from a fit's estimates (in `fitted.Names()`' order), its χ² and
// degrees of freedom: a diagnosis's selected model, which is no IdentifyResult.
DampingLawEnvelope FitDampingLaws(const FitData& data, const ModelStructure& fitted,
                                  const std::vector<ParameterEstimate>& parameters, double chi_square,
                                  int degrees_of_freedom, const IdentifyOptions& options);

// One law's fit from a parameter list (as the identify result's), NaN-free.
DampingLawFit DampingLawFitOf(const std::string& law, const std::vector<ParameterEstimate>& parameters,
                              double chi_square, int degrees_of_freedom);

// The law whose parameters are the answer: the fitted law (laws[0]) when
// the data accept it, else the accepted law of least χ²; nullptr when the
// laws were not refitted (or none converged).
const DampingLawFit* AnswerLaw(const DampingLawEnvelope& envelope);

// The acceptance and the intervals, from the laws' fits (laws[0] the fitted
// law) and the truncation refit; exposed for tests and for reading a result
// file back.
void JudgeDampingLaws(DampingLawEnvelope* envelope);

}  // namespace beamid::solver
