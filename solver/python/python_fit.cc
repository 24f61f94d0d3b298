// identify, predict and diagnose: the model-based use cases, as `beamid
// identify`, `predict` and `diagnose` run them (solver/workflow/).
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "hb/errors.h"
#include "solver/diagnosis/diagnosis.h"
#include "solver/estimation/damping_laws.h"
#include "solver/estimation/fit_data.h"
#include "solver/estimation/result_file.h"
#include "solver/python/module_functions.h"
#include "solver/python/python_arrays.h"
#include "solver/python/python_errors.h"
#include "solver/python/python_run.h"
#include "solver/workflow/diagnose_campaign.h"
#include "solver/workflow/identify_campaign.h"
#include "solver/workflow/predict_campaign.h"

namespace py = pybind11;
using namespace pybind11::literals;

namespace beamid::python {
namespace {

solver::PhasorUncertainty ParsePhasorUncertainty(const std::string& name) {
  std::string names;
  for (const auto& [value, text] : solver::kPhasorUncertaintyNames) {
    if (text == name) return value;
    names += (names.empty() ? "" : ", ") + std::string(text);
  }
  throw InputError("phasor_uncertainty: unknown weighting '" + name + "' (use " + names + ")");
}

// A request of identify or diagnose with the arguments they share: the
// campaign, its fitted and held-out channels, where the phasors come from,
// the model's harmonics and the weighting.
template <typename Request>
Request CampaignRequest(const Path& campaign_folder, const std::optional<std::vector<std::string>>& fit,
                        const std::vector<std::string>& validate, const OptionalPath& phasors,
                        bool skip_bad_steps, int harmonics, int fit_harmonics, const std::string& phasor_uncertainty) {
  Request request;
  request.campaign_folder = campaign_folder.string();
  request.fit_channels = fit;
  request.validate_channels = validate;
  request.phasor_input.phasors_file = TextOf(phasors);
  request.phasor_input.skip_bad_steps = skip_bad_steps;
  request.harmonics = harmonics;
  request.fit_harmonics = fit_harmonics;
  request.phasor_uncertainty = ParsePhasorUncertainty(phasor_uncertainty);
  return request;
}

py::array_t<double> MatrixToArray(const Eigen::MatrixXd& m) {
  py::array_t<double> array({static_cast<py::ssize_t>(m.rows()), static_cast<py::ssize_t>(m.cols())});
  auto view = array.mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j) view(i, j) = m(i, j);
  return array;
}

py::dict EstimateToPython(const std::string& unit, double value, double std, double lower_95, double upper_95,
                          double std_model_error) {
  py::dict d("value"_a = value, "std"_a = std, "lower_95"_a = lower_95, "upper_95"_a = upper_95,
             "std_model_error"_a = std_model_error, "unit"_a = unit);
  return d;
}

py::dict EstimatesToPython(const std::vector<solver::ParameterEstimate>& parameters) {
  py::dict d;
  for (const auto& p : parameters)
    d[py::str(p.name)] = EstimateToPython(p.unit, p.value, p.std, p.lower_95, p.upper_95, p.std_model_error);
  return d;
}

// The parameters of result.json, each with its total interval where the
// damping laws were refitted (NaN where not).
py::dict ResultParametersToPython(const solver::ResultFile& file) {
  py::dict d;
  for (const solver::ResultParameter& p : file.parameters) {
    py::dict estimate = EstimateToPython(p.unit, p.value, p.std, p.lower_95, p.upper_95, p.std_model_error);
    const auto& intervals = file.damping_laws.intervals;
    const auto total = std::find_if(intervals.begin(), intervals.end(),
                                    [&](const solver::ModelFormInterval& i) { return i.name == p.name; });
    estimate["total_lower_95"] = total == intervals.end() ? kMissing : total->lower_95;
    estimate["total_upper_95"] = total == intervals.end() ? kMissing : total->upper_95;
    d[py::str(p.name)] = estimate;
  }
  return d;
}

// The columns a table of steps starts with: each step's level, its
// recording's file and its frequency [Hz].
struct StepColumns {
  py::list levels, files;
  py::array_t<double> frequency_hz;
};
template <typename Step>
StepColumns StepColumnsOf(const std::vector<Step>& steps) {
  StepColumns columns;
  columns.frequency_hz = NanArray(steps.size());
  for (std::size_t i = 0; i < steps.size(); ++i) {
    columns.levels.append(steps[i].level);
    columns.files.append(steps[i].file);
    columns.frequency_hz.mutable_at(static_cast<py::ssize_t>(i)) = steps[i].frequency_hz;
  }
  return columns;
}

// A held-out channel's prediction: rows are its steps, columns harmonics.
py::dict HeldOutToPython(const solver::HeldOutChannel& channel) {
  std::size_t harmonics = 0;
  for (const auto& s : channel.steps) harmonics = std::max(harmonics, s.harmonics.size());
  const std::size_t n = channel.steps.size();
  const StepColumns steps = StepColumnsOf(channel.steps);
  using Complex = std::complex<double>;
  auto predicted = NanMatrix<Complex>(n, harmonics), measured = NanMatrix<Complex>(n, harmonics);
  auto error = NanMatrix<double>(n, harmonics), measured_std = NanMatrix<double>(n, harmonics);
  for (std::size_t i = 0; i < n; ++i) {
    const solver::HeldOutStep& s = channel.steps[i];
    const auto row = static_cast<py::ssize_t>(i);
    for (std::size_t k = 0; k < s.harmonics.size(); ++k) {
      const auto column = static_cast<py::ssize_t>(k);
      predicted.mutable_at(row, column) = s.harmonics[k].predicted;
      measured.mutable_at(row, column) = s.harmonics[k].measured;
      error.mutable_at(row, column) = s.harmonics[k].relative_error;
      measured_std.mutable_at(row, column) = s.harmonics[k].measured_relative_std;
    }
  }
  py::dict d("position_m"_a = channel.position_m, "worst_h1_relative_error"_a = channel.worst_h1_relative_error,
             "worst_h3_relative_error"_a = channel.worst_h3_relative_error,
             "measurable_relative_std"_a = channel.measurable_relative_std, "levels"_a = steps.levels,
             "files"_a = steps.files, "frequency_hz"_a = steps.frequency_hz, "predicted"_a = predicted,
             "measured"_a = measured, "relative_error"_a = error, "measured_relative_std"_a = measured_std);
  return d;
}

py::dict IdentifyOutcomeToPython(const workflow::IdentifyOutcome& outcome) {
  const solver::ResultFile& file = outcome.result_file;
  const solver::IdentifyResult& result = outcome.Result();
  py::dict d("kind"_a = "identify", "model"_a = outcome.family->Name(),
             "parameters"_a = ResultParametersToPython(file));
  py::list names;
  for (const auto& p : file.parameters) names.append(p.name);
  d["parameter_names"] = names;
  d["covariance"] = MatrixToArray(file.covariance);
  d["correlation"] = MatrixToArray(file.correlation);
  d["total_interval_parts"] = file.damping_laws.empty()
                                  ? py::object(py::none())
                                  : py::object(py::str(solver::TotalIntervalParts(file.damping_laws)));
  py::dict fit("chi_square"_a = file.fit.chi_square, "degrees_of_freedom"_a = file.fit.degrees_of_freedom,
               "reduced_chi_square"_a = file.fit.reduced_chi_square, "within_noise"_a = outcome.WithinNoise(),
               "verdict"_a = result.verdict.text, "seconds"_a = file.fit.seconds,
               "num_starts"_a = file.fit.starts.size(), "starts_at_best"_a = file.fit.starts_at_best,
               "num_steps"_a = outcome.fit.steps.size(), "channels"_a = ToList(file.model.fit_channels));
  d["fit"] = fit;
  py::dict validation;
  for (const solver::HeldOutChannel& channel : file.validation)
    validation[py::str(channel.channel)] = HeldOutToPython(channel);
  d["validation"] = validation;
  d["warnings"] = ToList(file.warnings);
  return d;
}

py::dict FitSummaryToPython(const solver::FitSummary& fit) {
  py::dict d("parameters"_a = EstimatesToPython(fit.parameters), "chi_square"_a = fit.chi_square,
             "degrees_of_freedom"_a = fit.degrees_of_freedom, "reduced_chi_square"_a = fit.reduced_chi_square,
             "aic"_a = fit.aic, "bic"_a = fit.bic, "held_out_chi_square"_a = fit.held_out_chi_square,
             "held_out_h1_relative_error"_a = fit.held_out_h1_relative_error);
  return d;
}

py::dict CandidateToPython(const solver::CandidateOutcome& c) {
  py::dict d("name"_a = c.name, "description"_a = c.description,
             "status"_a = std::string(schema::NameOf(c.status, solver::kRefitStatusNames)),
             "status_message"_a = c.status_message, "signature_score"_a = c.signature_score,
             "extra_parameters"_a = ToList(c.extra_parameters), "fit"_a = FitSummaryToPython(c.fit),
             "p_value"_a = c.p_value, "residual_drop"_a = c.residual_drop, "significant"_a = c.significant,
             "measurement"_a = c.measurement);
  return d;
}

py::dict DiagnosisToPython(const workflow::DiagnoseOutcome& outcome) {
  const solver::DiagnosisResult& r = outcome.diagnosis;
  py::dict d("kind"_a = "diagnosis", "verdict"_a = solver::ToString(r.verdict), "blame"_a = solver::ToString(r.blame),
             "ranked_by"_a = solver::ToString(r.ranked_by), "selected"_a = ToList(r.selected), "summary"_a = r.summary,
             "rest_within_noise"_a = r.rest_within_noise, "recording_findings"_a = ToList(r.recording_findings),
             "num_steps"_a = outcome.num_steps, "base"_a = FitSummaryToPython(r.base),
             "final"_a = FitSummaryToPython(r.final_fit));
  py::list candidates, combinations;
  for (const auto& c : r.candidates) candidates.append(CandidateToPython(c));
  for (const auto& c : r.combinations) combinations.append(CandidateToPython(c));
  d["candidates"] = candidates;
  d["combinations"] = combinations;
  d["curves_problem"] = outcome.curves_problem;
  return d;
}

py::dict PredictionToPython(const workflow::PredictOutcome& outcome) {
  const solver::PredictionFile& file = outcome.file;
  const std::size_t n = file.steps.size();
  const StepColumns steps = StepColumnsOf(file.steps);
  std::size_t harmonics = 0, samples = 0;
  for (const auto& s : file.steps) {
    harmonics = std::max(harmonics, s.harmonics.size());
    samples = std::max(samples, s.time_s.size());
  }
  py::array_t<bool> converged(static_cast<py::ssize_t>(n));
  using Complex = std::complex<double>;
  auto displacement = NanMatrix<Complex>(n, harmonics), acceleration = NanMatrix<Complex>(n, harmonics),
       measured = NanMatrix<Complex>(n, harmonics), predicted = NanMatrix<Complex>(n, harmonics);
  auto std_real = NanMatrix<double>(n, harmonics), std_imag = NanMatrix<double>(n, harmonics),
       error = NanMatrix<double>(n, harmonics);
  auto time = NanMatrix<double>(n, samples), history = NanMatrix<double>(n, samples),
       history_std = NanMatrix<double>(n, samples);
  for (std::size_t i = 0; i < n; ++i) {
    const solver::PredictionStep& s = file.steps[i];
    const auto row = static_cast<py::ssize_t>(i);
    converged.mutable_at(row) = s.converged;
    for (const solver::PredictionHarmonic& h : s.harmonics) {
      if (h.k < 1 || static_cast<std::size_t>(h.k) > harmonics) continue;
      const auto k = static_cast<py::ssize_t>(h.k - 1);
      displacement.mutable_at(row, k) = h.displacement_m;
      std_real.mutable_at(row, k) = h.displacement_std_real_m;
      std_imag.mutable_at(row, k) = h.displacement_std_imag_m;
      acceleration.mutable_at(row, k) = h.acceleration_m_s2;
      if (!h.compared) continue;
      measured.mutable_at(row, k) = h.measured;
      predicted.mutable_at(row, k) = h.predicted;
      error.mutable_at(row, k) = h.relative_error;
    }
    for (std::size_t j = 0; j < s.time_s.size(); ++j) {
      const auto column = static_cast<py::ssize_t>(j);
      time.mutable_at(row, column) = s.time_s[j];
      if (j < s.acceleration_m_s2.size()) history.mutable_at(row, column) = s.acceleration_m_s2[j];
      if (j < s.acceleration_std_m_s2.size()) history_std.mutable_at(row, column) = s.acceleration_std_m_s2[j];
    }
  }
  py::dict d("kind"_a = "prediction", "model"_a = outcome.family->Name(), "position_m"_a = file.position_m,
             "compared_channel"_a = file.compared_channel, "compared_quantity"_a = file.compared_quantity,
             "worst_h1_relative_error"_a = outcome.worst_h1_relative_error, "levels"_a = steps.levels,
             "files"_a = steps.files, "frequency_hz"_a = steps.frequency_hz, "converged"_a = converged,
             "displacement_m"_a = displacement, "displacement_std_real_m"_a = std_real,
             "displacement_std_imag_m"_a = std_imag, "acceleration_m_s2"_a = acceleration, "measured"_a = measured,
             "predicted"_a = predicted, "relative_error"_a = error, "time_s"_a = time,
             "acceleration_history_m_s2"_a = history, "acceleration_history_std_m_s2"_a = history_std);
  return d;
}


}  // namespace

void AddFitFunctions(py::module_& module) {
  module.def(
      "identify",
      [](const Path& campaign_folder, std::optional<std::vector<std::string>> fit,
         std::vector<std::string> validate, const std::string& model, const OptionalPath& phasors,
         bool skip_bad_steps, int harmonics, int fit_harmonics, const std::string& phasor_uncertainty, int starts,
         int workers, bool fit_ei_scale, bool fix_loss_factor, bool damping_laws, bool robust, double beam_loss_factor,
         const OptionalPath& output, const OptionalPath& csv_output, py::object progress) {
        PythonRun run(std::move(progress));
        auto request = CampaignRequest<workflow::IdentifyRequest>(campaign_folder, fit, validate, phasors,
                                                                  skip_bad_steps, harmonics, fit_harmonics,
                                                                  phasor_uncertainty);
        request.output = run.OutputPath(output, "result.json");
        request.csv_output = TextOf(csv_output);
        request.model = model;
        request.starts = starts;
        // Starts in worker processes (fork): PythonRun calls no Python from them.
        request.workers = workers;
        request.fit_ei_scale = fit_ei_scale;
        request.fix_loss_factor = fix_loss_factor;
        request.damping_envelope = damping_laws;
        request.robust = robust;
        request.beam_loss_factor = beam_loss_factor;
        return RunWorkflow(run, request, workflow::IdentifyCampaign, IdentifyOutcomeToPython, request.output, output);
      },
      py::arg("campaign_folder"), py::kw_only(), py::arg("fit") = py::none(),
      py::arg("validate") = std::vector<std::string>{}, py::arg("model") = "hb", py::arg("phasors") = py::none(),
      py::arg("skip_bad_steps") = false, py::arg("harmonics") = 5, py::arg("fit_harmonics") = 3,
      py::arg("phasor_uncertainty") = "propagated", py::arg("starts") = 0, py::arg("workers") = 0,
      py::arg("fit_ei_scale") = false, py::arg("fix_loss_factor") = false, py::arg("damping_laws") = true,
      py::arg("robust") = true, py::arg("beam_loss_factor") = 0.0, py::arg("output") = py::none(),
      py::arg("csv_output") = py::none(), py::arg("progress") = py::none(),
      R"(Identifies the support (k1, k2, k3, c and the beam's loss factor) from a campaign, as `beamid identify`
(docs/identify.md).

Arguments (the command line's defaults):
  campaign_folder     the folder holding campaign.json
  fit                 response channels to fit (None: every sensor neither ignored nor held out; --fit)
  validate            held-out channels, predicted and compared (--validate)
  model               'hb' (exact harmonic balance) or 'ms' (multiple scales)
  phasors             a phasors file of extract (None: extract them; --phasors)
  skip_bad_steps      leave out the steps whose recordings hold errors
  harmonics           H of the model (1..50; -H)
  fit_harmonics       K, harmonics 1..K fitted (1..50, K <= H)
  phasor_uncertainty  'propagated' or 'relative_floor'
  starts              further starts besides the direct estimate (0..1000)
  workers             worker processes for the starts (0: one per core)
  fit_ei_scale        also fit a scale of the bending stiffness EI
  fix_loss_factor     hold the beam's loss factor at beam_loss_factor
  damping_laws        refit under the other beam damping laws (False: --no-damping-laws)
  robust              test the steps for outliers and refit without them (False: --no-robust)
  beam_loss_factor    the loss factor's start, or its value when fixed (0..1)
  output              also keep result.json there (None: not kept)
  csv_output          also write the parameters' CSV table there (None: none)
  progress            None or a callable progress(task, fraction, what)

Returns a dict: parameters (per name: value, std, lower_95, upper_95,
std_model_error, total_lower_95, total_upper_95 (NaN where the damping laws
were not refitted), unit: k1 [N·m/rad], k2 [N·m/rad²], k3 [N·m/rad³], c
[N·m·s/rad], loss_factor [-]), parameter_names, covariance and correlation
(arrays in that order), total_interval_parts, fit (chi_square,
degrees_of_freedom, reduced_chi_square, within_noise, verdict, seconds,
num_starts, starts_at_best, num_steps, channels), validation (per held-out
channel: position_m, worst_h1_relative_error, worst_h3_relative_error,
levels, files, frequency_hz [Hz], predicted, measured (complex, steps ×
harmonics, in the channel's quantity, SI), relative_error), warnings,
run_warnings, notes, document (result.json as Python objects), output. A fit
that misses the data beyond their noise is returned with fit['within_noise']
False (the program's exit code 5). beamid.to_pandas(result) gives the
parameters' table.)");

  module.def(
      "predict",
      [](const Path& result, double x, const OptionalPath& campaign, const OptionalPath& output,
         py::object progress) {
        PythonRun run(std::move(progress));
        workflow::PredictRequest request{.result_file = result.string(),
                                         .campaign_folder = TextOf(campaign),
                                         .position_m = x,
                                         .output = run.OutputPath(output, "prediction.json")};
        // As the program: the prediction is written, the run still failed.
        const auto checked = [&](const workflow::PredictOutcome& outcome) {
          const std::string unconverged = outcome.Unconverged();
          if (!unconverged.empty())
            throw NumericalError("the harmonic balance did not converge at " + unconverged + " (written to " +
                                 request.output + " all the same)");
          return PredictionToPython(outcome);
        };
        return RunWorkflow(run, request, workflow::PredictCampaign, checked, request.output, output);
      },
      py::arg("result"), py::kw_only(), py::arg("x"), py::arg("campaign") = py::none(), py::arg("output") = py::none(),
      py::arg("progress") = py::none(),
      R"(The identified model's steady state at position x [m] of the beam for every step of its fit, as
`beamid predict` (with the model identify used).

Arguments:
  result    result.json of identify (a path: keep it with identify(..., output=PATH))
  x         position on the beam [m] (0..100; --x)
  campaign  the campaign to compare with, when a sensor sits at x (None: none)
  output    also keep the prediction file there (None: not kept)
  progress  None or a callable progress(task, fraction, what)

Returns a dict: model, position_m, compared_channel and compared_quantity
('' without), worst_h1_relative_error, levels, files, frequency_hz [Hz],
converged (arrays over the n steps), displacement_m (complex, n × H, peak
[m]) with displacement_std_real_m and displacement_std_imag_m,
acceleration_m_s2 (complex, n × H [m/s²]), measured, predicted (complex, in
the compared channel's quantity, NaN where not compared), relative_error,
time_s [s], acceleration_history_m_s2 and acceleration_history_std_m_s2
(n × samples, one period), document, output, run_warnings, notes. Raises
beamid.NumericalError when a step's balance did not converge (the program's
exit code 3; with output the file is written all the same).)");

  module.def(
      "diagnose",
      [](const Path& campaign_folder, std::optional<std::vector<std::string>> fit,
         std::vector<std::string> validate, std::vector<std::string> candidates, bool recording_check,
         const OptionalPath& phasors, bool skip_bad_steps, int harmonics, int fit_harmonics,
         const std::string& phasor_uncertainty, int workers, double significance, const OptionalPath& result,
         const OptionalPath& curves, const OptionalPath& output, py::object progress) {
        PythonRun run(std::move(progress));
        auto request = CampaignRequest<workflow::DiagnoseRequest>(
            campaign_folder, fit, validate, phasors, skip_bad_steps, harmonics, fit_harmonics, phasor_uncertainty);
        request.candidates = candidates;
        // Refits in worker processes (fork): PythonRun calls no Python from them.
        request.workers = workers;
        request.significance = significance;
        request.recording_check = recording_check;
        request.output = run.OutputPath(output, "diagnosis.json");
        request.curves = TextOf(curves);
        request.result_file = TextOf(result);
        return RunWorkflow(run, request, workflow::DiagnoseCampaign, DiagnosisToPython, request.output, output);
      },
      py::arg("campaign_folder"), py::kw_only(), py::arg("fit") = py::none(),
      py::arg("validate") = std::vector<std::string>{}, py::arg("candidates") = std::vector<std::string>{},
      py::arg("recording_check") = true, py::arg("phasors") = py::none(), py::arg("skip_bad_steps") = false,
      py::arg("harmonics") = 5, py::arg("fit_harmonics") = 3, py::arg("phasor_uncertainty") = "propagated",
      py::arg("workers") = 0, py::arg("significance") = 0.01, py::arg("result") = py::none(),
      py::arg("curves") = py::none(), py::arg("output") = py::none(), py::arg("progress") = py::none(),
      R"(Where the identified model misses a campaign and which left-out physics explains it, as `beamid diagnose`
(docs/diagnose.md).

Arguments (the command line's defaults):
  campaign_folder     the folder holding campaign.json
  fit, validate       fitted and held-out channels, as identify
  candidates          physics candidates to try (empty: all; --candidates)
  recording_check     try the measurement artefacts first (False: --no-recording-check)
  phasors, skip_bad_steps, harmonics, fit_harmonics, phasor_uncertainty: as identify
  workers             parallel refits (0: one per core)
  significance        family-wise significance of naming a cause (1e-12..0.5)
  result              identify's result.json on this campaign, named in the diagnosis
  curves              also write the response curves PREFIX.csv (and PREFIX.png with gnuplot)
  output              also keep diagnosis.json there (None: not kept)
  progress            None or a callable progress(task, fraction, what)

Returns a dict: verdict, blame, ranked_by, selected, summary,
rest_within_noise, recording_findings, num_steps, base and final (fit
summaries: parameters, chi_square, degrees_of_freedom, reduced_chi_square,
aic, bic, held_out_chi_square, held_out_h1_relative_error), candidates and
combinations (name, description, status, status_message, signature_score,
extra_parameters, fit, p_value, residual_drop, significant, measurement),
curves_problem, document (diagnosis.json), output, run_warnings, notes.)");
}

}  // namespace beamid::python
