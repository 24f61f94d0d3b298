#include "solver/estimation/start_record_io.h"

#include <stdexcept>

#include <nlohmann/json.hpp>

#include "hb/json_field.h"
#include "hb/strict_json.h"

namespace beamid::solver {

std::string StartRecordToText(const StartRecord& record) {
  const StartOutcome& o = record.outcome;
  const nlohmann::json j = {{"objective", ExactJsonNumber(o.objective)},
                            {"success", o.success},
                            {"iterations", o.iterations},
                            {"status", o.status},
                            {"status_code", o.status_code},
                            {"route", static_cast<int>(o.route)},
                            {"branch_repairs", o.branch_repairs},
                            {"parameters", ExactJsonNumbers(o.parameters)},
                            {"scaled_at", ExactJsonNumbers(o.scaled_at)},
                            {"x", ExactJsonNumbers(record.x)}};
  return j.dump();
}

StartRecord StartRecordFromText(const std::string& text) {
  try {
    const nlohmann::json j = ParseStrictJson<nlohmann::json>(text, "a start's record", "");
    StartRecord record;
    StartOutcome& o = record.outcome;
    o.objective = ExactNumberFromJson(j.at("objective"));
    o.success = j.at("success").get<bool>();
    o.iterations = j.at("iterations").get<int>();
    o.status = j.at("status").get<std::string>();
    o.status_code = j.at("status_code").get<int>();
    const int route = j.at("route").get<int>();
    if (route != static_cast<int>(StartRoute::kMeasuredStates) && route != static_cast<int>(StartRoute::kFeasibleStates))
      throw std::runtime_error("unknown route " + std::to_string(route));
    o.route = static_cast<StartRoute>(route);
    o.branch_repairs = j.at("branch_repairs").get<int>();
    o.parameters = ExactNumbersFromJson(j.at("parameters"));
    o.scaled_at = ExactNumbersFromJson(j.at("scaled_at"));
    record.x = ExactNumbersFromJson(j.at("x"));
    return record;
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("a start's record is damaged: ") + e.what());
  }
}

}  // namespace beamid::solver
