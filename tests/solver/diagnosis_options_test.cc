// DiagnosisOptions refuse a value out of range before Diagnose does any work
// (a bad option must not cost minutes of fits), and the message names the
// field, its value and the allowed range.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hb/errors.h"
#include "solver/diagnosis/diagnosis.h"

namespace beamid::solver {
namespace {

struct Invalid {
  std::string field;
  std::string value;
  DiagnosisOptions options;
};

std::vector<Invalid> InvalidOptions() {
  std::vector<Invalid> cases;
  DiagnosisOptions o;
  o.significance = 5.0;
  cases.push_back({"significance", "5", o});
  o = {};
  o.significance = 0.0;
  cases.push_back({"significance", "0", o});
  o = {};
  o.num_workers = -1;
  cases.push_back({"num_workers", "-1", o});
  o = {};
  o.model_harmonics = 0;
  cases.push_back({"model_harmonics", "0", o});
  o = {};
  o.refit_max_iterations = 0;
  cases.push_back({"refit_max_iterations", "0", o});
  o = {};
  o.min_relative_improvement = -0.1;
  cases.push_back({"min_relative_improvement", "-0.1", o});
  o = {};
  o.candidates = {"support_friction", "gremlins"};
  cases.push_back({"candidates", "'gremlins'", o});
  return cases;
}

TEST(DiagnosisOptions, RefusesEachInvalidFieldNamingItsValueAndRange) {
  for (const Invalid& c : InvalidOptions()) {
    try {
      c.options.Validate();
      ADD_FAILURE() << c.field << " = " << c.value << " was accepted";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("DiagnosisOptions." + c.field + " = " + c.value + ": must be "), std::string::npos)
          << message;
    }
  }
}

TEST(DiagnosisOptions, AcceptsTheDefaultsAndTheLibrarysCandidates) {
  EXPECT_NO_THROW(DiagnosisOptions{}.Validate());
  DiagnosisOptions o;
  o.candidates = {"support_friction", "harmonic_truncation"};
  o.significance = 0.5;
  o.num_workers = 1;
  o.model_harmonics = 1;
  o.refit_max_iterations = 1;
  EXPECT_NO_THROW(o.Validate());
}

// Diagnose validates first: no stage starts (no progress reported), and the
// error is the option's, not the empty data's.
TEST(Diagnose, RefusesAnInvalidOptionBeforeAnyWork) {
  for (const Invalid& c : InvalidOptions()) {
    int progress_calls = 0;
    try {
      Diagnose(FitData{}, FitData{}, FitData{}, c.options, [&](double, const std::string&) { ++progress_calls; });
      ADD_FAILURE() << c.field << " = " << c.value << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("DiagnosisOptions." + c.field), std::string::npos) << e.what();
    }
    EXPECT_EQ(progress_calls, 0) << c.field;
  }
}

}  // namespace
}  // namespace beamid::solver
