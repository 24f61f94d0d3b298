#include "solver/cli/cli_output.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>

#include <fmt/core.h>
#include <unistd.h>

#include "hb/option_checks.h"

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

void AddPhasorUncertaintyOption(CLI::App* command, solver::PhasorUncertainty* uncertainty) {
  std::map<std::string, solver::PhasorUncertainty> names;
  for (const auto& [value, name] : solver::kPhasorUncertaintyNames) names.emplace(std::string(name), value);
  std::vector<std::string> keys;
  for (const auto& [name, value] : names) keys.push_back(name);
  command
      ->add_option_function<std::string>(
          "--phasor-uncertainty", [uncertainty, names](const std::string& name) { *uncertainty = names.at(name); },
          "How each phasor is weighed: relative_floor (its noise, raised to 1e-4 of the channel's largest "
          "fundamental) or propagated (its noise and the force's and the frequency's errors propagated into it; the "
          "model's residual error is estimated by the fit and reported on its own; docs/identify.md)")
      ->check(CLI::IsMember(keys))
      ->type_name("TEXT")
      ->default_str("propagated");
}

workflow::RunObserver CliObserver(const GlobalOptions& global) {
  // One task at a time; the observer is copied into the workflow's calls.
  auto task = std::make_shared<std::optional<Progress>>();
  return {.begin = [task, &global](const std::string& label) { task->emplace(label, global); },
          .progress =
              [task](double fraction, const std::string& what) {
                if (task->has_value()) (*task)->Update(fraction, what);
              },
          .end =
              [task] {
                if (task->has_value()) (*task)->Done();
                task->reset();
              },
          .warning =
              [&global](const std::string& source, const std::string& text) {
                if (!global.quiet) PrintToStderr(fmt::format("beamid {}: warning: {}\n", source, text));
              },
          .note =
              [&global](const std::string& text) {
                if (!global.quiet) PrintToStderr(text + "\n");
              }};
}

void AddPhasorInputOptions(CLI::App* command, workflow::PhasorInput* input) {
  command->add_option("--phasors", input->phasors_file, "Use phasors from 'beamid extract' instead of extracting")
      ->check(NonEmptyPath());
  command->add_flag("--skip-bad-steps", input->skip_bad_steps,
                    "Analyse the other steps when some recordings hold errors (they are listed); without it the "
                    "run stops with the list");
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
  fmt::print("  total 95 % intervals: {}\n", solver::TotalIntervalParts(envelope));
  for (const auto& i : envelope.intervals) {
    std::string flags;
    if (i.depends_on_damping_law) flags += "   [DEPENDS ON THE DAMPING LAW: another law that fits puts it outside the "
                                           "statistical interval]";
    if (i.depends_on_truncation) flags += "   [DEPENDS ON THE HARMONIC TRUNCATION: more harmonics put it outside the "
                                          "statistical interval; analyse with more (-H)]";
    fmt::print("    {:<10} {:.6g} … {:.6g} {}  ({:.2g}× the statistical width; truncation shift {:+.2g}){}\n", i.name,
               i.lower_95, i.upper_95, i.unit, i.WidthRatio(), i.truncation_shift, flags);
  }
}

}  // namespace beamid::cli
