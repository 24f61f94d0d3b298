#include "hb/campaign_file.h"

#include <nlohmann/json.hpp>

#include "hb/input_limits.h"

namespace beamid::hb {
namespace {

constexpr schema::Format kCampaignFileSchema{
    kCampaignFileFormat, "campaign description",
    "correct campaign.json as docs/campaign-format.md describes it (SI units, as each "
    "key's suffix says)"};

// A bound on the work a file can cause: a stepped-sine test has hundreds.
constexpr std::size_t kMaxSteps = 100'000;

// The recording reader's bound (signal/table_reader.h): no column beyond it exists.
constexpr int kMaxRecordingColumns = 10'000;
// An export's metadata block is a screenful; thousands of lines are a
// mistake (the data rows counted as metadata).
constexpr int kMaxLinesBeforeHeader = 10'000;

// The keys of the excitation and of a sensor differ in their last one.
enum class ChannelRole { kExcitation, kSensor };

void DescribeChannel(auto& io, auto& c, ChannelRole role) {
  using schema::TextRule;
  io.Text("channel", c.channel, TextRule::kNotEmpty);
  io.NamesChannel(c.channel);
  io.Text("column", c.column, TextRule::kNotEmpty, schema::kOmittedWhenEmpty);
  if (schema::Writes(io, c.column_number > 0))
    io.Integer("column_number", c.column_number, 1, kMaxRecordingColumns, schema::kOptional);
  io.Number("position_m", c.position_m, "m", schema::NonNegative());
  io.Text("quantity", c.quantity, TextRule::kNotEmpty);
  io.Text("unit", c.unit, TextRule::kNotEmpty);
  if (role == ChannelRole::kExcitation)
    io.Number("sensitivity_N_per_V", c.sensitivity_N_per_V, "N/V", schema::Positive());
  else
    io.Number("mass_kg", c.mass_kg, "kg", schema::NonNegative());
}

}  // namespace

// The declaration of campaign.json (hb/json_schema.h): its writer, reader
// and documentation. The beam's ranges are a beam test's (BeamProperties::
// Validate); a width or thickness beyond the length is Validate's to refuse.
void Describe(auto& io, schema::Like<CampaignFile> auto& f) {
  using schema::TextRule;
  io.Constant("format", kCampaignFileFormat);
  io.Text("beamid_version", f.beamid_version, TextRule::kAny, schema::kOmittedWhenEmpty);
  io.Text("name", f.name, TextRule::kNotEmpty, schema::kOmittedWhenEmpty);
  io.Object("beam", f.beam, schema::Presence::kRequired, [](auto& beam_io, auto& b) {
    beam_io.Number("length_m", b.length_m, "m", schema::Between(1e-3, 100.0));
    beam_io.Number("width_m", b.width_m, "m", schema::Between(1e-6, 100.0));
    beam_io.Number("thickness_m", b.thickness_m, "m", schema::Between(1e-6, 100.0));
    beam_io.Number("youngs_modulus_Pa", b.youngs_modulus_Pa, "Pa", schema::Between(1e6, 1e13));
    beam_io.Number("density_kg_m3", b.density_kg_m3, "kg/m³", schema::Between(1.0, 1e5));
  });
  io.Object("excitation", f.excitation, schema::Presence::kRequired,
            [](auto& channel_io, auto& c) { DescribeChannel(channel_io, c, ChannelRole::kExcitation); });
  io.List("sensors", f.sensors, static_cast<std::size_t>(kMaxPointsOnBeam), schema::Presence::kRequired,
          [](auto& channel_io, auto& c) { DescribeChannel(channel_io, c, ChannelRole::kSensor); });
  io.Check(!f.sensors.empty(), "sensors lists at least one response channel", "sensors");
  io.List("steps", f.steps, kMaxSteps, schema::Presence::kRequired, [](auto& step_io, auto& s) {
    step_io.Text("file", s.file, TextRule::kNotEmpty);
    step_io.Number("frequency_Hz", s.frequency_hz, "Hz", schema::Positive());
    step_io.Text("level", s.level, TextRule::kNotEmpty);
  });
  io.Check(!f.steps.empty(), "steps lists at least one recording", "steps");
  io.Number("sample_rate_Hz", f.sample_rate_hz, "Hz", schema::Positive());
  io.Texts("ignore_channels", f.ignore_channels, static_cast<std::size_t>(kMaxPointsOnBeam), TextRule::kNotEmpty,
           schema::kOmittedWhenEmpty);
  io.Object("recording_layout", f.recording_layout, schema::kOptional, [](auto& layout_io, auto& l) {
    layout_io.Integer("lines_before_header", l.lines_before_header, 0, kMaxLinesBeforeHeader, schema::kOptional);
    layout_io.Boolean("units_row", l.units_row, schema::kOptional);
  });
}

std::vector<schema::FieldDoc> CampaignFileFields() { return schema::Fields<CampaignFile>(); }

// Two spaces, as the simulator has always written it: the file is one a
// person reads and edits.
std::string CampaignFileToJson(const CampaignFile& file) {
  nlohmann::ordered_json json;
  schema::Writer writer(json);
  Describe(writer, file);
  return json.dump(2) + "\n";
}

CampaignFile CampaignFileFromJson(const std::string& text, const std::string& source) {
  return schema::FromJson<CampaignFile>(text, source, kCampaignFileSchema);
}

}  // namespace beamid::hb
