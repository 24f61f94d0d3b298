// A simulation scenario: the true physics of a stepped-sine test (beam,
// support law, attachments, damping, force distortion) and how the test is
// run and recorded (levels, frequency steps, timing, sensors, noise). The
// JSON format (format "beamid-scenario/1") is documented in docs/simulator.md;
// `beamid simulate` turns a scenario into a campaign (docs/campaign-format.md)
// plus a truth file. This file holds the format's one reader and writer.
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
  double force_amplitude_N = 0.0;   // fundamental of the controlled force
  std::vector<double> frequencies_hz;  // nominal, in the order they are run
};

// Measurement noise of one channel, in the channel's written unit.
struct ChannelNoise {
  double relative_rms = 0.0;  // Gaussian σ as a fraction of the step's noise-free RMS
  double absolute = 0.0;      // Gaussian σ added on top
  int adc_bits = 0;           // 0 = no quantisation
  double adc_range = 0.0;     // full scale ±range; values beyond are clipped
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
};

struct Scenario {
  std::string name;
  BeamProperties beam;          // the true beam (loss_factor: structural damping η)
  BeamProperties nominal_beam;  // written to campaign.json
  PolynomialSupportLaw::Coefficients polynomial;
  std::optional<JenkinsSupportLaw::Parameters_> jenkins;
  double one_sided_stiffness_Nm_rad = 0.0;  // OneSidedStiffnessLaw in parallel when non-zero
  LinearAttachments attachments;  // concealed attachments (sensor masses not included)
  // ω_ref/2π of the stiffness-proportional damping (0 = first natural frequency).
  double damping_reference_frequency_hz = 0.0;
  int mesh_min_elements = 40;

  std::string force_channel = "force";
  double force_position_m = 0.570;
  std::vector<ForceHarmonic> force_distortion;
  std::vector<ScenarioSensor> sensors;
  std::vector<double> hidden_positions_m;  // truth only, not in the campaign
  std::vector<ScenarioLevel> levels;
  ScenarioTiming timing;

  ChannelNoise default_noise;
  std::map<std::string, ChannelNoise> channel_noise;  // overrides per channel
  double clock_offset_ppm = 0.0;  // true f = nominal·(1 + ppm·1e-6)
  std::uint64_t seed = 1;

  // The true support law: the polynomial, plus the Jenkins element and the
  // one-sided stiffness in parallel.
  std::unique_ptr<SupportLaw> MakeSupportLaw() const;
  // Concealed attachments plus the sensors' masses.
  LinearAttachments TrueAttachments() const;
  const ChannelNoise& NoiseOf(const std::string& channel) const;
  int NumSteps() const;
};

// Size of a written unit in SI for a quantity (docs/campaign-format.md): 9.80665
// for acceleration in g, 1e-3 for mm or mm/s, 1 for SI; 0 if the unit does
// not belong to the quantity.
double UnitToSi(const std::string& quantity, const std::string& unit);

// The value of the optional "format" key. A file without it (every file
// written before the key) reads as this version; another value is refused.
inline constexpr std::string_view kScenarioFormat = "beamid-scenario/1";

// Parses and validates a scenario. Throws std::invalid_argument naming
// `source` (the file), the field and what to fix; unknown fields are errors
// (a typo must not silently fall back to a default). A "format" other than
// kScenarioFormat is an InputError; "beamid_version" is accepted and ignored.
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
