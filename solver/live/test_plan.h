// What a running test should do next, as `beamid watch` tells the rig: the
// next step (level, force, frequency, how long to settle and to record) and
// why, or that the test is done and why; with the identification so far
// beside it. docs/test-plan-format.md describes the file (format
// "beamid-test-plan/1") that a DAQ script polls.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace beamid::solver {

inline constexpr const char* kTestPlanFormat = "beamid-test-plan/1";

// A force level the test may use: its label (campaign.json's "level") and
// the force amplitude the rig applies at it [N].
struct PlanLevel {
  std::string label;
  double force_N = 0.0;
};

// Which way a level's frequency is stepped. A hardening support bends the
// resonance up as the amplitude grows, a softening one down; each is swept
// towards where the resonance leans, so that the resonant branch of a fold
// is followed to its end and the jump off it is met there, as a test
// engineer sweeps it.
enum class SweepDirection { kUp, kDown };

struct PlannedStep {
  std::string level;
  double force_N = 0.0;
  double frequency_hz = 0.0;
  double settle_s = 0.0;  // drive at the new frequency this long before recording
  double record_s = 0.0;  // then record this long
  std::string reason;     // one sentence: why this step
  // What it is expected to teach: the fall of log det of the target
  // parameters' covariance (nats; 0 for a step the plan repeats or a sweep
  // step taken before a fit exists), and per second of rig time.
  double expected_gain = 0.0;
  double expected_gain_per_s = 0.0;
  bool repeat = false;    // the same step as the last, measured again
  SweepDirection sweep = SweepDirection::kUp;  // the way this step's level is swept
};

struct PlanParameter {
  std::string name;
  std::string unit;
  double value = 0.0;
  double std = 0.0;
  double target_std = 0.0;  // 0: not a target
  // The 95 % interval: value ± 1.96σ, or, once the test is done with the fit
  // within the noise, the model-form interval over the beam's damping laws
  // and the harmonic truncation (solver/estimation/damping_laws.h), as
  // `beamid identify` gives it.
  double lower_95 = 0.0;
  double upper_95 = 0.0;
  bool depends_on_damping_law = false;  // another accepted law's value lies outside value ± 1.96σ
};

// The diagnosis run on the steps so far when the fit missed them beyond
// their noise (solver/diagnosis/diagnosis.h).
struct PlanDiagnosis {
  int steps = 0;                      // usable steps it saw
  std::string verdict;                // "cause named", "causes indistinguishable", ...
  std::vector<std::string> selected;  // the cause(s) named; {"none"} when none
  std::string summary;                // its summary, as diagnosis.json's
  // The identification now holds the named physics (its parameters beside
  // k1..c): the fit and the plan go on with it.
  bool model_extended = false;
  // Causes indistinguishable: the steps that would tell them apart, where
  // the plan now measures (empty otherwise).
  std::string focus_level;
  double focus_low_hz = 0.0, focus_high_hz = 0.0;
  double seconds = 0.0;
};

struct TestPlan {
  int sequence = 0;            // grows by one with every plan written
  bool done = false;
  std::string done_reason;     // why the test may stop
  std::optional<PlannedStep> next;
  int steps_analysed = 0;      // usable steps so far
  double rig_time_s = 0.0;     // settle + record of the steps asked for so far
  std::vector<PlanParameter> parameters;  // empty before the first fit
  double reduced_chi_square = 0.0;        // of the last fit (0 before)
  std::string fit_verdict;                // the last fit's verdict, one sentence
  std::vector<std::string> warnings;      // of the last step or fit
  std::string model;                      // "polynomial support", or it with the named physics
  std::string intervals;                  // what lower_95..upper_95 hold
  std::optional<PlanDiagnosis> diagnosis; // the last one run
};

}  // namespace beamid::solver
