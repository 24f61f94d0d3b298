// Whether a file derived from a campaign (phasors, result, prediction,
// diagnosis) was derived from this campaign's very bytes: the file carries
// the campaign's content hash ("campaign_sha256", signal/campaign_hash.h) and
// a command that reads it together with a campaign compares the two. Two
// campaigns with the same name, files and levels but other recordings differ
// here, a copy of the campaign moved elsewhere does not. A file without the
// hash (written by a beamid older than the key) is refused too: nothing shows
// which recordings it came from, and re-deriving it is the one honest fix.
#pragma once

#include <string>

#include "signal/campaign.h"

namespace beamid::signal {

// What a derived file says of its campaign.
struct CampaignOfFile {
  std::string file;    // names the file in messages ("--phasors p.json", "result.json", …)
  std::string sha256;  // its "campaign_sha256"; "" in a file older than the key
  std::string name;    // its campaign's name, for the message
};

// Throws InputError naming the file, campaign.json and `fix` unless the file
// carries campaign.sha256 (campaign must come from ReadCampaign).
void RequireDerivedFrom(const CampaignOfFile& derived, const Campaign& campaign, const std::string& fix);

// The same check between two derived files (a diagnosis and its result):
// throws InputError naming both and `fix` unless they carry the same hash.
void RequireSameCampaign(const CampaignOfFile& derived, const CampaignOfFile& other, const std::string& fix);

}  // namespace beamid::signal
