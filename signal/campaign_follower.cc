#include "signal/campaign_follower.h"

#include <chrono>
#include <system_error>
#include <utility>

#include "hb/option_checks.h"
#include "hb/text_file.h"
#include "signal/input_error.h"

namespace beamid::signal {

void CampaignFollowerOptions::Validate() const {
  checks.Validate();
  option_checks::RequireInRange("--stable", stable_s, 0.0, 3600.0);
  option_checks::RequireInRange("invalid_looks", invalid_looks, 1, 1000000);
}

CampaignFollower::CampaignFollower(std::filesystem::path folder, const CampaignFollowerOptions& options)
    : folder_(std::move(folder)), options_(options) {
  options_.Validate();
}

std::optional<CampaignFollower::FileSignature> CampaignFollower::SignatureOf(const std::filesystem::path& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error) || error) return std::nullopt;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error) return std::nullopt;
  const auto modified = std::filesystem::last_write_time(path, error);
  if (error) return std::nullopt;
  return FileSignature{
      .size = size,
      .modified_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(modified.time_since_epoch()).count()};
}

namespace {

// What a campaign's analysis rests on: its channels, in order, and the beam.
bool SameLayout(const Campaign& a, const Campaign& b) {
  const auto ca = a.Channels();
  const auto cb = b.Channels();
  if (ca.size() != cb.size()) return false;
  for (std::size_t i = 0; i < ca.size(); ++i)
    if (ca[i]->channel != cb[i]->channel || ca[i]->quantity != cb[i]->quantity ||
        ca[i]->to_si_factor != cb[i]->to_si_factor || ca[i]->position_m != cb[i]->position_m)
      return false;
  return a.beam.length_m == b.beam.length_m && a.beam.youngs_modulus_Pa == b.beam.youngs_modulus_Pa &&
         a.excitation.position_m == b.excitation.position_m;
}

}  // namespace

void CampaignFollower::ReadCampaignIfChanged() {
  const std::filesystem::path file = folder_ / "campaign.json";
  const std::optional<FileSignature> signature = SignatureOf(file);
  if (!signature || signature == campaign_signature_) return;
  try {
    Campaign campaign = ParseCampaign(ReadTextFile(file, "campaign description", "check read permissions"), folder_,
                                      file.string());
    // A campaign.json that is valid but names a file outside the folder is
    // no half-written file: refused at once.
    invalid_in_a_row_ = 0;
    campaign_signature_ = signature;
    RequireRecordingsInside(campaign, file, false);
    if (campaign_ && !SameLayout(*campaign_, campaign))
      throw InputError(file.string(), "",
                       "the channels or the beam changed while the campaign was followed; the steps analysed so far "
                       "were read with the old ones",
                       "start a new campaign folder for a new set-up");
    campaign_ = std::move(campaign);
  } catch (const InputError& e) {
    if (campaign_signature_ == signature) throw;  // parsed, and wrong
    if (++invalid_in_a_row_ >= options_.invalid_looks) throw;
  }
}

std::vector<FollowedStep> CampaignFollower::Look(double now_s) {
  ReadCampaignIfChanged();
  std::vector<FollowedStep> out;
  if (!campaign_) return out;
  const Campaign& campaign = *campaign_;
  for (std::size_t i = 0; i < campaign.steps.size(); ++i) {
    const Step& step = campaign.steps[i];
    const std::optional<FileSignature> signature = SignatureOf(campaign.StepPath(step));
    if (!signature) continue;
    auto [it, is_new] = seen_.try_emplace(step.file, Seen{.signature = *signature, .since_s = now_s});
    Seen& seen = it->second;
    if (!is_new && seen.signature != *signature) {
      // Still being written, or written anew after a faulty take.
      seen = Seen{.signature = *signature, .since_s = now_s};
      continue;
    }
    if (seen.handed_out || now_s - seen.since_s < options_.stable_s || is_new) continue;
    FollowedStep followed{.index = static_cast<int>(i), .step = step};
    followed.again = seen_again_.contains(step.file);
    try {
      followed.recording = ReadRecording(campaign, step, options_.checks);
    } catch (const std::invalid_argument& e) {
      followed.status = FollowedStatus::kFaulty;
      followed.error = e.what();
    }
    seen.handed_out = true;
    seen_again_.insert(step.file);
    out.push_back(std::move(followed));
  }
  return out;
}

int CampaignFollower::waiting() const {
  if (!campaign_) return 0;
  int count = 0;
  for (const Step& step : campaign_->steps) {
    const auto it = seen_.find(step.file);
    if (it == seen_.end() || !it->second.handed_out) ++count;
  }
  return count;
}

}  // namespace beamid::signal
