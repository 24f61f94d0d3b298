// read_campaign and extract: a campaign folder and its harmonic phasors, as
// `beamid extract` computes them (solver/workflow/extract_campaign.h).
#include <cstdint>
#include <map>
#include <utility>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "signal/campaign.h"
#include "signal/phasor_set.h"
#include "signal/quantity.h"
#include "solver/python/module_functions.h"
#include "solver/python/python_arrays.h"
#include "solver/python/python_errors.h"
#include "solver/python/python_run.h"
#include "solver/workflow/campaign_input.h"
#include "solver/workflow/extract_campaign.h"

namespace py = pybind11;
using namespace pybind11::literals;

namespace beamid::python {
namespace {

py::dict ChannelSpecToPython(const signal::ChannelSpec& spec) {
  py::dict d("channel"_a = spec.channel, "position_m"_a = spec.position_m,
             "quantity"_a = std::string(signal::QuantityName(spec.quantity)), "unit"_a = spec.unit,
             "to_si_factor"_a = spec.to_si_factor, "mass_kg"_a = OrNone(spec.mass_kg));
  return d;
}

py::dict CampaignToPython(const signal::Campaign& campaign) {
  py::dict d("name"_a = campaign.name, "folder"_a = campaign.folder.string(), "sha256"_a = campaign.sha256);
  const hb::BeamProperties& beam = campaign.beam;
  d["beam"] = py::dict(py::arg("length_m") = beam.length_m, py::arg("width_m") = beam.width_m,
                       py::arg("thickness_m") = beam.thickness_m, py::arg("youngs_modulus_Pa") = beam.youngs_modulus_Pa,
                       py::arg("density_kg_m3") = beam.density_kg_m3, py::arg("loss_factor") = beam.loss_factor);
  d["excitation"] = ChannelSpecToPython(campaign.excitation);
  py::list sensors;
  for (const signal::ChannelSpec& s : campaign.sensors) sensors.append(ChannelSpecToPython(s));
  d["sensors"] = sensors;
  d["ignored_channels"] = ToList(campaign.ignored_channels);
  d["sample_rate_hz"] = OrNone(campaign.sample_rate_hz);
  py::list steps, levels;
  for (const signal::Step& step : campaign.steps) {
    steps.append(py::dict(py::arg("file") = step.file, py::arg("frequency_hz") = step.frequency_hz,
                          py::arg("level") = step.level));
    if (!levels.contains(step.level)) levels.append(step.level);
  }
  d["steps"] = steps;
  d["levels"] = levels;
  d["warnings"] = ToList(campaign.warnings);
  return d;
}

// One channel's phasors over a level's steps: rows are steps, columns
// harmonics 1..H; NaN where a step lacks the channel or the harmonic.
struct ChannelColumns {
  std::string quantity, unit;
  double position_m = 0.0;
  py::array_t<std::complex<double>> phasors;
  py::array_t<double> std_real, std_imag, correlation, std_amplitude, std_phase_rad;
  py::array_t<double> mean, thd, snr_db, noise_rms;
};

// steps: the level's, with their index among all the extracted steps.
py::dict LevelToPython(const std::vector<std::pair<std::size_t, const signal::StepPhasors*>>& steps,
                       int num_harmonics) {
  const std::size_t n = steps.size();
  py::list files;
  py::array_t<std::int64_t> index(static_cast<py::ssize_t>(n));
  py::array_t<double> nominal = NanArray(n), frequency = NanArray(n), frequency_std = NanArray(n),
                      step_snr = NanArray(n);
  std::vector<std::string> order;
  std::map<std::string, ChannelColumns> channels;
  for (std::size_t i = 0; i < n; ++i) {
    const signal::StepPhasors& step = *steps[i].second;
    const auto row = static_cast<py::ssize_t>(i);
    index.mutable_at(row) = static_cast<std::int64_t>(steps[i].first);
    files.append(step.file);
    nominal.mutable_at(row) = step.nominal_frequency_hz;
    frequency.mutable_at(row) = step.frequency_hz;
    frequency_std.mutable_at(row) = step.frequency_std_hz;
    step_snr.mutable_at(row) = step.quality.snr_db;
    std::vector<const signal::ChannelPhasors*> present{&step.force};
    for (const auto& r : step.responses) present.push_back(&r);
    for (const signal::ChannelPhasors* c : present) {
      auto [it, added] = channels.try_emplace(c->channel);
      ChannelColumns& columns = it->second;
      if (added) {
        order.push_back(c->channel);
        columns.quantity = std::string(signal::QuantityName(c->quantity));
        columns.unit = std::string(signal::SiUnit(c->quantity));
        columns.position_m = c->position_m;
        const auto h = static_cast<std::size_t>(num_harmonics);
        columns.phasors = NanMatrix<std::complex<double>>(n, h);
        for (auto* a : {&columns.std_real, &columns.std_imag, &columns.correlation, &columns.std_amplitude,
                        &columns.std_phase_rad})
          *a = NanMatrix<double>(n, h);
        for (auto* a : {&columns.mean, &columns.thd, &columns.snr_db, &columns.noise_rms}) *a = NanArray(n);
      }
      columns.mean.mutable_at(row) = c->mean;
      columns.thd.mutable_at(row) = c->thd;
      columns.snr_db.mutable_at(row) = c->snr_db;
      columns.noise_rms.mutable_at(row) = c->noise_rms;
      for (const signal::HarmonicPhasor& p : c->harmonics) {
        if (p.harmonic < 1 || p.harmonic > num_harmonics) continue;
        const auto k = static_cast<py::ssize_t>(p.harmonic - 1);
        columns.phasors.mutable_at(row, k) = p.value;
        columns.std_real.mutable_at(row, k) = p.std_real;
        columns.std_imag.mutable_at(row, k) = p.std_imag;
        columns.correlation.mutable_at(row, k) = p.correlation;
        columns.std_amplitude.mutable_at(row, k) = p.AmplitudeStd();
        columns.std_phase_rad.mutable_at(row, k) = p.PhaseStdRad();
      }
    }
  }
  py::dict by_channel;
  for (const std::string& name : order) {
    const ChannelColumns& c = channels.at(name);
    py::dict d("quantity"_a = c.quantity, "unit"_a = c.unit, "position_m"_a = c.position_m, "phasors"_a = c.phasors,
               "std_real"_a = c.std_real, "std_imag"_a = c.std_imag, "correlation"_a = c.correlation,
               "std_amplitude"_a = c.std_amplitude, "std_phase_rad"_a = c.std_phase_rad, "mean"_a = c.mean,
               "thd"_a = c.thd, "snr_db"_a = c.snr_db, "noise_rms"_a = c.noise_rms);
    by_channel[py::str(name)] = d;
  }
  py::dict level("step_index"_a = index, "files"_a = files, "nominal_frequency_hz"_a = nominal,
                 "frequency_hz"_a = frequency, "frequency_std_hz"_a = frequency_std, "snr_db"_a = step_snr,
                 "channels"_a = by_channel);
  return level;
}

py::dict PhasorSetToPython(const signal::PhasorSet& set) {
  std::vector<std::string> labels;
  std::map<std::string, std::vector<std::pair<std::size_t, const signal::StepPhasors*>>> by_level;
  for (std::size_t i = 0; i < set.steps.size(); ++i) {
    auto [it, added] = by_level.try_emplace(set.steps[i].level);
    if (added) labels.push_back(set.steps[i].level);
    it->second.emplace_back(i, &set.steps[i]);
  }
  py::dict levels;
  for (const std::string& label : labels) levels[py::str(label)] = LevelToPython(by_level.at(label), set.num_harmonics);
  py::list skipped;
  for (const signal::SkippedStep& s : set.skipped)
    skipped.append(py::dict(py::arg("file") = s.file, py::arg("level") = s.level,
                            py::arg("nominal_frequency_hz") = s.nominal_frequency_hz, py::arg("reason") = s.reason));
  py::dict d("kind"_a = "phasors", "campaign"_a = set.campaign, "campaign_sha256"_a = set.campaign_sha256,
             "num_harmonics"_a = set.num_harmonics, "levels"_a = levels, "skipped"_a = skipped);
  return d;
}

}  // namespace

void AddCampaignFunctions(py::module_& module) {
  module.def(
      "read_campaign",
      [](const Path& folder) {
        PythonRun run{py::none()};
        const signal::Campaign campaign = run.Run([&](const workflow::RunObserver& observer) {
          return workflow::ReadCampaignAndWarn("read_campaign", folder, observer);
        });
        run.IssueWarnings(WarningCategory());
        return CampaignToPython(campaign);
      },
      py::arg("folder"),
      R"(Reads and checks a campaign folder's campaign.json (docs/campaign-format.md).

Returns a dict: name, folder, sha256 (the campaign's content hash), beam
(length_m, width_m, thickness_m [m], youngs_modulus_Pa [Pa], density_kg_m3
[kg/m³], loss_factor [-]), excitation and sensors (each: channel, position_m
[m], quantity, unit as in the files, to_si_factor, mass_kg [kg] or None),
ignored_channels, sample_rate_hz [Hz] or None, steps (file, frequency_hz [Hz],
level, in the order they were run), levels (labels in order), warnings.
Raises beamid.InputError naming the file, the entry and the fix.)");

  module.def(
      "extract",
      [](const Path& campaign_folder, int harmonics, std::optional<std::vector<std::string>> channels,
         bool skip_bad_steps, bool remove_ringing, int threads, const OptionalPath& output,
         const OptionalPath& csv_output, py::object progress) {
        PythonRun run(std::move(progress));
        workflow::ExtractRequest request{.campaign_folder = campaign_folder.string(),
                                         .harmonics = harmonics,
                                         .output = run.OutputPath(output, "phasors.json"),
                                         .csv_output = TextOf(csv_output),
                                         .threads = threads,
                                         .channels = channels.value_or(std::vector<std::string>{}),
                                         .skip_bad_steps = skip_bad_steps,
                                         .remove_ringing = remove_ringing};
        const workflow::ExtractOutcome outcome = run.Run(
            [&](const workflow::RunObserver& observer) { return workflow::ExtractCampaign(request, observer); });
        run.IssueWarnings(WarningCategory());
        py::dict d = PhasorSetToPython(outcome.phasors);
        d["run_warnings"] = run.Warnings();
        d["output"] = PythonOf(output);
        return d;
      },
      py::arg("campaign_folder"), py::kw_only(), py::arg("harmonics") = 5, py::arg("channels") = py::none(),
      py::arg("skip_bad_steps") = false, py::arg("remove_ringing") = false, py::arg("threads") = 0,
      py::arg("output") = py::none(), py::arg("csv_output") = py::none(), py::arg("progress") = py::none(),
      R"(The harmonic phasors of every step of a campaign, as `beamid extract` computes them (docs/signal.md).

Arguments (the command line's defaults):
  campaign_folder  the folder holding campaign.json
  harmonics        H, harmonics 1..H per channel (1..50; -H)
  channels         the sensors analysed (None: every one not ignored; --channel)
  skip_bad_steps   leave out, and list, the steps whose recordings hold errors
  remove_ringing   fit the frequency step's ringing out of the phasors
  threads          worker threads (0: one per core)
  output           also keep the phasors file (JSON, beamid-phasors/1) there (None: not kept)
  csv_output       also write the CSV table there (None: none)
  progress         None or a callable progress(task, fraction, what)

Returns a dict: campaign, campaign_sha256, num_harmonics (H), skipped (file,
level, nominal_frequency_hz, reason), run_warnings, output, and levels: per level
label (in campaign order) a dict with step_index (each step's place among
all the extracted steps), files, nominal_frequency_hz, frequency_hz,
frequency_std_hz [Hz] and snr_db [dB] (arrays over the level's n steps) and
channels: per channel (force first) quantity, unit (SI),
position_m [m], phasors (complex, n × H, peak, SI, force fundamental real
positive), std_real, std_imag, correlation, std_amplitude, std_phase_rad
[rad] (n × H), mean, thd, snr_db, noise_rms (n). beamid.to_pandas(phasors)
gives the CSV table's rows.)");
}

}  // namespace beamid::python
