// campaign.json (signal::ParseCampaign).
#include "signal/campaign.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return beamid::fuzz::Accept(
      [&] { beamid::signal::ParseCampaign(beamid::fuzz::AsText(data, size), "fuzz", "fuzz/campaign.json"); });
}
