// A step's CSV recording (signal::ParseRecording), against a fixed campaign.
#include "signal/campaign.h"
#include "signal/recording.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const beamid::signal::Campaign campaign =
      beamid::signal::ParseCampaign(beamid::fuzz::kCampaignJson, "fuzz", "fuzz/campaign.json");
  return beamid::fuzz::Accept([&] {
    beamid::signal::ParseRecording(beamid::fuzz::AsText(data, size), campaign, campaign.steps.front(),
                                   "fuzz/step_000.csv");
  });
}
