// Diagnosis of a model-vs-recording mismatch: fit the base model
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
//   harmonics or fewer and no parameters of its own (harmonic_truncation)
//   instead of χ²_base, when that fits better;
// ranked by BIC = χ² + P·ln(n) (AIC = χ² + 2P also reported) and VALIDATED
// on the held-out channels: a significant candidate that predicts them
// decisively better than the in-sample winner is named instead (a refit can
// bend itself to the fitted channels; only a real cause predicts the others),
//   decisive: Δχ²/s² > kDecisiveChiSquare (6.63, χ²₁ at 99 %), s² the
//   better model's reduced χ² (at least 1), in sample and held out alike;
// when neither in sample nor held out separates the two best, the verdict is
// "causes indistinguishable" and names both. After the cause, the summary
// says whether the rest of the misfit lies within the noise. Without a
// significant candidate the verdict is "unexplained", with the location's
// findings, when the location's test finds a misfit (and, under the relative
// floor, the base's reduced χ² exceeds the acceptable one), else "no
// significant discrepancy".
//
// Diagnose runs it as named stages, each a function returning a struct and
// usable on its own (a robust base fit or a measurement-artefact check can
// slot in between): FitBase → ValidateOnHeldOut → Locate → RefitCandidates
// (refits and likelihood-ratio tests) → ValidateOnHeldOut of each refit →
// DecideVerdict.
#pragma once

#include <complex>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "hb/json_schema.h"

#include "solver/diagnosis/candidate_physics.h"
#include "solver/diagnosis/fitted_model.h"
#include "solver/diagnosis/measurement_suggestion.h"
#include "solver/estimation/chi_square.h"
#include "solver/estimation/damping_laws.h"
#include "solver/estimation/fit_data.h"
#include "solver/estimation/fit_problem.h"
#include "solver/estimation/model_family.h"
#include "solver/estimation/sensor_backbone.h"
#include "solver/estimation/identify.h"
#include "solver/diagnosis/misfit_location.h"

namespace beamid::solver {

struct DiagnosisOptions {
  // The family of the base model and of every candidate's refit.
  const ModelFamily* family = &HarmonicBalanceFamily();
  int model_harmonics = 5;          // H of the base model
  bool fit_loss_factor = true;      // the beam's η beside the support (as `beamid identify`)
  double loss_factor_start = 1e-4;
  // The beam's η fitted as the modal loss factor η_m (hb/matched_modal_loss.h,
  // the time-domain simulator's law) instead of E(1 + iη): for campaigns
  // whose damping law is known, where the named model must hold it exactly.
  bool modal_loss_factor = false;
  std::vector<std::string> candidates;  // names to try (empty: the whole library)
  // Family-wise significance of naming a cause (Bonferroni over the candidates).
  double significance = 0.01;
  // Share of the base χ² a cause must remove.
  double min_relative_improvement = 0.2;
  // A fit lies "within the noise" up to this reduced χ²: the rest after a
  // named cause; "unexplained" needs a base beyond it under the relative
  // floor (under propagated σ the location's test decides); a fault of the
  // recording (but a freed step, which physics peaking at one step also
  // explains) or a linear candidate that brings a base beyond it within it
  // spares the costlier refits, as does a base within it where no linear
  // candidate is significant. The model's own errors keep it above 1 on
  // correct physics; `beamid identify` warns above the same value. It gates
  // no test of a cause.
  double acceptable_reduced_chi_square = 4.0;
  int num_workers = 0;              // 0: one per hardware core
  IpoptOptions ipopt;     // the base fit's
  // Each candidate refit starts at the base optimum and needs < 40
  // iterations when the candidate fits; a start that wanders is cut short
  // (by iterations, not time: the verdict must not depend on the machine).
  int refit_max_iterations = 80;
  // When the named cause leaves a misfit beyond acceptable_reduced_chi_square,
  // it is refitted together with each of this many other candidates (those
  // whose own refit converged, best BIC first, then those whose refit from the
  // base failed, by signature score); a pair is named when it is
  // significant against the cause alone and predicts the held-out channels
  // at least as well. 0: no pairs.
  int max_pair_partners = 2;
  // Check the recording first: the measurement artefacts of
  // solver/diagnosis/measurement_artefacts.h beside the physics candidates.
  bool measurement_artefacts = true;
  // Refit a selected model of the physics under the other beam damping laws,
  // so that its parameters carry model-form intervals as identify's do
  // (solver/estimation/damping_laws.h): three more refits of one model.
  bool damping_laws = true;
  // Points of the selected model's backbone (DiagnosisResult::final_backbone).
  int backbone_points = 40;

  // Throws beamid::InputError naming the first field out of its range, its
  // value and the range, so that a bad option fails before minutes of fits.
  void Validate() const;
};

// The beam's damping parameter a diagnosis fits beside the support
// (DiagnosisOptions::fit_loss_factor): η or η_m, from loss_factor_start.
LinearParameter BeamLossFactor(const DiagnosisOptions& options);

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
  int held_out_num_residuals = 0;  // of held_out_chi_square (0: unknown)
};

// What became of a candidate's refit; CandidateOutcome::status_message says why.
enum class RefitStatus { kRefitted, kFailed, kNotRefitted };
inline constexpr schema::Name<RefitStatus> kRefitStatusNames[] = {
    {RefitStatus::kRefitted, "refitted"}, {RefitStatus::kFailed, "failed"}, {RefitStatus::kNotRefitted, "not_refitted"}};

struct CandidateOutcome {
  std::string name;
  std::string description;
  std::string rig_check;            // what to check on the rig when it is named
  double signature_score = 0.0;     // match with the located misfit, 0..1
  std::vector<std::string> extra_parameters;
  RefitStatus status = RefitStatus::kFailed;
  std::string status_message;       // why it failed or was not refitted; "" when refitted
  bool Refitted() const { return status == RefitStatus::kRefitted; }
  FitSummary fit;
  double likelihood_ratio = 0.0;    // Λ
  int test_dof = 0;                 // q
  double p_value = 1.0;
  double residual_drop = 1.0;       // χ²_base / χ²_candidate
  bool significant = false;
  double seconds = 0.0;             // Ipopt time of its refits (all starts)
  // A fault of the recording (solver/diagnosis/measurement_artefacts.h), not physics.
  bool measurement = false;
};

// What a diagnosis concludes, by the names diagnosis.json and its summary
// give them.
enum class DiagnosisVerdict {
  kCauseNamed,
  kCombinationNamed,
  kCausesIndistinguishable,
  kNoSignificantDiscrepancy,
  kUnexplained,
};
inline constexpr schema::Name<DiagnosisVerdict> kDiagnosisVerdictNames[] = {
    {DiagnosisVerdict::kCauseNamed, "cause named"},
    {DiagnosisVerdict::kCombinationNamed, "combination named"},
    {DiagnosisVerdict::kCausesIndistinguishable, "causes indistinguishable"},
    {DiagnosisVerdict::kNoSignificantDiscrepancy, "no significant discrepancy"},
    {DiagnosisVerdict::kUnexplained, "unexplained"},
};

// Who is to blame for the named cause: a measurement artefact or missing
// physics; "" when none is named.
enum class Blame { kNone, kRecording, kModel };
inline constexpr schema::Name<Blame> kBlameNames[] = {
    {Blame::kNone, ""}, {Blame::kRecording, "the recording"}, {Blame::kModel, "the model"}};

// How the named cause was chosen: the held-out channels (they decided, or
// confirmed the in-sample ranking), the levels left out in turn (no held-out
// channel: ValidateOnLeftOutLevels) or the in-sample BIC (neither); "" when
// none is named.
enum class RankedBy { kNone, kHeldOutChannels, kLevelsLeftOut, kInSampleBic };
inline constexpr schema::Name<RankedBy> kRankedByNames[] = {{RankedBy::kNone, ""},
                                                            {RankedBy::kHeldOutChannels, "held-out channels"},
                                                            {RankedBy::kLevelsLeftOut, "levels left out in turn"},
                                                            {RankedBy::kInSampleBic, "in-sample BIC"}};

inline std::string ToString(DiagnosisVerdict v) { return std::string(schema::NameOf(v, kDiagnosisVerdictNames)); }
inline std::string ToString(Blame b) { return std::string(schema::NameOf(b, kBlameNames)); }
inline std::string ToString(RankedBy r) { return std::string(schema::NameOf(r, kRankedByNames)); }
// For the tests' messages.
inline std::ostream& operator<<(std::ostream& out, DiagnosisVerdict v) { return out << ToString(v); }
inline std::ostream& operator<<(std::ostream& out, Blame b) { return out << ToString(b); }
inline std::ostream& operator<<(std::ostream& out, RankedBy r) { return out << ToString(r); }

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
  // Per harmonic k = 1..K of the channel's data, the whitened misfit
  // |L⁻¹(Y_model − Y_measured)| of the base and the final model (solver/
  // estimation/fit_data.h): their squares over the fitted channels sum to
  // each fit's χ². Empty in files written before they were kept.
  std::vector<double> base_misfit_sigma, final_misfit_sigma;
};

// The selected model's backbone as the reference sensor (the first fitted
// channel) sees it (solver/estimation/sensor_backbone.h), to draw beside the
// base model's; empty when no physics is named or it could not be traced.
struct SelectedBackbone {
  std::string channel;
  double position_m = 0.0;
  std::vector<SensorBackbonePoint> points;
  std::string error;  // why points is empty, when tracing failed
  bool empty() const { return points.empty() && error.empty(); }
};

struct DiagnosisResult {
  FitSummary base;
  std::optional<MisfitLocation> location;  // empty if locating failed
  std::string location_error;
  std::vector<CandidateOutcome> candidates;  // ranked: significant first, by BIC
  std::vector<std::string> selected;         // {"none"} when no cause is named; two for a pair or a tie
  Blame blame = Blame::kNone;
  // What the extraction flagged in the fitted steps (records cut before they
  // settled), whatever the verdict: the recording to check first.
  std::vector<std::string> recording_findings;
  DiagnosisVerdict verdict = DiagnosisVerdict::kNoSignificantDiscrepancy;
  RankedBy ranked_by = RankedBy::kNone;
  // After the selected model, the rest of the misfit lies within the noise
  // (reduced χ² ≤ acceptable_reduced_chi_square); false: only part explained.
  bool rest_within_noise = true;
  // The pairs tried after the named cause (empty when it explained the
  // misfit): "cause + partner", tested against the cause alone.
  std::vector<CandidateOutcome> combinations;
  // With "causes indistinguishable": where to measure to tell the two apart.
  std::optional<MeasurementSuggestion> suggestion;
  FitSummary final_fit;                      // the selected model (the base when none)
  std::vector<std::string> final_extra_parameters;
  // The selected physics refitted under the other beam damping laws, and its
  // parameters' model-form intervals; empty when no physics is named, its
  // model holds no loss factor, or DiagnosisOptions::damping_laws is off.
  DampingLawEnvelope final_damping_laws;
  std::vector<ResponsePoint> response;
  SelectedBackbone final_backbone;
  std::string summary;
  double seconds = 0.0;
};

using DiagnosisProgress = std::function<void(double fraction, const std::string& what)>;

// fit: the fitted channels (harmonics 1..K). validation: held-out channels
// (may have none). located: the channels to examine with harmonics 1..5
// (beyond K); empty channels: fit's. Throws beamid::InputError on invalid
// options (before any fit) and std::runtime_error when the base fit fails.
DiagnosisResult Diagnose(const FitData& fit, const FitData& validation, const FitData& located,
                         const DiagnosisOptions& options = {}, const DiagnosisProgress& progress = {});

// ---- The stages of Diagnose ----

// A fit's summary: χ², its degrees of freedom and information criteria for
// the structure's parameters plus extra_parameters more (a measurement
// artefact's, which the structure does not hold).
FitSummary SummarizeFit(const ModelStructure& structure, int harmonics, double chi_square, int num_residuals,
                        const std::vector<double>& values, const std::vector<double>& std, int extra_parameters = 0);
// The options of a candidate's refit from the base optimum (Ipopt capped at
// refit_max_iterations, no continuation).
IdentifyOptions CandidateRefitOptions(const DiagnosisOptions& options, int model_harmonics);
// The likelihood-ratio test of a refit (outcome->fit, test_dof) against
// reference_chi_square (header), Bonferroni over num_candidates; fills
// likelihood_ratio, p_value, residual_drop and significant.
void TestAgainstReference(double reference_chi_square, const FitSummary& base, int num_candidates,
                          const DiagnosisOptions& options, CandidateOutcome* outcome);

// Stage 1, the base model: the polynomial support alone from the direct
// estimate (robust even when the misfit is large), then with the beam's loss
// factor from there, kept only when it fits better (a large misfit can run
// the loss factor to its bound). Every later stage is measured against it.
struct BaseFit {
  FittedModel model;
  FitSummary summary;  // held-out fields NaN (ValidateOnHeldOut fills them)
};
BaseFit FitBase(const FitData& fit, const DiagnosisOptions& options);

// Validation: a fitted model's prediction of channels it did not fit — the
// check that a named cause generalises rather than bends the fit.
struct HeldOutCheck {
  // χ² of harmonics 1..K, and the relative RMS error of the first harmonic
  // over all steps, sqrt(Σ|ΔY₁|²/Σ|Y₁|²); NaN without held-out channels.
  double chi_square = std::numeric_limits<double>::quiet_NaN();
  double h1_relative_error = std::numeric_limits<double>::quiet_NaN();
  int num_residuals = 0;
};
// skip_step: a step left out of the check (-1: none), e.g. an outlying
// step whose held-out channels share its faulty record.
HeldOutCheck ValidateOnHeldOut(const FittedModel& model, const FitData& validation, int skip_step = -1);
// Validation without a held-out channel: each level left out in turn, the
// model refitted to the others from its optimum (CandidateRefitOptions), and
// its prediction of the left-out level's channels compared with them; χ² and
// the first harmonic's error summed over the levels. A model that bent
// itself to the data it saw predicts a level it did not see worse. NaN with
// fewer than two levels or when a refit fails.
HeldOutCheck ValidateOnLeftOutLevels(const FittedModel& model, const DiagnosisOptions& options);

// Stage 2, where the base misses: LocateMisfit of its residuals on the
// located channels (harmonics beyond the fitted ones included) against the
// exact linear beam of the base. A failure there is reported, not thrown:
// the refits still decide.
struct LocationStage {
  std::optional<MisfitLocation> location;
  std::string error;  // why location is empty
};
LocationStage Locate(const FitData& fit, const BaseFit& base, const FitData& located);

// Stage 3, every candidate refitted from the base optimum (all candidates
// and starts in parallel worker processes; the linear ones first, and the
// costlier ones — more harmonics, a changed support law — only when no
// significant linear one brings the misfit within the noise, nor the base
// fits within it: the others then say "not refitted"), its best start, and its
// likelihood-ratio test against the base (or, for one balanced with more
// harmonics, against the refit with those harmonics alone). Held-out fields
// NaN (ValidateOnHeldOut of `models`).
struct CandidateRefits {
  std::vector<CandidateOutcome> outcomes;           // library order, not ranked
  std::vector<std::unique_ptr<FittedModel>> models;  // [c]; null when its refit failed
};
// done of num_jobs refits have returned, the latest of candidate `name`.
using RefitProgress = std::function<void(int done, int num_jobs, const std::string& name)>;
// explained_by: a measurement artefact that already brings the misfit within
// the noise ("" when none): then no candidate is refitted (each says so).
// num_candidates: of the whole diagnosis, for the Bonferroni correction (0: these).
CandidateRefits RefitCandidates(const FitData& fit, const BaseFit& base, const std::optional<MisfitLocation>& location,
                                const DiagnosisOptions& options, const RefitProgress& progress = {},
                                const std::string& explained_by = "", int num_candidates = 0);

// After the verdict, when the named cause leaves a misfit beyond the noise:
// the cause's refit extended by each partner from its optimum (parallel
// workers), each pair tested against the cause alone (its fit as "base").
CandidateRefits RefitPairs(const FitData& fit, const FittedModel& first, const CandidateOutcome& first_outcome,
                           const std::vector<std::string>& partners, const DiagnosisOptions& options,
                           const RefitProgress& progress = {});
// The partners of the cause: options.max_pair_partners of the others with
// parameters of their own, converged ones first (by BIC), then failed ones.
std::vector<std::string> PairPartners(const std::vector<CandidateOutcome>& ranked, const std::string& cause,
                                      const DiagnosisOptions& options);
// The pair to name: significant against the cause alone, predicting the
// held-out channels no worse, best BIC; -1 when none.
int ChoosePair(const std::vector<CandidateOutcome>& pairs, const FitSummary& first);

// Stage 4, the verdict: candidates ranked (significant first, converged by
// BIC, then by signature score), the significant one that predicts the
// held-out channels decisively better moved to the front (header); the best
// named as the cause when significant — with the runner-up as "causes
// indistinguishable" when neither in sample nor held out separates them —
// else "unexplained" when the location (when there is one) finds a
// significant misfit — and, under the relative floor, the base misfit
// exceeds acceptable_reduced_chi_square — else "no significant discrepancy".
struct Verdict {
  std::vector<int> ranking;  // indices into the candidates, best first
  int cause = -1;            // index of the named cause; -1 when none
  int tied_with = -1;        // index of the candidate the data cannot tell from it; -1 when none
  DiagnosisVerdict verdict = DiagnosisVerdict::kNoSignificantDiscrepancy;
  RankedBy ranked_by = RankedBy::kNone;
  std::vector<std::string> selected;
};
// Whether the data separate two fits (header), in sample or on the held-out channels.
bool SeparatedInSample(const FitSummary& a, const FitSummary& b);
bool SeparatedHeldOut(const FitSummary& a, const FitSummary& b);
// validated_on: what the held-out fields measure (the held-out channels or
// the levels left out in turn), the ranked_by when they decide.
// weighting: how the data's σ were made; under kPropagated the location's
// test alone tells a misfit (its false-alarm rate is the one it states),
// under the relative floor the base must also exceed the acceptable reduced χ².
Verdict DecideVerdict(const FitSummary& base, const std::optional<MisfitLocation>& location,
                      PhasorUncertainty weighting, const std::vector<CandidateOutcome>& candidates,
                      const DiagnosisOptions& options, RankedBy validated_on = RankedBy::kHeldOutChannels);

// CSV of the response curves: level, frequency, channel, held_out, then
// amplitude and phase of measured, base and final first harmonics.
std::string ResponseCsv(const DiagnosisResult& result);

}  // namespace beamid::solver
