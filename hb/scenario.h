// A simulation scenario: the true physics of a stepped-sine test (beam,
// support law, attachments, damping, force distortion) and how the test is
// run and recorded (levels, frequency steps, timing, sensors, noise). The
// JSON format (format "beamid-scenario/1") is documented in docs/simulator.md;
// `beamid simulate` turns a scenario into a campaign (docs/campaign-format.md)
// plus a truth file. The format is declared once (hb/json_schema.h); that
// declaration is its reader, its writer and its field table.
//
// Everything is SI except where a field names its unit (frequencies in Hz,
// clock offset in ppm, noise of a channel in the channel's written unit).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hb/beam_properties.h"
#include "hb/json_schema.h"
#include "hb/linear_attachments.h"
#include "hb/support_law.h"

namespace beamid::hb {

struct ScenarioSensor {
  std::string channel;
  double position_m = 0.0;
  std::string quantity = "acceleration";  // acceleration | velocity | displacement
  std::string unit = "m/s^2";             // a unit of docs/campaign-format.md matching the quantity
  // The sensor's mass: a point mass of the true beam, and written to
  // campaign.json (the engineer knows it). 0 = massless, not written.
  double mass_kg = 0.0;

  // Measurement artefacts, concealed from campaign.json and listed in
  // truth.json; the defaults record the beam as it is (docs/simulator.md).
  // A calibration off by this fraction: the channel records (1 + g)·signal,
  // before its noise. > −1.
  double gain_error_relative = 0.0;
  // The channel records the signal at t − delay_s (another anti-alias
  // filter than the other channels'). 0 ≤ delay_s ≤ kMaxSensorDelay_s.
  double delay_s = 0.0;
  // Where the test plan says the sensor is: the position written to
  // campaign.json. The beam is measured at position_m. Empty = position_m.
  std::optional<double> stated_position_m;

  double StatedPosition_m() const { return stated_position_m.value_or(position_m); }
  bool HasArtefact() const { return gain_error_relative != 0.0 || delay_s != 0.0 || stated_position_m.has_value(); }
};

// A delay is a filter's group delay, a few samples at most.
inline constexpr double kMaxSensorDelay_s = 0.01;
// A clock (or a stated sample rate) off by more than 5 % is a wrong setting,
// not a drifting crystal, and would move a sweep off its resonance.
inline constexpr double kMaxDaqClockError = 0.05;

// A step recorded before it settled (timing.early_records): the step of
// `level` whose nominal frequency is frequency_hz is recorded after
// settle_s of integration from its frequency change instead of the settling
// rule, so its recording holds a transient that has not decayed.
struct EarlyRecord {
  std::string level;          // a level's label
  double frequency_hz = 0.0;  // nominal; one of that level's steps
  double settle_s = 0.0;      // > 0: from the frequency change to the recording's first sample
};

// Harmonic k of the force relative to its fundamental:
// F(t) = F₁·[cos φ + Σ ratio_k·cos(kφ + phase_k)].
struct ForceHarmonic {
  int harmonic = 2;
  double amplitude_ratio = 0.0;
  double phase_rad = 0.0;
};

struct ScenarioLevel {
  std::string label;
  double force_amplitude_N = 0.0;   // fundamental of the controlled force (force drive only; 0 otherwise)
  // Fundamental of the amplifier's input voltage (voltage drive only; 0
  // otherwise). The force is then g(f)·voltage, see ScenarioAmplifier.
  double voltage_amplitude_V = 0.0;
  // Fundamental of the base's acceleration (base excitation; 0 otherwise).
  double base_acceleration_amplitude_m_s2 = 0.0;
  std::vector<double> frequencies_hz;  // nominal, in the order they are run
};

// Measurement noise of one channel, in the channel's written unit.
struct ChannelNoise {
  double relative_rms = 0.0;  // Gaussian σ as a fraction of the step's noise-free RMS
  double absolute = 0.0;      // Gaussian σ added on top
  int adc_bits = 0;           // 0 = no quantisation
  double adc_range = 0.0;     // full scale ±range; values beyond are clipped
  // RMS of a low-frequency 1/f ("pink") drift added to the channel, spanning
  // 1/T .. f_s/2 of each recording of duration T (hb/internal/pink_noise.h). 0 = none.
  double pink_rms = 0.0;
};

struct ScenarioTiming {
  double sample_rate_hz = 5120.0;
  // Upper bound on the integration step; the step is 1/(sample_rate·n) with
  // the smallest integer n that satisfies it.
  double max_time_step_s = 1.0 / 40000.0;
  // After each frequency change the simulator integrates at least settle_min_s
  // and at most settle_max_s, until the fundamental of every channel changes
  // by less than settle_tolerance (relative) between consecutive windows of
  // whole periods (≥ 40 ms each).
  double settle_min_s = 0.2;
  double settle_max_s = 6.0;
  double settle_tolerance = 1e-5;
  // Each recording starts with the last transient_s of the settling, then
  // record_s of steady state.
  double transient_s = 0.05;
  double record_s = 0.5;
  // Start every level from rest (the shaker stops between levels).
  bool restart_each_level = true;
  // The shaker is switched off inside every recording, at this fraction of
  // the recording's duration (file time, transient included); the beam then
  // rings down and the excitation channel records only its noise. 0 = never.
  // It must fall inside the steady part: > transient_s/(transient_s + record_s), < 1.
  double excitation_stop_fraction = 0.0;
  // A measurement artefact, concealed from campaign.json and listed in
  // truth.json: the acquisition's sample clock runs at
  // sample_rate_hz·(1 + ε) while the files state sample_rate_hz, so sample
  // n is taken at the true time n/(sample_rate_hz·(1 + ε)) and labelled
  // n/sample_rate_hz; every frequency read from the files is the true one
  // divided by 1 + ε. Not the generator's clock (noise.clock_offset_ppm),
  // which moves the excitation, not the time axis. |ε| ≤ kMaxDaqClockError.
  double daq_clock_error_relative = 0.0;
  // Steps recorded before they settled; empty = every step settles.
  std::vector<EarlyRecord> early_records;

  // The rate at which the acquisition truly samples [Hz].
  double TrueSampleRate_hz() const { return sample_rate_hz * (1.0 + daq_clock_error_relative); }
};

// What the excitation channel records and the level's amplitude sets
// (excitation.quantity): "force" (default) a force at excitation.position_m;
// "voltage" the amplifier's input (ScenarioAmplifier below);
// "base_acceleration" the acceleration a_b of the clamp and the support rod,
// which a shaker moves together: the beam, in coordinates relative to them,
// carries the inertial load −ρA·a_b (and −m·a_b on every point mass), and
// the sensors, all accelerometers, record the absolute acceleration
// (relative + a_b).
enum class ExcitationQuantity { kForce, kVoltage, kBaseAcceleration };
// "force", "voltage", "base_acceleration".
const char* ExcitationQuantityName(ExcitationQuantity quantity);

// What drives the shaker. With a force drive (the default) the level's
// amplitude is the force. With a voltage drive it is the amplifier's input
// voltage V0, the excitation channel records that voltage (in V), and the
// force applied is g(f)·V0 with a gain that sags near the first resonance
// (the amplifier's current limit against the shaker's back EMF):
//     g(f) = g0·(1 − sag/(1 + ((f − f1)/b)²)),  b = kAmplifierSagBandRelative·f1,
// f1 the true first natural frequency (the FE model with the law's initial
// stiffness). Each harmonic k of the voltage is applied with g(k·f).
struct ScenarioAmplifier {
  double gain_N_per_V = 0.0;       // g0 (voltage drive: required, > 0)
  double sag = 0.0;                // 0 ≤ sag < 1: relative dip of the gain at f1

  // g(f) [N/V] for the true first natural frequency f1.
  double Gain_N_per_V(double frequency_hz, double first_natural_hz) const;
};
inline constexpr double kAmplifierSagBandRelative = 0.02;

struct Scenario {
  std::string name = "simulated stepped-sine campaign";
  BeamProperties beam;          // the true beam (loss_factor: structural damping η)
  BeamProperties nominal_beam;  // written to campaign.json
  PolynomialSupportLaw::Coefficients polynomial;
  std::optional<JenkinsSupportLaw::Parameters_> jenkins;
  double one_sided_stiffness_Nm_rad = 0.0;  // OneSidedStiffnessLaw in parallel when non-zero
  LinearAttachments attachments;  // concealed attachments (sensor masses not included)
  // ω_ref/2π of the stiffness-proportional damping (0 = first natural frequency).
  double damping_reference_frequency_hz = 0.0;
  // ζ_j of modal damping of the beam's modes (hb/time_simulator.h), mode 1
  // first, beside beam's loss factor and Rayleigh damping; empty = none.
  std::vector<double> modal_damping_ratios;
  int mesh_min_elements = 40;

  std::string force_channel = "force";
  double force_position_m = 0.570;  // 0 with base excitation
  std::vector<ForceHarmonic> force_distortion;  // of the recorded excitation signal
  ExcitationQuantity excitation_quantity = ExcitationQuantity::kForce;
  ScenarioAmplifier amplifier;  // voltage drive only
  std::vector<ScenarioSensor> sensors;
  std::vector<double> hidden_positions_m;  // truth only, not in the campaign
  std::vector<ScenarioLevel> levels;
  ScenarioTiming timing;

  ChannelNoise default_noise;
  std::map<std::string, ChannelNoise> channel_noise;  // overrides per channel
  double clock_offset_ppm = 0.0;  // true f = nominal·(1 + ppm·1e-6)
  std::uint64_t seed = 1;
  // Every response channel's recorded signal is scaled by
  // 1 + creep·(t/T − 1/2) over each steady record of duration T (t from the
  // steady start; the transient before it continues the line), so the
  // record-mean amplitude is the truth and it creeps by `creep` over the
  // record (a sensor warming up). 0 = none.
  double amplitude_creep_relative = 0.0;

  // The true support law: the polynomial, plus the Jenkins element and the
  // one-sided stiffness in parallel.
  std::unique_ptr<SupportLaw> MakeSupportLaw() const;
  // Concealed attachments plus the sensors' masses.
  LinearAttachments TrueAttachments() const;
  const ChannelNoise& NoiseOf(const std::string& channel) const;
  bool VoltageDrive() const { return excitation_quantity == ExcitationQuantity::kVoltage; }
  bool BaseExcitation() const { return excitation_quantity == ExcitationQuantity::kBaseAcceleration; }
  int NumSteps() const;
  // The early record of the level's step at this nominal frequency (the
  // reader matched it to 1e-9 relative), or null.
  const EarlyRecord* EarlyRecordOf(const std::string& level, double nominal_frequency_hz) const;
};

// Size of a written unit in SI for a quantity (docs/campaign-format.md): 9.80665
// for acceleration in g, 1e-3 for mm or mm/s, 1 for SI; 0 if the unit does
// not belong to the quantity.
double UnitToSi(const std::string& quantity, const std::string& unit);

// The value of the optional "format" key. A file without it (every file
// written before the key) reads as this version; another value is refused.
inline constexpr std::string_view kScenarioFormat = "beamid-scenario/1";

// The fields of the JSON file: path, type, unit, range (docs/formats.md).
std::vector<schema::FieldDoc> ScenarioFields();

// Parses and validates a scenario. Throws InputError (a
// std::invalid_argument) naming `source` (the file), the field and what to
// fix; unknown fields are errors (a typo must not silently fall back to a
// default), and so is a "format" other than kScenarioFormat;
// "beamid_version" is accepted and ignored.
Scenario ParseScenario(const std::string& json_text, const std::string& source);
Scenario ReadScenario(const std::filesystem::path& file);

// Every field the reader reads, with "format" and "beamid_version", so that
// reading the text gives the same Scenario back. What the struct does not
// keep is written in its resolved form: the frequencies as the list in run
// order (no range, no "direction"), the nominal beam in full. A rigid
// attachment (infinite stiffness) is left out, as JSON has no infinity.
std::string ScenarioToJson(const Scenario& scenario);
// Atomically (hb/text_file.h): the old file or the new one, never half.
void WriteScenarioFile(const std::filesystem::path& path, const Scenario& scenario);

}  // namespace beamid::hb
