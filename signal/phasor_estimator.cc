#include "signal/phasor_estimator.h"

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <vector>

#include "hb/option_checks.h"
#include "signal/input_error.h"
#include "signal/internal/text.h"
#include "signal/settling_uncertainty.h"

namespace beamid::signal {
namespace {

using internal::FormatNumber;

}  // namespace

std::vector<ChannelPhasors> ReferencePhasors(const HarmonicFit& fit, std::size_t reference_channel,
                                             const std::vector<const ChannelSpec*>& specs) {
  const ChannelFit& reference = fit.channels[reference_channel];
  const std::complex<double> f1 = reference.phasors(0);
  const double phi = std::arg(f1);
  const Eigen::Vector2d w(-std::sin(phi), std::cos(phi));
  const double phase_variance = w.dot(reference.covariances[0] * w) / std::norm(f1);

  std::vector<ChannelPhasors> result;
  for (std::size_t c = 0; c < fit.channels.size(); ++c) {
    const ChannelFit& channel_fit = fit.channels[c];
    ChannelPhasors channel;
    channel.channel = specs[c]->channel;
    channel.quantity = specs[c]->quantity;
    channel.position_m = specs[c]->position_m;
    channel.mean = channel_fit.mean;
    channel.noise_rms = channel_fit.residual_rms;
    double signal_power = 0.0, harmonic_power = 0.0;
    for (int k = 1; k <= fit.num_harmonics; ++k) {
      const std::complex<double> x = channel_fit.phasors(k - 1);
      HarmonicPhasor phasor;
      phasor.harmonic = k;
      phasor.value = x * std::polar(1.0, -k * phi);
      const Eigen::Matrix2d& cx = channel_fit.covariances[static_cast<std::size_t>(k - 1)];
      if (c == reference_channel && k == 1) {
        const Eigen::Vector2d u(std::cos(phi), std::sin(phi));
        phasor.value = std::abs(x);
        Eigen::Matrix2d cz = Eigen::Matrix2d::Zero();
        cz(0, 0) = u.dot(cx * u);
        phasor.SetCovariance(cz);
      } else {
        const Eigen::Matrix2d r = Eigen::Rotation2Dd(-k * phi).toRotationMatrix();
        const Eigen::Vector2d v(phasor.value.imag(), -phasor.value.real());
        phasor.SetCovariance(r * cx * r.transpose() + k * k * phase_variance * v * v.transpose());
      }
      signal_power += 0.5 * std::norm(x);
      if (k >= 2) harmonic_power += std::norm(x);
      channel.harmonics.push_back(phasor);
    }
    channel.thd = std::abs(channel_fit.phasors(0)) > 0.0 ? std::sqrt(harmonic_power) / std::abs(channel_fit.phasors(0)) : 0.0;
    const double noise_power = channel_fit.residual_rms * channel_fit.residual_rms;
    channel.snr_db = noise_power > 0.0 ? 10.0 * std::log10(signal_power / noise_power) : 300.0;
    result.push_back(std::move(channel));
  }
  return result;
}

void PhasorEstimatorOptions::Validate() const {
  using namespace option_checks;
  RequireInRange("PhasorEstimatorOptions.num_harmonics", num_harmonics, 1, kMaxHarmonics);
  // The frequency estimator runs with H harmonics whatever frequency.num_harmonics says.
  FrequencyEstimatorOptions used = frequency;
  used.num_harmonics = num_harmonics;
  used.Validate();
  steady_state.Validate();
  RequireNonNegative("PhasorEstimatorOptions.warn_snr_db", warn_snr_db);
  RequireNonNegative("PhasorEstimatorOptions.warn_frequency_offset_rel", warn_frequency_offset_rel);
  RequireInRange("PhasorEstimatorOptions.warn_transient_fraction", warn_transient_fraction, 0.0, 1.0);
  RequireNonNegative("PhasorEstimatorOptions.min_force_snr", min_force_snr);
  RequireNonNegative("PhasorEstimatorOptions.note_drift_relative", note_drift_relative);
  RequireNonNegative("PhasorEstimatorOptions.min_converter_steps", min_converter_steps);
  driven_span.Validate();
  free_decay.Validate();
  transient.Validate();
}

StepPhasors EstimateStepPhasors(const Recording& recording, const Campaign& campaign, const Step& step,
                                const PhasorEstimatorOptions& options) {
  options.Validate();
  // The recording's channels in its column order: campaign.json's, less
  // those of no use to the analysis that its file could not give
  // (signal/recording.h).
  std::vector<const ChannelSpec*> specs;
  for (const std::string& name : recording.channels)
    for (const ChannelSpec* spec : campaign.Channels())
      if (spec->channel == name) specs.push_back(spec);
  if (specs.size() != recording.channels.size() || specs.empty() ||
      recording.channels.front() != campaign.excitation.channel ||
      recording.samples.cols() != static_cast<Eigen::Index>(specs.size()))
    throw std::invalid_argument(recording.file + ": the recording's channels do not follow campaign.json's");
  const double fs = recording.sample_rate_hz;
  const std::string& force_name = campaign.excitation.channel;
  const std::string unit(SiUnit(campaign.excitation.quantity));
  FrequencyEstimatorOptions frequency_options = options.frequency;
  frequency_options.num_harmonics = options.num_harmonics;

  // 0. Only the part during which the excitation runs.
  const DrivenSpan span = FindDrivenSpan(recording.samples.col(0), fs, step.frequency_hz, options.driven_span);
  const auto driven = recording.samples.middleRows(span.first_sample, span.end_sample - span.first_sample);
  const Eigen::Index n = driven.rows();
  if (static_cast<double>(n) < options.steady_state.min_steady_periods * fs / step.frequency_hz)
    throw InputError(recording.file, force_name, span.Describe(fs, recording.NumSamples()) + ", too short for a step",
                     "record with the excitation running until the end of the record");

  // 1. Frequency on the last half, assumed steady.
  const Eigen::Index half = n / 2;
  FrequencyEstimate first;
  try {
    first = EstimateFrequency(driven.col(0).tail(half), fs, step.frequency_hz, frequency_options);
  } catch (const std::invalid_argument& e) {
    throw InputError(recording.file, force_name, e.what(), "check the step's frequency_Hz and the sample rate");
  } catch (const std::runtime_error& e) {
    // No stable sine to lock on: the force column holds no excitation.
    throw InputError(recording.file, force_name,
                     "no excitation near the nominal " + FormatNumber(step.frequency_hz) + " Hz (" + e.what() + ")",
                     "check which column holds the excitation and the step's frequency_Hz");
  }
  if (first.fundamental_amplitude < options.min_force_snr * first.fundamental_std)
    throw InputError(recording.file, force_name,
                     "no excitation near the nominal " + FormatNumber(step.frequency_hz) +
                         " Hz (excitation fundamental " + FormatNumber(first.fundamental_amplitude) + " " + unit +
                         ", noise " + FormatNumber(first.fundamental_std) + " " + unit + ")",
                     "check which column holds the excitation and the step's frequency_Hz");

  // 2. Steady state, judged on the channels the analysis uses: a rattling
  // accelerometer nobody fits must not cut every step's record.
  std::vector<Eigen::Index> judged;
  std::vector<std::string> judged_names;
  for (std::size_t c = 0; c < recording.channels.size(); ++c)
    if (campaign.Use(recording.channels[c]) == ChannelUse::kUsed) {
      judged.push_back(static_cast<Eigen::Index>(c));
      judged_names.push_back(recording.channels[c]);
    }
  const SteadyState steady = DetectSteadyState(driven(Eigen::all, judged), judged_names, fs, first.frequency_hz,
                                               options.num_harmonics, recording.file, options.steady_state);
  const auto steady_samples = driven.bottomRows(n - steady.first_sample);

  // 3–4. Frequency and phasors on the steady part.
  const FrequencyEstimate frequency =
      EstimateFrequency(steady_samples.col(0), fs, step.frequency_hz, frequency_options, first.frequency_hz);
  HarmonicFit fit = FitHarmonics(steady_samples, fs, frequency.frequency_hz, options.num_harmonics);
  std::vector<bool> used;
  for (const auto* spec : specs) used.push_back(campaign.Use(spec->channel) == ChannelUse::kUsed);
  // The ringing is judged on the responses: the force is the reference.
  std::vector<bool> rings = used;
  rings.front() = false;
  const SettlingTransient ringing = options.settling_transient
                                        ? RemoveSettlingTransient(steady_samples, fs, rings, fit, options.transient)
                                        : SettlingTransient{};

  // 5. Reference and pack.
  std::vector<ChannelPhasors> channels = ReferencePhasors(fit, 0, specs);
  std::vector<std::pair<std::string, std::string>> coarse;  // channel, what to say
  for (std::size_t c = 0; c < channels.size(); ++c) {
    // A channel resolved by a few converter steps errs by a fraction of a
    // step whatever the record's length: the error is the quantiser's,
    // locked to the signal, not noise that averages out. Its variance
    // step²/12 per component is added to what the residual shows.
    const ConverterResolution resolution = ResolutionOf(recording.samples.col(static_cast<Eigen::Index>(c)));
    if (resolution.step <= 0.0 || resolution.num_steps >= options.min_converter_steps) continue;
    const double variance = resolution.step * resolution.step / 12.0;
    for (auto& harmonic : channels[c].harmonics)
      harmonic.SetCovariance(harmonic.Covariance() + variance * Eigen::Matrix2d::Identity());
    coarse.emplace_back(channels[c].channel, "channel '" + channels[c].channel + "' spans only " +
                     FormatNumber(std::round(resolution.num_steps)) + " converter steps of " +
                     FormatNumber(resolution.step) + " " + std::string(SiUnit(channels[c].quantity)) +
                     ": its phasors' uncertainty includes the quantisation error (±" +
                     FormatNumber(std::sqrt(variance)) + " per component); a smaller input range resolves it");
  }
  StepPhasors result;
  result.file = step.file;
  result.level = step.level;
  result.nominal_frequency_hz = step.frequency_hz;
  result.frequency_hz = frequency.frequency_hz;
  result.frequency_std_hz = frequency.std_hz;
  result.force = std::move(channels.front());
  result.responses.assign(std::make_move_iterator(channels.begin() + 1), std::make_move_iterator(channels.end()));

  if (span.stops_early && span.end_sample < recording.NumSamples())
    for (std::size_t c = 1; c < specs.size(); ++c)
      if (used[c]) {
        FreeDecay decay = AnalyseFreeDecay(recording.samples.col(static_cast<Eigen::Index>(c)).tail(
                                               recording.NumSamples() - span.end_sample),
                                           fs, static_cast<double>(span.end_sample) / fs, frequency.frequency_hz,
                                           specs[c]->channel, options.free_decay);
        if (!decay.points.empty()) result.free_decays.push_back(std::move(decay));
      }

  StepQuality& quality = result.quality;
  for (auto& [channel, text] : coarse)
    (campaign.Use(channel) == ChannelUse::kIgnored ? quality.notes : quality.warnings).push_back(std::move(text));
  quality.settled_after_s = static_cast<double>(span.first_sample + steady.first_sample) / fs;
  if (const std::string stop = span.Describe(fs, recording.NumSamples()); !stop.empty())
    quality.warnings.push_back(stop);
  if (!steady.drift_channel.empty())
    (steady.drift_relative > options.note_drift_relative ? quality.warnings : quality.notes).push_back(steady.reason);
  quality.analysed_duration_s = static_cast<double>(steady_samples.rows()) / fs;
  quality.settling = steady.reason;
  if (ringing.removed) {
    quality.ringing = true;
    quality.ringing_relative = ringing.amplitude_relative;
    quality.ringing_decay_rate_per_s = ringing.decay_rate_per_s;
    quality.ringing_beat_hz = ringing.beat_hz;
    quality.ringing_channel = specs[ringing.channel]->channel;
    const auto three_digits = [](double value) {
      char buffer[32];
      std::snprintf(buffer, sizeof buffer, "%.3g", value);
      return std::string(buffer);
    };
    quality.warnings.push_back(
        "still ringing from the frequency step: a free vibration beating " + three_digits(ringing.beat_hz) +
        " Hz from the drive and decaying at " + three_digits(ringing.decay_rate_per_s) + " 1/s was " +
        three_digits(100.0 * ringing.amplitude_relative) + " % of '" + quality.ringing_channel +
        "' at the start of the analysed part; it was fitted out and the phasors' uncertainty includes the "
        "separation (wait longer after each frequency step)");
  }
  quality.snr_db = result.force.snr_db;
  std::vector<const ChannelPhasors*> all{&result.force};
  for (const auto& response : result.responses) all.push_back(&response);
  for (const auto* channel : all) {
    if (campaign.Use(channel->channel) == ChannelUse::kUsed) quality.snr_db = std::min(quality.snr_db, channel->snr_db);
    if (channel->snr_db < options.warn_snr_db)
      (campaign.Use(channel->channel) == ChannelUse::kIgnored ? quality.notes : quality.warnings).push_back("channel '" + channel->channel + "': SNR " +
                                 FormatNumber(std::round(channel->snr_db * 10.0) / 10.0) + " dB is below " +
                                 FormatNumber(options.warn_snr_db) + " dB");
  }
  const double offset = frequency.frequency_hz / step.frequency_hz - 1.0;
  if (std::abs(offset) > options.warn_frequency_offset_rel)
    quality.warnings.push_back("estimated frequency " + FormatNumber(frequency.frequency_hz) + " Hz is " +
                               FormatNumber(std::round(offset * 1e4) / 100.0) + " % from the nominal " +
                               FormatNumber(step.frequency_hz) + " Hz");
  if (fit.num_harmonics < options.num_harmonics)
    quality.warnings.push_back("only harmonics 1.." + std::to_string(fit.num_harmonics) +
                               " lie below the Nyquist frequency " + FormatNumber(0.5 * fs) + " Hz");
  if (static_cast<double>(steady.first_sample) > options.warn_transient_fraction * static_cast<double>(n)) {
    std::string text = "the transient took " +
                       FormatNumber(std::round(100.0 * static_cast<double>(steady.first_sample) / n)) + " % of the " +
                       (span.stops_early || span.starts_late ? "driven part" : "record") + "; record longer";
    // What is left of the transient is an error of the phasors, which the
    // fit must weigh. A steady state with the drift model is raised too: the
    // transient that made the periodic model drop so much is still there (the
    // drift model bends to part of it), and where a channel only drifts
    // linearly its halves differ by the drift, which makes the raise
    // conservative there, never overconfident.
    std::vector<ChannelPhasors> all_channels{result.force};
    all_channels.insert(all_channels.end(), result.responses.begin(), result.responses.end());
    const SettlingUncertainty unsettled =
        options.settling_uncertainty ? AddSettlingUncertainty(steady_samples, fs, frequency.frequency_hz,
                                                              fit.num_harmonics, specs, used, all_channels)
                                     : SettlingUncertainty{};
    if (unsettled.raised) {
      result.force = std::move(all_channels.front());
      std::move(all_channels.begin() + 1, all_channels.end(), result.responses.begin());
      quality.unsettled = true;
      quality.unsettled_change_relative = unsettled.change_relative;
      quality.unsettled_channel = unsettled.channel;
      text += "; what is left of it changes '" + unsettled.channel + "' by " +
              FormatNumber(std::round(unsettled.change_relative * 1e4) / 100.0) +
              " % between the halves of the analysed part, which its phasors' uncertainty now includes";
    }
    quality.warnings.push_back(std::move(text));
  }
  return result;
}

}  // namespace beamid::signal
