// A start's record as a worker process hands it back to Identify: every
// field, every double bit for bit (NaN, infinities, subnormals, the last
// digit), since an identification must not depend on the number of workers;
// damaged text is refused, never read as a start.
#include "solver/estimation/start_record_io.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include <gtest/gtest.h>

namespace beamid::solver {
namespace {

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool SameBits(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!SameBits(a[i], b[i])) return false;
  return true;
}

StartRecord Record() {
  StartRecord r;
  r.outcome.objective = 0.1 + 0.2;  // 0.30000000000000004: the last digit must survive
  r.outcome.success = true;
  r.outcome.iterations = 37;
  r.outcome.status = "Solve_Succeeded";
  r.outcome.status_code = 1;
  r.outcome.route = StartRoute::kFeasibleStates;
  r.outcome.branch_repairs = 2;
  r.outcome.parameters = {150.00297, -4.02, 299992.2, 0.0500293, 1.9e-4};
  r.outcome.scaled_at = {149.0, 1e-300, std::numeric_limits<double>::denorm_min(), 0.05, 2e-4};
  r.x = {1.0 / 3.0, -0.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
         -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::max(), 6.02214076e23};
  return r;
}

TEST(StartRecord, RoundTripsEveryFieldBitForBit) {
  const StartRecord a = Record();
  const StartRecord b = StartRecordFromText(StartRecordToText(a));
  EXPECT_TRUE(SameBits(a.outcome.objective, b.outcome.objective));
  EXPECT_EQ(a.outcome.success, b.outcome.success);
  EXPECT_EQ(a.outcome.iterations, b.outcome.iterations);
  EXPECT_EQ(a.outcome.status, b.outcome.status);
  EXPECT_EQ(a.outcome.status_code, b.outcome.status_code);
  EXPECT_EQ(a.outcome.route, b.outcome.route);
  EXPECT_EQ(a.outcome.branch_repairs, b.outcome.branch_repairs);
  EXPECT_TRUE(SameBits(a.outcome.parameters, b.outcome.parameters));
  EXPECT_TRUE(SameBits(a.outcome.scaled_at, b.outcome.scaled_at));
  EXPECT_TRUE(std::isnan(b.x[2]));
  // A NaN's payload need not survive, its NaN-ness must.
  std::vector<double> ax = a.x, bx = b.x;
  ax[2] = bx[2] = 0.0;
  EXPECT_TRUE(SameBits(ax, bx));
  EXPECT_TRUE(std::signbit(b.x[1]));  // -0.0 stays negative
}

TEST(StartRecord, DamagedTextIsRefused) {
  const std::string good = StartRecordToText(Record());
  EXPECT_THROW(StartRecordFromText(good.substr(0, good.size() / 2)), std::runtime_error);
  EXPECT_THROW(StartRecordFromText(""), std::runtime_error);
  std::string unknown_route = good;
  unknown_route.replace(unknown_route.find("\"route\":1"), 9, "\"route\":7");
  EXPECT_THROW(StartRecordFromText(unknown_route), std::runtime_error);
  std::string word = good;
  word.replace(word.find("\"nan\""), 5, "\"zap\"");
  EXPECT_THROW(StartRecordFromText(word), std::runtime_error);
}

}  // namespace
}  // namespace beamid::solver
