// result.json of `beamid identify` (format "beamid-result/1") as one plain
// value: the identified parameters with their uncertainty, the fit and its
// starts, the quality per channel, harmonic and level, the prediction error
// at held-out channels, and the model with its fitted steady states — all
// that `beamid predict` and `beamid report` need to rebuild the model.
// MakeResultFile computes it from a fit; solver/estimation/result_io.h is the
// file's one reader and writer. SI units; a number the fit could not give
// (a variance that is not finite, a failed start's objective) is NaN.
#pragma once

#include <complex>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "hb/beam_properties.h"
#include "hb/linear_attachments.h"
#include "solver/estimation/damping_laws.h"
#include "solver/estimation/fit_data.h"
#include "solver/estimation/fit_verdict.h"
#include "solver/estimation/model_family.h"
#include "solver/estimation/multistart.h"
#include "solver/estimation/robust_fit.h"

namespace beamid::solver {

inline constexpr std::string_view kResultFormat = "beamid-result/1";

struct ResultCampaign {
  std::string folder;           // as given to identify
  std::string name;
  std::string absolute_folder;  // empty: not recorded
  std::string sha256;           // content hash (signal/campaign_hash.h), "campaign_sha256"; "" in older files
};

struct ResultModel {
  ModelKind kind = ModelKind::kHarmonicBalance;
  std::string law = "polynomial";   // hb::SupportLaw::Name()
  hb::BeamProperties beam;          // nominal, with the loss factor identify started from
  double force_position_m = 0.0;
  std::vector<hb::PointMass> sensor_masses;
  std::vector<std::string> fit_channels;
  int num_fit_harmonics = 3;  // K
  int num_harmonics = 5;      // H of the model (3 for ms)
  PhasorUncertainty phasor_uncertainty = PhasorUncertainty::kRelativeFloor;  // how the data were weighed
};

struct ResultParameter {
  std::string name;
  std::string unit;
  double value = 0.0;
  double std = 0.0;
  double lower_95 = 0.0, upper_95 = 0.0;  // "ci95"
  double std_model_error = 0.0;  // std's part from the residual model error (0 in older files)
};

struct ResultStart {
  std::vector<double> start;       // physical parameters, parameter order
  std::vector<double> parameters;  // where it ended (empty when it failed before Ipopt)
  double objective = 0.0;          // ½χ²
  bool converged = false;
  int iterations = 0;
  std::string status;
  StartRoute states_seeded = StartRoute::kMeasuredStates;
  int branch_repairs = 0;
};

struct ResultMinimum {
  std::vector<double> parameters;
  double chi_square = 0.0;
  int num_starts = 0;  // "starts"
};

// The linear least-squares estimate from the reconstructed support rotation.
struct ResultDirectEstimate {
  double k1_Nm_rad = 0.0, k2_Nm_rad2 = 0.0, k3_Nm_rad3 = 0.0, c_Nms_rad = 0.0;
  double relative_residual = 0.0;
};

struct ResultFit {
  double chi_square = 0.0;
  int degrees_of_freedom = 0;
  double reduced_chi_square = 0.0;
  FitVerdict verdict;  // files written before the verdict: judged from reduced_chi_square on reading
  double seconds = 0.0;
  std::vector<ResultStart> starts;  // [0]: from the direct estimate
  int best_start = 0;
  int starts_at_best = 0;
  std::vector<ResultMinimum> minima;  // best first
  double second_minimum_chi_square_gap = 0.0;
  bool minimum_decisive = true;
  ResultDirectEstimate direct_estimate;
  // The residual model error per fitted harmonic ([k-1]; empty unless the
  // phasors' σ are calibrated: solver/estimation/model_error.h).
  std::vector<ModelErrorEstimate> model_errors;
};

// Fit quality of one fitted channel: per harmonic ([k-1]: harmonic k,
// "h1".."hK" in the file) and level.
struct LevelQuality {
  std::string level;
  double relative_rms_error = 0.0;
  double chi_square = 0.0;
  int num_steps = 0;  // "steps"
  // The phasors' σ term by term (solver/estimation/phasor_uncertainty.h),
  // each √(Σσ²/Σ|Y|²) over the level's steps ("relative_std"; 0 in older
  // files). Under the relative floor, model_error holds the floor; with
  // calibrated σ, the residual model error ε_k·|Ŷ_1| the fit estimated.
  PhasorUncertaintyBudget relative_std;
};
struct ChannelQuality {
  std::string channel;
  std::vector<std::vector<LevelQuality>> harmonics;
};

// Prediction at one held-out channel. Per step and harmonic ([k-1]: harmonic
// k, keys "hk_..." in the file) the predicted and measured phasors in the
// channel's quantity, the relative error and the measurement's own relative
// uncertainty; the worst errors count only the steps where the measurement
// resolves an error of measurable_relative_std.
struct HeldOutHarmonic {
  double relative_error = 0.0;
  double measured_relative_std = 0.0;
  std::complex<double> predicted;
  std::complex<double> measured;
};
struct HeldOutStep {
  std::string level;
  std::string file;
  double frequency_hz = 0.0;
  std::vector<HeldOutHarmonic> harmonics;
};
struct HeldOutChannel {
  std::string channel;
  double position_m = 0.0;
  double worst_h1_relative_error = 0.0;
  double worst_h3_relative_error = 0.0;
  double measurable_relative_std = 0.0;
  // 0: no step resolves that harmonic's error, and its worst error is NaN
  // (null in the file): nothing was measured there, not a perfect prediction.
  int measurable_steps_h1 = 0;
  int measurable_steps_h3 = 0;
  std::vector<HeldOutStep> steps;
};

// A fitted step: the force that drove it and the model's state there.
struct ResultStep {
  std::string level;
  std::string file;
  double frequency_hz = 0.0;
  Eigen::VectorXcd force_N;             // F_0..F_H
  Eigen::VectorXcd state;               // the family's (ModelFamily::StateName: Θ_0..Θ_H, U, …)
};

// The robust fit (solver/estimation/robust_fit.h): the outlying steps it
// found (left out when applied) and the ordinary fit's parameters, with
// them; written only when it found outliers.
struct ResultRobustFit {
  bool applied = false;
  std::string note;
  std::vector<OutlyingStep> outliers;
  std::vector<ParameterEstimate> ordinary_parameters;
  double ordinary_chi_square = 0.0;
  int ordinary_degrees_of_freedom = 0;
};

// A step whose record was cut before it settled: its phasors' uncertainty
// includes the change between the halves of the analysed part
// (signal/settling_uncertainty.h).
struct ResultUnsettledStep {
  std::string level;
  std::string file;
  double frequency_hz = 0.0;
  double change_relative = 0.0;
};

struct ResultFile {
  std::string beamid_version;  // of the writer; empty in files written before it was recorded
  ResultCampaign campaign;
  ResultModel model;
  std::vector<ResultParameter> parameters;  // in parameter order (the structure's: law, then linear)
  std::vector<std::string> linear_parameters;
  Eigen::MatrixXd covariance;   // parameter order
  Eigen::MatrixXd correlation;
  ResultFit fit;
  // The fit refitted under the beam's other damping laws, and the model-form
  // intervals (solver/estimation/damping_laws.h); empty when not computed.
  DampingLawEnvelope damping_laws;
  std::optional<ResultRobustFit> robust_fit;
  std::vector<ResultUnsettledStep> unsettled_steps;  // of the fit's data (left-out steps included)
  std::vector<std::string> warnings;
  std::vector<ChannelQuality> quality;     // fitted channels, in fit order
  std::vector<HeldOutChannel> validation;  // empty: no held-out channel
  std::vector<ResultStep> steps;           // the fit's steps
};

struct FitData;
class FitProblem;
struct IdentifyResult;

struct ResultContext {
  std::string campaign_folder;
  std::string campaign_name;
  std::string campaign_absolute_folder;  // lets `beamid report` find the campaign from elsewhere; "" = none
  std::string campaign_sha256;           // the campaign's content hash (signal::Campaign::sha256)
  const ModelFamily* family = &HarmonicBalanceFamily();  // the family `problem` is of
};

// `problem` must be the problem whose variables result.x are (its internal
// scales set by FeasiblePoint at the best start); `validation` holds the
// held-out channels' data (no channels: no validation). beamid_version is
// this program's.
ResultFile MakeResultFile(const FitData& fit, const FitData& validation, FitProblem& problem,
                          const IdentifyResult& result, const ResultContext& context);


}  // namespace beamid::solver
