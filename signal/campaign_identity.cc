#include "signal/campaign_identity.h"

#include <stdexcept>

#include "signal/input_error.h"

namespace beamid::signal {
namespace {

// The first 12 hex digits: enough to tell two campaigns apart in a message.
std::string Short(const std::string& sha256) { return sha256.substr(0, 12) + "…"; }

[[noreturn]] void RefuseOlder(const CampaignOfFile& derived, const std::string& against, const std::string& fix) {
  throw InputError(derived.file + ": written by an older beamid, without the campaign's content hash "
                   "(\"campaign_sha256\"), so nothing shows that it was derived from " + against +
                   ". Fix: " + fix);
}

}  // namespace

void RequireDerivedFrom(const CampaignOfFile& derived, const Campaign& campaign, const std::string& fix) {
  if (campaign.sha256.empty()) throw std::logic_error("RequireDerivedFrom: the campaign was not read by ReadCampaign");
  const std::string campaign_json = (campaign.folder / "campaign.json").string();
  if (derived.sha256.empty()) RefuseOlder(derived, campaign_json + " and its recordings", fix);
  if (derived.sha256 == campaign.sha256) return;
  throw InputError(derived.file + ": is of campaign '" + derived.name + "' (content SHA-256 " + Short(derived.sha256) +
                   "), not of campaign '" + campaign.name + "' in " + campaign_json + " (content SHA-256 " +
                   Short(campaign.sha256) + "): campaign.json or a recording differs. Fix: " + fix);
}

void RequireSameCampaign(const CampaignOfFile& derived, const CampaignOfFile& other, const std::string& fix) {
  if (derived.sha256.empty()) RefuseOlder(derived, "the campaign of " + other.file, fix);
  if (other.sha256.empty()) RefuseOlder(other, "the campaign of " + derived.file, fix);
  if (derived.sha256 == other.sha256) return;
  throw InputError(derived.file + ": is of campaign '" + derived.name + "' (content SHA-256 " + Short(derived.sha256) +
                   "), not of the campaign of " + other.file + " ('" + other.name + "', content SHA-256 " +
                   Short(other.sha256) + "). Fix: " + fix);
}

}  // namespace beamid::signal
