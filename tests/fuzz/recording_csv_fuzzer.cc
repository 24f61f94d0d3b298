// A step's CSV recording (signal::ParseRecording), against a fixed campaign
// and against the same campaign with vel2 ignored and only acc1 analysed
// (the channels whose reading problems are findings, not errors). Whatever
// the input, what the reader says and keeps must be valid UTF-8: messages
// reach the phasors file, and its JSON writer throws on anything else.
#include <cstdlib>

#include "hb/errors.h"
#include "signal/campaign.h"
#include "signal/internal/text.h"
#include "signal/recording.h"
#include "tests/fuzz/fuzz_input.h"

namespace {

void RequireUtf8(const std::string& text) {
  if (!beamid::signal::internal::IsValidUtf8(text)) std::abort();
}

void Read(std::string_view text, const beamid::signal::Campaign& campaign) {
  try {
    const beamid::signal::Recording recording =
        beamid::signal::ParseRecording(text, campaign, campaign.steps.front(), "fuzz/step_000.csv");
    for (const auto& column : recording.ignored_columns) RequireUtf8(column);
    for (const auto& finding : recording.findings) RequireUtf8(finding.Text());
  } catch (const beamid::InputError& e) {
    RequireUtf8(e.what());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const beamid::signal::Campaign campaign =
      beamid::signal::ParseCampaign(beamid::fuzz::kCampaignJson, "fuzz", "fuzz/campaign.json");
  static const beamid::signal::Campaign partial = [] {
    std::string json = beamid::fuzz::kCampaignJson;
    json.insert(json.rfind('}'), R"(, "ignore_channels": ["vel2"])");
    beamid::signal::Campaign c = beamid::signal::ParseCampaign(json, "fuzz", "fuzz/campaign.json");
    c.Analyse({"acc1"});
    return c;
  }();
  return beamid::fuzz::Accept([&] {
    Read(beamid::fuzz::AsText(data, size), campaign);
    Read(beamid::fuzz::AsText(data, size), partial);
  });
}
