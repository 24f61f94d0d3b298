// The content hash of a campaign: SHA-256 (OpenSSL's EVP) over campaign.json
// and every step's recording, so that a file derived from a campaign
// (phasors, result, prediction, diagnosis) can be told to be of these very
// bytes, not of another campaign that happens to have the same name, files
// and levels. The hashed stream is, for campaign.json and then each step in
// the campaign's order, the file's name relative to the campaign folder and
// its bytes, each preceded by its length (8 bytes, little-endian): bytes
// moved from one file to the next change it, the folder's own path does not
// (a copied campaign keeps its hash). Each step file's own SHA-256 is kept
// too, so that a recording copied into another step can be named.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace beamid::signal {

struct CampaignHash {
  std::string sha256;                    // of the whole campaign, 64 lowercase hex digits
  std::vector<std::string> step_sha256;  // each step file's own (what sha256sum prints), campaign order
};

// folder holds campaign.json; step_files are the steps' "file" entries in
// campaign order. Throws InputError naming a file that cannot be read
// (or that changed size while read).
CampaignHash HashCampaign(const std::filesystem::path& folder, const std::vector<std::string>& step_files);

// SHA-256 of one file's bytes, as sha256sum prints it. Throws InputError.
std::string FileSha256(const std::filesystem::path& file);

}  // namespace beamid::signal
