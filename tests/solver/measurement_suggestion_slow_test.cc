// What to measure next: a campaign from the independent
// time-domain simulator whose two fitted accelerometers cannot tell an
// unreported 10 g mass at 0.53 m (added_mass, free position) from heavier
// instruments (instrument_masses: masses at the drive point and at the two
// sensors). The diagnosis must say so and suggest where to add an
// accelerometer; the campaign also recorded one at every position the
// suggestion considers, so the test can then add the suggested one as a
// held-out channel — which must separate the two and name the true cause —
// and one where the suggestion expects nothing, which must not.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <fmt/core.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "solver/diagnosis/diagnosis.h"
#include "tests/support/simulated_campaign.h"

namespace beamid::solver {
namespace {

constexpr int kProbes = 39;  // the suggestion's grid: x = L·i/40

// The paper's set-up (examples/scenarios/paper_base.json) with the mass,
// acc1 at 0.3 m and acc2 at the drive point 0.57 m, a probe accelerometer at
// every grid position, 3 levels × 9 steps, and accelerometers whose noise is
// mostly a floor (1.3 m/s² rms broadband: cheap sensors on a long cable).
nlohmann::json TieScenario() {
  std::ifstream file("examples/scenarios/paper_base.json");
  nlohmann::json s = nlohmann::json::parse(file);
  s["name"] = "two sensors that cannot tell a mass at 0.53 m from heavier instruments";
  s["attachments"] = {{"point_masses", {{{"position_m", 0.53}, {"mass_kg", 0.01}}}}};
  nlohmann::json sensors = nlohmann::json::array();
  sensors.push_back({{"channel", "acc1"}, {"position_m", 0.3}, {"quantity", "acceleration"}, {"unit", "m/s^2"}});
  sensors.push_back({{"channel", "acc2"}, {"position_m", 0.57}, {"quantity", "acceleration"}, {"unit", "m/s^2"}});
  for (int i = 1; i <= kProbes; ++i) {
    const double x = 0.6 * i / (kProbes + 1);
    if (std::abs(x - 0.3) < 1e-9 || std::abs(x - 0.57) < 1e-9) continue;
    sensors.push_back({{"channel", fmt::format("p{:02d}", i)},
                       {"position_m", std::round(x * 1e6) / 1e6},
                       {"quantity", "acceleration"},
                       {"unit", "m/s^2"}});
  }
  s["sensors"] = sensors;
  s.erase("hidden_positions_m");
  for (auto& level : s["levels"]) level["frequencies_Hz"] = {{"start", 51.0}, {"stop", 57.0}, {"step", 0.75}};
  s["timing"]["record_s"] = 0.4;
  s["noise"]["default"]["relative_rms"] = 0.003;
  s["noise"]["default"]["absolute"] = 1.3;
  return s;
}

std::string ProbeAt(double position_m) {
  return fmt::format("p{:02d}", static_cast<int>(std::lround(position_m / 0.6 * (kProbes + 1))));
}

TEST(MeasurementSuggestion, TheSuggestedAccelerometerSeparatesTwoCausesThatTiedAndAUselessOneDoesNot) {
  const testing::ExtractedCampaign campaign = testing::SimulateCampaign(TieScenario(), "beamid_suggestion_test");
  DiagnosisOptions options;
  options.candidates = {"added_mass", "instrument_masses"};
  options.num_workers = 2;
  const FitData fit = campaign.Fit({"acc1", "acc2"});
  const FitData located = campaign.Fit({"acc1", "acc2"}, 5);

  const DiagnosisResult tie = Diagnose(fit, FitData{}, located, options);
  std::printf("two sensors: %s\n", tie.summary.c_str());
  ASSERT_EQ(tie.verdict, DiagnosisVerdict::kCausesIndistinguishable);
  ASSERT_EQ(tie.selected.size(), 2u);
  ASSERT_TRUE(tie.suggestion.has_value());
  const MeasurementSuggestion& s = *tie.suggestion;
  ASSERT_EQ(static_cast<int>(s.positions.size()), kProbes);
  EXPECT_GT(s.best.expected_chi_square_difference, 2.0 * s.current_expected)
      << "the suggested sensor should carry more than the two already there";
  // Where the suggestion expects least, away from the clamp (where nothing moves).
  const PositionGain* useless = nullptr;
  for (const auto& p : s.positions)
    if (p.position_m > 0.1 && (!useless || p.expected_chi_square_difference < useless->expected_chi_square_difference))
      useless = &p;
  ASSERT_NE(useless, nullptr);
  EXPECT_LT(useless->expected_chi_square_difference, 0.1 * s.best.expected_chi_square_difference);

  const DiagnosisResult added = Diagnose(fit, campaign.Fit({ProbeAt(s.best.position_m)}), located, options);
  std::printf("with %s at %.3f m held out: %s\n", ProbeAt(s.best.position_m).c_str(), s.best.position_m,
              added.summary.c_str());
  EXPECT_EQ(added.verdict, DiagnosisVerdict::kCauseNamed);
  EXPECT_EQ(added.selected, std::vector<std::string>{"added_mass"});
  EXPECT_EQ(added.ranked_by, RankedBy::kHeldOutChannels);

  const DiagnosisResult useless_added = Diagnose(fit, campaign.Fit({ProbeAt(useless->position_m)}), located, options);
  std::printf("with %s at %.3f m held out: %s\n", ProbeAt(useless->position_m).c_str(), useless->position_m,
              ToString(useless_added.verdict).c_str());
  EXPECT_EQ(useless_added.verdict, DiagnosisVerdict::kCausesIndistinguishable);
  std::filesystem::remove_all(campaign.folder);
}

}  // namespace
}  // namespace beamid::solver
