// The plan file a DAQ script polls (docs/test-plan-format.md): every field
// written is read back as it was, the sweep's way among them; a plan of an
// older beamid without "sweep" reads as swept up; a way that is neither,
// or a step with no frequency, is refused naming the field.
#include "solver/live/test_plan_io.h"

#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hb/errors.h"

namespace beamid::solver {
namespace {

TestPlan APlan() {
  TestPlan plan{.sequence = 7,
                .done = false,
                .next = PlannedStep{.level = "high",
                                    .force_N = 9.0,
                                    .frequency_hz = 53.15,
                                    .settle_s = 7.5,
                                    .record_s = 3.2,
                                    .reason = "sweeping high downwards: the fitted support softens",
                                    .expected_gain = 1.25,
                                    .expected_gain_per_s = 0.125,
                                    .sweep = SweepDirection::kDown},
                .steps_analysed = 8,
                .rig_time_s = 81.5,
                .parameters = {{.name = "k1",
                                .unit = "N*m/rad",
                                .value = 150.0,
                                .std = 0.002,
                                .target_std = 0.001,
                                .lower_95 = 149.99,
                                .upper_95 = 150.01,
                                .depends_on_damping_law = true}},
                .reduced_chi_square = 0.93,
                .fit_verdict = "fits within the noise",
                .warnings = {"a warning"},
                .model = "polynomial support",
                .intervals = "statistical (value ± 1.96σ)"};
  plan.diagnosis = PlanDiagnosis{.steps = 8, .verdict = "cause named", .selected = {"added_mass"}, .seconds = 4.5};
  return plan;
}

TEST(TestPlanFile, EveryFieldWrittenIsReadBackTheSweepsWayAmongThem) {
  const TestPlan plan = APlan();
  const TestPlan back = ParseTestPlan(TestPlanJson(plan), "plan.json");
  EXPECT_EQ(back.sequence, plan.sequence);
  ASSERT_TRUE(back.next.has_value());
  EXPECT_EQ(back.next->level, "high");
  EXPECT_EQ(back.next->frequency_hz, 53.15);
  EXPECT_EQ(back.next->settle_s, 7.5);
  EXPECT_EQ(back.next->record_s, 3.2);
  EXPECT_EQ(back.next->sweep, SweepDirection::kDown);
  EXPECT_EQ(back.next->reason, plan.next->reason);
  EXPECT_EQ(back.next->expected_gain_per_s, 0.125);
  ASSERT_EQ(back.parameters.size(), 1u);
  EXPECT_EQ(back.parameters[0].upper_95, 150.01);
  EXPECT_TRUE(back.parameters[0].depends_on_damping_law);
  ASSERT_TRUE(back.diagnosis.has_value());
  EXPECT_EQ(back.diagnosis->selected, std::vector<std::string>{"added_mass"});
  EXPECT_EQ(TestPlanJson(back), TestPlanJson(plan));
}

TEST(TestPlanFile, APlanWithoutTheSweepsWayIsSweptUpAndAWayThatIsNeitherIsRefused) {
  nlohmann::json json = nlohmann::json::parse(TestPlanJson(APlan()));
  EXPECT_EQ(json["next"]["sweep"], "down");
  json["next"].erase("sweep");
  EXPECT_EQ(ParseTestPlan(json.dump(), "old.json").next->sweep, SweepDirection::kUp);

  json["next"]["sweep"] = "sideways";
  try {
    ParseTestPlan(json.dump(), "bad.json");
    ADD_FAILURE() << "a sweep that is neither up nor down was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.json"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("sweep"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("\"up\" or \"down\""), std::string::npos) << e.what();
  }
  json["next"]["sweep"] = "up";
  json["next"]["frequency_Hz"] = 0.0;
  EXPECT_THROW(ParseTestPlan(json.dump(), "bad.json"), InputError);
}

}  // namespace
}  // namespace beamid::solver
