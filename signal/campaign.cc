#include "signal/campaign.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "hb/input_limits.h"
#include "hb/strict_json.h"
#include "hb/text_file.h"
#include "signal/campaign_hash.h"
#include "signal/input_error.h"
#include "signal/internal/text.h"

namespace beamid::signal {
namespace {

using nlohmann::json;

// Validation context: the file and the path of the JSON entry being read
// (e.g. "sensors[2]"), so every message points at the offending entry.
class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void Fail(const std::string& where, const std::string& channel, const std::string& problem,
                         const std::string& fix) const {
    throw InputError(source_, channel, (where.empty() ? "" : where + ": ") + problem, fix);
  }

  void RequireObject(const json& value, const std::string& where) const {
    if (!value.is_object()) Fail(where, "", "must be a JSON object {...}", "see the campaign format spec");
  }

  void OnlyKeys(const json& object, const std::string& where, std::initializer_list<std::string_view> keys) const {
    for (const auto& [key, unused] : object.items()) {
      bool known = false;
      for (auto k : keys) known = known || key == k;
      if (known) continue;
      std::string accepted;
      for (auto k : keys) accepted += (accepted.empty() ? "" : ", ") + std::string(k);
      Fail(where, "", "unknown key '" + key + "'", "use only the keys " + accepted + " (check the spelling)");
    }
  }

  const json& Member(const json& object, const std::string& where, const std::string& key) const {
    auto it = object.find(key);
    if (it == object.end()) Fail(where, "", "missing key '" + key + "'", "add \"" + key + "\"");
    return *it;
  }

  std::string String(const json& object, const std::string& where, const std::string& key) const {
    const json& value = Member(object, where, key);
    if (!value.is_string() || value.get<std::string>().empty())
      Fail(where, "", "'" + key + "' must be a non-empty string", "write it as \"" + key + "\": \"...\"");
    std::string text = value.get<std::string>();
    // Names and labels end up in file names, CSV columns, plot titles and
    // reports: a line break or another control character has no place there
    // (the value itself is not repeated, so that the message stays one line).
    for (std::size_t i = 0; i < text.size(); ++i) {
      const auto byte = static_cast<unsigned char>(text[i]);
      if (byte < 0x20 || byte == 0x7F)
        Fail(where, "",
             "'" + key + "' holds a control character (byte " + std::to_string(byte) + " at position " +
                 std::to_string(i + 1) + ": a line break, tab or the like)",
             "write \"" + key + "\" without line breaks, tabs or other control characters");
    }
    return text;
  }

  // A finite number, > 0 (or >= 0 when zero_allowed).
  double Number(const json& object, const std::string& where, const std::string& key, bool zero_allowed = false,
                const std::string& channel = "") const {
    const json& value = Member(object, where, key);
    if (!value.is_number())
      Fail(where, channel, "'" + key + "' must be a number", "write a plain number in SI, e.g. \"" + key + "\": 0.5");
    double x = value.get<double>();
    if (!std::isfinite(x) || x < 0.0 || (!zero_allowed && x == 0.0))
      Fail(where, channel, "'" + key + "' = " + internal::FormatNumber(x) + " is not physical",
           std::string("give a ") + (zero_allowed ? "non-negative" : "positive") + " value");
    return x;
  }

  ChannelSpec Channel(const json& entry, const std::string& where, bool is_excitation, double length_m) const {
    RequireObject(entry, where);
    if (is_excitation)
      OnlyKeys(entry, where, {"channel", "position_m", "quantity", "unit", "sensitivity_N_per_V"});
    else
      OnlyKeys(entry, where, {"channel", "position_m", "quantity", "unit", "mass_kg"});
    ChannelSpec spec;
    spec.channel = String(entry, where, "channel");
    if (spec.channel == "time_s")
      Fail(where, spec.channel, "'time_s' is the time column, not a channel", "rename the channel");
    spec.position_m = Number(entry, where, "position_m", /*zero_allowed=*/true, spec.channel);
    if (spec.position_m > length_m)
      Fail(where, spec.channel,
           "position_m = " + internal::FormatNumber(spec.position_m) + " lies beyond the beam end (length_m = " +
               internal::FormatNumber(length_m) + ")",
           "measure x from the clamp, in metres");
    std::string quantity_name = String(entry, where, "quantity");
    auto quantity = ParseQuantity(quantity_name);
    if (is_excitation && (!quantity || !IsExcitationQuantity(*quantity)))
      Fail(where, spec.channel, "the excitation quantity is '" + quantity_name + "'",
           "use \"force\" (N, a force transducer), \"voltage\" (V, the amplifier's drive) or \"base_acceleration\" "
           "(the clamp's acceleration)");
    if (!is_excitation && (!quantity || !IsResponseQuantity(*quantity)))
      Fail(where, spec.channel, "unknown sensor quantity '" + quantity_name + "'",
           "use \"acceleration\", \"velocity\" or \"displacement\"");
    spec.quantity = *quantity;
    spec.unit = String(entry, where, "unit");
    auto factor = UnitToSiFactor(spec.quantity, spec.unit);
    if (!factor)
      Fail(where, spec.channel,
           "unit '" + spec.unit + "' is not accepted for a " + std::string(QuantityName(spec.quantity)),
           "use one of " + AcceptedUnits(spec.quantity) + " (all accepted units: N, V, mV, m/s^2, g, m/s, mm/s, m, mm)");
    spec.to_si_factor = *factor;
    if (entry.contains("sensitivity_N_per_V")) {
      if (spec.quantity != Quantity::kVoltage)
        Fail(where, spec.channel, "'sensitivity_N_per_V' is given for a " + quantity_name + " excitation",
             "give it only with \"quantity\": \"voltage\"");
      spec.sensitivity_N_per_V = Number(entry, where, "sensitivity_N_per_V", /*zero_allowed=*/false, spec.channel);
    }
    if (!is_excitation && entry.contains("mass_kg"))
      spec.mass_kg = Number(entry, where, "mass_kg", /*zero_allowed=*/true, spec.channel);
    return spec;
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
  Reader reader(source);
  // Strict: a key written twice, at any depth, would silently take one of
  // its values; a number beyond double's range is refused too.
  const json root = ParseStrictJson<json>(json_text, source, "see docs/campaign-format.md");
  reader.RequireObject(root, "");
  reader.OnlyKeys(root, "", {"format", "beamid_version", "name", "beam", "excitation", "sensors", "steps", "sample_rate_Hz",
                             "ignore_channels"});

  Campaign campaign;
  campaign.folder = folder;
  std::string format = reader.String(root, "", "format");
  if (format != kCampaignFormat)
    reader.Fail("", "", "format '" + format + "' is not supported",
                "this beamid reads \"format\": \"" + std::string(kCampaignFormat) + "\"");
  if (root.contains("name")) campaign.name = reader.String(root, "", "name");

  const json& beam = reader.Member(root, "", "beam");
  reader.RequireObject(beam, "beam");
  reader.OnlyKeys(beam, "beam", {"length_m", "width_m", "thickness_m", "youngs_modulus_Pa", "density_kg_m3"});
  campaign.beam.length_m = reader.Number(beam, "beam", "length_m");
  campaign.beam.width_m = reader.Number(beam, "beam", "width_m");
  campaign.beam.thickness_m = reader.Number(beam, "beam", "thickness_m");
  campaign.beam.youngs_modulus_Pa = reader.Number(beam, "beam", "youngs_modulus_Pa");
  campaign.beam.density_kg_m3 = reader.Number(beam, "beam", "density_kg_m3");
  try {
    campaign.beam.Validate();
  } catch (const std::invalid_argument& e) {
    reader.Fail("beam", "", e.what(), "give the beam's nominal values in SI (m, Pa, kg/m³)");
  }

  campaign.excitation =
      reader.Channel(reader.Member(root, "", "excitation"), "excitation", true, campaign.beam.length_m);

  const json& sensors = reader.Member(root, "", "sensors");
  if (!sensors.is_array() || sensors.empty())
    reader.Fail("", "", "'sensors' must be a non-empty array", "list at least one response channel");
  if (sensors.size() > static_cast<std::size_t>(hb::kMaxPointsOnBeam))
    reader.Fail("", "", "'sensors' lists " + std::to_string(sensors.size()) + " channels, more than the " +
                            std::to_string(hb::kMaxPointsOnBeam) + " beamid analyses",
                "give at most " + std::to_string(hb::kMaxPointsOnBeam) + " sensors");
  std::set<std::string> names{campaign.excitation.channel};
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    std::string where = "sensors[" + std::to_string(i) + "]";
    campaign.sensors.push_back(reader.Channel(sensors[i], where, false, campaign.beam.length_m));
    if (!names.insert(campaign.sensors.back().channel).second)
      reader.Fail(where, campaign.sensors.back().channel, "the channel name is used twice",
                  "give every channel its own column name");
  }

  const json& steps = reader.Member(root, "", "steps");
  if (!steps.is_array() || steps.empty())
    reader.Fail("", "", "'steps' must be a non-empty array", "list one entry per recording");
  for (std::size_t i = 0; i < steps.size(); ++i) {
    std::string where = "steps[" + std::to_string(i) + "]";
    reader.RequireObject(steps[i], where);
    reader.OnlyKeys(steps[i], where, {"file", "frequency_Hz", "level"});
    Step step;
    step.file = reader.String(steps[i], where, "file");
    step.frequency_hz = reader.Number(steps[i], where, "frequency_Hz");
    step.level = reader.String(steps[i], where, "level");
    campaign.steps.push_back(std::move(step));
  }
  if (root.contains("sample_rate_Hz")) campaign.sample_rate_hz = reader.Number(root, "", "sample_rate_Hz");
  if (root.contains("ignore_channels")) {
    const json& ignored = root.at("ignore_channels");
    if (!ignored.is_array())
      reader.Fail("", "", "'ignore_channels' must be an array of sensor channel names",
                  "write e.g. \"ignore_channels\": [\"acc4\"]");
    for (std::size_t i = 0; i < ignored.size(); ++i) {
      const std::string where = "ignore_channels[" + std::to_string(i) + "]";
      if (!ignored[i].is_string())
        reader.Fail(where, "", "must be a sensor's channel name (a string)", "write the name in quotes");
      const std::string name = ignored[i].get<std::string>();
      if (name == campaign.excitation.channel)
        reader.Fail(where, name, "the excitation cannot be ignored: every step is referenced to it",
                    "remove it from ignore_channels");
      const bool known = std::any_of(campaign.sensors.begin(), campaign.sensors.end(),
                                     [&](const ChannelSpec& sensor) { return sensor.channel == name; });
      if (!known)
        reader.Fail(where, name, "names no sensor of the campaign", "use a channel name listed under \"sensors\"");
      if (std::find(campaign.ignored_channels.begin(), campaign.ignored_channels.end(), name) !=
          campaign.ignored_channels.end())
        reader.Fail(where, name, "the channel is listed twice", "list it once");
      campaign.ignored_channels.push_back(name);
    }
  }
  return campaign;
}

Campaign ReadCampaign(const std::filesystem::path& folder) {
  const std::filesystem::path file = folder / "campaign.json";
  Campaign campaign = ParseCampaign(
      ReadTextFile(file, "campaign description", "give the folder that holds campaign.json (and check read permissions)"),
      folder, file.string());
  std::error_code error;
  const std::filesystem::path root = std::filesystem::weakly_canonical(std::filesystem::absolute(folder), error);
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
      throw InputError(file.string(), "",
                       where + "'s file \"" + campaign.steps[i].file + "\" lies outside the campaign folder",
                       "keep every recording inside the campaign folder and name it relative to it");
    if (!recordings.insert(resolved).second)
      throw InputError(file.string(), "",
                       where + "'s file \"" + campaign.steps[i].file + "\" is named by another step too",
                       "give every step its own recording (a step listed twice would count twice in the fit)");
    // A folder, a FIFO or a device named as a recording is said to be one,
    // not "missing": the fix differs.
    if (const std::string kind = FileKind(path); kind == "missing")
      throw InputError(path.string(), "",
                       "recording of steps[" + std::to_string(i) + "] is missing (named in " + file.string() + ")",
                       "copy the recording into the campaign folder or correct its \"file\" entry");
    else if (!kind.empty())
      throw InputError(path.string(), "",
                       "recording of steps[" + std::to_string(i) + "] is " + kind + ", not a file (named in " +
                           file.string() + ")",
                       "put the recording itself (a regular file) there or correct its \"file\" entry");
  }
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
