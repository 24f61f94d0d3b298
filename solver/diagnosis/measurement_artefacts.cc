#include "solver/diagnosis/measurement_artefacts.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "solver/diagnosis/diagnosis_io.h"
#include "solver/estimation/internal/worker_processes.h"
#include "solver/estimation/model_phasors.h"
#include "solver/estimation/parameter_covariance.h"
#include "solver/estimation/robust_fit.h"
#include "solver/estimation/whitened_misfit.h"

namespace beamid::solver {
namespace {

using Complex = std::complex<double>;

// A weightless step keeps this share of its whitening (header).
constexpr double kLeftOutWeight = 1e-6;
// Rounds of artefact estimate and physics refit (header).
constexpr int kMaxRounds = 8;
// A generator's and an acquisition's crystal are good to ~100 ppm: read
// frequencies further than this from the stated ones show a clock (or a
// stated sample rate) that is off.
constexpr double kClockEvidence = 5e-4;
// The artefact's parameter has converged when a round moves it by less than this share.
constexpr double kConvergedRelative = 1e-3;
// A first round that leaves more than this share of the base's χ² ends the
// rounds: each round takes ~2/3 of the way to the joint optimum (below), so
// the joint fit would still leave over 85 % — the artefact is no explanation,
// and its further rounds (a physics refit each) would cost the diagnosis
// seconds on every campaign whose misfit is physics.
constexpr double kUnpromisingShare = 0.9;

// Gauss–Newton for one scalar of the misfit of `channels`: residual(θ) per
// step, channel and harmonic, its derivative by the callback; returns θ and
// its std.
template <typename Residual>
ArtefactEstimate ScalarGaussNewton(const FitData& fit, const std::vector<int>& channels, double start,
                                   double step_scale, const Residual& residual) {
  double theta = start, jtj = 0.0, chi2 = 0.0;
  for (int iteration = 0; iteration < 8; ++iteration) {
    double jtr = 0.0;
    jtj = 0.0;
    chi2 = 0.0;
    for (std::size_t i = 0; i < fit.steps.size(); ++i)
      for (int c : channels)
        for (int k = 1; k <= fit.num_fit_harmonics; ++k) {
          Eigen::Vector2d r, dr;
          residual(i, c, k, theta, &r, &dr);
          jtr += dr.dot(r);
          jtj += dr.squaredNorm();
          chi2 += r.squaredNorm();
        }
    if (jtj <= 0.0) break;
    const double delta = -jtr / jtj;
    theta += delta;
    if (std::abs(delta) < 1e-9 * step_scale) break;
  }
  const int n = 2 * static_cast<int>(fit.steps.size() * channels.size()) * fit.num_fit_harmonics;
  const double scale = std::max(1.0, chi2 / std::max(1, n - 1));
  return {.value = theta, .std = jtj > 0.0 ? std::sqrt(scale / jtj) : 0.0};
}

std::string StepLabel(const FitStep& s) { return fmt::format("{} {:.4g} Hz", s.level, s.FrequencyHz()); }

// Gauss–Newton on the model's phasors as a function of one parameter of the
// data (`corrected(θ)`), linearised by central differences of step h about
// the current θ, until a step moves θ by less than `converged`.
template <typename Corrected, typename Evaluate>
ArtefactEstimate FiniteDifferenceGaussNewton(const FitData& fit, const std::vector<int>& channels, double h,
                                             double converged, const Corrected& corrected,
                                             const Evaluate& phasors_at) {
  double theta = 0.0;
  ArtefactEstimate estimate;
  for (int iteration = 0; iteration < 4; ++iteration) {
    const auto y0 = phasors_at(corrected(theta)), yp = phasors_at(corrected(theta + h)),
               ym = phasors_at(corrected(theta - h));
    const ArtefactEstimate step = ScalarGaussNewton(
        fit, channels, 0.0, h, [&](std::size_t i, int c, int k, double d, Eigen::Vector2d* r, Eigen::Vector2d* dr) {
          const FitStep& s = fit.steps[i];
          const Complex slope = (yp[i](c, k - 1) - ym[i](c, k - 1)) / (2.0 * h);
          *r = Whitened(s, c, k, y0[i](c, k - 1) + d * slope - s.measured(c, k - 1));
          *dr = Whitened(s, c, k, slope);
        });
    theta += step.value;
    estimate = {.value = theta, .std = step.std};
    if (std::abs(step.value) < converged) break;
  }
  return estimate;
}

std::vector<int> AllChannels(const FitData& fit) {
  std::vector<int> channels(fit.channels.size());
  for (std::size_t c = 0; c < channels.size(); ++c) channels[c] = static_cast<int>(c);
  return channels;
}

}  // namespace

const char* ArtefactKindName(ArtefactKind kind) {
  switch (kind) {
    case ArtefactKind::kSensorGain: return "sensor_gain";
    case ArtefactKind::kSensorPhaseDelay: return "sensor_phase_delay";
    case ArtefactKind::kSensorPosition: return "sensor_position";
    case ArtefactKind::kOutlyingStep: return "outlying_step";
    case ArtefactKind::kClockError: return "clock_error";
  }
  return "";
}

std::string ArtefactName(const FitData& fit, const MeasurementArtefact& a) {
  if (a.kind == ArtefactKind::kOutlyingStep)
    return std::string(ArtefactKindName(a.kind)) + "(" + StepLabel(fit.steps[static_cast<std::size_t>(a.step)]) + ")";
  if (a.kind == ArtefactKind::kClockError) return ArtefactKindName(a.kind);  // one clock for every channel
  return std::string(ArtefactKindName(a.kind)) + "(" + fit.channels[static_cast<std::size_t>(a.channel)].channel + ")";
}

FitData CorrectedData(const FitData& fit, const MeasurementArtefact& a) {
  FitData out = fit;
  switch (a.kind) {
    case ArtefactKind::kSensorGain:
      for (auto& s : out.steps) {
        s.measured.row(a.channel) /= 1.0 + a.value;
        s.std_amplitude.row(a.channel) /= 1.0 + a.value;
        for (auto& w : s.whitening[static_cast<std::size_t>(a.channel)]) w *= 1.0 + a.value;
        for (auto& shared : s.shared_errors) shared.row(a.channel) /= 1.0 + a.value;
      }
      break;
    case ArtefactKind::kSensorPhaseDelay:
      for (auto& s : out.steps)
        for (int k = 1; k <= out.num_fit_harmonics; ++k) {
          const double angle = k * s.omega_rad_s * a.value;
          s.measured(a.channel, k - 1) *= std::polar(1.0, angle);
          for (auto& shared : s.shared_errors) shared(a.channel, k - 1) *= std::polar(1.0, angle);
          auto& w = s.whitening[static_cast<std::size_t>(a.channel)][static_cast<std::size_t>(k - 1)];
          w = w * Eigen::Rotation2Dd(-angle).toRotationMatrix();
        }
      break;
    case ArtefactKind::kSensorPosition:
      out.channels[static_cast<std::size_t>(a.channel)].position_m += a.value;
      break;
    case ArtefactKind::kOutlyingStep:
      for (auto& channel : out.steps[static_cast<std::size_t>(a.step)].whitening)
        for (auto& w : channel) w *= kLeftOutWeight;
      break;
    case ArtefactKind::kClockError:
      for (auto& s : out.steps) s.omega_rad_s *= 1.0 + a.value;
      break;
  }
  return out;
}

ArtefactEstimate EstimateGain(const FitData& fit, const std::vector<Eigen::MatrixXcd>& model, int c) {
  // Linear in (1 + g): the closed form is Gauss–Newton's first step from 0.
  return ScalarGaussNewton(fit, {c}, 0.0, 1.0, [&](std::size_t i, int, int k, double g, Eigen::Vector2d* r, Eigen::Vector2d* dr) {
    const FitStep& s = fit.steps[i];
    const Complex y = model[i](c, k - 1);
    *r = Whitened(s, c, k, (1.0 + g) * y - s.measured(c, k - 1));
    *dr = Whitened(s, c, k, y);
  });
}

ArtefactEstimate EstimatePhaseDelay(const FitData& fit, const std::vector<Eigen::MatrixXcd>& model, int c) {
  return ScalarGaussNewton(fit, {c}, 0.0, 1e-3, [&](std::size_t i, int, int k, double tau, Eigen::Vector2d* r, Eigen::Vector2d* dr) {
    const FitStep& s = fit.steps[i];
    const double kw = k * s.omega_rad_s;
    const Complex delayed = std::polar(1.0, -kw * tau) * model[i](c, k - 1);
    *r = Whitened(s, c, k, delayed - s.measured(c, k - 1));
    *dr = Whitened(s, c, k, Complex(0.0, -kw) * delayed);
  });
}

ArtefactEstimate EstimatePosition(const FitData& fit, const FittedModel& model, int c) {
  // The mode shapes are smooth on a 1 mm scale.
  return FiniteDifferenceGaussNewton(
      fit, {c}, 1e-3, 1e-6,
      [&](double d) { return CorrectedData(fit, {.kind = ArtefactKind::kSensorPosition, .channel = c, .value = d}); },
      [&](const FitData& data) { return model.Phasors(data); });
}

ArtefactEstimate EstimateClockError(const FitData& fit, const FittedModel& model) {
  // The fitted states hold the response at the frequencies the model was
  // fitted at: at others it is solved anew (with the fitted parameters,
  // Newton from the support rotation the measurements show, so on the
  // test's branch). A step of 10⁻⁴ is 1/50 of the resonance's half-width
  // at the paper's damping (ζ ≈ 0.6 %), where the response bends most.
  const std::vector<double> parameters = model.structure.Values();
  return FiniteDifferenceGaussNewton(
      fit, AllChannels(fit), 1e-4, 1e-8,
      [&](double e) { return CorrectedData(fit, {.kind = ArtefactKind::kClockError, .value = e}); },
      [&](const FitData& data) {
        const std::unique_ptr<FitProblem> problem =
            model.family->MakeProblem(data, model.structure, ModelOptions{.num_harmonics = model.model_harmonics});
        return ModelPhasors(data, *problem, problem->FeasiblePoint(parameters));
      });
}

double ClockErrorFromStatedFrequencies(const FitData& fit) {
  std::vector<double> ratios;
  for (const FitStep& s : fit.steps)
    if (s.nominal_frequency_hz > 0.0 && s.omega_rad_s > 0.0) ratios.push_back(s.nominal_frequency_hz / s.FrequencyHz() - 1.0);
  if (ratios.empty()) return 0.0;
  // The median: a step whose frequency the extraction misread does not move it.
  const auto middle = ratios.begin() + static_cast<std::ptrdiff_t>(ratios.size() / 2);
  std::nth_element(ratios.begin(), middle, ratios.end());
  return *middle;
}

std::vector<int> SuspectSteps(const FitData& fit, const FittedModel& base, int max_steps) {
  std::vector<int> steps;
  for (int i = 0; i < static_cast<int>(fit.steps.size()); ++i)
    if (fit.steps[static_cast<std::size_t>(i)].unsettled && static_cast<int>(steps.size()) < max_steps) steps.push_back(i);
  std::vector<OutlyingStep> outliers = FindOutlyingSteps(fit, StepChiSquares(*base.problem, base.x), {});
  std::stable_sort(outliers.begin(), outliers.end(),
                   [](const OutlyingStep& a, const OutlyingStep& b) { return a.chi_square > b.chi_square; });
  for (const auto& o : outliers)
    if (static_cast<int>(steps.size()) < max_steps && std::find(steps.begin(), steps.end(), o.step) == steps.end())
      steps.push_back(o.step);
  return steps;
}

std::string ArtefactRigCheck(const FitData& fit, const MeasurementArtefact& a) {
  if (a.kind == ArtefactKind::kOutlyingStep) {
    const FitStep& s = fit.steps[static_cast<std::size_t>(a.step)];
    return fmt::format("re-record {} ({}){}", StepLabel(s), s.file,
                       s.unsettled ? " with a longer settle: the extraction found its record cut before it settled"
                                   : ": it alone misses the model (a glitch, a step recorded too early, a loose cable)");
  }
  if (a.kind == ArtefactKind::kClockError)
    return fmt::format("check the acquisition's sample rate (its clock, the rate written in the files): the "
                       "frequencies read {:.2f} % {} (the clock runs {:.0f} ppm {})",
                       100.0 * std::abs(a.value) / (1.0 + a.value), a.value > 0.0 ? "low" : "high",
                       1e6 * std::abs(a.value), a.value > 0.0 ? "fast" : "slow");
  const FitChannel& channel = fit.channels[static_cast<std::size_t>(a.channel)];
  switch (a.kind) {
    case ArtefactKind::kSensorGain:
      return fmt::format("check {}'s calibration (sensitivity, the acquisition's scaling): it reads {:.1f} % {}",
                         channel.channel, 100.0 * std::abs(a.value), a.value > 0.0 ? "high" : "low");
    case ArtefactKind::kSensorPhaseDelay:
      return fmt::format("check {}'s signal path (anti-alias filter, a channel sampled late): it {} by {:.3g} ms",
                         channel.channel, a.value > 0.0 ? "lags" : "leads", 1e3 * std::abs(a.value));
    case ArtefactKind::kSensorPosition:
      return fmt::format("measure {}'s position on the beam: the fit puts it at {:.4f} m, {:.1f} mm from the stated "
                         "{:.4f} m",
                         channel.channel, channel.position_m + a.value, 1e3 * std::abs(a.value), channel.position_m);
    case ArtefactKind::kOutlyingStep:
    case ArtefactKind::kClockError: break;
  }
  return "";
}

namespace {

ArtefactEstimate Estimate(const FitData& fit, const FittedModel& model, const MeasurementArtefact& artefact) {
  switch (artefact.kind) {
    case ArtefactKind::kSensorGain: return EstimateGain(fit, model.Phasors(fit), artefact.channel);
    case ArtefactKind::kSensorPhaseDelay: return EstimatePhaseDelay(fit, model.Phasors(fit), artefact.channel);
    case ArtefactKind::kSensorPosition: return EstimatePosition(fit, model, artefact.channel);
    case ArtefactKind::kClockError: return EstimateClockError(fit, model);
    case ArtefactKind::kOutlyingStep: break;
  }
  return {};
}

struct ArtefactFit {
  ArtefactEstimate estimate;  // value: the one the refit's data were corrected with
  double chi_square = 0.0;
  std::vector<double> values, std;
  std::unique_ptr<FittedModel> model;
  std::vector<double> scaled_at;  // of the last refit, to rebuild its model in another process
};

// The base physics refitted from out->values on the data `artefact`
// corrects: out's values, std, χ² and model.
void RefitPhysics(const FitData& fit, const BaseFit& base, const ModelStructure& structure,
                  const IdentifyOptions& refit, const MeasurementArtefact& artefact, ArtefactFit* out) {
  const FitData corrected = CorrectedData(fit, artefact);
  ModelStructure from = structure;
  from.SetValues(out->values);
  const IdentifyResult r = IdentifyWith([&] { return refit.family->MakeProblem(corrected, from, refit.model); },
                                        from, out->values, refit);
  out->values.clear();
  out->std.clear();
  for (const auto& p : r.parameters) {
    out->values.push_back(p.value);
    out->std.push_back(p.std);
  }
  out->chi_square = r.chi_square;
  out->scaled_at = r.starts[static_cast<std::size_t>(r.best_start)].scaled_at;
  out->model = std::make_unique<FittedModel>(corrected, *refit.family, from, base.model.model_harmonics,
                                             out->scaled_at, r.x, out->values);
}

// The whitened residuals of `data` against `model`'s phasors, in
// FitData::NumResiduals' order (step, channel, harmonic, real then imaginary).
Eigen::VectorXd WhitenedResiduals(const FitData& data, const std::vector<Eigen::MatrixXcd>& model) {
  Eigen::VectorXd r(data.NumResiduals());
  Eigen::Index row = 0;
  for (std::size_t i = 0; i < data.steps.size(); ++i)
    for (int c = 0; c < static_cast<int>(data.channels.size()); ++c)
      for (int k = 1; k <= data.num_fit_harmonics; ++k, row += 2)
        r.segment<2>(row) = Whitened(data.steps[i], c, k, model[i](c, k - 1) - data.steps[i].measured(c, k - 1));
  return r;
}

// The artefact's and the physics' uncertainties with both free: the joint
// fit's covariance, linearised at the rounds' optimum. The rounds' own are
// each conditional on the other, too narrow where a gain and the support's
// stiffnesses are correlated, and the artefact's scalar fit counts its
// channel's phasors as independent where a step's channels share the
// force's and the frequency's errors. Here the artefact's column, the
// whitened residuals' change per unit of its parameter with the physics
// held (central differences one conditional σ wide), joins the refit's
// reduced Jacobian, and the covariance is identify's, those shared errors
// and the residual model error included (parameter_covariance.h). Over
// 200 realisations a named gain covers 96.5 % at rms z 1.00.
void JointUncertainties(const FitData& fit, const MeasurementArtefact& artefact, ArtefactFit* out) {
  const double h = out->estimate.std;
  if (!(h > 0.0) || !out->model) return;
  FittedModel& model = *out->model;
  auto residuals_at = [&](double value) {
    MeasurementArtefact moved = artefact;
    moved.value = value;
    const FitData data = CorrectedData(fit, moved);
    return WhitenedResiduals(data, model.Phasors(data));
  };
  const Eigen::MatrixXd physics = model.problem->ReducedResidualJacobian(model.x);
  Eigen::MatrixXd j(physics.rows(), physics.cols() + 1);
  j << physics, (residuals_at(artefact.value + h) - residuals_at(artefact.value - h)) / (2.0 * h);
  const int dof = std::max(1, fit.NumResiduals() - static_cast<int>(j.cols()));
  std::vector<ModelErrorEstimate> errors;
  const Eigen::MatrixXd model_error = model.problem->ModelErrorInformation(model.x, j, dof, &errors);
  const double scale = errors.empty() ? std::max(1.0, out->chi_square / dof) : 1.0;
  const Eigen::VectorXd std =
      SandwichCovariance(j, model.problem->SharedErrorInformation(j), model_error, scale).total.diagonal().cwiseSqrt();
  for (std::size_t p = 0; p < out->std.size() && p < static_cast<std::size_t>(physics.cols()); ++p)
    out->std[p] = std[static_cast<Eigen::Index>(p)];
  out->estimate.std = std[physics.cols()];
}

// Block coordinate descent (header), accelerated: the rounds converge
// linearly (measured on a 5 % gain error: each removes ~2/3 of the distance
// to the joint optimum), so Aitken's Δ² extrapolates three successive
// estimates to where they head. The uncertainties are then the joint
// fit's (JointUncertainties).
ArtefactFit FitArtefact(const FitData& fit, const BaseFit& base, const ModelStructure& structure,
                        const IdentifyOptions& refit, MeasurementArtefact* artefact) {
  ArtefactFit out;
  out.values = structure.Values();
  const FittedModel* at = &base.model;
  std::vector<double> sequence;
  for (int round = 0; round < kMaxRounds; ++round) {
    if (artefact->kind == ArtefactKind::kOutlyingStep) {
      if (round > 0) break;
    } else {
      out.estimate = Estimate(fit, *at, *artefact);
      const double used = artefact->value;
      if (round > 0 && std::abs(out.estimate.value - used) <= kConvergedRelative * std::abs(out.estimate.value)) {
        out.estimate.value = used;
        break;
      }
      sequence.push_back(out.estimate.value);
      double next = out.estimate.value;
      const std::size_t n = sequence.size();
      if (n >= 3) {
        const double ratio = (sequence[n - 1] - sequence[n - 2]) / (sequence[n - 2] - sequence[n - 3]);
        if (ratio > 0.0 && ratio < 0.9) {
          next = sequence[n - 1] + (sequence[n - 1] - sequence[n - 2]) * ratio / (1.0 - ratio);
          sequence = {next};
        }
      }
      artefact->value = out.estimate.value = next;
    }
    RefitPhysics(fit, base, structure, refit, *artefact, &out);
    at = out.model.get();
    if (out.chi_square > kUnpromisingShare * base.summary.chi_square) break;
  }
  if (artefact->kind != ArtefactKind::kOutlyingStep) JointUncertainties(fit, *artefact, &out);
  return out;
}

// The clock error by its profile χ²(ε), the physics refitted at each ε,
// from the value the stated frequencies give. Block coordinate descent
// crawls here: ε and the support's k1 both move the resonance, so with the
// physics held the best ε stays where the physics put it (measured on
// paper_clock_error: after 8 rounds χ² 6.4·10⁴ of the base's 6.6·10⁴, where
// the joint optimum is at 21). The profile is minimised by parabolas through
// three refits; its curvature gives ε's standard uncertainty with the
// physics free (Δχ² = 1, scaled by max(1, reduced χ²)).
ArtefactFit FitClockError(const FitData& fit, const BaseFit& base, const ModelStructure& structure,
                          const IdentifyOptions& refit, MeasurementArtefact* artefact) {
  std::vector<double> warm = structure.Values();
  auto at = [&](double e) {
    ArtefactFit f;
    f.values = warm;
    RefitPhysics(fit, base, structure, refit, {.kind = ArtefactKind::kClockError, .value = e}, &f);
    f.estimate.value = e;
    return f;
  };
  double centre = artefact->value, spacing = 0.1 * std::abs(centre), sigma = 0.0;
  ArtefactFit mid = at(centre);
  warm = mid.values;
  // d(physics)/dε along the profile, from the last bracket.
  std::vector<double> slopes(mid.values.size(), 0.0);
  for (int iteration = 0; iteration < 4; ++iteration) {
    const ArtefactFit low = at(centre - spacing), high = at(centre + spacing);
    const double a = (low.chi_square + high.chi_square - 2.0 * mid.chi_square) / (2.0 * spacing * spacing);
    if (!(a > 0.0)) break;  // not a minimum's neighbourhood: keep the centre
    for (std::size_t j = 0; j < slopes.size() && j < low.values.size() && j < high.values.size(); ++j)
      slopes[j] = (high.values[j] - low.values[j]) / (2.0 * spacing);
    const int dof = std::max(1, fit.NumResiduals() - static_cast<int>(mid.values.size()) - 1);
    // Within the bracket's reach: beyond it the parabola is an extrapolation.
    const double offset = std::clamp(-(high.chi_square - low.chi_square) / (4.0 * a * spacing), -4.0 * spacing,
                                     4.0 * spacing);
    ArtefactFit next = at(centre + offset);
    if (next.chi_square <= mid.chi_square) {
      centre += offset;
      mid = std::move(next);
      warm = mid.values;
    }
    sigma = std::sqrt(std::max(1.0, mid.chi_square / dof) / a);
    if (std::abs(offset) <= std::max(0.1 * sigma, kConvergedRelative * std::abs(centre))) break;
    // Near the minimum a tighter bracket, still well above the refits' own scatter in χ².
    spacing = std::min(spacing, std::max(3.0 * sigma, 0.01 * std::abs(centre)));
  }
  // The physics' uncertainties at a fixed ε are conditional on it: with ε
  // free each takes the share ε's uncertainty moves it by (the marginal
  // variance of a linearised fit: σ² + (∂p/∂ε)²σ_ε²).
  for (std::size_t j = 0; j < mid.std.size() && j < slopes.size(); ++j)
    mid.std[j] = std::hypot(mid.std[j], slopes[j] * sigma);
  mid.estimate = {.value = centre, .std = sigma};
  artefact->value = centre;
  return mid;
}

std::string Description(ArtefactKind kind) {
  switch (kind) {
    case ArtefactKind::kSensorGain: return "a sensor whose calibration is off: it reads a fixed share high or low";
    case ArtefactKind::kSensorPhaseDelay:
      return "a sensor channel delayed against the force (another filter, sampled late)";
    case ArtefactKind::kSensorPosition: return "a sensor glued elsewhere than the test plan states";
    case ArtefactKind::kOutlyingStep:
      return "a step whose recording the model cannot follow (recorded before it settled, a glitch)";
    case ArtefactKind::kClockError:
      return "the acquisition's sample clock (or the stated sample rate) is off: every frequency reads (1 + ε) "
             "low or high";
  }
  return "";
}

// The artefact's parameter: name and unit (none for a step).
std::pair<std::string, std::string> Parameter(const FitData& fit, const MeasurementArtefact& artefact) {
  const std::string& channel = artefact.channel >= 0 ? fit.channels[static_cast<std::size_t>(artefact.channel)].channel : "";
  switch (artefact.kind) {
    case ArtefactKind::kSensorGain: return {"gain_error_" + channel, "1"};
    case ArtefactKind::kSensorPhaseDelay: return {"delay_" + channel, "s"};
    case ArtefactKind::kSensorPosition: return {"position_error_" + channel, "m"};
    case ArtefactKind::kClockError: return {"clock_error", "1"};
    case ArtefactKind::kOutlyingStep: break;
  }
  return {"", ""};
}

}  // namespace

CandidateRefits RefitMeasurementArtefacts(const FitData& fit, const FitData& validation, const BaseFit& base,
                                          const DiagnosisOptions& options, int num_physics_candidates,
                                          const RefitProgress& progress) {
  std::vector<MeasurementArtefact> artefacts;
  for (int c = 0; c < static_cast<int>(fit.channels.size()); ++c)
    for (ArtefactKind kind : {ArtefactKind::kSensorGain, ArtefactKind::kSensorPhaseDelay, ArtefactKind::kSensorPosition})
      artefacts.push_back({.kind = kind, .channel = c});
  // A clock error is exactly a rescaled beam and support (at ω(1 + ε) the
  // model's K/(1 + ε)², C/(1 + ε) and its accelerations read the same), so
  // only the frequencies campaign.json states, set on the generator's own
  // clock, tell it from a modulus error: it is tried only when they show it.
  const double stated_clock_error = ClockErrorFromStatedFrequencies(fit);
  if (std::abs(stated_clock_error) > kClockEvidence)
    artefacts.push_back({.kind = ArtefactKind::kClockError, .value = stated_clock_error});
  for (int i : SuspectSteps(fit, base.model)) artefacts.push_back({.kind = ArtefactKind::kOutlyingStep, .step = i});

  const int num_candidates = num_physics_candidates + static_cast<int>(artefacts.size());
  const int per_step = 2 * static_cast<int>(fit.channels.size()) * fit.num_fit_harmonics;
  const IdentifyOptions refit = CandidateRefitOptions(options, base.model.model_harmonics);
  // The beam's loss factor in every refit when the diagnosis fits it: a base
  // that a recording fault kept from fitting it (FitBase keeps the loss factor
  // only where it lowers the misfit) would otherwise leave the beam's damping
  // in c once the fault is corrected.
  ModelStructure structure = base.model.structure;
  int added = 0;
  const auto names = structure.Names();
  const LinearParameter loss = BeamLossFactor(options);
  if (options.fit_loss_factor && std::find(names.begin(), names.end(), loss.name) == names.end()) {
    std::vector<double> values = structure.Values();
    structure.linear.push_back(loss);
    values.push_back(options.loss_factor_start);
    structure.SetValues(values);
    added = 1;
  }
  // Each artefact's rounds of refits in a worker process (their models are
  // rebuilt here from the record, on the data corrected as in the worker).
  CandidateRefits out;
  out.outcomes.resize(artefacts.size());
  out.models.resize(artefacts.size());
  const int workers = options.num_workers > 0 ? options.num_workers
                                              : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  internal::RunTextJobsInWorkers(
      static_cast<int>(artefacts.size()), std::min<int>(workers, static_cast<int>(artefacts.size())),
      [&](int a) {
        MeasurementArtefact artefact = artefacts[static_cast<std::size_t>(a)];
        const auto started = std::chrono::steady_clock::now();
        ArtefactFit f = artefact.kind == ArtefactKind::kClockError ? FitClockError(fit, base, structure, refit, &artefact)
                                                                   : FitArtefact(fit, base, structure, refit, &artefact);
        CandidateRefit record{.chi_square = f.chi_square,
                              .seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(),
                              .values = f.values,
                              .std = f.std,
                              .scaled_at = f.scaled_at,
                              .x = std::vector<double>(f.model->x.data(), f.model->x.data() + f.model->x.size()),
                              .artefact_value = artefact.value,
                              .artefact_std = f.estimate.std};
        return CandidateRefitToText(record);
      },
      [&](int a, const std::string& text, const std::string& error, int done) {
        MeasurementArtefact artefact = artefacts[static_cast<std::size_t>(a)];
        const auto [parameter, unit] = Parameter(fit, artefact);
        CandidateOutcome outcome{.name = ArtefactName(fit, artefact),
                                 .description = Description(artefact.kind),
                                 .extra_parameters = parameter.empty() ? std::vector<std::string>{}
                                                                       : std::vector<std::string>{parameter},
                                 .test_dof = added + (artefact.kind == ArtefactKind::kOutlyingStep ? per_step : 1),
                                 .measurement = true};
        std::unique_ptr<FittedModel> model;
        try {
          if (!error.empty()) throw std::runtime_error(error);
          const CandidateRefit f = CandidateRefitFromText(text);
          if (f.values.size() != static_cast<std::size_t>(structure.NumParameters()) || f.std.size() != f.values.size())
            throw std::runtime_error("a recording check's record holds the wrong number of parameters");
          artefact.value = f.artefact_value;
          outcome.seconds = f.seconds;
          outcome.fit = SummarizeFit(structure, base.model.model_harmonics, f.chi_square, fit.NumResiduals(), f.values,
                                     f.std, outcome.test_dof - added);
          if (!parameter.empty())
            outcome.fit.parameters.push_back({.name = parameter,
                                              .unit = unit,
                                              .value = f.artefact_value,
                                              .std = f.artefact_std,
                                              .lower_95 = f.artefact_value - 1.96 * f.artefact_std,
                                              .upper_95 = f.artefact_value + 1.96 * f.artefact_std});
          outcome.status = RefitStatus::kRefitted;
          TestAgainstReference(base.summary.chi_square, base.summary, num_candidates, options, &outcome);
          model = std::make_unique<FittedModel>(
              CorrectedData(fit, artefact), *refit.family, structure, base.model.model_harmonics, f.scaled_at,
              Eigen::Map<const Eigen::VectorXd>(f.x.data(), static_cast<Eigen::Index>(f.x.size())), f.values);
          // The held-out channels were read on the same clock; the sensors'
          // faults are their own channels' only.
          const HeldOutCheck held_out =
              ValidateOnHeldOut(*model, artefact.kind == ArtefactKind::kClockError ? CorrectedData(validation, artefact)
                                                                                   : validation,
                                artefact.step);
          outcome.fit.held_out_chi_square = held_out.chi_square;
          outcome.fit.held_out_h1_relative_error = held_out.h1_relative_error;
          outcome.fit.held_out_num_residuals = held_out.num_residuals;
        } catch (const std::exception& e) {
          outcome.status_message = e.what();
        }
        outcome.rig_check = ArtefactRigCheck(fit, artefact);
        out.outcomes[static_cast<std::size_t>(a)] = std::move(outcome);
        out.models[static_cast<std::size_t>(a)] = std::move(model);
        if (progress)
          progress(done, static_cast<int>(artefacts.size()), out.outcomes[static_cast<std::size_t>(a)].name);
      });
  return out;
}

}  // namespace beamid::solver
