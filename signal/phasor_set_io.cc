#include "signal/phasor_set_io.h"

#include <cstdio>
#include <type_traits>

#include <fmt/format.h>

#include "hb/input_limits.h"
#include "hb/text_file.h"
#include "hb/version.h"
#include "signal/free_decay_schema.h"

namespace beamid::signal {
namespace {

constexpr const char* kConvention =
    "x(t) = mean + sum_k Re(X_k exp(i k omega t)); X_k complex peak phasor in SI units; every step rotated so that "
    "the force fundamental X_1 is real and positive (harmonic k by k times the angle); std_re, std_im and "
    "correlation give the standard uncertainty of (Re X_k, Im X_k)";

constexpr schema::Format kPhasorSetSchema{
    kPhasorFormat, "phasors file", "give the phasors file written by 'beamid extract' (see docs/signal.md), unedited"};

// extract's -H takes 1..50.
constexpr int kMaxPhasorHarmonics = 50;
// A bound on the work a file can cause: a stepped-sine test has hundreds.
constexpr std::size_t kMaxSteps = 100'000;
constexpr std::size_t kMaxMessages = 10'000;

enum class Role { kExcitation, kResponse };
constexpr schema::Name<Role> kRoles[] = {{Role::kExcitation, "excitation"}, {Role::kResponse, "response"}};

// The phasors' unit is their channel's SI unit ("unit").
constexpr std::string_view kChannelUnit = "the channel's";

Role RoleOf(Quantity quantity) { return IsExcitationQuantity(quantity) ? Role::kExcitation : Role::kResponse; }

}  // namespace

// The declaration of the JSON file (hb/json_schema.h): its writer, reader
// and documentation. Amplitude and phase and their uncertainties are
// written for a reader's convenience; re, im and their covariance are the
// data.
void Describe(auto& io, schema::Like<HarmonicPhasor> auto& h) {
  constexpr bool kReading = std::remove_cvref_t<decltype(io)>::kReading;
  double re = h.value.real(), im = h.value.imag();
  io.Integer("k", h.harmonic, 0, kMaxPhasorHarmonics);
  io.Number("re", re, kChannelUnit);
  io.Number("im", im, kChannelUnit);
  if constexpr (kReading) h.value = {re, im};
  io.Derived("amplitude", h.Amplitude(), kChannelUnit);
  io.Derived("phase_rad", h.PhaseRad(), "rad");
  io.Number("std_re", h.std_real, kChannelUnit, schema::NonNegative());
  io.Number("std_im", h.std_imag, kChannelUnit, schema::NonNegative());
  io.Number("correlation", h.correlation, "1", schema::Between(-1.0, 1.0));
  io.Derived("std_amplitude", h.AmplitudeStd(), kChannelUnit);
  io.Derived("std_phase_rad", h.PhaseStdRad(), "rad");
}

void Describe(auto& io, schema::Like<ChannelPhasors> auto& c) {
  Role role = RoleOf(c.quantity);
  std::string unit(SiUnit(c.quantity));
  io.Text("channel", c.channel, schema::TextRule::kNotEmpty);
  io.NamesChannel(c.channel);
  io.Choice("role", role, kRoles);
  io.Choice("quantity", c.quantity, kQuantityNames);
  io.Check(role == RoleOf(c.quantity), "the role is \"excitation\" for a force, voltage or base_acceleration, "
                                       "\"response\" for the others", "role");
  io.Text("unit", unit);
  io.Check(unit == SiUnit(c.quantity), "the unit is the quantity's SI unit", "unit");
  io.Number("position_m", c.position_m, "m", schema::NonNegative());
  io.Number("mean", c.mean, kChannelUnit);
  io.Number("thd", c.thd, "1", schema::NonNegative());
  io.Number("snr_dB", c.snr_db, "dB");
  io.Number("noise_rms", c.noise_rms, kChannelUnit, schema::NonNegative());
  io.List("harmonics", c.harmonics, kMaxPhasorHarmonics + 1);
}

void Describe(auto& io, schema::Like<StepQuality> auto& q) {
  io.Number("snr_dB", q.snr_db, "dB");
  io.Number("settled_after_s", q.settled_after_s, "s", schema::NonNegative());
  io.Number("analysed_duration_s", q.analysed_duration_s, "s", schema::NonNegative());
  io.Text("settling", q.settling);
  io.Texts("warnings", q.warnings, kMaxMessages);
  io.Texts("notes", q.notes, kMaxMessages, schema::TextRule::kAny, schema::kOmittedWhenEmpty);
  io.OptionalObject("unsettled", q.unsettled, q, [](auto& u_io, auto& u) {
    u_io.Number("change_relative", u.unsettled_change_relative, "1", schema::NonNegative());
    u_io.Text("channel", u.unsettled_channel, schema::TextRule::kNotEmpty);
  });
  io.OptionalObject("ringing", q.ringing, q, [](auto& r_io, auto& r) {
    r_io.Number("amplitude_relative", r.ringing_relative, "1", schema::NonNegative());
    r_io.Number("decay_rate_per_s", r.ringing_decay_rate_per_s, "1/s", schema::NonNegative());
    r_io.Number("beat_Hz", r.ringing_beat_hz, "Hz", schema::NonNegative());
    r_io.Text("channel", r.ringing_channel, schema::TextRule::kNotEmpty);
  });
}

void Describe(auto& io, schema::Like<StepPhasors> auto& step) {
  io.Text("file", step.file, schema::TextRule::kNotEmpty);
  io.Text("level", step.level);
  io.Number("nominal_frequency_Hz", step.nominal_frequency_hz, "Hz", schema::Positive());
  io.Number("frequency_Hz", step.frequency_hz, "Hz", schema::Positive());
  io.Number("frequency_std_Hz", step.frequency_std_hz, "Hz", schema::NonNegative());
  io.Object("quality", step.quality);
  // The file lists the force first, then the responses.
  std::vector<ChannelPhasors> channels;
  if constexpr (!std::remove_cvref_t<decltype(io)>::kReading) {
    channels.push_back(step.force);
    channels.insert(channels.end(), step.responses.begin(), step.responses.end());
  }
  io.List("channels", channels, static_cast<std::size_t>(hb::kMaxPointsOnBeam) + 1);
  io.List("free_decay", step.free_decays, static_cast<std::size_t>(hb::kMaxPointsOnBeam), schema::kOmittedWhenEmpty);
  bool ordered = !channels.empty() && RoleOf(channels.front().quantity) == Role::kExcitation;
  for (std::size_t c = 1; c < channels.size(); ++c) ordered = ordered && RoleOf(channels[c].quantity) == Role::kResponse;
  io.Check(ordered, "the excitation channel comes first, the responses after it", "channels");
  if constexpr (std::remove_cvref_t<decltype(io)>::kReading) {
    step.force = channels.front();
    step.responses.assign(channels.begin() + 1, channels.end());
  }
}

void Describe(auto& io, schema::Like<SkippedStep> auto& step) {
  io.Text("file", step.file, schema::TextRule::kNotEmpty);
  io.Text("level", step.level);
  io.Number("nominal_frequency_Hz", step.nominal_frequency_hz, "Hz", schema::Positive());
  io.Text("reason", step.reason);
}

void Describe(auto& io, schema::Like<PhasorSet> auto& set) {
  std::string version = kVersion, convention = kConvention;  // written for the reader, not read
  io.Constant("format", kPhasorFormat);
  io.Text("beamid_version", version, schema::TextRule::kAny, schema::kOptional);
  io.Text("convention", convention, schema::TextRule::kAny, schema::kOptional);
  io.Text("campaign", set.campaign);
  io.Text("campaign_sha256", set.campaign_sha256, schema::TextRule::kAny, schema::kOptional);  // "" in older files
  io.Integer("num_harmonics", set.num_harmonics, 1, kMaxPhasorHarmonics);
  io.List("steps", set.steps, kMaxSteps);
  io.List("skipped_steps", set.skipped, kMaxSteps, schema::kOmittedWhenEmpty);
  // Every phasor's harmonic lies in 0..num_harmonics.
  std::string beyond;
  for (std::size_t s = 0; s < set.steps.size() && beyond.empty(); ++s) {
    const StepPhasors& step = set.steps[s];
    for (std::size_t c = 0; c <= step.responses.size() && beyond.empty(); ++c) {
      const ChannelPhasors& channel = c == 0 ? step.force : step.responses[c - 1];
      const bool too_many = channel.harmonics.size() > static_cast<std::size_t>(set.num_harmonics) + 1;
      for (std::size_t k = 0; k < channel.harmonics.size() && beyond.empty(); ++k)
        if (too_many || channel.harmonics[k].harmonic > set.num_harmonics)
          beyond = fmt::format("steps[{}].channels[{}].harmonics[{}].k", s, c, k);
    }
  }
  io.Check(beyond.empty(), "a channel holds at most num_harmonics + 1 phasors, each of a harmonic k <= num_harmonics",
           beyond);
}

std::vector<schema::FieldDoc> PhasorSetFields() { return schema::Fields<PhasorSet>(); }

std::string PhasorSetToJson(const PhasorSet& set) { return schema::ToJson(set); }

PhasorSet PhasorSetFromJson(std::string_view json_text, const std::string& source) {
  return schema::FromJson<PhasorSet>(std::string(json_text), source, kPhasorSetSchema);
}

std::string PhasorSetToCsv(const PhasorSet& set) {
  std::string csv =
      "file,level,nominal_frequency_Hz,frequency_Hz,frequency_std_Hz,channel,quantity,unit,position_m,harmonic,re,im,"
      "amplitude,phase_rad,std_re,std_im,correlation,std_amplitude,std_phase_rad,thd,snr_dB\n";
  char numbers[512];
  for (const auto& step : set.steps) {
    std::vector<const ChannelPhasors*> channels{&step.force};
    for (const auto& response : step.responses) channels.push_back(&response);
    for (const auto* channel : channels) {
      for (const auto& h : channel->harmonics) {
        std::snprintf(numbers, sizeof numbers,
                      "%.12g,%.12g,%.6g,%s,%s,%s,%.6g,%d,%.12g,%.12g,%.12g,%.12g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.4g\n",
                      step.nominal_frequency_hz, step.frequency_hz, step.frequency_std_hz, channel->channel.c_str(),
                      std::string(QuantityName(channel->quantity)).c_str(),
                      std::string(SiUnit(channel->quantity)).c_str(), channel->position_m, h.harmonic, h.value.real(),
                      h.value.imag(), h.Amplitude(), h.PhaseRad(), h.std_real, h.std_imag, h.correlation,
                      h.AmplitudeStd(), h.PhaseStdRad(), channel->thd, channel->snr_db);
        csv += step.file + "," + step.level + "," + numbers;
      }
    }
  }
  return csv;
}

void WritePhasorSetJson(const PhasorSet& set, const std::filesystem::path& file) {
  WriteTextFileAtomically(file, PhasorSetToJson(set));
}

void WritePhasorSetCsv(const PhasorSet& set, const std::filesystem::path& file) {
  WriteTextFileAtomically(file, PhasorSetToCsv(set));
}

PhasorSet ReadPhasorSetJson(const std::filesystem::path& file) {
  return PhasorSetFromJson(ReadTextFile(file, "phasors file", "run 'beamid extract' first, or check the path"),
                           file.string());
}

}  // namespace beamid::signal
