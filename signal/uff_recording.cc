#include "signal/uff_recording.h"

#include <cmath>
#include <optional>

#include "signal/input_error.h"
#include "signal/internal/channel_defects.h"
#include "signal/internal/text.h"
#include "signal/quality_finding.h"

namespace beamid::signal {
namespace {

using internal::ChannelDefects;
using internal::Excerpt;
using internal::FormatNumber;

// Datasets named in a message: the first few say what the file holds.
constexpr std::size_t kMaxDatasetsNamed = 8;

double AbscissaToSeconds(const Uff58Dataset& dataset, const std::string& source) {
  const Uff58Axis& axis = dataset.abscissa;
  if (axis.data_type != 0 && axis.data_type != 1 && axis.data_type != 17)
    throw InputError(source, "",
                     dataset.Describe() + ": the abscissa's specific data type is " +
                         std::to_string(axis.data_type) + ", not time (17)",
                     "export the time histories, with time as abscissa");
  if (axis.unit.empty() || axis.unit == "s" || axis.unit == "sec") return 1.0;
  if (axis.unit == "ms") return 1e-3;
  throw InputError(source, "", dataset.Describe() + ": abscissa unit '" + Excerpt(axis.unit) + "' is not a time unit",
                   "export time in s (or ms)");
}

}  // namespace

Recording RecordingFromUff58(const std::vector<Uff58Dataset>& datasets, const Campaign& campaign, const Step& step,
                             const std::string& source, const RecordingChecks& checks) {
  const auto channels = campaign.Channels();
  ChannelDefects defects(campaign, channels, source);
  std::vector<const Uff58Dataset*> matched(channels.size(), nullptr);
  std::string found;
  for (std::size_t d = 0; d < datasets.size(); ++d) {
    const Uff58Dataset& dataset = datasets[d];
    const std::string candidates[] = {dataset.id_lines[0], dataset.response_entity, dataset.NodeDirection()};
    std::optional<std::size_t> channel;
    for (const std::string& candidate : candidates) {
      std::string name = candidate;
      while (!name.empty() && name.front() == ' ') name.erase(name.begin());
      for (std::size_t c = 0; c < channels.size() && !channel; ++c)
        if (!name.empty() && channels[c]->channel == name) channel = c;
      if (channel) break;
    }
    // A few datasets say what the file holds; thousands stay one line.
    if (d < kMaxDatasetsNamed)
      found += (found.empty() ? "" : ", ") + std::string("'") + Excerpt(dataset.id_lines[0]) + "' (node " +
               dataset.NodeDirection() + ")";
    else if (d + 1 == datasets.size())
      found += " and " + std::to_string(datasets.size() - kMaxDatasetsNamed) + " more";
    if (!channel) {
      std::string known;
      for (const auto* ch : channels) known += (known.empty() ? "" : ", ") + ch->channel;
      throw InputError(source, Excerpt(dataset.id_lines[0]),
                       dataset.Describe() + " names no channel of campaign.json (ID line 1 '" +
                           Excerpt(dataset.id_lines[0]) + "', entity '" + Excerpt(dataset.response_entity) +
                           "', node " + dataset.NodeDirection() + ")",
                       "write a channel name (" + known +
                           ") in ID line 1, or add the channel to campaign.json's sensors");
    }
    if (matched[*channel]) {
      defects.Report(*channel, matched[*channel]->Describe() + " and " + dataset.Describe() + " both hold this channel",
                     "export each channel once per file");
      continue;
    }
    matched[*channel] = &dataset;
  }
  for (std::size_t c = 0; c < channels.size(); ++c)
    if (!matched[c])
      defects.Report(c, "no dataset 58 holds the channel of campaign.json (the file holds " + found + ")",
                     "export this channel into the file, or write its name in the dataset's ID line 1");

  // The excitation is always used: a problem of it has thrown above.
  const Uff58Dataset& reference = *matched[0];
  const double seconds = AbscissaToSeconds(reference, source);
  const double dt_s = reference.abscissa_step * seconds;
  const double start_s = reference.abscissa_start * seconds;
  const std::size_t num_samples = reference.values.size();
  Recording recording;
  recording.file = source;
  recording.sample_rate_hz = 1.0 / dt_s;
  recording.start_time_s = start_s;
  // Every channel judged before the samples are copied: a channel left out
  // takes no room.
  for (std::size_t c = 0; c < channels.size(); ++c) {
    if (defects.Dropped(c)) continue;
    const ChannelSpec& spec = *channels[c];
    const Uff58Dataset& dataset = *matched[c];
    const double this_seconds = AbscissaToSeconds(dataset, source);
    const double this_dt_s = dataset.abscissa_step * this_seconds;
    if (dataset.values.size() != num_samples || std::abs(this_dt_s / dt_s - 1.0) > 1e-9 ||
        std::abs(dataset.abscissa_start * this_seconds - start_s) > checks.max_time_deviation_samples * dt_s) {
      defects.Report(c,
                     dataset.Describe() + " holds " + std::to_string(dataset.values.size()) + " samples from t = " +
                         FormatNumber(dataset.abscissa_start * this_seconds) + " s every " + FormatNumber(this_dt_s) +
                         " s, but channel '" + channels[0]->channel + "' has " + std::to_string(num_samples) +
                         " samples from t = " + FormatNumber(start_s) + " s every " + FormatNumber(dt_s) + " s",
                     "export all channels of a step together, with one sample rate and the same time span");
      continue;
    }
    if (auto quantity = Uff58Quantity(dataset.ordinate.data_type); quantity && *quantity != spec.quantity) {
      defects.Report(c,
                     dataset.Describe() + " holds " + std::string(QuantityName(*quantity)) + " (record 9 data type " +
                         std::to_string(dataset.ordinate.data_type) + ") but campaign.json's channel is a " +
                         std::string(QuantityName(spec.quantity)),
                     "match the dataset to the right channel, or correct the quantity in campaign.json");
      continue;
    }
    // Record 9's unit, when given, must be campaign.json's, as a CSV
    // header's must: one of the two is wrong, and beamid will not guess
    // which (a g read as m/s² is an error of 9.81).
    if (!dataset.ordinate.unit.empty()) {
      const std::string unit = Uff58Unit(dataset.ordinate.unit);
      if (!UnitToSiFactor(spec.quantity, unit)) {
        defects.Report(c,
                       dataset.Describe() + ": unit '" + Excerpt(dataset.ordinate.unit) +
                           "' (record 9) is not accepted for a " + std::string(QuantityName(spec.quantity)),
                       "export in one of " + AcceptedUnits(spec.quantity) +
                           ", or blank the units label to use campaign.json's unit");
        continue;
      }
      if (unit != spec.unit) {
        defects.Report(c,
                       dataset.Describe() + ": record 9 gives the unit '" + Excerpt(dataset.ordinate.unit) +
                           "' but campaign.json declares '" + spec.unit + "' for this channel",
                       "make them agree: correct the channel's \"unit\" in campaign.json, or export the channel in " +
                           spec.unit + " (or blank record 9's units label)");
        continue;
      }
    }
    for (std::size_t n = 0; n < num_samples; ++n)
      if (!std::isfinite(dataset.values[n])) {
        defects.Report(c,
                       dataset.Describe() + ": NaN or infinite value at sample " + std::to_string(n) + " (t = " +
                           FormatNumber(start_s + static_cast<double>(n) * dt_s) + " s)",
                       "remove or repair the invalid samples (a NaN is no measurement)");
        break;
      }
  }
  std::vector<std::size_t> kept;
  for (std::size_t c = 0; c < channels.size(); ++c)
    if (!defects.Dropped(c)) kept.push_back(c);
  Eigen::MatrixXd samples(static_cast<Eigen::Index>(num_samples), static_cast<Eigen::Index>(kept.size()));
  for (std::size_t k = 0; k < kept.size(); ++k) {
    const ChannelSpec& spec = *channels[kept[k]];
    recording.channels.push_back(spec.channel);
    const std::vector<double>& values = matched[kept[k]]->values;
    samples.col(static_cast<Eigen::Index>(k)) =
        spec.to_si_factor * Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(num_samples));
  }
  if (campaign.sample_rate_hz &&
      std::abs(recording.sample_rate_hz / *campaign.sample_rate_hz - 1.0) > checks.sample_rate_tolerance_rel)
    throw InputError(source, "",
                     "record 7 gives dx = " + FormatNumber(dt_s) + " s, i.e. " +
                         FormatNumber(recording.sample_rate_hz) + " Hz, but campaign.json says sample_rate_Hz = " +
                         FormatNumber(*campaign.sample_rate_hz),
                     "correct sample_rate_Hz in campaign.json or export at that rate");
  defects.Finish(recording, std::move(samples), step, checks);
  return recording;
}

}  // namespace beamid::signal
