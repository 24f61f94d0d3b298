// Universal files, datasets 58 and 58b, ASCII and binary (signal::ParseUff58),
// and what parses as a step's recording of the fuzz campaign
// (signal::RecordingFromUff58); the same bytes read as a stepped sine's
// spectra and frequency responses (signal::FirstHarmonicLevelFromUff58).
// Messages must be valid UTF-8 whatever the file's ID lines and labels hold.
#include <cstdlib>

#include "hb/errors.h"
#include "signal/campaign.h"
#include "signal/internal/text.h"
#include "signal/uff58.h"
#include "signal/uff58_level.h"
#include "signal/uff_recording.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const beamid::signal::Campaign campaign =
      beamid::signal::ParseCampaign(beamid::fuzz::kCampaignJson, "fuzz", "fuzz/campaign.json");
  return beamid::fuzz::Accept([&] {
    try {
      const auto datasets = beamid::signal::ParseUff58(beamid::fuzz::AsText(data, size), "fuzz/step.uff");
      beamid::signal::RecordingFromUff58(datasets, campaign, campaign.steps.front(), "fuzz/step.uff");
    } catch (const beamid::InputError& e) {
      if (!beamid::signal::internal::IsValidUtf8(e.what())) std::abort();
    }
    try {
      const auto datasets = beamid::signal::ParseUff58(beamid::fuzz::AsText(data, size), "fuzz/level.uff",
                                                       beamid::signal::Uff58Functions::kFrequencyFunctions);
      beamid::signal::FirstHarmonicLevelFromUff58(datasets, "fuzz/level.uff", "level");
    } catch (const beamid::InputError& e) {
      if (!beamid::signal::internal::IsValidUtf8(e.what())) std::abort();
    }
  });
}
