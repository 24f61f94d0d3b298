#include "solver/report/report_input.h"

#include <stdexcept>

#include <nlohmann/json.hpp>

#include "hb/errors.h"
#include "hb/strict_json.h"
#include "hb/text_file.h"
#include "signal/campaign_identity.h"
#include "solver/estimation/result_io.h"

namespace beamid::solver {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

bool IsDiagnosis(const Json& j) {
  return j.is_object() && (j.contains("selected") || j.contains("candidates") || j.contains("location") ||
                           j.contains("summary")) && j.value("format", "") != kResultFormat;
}

fs::path Relative(const fs::path& path, const fs::path& base_file) {
  if (path.is_absolute() || fs::exists(path)) return path;
  return base_file.parent_path() / path;
}

}  // namespace

ReportInput LoadReportInput(const fs::path& input_file, const std::optional<fs::path>& campaign_folder) {
  ReportInput input;
  input.input_file = input_file;
  input.result_file = input_file;
  const std::string text = ReadTextFile(input_file, "result or diagnosis file", "check the path");
  const Json j = ParseStrictJson<Json>(text, input_file.string(), "see docs/report.md");
  if (IsDiagnosis(j)) {
    DiagnosisFile diagnosis = DiagnosisFileFromJson(text, input_file.string());
    if (!diagnosis.embedded_result_json.empty()) {
      input.result =
          ResultFileFromJson(diagnosis.embedded_result_json, input_file.string() + " (its embedded result)");
    } else if (!diagnosis.result_file.empty()) {
      input.result_file = Relative(diagnosis.result_file, input_file);
      input.result = ReadResultFile(input.result_file);
    } else {
      throw InputError(input_file.string() +
                       ": the diagnosis holds no result (neither \"result\" nor \"result_file\"). Fix: give the "
                       "result.json of 'beamid identify' instead, or run 'beamid diagnose' with --result");
    }
    // A diagnosis and a result of two campaigns would be mixed into one page.
    signal::RequireSameCampaign(
        {.file = input_file.string(), .sha256 = diagnosis.campaign_sha256, .name = diagnosis.campaign_name},
        {.file = input.result_file.string(), .sha256 = input.result.campaign.sha256, .name = input.result.campaign.name},
        "run 'beamid diagnose' with --result naming the result.json of the campaign diagnosed");
    input.diagnosis = std::move(diagnosis);
  } else {
    if (!j.is_object() || j.value("format", "") != kResultFormat)
      throw InputError(input_file.string() +
                       ": not a beamid result (format must be \"beamid-result/1\"). Fix: give the "
                       "result.json of 'beamid identify' or a diagnosis.json of 'beamid diagnose'");
    input.result = ResultFileFromJson(text, input_file.string());
  }
  if (campaign_folder) {
    input.campaign_folder = *campaign_folder;
  } else {
    const std::string& folder = input.result.campaign.folder;
    const std::string& absolute = input.result.campaign.absolute_folder;
    if (folder.empty() && absolute.empty())
      throw std::invalid_argument(input.result_file.string() +
                                  ": the result names no campaign folder. Fix: give it with --campaign DIR");
    input.campaign_folder = folder.empty() ? fs::path(absolute) : Relative(folder, input.result_file);
    if (!fs::is_regular_file(input.campaign_folder / "campaign.json") && !absolute.empty())
      input.campaign_folder = absolute;
  }
  if (!fs::is_regular_file(input.campaign_folder / "campaign.json"))
    throw std::invalid_argument(input.campaign_folder.string() +
                                ": no campaign.json there (the campaign of " + input.result_file.string() +
                                "). Fix: give the campaign folder with --campaign DIR");
  return input;
}

}  // namespace beamid::solver
