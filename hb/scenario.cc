#include "hb/scenario.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "hb/errors.h"
#include "hb/strict_json.h"
#include "hb/text_file.h"
#include "hb/version.h"
#include "hb/internal/json_object_reader.h"
#include "hb/internal/json_object_writer.h"

namespace beamid::hb {
namespace {

using Json = nlohmann::json;
using internal::ObjectReader;
using internal::OrderedJson;
using internal::ReadBeam;

}  // namespace

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

ChannelNoise ReadNoise(ObjectReader& r) {
  ChannelNoise n;
  n.relative_rms = r.NonNegative("relative_rms", 0.0);
  n.absolute = r.NonNegative("absolute", 0.0);
  const double bits = r.NonNegative("adc_bits", 0.0);
  if (bits != std::floor(bits) || bits > 32) r.FailField("adc_bits", "must be an integer from 0 to 32");
  n.adc_bits = static_cast<int>(bits);
  n.adc_range = r.NonNegative("adc_range", 0.0);
  if (n.adc_bits > 0 && !(n.adc_range > 0.0)) r.FailField("adc_range", "must be positive when adc_bits is set");
  n.pink_rms = r.NonNegative("pink_rms", 0.0);
  return n;
}

std::vector<double> ReadFrequencies(ObjectReader& level) {
  const Json& spec = level.Raw("frequencies_Hz");
  const std::string path = level.PathOf("frequencies_Hz");
  std::vector<double> f;
  if (spec.is_array()) {
    if (spec.size() > 100000) throw std::invalid_argument(level.source() + ": " + path + " lists more than 100000 steps");
    for (const Json& v : spec) {
      if (!v.is_number()) throw std::invalid_argument(level.source() + ": " + path + " must hold numbers");
      f.push_back(v.get<double>());
    }
  } else {
    ObjectReader range(spec, level.source(), path);
    const double start = range.Positive("start", 0.0), stop = range.Positive("stop", 0.0);
    const double step = range.Positive("step", 0.0);
    if (stop < start) range.FailField("stop", "must not be below start (use \"direction\": \"down\" to sweep down)");
    const int count = static_cast<int>(std::floor((stop - start) / step + 1e-9)) + 1;
    if (count > 100000) range.FailField("step", "gives more than 100000 steps");
    for (int i = 0; i < count; ++i) f.push_back(start + step * i);
  }
  if (f.empty()) throw std::invalid_argument(level.source() + ": " + path + " holds no frequency");
  for (double x : f)
    if (!(x > 0.0 && std::isfinite(x))) throw std::invalid_argument(level.source() + ": " + path + " must be positive");
  const std::string direction = level.String("direction", "up");
  if (direction == "down") std::reverse(f.begin(), f.end());
  else if (direction != "up") level.FailField("direction", "must be \"up\" or \"down\"");
  return f;
}

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

// ---------------------------------------------------------------- reading, one helper per section

Json ParseJson(const std::string& json_text, const std::string& source) {
  return ParseStrictJson<Json>(json_text, source, "see docs/simulator.md");
}

// Checked first, so that another kind of file (a model file has no levels)
// is named as such instead of by its first missing field.
void ReadFormat(ObjectReader& top) {
  top.String("beamid_version", "");  // the writer's stamp: for the reader of the file, not for beamid
  const std::string format = top.String("format", std::string(kScenarioFormat));
  if (format != kScenarioFormat)
    throw InputError(top.source() + ": field \"format\" is \"" + format + "\", not \"" + std::string(kScenarioFormat) +
                     "\". Fix: give a simulation scenario (docs/simulator.md), or remove \"format\"");
}

void ReadBeams(ObjectReader& top, Scenario& s) {
  {
    ObjectReader beam(top.Raw("beam"), top.source(), "beam");
    // The true beam is spelled out: a default would hide a forgotten field.
    for (const char* key : {"length_m", "width_m", "thickness_m", "youngs_modulus_Pa", "density_kg_m3"})
      if (!beam.Has(key)) beam.FailField(key, "is required (the true beam)");
    ReadBeam(beam, s.beam, true);
  }
  s.nominal_beam = s.beam;
  s.nominal_beam.loss_factor = 0.0;
  s.nominal_beam.rayleigh_mass_1_s = 0.0;
  s.nominal_beam.rayleigh_stiffness_s = 0.0;
  if (top.Has("nominal_beam")) {
    ObjectReader nominal(top.Raw("nominal_beam"), top.source(), "nominal_beam");
    ReadBeam(nominal, s.nominal_beam, false);
  }
}

void ReadDampingAndMesh(ObjectReader& top, Scenario& s) {
  if (top.Has("damping")) {
    ObjectReader d(top.Raw("damping"), top.source(), "damping");
    s.damping_reference_frequency_hz = d.NonNegative("reference_frequency_Hz", 0.0);
    if (d.Has("modal_damping_ratios")) {
      const Json& ratios = d.Array("modal_damping_ratios");
      for (std::size_t j = 0; j < ratios.size(); ++j) {
        const std::string key = "modal_damping_ratios[" + std::to_string(j) + "]";
        if (!ratios[j].is_number() || !(ratios[j].get<double>() >= 0.0 && ratios[j].get<double>() < 1.0))
          d.FailField(key, "must be a damping ratio in [0, 1)");
        s.modal_damping_ratios.push_back(ratios[j].get<double>());
      }
    }
  }
  if (top.Has("mesh")) {
    ObjectReader m(top.Raw("mesh"), top.source(), "mesh");
    const double n = m.Positive("min_elements", 40);
    if (n != std::floor(n) || n > 2000) m.FailField("min_elements", "must be an integer from 1 to 2000");
    s.mesh_min_elements = static_cast<int>(n);
  }
}

// "quantity": "force" (default) | "voltage" | "base_acceleration".
ExcitationQuantity ReadExcitationQuantity(ObjectReader& e) {
  const std::string quantity = e.String("quantity", "force");
  for (ExcitationQuantity q : {ExcitationQuantity::kForce, ExcitationQuantity::kVoltage, ExcitationQuantity::kBaseAcceleration})
    if (quantity == ExcitationQuantityName(q)) return q;
  e.FailField("quantity", "must be \"force\" (the level's amplitude is the force), \"voltage\" (the amplifier's input) "
                          "or \"base_acceleration\" (the clamp and the support move together)");
}

// The amplifier's fields belong to a voltage drive only, so that another
// drive cannot carry a gain that silently does nothing.
void ReadAmplifier(ObjectReader& e, bool voltage_drive, ScenarioAmplifier& amplifier) {
  if (!voltage_drive) {
    for (const char* key : {"amplifier_gain_N_per_V", "amplifier_sag"})
      if (e.Has(key)) e.FailField(key, "belongs to a voltage drive; remove it or set excitation.quantity to \"voltage\"");
    return;
  }
  if (!e.Has("amplifier_gain_N_per_V"))
    e.FailField("amplifier_gain_N_per_V", "is required with excitation.quantity \"voltage\" (the amplifier's gain g0 in N/V)");
  amplifier.gain_N_per_V = e.Positive("amplifier_gain_N_per_V", 0.0);
  amplifier.sag = e.NonNegative("amplifier_sag", 0.0);
  if (!(amplifier.sag < 1.0)) e.FailField("amplifier_sag", "must lie in [0, 1): the gain at f1 is g0·(1 − sag)");
}

void ReadExcitation(ObjectReader& top, Scenario& s) {
  ObjectReader e(top.Raw("excitation"), top.source(), "excitation");
  s.force_channel = e.String("channel", "force");
  s.excitation_quantity = ReadExcitationQuantity(e);
  if (s.BaseExcitation()) {
    // The base moves clamp and support at once: there is no point of action.
    if (e.Has("position_m"))
      e.FailField("position_m", "must be left out with quantity \"base_acceleration\" (the clamp and the support move together)");
    s.force_position_m = 0.0;
  } else {
    s.force_position_m = e.Positive("position_m", 0.0);
  }
  ReadAmplifier(e, s.VoltageDrive(), s.amplifier);
  if (!e.Has("distortion")) return;
  const Json& list = e.Array("distortion");
  for (size_t i = 0; i < list.size(); ++i) {
    ObjectReader h(list[i], top.source(), "excitation.distortion[" + std::to_string(i) + "]");
    const double k = h.Number("harmonic");
    if (k != std::floor(k) || k < 2 || k > 20) h.FailField("harmonic", "must be an integer from 2 to 20");
    s.force_distortion.push_back({static_cast<int>(k), h.NonNegative("amplitude_ratio", 0.0), h.Number("phase_rad", 0.0)});
  }
}

ScenarioSensor ReadSensor(ObjectReader& r) {
  ScenarioSensor sensor;
  sensor.channel = r.String("channel", "");
  sensor.position_m = r.Positive("position_m", 0.0);
  sensor.quantity = r.String("quantity", "acceleration");
  const std::string default_unit =
      sensor.quantity == "velocity" ? "m/s" : sensor.quantity == "displacement" ? "m" : "m/s^2";
  sensor.unit = r.String("unit", default_unit);
  sensor.mass_kg = r.NonNegative("mass_kg", 0.0);
  // The measurement artefacts (the position is checked against the beam in
  // CheckPositionsAndChannels).
  sensor.gain_error_relative = r.Number("gain_error_relative", 0.0);
  if (!(sensor.gain_error_relative > -1.0))
    r.FailField("gain_error_relative", "must be above -1: the channel records (1 + gain_error_relative)·signal "
                                       "(0.05 reads 5 % high)");
  sensor.delay_s = r.NonNegative("delay_s", 0.0);
  if (sensor.delay_s > kMaxSensorDelay_s)
    r.FailField("delay_s", "must not exceed " + std::to_string(kMaxSensorDelay_s) +
                               " s (an anti-alias filter's delay, a few samples)");
  if (r.Has("stated_position_m")) sensor.stated_position_m = r.Number("stated_position_m");
  if (sensor.quantity != "acceleration" && sensor.quantity != "velocity" && sensor.quantity != "displacement")
    r.FailField("quantity", "must be acceleration, velocity or displacement");
  if (UnitToSi(sensor.quantity, sensor.unit) == 0.0)
    r.FailField("unit", "'" + sensor.unit + "' is not a unit of " + sensor.quantity + " (m/s^2, g, m/s, mm/s, m, mm)");
  return sensor;
}

void ReadSensorsAndHiddenPositions(ObjectReader& top, Scenario& s) {
  const Json& sensors = top.PointList("sensors");
  if (sensors.empty()) top.FailField("sensors", "must list at least one sensor");
  for (size_t i = 0; i < sensors.size(); ++i) {
    ObjectReader r(sensors[i], top.source(), "sensors[" + std::to_string(i) + "]");
    s.sensors.push_back(ReadSensor(r));
  }
  if (!top.Has("hidden_positions_m")) return;
  for (const Json& v : top.PointList("hidden_positions_m")) {
    if (!v.is_number()) top.FailField("hidden_positions_m", "must hold numbers");
    s.hidden_positions_m.push_back(v.get<double>());
  }
}

// The one amplitude field of the scenario's excitation quantity; another
// quantity's field is refused (it would be silently ignored).
void ReadLevelAmplitude(ObjectReader& r, ExcitationQuantity quantity, ScenarioLevel& level) {
  struct Field {
    ExcitationQuantity quantity;
    const char* key;
    double* value;
  };
  const Field fields[] = {{ExcitationQuantity::kForce, "force_amplitude_N", &level.force_amplitude_N},
                          {ExcitationQuantity::kVoltage, "voltage_amplitude_V", &level.voltage_amplitude_V},
                          {ExcitationQuantity::kBaseAcceleration, "base_acceleration_amplitude_m_s2",
                           &level.base_acceleration_amplitude_m_s2}};
  const char* wanted = "";
  for (const Field& f : fields)
    if (f.quantity == quantity) wanted = f.key;
  // Another drive's field first: its message names the one to give instead.
  for (const Field& f : fields)
    if (f.quantity != quantity && r.Has(f.key))
      r.FailField(f.key, std::string("is not the drive with excitation.quantity \"") + ExcitationQuantityName(quantity) +
                             "\"; give " + wanted);
  for (const Field& f : fields) {
    if (f.quantity != quantity) continue;
    if (quantity != ExcitationQuantity::kForce && !r.Has(f.key))
      r.FailField(f.key, std::string("is required with excitation.quantity \"") + ExcitationQuantityName(quantity) + "\"");
    *f.value = r.Positive(f.key, 0.0);
  }
}

void ReadLevels(ObjectReader& top, Scenario& s) {
  const Json& levels = top.Array("levels");
  if (levels.empty()) top.FailField("levels", "must list at least one level");
  for (size_t i = 0; i < levels.size(); ++i) {
    ObjectReader r(levels[i], top.source(), "levels[" + std::to_string(i) + "]");
    ScenarioLevel level;
    level.label = r.String("label", "");
    if (!IsSafeLabel(level.label))
      r.FailField("label", "must be 1-64 letters, digits, '_' or '-' (it names the level's folder)");
    ReadLevelAmplitude(r, s.excitation_quantity, level);
    level.frequencies_hz = ReadFrequencies(r);
    s.levels.push_back(std::move(level));
  }
}

// timing.early_records: each names one step of a level that the scenario runs.
void ReadEarlyRecords(ObjectReader& t, const std::vector<ScenarioLevel>& levels, std::vector<EarlyRecord>& out) {
  if (!t.Has("early_records")) return;
  const Json& list = t.Array("early_records");
  for (size_t i = 0; i < list.size(); ++i) {
    ObjectReader r(list[i], t.source(), "timing.early_records[" + std::to_string(i) + "]");
    EarlyRecord early;
    if (!r.Has("level")) r.FailField("level", "is required (the label of the level whose step is recorded early)");
    early.level = r.String("level", "");
    early.frequency_hz = r.Number("frequency_Hz");
    early.settle_s = r.Number("settle_s");
    if (!(early.settle_s > 0.0 && early.settle_s <= 3600.0))
      r.FailField("settle_s", "must lie in (0, 3600] s: the time integrated after the frequency change before the "
                              "recording starts");
    const auto level = std::find_if(levels.begin(), levels.end(), [&](const ScenarioLevel& l) { return l.label == early.level; });
    if (level == levels.end()) {
      std::string labels;
      for (const ScenarioLevel& l : levels) labels += (labels.empty() ? "" : ", ") + l.label;
      r.FailField("level", "'" + early.level + "' is not a level of the scenario; give one of: " + labels);
    }
    const auto steps = std::count_if(level->frequencies_hz.begin(), level->frequencies_hz.end(),
                                     [&](double f) { return SameNominalFrequency(early.frequency_hz, f); });
    if (steps == 0) {
      const auto [lowest, highest] = std::minmax_element(level->frequencies_hz.begin(), level->frequencies_hz.end());
      r.FailField("frequency_Hz", "= " + std::to_string(early.frequency_hz) + " Hz is not a step of level '" +
                                      early.level + "' (its " + std::to_string(level->frequencies_hz.size()) +
                                      " steps run from " + std::to_string(*lowest) + " to " + std::to_string(*highest) +
                                      " Hz); give one step's nominal frequency (to 1e-9 relative)");
    }
    if (steps > 1)
      r.FailField("frequency_Hz", "= " + std::to_string(early.frequency_hz) + " Hz is run " + std::to_string(steps) +
                                      " times by level '" + early.level + "'; an early record must name one step");
    for (size_t j = 0; j < out.size(); ++j)
      if (out[j].level == early.level && SameNominalFrequency(early.frequency_hz, out[j].frequency_hz))
        r.FailField("frequency_Hz", "names the step of timing.early_records[" + std::to_string(j) + "] again");
    out.push_back(std::move(early));
  }
}

void ReadTiming(ObjectReader& top, const std::vector<ScenarioLevel>& levels, ScenarioTiming& timing) {
  if (!top.Has("timing")) return;
  ObjectReader t(top.Raw("timing"), top.source(), "timing");
  timing.sample_rate_hz = t.Positive("sample_rate_Hz", timing.sample_rate_hz);
  timing.max_time_step_s = t.Positive("max_time_step_s", timing.max_time_step_s);
  timing.settle_min_s = t.NonNegative("settle_min_s", timing.settle_min_s);
  timing.settle_max_s = t.Positive("settle_max_s", timing.settle_max_s);
  timing.settle_tolerance = t.Positive("settle_tolerance", timing.settle_tolerance);
  timing.transient_s = t.NonNegative("transient_s", timing.transient_s);
  timing.record_s = t.Positive("record_s", timing.record_s);
  timing.restart_each_level = t.Bool("restart_each_level", timing.restart_each_level);
  timing.excitation_stop_fraction = t.NonNegative("excitation_stop_fraction", timing.excitation_stop_fraction);
  if (timing.excitation_stop_fraction != 0.0) {
    // The truth is fitted over the steady part before the stop, so the stop
    // must leave some of it (and happen before the file ends).
    const double earliest = timing.transient_s / (timing.transient_s + timing.record_s);
    if (!(timing.excitation_stop_fraction > earliest && timing.excitation_stop_fraction < 1.0))
      t.FailField("excitation_stop_fraction", "must be 0 (never) or lie between transient_s/(transient_s + record_s) = " +
                                                  std::to_string(earliest) +
                                                  " and 1, so that the force stops inside the steady record");
  }
  timing.daq_clock_error_relative = t.Number("daq_clock_error_relative", timing.daq_clock_error_relative);
  if (!(std::abs(timing.daq_clock_error_relative) <= kMaxDaqClockError))
    t.FailField("daq_clock_error_relative", "must lie within ±" + std::to_string(kMaxDaqClockError) +
                                                " (the acquisition's clock runs (1 + this) fast against the stated "
                                                "sample_rate_Hz; 0.002 is 2000 ppm, a rate stated 0.2 % low)");
  if (timing.settle_max_s < timing.settle_min_s) t.FailField("settle_max_s", "must not be below settle_min_s");
  // Limits that keep one simulated step within memory and minutes: at
  // most 2^24 samples per record, and a time step no finer than 1e-7 s.
  if (timing.record_s * timing.sample_rate_hz > 16777216.0)
    t.FailField("record_s", "times sample_rate_Hz gives more than 16777216 samples per record; record shorter");
  if (timing.max_time_step_s < 1e-7) t.FailField("max_time_step_s", "must be at least 1e-7 s");
  if (timing.settle_max_s > 3600.0) t.FailField("settle_max_s", "must not exceed 3600 s");
  ReadEarlyRecords(t, levels, timing.early_records);
}

void ReadNoiseSection(ObjectReader& top, Scenario& s) {
  if (!top.Has("noise")) return;
  ObjectReader n(top.Raw("noise"), top.source(), "noise");
  const double seed = n.NonNegative("seed", 1.0);
  if (seed != std::floor(seed) || seed > 9.0e15) n.FailField("seed", "must be a non-negative integer");
  s.seed = static_cast<std::uint64_t>(seed);
  s.clock_offset_ppm = n.Number("clock_offset_ppm", 0.0);
  if (std::abs(s.clock_offset_ppm) > 1e4) n.FailField("clock_offset_ppm", "must lie within ±10000 ppm");
  s.amplitude_creep_relative = n.Number("amplitude_creep_relative", 0.0);
  // The scale 1 + creep·(t/T − 1/2) must stay positive over the whole file,
  // whose transient (t < 0) continues the line.
  const double reach = s.timing.transient_s / s.timing.record_s + 0.5;
  if (!(std::abs(s.amplitude_creep_relative) * reach < 1.0))
    n.FailField("amplitude_creep_relative", "must lie within ±" + std::to_string(1.0 / reach) +
                                                " (the scale 1 + creep·(t/T − 1/2) must stay positive over the transient and the record)");
  if (n.Has("default")) {
    ObjectReader d(n.Raw("default"), top.source(), "noise.default");
    s.default_noise = ReadNoise(d);
  }
  if (n.Has("channels")) {
    const Json& channels = n.Raw("channels");
    if (!channels.is_object()) n.FailField("channels", "must map channel names to noise settings");
    for (const auto& [channel, spec] : channels.items()) {
      ObjectReader c(spec, top.source(), "noise.channels." + channel);
      s.channel_noise[channel] = ReadNoise(c);
    }
  }
}

// ---------------------------------------------------------------- consistency of the whole

void ValidateBeams(const Scenario& s, const std::string& source) {
  try {
    s.beam.Validate();
    s.nominal_beam.Validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(source + ": " + e.what() + ". Fix: give the beam in SI (m, Pa, kg/m³)");
  }
}

void CheckPositionsAndChannels(const Scenario& s, const std::string& source) {
  const double length = s.beam.length_m;
  auto inside = [&](double x, const std::string& what, bool allow_ends) {
    if (!(x >= 0.0 && x <= length) || (!allow_ends && (x <= 0.0 || x >= length)))
      throw std::invalid_argument(source + ": " + what + " = " + std::to_string(x) + " m lies outside the beam (0, " +
                                  std::to_string(length) + ") m");
  };
  if (!s.BaseExcitation()) inside(s.force_position_m, "excitation.position_m", false);
  std::set<std::string> channels{s.force_channel};
  if (s.force_channel.empty() || s.force_channel == "time_s")
    throw std::invalid_argument(source + ": excitation.channel must be a name other than time_s");
  for (size_t i = 0; i < s.sensors.size(); ++i) {
    const ScenarioSensor& sensor = s.sensors[i];
    inside(sensor.position_m, "sensor " + sensor.channel + " position_m", false);
    // The test plan may place a sensor at the support's end (x = L), not at the clamp.
    if (sensor.stated_position_m && !(*sensor.stated_position_m > 0.0 && *sensor.stated_position_m <= length))
      throw std::invalid_argument(source + ": sensors[" + std::to_string(i) + "].stated_position_m = " +
                                  std::to_string(*sensor.stated_position_m) + " m lies outside the beam (0, " +
                                  std::to_string(length) + "] m; give where the test plan says sensor " +
                                  sensor.channel + " is");
    // Absolute velocity and displacement would need the base's integrated
    // motion, whose constants a real rig does not define.
    if (s.BaseExcitation() && sensor.quantity != "acceleration")
      throw std::invalid_argument(source + ": sensor " + sensor.channel + " quantity must be acceleration with "
                                  "excitation.quantity \"base_acceleration\" (the sensors record absolute acceleration)");
    if (sensor.channel.empty() || sensor.channel == "time_s" || sensor.channel.find(',') != std::string::npos)
      throw std::invalid_argument(source + ": sensor channel '" + sensor.channel +
                                  "' must be a non-empty name without commas, other than time_s");
    if (!channels.insert(sensor.channel).second)
      throw std::invalid_argument(source + ": channel name '" + sensor.channel + "' is used twice");
  }
  for (double x : s.hidden_positions_m) inside(x, "hidden_positions_m", true);
  for (const PointMass& m : s.attachments.point_masses) inside(m.position_m, "attachments point mass position_m", true);
  for (const auto& [channel, noise] : s.channel_noise)
    if (!channels.count(channel))
      throw std::invalid_argument(source + ": noise.channels names '" + channel + "', which is not a channel");
}

void CheckLevelsAndFrequencies(const Scenario& s, const std::string& source) {
  std::set<std::string> labels;
  for (const ScenarioLevel& level : s.levels)
    if (!labels.insert(level.label).second)
      throw std::invalid_argument(source + ": level label '" + level.label + "' is used twice");
  const double nyquist_hz = 0.5 * s.timing.sample_rate_hz;
  for (const ScenarioLevel& level : s.levels)
    for (double f : level.frequencies_hz)
      if (5.0 * f >= nyquist_hz)
        throw std::invalid_argument(source + ": level " + level.label + " runs " + std::to_string(f) +
                                    " Hz, whose 5th harmonic is above the Nyquist frequency of sample_rate_Hz; "
                                    "raise timing.sample_rate_Hz");
  double max_frequency_hz = 0.0;
  for (const ScenarioLevel& level : s.levels)
    for (double f : level.frequencies_hz) max_frequency_hz = std::max(max_frequency_hz, f);
  for (const ForceHarmonic& h : s.force_distortion)
    if (h.harmonic * max_frequency_hz >= nyquist_hz)
      throw std::invalid_argument(source + ": excitation.distortion harmonic " + std::to_string(h.harmonic) +
                                  " exceeds the Nyquist frequency; raise timing.sample_rate_Hz");
}

// ---------------------------------------------------------------- writing, one helper per section

OrderedJson NoiseToJson(const ChannelNoise& n) {
  OrderedJson out = OrderedJson::object();
  out["relative_rms"] = n.relative_rms;
  out["absolute"] = n.absolute;
  out["adc_bits"] = n.adc_bits;
  out["adc_range"] = n.adc_range;
  out["pink_rms"] = n.pink_rms;
  return out;
}

OrderedJson ExcitationToJson(const Scenario& s) {
  OrderedJson distortion = OrderedJson::array();
  for (const ForceHarmonic& h : s.force_distortion) {
    OrderedJson j = OrderedJson::object();
    j["harmonic"] = h.harmonic;
    j["amplitude_ratio"] = h.amplitude_ratio;
    j["phase_rad"] = h.phase_rad;
    distortion.push_back(j);
  }
  OrderedJson out = OrderedJson::object();
  out["channel"] = s.force_channel;
  if (!s.BaseExcitation()) out["position_m"] = s.force_position_m;
  // The quantity and the amplifier's fields only when not a force drive: the
  // reader refuses the amplifier otherwise (and a force drive's file stays a
  // model file).
  if (s.excitation_quantity != ExcitationQuantity::kForce) out["quantity"] = ExcitationQuantityName(s.excitation_quantity);
  if (s.VoltageDrive()) {
    out["amplifier_gain_N_per_V"] = s.amplifier.gain_N_per_V;
    out["amplifier_sag"] = s.amplifier.sag;
  }
  out["distortion"] = distortion;
  return out;
}

OrderedJson SensorsToJson(const std::vector<ScenarioSensor>& sensors) {
  OrderedJson out = OrderedJson::array();
  for (const ScenarioSensor& sensor : sensors) {
    OrderedJson j = OrderedJson::object();
    j["channel"] = sensor.channel;
    j["position_m"] = sensor.position_m;
    j["quantity"] = sensor.quantity;
    j["unit"] = sensor.unit;
    j["mass_kg"] = sensor.mass_kg;
    // The artefacts only when set: a scenario without them stays a model
    // file (hb/model_file.h), whose sensors know no such fields.
    if (sensor.gain_error_relative != 0.0) j["gain_error_relative"] = sensor.gain_error_relative;
    if (sensor.delay_s != 0.0) j["delay_s"] = sensor.delay_s;
    if (sensor.stated_position_m) j["stated_position_m"] = *sensor.stated_position_m;
    out.push_back(j);
  }
  return out;
}

// The frequencies as the list in run order: the reader's range and
// "direction" are only ways of spelling that list.
OrderedJson LevelsToJson(const std::vector<ScenarioLevel>& levels, ExcitationQuantity quantity) {
  OrderedJson out = OrderedJson::array();
  for (const ScenarioLevel& level : levels) {
    OrderedJson j = OrderedJson::object();
    j["label"] = level.label;
    if (quantity == ExcitationQuantity::kVoltage) j["voltage_amplitude_V"] = level.voltage_amplitude_V;
    else if (quantity == ExcitationQuantity::kBaseAcceleration)
      j["base_acceleration_amplitude_m_s2"] = level.base_acceleration_amplitude_m_s2;
    else j["force_amplitude_N"] = level.force_amplitude_N;
    j["frequencies_Hz"] = level.frequencies_hz;
    out.push_back(j);
  }
  return out;
}

OrderedJson TimingToJson(const ScenarioTiming& t) {
  OrderedJson out = OrderedJson::object();
  out["sample_rate_Hz"] = t.sample_rate_hz;
  out["max_time_step_s"] = t.max_time_step_s;
  out["settle_min_s"] = t.settle_min_s;
  out["settle_max_s"] = t.settle_max_s;
  out["settle_tolerance"] = t.settle_tolerance;
  out["transient_s"] = t.transient_s;
  out["record_s"] = t.record_s;
  out["restart_each_level"] = t.restart_each_level;
  out["excitation_stop_fraction"] = t.excitation_stop_fraction;
  if (t.daq_clock_error_relative != 0.0) out["daq_clock_error_relative"] = t.daq_clock_error_relative;
  if (!t.early_records.empty()) {
    OrderedJson early = OrderedJson::array();
    for (const EarlyRecord& e : t.early_records) {
      OrderedJson j = OrderedJson::object();
      j["level"] = e.level;
      j["frequency_Hz"] = e.frequency_hz;
      j["settle_s"] = e.settle_s;
      early.push_back(j);
    }
    out["early_records"] = early;
  }
  return out;
}

OrderedJson NoiseSectionToJson(const Scenario& s) {
  OrderedJson channels = OrderedJson::object();
  for (const auto& [channel, noise] : s.channel_noise) channels[channel] = NoiseToJson(noise);
  OrderedJson out = OrderedJson::object();
  out["seed"] = s.seed;
  out["clock_offset_ppm"] = s.clock_offset_ppm;
  out["amplitude_creep_relative"] = s.amplitude_creep_relative;
  out["default"] = NoiseToJson(s.default_noise);
  out["channels"] = channels;
  return out;
}

}  // namespace

Scenario ParseScenario(const std::string& json_text, const std::string& source) {
  const Json root = ParseJson(json_text, source);
  Scenario s;
  // `top` refuses its unknown fields when it goes, after the checks of the whole.
  ObjectReader top(root, source, "");
  ReadFormat(top);
  s.name = top.String("name", "simulated stepped-sine campaign");
  ReadBeams(top, s);
  internal::ReadSupport(top, "docs/simulator.md", s.polynomial, s.jenkins, s.one_sided_stiffness_Nm_rad);
  internal::ReadAttachments(top, "docs/simulator.md", s.attachments);
  ReadDampingAndMesh(top, s);
  ReadExcitation(top, s);
  ReadSensorsAndHiddenPositions(top, s);
  ReadLevels(top, s);
  ReadTiming(top, s.levels, s.timing);
  ReadNoiseSection(top, s);
  ValidateBeams(s, source);
  CheckPositionsAndChannels(s, source);
  CheckLevelsAndFrequencies(s, source);
  return s;
}

Scenario ReadScenario(const std::filesystem::path& file) {
  return ParseScenario(ReadTextFile(file, "scenario file", "check the path"), file.string());
}

std::string ScenarioToJson(const Scenario& s) {
  OrderedJson root = OrderedJson::object();
  root["format"] = std::string(kScenarioFormat);
  root["beamid_version"] = kVersion;
  root["name"] = s.name;
  root["beam"] = internal::BeamToJson(s.beam);
  root["nominal_beam"] = internal::BeamToJson(s.nominal_beam);
  root["support"] = internal::SupportToJson(s.polynomial, s.jenkins, s.one_sided_stiffness_Nm_rad);
  root["attachments"] = internal::AttachmentsToJson(s.attachments);
  root["damping"] = {{"reference_frequency_Hz", s.damping_reference_frequency_hz}};
  if (!s.modal_damping_ratios.empty()) root["damping"]["modal_damping_ratios"] = s.modal_damping_ratios;
  root["mesh"] = {{"min_elements", s.mesh_min_elements}};
  root["excitation"] = ExcitationToJson(s);
  root["sensors"] = SensorsToJson(s.sensors);
  root["hidden_positions_m"] = s.hidden_positions_m;
  root["levels"] = LevelsToJson(s.levels, s.excitation_quantity);
  root["timing"] = TimingToJson(s.timing);
  root["noise"] = NoiseSectionToJson(s);
  return root.dump(2) + "\n";
}

void WriteScenarioFile(const std::filesystem::path& path, const Scenario& scenario) {
  WriteTextFileAtomically(path, ScenarioToJson(scenario));
}

}  // namespace beamid::hb
