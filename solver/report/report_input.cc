#include "solver/report/report_input.h"

#include <fstream>
#include <stdexcept>

namespace beamid::solver {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

Json ReadJson(const fs::path& file, const std::string& what) {
  std::ifstream in(file);
  if (!in) throw std::invalid_argument(file.string() + ": cannot open the " + what + " (check the path)");
  try {
    return Json::parse(in);
  } catch (const Json::exception& e) {  // syntax, and numbers beyond double (1e400)
    throw std::invalid_argument(file.string() + ": not valid JSON (" + e.what() + ")");
  }
}

bool IsDiagnosis(const Json& j) {
  return j.is_object() && (j.contains("selected") || j.contains("candidates") || j.contains("location") ||
                           j.contains("summary")) && j.value("format", "") != "beamid-result/1";
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
  Json j = ReadJson(input_file, "result or diagnosis file");
  if (IsDiagnosis(j)) {
    input.diagnosis = j;
    const Json* result = j.contains("result") ? &j["result"] : j.contains("result_file") ? &j["result_file"] : nullptr;
    if (!result)
      throw std::invalid_argument(input_file.string() +
                                  ": the diagnosis holds no result (neither \"result\" nor \"result_file\"). Fix: "
                                  "give the result.json of 'beamid identify' instead, or a diagnosis that embeds it");
    if (result->is_string()) {
      input.result_file = Relative(result->get<std::string>(), input_file);
      input.result = ReadJson(input.result_file, "result file named by the diagnosis");
    } else {
      input.result = *result;
    }
  } else {
    input.result = std::move(j);
  }
  if (!input.result.is_object() || input.result.value("format", "") != "beamid-result/1")
    throw std::invalid_argument(input.result_file.string() +
                                ": not a beamid result (format must be \"beamid-result/1\"). Fix: give the "
                                "result.json of 'beamid identify' or a diagnosis.json of 'beamid diagnose'");
  if (campaign_folder) {
    input.campaign_folder = *campaign_folder;
  } else {
    const Json campaign = input.result.value("campaign", Json::object());
    const std::string folder = campaign.is_object() ? campaign.value("folder", "") : "";
    const std::string absolute = campaign.is_object() ? campaign.value("absolute_folder", "") : "";
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
