#include "solver/report/report_curves.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <map>
#include <numbers>
#include <stdexcept>


#include "signal/quantity.h"
#include "signal/first_harmonic_level.h"
#include "solver/estimation/fit_data.h"
#include "solver/estimation/sensor_backbone.h"
#include "solver/backbone/measured_backbone.h"
#include "solver/estimation/whitened_misfit.h"

namespace beamid::solver {
namespace {

using Complex = std::complex<double>;
constexpr double kTwoPi = 2.0 * std::numbers::pi;

// Phasor of the channel's quantity from a displacement phasor: (ikω)^order.
Complex FromDisplacement(Complex displacement, int order, double k_omega) {
  return DerivativeFactor(order, k_omega) * displacement;
}

std::vector<double> Positions(const std::vector<ReportChannel>& channels) {
  std::vector<double> out;
  for (const auto& c : channels) out.push_back(c.position_m);
  return out;
}

const IdentifiedStep* FindStep(const IdentifiedModel& model, const std::string& file) {
  for (const auto& s : model.steps)
    if (s.file == file) return &s;
  return nullptr;
}

std::vector<ReportChannel> Channels(const ResultFile& result, const signal::Campaign& campaign) {
  const std::vector<std::string>& fitted = result.model.fit_channels;
  std::vector<ReportChannel> out;
  for (const auto& s : campaign.sensors)
    out.push_back({.channel = s.channel, .position_m = s.position_m,
                   .derivative_order = signal::DerivativeOrder(s.quantity),
                   .si_unit = std::string(signal::SiUnit(s.quantity)),
                   .fitted = std::find(fitted.begin(), fitted.end(), s.channel) != fitted.end()});
  return out;
}

// An amplitude of displacement in the quantity of a channel of that
// derivative order, at one frequency.
double ToChannel(double displacement_m, double frequency_hz, int derivative_order) {
  return displacement_m * std::pow(kTwoPi * frequency_hz, derivative_order);
}

// The single-nonlinear-mode fit across levels, drawn over the measured range
// of amplitudes (nothing when the fit failed).
void SingleModeFitCurve(const MeasuredBackbone& measured, int derivative_order, MeasuredNonlinearMode& mode) {
  const SingleModeFit& fit = measured.fit;
  if (!fit.ok) return;
  mode.fit_form = fit.FormName();
  mode.damping_rate_trend = measured.damping_trend.verdict;
  mode.damping_rate_trend_z = measured.damping_trend.damping_rate_z;
  constexpr int kCurvePoints = 60;
  for (int k = 0; k <= kCurvePoints; ++k) {
    const double a = measured.min_amplitude_m +
                     (measured.max_amplitude_m - measured.min_amplitude_m) * k / static_cast<double>(kCurvePoints);
    const double f = fit.NaturalFrequency_rad_s(a) / kTwoPi;
    mode.fit.push_back({.amplitude = ToChannel(a, f, derivative_order),
                        .frequency_hz = f,
                        .frequency_std_hz = fit.NaturalFrequencyStd_rad_s(a) / kTwoPi,
                        .damping_ratio = fit.DampingRatio(a),
                        .damping_ratio_std = fit.DampingRatioStd(a)});
  }
}

// The measured phase-resonance points of every level at `reference`, set
// beside the model's backbone there (amplitudes of displacement).
void MeasuredPhaseResonance(const signal::PhasorSet& phasors, const ReportChannel& reference,
                            const std::vector<SensorBackbonePoint>& model_backbone, ReportCurves& curves) {
  MeasuredBackbone measured;
  try {
    measured = AnalyseMeasuredBackbone(signal::FirstHarmonicLevels(phasors, reference.channel, "the phasors"));
  } catch (const std::exception& error) {
    curves.phase_resonance_warnings.push_back(error.what());
    return;
  }
  // The levels' own notes go beside their points; the rest are warnings.
  for (const auto& warning : measured.warnings)
    if (std::none_of(measured.levels.begin(), measured.levels.end(), [&](const LevelResonance& level) {
          return level.quadrature_frequency_hz.valid && !level.quadrature_note.empty() &&
                 warning.ends_with(level.quadrature_note);
        }))
      curves.phase_resonance_warnings.push_back(warning);
  const auto to_channel = [&](double displacement_m, double frequency_hz) {
    return ToChannel(displacement_m, frequency_hz, reference.derivative_order);
  };
  MeasuredNonlinearMode& mode = curves.measured_mode;
  for (const auto& level : measured.levels) {
    if (!level.quadrature_frequency_hz.valid) continue;
    auto value = [](const Estimate& e) { return e.valid ? e.value : NAN; };
    auto std = [](const Estimate& e) { return e.valid ? e.std : NAN; };
    mode.damping.push_back({.level = level.label,
                            .amplitude = to_channel(level.quadrature_amplitude_m.value, level.quadrature_frequency_hz.value),
                            .quadrature = value(level.quadrature_damping_ratio),
                            .quadrature_std = std(level.quadrature_damping_ratio),
                            .local = value(level.local_damping_ratio),
                            .local_std = std(level.local_damping_ratio),
                            .half_power = value(level.half_power_damping_ratio),
                            .half_power_std = std(level.half_power_damping_ratio)});
    const double f = level.quadrature_frequency_hz.value, f_std = level.quadrature_frequency_hz.std;
    const double a = level.quadrature_amplitude_m.value, a_std = level.quadrature_amplitude_m.std;
    // σ of the difference: the point's frequency and, through the backbone's slope, its amplitude.
    const double model_f = BackboneFrequencyAt_hz(model_backbone, a);
    const double slope = (BackboneFrequencyAt_hz(model_backbone, 1.01 * a) -
                          BackboneFrequencyAt_hz(model_backbone, 0.99 * a)) / (0.02 * a);
    const double sigma = std::hypot(f_std, std::isfinite(slope) ? slope * a_std : 0.0);
    curves.phase_resonance.push_back({.level = level.label,
                                      .frequency_hz = f,
                                      .frequency_std_hz = f_std,
                                      .amplitude = to_channel(a, f),
                                      .amplitude_std = to_channel(a_std, f),
                                      .damping_ratio = level.quadrature_damping_ratio.value,
                                      .damping_ratio_std = level.quadrature_damping_ratio.std,
                                      .model_frequency_hz = model_f,
                                      .z = (f - model_f) / sigma,
                                      .note = level.quadrature_note});
  }
  SingleModeFitCurve(measured, reference.derivative_order, mode);
}

using Progress = std::function<void(double, const std::string&)>;

void Report(const Progress& progress, double fraction, const std::string& what) {
  if (progress) progress(fraction, what);
}

// The backbone and the phase resonances are drawn at the first fitted
// channel: that is where the fit has the most say about the model.
int ReferenceChannel(const std::vector<ReportChannel>& channels) {
  for (std::size_t c = 0; c < channels.size(); ++c)
    if (channels[c].fitted) return static_cast<int>(c);
  return 0;
}

// Levels in campaign order (the order the test was run in).
std::vector<std::string> LevelNames(const signal::PhasorSet& phasors) {
  std::vector<std::string> names;
  for (const auto& step : phasors.steps)
    if (std::find(names.begin(), names.end(), step.level) == names.end()) names.push_back(step.level);
  return names;
}

struct FrequencySpan {
  double min_hz = 1e300, max_hz = 0.0;
};

// A level's measured points and mean force; `span` is the range of its steps,
// which the model's curve must cover.
LevelCurves MeasuredLevel(const signal::PhasorSet& phasors, const std::vector<ReportChannel>& channels,
                          const std::string& name, FrequencySpan& span) {
  LevelCurves level{.level = name};
  double force_sum = 0.0;
  for (const auto& step : phasors.steps) {
    if (step.level != level.level) continue;
    MeasuredPoint point{.frequency_hz = step.frequency_hz, .amplitude = {}, .file = step.file};
    if (step.quality.unsettled) point.flag = "recorded before it settled";
    const Complex force = step.force.Harmonic(1).value;  // real and positive: the phase reference
    point.force_amplitude_N = std::abs(force);
    for (const auto& channel : channels) {
      const signal::ChannelPhasors* p = step.Find(channel.channel);
      point.amplitude.push_back(p ? p->Harmonic(1).Amplitude() : std::nan(""));
      point.phase_deg.push_back(p ? DisplacementPhaseDeg(p->Harmonic(1).value / force, channel.derivative_order)
                                  : std::nan(""));
      std::vector<double> higher;
      for (int k = 2; k <= kReportHarmonics; ++k)
        higher.push_back(p && static_cast<int>(p->harmonics.size()) >= k ? p->Harmonic(k).Amplitude() : std::nan(""));
      point.higher_harmonics.push_back(std::move(higher));
    }
    force_sum += std::abs(force);
    span.min_hz = std::min(span.min_hz, step.frequency_hz);
    span.max_hz = std::max(span.max_hz, step.frequency_hz);
    level.measured.push_back(std::move(point));
  }
  level.force_amplitude_N = force_sum / static_cast<double>(level.measured.size());
  return level;
}

// The model's frequency response under a pure sine of the level's mean force,
// a little wider than the measured span so that its ends show (the model's
// family traces it).
void TraceModelCurve(const IdentifiedModel& model, const std::vector<ReportChannel>& channels,
                     const std::vector<double>& positions, const FrequencySpan& span, int max_points,
                     const std::function<void(double)>& on_fraction, LevelCurves& level) {
  const double margin = 0.01 * (span.max_hz - span.min_hz) + 1e-3 * span.min_hz;
  const ModelResponse response =
      model.family->FrequencyResponse(model, level.force_amplitude_N, kTwoPi * (span.min_hz - margin),
                                      kTwoPi * (span.max_hz + margin), max_points, positions, on_fraction);
  level.model_complete = response.reached_end;
  level.model_message = response.message;
  for (const auto& p : response.points) {
    ModelCurvePoint point{.frequency_hz = p.omega_rad_s / kTwoPi, .stable = p.stable};
    for (std::size_t c = 0; c < channels.size(); ++c) {
      const Eigen::VectorXcd y = p.displacement_m.row(static_cast<Eigen::Index>(c));
      const int order = channels[c].derivative_order;
      const Complex x1 = FromDisplacement(y[1], order, p.omega_rad_s);
      point.amplitude.push_back(std::abs(x1));
      point.phase_deg.push_back(DisplacementPhaseDeg(x1 / level.force_amplitude_N, order));
      std::vector<double> higher;
      for (int k = 2; k <= kReportHarmonics; ++k)
        higher.push_back(k < y.size() ? std::abs(FromDisplacement(y[k], order, k * p.omega_rad_s)) : std::nan(""));
      point.higher_harmonics.push_back(std::move(higher));
    }
    level.model.push_back(std::move(point));
  }
}

// Measured and model curves of every level; the first half of the progress.
std::vector<LevelCurves> FrequencyResponses(const IdentifiedModel& model, const signal::PhasorSet& phasors,
                                            const std::vector<ReportChannel>& channels,
                                            const std::vector<std::string>& level_names,
                                            const ReportCurveOptions& options, const Progress& progress) {
  const std::vector<double> positions = Positions(channels);
  std::vector<LevelCurves> levels;
  for (std::size_t l = 0; l < level_names.size(); ++l) {
    FrequencySpan span;
    LevelCurves level = MeasuredLevel(phasors, channels, level_names[l], span);
    Report(progress, 0.5 * l / level_names.size(), "frequency response of level " + level.level);
    TraceModelCurve(model, channels, positions, span, options.frc_max_points,
                    [&](double fraction) {
                      Report(progress, 0.5 * (l + fraction) / level_names.size(), "frequency response");
                    },
                    level);
    levels.push_back(std::move(level));
  }
  return levels;
}

// The model's backbone at the reference sensor over the identified steps'
// range of amplitudes (the family's; empty when there is none or it fails:
// the page is still worth having without it), also stored in the channel's
// quantity.
std::vector<SensorBackbonePoint> ModelBackbone(const IdentifiedModel& model, const ReportChannel& reference,
                                               int num_points, ReportCurves& curves) {
  std::vector<SensorBackbonePoint> model_backbone;
  try {
    model_backbone = model.family->BackboneAtSensor(model, reference.position_m, num_points);
  } catch (const std::runtime_error& error) {
    curves.phase_resonance_warnings.push_back(std::string("the model's backbone: ") + error.what());
  }
  for (const auto& p : model_backbone)
    curves.backbone.push_back(
        {p.frequency_hz, ToChannel(p.amplitude_m, p.frequency_hz, reference.derivative_order), ""});
  return model_backbone;
}

// The level's step of largest predicted acceleration (|Y_1|·f² ∝ it), where
// the nonlinearity shows most; null when the level has no predicted step.
const PredictedStep* LargestResponse(const std::vector<PredictedStep>& predicted, const std::string& level) {
  const PredictedStep* best = nullptr;
  for (const auto& p : predicted)
    if (p.level == level && (!best || std::abs(p.displacement_m[1]) * p.frequency_hz * p.frequency_hz >
                                          std::abs(best->displacement_m[1]) * best->frequency_hz * best->frequency_hz))
      best = &p;
  return best;
}

// The predicted history beside the recording's harmonics, resynthesised at
// the prediction's times as acceleration.
TimeHistory PredictedBesideMeasured(const PredictedStep& best, const signal::ChannelPhasors& channel,
                                    int derivative_order, const std::string& level) {
  TimeHistory history{.level = level, .frequency_hz = best.frequency_hz};
  const double omega = kTwoPi * best.frequency_hz;
  for (Eigen::Index n = 0; n < best.time_s.size(); ++n) {
    const double t = best.time_s[n];
    double a = 0.0;
    for (const auto& harmonic : channel.harmonics) {
      const double kw = harmonic.harmonic * omega;
      const Complex acc = DerivativeFactor(2 - derivative_order, kw) * harmonic.value;  // to acceleration
      a += std::real(acc * std::polar(1.0, kw * t));
    }
    history.time_s.push_back(t);
    history.predicted.push_back(best.acceleration_m_s2[n]);
    history.predicted_std.push_back(best.acceleration_std_m_s2[n]);
    history.measured.push_back(a);
  }
  return history;
}

// Predicted and measured histories at the first held-out channel, one per level.
void HeldOutHistories(const ResultFile& result, const signal::Campaign& campaign, const signal::PhasorSet& phasors,
                      const IdentifiedModel& model, const std::vector<std::string>& level_names,
                      int samples_per_period, ReportCurves& curves) {
  if (result.validation.empty()) return;
  curves.held_out_channel = result.validation.front().channel;
  const auto it = std::find_if(curves.channels.begin(), curves.channels.end(),
                               [&](const ReportChannel& c) { return c.channel == curves.held_out_channel; });
  if (it == curves.channels.end())
    throw std::invalid_argument("the held-out channel '" + curves.held_out_channel +
                                "' of the result is not a sensor of campaign " + campaign.folder.string());
  const std::vector<PredictedStep> predicted = PredictAt(model, it->position_m, samples_per_period);
  for (const auto& name : level_names) {
    const PredictedStep* best = LargestResponse(predicted, name);
    if (!best) continue;
    const signal::StepPhasors* measured = nullptr;
    for (const auto& s : phasors.steps)
      if (s.file == best->file) measured = &s;
    const signal::ChannelPhasors* channel = measured ? measured->Find(curves.held_out_channel) : nullptr;
    if (!channel) continue;
    curves.time_histories.push_back(PredictedBesideMeasured(*best, *channel, it->derivative_order, name));
  }
}

// Residual map of the fitted channels, from the fitted states (the model's
// family rebuilds their sensor phasors); NaN where a step has no identified
// state.
ResidualMap Residuals(const ResultFile& result, const signal::Campaign& campaign, const signal::PhasorSet& phasors,
                      const IdentifiedModel& model, const std::vector<ReportChannel>& channels) {
  std::vector<std::string> fitted;
  for (const auto& c : channels)
    if (c.fitted) fitted.push_back(c.channel);
  const int k_fit = result.model.num_fit_harmonics;
  const FitData fit = MakeFitData(
      campaign, phasors,
      {.channels = fitted, .num_fit_harmonics = k_fit, .uncertainty = result.model.phasor_uncertainty});
  std::vector<double> fit_positions;
  for (const auto& c : fit.channels) fit_positions.push_back(c.position_m);
  const std::vector<Eigen::MatrixXcd> fitted_y = model.family->FittedDisplacements(model, fit_positions);
  ResidualMap residuals;
  for (const auto& c : fit.channels)
    for (int k = 1; k <= k_fit; ++k) residuals.rows.push_back(c.channel + " h" + std::to_string(k));
  residuals.whitened_norm = Eigen::MatrixXd::Constant(static_cast<Eigen::Index>(residuals.rows.size()),
                                                      static_cast<Eigen::Index>(fit.steps.size()), std::nan(""));
  for (std::size_t i = 0; i < fit.steps.size(); ++i) {
    const FitStep& s = fit.steps[i];
    residuals.step_level.push_back(s.level);
    residuals.step_frequency_hz.push_back(s.omega_rad_s / kTwoPi);
    const IdentifiedStep* identified = FindStep(model, s.file);
    if (!identified) continue;
    const Eigen::MatrixXcd& y = fitted_y[static_cast<std::size_t>(identified - model.steps.data())];
    for (std::size_t c = 0; c < fit.channels.size(); ++c)
      for (int k = 1; k <= k_fit; ++k) {
        const Complex misfit = FromDisplacement(y(static_cast<Eigen::Index>(c), k), fit.channels[c].derivative_order,
                                                k * identified->omega_rad_s) -
                               s.measured(static_cast<Eigen::Index>(c), k - 1);
        residuals.whitened_norm(static_cast<Eigen::Index>(c * k_fit + k - 1), static_cast<Eigen::Index>(i)) =
            Whitened(s, static_cast<int>(c), k, misfit).norm();
      }
  }
  return residuals;
}

}  // namespace

LevelCurves MeasuredLevelCurves(const signal::PhasorSet& phasors, const std::vector<ReportChannel>& channels,
                                const std::string& level) {
  FrequencySpan span;
  return MeasuredLevel(phasors, channels, level, span);
}

double DisplacementPhaseDeg(Complex response_per_force, int derivative_order) {
  double phase = std::arg(response_per_force) * 180.0 / std::numbers::pi - 90.0 * derivative_order;
  phase = std::fmod(phase, 360.0);
  if (phase <= -180.0) phase += 360.0;
  if (phase > 180.0) phase -= 360.0;
  return phase;
}

ReportCurves ComputeReportCurves(const ResultFile& result, const signal::Campaign& campaign,
                                 const signal::PhasorSet& phasors, const ReportCurveOptions& options,
                                 const std::function<void(double, const std::string&)>& progress) {
  const IdentifiedModel model = ToIdentifiedModel(result);
  ReportCurves curves;
  curves.channels = Channels(result, campaign);
  curves.reference_channel = ReferenceChannel(curves.channels);
  const std::vector<std::string> level_names = LevelNames(phasors);
  curves.levels = FrequencyResponses(model, phasors, curves.channels, level_names, options, progress);
  if (result.robust_fit && result.robust_fit->applied)
    for (auto& level : curves.levels)
      for (auto& point : level.measured)
        for (const auto& outlier : result.robust_fit->outliers)
          if (outlier.file == point.file)
            point.flag += std::string(point.flag.empty() ? "" : "; ") + "left out by the robust fit";

  Report(progress, 0.5, "backbone");
  const ReportChannel& reference = curves.channels[static_cast<std::size_t>(curves.reference_channel)];
  const std::vector<SensorBackbonePoint> model_backbone =
      ModelBackbone(model, reference, options.backbone_points, curves);
  MeasuredPhaseResonance(phasors, reference, model_backbone, curves);

  Report(progress, 0.6, "prediction at the held-out channel");
  HeldOutHistories(result, campaign, phasors, model, level_names, options.samples_per_period, curves);

  Report(progress, 0.9, "residual map");
  curves.residuals = Residuals(result, campaign, phasors, model, curves.channels);
  Report(progress, 1.0, "done");
  return curves;
}

}  // namespace beamid::solver
