#include "solver/cli/cli_output.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include <fmt/core.h>
#include <unistd.h>

#include "hb/errors.h"
#include "hb/option_checks.h"
#include "hb/text_file.h"
#include "signal/campaign_extractor.h"
#include "signal/campaign_identity.h"
#include "signal/phasor_set_io.h"

namespace beamid::cli {

Progress::Progress(std::string label, const GlobalOptions& global)
    : label_(std::move(label)),
      quiet_(global.quiet),
      json_(global.JsonProgress()),
      terminal_(isatty(fileno(stderr)) != 0),
      start_(std::chrono::steady_clock::now()) {}

Progress::~Progress() { Done(); }

void Progress::Update(double fraction, const std::string& what) {
  if (done_ || (quiet_ && !json_)) return;
  const int percent = static_cast<int>(100.0 * std::clamp(fraction, 0.0, 1.0));
  const bool every_percent = json_ || terminal_;
  if (every_percent ? percent == last_percent_ : percent / 10 == last_percent_ / 10) return;
  last_percent_ = percent;
  if (json_) {
    nlohmann::json line = {{"event", "progress"}, {"task", label_}, {"fraction", percent / 100.0}};
    if (!what.empty()) line["what"] = what;
    PrintToStderr(line.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  } else if (terminal_) {
    // Pad so that a shorter "what" overwrites a longer one.
    PrintToStderr(fmt::format("\r{}  {:3d} %  {:<40.40}", label_, percent, what));
  } else {
    PrintToStderr(fmt::format("{}  {:3d} %{}\n", label_, percent, what.empty() ? "" : "  " + what));
  }
}

void Progress::Done() {
  if (done_) return;
  done_ = true;
  if (json_) {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    PrintToStderr(nlohmann::json({{"event", "done"}, {"task", label_}, {"seconds", seconds}}).dump() + "\n");
  } else if (!quiet_ && terminal_) {
    PrintToStderr(fmt::format("\r{}  done{:<50}\n", label_, ""));
  }
}

void PrintJsonExit(int exit_code, const std::string& message) {
  nlohmann::json line = {{"event", "exit"}, {"exit_code", exit_code}};
  if (!message.empty()) line["message"] = message;
  PrintToStderr(line.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

nlohmann::json PhasorsToJson(const Eigen::VectorXcd& phasors) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& p : phasors) out.push_back({p.real(), p.imag()});
  return out;
}

void WriteTextFile(const std::filesystem::path& path, const std::string& text) {
  std::error_code error;
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), error);
  WriteTextFileAtomically(path, text);
}

void PrintToStderr(std::string_view text) noexcept {
  std::fwrite(text.data(), 1, text.size(), stderr);
  std::fflush(stderr);
  std::clearerr(stderr);
}

CLI::Validator FiniteRange(double min, double max) {
  const std::string range = option_checks::FormatValue(min) + " … " + option_checks::FormatValue(max);
  return CLI::Validator(
      [min, max, range](std::string& input) -> std::string {
        double value = 0.0;
        if (!CLI::detail::lexical_cast(input, value)) return "'" + input + "' is not a number";
        if (!(std::isfinite(value) && value >= min && value <= max))
          return "'" + input + "' must be a finite number in " + range;
        return std::string();
      },
      "FINITE in [" + range + "]");
}

CLI::Validator NonEmptyPath() {
  return CLI::Validator(
      [](std::string& input) -> std::string { return input.empty() ? "an empty path: give a file or folder name" : ""; },
      "PATH");
}

void AddModelHarmonicsOptions(CLI::App* command, int* harmonics, int* fit_harmonics, const std::string& model_help) {
  command->add_option("-H,--harmonics", *harmonics, model_help)->check(CLI::Range(1, 50))->capture_default_str();
  command->add_option("--fit-harmonics", *fit_harmonics, "Harmonics 1..K fitted (K <= -H)")
      ->check(CLI::Range(1, 50))
      ->capture_default_str();
}

void RequireFitWithinModelHarmonics(int fit_harmonics, int harmonics) {
  if (fit_harmonics > harmonics)
    throw InputError("--fit-harmonics " + std::to_string(fit_harmonics) + " exceeds the model's -H " +
                     std::to_string(harmonics) + ": fit at most the harmonics the model holds");
}

signal::Campaign ReadCampaignAndWarn(const std::string& command, const std::filesystem::path& folder,
                                     const GlobalOptions& global) {
  signal::Campaign campaign = signal::ReadCampaign(folder);
  if (!global.quiet)
    for (const auto& warning : campaign.warnings) fmt::print(stderr, "beamid {}: warning: {}\n", command, warning);
  return campaign;
}

CampaignForAnalysis ReadCampaignForAnalysis(const std::string& command, const std::string& folder,
                                            const std::vector<std::string>& fit_channels,
                                            const std::vector<std::string>& validate_channels,
                                            const GlobalOptions& global) {
  CampaignForAnalysis out{.campaign = ReadCampaignAndWarn(command, folder, global), .fit_channels = fit_channels};
  const signal::Campaign& campaign = out.campaign;
  const auto validated = [&](const std::string& channel) {
    return std::find(validate_channels.begin(), validate_channels.end(), channel) != validate_channels.end();
  };
  for (const auto& channel : fit_channels)
    if (validated(channel))
      throw InputError("--validate " + channel + ": the channel is also fitted (--fit), so its held-out error "
                       "would be a fitted residual, not a prediction. Fix: leave " + channel +
                       " out of --fit or out of --validate");
  if (out.fit_channels.empty())
    for (const auto& sensor : campaign.sensors)
      if (campaign.Use(sensor.channel) != signal::ChannelUse::kIgnored && !validated(sensor.channel))
        out.fit_channels.push_back(sensor.channel);
  if (out.fit_channels.empty()) {
    const std::string campaign_json = (campaign.folder / "campaign.json").string();
    throw InputError(campaign_json + ": no sensor is left to fit: every sensor is listed in ignore_channels" +
                     (validate_channels.empty() ? std::string() : " or held out with --validate") +
                     ". Fix: remove a sensor from ignore_channels in " + campaign_json +
                     (validate_channels.empty() ? std::string() : ", or hold out fewer channels"));
  }
  std::vector<std::string> analysed = out.fit_channels;
  analysed.insert(analysed.end(), validate_channels.begin(), validate_channels.end());
  out.campaign.Analyse(analysed);
  return out;
}

void AddPhasorInputOptions(CLI::App* command, PhasorInput* input) {
  command->add_option("--phasors", input->phasors_file, "Use phasors from 'beamid extract' instead of extracting")
      ->check(NonEmptyPath());
  command->add_flag("--skip-bad-steps", input->skip_bad_steps,
                    "Analyse the other steps when some recordings hold errors (they are listed); without it the "
                    "run stops with the list");
}

void PrintSkippedSteps(const std::string& command, const signal::PhasorSet& phasors, const GlobalOptions& global) {
  if (global.quiet) return;
  for (const auto& step : phasors.skipped)
    PrintToStderr(fmt::format("beamid {}: warning: skipped {} ({} Hz, {}): {}\n", command, step.file,
                              step.nominal_frequency_hz, step.level, step.reason));
}

signal::PhasorSet ReadOrExtractPhasors(const signal::Campaign& campaign, const PhasorInput& input, int num_harmonics,
                                       const GlobalOptions& global) {
  if (!input.phasors_file.empty()) {
    signal::PhasorSet phasors = signal::ReadPhasorSetJson(input.phasors_file);
    // The phasors must be this campaign's, every step once (extracted or
    // skipped) and in its order: a file from another campaign or of a
    // subset would be fitted silently.
    bool same = phasors.steps.size() + phasors.skipped.size() == campaign.steps.size();
    std::size_t extracted = 0, skipped = 0;
    for (std::size_t i = 0; same && i < campaign.steps.size(); ++i) {
      const auto& step = campaign.steps[i];
      if (extracted < phasors.steps.size() && phasors.steps[extracted].file == step.file &&
          phasors.steps[extracted].level == step.level)
        ++extracted;
      else if (skipped < phasors.skipped.size() && phasors.skipped[skipped].file == step.file &&
               phasors.skipped[skipped].level == step.level)
        ++skipped;
      else
        same = false;
    }
    if (!same)
      throw InputError(input.phasors_file + ": these phasors are not the campaign's (" +
                       std::to_string(phasors.steps.size() + phasors.skipped.size()) + " steps against the campaign's " +
                       std::to_string(campaign.steps.size()) +
                       ", or other files or levels). Fix: extract this campaign again (beamid extract) or give "
                       "the phasor file extracted from it");
    // The same files and levels may hold other recordings (another beam,
    // another day): only the content hash tells.
    signal::RequireDerivedFrom({.file = "--phasors " + input.phasors_file,
                                .sha256 = phasors.campaign_sha256,
                                .name = phasors.campaign},
                               campaign,
                               "extract this campaign again (beamid extract " + campaign.folder.string() +
                                   ") or give the phasor file extracted from it");
    if (!phasors.skipped.empty() && !input.skip_bad_steps)
      throw InputError(input.phasors_file + ": " + std::to_string(phasors.skipped.size()) +
                       " steps were skipped at extraction (bad recordings). Fix: add --skip-bad-steps to analyse "
                       "the other steps, or repair the recordings and extract again");
    PrintSkippedSteps("extract", phasors, global);
    return phasors;
  }
  Progress progress("extract", global);
  signal::ExtractOptions extract;
  extract.estimator.num_harmonics = num_harmonics;
  extract.skip_bad_steps = input.skip_bad_steps;
  extract.progress = [&](std::size_t done, std::size_t total, const signal::StepPhasors&) {
    progress.Update(static_cast<double>(done) / total);
  };
  signal::PhasorSet phasors = signal::ExtractCampaign(campaign, extract);
  progress.Done();
  PrintSkippedSteps("extract", phasors, global);
  return phasors;
}

void PrintDampingLaws(const solver::DampingLawEnvelope& envelope) {
  if (envelope.laws.empty()) return;
  fmt::print("  beam damping laws (the fit assumes loss_factor):\n");
  for (const auto& law : envelope.laws)
    if (law.converged)
      fmt::print("    {:<23} reduced chi-square {:.3g}  {}\n", law.law, law.reduced_chi_square,
                 law.accepted ? "fits: accepted" : "rejected by the data");
    else
      fmt::print("    {:<23} {}\n", law.law, law.status);
  fmt::print("  model-form 95 % intervals (envelope over the accepted damping laws):\n");
  for (const auto& i : envelope.intervals)
    fmt::print("    {:<10} {:.6g} … {:.6g} {}{}\n", i.name, i.lower_95, i.upper_95, i.unit,
               i.depends_on_damping_law ? "   [DEPENDS ON THE DAMPING LAW: another law that fits puts it outside the "
                                          "statistical interval]"
                                        : "");
}

}  // namespace beamid::cli
