#include "signal/uff_recording.h"

#include <cmath>
#include <optional>

#include "signal/input_error.h"
#include "signal/internal/text.h"

namespace beamid::signal {
namespace {

using internal::FormatNumber;

// Specific data types of records 8..11 that name a quantity.
std::optional<Quantity> QuantityOfDataType(int data_type) {
  switch (data_type) {
    case 8: return Quantity::kDisplacement;
    case 11: return Quantity::kVelocity;
    case 12: return Quantity::kAcceleration;
    case 9:
    case 13: return Quantity::kForce;
    default: return std::nullopt;
  }
}

// The spellings of acquisition systems for the units the campaign format
// accepts ("m/s2", "m/s**2", "G", "mm/sec", …) in the campaign's words.
std::string CanonicalUnit(std::string unit) {
  std::string compact;
  for (char c : unit)
    if (c != ' ') compact += c;
  if (compact == "m/s2" || compact == "m/s**2" || compact == "m/s\xC2\xB2" || compact == "ms^-2" ||
      compact == "m/s/s" || compact == "m/sec^2" || compact == "m/sec2")
    return "m/s^2";
  if (compact == "G") return "g";
  if (compact == "mm/sec") return "mm/s";
  if (compact == "m/sec") return "m/s";
  return compact;
}

double AbscissaToSeconds(const Uff58Dataset& dataset, const std::string& source) {
  const Uff58Axis& axis = dataset.abscissa;
  if (axis.data_type != 0 && axis.data_type != 1 && axis.data_type != 17)
    throw InputError(source, "",
                     dataset.Describe() + ": the abscissa's specific data type is " +
                         std::to_string(axis.data_type) + ", not time (17)",
                     "export the time histories, with time as abscissa");
  if (axis.unit.empty() || axis.unit == "s" || axis.unit == "sec") return 1.0;
  if (axis.unit == "ms") return 1e-3;
  throw InputError(source, "", dataset.Describe() + ": abscissa unit '" + axis.unit + "' is not a time unit",
                   "export time in s (or ms)");
}

}  // namespace

Recording RecordingFromUff58(const std::vector<Uff58Dataset>& datasets, const Campaign& campaign, const Step& step,
                             const std::string& source, const RecordingChecks& checks) {
  const auto channels = campaign.Channels();
  std::vector<const Uff58Dataset*> matched(channels.size(), nullptr);
  std::string found;
  for (const Uff58Dataset& dataset : datasets) {
    const std::string candidates[] = {dataset.id_lines[0], dataset.response_entity, dataset.NodeDirection()};
    std::optional<std::size_t> channel;
    for (const std::string& candidate : candidates) {
      std::string name = candidate;
      while (!name.empty() && name.front() == ' ') name.erase(name.begin());
      for (std::size_t c = 0; c < channels.size() && !channel; ++c)
        if (!name.empty() && channels[c]->channel == name) channel = c;
      if (channel) break;
    }
    found += (found.empty() ? "" : ", ") + std::string("'") + dataset.id_lines[0] + "' (node " +
             dataset.NodeDirection() + ")";
    if (!channel) {
      std::string known;
      for (const auto* ch : channels) known += (known.empty() ? "" : ", ") + ch->channel;
      throw InputError(source, dataset.id_lines[0],
                       dataset.Describe() + " names no channel of campaign.json (ID line 1 '" + dataset.id_lines[0] +
                           "', entity '" + dataset.response_entity + "', node " + dataset.NodeDirection() + ")",
                       "write a channel name (" + known +
                           ") in ID line 1, or add the channel to campaign.json's sensors");
    }
    if (matched[*channel])
      throw InputError(source, channels[*channel]->channel,
                       matched[*channel]->Describe() + " and " + dataset.Describe() + " both hold this channel",
                       "export each channel once per file");
    matched[*channel] = &dataset;
  }
  for (std::size_t c = 0; c < channels.size(); ++c)
    if (!matched[c])
      throw InputError(source, channels[c]->channel,
                       "no dataset 58 holds the channel of campaign.json (the file holds " + found + ")",
                       "export this channel into the file, or write its name in the dataset's ID line 1");

  const Uff58Dataset& reference = *matched[0];
  const double seconds = AbscissaToSeconds(reference, source);
  const double dt_s = reference.abscissa_step * seconds;
  const double start_s = reference.abscissa_start * seconds;
  const std::size_t num_samples = reference.values.size();
  Recording recording;
  recording.file = source;
  recording.sample_rate_hz = 1.0 / dt_s;
  recording.start_time_s = start_s;
  Eigen::MatrixXd samples(static_cast<Eigen::Index>(num_samples), static_cast<Eigen::Index>(channels.size()));
  for (std::size_t c = 0; c < channels.size(); ++c) {
    const ChannelSpec& spec = *channels[c];
    const Uff58Dataset& dataset = *matched[c];
    recording.channels.push_back(spec.channel);
    const double this_seconds = AbscissaToSeconds(dataset, source);
    const double this_dt_s = dataset.abscissa_step * this_seconds;
    if (dataset.values.size() != num_samples || std::abs(this_dt_s / dt_s - 1.0) > 1e-9 ||
        std::abs(dataset.abscissa_start * this_seconds - start_s) > checks.max_time_deviation_samples * dt_s)
      throw InputError(source, spec.channel,
                       dataset.Describe() + " holds " + std::to_string(dataset.values.size()) + " samples from t = " +
                           FormatNumber(dataset.abscissa_start * this_seconds) + " s every " + FormatNumber(this_dt_s) +
                           " s, but channel '" + channels[0]->channel + "' has " + std::to_string(num_samples) +
                           " samples from t = " + FormatNumber(start_s) + " s every " + FormatNumber(dt_s) + " s",
                       "export all channels of a step together, with one sample rate and the same time span");
    if (auto quantity = QuantityOfDataType(dataset.ordinate.data_type); quantity && *quantity != spec.quantity)
      throw InputError(source, spec.channel,
                       dataset.Describe() + " holds " + std::string(QuantityName(*quantity)) +
                           " (record 9 data type " + std::to_string(dataset.ordinate.data_type) +
                           ") but campaign.json's channel is a " + std::string(QuantityName(spec.quantity)),
                       "match the dataset to the right channel, or correct the quantity in campaign.json");
    double to_si = spec.to_si_factor;
    if (!dataset.ordinate.unit.empty()) {
      const auto factor = UnitToSiFactor(spec.quantity, CanonicalUnit(dataset.ordinate.unit));
      if (!factor)
        throw InputError(source, spec.channel,
                         dataset.Describe() + ": unit '" + dataset.ordinate.unit + "' (record 9) is not accepted for a " +
                             std::string(QuantityName(spec.quantity)),
                         "export in one of " + AcceptedUnits(spec.quantity) +
                             ", or blank the units label to use campaign.json's unit");
      to_si = *factor;
    }
    for (std::size_t n = 0; n < num_samples; ++n) {
      const double value = dataset.values[n];
      if (!std::isfinite(value))
        throw InputError(source, spec.channel,
                         dataset.Describe() + ": NaN or infinite value at sample " + std::to_string(n) + " (t = " +
                             FormatNumber(start_s + static_cast<double>(n) * dt_s) + " s)",
                         "remove or repair the invalid samples (a NaN is no measurement)");
      samples(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(c)) = to_si * value;
    }
  }
  if (campaign.sample_rate_hz &&
      std::abs(recording.sample_rate_hz / *campaign.sample_rate_hz - 1.0) > checks.sample_rate_tolerance_rel)
    throw InputError(source, "",
                     "record 7 gives dx = " + FormatNumber(dt_s) + " s, i.e. " +
                         FormatNumber(recording.sample_rate_hz) + " Hz, but campaign.json says sample_rate_Hz = " +
                         FormatNumber(*campaign.sample_rate_hz),
                     "correct sample_rate_Hz in campaign.json or export at that rate");
  recording.findings = GradeFindings(CheckChannels(samples, recording.channels, recording.sample_rate_hz,
                                                  recording.start_time_s, step.frequency_hz, source, checks),
                                    campaign, source);
  recording.samples = std::move(samples);
  return recording;
}

}  // namespace beamid::signal
