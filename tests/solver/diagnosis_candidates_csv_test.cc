// The diagnosis' candidate table as CSV (solver/diagnosis/
// diagnosis_candidates_csv.h): one row per model in the diagnosis' order,
// every row as wide as the header, the verdict on the rows it names, the
// numbers as the diagnosis holds them, and empty cells where a refit gave
// none.
#include "solver/diagnosis/diagnosis_candidates_csv.h"

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/csv_text.h"

namespace beamid::solver {
namespace {

using beamid::testing::G9;

// Cells of a line, a quoted cell (RFC 4180) kept whole with its quotes.
std::vector<std::string> QuotedCells(const std::string& line) {
  std::vector<std::string> cells(1);
  bool quoted = false;
  for (const char c : line) {
    if (c == '"') quoted = !quoted;
    if (c == ',' && !quoted)
      cells.emplace_back();
    else
      cells.back() += c;
  }
  return cells;
}

FitSummary Fit(double chi_square, int dof, double held_out) {
  return {.parameters = {{.name = "k1", .unit = "N·m/rad", .value = 120.0, .std = 1.5},
                         {.name = "slip_moment", .unit = "N·m", .value = 2.5e-3, .std = 1e-4}},
          .chi_square = chi_square,
          .degrees_of_freedom = dof,
          .reduced_chi_square = chi_square / dof,
          .aic = chi_square + 4,
          .bic = chi_square + 9,
          .held_out_chi_square = held_out,
          .held_out_h1_relative_error = held_out / 1000};
}

DiagnosisResult Diagnosis() {
  DiagnosisResult d;
  d.base = Fit(5000.0, 100, 800.0);
  d.verdict = DiagnosisVerdict::kCombinationNamed;
  d.selected = {"support_friction", "added_mass"};
  d.candidates = {
      {.name = "support_friction", .rig_check = "look at the rod, the contact", .signature_score = 0.91,
       .extra_parameters = {"slip_moment"}, .status = RefitStatus::kRefitted, .fit = Fit(140.0, 99, 120.0),
       .likelihood_ratio = 4860.0, .test_dof = 1, .p_value = 1e-300, .residual_drop = 35.7, .significant = true},
      {.name = "added_mass", .signature_score = 0.4, .extra_parameters = {"mass"}, .status = RefitStatus::kFailed,
       .status_message = "Ipopt stopped, restoration failed", .fit = Fit(NAN, 99, NAN)},
      {.name = "sensor_gain(acc1)", .signature_score = 0.1, .status = RefitStatus::kNotRefitted,
       .status_message = "not refitted: the base model already fits, within the noise", .measurement = true}};
  d.combinations = {{.name = "support_friction + added_mass", .status = RefitStatus::kRefitted,
                     .fit = Fit(101.0, 98, 99.0), .likelihood_ratio = 39.0, .test_dof = 1, .p_value = 4e-10,
                     .residual_drop = 1.39, .significant = true}};
  return d;
}

TEST(DiagnosisCandidatesCsv, OneRowPerModelInTheDiagnosisOrderWithItsNumbers) {
  const DiagnosisResult d = Diagnosis();
  const std::vector<std::string> lines = beamid::testing::Lines(DiagnosisCandidatesCsv(d));
  ASSERT_EQ(lines.size(), 1 + 1 + d.candidates.size() + d.combinations.size());
  const std::vector<std::string> header = QuotedCells(lines[0]);
  const auto column = [&](const std::string& name) {
    const auto at = std::find(header.begin(), header.end(), name);
    EXPECT_NE(at, header.end()) << name;
    return static_cast<std::size_t>(at - header.begin());
  };
  std::vector<std::vector<std::string>> rows;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    rows.push_back(QuotedCells(lines[i]));
    EXPECT_EQ(rows.back().size(), header.size()) << lines[i];
  }
  EXPECT_EQ(rows[0][column("kind")], "base");
  EXPECT_EQ(rows[0][column("chi_square")], G9(5000.0));
  EXPECT_EQ(rows[0][column("likelihood_ratio")], "");  // the base is tested against nothing
  for (std::size_t c = 0; c < d.candidates.size(); ++c) {
    EXPECT_EQ(rows[1 + c][column("kind")], "candidate");
    EXPECT_EQ(rows[1 + c][column("rank")], std::to_string(c + 1));
  }
  const auto& friction = rows[1];
  EXPECT_EQ(friction[column("name")], "support_friction");
  EXPECT_EQ(friction[column("named")], "combination named");
  EXPECT_EQ(friction[column("chi_square")], G9(140.0));
  EXPECT_EQ(friction[column("degrees_of_freedom")], "99");
  EXPECT_EQ(friction[column("bic")], G9(149.0));
  EXPECT_EQ(friction[column("p_value")], "1e-300");
  EXPECT_EQ(friction[column("significant")], "yes");
  EXPECT_EQ(friction[column("held_out_chi_square")], "120");
  // Its own parameter only, not the base model's k1.
  EXPECT_EQ(friction[column("own_parameters")], "slip_moment = 0.0025 ± 0.0001 N·m");
  const auto& failed = rows[2];
  EXPECT_EQ(failed[column("named")], "combination named");
  EXPECT_EQ(failed[column("status")], "failed");
  EXPECT_EQ(failed[column("chi_square")], "");
  EXPECT_EQ(failed[column("p_value")], "");
  EXPECT_EQ(failed[column("status_message")], "\"Ipopt stopped, restoration failed\"");
  const auto& artefact = rows[3];
  EXPECT_EQ(artefact[column("named")], "");
  EXPECT_EQ(artefact[column("measurement")], "yes");
  EXPECT_EQ(artefact[column("status")], "not_refitted");
  EXPECT_EQ(artefact[column("signature_score")], "0.100");
  const auto& pair = rows[4];
  EXPECT_EQ(pair[column("kind")], "pair");
  EXPECT_EQ(pair[column("name")], "support_friction + added_mass");
  EXPECT_EQ(pair[column("named")], "combination named");
  EXPECT_EQ(pair[column("likelihood_ratio")], "39");
}

TEST(DiagnosisCandidatesCsv, ACandidateOutsideTheVerdictIsNotNamed) {
  DiagnosisResult d = Diagnosis();
  d.verdict = DiagnosisVerdict::kCauseNamed;
  d.selected = {"support_friction"};
  const std::vector<std::string> lines = beamid::testing::Lines(DiagnosisCandidatesCsv(d));
  EXPECT_EQ(QuotedCells(lines[2])[3], "cause named");
  EXPECT_EQ(QuotedCells(lines[3])[3], "");
  EXPECT_EQ(QuotedCells(lines[5])[3], "");  // the pair is not the answer
}

}  // namespace
}  // namespace beamid::solver
