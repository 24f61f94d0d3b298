// A JSON file read whole (campaign.json, truth.json, a phasors file), for
// tests that check what a writer put in it.
#pragma once

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

namespace beamid::testing {

inline nlohmann::json ReadJsonFile(const std::filesystem::path& file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

}  // namespace beamid::testing
