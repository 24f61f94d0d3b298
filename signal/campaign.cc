#include "signal/campaign.h"

#include <algorithm>
#include <set>

#include "hb/campaign_file.h"
#include "hb/text_file.h"
#include "signal/campaign_hash.h"
#include "signal/input_error.h"
#include "signal/internal/text.h"

namespace beamid::signal {
namespace {

// What the words of a channel mean, once hb/campaign_file.h has read the
// file's shape: `where` ("sensors[2]") and the channel name every complaint.
class Meaning {
 public:
  explicit Meaning(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void Fail(const std::string& where, const std::string& channel, const std::string& problem,
                         const std::string& fix) const {
    throw InputError(source_, channel, (where.empty() ? "" : where + ": ") + problem, fix);
  }

  ChannelSpec Channel(const hb::CampaignChannel& entry, const std::string& where, bool is_excitation,
                      double length_m) const {
    ChannelSpec spec;
    spec.channel = entry.channel;
    if (spec.channel == "time_s")
      Fail(where, spec.channel, "'time_s' is the time column, not a channel", "rename the channel");
    spec.position_m = entry.position_m;
    if (spec.position_m > length_m)
      Fail(where, spec.channel,
           "position_m = " + internal::FormatNumber(spec.position_m) + " lies beyond the beam end (length_m = " +
               internal::FormatNumber(length_m) + ")",
           "measure x from the clamp, in metres");
    const std::string& quantity_name = entry.quantity;
    auto quantity = ParseQuantity(quantity_name);
    if (is_excitation && (!quantity || !IsExcitationQuantity(*quantity)))
      Fail(where, spec.channel, "the excitation quantity is '" + quantity_name + "'",
           "use \"force\" (N, a force transducer), \"voltage\" (V, the amplifier's drive) or \"base_acceleration\" "
           "(the clamp's acceleration)");
    if (!is_excitation && (!quantity || !IsResponseQuantity(*quantity)))
      Fail(where, spec.channel, "unknown sensor quantity '" + quantity_name + "'",
           "use \"acceleration\", \"velocity\" or \"displacement\"");
    spec.quantity = *quantity;
    spec.unit = entry.unit;
    auto factor = UnitToSiFactor(spec.quantity, spec.unit);
    if (!factor)
      Fail(where, spec.channel,
           "unit '" + spec.unit + "' is not accepted for a " + std::string(QuantityName(spec.quantity)),
           "use one of " + AcceptedUnits(spec.quantity) + " (all accepted units: N, V, mV, m/s^2, g, m/s, mm/s, m, mm)");
    spec.to_si_factor = *factor;
    if (entry.sensitivity_N_per_V && spec.quantity != Quantity::kVoltage)
      Fail(where, spec.channel, "'sensitivity_N_per_V' is given for a " + quantity_name + " excitation",
           "give it only with \"quantity\": \"voltage\"");
    spec.sensitivity_N_per_V = entry.sensitivity_N_per_V;
    spec.mass_kg = entry.mass_kg;
    if (!entry.column.empty() && entry.column_number > 0)
      Fail(where, spec.channel,
           "gives both \"column\": \"" + entry.column + "\" and \"column_number\": " +
               std::to_string(entry.column_number),
           "name the recording column one way: by its header text or by its number");
    spec.column = entry.column;
    spec.column_number = entry.column_number;
    return spec;
  }

  // Two channels reading one column would be one signal analysed twice.
  void RequireOwnColumns(const std::vector<std::pair<std::string, const ChannelSpec*>>& channels) const {
    for (std::size_t i = 0; i < channels.size(); ++i)
      for (std::size_t j = 0; j < i; ++j) {
        const ChannelSpec& a = *channels[j].second;
        const ChannelSpec& b = *channels[i].second;
        const bool same_text = !b.column.empty() && b.column == a.column;
        const bool same_number = b.column_number > 0 && b.column_number == a.column_number;
        if (same_text || same_number)
          Fail(channels[i].first, b.channel,
               "reads the same recording column as " + channels[j].first + " (" + a.channel + "): " +
                   (same_text ? "\"column\": \"" + b.column + "\"" : "\"column_number\": " +
                                                                        std::to_string(b.column_number)),
               "give every channel its own column");
      }
  }

 private:
  std::string source_;
};

}  // namespace

ChannelUse Campaign::Use(std::string_view channel) const {
  if (channel == excitation.channel) return ChannelUse::kUsed;
  if (std::find(ignored_channels.begin(), ignored_channels.end(), channel) != ignored_channels.end())
    return ChannelUse::kIgnored;
  if (analysed_sensors.empty() ||
      std::find(analysed_sensors.begin(), analysed_sensors.end(), channel) != analysed_sensors.end())
    return ChannelUse::kUsed;
  return ChannelUse::kUnused;
}

void Campaign::Analyse(const std::vector<std::string>& channels) {
  const std::string source = (folder / "campaign.json").string();
  for (const auto& channel : channels) {
    if (std::none_of(sensors.begin(), sensors.end(),
                     [&](const ChannelSpec& sensor) { return sensor.channel == channel; })) {
      std::string known;
      for (const auto& sensor : sensors) known += (known.empty() ? "" : ", ") + sensor.channel;
      throw InputError(source, channel, "is not a sensor of the campaign (sensors: " + known + ")",
                       "name one of the channels listed under \"sensors\"");
    }
    if (Use(channel) == ChannelUse::kIgnored)
      throw InputError(source, channel, "the channel is listed in ignore_channels, so it cannot be analysed",
                       "remove it from ignore_channels, or analyse other channels");
  }
  analysed_sensors = channels;
}

std::vector<const ChannelSpec*> Campaign::Channels() const {
  std::vector<const ChannelSpec*> channels{&excitation};
  for (const auto& sensor : sensors) channels.push_back(&sensor);
  return channels;
}

Campaign ParseCampaign(std::string_view json_text, const std::filesystem::path& folder, const std::string& source) {
  // The file's shape: strict JSON (a key written twice, at any depth, would
  // silently take one of its values), no unknown key, every number in range.
  const hb::CampaignFile file = hb::CampaignFileFromJson(std::string(json_text), source);
  const Meaning meaning(source);

  Campaign campaign;
  campaign.folder = folder;
  campaign.name = file.name;
  campaign.beam = file.beam;
  try {
    campaign.beam.Validate();
  } catch (const std::invalid_argument& e) {
    meaning.Fail("beam", "", e.what(), "give the beam's nominal values in SI (m, Pa, kg/m³)");
  }

  campaign.excitation = meaning.Channel(file.excitation, "excitation", true, campaign.beam.length_m);
  std::set<std::string> names{campaign.excitation.channel};
  for (std::size_t i = 0; i < file.sensors.size(); ++i) {
    std::string where = "sensors[" + std::to_string(i) + "]";
    campaign.sensors.push_back(meaning.Channel(file.sensors[i], where, false, campaign.beam.length_m));
    if (!names.insert(campaign.sensors.back().channel).second)
      meaning.Fail(where, campaign.sensors.back().channel, "the channel name is used twice",
                   "give every channel its own column name");
  }

  std::vector<std::pair<std::string, const ChannelSpec*>> columns{{"excitation", &campaign.excitation}};
  for (std::size_t i = 0; i < campaign.sensors.size(); ++i)
    columns.emplace_back("sensors[" + std::to_string(i) + "]", &campaign.sensors[i]);
  meaning.RequireOwnColumns(columns);
  if (file.recording_layout)
    campaign.recording_layout = {.lines_before_header = file.recording_layout->lines_before_header,
                                 .units_row = file.recording_layout->units_row};
  campaign.recording_layout.declared_in = "\"recording_layout\" of " + source;

  for (const hb::CampaignStep& step : file.steps)
    campaign.steps.push_back({.file = step.file, .frequency_hz = step.frequency_hz, .level = step.level});
  campaign.sample_rate_hz = file.sample_rate_hz;
  for (std::size_t i = 0; i < file.ignore_channels.size(); ++i) {
    const std::string where = "ignore_channels[" + std::to_string(i) + "]";
    const std::string& name = file.ignore_channels[i];
    if (name == campaign.excitation.channel)
      meaning.Fail(where, name, "the excitation cannot be ignored: every step is referenced to it",
                   "remove it from ignore_channels");
    const bool known = std::any_of(campaign.sensors.begin(), campaign.sensors.end(),
                                   [&](const ChannelSpec& sensor) { return sensor.channel == name; });
    if (!known)
      meaning.Fail(where, name, "names no sensor of the campaign", "use a channel name listed under \"sensors\"");
    if (std::find(campaign.ignored_channels.begin(), campaign.ignored_channels.end(), name) !=
        campaign.ignored_channels.end())
      meaning.Fail(where, name, "the channel is listed twice", "list it once");
    campaign.ignored_channels.push_back(name);
  }
  return campaign;
}

void RequireRecordingsInside(const Campaign& campaign, const std::filesystem::path& source, bool missing_is_error) {
  const std::string file = source.string();
  std::error_code error;
  const std::filesystem::path root =
      std::filesystem::weakly_canonical(std::filesystem::absolute(campaign.folder), error);
  std::set<std::filesystem::path> recordings;
  for (std::size_t i = 0; i < campaign.steps.size(); ++i) {
    const auto path = campaign.StepPath(campaign.steps[i]);
    const std::string where = "steps[" + std::to_string(i) + "]";
    // Recordings stay inside the campaign folder, links resolved: a
    // campaign.json from elsewhere must not make beamid read (and quote in
    // its errors) any file on the machine.
    const std::filesystem::path resolved = std::filesystem::weakly_canonical(std::filesystem::absolute(path), error);
    const auto [mismatch, unused] = std::mismatch(root.begin(), root.end(), resolved.begin(), resolved.end());
    if (error || mismatch != root.end() || resolved == root)
      throw InputError(file, "", where + "'s file \"" + campaign.steps[i].file + "\" lies outside the campaign folder",
                       "keep every recording inside the campaign folder and name it relative to it");
    if (!recordings.insert(resolved).second)
      throw InputError(file, "", where + "'s file \"" + campaign.steps[i].file + "\" is named by another step too",
                       "give every step its own recording (a step listed twice would count twice in the fit)");
    // A folder, a FIFO or a device named as a recording is said to be one,
    // not "missing": the fix differs.
    if (const std::string kind = FileKind(path); kind == "missing") {
      if (missing_is_error)
        throw InputError(path.string(), "",
                         "recording of " + where + " is missing (named in " + file + ")",
                         "copy the recording into the campaign folder or correct its \"file\" entry");
    } else if (!kind.empty()) {
      throw InputError(path.string(), "",
                       "recording of " + where + " is " + kind + ", not a file (named in " + file + ")",
                       "put the recording itself (a regular file) there or correct its \"file\" entry");
    }
  }
}

Campaign ReadCampaign(const std::filesystem::path& folder) {
  const std::filesystem::path file = folder / "campaign.json";
  Campaign campaign = ParseCampaign(
      ReadTextFile(file, "campaign description",
                   "give the folder that holds campaign.json (and check read permissions)"),
      folder, file.string());
  RequireRecordingsInside(campaign, file, true);
  std::vector<std::string> files;
  for (const auto& step : campaign.steps) files.push_back(step.file);
  const CampaignHash hash = HashCampaign(folder, files);
  campaign.sha256 = hash.sha256;
  // Two steps with the same bytes are one measurement fitted twice, at two
  // nominal frequencies or levels: a copy made by mistake, most likely.
  for (std::size_t i = 0; i < files.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (hash.step_sha256[i] == hash.step_sha256[j]) {
        campaign.warnings.push_back("the recording " + campaign.StepPath(campaign.steps[i]).string() + " of steps[" +
                                    std::to_string(i) + "] holds the same bytes as " +
                                    campaign.StepPath(campaign.steps[j]).string() + " (steps[" + std::to_string(j) +
                                    "]): the same measurement would count twice; copy the right recording in, or "
                                    "remove the step from " + file.string());
        break;
      }
  return campaign;
}

}  // namespace beamid::signal
