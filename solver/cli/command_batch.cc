// beamid batch: the same identification over many campaigns, each in
// processes of its own, with one summary (CSV and an HTML index linking each
// report). The work is workflow::BatchCampaigns; this parses the options,
// prints the summary and maps the campaigns' outcome to the exit code: the
// first failed campaign's class, else 5 when a fit misses its data.
#include <filesystem>
#include <stdexcept>
#include <string>

#include <fmt/core.h>

#include "hb/errors.h"
#include "solver/cli/cli_output.h"
#include "solver/cli/command_registry.h"
#include "solver/workflow/batch_campaigns.h"

namespace beamid::cli {
namespace {

void PrintSummary(const workflow::BatchSummary& summary, const std::string& output) {
  for (const workflow::BatchRow& row : summary.rows) {
    const workflow::BatchEntry& e = row.entry;
    std::string said = e.status == workflow::BatchStatus::kFailed ? e.message : row.verdict;
    fmt::print("  {:<24} {:<7} {}\n", row.folder, schema::NameOf(e.status, workflow::kBatchStatusNames), said);
  }
  fmt::print("wrote {0}/summary.csv and {0}/index.html ({1} campaign{2})\n", output, summary.rows.size(),
             summary.rows.size() == 1 ? "" : "s");
}

[[noreturn]] void ThrowExit(int code, const std::string& message) {
  switch (code) {
    case kExitBadInput: throw InputError(message);
    case kExitNoConvergence: throw NumericalError(message);
    case kExitEnvironment: throw EnvironmentError(message);
    case kExitModelMissesData: throw ModelMissesData(message);
    default: throw std::runtime_error(message);
  }
}

void RunBatch(workflow::BatchRequest& request, bool collect_only, const GlobalOptions& global) {
  if (collect_only) {
    const workflow::BatchSummary summary = workflow::CollectBatchSummary(request.output, CliObserver(global));
    if (!global.quiet) PrintSummary(summary, request.output);
    return;
  }
  request.program = std::filesystem::read_symlink("/proc/self/exe").string();
  const workflow::BatchOutcome outcome = workflow::BatchCampaigns(request, CliObserver(global));
  if (!global.quiet) {
    PrintSummary(outcome.summary, request.output);
    fmt::print("{} campaigns in {:.1f} s: {} fitted within their noise, {} beyond it, {} failed\n",
               request.campaigns.size(), outcome.seconds, outcome.fitted, outcome.misfit, outcome.failed);
  }
  if (outcome.exit_code == 0) return;
  if (outcome.failed == 0)
    ThrowExit(outcome.exit_code, fmt::format("{} of {} fits miss their data beyond the noise (see {}/summary.csv); "
                                             "run beamid diagnose on them",
                                             outcome.misfit, request.campaigns.size(), request.output));
  ThrowExit(outcome.exit_code, fmt::format("{} of {} campaigns failed (see {}/summary.csv); the first, {}",
                                           outcome.failed, request.campaigns.size(), request.output,
                                           outcome.first_failure));
}

BEAMID_REGISTER_COMMAND("batch", [](CLI::App& app, const GlobalOptions& global) {
  auto request = std::make_shared<workflow::BatchRequest>();
  auto collect_only = std::make_shared<bool>(false);
  CLI::App* sub = app.add_subcommand(
      "batch",
      "Identify many campaigns with the same options, each in processes of its own, JOBS at a time; one\n"
      "folder of results per campaign under OUTPUT and one summary (summary.csv, index.html) across them.\n"
      "Example: beamid batch specimens/* --fit acc1,acc2 --validate acc3 -o batch --jobs 4\n"
      "Example: beamid batch --collect -o batch   (the summary of the folders a cluster's job array wrote)");
  sub->add_option("campaigns", request->campaigns, "Campaign folders (each holds campaign.json)");
  sub->add_option("-o,--output", request->output,
                  "Output folder: OUTPUT/<campaign>/ (result.json, parameters.csv, report.html, batch.json), "
                  "OUTPUT/summary.csv and OUTPUT/index.html")
      ->capture_default_str();
  sub->add_option("-j,--jobs", request->jobs, "Campaigns at a time (0: one per core)")
      ->check(CLI::Range(0, 256))
      ->capture_default_str();
  sub->add_option("--fit", request->fit_channels,
                  "Response channels to fit, comma-separated (default: every sensor neither ignored nor held out)")
      ->delimiter(',')
      ->allow_extra_args(false);  // one argument: the campaign folders that follow are no channels
  sub->add_option("--validate", request->validate_channels, "Held-out channels to predict and compare, comma-separated")
      ->delimiter(',')
      ->allow_extra_args(false);
  sub->add_option("--model", request->model, "Model family (as beamid identify --model)")->capture_default_str();
  sub->add_option("-H,--harmonics", request->harmonics, "Harmonics of the model")
      ->check(CLI::Range(1, 50))
      ->capture_default_str();
  sub->add_flag("!--no-report", request->report, "Do not write each campaign's report.html");
  sub->add_flag("--collect", *collect_only,
                "Only (re)write the summary of the campaign folders OUTPUT holds (after a cluster's job array)");
  sub->callback([request, collect_only, &global] {
    if (*collect_only && !request->campaigns.empty())
      throw InputError("batch --collect takes no campaign: it summarises the folders -o OUTPUT holds");
    RunBatch(*request, *collect_only, global);
  });
});

}  // namespace
}  // namespace beamid::cli
