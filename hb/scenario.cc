#include "hb/scenario.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <stdexcept>
#include <type_traits>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "hb/errors.h"
#include "hb/input_limits.h"
#include "hb/internal/model_sections.h"
#include "hb/json_schema.h"
#include "hb/text_file.h"
#include "hb/version.h"

namespace beamid::hb {

double UnitToSi(const std::string& quantity, const std::string& unit) {
  if (quantity == "acceleration" && unit == "m/s^2") return 1.0;
  if (quantity == "acceleration" && unit == "g") return 9.80665;
  if (quantity == "velocity" && unit == "m/s") return 1.0;
  if (quantity == "velocity" && unit == "mm/s") return 1e-3;
  if (quantity == "displacement" && unit == "m") return 1.0;
  if (quantity == "displacement" && unit == "mm") return 1e-3;
  return 0.0;
}
namespace {

bool IsSafeLabel(const std::string& label) {
  if (label.empty() || label.size() > 64) return false;
  for (char c : label)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-')) return false;
  return true;
}

}  // namespace

const char* ExcitationQuantityName(ExcitationQuantity quantity) {
  switch (quantity) {
    case ExcitationQuantity::kForce: return "force";
    case ExcitationQuantity::kVoltage: return "voltage";
    case ExcitationQuantity::kBaseAcceleration: return "base_acceleration";
  }
  return "force";
}

double ScenarioAmplifier::Gain_N_per_V(double frequency_hz, double first_natural_hz) const {
  const double detuning = (frequency_hz - first_natural_hz) / (kAmplifierSagBandRelative * first_natural_hz);
  return gain_N_per_V * (1.0 - sag / (1.0 + detuning * detuning));
}

std::unique_ptr<SupportLaw> Scenario::MakeSupportLaw() const { return MakePolynomialSupportLaw(polynomial, jenkins, one_sided_stiffness_Nm_rad); }

LinearAttachments Scenario::TrueAttachments() const {
  LinearAttachments all = attachments;
  for (const ScenarioSensor& s : sensors)
    if (s.mass_kg > 0.0) all.point_masses.push_back({s.position_m, s.mass_kg});
  return all;
}

const ChannelNoise& Scenario::NoiseOf(const std::string& channel) const {
  const auto it = channel_noise.find(channel);
  return it == channel_noise.end() ? default_noise : it->second;
}

namespace {

// An early record names its step by the nominal frequency, which a JSON
// writer may round in its last digits.
bool SameNominalFrequency(double a_hz, double b_hz) { return std::abs(a_hz - b_hz) <= 1e-9 * std::abs(b_hz); }

}  // namespace

const EarlyRecord* Scenario::EarlyRecordOf(const std::string& level, double nominal_frequency_hz) const {
  for (const EarlyRecord& early : timing.early_records)
    if (early.level == level && SameNominalFrequency(early.frequency_hz, nominal_frequency_hz)) return &early;
  return nullptr;
}

int Scenario::NumSteps() const {
  int n = 0;
  for (const ScenarioLevel& level : levels) n += static_cast<int>(level.frequencies_hz.size());
  return n;
}
namespace {

constexpr schema::Format kScenarioSchema{kScenarioFormat, "simulation scenario",
                                         "give a simulation scenario (docs/simulator.md)"};

// Bounds on what a file can make the simulator run: far above any test's.
constexpr std::size_t kMaxLevels = 1'000;
constexpr std::size_t kMaxStepsPerLevel = 100'000;
constexpr std::size_t kMaxModes = 1'000;
constexpr std::size_t kMaxDistortionHarmonics = 100;

template <typename Io>
constexpr bool kReading = std::remove_cvref_t<Io>::kReading;

constexpr schema::Name<ExcitationQuantity> kQuantityNames[] = {{ExcitationQuantity::kForce, "force"},
                                                               {ExcitationQuantity::kVoltage, "voltage"},
                                                               {ExcitationQuantity::kBaseAcceleration,
                                                                "base_acceleration"}};

// The level's amplitude: one field per excitation quantity.
struct Amplitude {
  ExcitationQuantity quantity;
  const char* key;
  const char* unit;
  double ScenarioLevel::*value;
};
constexpr Amplitude kAmplitudes[] = {
    {ExcitationQuantity::kForce, "force_amplitude_N", "N", &ScenarioLevel::force_amplitude_N},
    {ExcitationQuantity::kVoltage, "voltage_amplitude_V", "V", &ScenarioLevel::voltage_amplitude_V},
    {ExcitationQuantity::kBaseAcceleration, "base_acceleration_amplitude_m_s2", "m/s²",
     &ScenarioLevel::base_acceleration_amplitude_m_s2}};

const char* AmplitudeKey(ExcitationQuantity quantity) {
  for (const Amplitude& a : kAmplitudes)
    if (a.quantity == quantity) return a.key;
  return "";
}

// "frequencies_Hz" may also be written as a range, run upwards unless the
// level's "direction" is "down". The writer writes the list in run order.
struct FrequencyRange {
  double start_hz = 0.0, stop_hz = 0.0, step_hz = 0.0;
  // As a double: a range of 1e300 steps must be refused, not overflow.
  double Steps() const { return std::floor((stop_hz - start_hz) / step_hz + 1e-9) + 1.0; }
};
enum class Direction { kUp, kDown };
constexpr schema::Name<Direction> kDirectionNames[] = {{Direction::kUp, "up"}, {Direction::kDown, "down"}};

std::string DefaultUnit(const std::string& quantity) {
  return quantity == "velocity" ? "m/s" : quantity == "displacement" ? "m" : "m/s^2";
}

// The first early record that names no step, or a step another one names,
// as its path below "timing" and the rule it breaks; empty when none.
struct Problem {
  std::string where, rule;
};
Problem EarlyRecordProblem(const std::vector<EarlyRecord>& records, const std::vector<ScenarioLevel>& levels) {
  for (std::size_t i = 0; i < records.size(); ++i) {
    const EarlyRecord& early = records[i];
    const std::string at = fmt::format("early_records[{}]", i);
    const auto level =
        std::find_if(levels.begin(), levels.end(), [&](const ScenarioLevel& l) { return l.label == early.level; });
    if (level == levels.end()) {
      std::string labels;
      for (const ScenarioLevel& l : levels) labels += (labels.empty() ? "" : ", ") + l.label;
      return {at + ".level", "'" + early.level + "' is not a level of the scenario; give one of: " + labels};
    }
    const auto steps = std::count_if(level->frequencies_hz.begin(), level->frequencies_hz.end(),
                                     [&](double f) { return SameNominalFrequency(early.frequency_hz, f); });
    if (steps == 0) {
      const auto [lowest, highest] = std::minmax_element(level->frequencies_hz.begin(), level->frequencies_hz.end());
      return {at + ".frequency_Hz",
              fmt::format("{} Hz is not a step of level '{}' (its {} steps run from {} to {} Hz); give one step's "
                          "nominal frequency (to 1e-9 relative)",
                          early.frequency_hz, early.level, level->frequencies_hz.size(), *lowest, *highest)};
    }
    if (steps > 1)
      return {at + ".frequency_Hz", fmt::format("{} Hz is run {} times by level '{}'; an early record must name one step",
                                                early.frequency_hz, steps, early.level)};
    for (std::size_t j = 0; j < i; ++j)
      if (records[j].level == early.level && SameNominalFrequency(early.frequency_hz, records[j].frequency_hz))
        return {at + ".frequency_Hz", fmt::format("names the step of timing.early_records[{}] again", j)};
  }
  return {};
}

}  // namespace

// The measurement noise of a channel (noise.default, noise.channels.<name>).
void Describe(auto& io, schema::Like<ChannelNoise> auto& n) {
  using schema::kOptional;
  io.Number("relative_rms", n.relative_rms, "1", schema::NonNegative(), kOptional);
  io.Number("absolute", n.absolute, "the channel's unit", schema::NonNegative(), kOptional);
  io.Integer("adc_bits", n.adc_bits, 0, 32, kOptional);
  io.Number("adc_range", n.adc_range, "the channel's unit", schema::NonNegative(), kOptional);
  io.Check(n.adc_bits == 0 || n.adc_range > 0.0, "adc_range > 0 when adc_bits is set", "adc_range");
  io.Number("pink_rms", n.pink_rms, "the channel's unit", schema::NonNegative(), kOptional);
}

// The declaration of the JSON file (hb/json_schema.h): its writer, reader
// and documentation. What depends on the excitation quantity (the
// amplifier, the levels' amplitude field, the sensors' quantity) follows it;
// the frequencies of a level are a list or a range.
void Describe(auto& io, schema::Like<Scenario> auto& s) {
  using schema::kOptional;
  using schema::Presence;
  using schema::TextRule;
  // Checked first, so that another kind of file (a model file has no
  // levels) is named as such instead of by its first missing field.
  io.Constant("format", kScenarioFormat, kOptional);
  std::string version(kVersion);  // the writer's stamp: for the reader of the file, not for beamid
  io.Text("beamid_version", version, TextRule::kAny, kOptional);
  io.Text("name", s.name, TextRule::kAny, kOptional);
  // The true beam is spelled out: a default would hide a forgotten field.
  io.Object("beam", s.beam, Presence::kRequired,
            [](auto& b, auto& beam) { internal::DescribeBeam(b, beam, Presence::kRequired); });
  // The nominal beam (written to campaign.json) is the true one, undamped,
  // except where it says otherwise.
  if constexpr (kReading<decltype(io)>) {
    s.nominal_beam = s.beam;
    s.nominal_beam.loss_factor = s.nominal_beam.rayleigh_mass_1_s = s.nominal_beam.rayleigh_stiffness_s = 0.0;
  }
  io.Object("nominal_beam", s.nominal_beam, kOptional,
            [](auto& b, auto& beam) { internal::DescribeBeam(b, beam, kOptional); });
  io.Object("support", s, Presence::kRequired, [](auto& support, auto& sc) {
    internal::DescribeSupport(support, sc.polynomial, sc.jenkins, sc.one_sided_stiffness_Nm_rad);
  });
  io.Object("attachments", s.attachments, kOptional,
            [](auto& a, auto& attachments) { internal::DescribeAttachments(a, attachments); });
  io.Object("damping", s, kOptional, [](auto& d, auto& sc) {
    d.Number("reference_frequency_Hz", sc.damping_reference_frequency_hz, "Hz", schema::NonNegative(), kOptional);
    if (schema::Writes(d, !sc.modal_damping_ratios.empty()))
      d.Numbers("modal_damping_ratios", sc.modal_damping_ratios, "1", schema::Between(0.0, 1.0), kMaxModes, kOptional);
    d.Check(std::all_of(sc.modal_damping_ratios.begin(), sc.modal_damping_ratios.end(), [](double z) { return z < 1.0; }),
            "every modal damping ratio < 1", "modal_damping_ratios");
  });
  io.Object("mesh", s.mesh_min_elements, kOptional,
            [](auto& m, auto& n) { m.Integer("min_elements", n, 1, 2000, kOptional); });
  io.Object("excitation", s, Presence::kRequired, [](auto& e, auto& sc) {
    e.Text("channel", sc.force_channel, TextRule::kNotEmpty, kOptional);
    if (schema::Writes(e, sc.excitation_quantity != ExcitationQuantity::kForce))
      e.Choice("quantity", sc.excitation_quantity, kQuantityNames, kOptional);
    // The base moves clamp and support at once: there is no point of action.
    if (schema::InVariant(e, !sc.BaseExcitation()))
      e.Number("position_m", sc.force_position_m, "m", schema::Positive());
    else
      e.Refused("position_m", "must be left out with quantity \"base_acceleration\" (the clamp and the support move together)",
                "remove it");
    // The amplifier's fields belong to a voltage drive only, so that another
    // drive cannot carry a gain that silently does nothing.
    if (schema::InVariant(e, sc.VoltageDrive())) {
      e.Number("amplifier_gain_N_per_V", sc.amplifier.gain_N_per_V, "N/V", schema::Positive());
      e.Number("amplifier_sag", sc.amplifier.sag, "1", schema::Between(0.0, 1.0), kOptional);
      e.Check(sc.amplifier.sag < 1.0, "amplifier_sag < 1 (the gain at f1 is g0·(1 − sag))", "amplifier_sag");
    } else {
      for (const char* key : {"amplifier_gain_N_per_V", "amplifier_sag"})
        e.Refused(key, "belongs to a voltage drive", "remove it or set excitation.quantity to \"voltage\"");
    }
    e.List("distortion", sc.force_distortion, kMaxDistortionHarmonics, kOptional, [](auto& h, auto& harmonic) {
      h.Integer("harmonic", harmonic.harmonic, 2, 20);
      h.Number("amplitude_ratio", harmonic.amplitude_ratio, "1", schema::NonNegative(), kOptional);
      h.Number("phase_rad", harmonic.phase_rad, "rad", schema::Any(), kOptional);
    });
  });
  io.List("sensors", s.sensors, kMaxPointsOnBeam, Presence::kRequired, [&s](auto& r, auto& sensor) {
    r.Text("channel", sensor.channel, TextRule::kNotEmpty);
    r.Check(sensor.channel != "time_s" && sensor.channel.find(',') == std::string::npos,
            "a channel is named without commas, other than time_s", "channel");
    r.Number("position_m", sensor.position_m, "m", schema::Positive());
    r.Text("quantity", sensor.quantity, TextRule::kNotEmpty, kOptional);
    r.Check(sensor.quantity == "acceleration" || sensor.quantity == "velocity" || sensor.quantity == "displacement",
            "quantity is acceleration, velocity or displacement", "quantity");
    // Absolute velocity and displacement would need the base's integrated
    // motion, whose constants a real rig does not define.
    r.Check(!s.BaseExcitation() || sensor.quantity == "acceleration",
            "quantity is acceleration with excitation.quantity \"base_acceleration\" (the sensors record absolute "
            "acceleration)",
            "quantity");
    if constexpr (kReading<decltype(r)>) sensor.unit = DefaultUnit(sensor.quantity);
    r.Text("unit", sensor.unit, TextRule::kNotEmpty, kOptional);
    r.Check(UnitToSi(sensor.quantity, sensor.unit) != 0.0,
            "unit is one of the quantity's (acceleration: m/s^2, g; velocity: m/s, mm/s; displacement: m, mm)",
            "unit");
    r.Number("mass_kg", sensor.mass_kg, "kg", schema::NonNegative(), kOptional);
    // The measurement artefacts, only when set: a scenario without them stays
    // a model file (hb/model_file.h). The stated position is checked against
    // the beam with the other positions.
    if (schema::Writes(r, sensor.gain_error_relative != 0.0))
      r.Number("gain_error_relative", sensor.gain_error_relative, "1", schema::Limits{.min = -1.0, .min_open = true},
               kOptional);
    if (schema::Writes(r, sensor.delay_s != 0.0))
      r.Number("delay_s", sensor.delay_s, "s", schema::Between(0.0, kMaxSensorDelay_s), kOptional);
    double stated_m = sensor.stated_position_m.value_or(std::nan(""));
    if (schema::Writes(r, sensor.stated_position_m.has_value()))
      r.Number("stated_position_m", stated_m, "m", schema::Positive(), kOptional);
    if constexpr (kReading<decltype(r)>)
      if (!std::isnan(stated_m)) sensor.stated_position_m = stated_m;
  });
  io.Check(!s.sensors.empty(), "lists at least one sensor", "sensors");
  io.Numbers("hidden_positions_m", s.hidden_positions_m, "m", schema::NonNegative(), kMaxPointsOnBeam, kOptional);
  io.List("levels", s.levels, kMaxLevels, Presence::kRequired, [&s](auto& l, auto& level) {
    l.Text("label", level.label, TextRule::kNotEmpty);
    l.Check(IsSafeLabel(level.label), "a label is 1-64 letters, digits, '_' or '-' (it names the level's folder)",
            "label");
    // The one amplitude field of the excitation quantity; another quantity's
    // field is refused (it would be silently ignored), naming the one to give.
    for (const Amplitude& a : kAmplitudes)
      if (!schema::InVariant(l, a.quantity == s.excitation_quantity))
        l.Refused(a.key,
                  fmt::format("is not the drive with excitation.quantity \"{}\"",
                              ExcitationQuantityName(s.excitation_quantity)),
                  fmt::format("give {}", AmplitudeKey(s.excitation_quantity)));
    for (const Amplitude& a : kAmplitudes)
      if (schema::InVariant(l, a.quantity == s.excitation_quantity))
        l.Number(a.key, level.*a.value, a.unit, schema::Positive());
    FrequencyRange range;
    l.NumbersOr("frequencies_Hz", level.frequencies_hz, "Hz", schema::Positive(), kMaxStepsPerLevel, range,
                Presence::kRequired, [](auto& r, auto& f) {
                  r.Number("start", f.start_hz, "Hz", schema::Positive());
                  r.Number("stop", f.stop_hz, "Hz", schema::Positive());
                  r.Number("step", f.step_hz, "Hz", schema::Positive());
                  r.Check(f.stop_hz >= f.start_hz, "stop ≥ start (\"direction\": \"down\" sweeps down)", "stop");
                  r.Check(f.step_hz <= 0.0 || f.Steps() <= static_cast<double>(kMaxStepsPerLevel),
                          "at most 100000 steps from start to stop", "step");
                });
    if constexpr (kReading<decltype(l)>)
      if (range.step_hz > 0.0)
        for (std::size_t i = 0; i < static_cast<std::size_t>(range.Steps()); ++i)
          level.frequencies_hz.push_back(range.start_hz + range.step_hz * static_cast<double>(i));
    l.Check(!level.frequencies_hz.empty(), "frequencies_Hz holds at least one frequency", "frequencies_Hz");
    Direction direction = Direction::kUp;
    if (schema::Writes(l, false)) l.Choice("direction", direction, kDirectionNames, kOptional);
    if constexpr (kReading<decltype(l)>)
      if (direction == Direction::kDown) std::reverse(level.frequencies_hz.begin(), level.frequencies_hz.end());
  });
  io.Check(!s.levels.empty(), "lists at least one level", "levels");
  io.Object("timing", s.timing, kOptional, [&s](auto& t, auto& timing) {
    // Limits that keep one simulated step within memory and minutes: a time
    // step no finer than 1e-7 s, at most 2^24 samples per record.
    t.Number("sample_rate_Hz", timing.sample_rate_hz, "Hz", schema::Positive(), kOptional);
    t.Number("max_time_step_s", timing.max_time_step_s, "s", schema::Limits{.min = 1e-7}, kOptional);
    t.Number("settle_min_s", timing.settle_min_s, "s", schema::NonNegative(), kOptional);
    t.Number("settle_max_s", timing.settle_max_s, "s", schema::Limits{.min = 0.0, .max = 3600.0, .min_open = true},
             kOptional);
    t.Check(timing.settle_max_s >= timing.settle_min_s, "settle_max_s ≥ settle_min_s", "settle_max_s");
    t.Number("settle_tolerance", timing.settle_tolerance, "1", schema::Positive(), kOptional);
    t.Number("transient_s", timing.transient_s, "s", schema::NonNegative(), kOptional);
    t.Number("record_s", timing.record_s, "s", schema::Positive(), kOptional);
    t.Check(timing.record_s * timing.sample_rate_hz <= 16777216.0,
            "record_s · sample_rate_Hz ≤ 16777216 samples per record (record shorter)", "record_s");
    t.Boolean("restart_each_level", timing.restart_each_level, kOptional);
    t.Number("excitation_stop_fraction", timing.excitation_stop_fraction, "1", schema::Between(0.0, 1.0), kOptional);
    // The truth is fitted over the steady part before the stop, so the stop
    // must leave some of it (and happen before the file ends).
    const double earliest = timing.transient_s / (timing.transient_s + timing.record_s);
    t.Check(timing.excitation_stop_fraction == 0.0 ||
                (timing.excitation_stop_fraction > earliest && timing.excitation_stop_fraction < 1.0),
            "excitation_stop_fraction is 0 (never) or lies between transient_s/(transient_s + record_s) and 1, so that "
            "the force stops inside the steady record",
            "excitation_stop_fraction");
    // The acquisition's clock runs (1 + this) fast against the stated
    // sample_rate_Hz; 0.002 is 2000 ppm, a rate stated 0.2 % low.
    if (schema::Writes(t, timing.daq_clock_error_relative != 0.0))
      t.Number("daq_clock_error_relative", timing.daq_clock_error_relative, "1",
               schema::Between(-kMaxDaqClockError, kMaxDaqClockError), kOptional);
    if (schema::Writes(t, !timing.early_records.empty()))
      t.List("early_records", timing.early_records, kMaxLevels * kMaxStepsPerLevel, kOptional,
             [](auto& r, auto& early) {
               r.Text("level", early.level, TextRule::kNotEmpty);
               r.Number("frequency_Hz", early.frequency_hz, "Hz", schema::Positive());
               // From the frequency change to the recording's first sample.
               r.Number("settle_s", early.settle_s, "s", schema::Limits{.min = 0.0, .max = 3600.0, .min_open = true});
             });
    const Problem problem = EarlyRecordProblem(timing.early_records, s.levels);
    t.Check(problem.where.empty(),
            problem.where.empty() ? "an early record names one step of a level of the scenario, and no step twice"
                                  : problem.rule,
            problem.where);
  });
  io.Object("noise", s, kOptional, [](auto& n, auto& sc) {
    n.Integer("seed", sc.seed, 0, 9'000'000'000'000'000, kOptional);
    n.Number("clock_offset_ppm", sc.clock_offset_ppm, "ppm", schema::Between(-1e4, 1e4), kOptional);
    n.Number("amplitude_creep_relative", sc.amplitude_creep_relative, "1", schema::Between(-2.0, 2.0), kOptional);
    // The scale 1 + creep·(t/T − 1/2) must stay positive over the whole file,
    // whose transient (t < 0) continues the line.
    const double reach = sc.timing.transient_s / sc.timing.record_s + 0.5;
    n.Check(std::abs(sc.amplitude_creep_relative) * reach < 1.0,
            "|amplitude_creep_relative|·(transient_s/record_s + 1/2) < 1 (the scale 1 + creep·(t/T − 1/2) stays "
            "positive over the transient and the record)",
            "amplitude_creep_relative");
    n.Object("default", sc.default_noise, kOptional);
    n.Keyed("channels", sc.channel_noise, kMaxPointsOnBeam + 1, kOptional);
  });
}

std::vector<schema::FieldDoc> ScenarioFields() { return schema::Fields<Scenario>(); }

namespace {

// ---------------------------------------------------------------- consistency of the whole

void ValidateBeams(const Scenario& s, const std::string& source) {
  try {
    s.beam.Validate();
    s.nominal_beam.Validate();
  } catch (const std::invalid_argument& e) {
    throw InputError(source, "", e.what(), "give the beam in SI (m, Pa, kg/m³)");
  }
}

void CheckPositionsAndChannels(const Scenario& s, const std::string& source) {
  const double length = s.beam.length_m;
  auto inside = [&](double x, const std::string& what, bool allow_ends) {
    if (!(x >= 0.0 && x <= length) || (!allow_ends && (x <= 0.0 || x >= length)))
      throw InputError(source, "", fmt::format("{} = {} m lies outside the beam (0, {}) m", what, x, length),
                       "give a position on the beam (beam.length_m)");
  };
  if (!s.BaseExcitation()) inside(s.force_position_m, "excitation.position_m", false);
  std::set<std::string> channels{s.force_channel};
  if (s.force_channel == "time_s")
    throw InputError(source, "", "excitation.channel is time_s, the time column's name", "name the channel otherwise");
  for (size_t i = 0; i < s.sensors.size(); ++i) {
    const ScenarioSensor& sensor = s.sensors[i];
    inside(sensor.position_m, fmt::format("sensors[{}].position_m", i), false);
    // The test plan may place a sensor at the support's end (x = L), not at the clamp.
    if (sensor.stated_position_m && !(*sensor.stated_position_m > 0.0 && *sensor.stated_position_m <= length))
      throw InputError(source, "",
                       fmt::format("sensors[{}].stated_position_m = {} m lies outside the beam (0, {}] m", i,
                                   *sensor.stated_position_m, length),
                       "give where the test plan says sensor " + sensor.channel + " is");
    if (!channels.insert(sensor.channel).second)
      throw InputError(source, "",
                       fmt::format("sensors[{}].channel: channel name '{}' is used twice", i, sensor.channel),
                       "give every channel its own name");
  }
  for (double x : s.hidden_positions_m) inside(x, "hidden_positions_m", true);
  for (const PointMass& m : s.attachments.point_masses) inside(m.position_m, "attachments point mass position_m", true);
  for (const auto& [channel, noise] : s.channel_noise)
    if (!channels.count(channel))
      throw InputError(source, "", "noise.channels names '" + channel + "', which is not a channel",
                       "name the excitation's channel or a sensor's");
}

void CheckLevelsAndFrequencies(const Scenario& s, const std::string& source) {
  std::set<std::string> labels;
  for (std::size_t i = 0; i < s.levels.size(); ++i)
    if (!labels.insert(s.levels[i].label).second)
      throw InputError(source, "",
                       fmt::format("levels[{}].label: level label '{}' is used twice", i, s.levels[i].label),
                       "give every level its own label");
  const double nyquist_hz = 0.5 * s.timing.sample_rate_hz;
  for (const ScenarioLevel& level : s.levels)
    for (double f : level.frequencies_hz)
      if (5.0 * f >= nyquist_hz)
        throw InputError(
            source, "",
            fmt::format("level {} runs {} Hz, whose 5th harmonic is above the Nyquist frequency of sample_rate_Hz",
                        level.label, f),
            "raise timing.sample_rate_Hz");
  double max_frequency_hz = 0.0;
  for (const ScenarioLevel& level : s.levels)
    for (double f : level.frequencies_hz) max_frequency_hz = std::max(max_frequency_hz, f);
  for (const ForceHarmonic& h : s.force_distortion)
    if (h.harmonic * max_frequency_hz >= nyquist_hz)
      throw InputError(source, "",
                       fmt::format("excitation.distortion harmonic {} exceeds the Nyquist frequency", h.harmonic),
                       "raise timing.sample_rate_Hz");
}

}  // namespace

Scenario ParseScenario(const std::string& json_text, const std::string& source) {
  Scenario s = schema::FromJson<Scenario>(json_text, source, kScenarioSchema);
  if (s.BaseExcitation()) s.force_position_m = 0.0;
  ValidateBeams(s, source);
  CheckPositionsAndChannels(s, source);
  CheckLevelsAndFrequencies(s, source);
  return s;
}

Scenario ReadScenario(const std::filesystem::path& file) {
  return ParseScenario(ReadTextFile(file, "scenario file", "check the path"), file.string());
}

std::string ScenarioToJson(const Scenario& s) {
  nlohmann::ordered_json json;
  schema::Writer writer(json);
  Describe(writer, s);
  return json.dump(2) + "\n";
}

void WriteScenarioFile(const std::filesystem::path& path, const Scenario& scenario) {
  WriteTextFileAtomically(path, ScenarioToJson(scenario));
}

}  // namespace beamid::hb
