#include "hb/campaign_writer.h"

#include "hb/version.h"
#include "hb/errors.h"
#include "hb/text_file.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <numbers>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

namespace beamid::hb {
namespace {

using Json = nlohmann::json;

constexpr int kCsvSignificantDigits = 9;

void AppendNumber(std::string& out, double value, int precision) {
  char buffer[64];
  const auto result = precision > 0
                          ? std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, precision)
                          : std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

Json BeamJson(const BeamProperties& beam, bool with_loss) {
  Json j = {{"length_m", beam.length_m},
            {"width_m", beam.width_m},
            {"thickness_m", beam.thickness_m},
            {"youngs_modulus_Pa", beam.youngs_modulus_Pa},
            {"density_kg_m3", beam.density_kg_m3}};
  if (with_loss) j["loss_factor"] = beam.loss_factor;
  return j;
}

// Infinite (rigid) stiffnesses are written as null: JSON has no infinity.
Json StiffnessJson(double value) { return std::isfinite(value) ? Json(value) : Json(nullptr); }

Json PhasorsJson(const Eigen::VectorXcd& x) {
  Json harmonics = Json::array();
  for (Eigen::Index k = 1; k < x.size(); ++k) harmonics.push_back({x(k).real(), x(k).imag()});
  return {{"mean", x(0).real()}, {"harmonics", harmonics}};
}

// The rig's quirks are written only when present, so that a campaign
// without them is byte for byte what it was before they existed.
Json NoiseJson(const ChannelNoise& n) {
  Json j = {{"relative_rms", n.relative_rms}, {"absolute", n.absolute}, {"adc_bits", n.adc_bits}, {"adc_range", n.adc_range}};
  if (n.pink_rms > 0.0) j["pink_rms"] = n.pink_rms;
  return j;
}

// campaign.json's excitation: the force transducer, or with a voltage drive
// the amplifier's input voltage and its nominal gain g0 (what an engineer
// reads off the amplifier; the sag near resonance is concealed).
CampaignChannel CampaignExcitation(const Scenario& s) {
  if (s.BaseExcitation())
    return {.channel = s.force_channel, .position_m = 0.0, .quantity = "base_acceleration", .unit = "m/s^2"};
  if (!s.VoltageDrive())
    return {.channel = s.force_channel, .position_m = s.force_position_m, .quantity = "force", .unit = "N"};
  return {.channel = s.force_channel,
          .position_m = s.force_position_m,
          .quantity = "voltage",
          .unit = "V",
          .sensitivity_N_per_V = s.amplifier.gain_N_per_V};
}

void WriteFile(const std::filesystem::path& path, const std::string& text, std::uintmax_t& bytes) {
  WriteTextFileAtomically(path, text);
  bytes += text.size();
}

}  // namespace

CampaignWriter::CampaignWriter(const SteppedSineSimulation& simulation, const std::filesystem::path& directory,
                               const CampaignWriterOptions& options)
    : simulation_(simulation),
      directory_(directory),
      live_(options.live),
      noise_(simulation.scenario().seed),
      truth_steps_(std::make_unique<Json>(Json::array())),
      early_records_(std::make_unique<Json>(Json::array())) {
  const Scenario& s = simulation_.scenario();
  std::error_code error;
  std::filesystem::create_directories(directory_, error);
  if (error) throw std::invalid_argument(directory_.string() + ": cannot create the output directory (" + error.message() + ")");
  if (!options.overwrite && std::filesystem::exists(directory_ / "campaign.json"))
    throw std::invalid_argument(directory_.string() +
                                ": holds a campaign.json already; choose another directory or pass --overwrite");
  // campaign.json is the folder's completion mark, written last (Finish;
  // live, after each step: the steps written so far): while the steps are
  // rewritten the folder must not read as a campaign of the old steps.
  std::filesystem::remove(directory_ / "campaign.json", error);
  for (const ScenarioLevel& level : s.levels) {
    std::filesystem::create_directories(directory_ / level.label, error);
    if (error) throw std::invalid_argument((directory_ / level.label).string() + ": cannot create (" + error.message() + ")");
  }
}

CampaignWriter::~CampaignWriter() = default;

void CampaignWriter::Write(const SimulatedStep& step) {
  const Scenario& s = simulation_.scenario();
  const double fs = s.timing.sample_rate_hz;
  std::vector<std::string> names{s.force_channel};
  for (const ScenarioSensor& sensor : s.sensors) names.push_back(sensor.channel);

  const Eigen::MatrixXd written = noise_.Measure(s, step.recording, step.transient_samples, &clipped_samples_);
  std::string csv = "time_s";
  for (const std::string& name : names) csv += "," + name;
  csv += "\n";
  csv.reserve(static_cast<size_t>(written.rows()) * (written.cols() + 1) * 16);
  for (Eigen::Index i = 0; i < written.rows(); ++i) {
    AppendNumber(csv, static_cast<double>(i) / fs, 0);
    for (Eigen::Index c = 0; c < written.cols(); ++c) {
      csv += ',';
      AppendNumber(csv, written(i, c), kCsvSignificantDigits);
    }
    csv += '\n';
  }
  WriteFile(directory_ / step.file, csv, bytes_written_);

  campaign_steps_.push_back({.file = step.file, .frequency_hz = step.nominal_frequency_hz, .level = step.level});

  Json channels = Json::object();
  channels[s.force_channel] = PhasorsJson(step.channel_phasors[0]);
  channels[s.force_channel]["quantity"] = ExcitationQuantityName(s.excitation_quantity);
  channels[s.force_channel]["unit"] = s.VoltageDrive() ? "V" : s.BaseExcitation() ? "m/s^2" : "N";
  for (size_t i = 0; i < s.sensors.size(); ++i) {
    const ScenarioSensor& sensor = s.sensors[i];
    Json c = PhasorsJson(step.channel_phasors[i + 1]);
    c["quantity"] = sensor.quantity;
    c["unit"] = sensor.quantity == "acceleration" ? "m/s^2" : sensor.quantity == "velocity" ? "m/s" : "m";
    channels[sensor.channel] = c;
  }
  Json hidden = Json::array();
  for (size_t h = 0; h < s.hidden_positions_m.size(); ++h)
    hidden.push_back({{"position_m", s.hidden_positions_m[h]},
                      {"displacement_m", PhasorsJson(step.hidden_displacement_phasors[h])}});
  Json truth_step = {{"file", step.file},
                      {"level", step.level},
                      {"nominal_frequency_Hz", step.nominal_frequency_hz},
                      {"frequency_Hz", step.frequency_hz},
                      {"force_amplitude_N", step.force_amplitude_N},
                      {"settle_s", step.settle_s},
                      {"settled", step.settled},
                      {"settle_change", step.settle_change},
                      {"steady_start_s", step.transient_samples / fs},
                      {"channels", channels},
                      {"hidden", hidden},
                      {"support_rotation_rad", PhasorsJson(step.support_rotation_phasors)},
                      {"support_moment_Nm", PhasorsJson(step.support_moment_phasors)}};
  if (s.BaseExcitation()) {
    // No force acts: the base's acceleration is the drive (channels.<excitation>).
    truth_step.erase("force_amplitude_N");
    truth_step["base_acceleration_amplitude_m_s2"] = step.base_acceleration_amplitude_m_s2;
  }
  if (s.VoltageDrive()) {
    truth_step["voltage_amplitude_V"] = step.voltage_amplitude_V;
    truth_step["force_N"] = PhasorsJson(step.force_phasors);  // the true force: channel 0 holds the voltage
  }
  if (step.excitation_stop_s) truth_step["excitation_stop_s"] = *step.excitation_stop_s;
  if (step.early_record_settle_s) {
    truth_step["early_record_settle_s"] = *step.early_record_settle_s;
    early_records_->push_back({{"file", step.file},
                               {"level", step.level},
                               {"nominal_frequency_Hz", step.nominal_frequency_hz},
                               {"settle_s", *step.early_record_settle_s}});
  }
  truth_steps_->push_back(std::move(truth_step));
  // As an acquisition that lists each step once its file is whole.
  if (live_) WriteFile(directory_ / "campaign.json", CampaignFileToJson(CampaignSoFar()), bytes_written_);
}

CampaignFile CampaignWriter::CampaignSoFar() const {
  const Scenario& s = simulation_.scenario();
  CampaignFile campaign{.name = s.name,
                        .beam = s.nominal_beam,
                        .excitation = CampaignExcitation(s),
                        .steps = campaign_steps_,
                        .sample_rate_hz = s.timing.sample_rate_hz};
  for (const ScenarioSensor& sensor : s.sensors) {
    // Where the test plan says the sensor is, which need not be where it is.
    CampaignChannel c{.channel = sensor.channel,
                      .position_m = sensor.StatedPosition_m(),
                      .quantity = sensor.quantity,
                      .unit = sensor.unit};
    if (sensor.mass_kg > 0.0) c.mass_kg = sensor.mass_kg;
    campaign.sensors.push_back(c);
  }
  return campaign;
}

void CampaignWriter::Finish() {
  const Scenario& s = simulation_.scenario();
  const TimeSimulator& sim = simulation_.simulator();
  const CampaignFile campaign = CampaignSoFar();

  const std::unique_ptr<SupportLaw> law = s.MakeSupportLaw();
  Json parameters = Json::array();
  for (const LawParameter& p : law->Parameters()) parameters.push_back({{"name", p.name}, {"value", p.value}, {"unit", p.unit}});
  Json point_masses = Json::array();
  for (const PointMass& m : s.attachments.point_masses)
    point_masses.push_back({{"position_m", m.position_m}, {"mass_kg", m.mass_kg}});
  Json distortion = Json::array();
  for (const ForceHarmonic& h : s.force_distortion)
    distortion.push_back({{"harmonic", h.harmonic}, {"amplitude_ratio", h.amplitude_ratio}, {"phase_rad", h.phase_rad}});
  Json natural = Json::array();
  for (double w : sim.fe_beam().NaturalFrequencies_rad_s(3, law->InitialStiffness_Nm_rad()))
    natural.push_back(w / (2 * std::numbers::pi));
  Json noise = {{"seed", s.seed}, {"default", NoiseJson(s.default_noise)}, {"channels", Json::object()}};
  for (const auto& [channel, n] : s.channel_noise) noise["channels"][channel] = NoiseJson(n);
  if (s.amplitude_creep_relative != 0.0) noise["amplitude_creep_relative"] = s.amplitude_creep_relative;
  Json excitation = {{"channel", s.force_channel}, {"position_m", s.force_position_m}, {"distortion", distortion}};
  if (s.BaseExcitation()) excitation["quantity"] = "base_acceleration";
  if (s.VoltageDrive()) {
    excitation["quantity"] = "voltage";
    excitation["amplifier"] = {{"gain_N_per_V", s.amplifier.gain_N_per_V},
                               {"sag", s.amplifier.sag},
                               {"sag_center_Hz", simulation_.first_natural_frequency_hz()},
                               {"sag_band_Hz", kAmplifierSagBandRelative * simulation_.first_natural_frequency_hz()}};
  }
  if (s.timing.excitation_stop_fraction > 0.0) excitation["stop_fraction"] = s.timing.excitation_stop_fraction;

  // The measurement artefacts, only when the scenario has one (a campaign
  // without them is byte for byte what it was before they existed). Every
  // sensor is listed, so that a test reads any one's true and stated position.
  bool any_artefact = !s.timing.early_records.empty() || s.timing.daq_clock_error_relative != 0.0;
  Json artefact_sensors = Json::array();
  for (const ScenarioSensor& sensor : s.sensors) {
    any_artefact = any_artefact || sensor.HasArtefact();
    artefact_sensors.push_back({{"channel", sensor.channel},
                                {"position_m", sensor.position_m},
                                {"stated_position_m", sensor.StatedPosition_m()},
                                {"gain_error_relative", sensor.gain_error_relative},
                                {"delay_s", sensor.delay_s}});
  }

  Json truth = {
      {"format", "beamid-simulation-truth/1"},
      {"beamid_version", kVersion},
      {"scenario", s.name},
      {"beam", BeamJson(s.beam, true)},
      {"nominal_beam", BeamJson(s.nominal_beam, false)},
      {"support_law",
       {{"name", law->Name()},
        {"parameters", parameters},
        {"polynomial",
         {{"k1_Nm_rad", s.polynomial.k1_Nm_rad},
          {"k2_Nm_rad2", s.polynomial.k2_Nm_rad2},
          {"k3_Nm_rad3", s.polynomial.k3_Nm_rad3},
          {"c_Nms_rad", s.polynomial.c_Nms_rad}}},
        {"jenkins", s.jenkins ? Json{{"stiffness_Nm_rad", s.jenkins->stiffness_Nm_rad},
                                     {"slip_moment_Nm", s.jenkins->slip_moment_Nm}}
                              : Json(nullptr)},
         {"one_sided", s.one_sided_stiffness_Nm_rad != 0.0 ? Json{{"stiffness_Nm_rad", s.one_sided_stiffness_Nm_rad}}
                                                           : Json(nullptr)}}},
      {"attachments",
       {{"clamp_rotational_stiffness_Nm_rad", StiffnessJson(s.attachments.clamp_rotational_stiffness_Nm_rad)},
        {"support_translational_stiffness_N_m", StiffnessJson(s.attachments.support_translational_stiffness_N_m)},
        {"point_masses", point_masses}}},
      {"damping",
       s.damping_reference_frequency_hz > 0.0
           ? Json{{"model", "stiffness-proportional, C = beta*K"},
                  {"loss_factor", s.beam.loss_factor},
                  {"reference_frequency_Hz", sim.damping_reference_rad_s() / (2 * std::numbers::pi)},
                  {"beta_s", sim.stiffness_proportional_damping_s()}}
           : Json{{"model", "hysteretic at each step: modal c_j = eta*w_j^2/(k_j*w), k_j*w the harmonic nearest w_j"},
                  {"loss_factor", s.beam.loss_factor}}},
      {"viscous_damping",
       {{"rayleigh_mass_1_s", s.beam.rayleigh_mass_1_s},
        {"rayleigh_stiffness_s", s.beam.rayleigh_stiffness_s},
        {"modal_damping_ratios", s.modal_damping_ratios}}},
      {"excitation", excitation},
      {"generator_clock_offset_ppm", s.clock_offset_ppm},
      {"sample_rate_Hz", s.timing.sample_rate_hz},
      {"time_step_s", sim.time_step_s()},
      {"fe_elements", sim.fe_beam().NumElements()},
      {"natural_frequencies_Hz", natural},
      {"hidden_positions_m", s.hidden_positions_m},
      {"noise", noise},
      {"clipped_samples", clipped_samples_},
      {"steps", *truth_steps_}};
  if (any_artefact)
    truth["measurement_artefacts"] = {{"sensors", artefact_sensors},
                                      {"early_records", *early_records_},
                                      {"daq_clock_error_relative", s.timing.daq_clock_error_relative}};
  WriteFile(directory_ / "truth.json", truth.dump(1) + "\n", bytes_written_);
  // Last: a folder with campaign.json is a complete campaign.
  WriteFile(directory_ / "campaign.json", CampaignFileToJson(campaign), bytes_written_);
}

}  // namespace beamid::hb
