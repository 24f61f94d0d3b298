#include "signal/phasor_set_io.h"

#include "hb/input_limits.h"
#include "hb/strict_json.h"
#include "hb/version.h"
#include "hb/text_file.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "signal/input_error.h"

namespace beamid::signal {
namespace {

using nlohmann::json;

constexpr const char* kConvention =
    "x(t) = mean + sum_k Re(X_k exp(i k omega t)); X_k complex peak phasor in SI units; every step rotated so that "
    "the force fundamental X_1 is real and positive (harmonic k by k times the angle); std_re, std_im and "
    "correlation give the standard uncertainty of (Re X_k, Im X_k)";

json ChannelToJson(const ChannelPhasors& channel, const char* role) {
  json harmonics = json::array();
  for (const auto& h : channel.harmonics) {
    harmonics.push_back({{"k", h.harmonic},
                         {"re", h.value.real()},
                         {"im", h.value.imag()},
                         {"amplitude", h.Amplitude()},
                         {"phase_rad", h.PhaseRad()},
                         {"std_re", h.std_real},
                         {"std_im", h.std_imag},
                         {"correlation", h.correlation},
                         {"std_amplitude", h.AmplitudeStd()},
                         {"std_phase_rad", h.PhaseStdRad()}});
  }
  return {{"channel", channel.channel},
          {"role", role},
          {"quantity", QuantityName(channel.quantity)},
          {"unit", SiUnit(channel.quantity)},
          {"position_m", channel.position_m},
          {"mean", channel.mean},
          {"thd", channel.thd},
          {"snr_dB", channel.snr_db},
          {"noise_rms", channel.noise_rms},
          {"harmonics", harmonics}};
}

ChannelPhasors ChannelFromJson(const json& j) {
  ChannelPhasors channel;
  channel.channel = j.at("channel").get<std::string>();
  const auto quantity = ParseQuantity(j.at("quantity").get<std::string>());
  if (!quantity) throw std::invalid_argument("unknown quantity '" + j.at("quantity").get<std::string>() + "'");
  channel.quantity = *quantity;
  channel.position_m = j.at("position_m").get<double>();
  channel.mean = j.at("mean").get<double>();
  channel.thd = j.at("thd").get<double>();
  channel.snr_db = j.at("snr_dB").get<double>();
  channel.noise_rms = j.at("noise_rms").get<double>();
  for (const auto& h : j.at("harmonics")) {
    HarmonicPhasor phasor;
    phasor.harmonic = h.at("k").get<int>();
    phasor.value = {h.at("re").get<double>(), h.at("im").get<double>()};
    phasor.std_real = h.at("std_re").get<double>();
    phasor.std_imag = h.at("std_im").get<double>();
    phasor.correlation = h.at("correlation").get<double>();
    channel.harmonics.push_back(phasor);
  }
  return channel;
}

// The ranges of what extract writes: a value outside them was not measured
// (a negative uncertainty, a frequency of 0 Hz) and would reach the fit as a
// number. Each complaint names the entry's path in the file.
// extract's -H takes 1..50.
constexpr int kMaxPhasorHarmonics = 50;

void CheckPhasorSet(const PhasorSet& set, const std::string& source) {
  auto fail = [&](const std::string& where, const std::string& channel, double value, const std::string& problem) {
    char shown[32];
    std::snprintf(shown, sizeof shown, "%g", value);
    throw InputError(source, channel, where + " = " + shown + " " + problem,
                     "give the phasors file written by 'beamid extract' (see docs/signal.md), unedited");
  };
  if (set.num_harmonics < 1 || set.num_harmonics > kMaxPhasorHarmonics)
    fail("num_harmonics", "", set.num_harmonics, "must lie in 1.." + std::to_string(kMaxPhasorHarmonics));
  for (std::size_t i = 0; i < set.steps.size(); ++i) {
    const StepPhasors& step = set.steps[i];
    const std::string where = "steps[" + std::to_string(i) + "]";
    if (!(step.nominal_frequency_hz > 0.0)) fail(where + ".nominal_frequency_Hz", "", step.nominal_frequency_hz, "must be positive");
    if (!(step.frequency_hz > 0.0)) fail(where + ".frequency_Hz", "", step.frequency_hz, "must be positive");
    if (!(step.frequency_std_hz >= 0.0)) fail(where + ".frequency_std_Hz", "", step.frequency_std_hz, "must not be negative");
    if (step.responses.size() > static_cast<std::size_t>(hb::kMaxPointsOnBeam))
      fail(where + ".channels", "", static_cast<double>(step.responses.size()),
           "response channels are more than the " + std::to_string(hb::kMaxPointsOnBeam) + " beamid analyses");
    for (std::size_t c = 0; c <= step.responses.size(); ++c) {
      const ChannelPhasors& channel = c == 0 ? step.force : step.responses[c - 1];
      const std::string at = where + ".channels[" + std::to_string(c) + "]";
      if (channel.harmonics.size() > static_cast<std::size_t>(set.num_harmonics) + 1)
        fail(at + ".harmonics", channel.channel, static_cast<double>(channel.harmonics.size()),
             "phasors are more than num_harmonics + 1");
      for (std::size_t k = 0; k < channel.harmonics.size(); ++k) {
        const HarmonicPhasor& h = channel.harmonics[k];
        const std::string hk = at + ".harmonics[" + std::to_string(k) + "]";
        if (h.harmonic < 0 || h.harmonic > set.num_harmonics)
          fail(hk + ".k", channel.channel, h.harmonic, "must lie in 0..num_harmonics");
        if (!std::isfinite(h.value.real()) || !std::isfinite(h.value.imag()))
          fail(hk + ".re", channel.channel, h.value.real(), "or its im is not a finite number");
        if (!(h.std_real >= 0.0)) fail(hk + ".std_re", channel.channel, h.std_real, "must not be negative");
        if (!(h.std_imag >= 0.0)) fail(hk + ".std_im", channel.channel, h.std_imag, "must not be negative");
        if (!(std::abs(h.correlation) <= 1.0))
          fail(hk + ".correlation", channel.channel, h.correlation, "must lie in [-1, 1]");
      }
    }
  }
}

}  // namespace

std::string PhasorSetToJson(const PhasorSet& set) {
  json steps = json::array();
  for (const auto& step : set.steps) {
    json channels = json::array();
    channels.push_back(ChannelToJson(step.force, "excitation"));
    for (const auto& response : step.responses) channels.push_back(ChannelToJson(response, "response"));
    json quality = {{"snr_dB", step.quality.snr_db},
                    {"settled_after_s", step.quality.settled_after_s},
                    {"analysed_duration_s", step.quality.analysed_duration_s},
                    {"settling", step.quality.settling},
                    {"warnings", step.quality.warnings}};
    if (!step.quality.notes.empty()) quality["notes"] = step.quality.notes;
    if (step.quality.unsettled)
      quality["unsettled"] = {{"change_relative", step.quality.unsettled_change_relative},
                              {"channel", step.quality.unsettled_channel}};
    steps.push_back({{"file", step.file},
                     {"level", step.level},
                     {"nominal_frequency_Hz", step.nominal_frequency_hz},
                     {"frequency_Hz", step.frequency_hz},
                     {"frequency_std_Hz", step.frequency_std_hz},
                     {"quality", quality},
                     {"channels", channels}});
  }
  json root = {{"format", kPhasorFormat},
               {"beamid_version", kVersion},
               {"convention", kConvention},
               {"campaign", set.campaign},
               {"campaign_sha256", set.campaign_sha256},
               {"num_harmonics", set.num_harmonics},
               {"steps", steps}};
  if (!set.skipped.empty()) {
    json skipped = json::array();
    for (const auto& step : set.skipped)
      skipped.push_back({{"file", step.file},
                         {"level", step.level},
                         {"nominal_frequency_Hz", step.nominal_frequency_hz},
                         {"reason", step.reason}});
    root["skipped_steps"] = skipped;
  }
  return root.dump(1) + "\n";
}

PhasorSet PhasorSetFromJson(std::string_view json_text, const std::string& source) {
  try {
    const json root = ParseStrictJson<json>(json_text, source, "see docs/signal.md");
    if (root.at("format").get<std::string>() != kPhasorFormat)
      throw InputError(source, "", "format '" + root.at("format").get<std::string>() + "' is not supported",
                       "give a phasors file written by 'beamid extract' (" + std::string(kPhasorFormat) + ")");
    PhasorSet set;
    set.campaign = root.at("campaign").get<std::string>();
    if (root.contains("campaign_sha256")) set.campaign_sha256 = root.at("campaign_sha256").get<std::string>();
    set.num_harmonics = root.at("num_harmonics").get<int>();
    for (const auto& s : root.at("steps")) {
      StepPhasors step;
      step.file = s.at("file").get<std::string>();
      step.level = s.at("level").get<std::string>();
      step.nominal_frequency_hz = s.at("nominal_frequency_Hz").get<double>();
      step.frequency_hz = s.at("frequency_Hz").get<double>();
      step.frequency_std_hz = s.at("frequency_std_Hz").get<double>();
      const json& q = s.at("quality");
      step.quality.snr_db = q.at("snr_dB").get<double>();
      step.quality.settled_after_s = q.at("settled_after_s").get<double>();
      step.quality.analysed_duration_s = q.at("analysed_duration_s").get<double>();
      step.quality.settling = q.at("settling").get<std::string>();
      step.quality.warnings = q.at("warnings").get<std::vector<std::string>>();
      if (q.contains("notes")) step.quality.notes = q.at("notes").get<std::vector<std::string>>();
      if (q.contains("unsettled")) {
        step.quality.unsettled = true;
        step.quality.unsettled_change_relative = q.at("unsettled").at("change_relative").get<double>();
        step.quality.unsettled_channel = q.at("unsettled").at("channel").get<std::string>();
      }
      const json& channels = s.at("channels");
      if (channels.empty() || channels.front().at("role") != "excitation")
        throw std::invalid_argument("step '" + step.file + "' does not start with its excitation channel");
      step.force = ChannelFromJson(channels.front());
      for (std::size_t c = 1; c < channels.size(); ++c) step.responses.push_back(ChannelFromJson(channels[c]));
      set.steps.push_back(std::move(step));
    }
    if (root.contains("skipped_steps"))
      for (const auto& s : root.at("skipped_steps"))
        set.skipped.push_back({.file = s.at("file").get<std::string>(),
                               .level = s.at("level").get<std::string>(),
                               .nominal_frequency_hz = s.at("nominal_frequency_Hz").get<double>(),
                               .reason = s.at("reason").get<std::string>()});
    CheckPhasorSet(set, source);
    return set;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(source, "", std::string("not a valid phasors file (") + e.what() + ")",
                     "give a phasors file written by 'beamid extract'");
  }
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
