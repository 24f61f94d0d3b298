// Shared by the fuzz targets: what a reader may do with any input. It
// returns a value or throws an input error (std::invalid_argument and its
// subclasses: the message names the file and the fix). Anything else that
// escapes, and any crash, leak or undefined behaviour the sanitizers see, is
// a finding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

namespace beamid::fuzz {

inline std::string_view AsText(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// Runs a reader on one input; an input error is the expected refusal.
template <typename Reader>
int Accept(Reader&& reader) {
  try {
    reader();
  } catch (const std::invalid_argument&) {
  }
  return 0;
}

// A valid campaign description the recording and UFF targets read their
// input against (three channels: force, acc1 in g, vel2 in mm/s).
inline constexpr const char* kCampaignJson = R"({
  "format": "stepped-sine-campaign/1",
  "beam": {"length_m": 0.6, "width_m": 0.04, "thickness_m": 0.005, "youngs_modulus_Pa": 2.1e11, "density_kg_m3": 7850},
  "excitation": {"channel": "force", "position_m": 0.57, "quantity": "force", "unit": "N"},
  "sensors": [{"channel": "acc1", "position_m": 0.1, "quantity": "acceleration", "unit": "g"},
              {"channel": "vel2", "position_m": 0.3, "quantity": "velocity", "unit": "mm/s"}],
  "steps": [{"file": "step_000.csv", "frequency_Hz": 50.0, "level": "low"}]
})";

}  // namespace beamid::fuzz
