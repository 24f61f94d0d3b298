// Test support: a coverage study of identify's intervals. One noise-free
// campaign from the independent time-domain simulator (never from the
// harmonic-balance model being fitted), then independent realisations of
// the campaign's own measurement noise on those recordings (hb/noise.h, as
// `beamid simulate` applies it), each extracted and identified; for every
// parameter it counts how often the 95 % interval holds the truth and sums
// z = (estimate − truth)/σ. Calibrated intervals cover 95 % and give
// rms z = 1; a bias shows as mean z ≠ 0.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hb/scenario.h"
#include "solver/diagnosis/diagnosis.h"
#include "solver/estimation/fit_data.h"
#include "solver/estimation/identify.h"
#include "solver/estimation/model_structure.h"
#include "tests/support/proof_diagnosis.h"
#include "tests/support/simulated_campaign.h"

namespace beamid::testing {

struct ParameterCoverage {
  std::string name;
  double truth = 0.0;
  int covered = 0;    // realisations whose 95 % interval held the truth
  int estimated = 0;  // realisations that estimated it (z sums over those)
  double sum_z = 0.0, sum_z2 = 0.0;
  // The truth's least distance from an interval's end, in σ: a count that
  // the last bits of a fit could change has one near 0.
  double nearest_end_sigma = std::numeric_limits<double>::infinity();

  void Add(const solver::ParameterEstimate& estimate) {
    const double z = (estimate.value - truth) / estimate.std;
    sum_z += z;
    sum_z2 += z * z;
    ++estimated;
    covered += estimate.lower_95 <= truth && truth <= estimate.upper_95;
    nearest_end_sigma = std::min(
        nearest_end_sigma,
        std::min(std::abs(truth - estimate.lower_95), std::abs(estimate.upper_95 - truth)) / estimate.std);
  }
};

struct CoverageStudy {
  std::vector<ParameterCoverage> parameters;
  int realisations = 0;
  double sum_reduced_chi_square = 0.0;
  // Per step, the sums of where its analysed part starts [s] and their
  // squares over the realisations: whether the noise moves it.
  std::vector<double> sum_start_s, sum_start2_s;

  double Coverage(std::size_t j) const {
    return static_cast<double>(parameters[j].covered) / std::max(1, parameters[j].estimated);
  }
  double MeanZ(std::size_t j) const { return parameters[j].sum_z / parameters[j].estimated; }
  double RmsZ(std::size_t j) const { return std::sqrt(parameters[j].sum_z2 / parameters[j].estimated); }
  double MeanReducedChiSquare() const { return sum_reduced_chi_square / realisations; }
  // The analysed part's start: its standard deviation over the
  // realisations, rms over the steps.
  double WindowStartRms_s() const {
    double sum = 0.0;
    for (std::size_t i = 0; i < sum_start_s.size(); ++i) {
      const double mean = sum_start_s[i] / realisations;
      sum += std::max(0.0, sum_start2_s[i] / realisations - mean * mean);
    }
    return sum_start_s.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(sum_start_s.size()));
  }
  void AddWindowStarts(const signal::PhasorSet& phasors) {
    sum_start_s.resize(phasors.steps.size(), 0.0);
    sum_start2_s.resize(phasors.steps.size(), 0.0);
    for (std::size_t i = 0; i < phasors.steps.size(); ++i) {
      const double start = phasors.steps[i].quality.settled_after_s;
      sum_start_s[i] += start;
      sum_start2_s[i] += start * start;
    }
  }
};

inline void PrintStudy(const CoverageStudy& study) {
  for (std::size_t j = 0; j < study.parameters.size(); ++j)
    std::printf("%-22s coverage %5.1f %%, mean z %+.2f, rms z %.2f, truth nearest an end %.3f sigma\n",
                study.parameters[j].name.c_str(), 100.0 * study.Coverage(j), study.MeanZ(j), study.RmsZ(j),
                study.parameters[j].nearest_end_sigma);
}

// 50 realisations: rms z has a sampling σ of about 1/√100 = 0.1; 95 %
// coverage reads 90 % or less with probability 0.04, 100 % with 0.08 (the
// fixed seeds read 92–98 %). 100: rms z's σ is 0.07, and 90 % or less has
// probability 0.03, 100 % 0.006.
inline void ExpectCalibrated(const CoverageStudy& study, std::size_t j) {
  const std::string& name = study.parameters[j].name;
  EXPECT_GE(study.Coverage(j), 0.90) << name;
  EXPECT_LE(study.Coverage(j), 0.99) << name << ": intervals too wide";
  EXPECT_GE(study.RmsZ(j), 0.8) << name << ": intervals too wide";
  EXPECT_LE(study.RmsZ(j), 1.25) << name << ": intervals too narrow";
}

// The physics a study simulates and the model that is fitted to it, whose
// physics matches the simulation's up to what the name says.
struct CoveragePhysics {
  std::string name;
  hb::Scenario scenario;
  solver::ModelStructure structure;
  std::vector<double> truth;  // in structure.Names()' order
};

// The paper's example campaign with 15 steps per level (LeanPaperBase).
// "loss_factor": the beam's structural loss factor η = 2e-4, fitted as η; the
//   simulator dissipates exactly as E(1 + iη) only at the harmonic nearest
//   each mode (hb/time_simulator.h), so the harmonic-balance model's loss
//   factor is the simulated law up to the damping at the other harmonics.
// "modal_loss_factor": the same beam fitted as the modal loss factor η_m
//   (hb/matched_modal_loss.h), the simulator's own law.
// "rayleigh": Rayleigh beam damping α = 0.03 1/s, β = 4e-7 s (mode 1's
//   damping ratio ≈ 1.1e-4, as η's), fitted as α, β: the same law in both.
// Settling: kAsThePaper settles each step to 1e-5, whose ringing scatters
// the damping beyond its σ (c: rms z 1.41 with the modal law, 1.06 settled);
// kTight as SettleTightly (simulated_campaign.h): the physics the model holds.
enum class CoverageSettling { kAsThePaper, kTight };

inline CoveragePhysics MakeCoveragePhysics(const std::string& name,
                                           CoverageSettling settling = CoverageSettling::kAsThePaper) {
  nlohmann::json scenario = LeanExample("paper_base.json");
  CoveragePhysics physics{.name = name,
                          .scenario = {},
                          .structure = solver::PolynomialModel({.k1_Nm_rad = 100.0}),
                          .truth = {150.0, 0.0, 3e5, 0.05}};
  if (name == "loss_factor") {
    physics.structure.linear.push_back(solver::LossFactor(1e-4));
    physics.truth.push_back(2e-4);
  } else if (name == "modal_loss_factor") {
    physics.structure.linear.push_back(solver::ModalLossFactor(1e-4));
    physics.truth.push_back(2e-4);
  } else if (name == "rayleigh") {
    scenario["beam"]["loss_factor"] = 0.0;
    scenario["beam"]["rayleigh_mass_1_s"] = 0.03;
    scenario["beam"]["rayleigh_stiffness_s"] = 4e-7;
    physics.structure.linear.push_back(solver::RayleighMassDamping(0.01));
    physics.structure.linear.push_back(solver::RayleighStiffnessDamping(1e-7));
    physics.truth.push_back(0.03);
    physics.truth.push_back(4e-7);
  } else {
    throw std::invalid_argument("unknown coverage physics '" + name + "' (loss_factor, modal_loss_factor, rayleigh)");
  }
  if (settling == CoverageSettling::kTight) {
    SettleTightly(scenario);
    physics.name += "_settled";
  }
  physics.scenario = hb::ParseScenario(scenario.dump(), "paper_base.json, 15 steps per level, " + physics.name);
  return physics;
}

// The physics' noise-free campaign as simulated, and its campaign.json read back.
struct SimulatedCoverageCampaign {
  std::vector<hb::SimulatedStep> steps;
  signal::Campaign campaign;
};

inline SimulatedCoverageCampaign SimulateCoverageCampaign(const CoveragePhysics& physics) {
  const std::filesystem::path folder = UniqueTempPath("beamid_coverage_study_" + physics.name);
  std::filesystem::remove_all(folder);
  SimulatedCoverageCampaign simulated{.steps = SimulateInto(physics.scenario, folder), .campaign = {}};
  simulated.campaign = signal::ReadCampaign(folder);
  std::filesystem::remove_all(folder);
  return simulated;
}

// `realisations` noise draws from seeds first_seed, first_seed + 1, …, each
// fitted to acc1 and acc2 with `fit_options`' weighting; `each` (if set)
// sees every realisation's fit.
inline CoverageStudy RunCoverageStudy(
    const CoveragePhysics& physics, solver::FitDataOptions fit_options, int realisations, std::uint64_t first_seed,
    const std::function<void(int realisation, const solver::IdentifyResult&)>& each = {}) {
  const auto [steps, campaign] = SimulateCoverageCampaign(physics);

  CoverageStudy study;
  for (const std::string& name : physics.structure.Names())
    study.parameters.push_back({.name = name, .truth = physics.truth[study.parameters.size()]});
  fit_options.channels = {"acc1", "acc2"};
  for (int r = 0; r < realisations; ++r) {
    const signal::PhasorSet phasors = MeasureAgain(physics.scenario, steps, campaign, first_seed + r);
    study.AddWindowStarts(phasors);
    const solver::IdentifyResult result =
        solver::Identify(solver::MakeFitData(campaign, phasors, fit_options), physics.structure, {});
    for (std::size_t j = 0; j < study.parameters.size(); ++j) study.parameters[j].Add(result.parameters.at(j));
    if (each) each(r, result);
    study.sum_reduced_chi_square += result.reduced_chi_square;
    ++study.realisations;
  }
  return study;
}

// A cause concealed in the paper set-up (3 levels × 9 steps, as the
// diagnosis proofs), the name the diagnosis must select for it, and the
// truth of the named model's parameters.
// "none": nothing concealed; the diagnosis must name nothing.
// "sensor_gain": acc2 reads 1 % high (a calibration factor off), named
//   sensor_gain(acc2) with gain_error_acc2 beside the base physics.
// "friction": a Jenkins element (50 N·m/rad, slipping at 0.15 N·m) beside
//   k1 = 100, named support_friction; the simulator's steps settle to 5e-4
//   as examples/scenarios/paper_friction.json's.
// kExact: SettleTightly (simulated_campaign.h) and diagnosed with the modal
// loss factor, so that beside the cause the diagnosed model holds the
// simulated physics exactly.
enum class ConcealedPhysics { kAsThePaper, kExact };

struct ConcealedCause {
  std::string name;
  hb::Scenario scenario;
  std::string cause;
  std::vector<std::pair<std::string, double>> truth;
  bool exact = false;
};

inline ConcealedCause MakeConcealedCause(const std::string& name,
                                         ConcealedPhysics physics = ConcealedPhysics::kAsThePaper) {
  nlohmann::json scenario = PaperSetUpScenario();
  ConcealedCause cause{.name = name, .scenario = {}, .cause = {},
                       .truth = {{"k1", 150.0}, {"k2", 0.0}, {"k3", 3e5}, {"c", 0.05}, {"loss_factor", 2e-4}},
                       .exact = physics == ConcealedPhysics::kExact};
  if (cause.exact) cause.truth.back().first = "modal_loss_factor";
  if (name == "none") {
    cause.cause = "none";  // the base, whose fit the diagnosis reports when it finds nothing
  } else if (name == "sensor_gain") {
    for (nlohmann::json& sensor : scenario["sensors"])
      if (sensor["channel"] == "acc2") sensor["gain_error_relative"] = 0.01;
    cause.cause = "sensor_gain(acc2)";
    cause.truth.emplace_back("gain_error_acc2", 0.01);
  } else if (name == "friction") {
    AddSupportFriction(scenario, 100.0, 50.0, 0.15);
    cause.cause = "support_friction";
    cause.truth[0].second = 100.0;
    cause.truth.emplace_back("jenkins_stiffness", 50.0);
    cause.truth.emplace_back("jenkins_slip_moment", 0.15);
  } else {
    throw std::invalid_argument("unknown concealed cause '" + name + "' (none, sensor_gain, friction)");
  }
  // After the cause: the friction's own settling would undo it.
  if (cause.exact) SettleTightly(scenario);
  cause.scenario = hb::ParseScenario(scenario.dump(), "paper set-up, " + name + (cause.exact ? ", exact" : ""));
  return cause;
}

// The coverage of the named model's intervals: each realisation diagnosed
// as the proofs do (acc1 and acc2 fitted, acc3 held out, located to the 5th
// harmonic) under `weighting`. A realisation that selects another model
// holds no truth; `named` counts those that select the cause.
struct DiagnosisCoverageStudy {
  CoverageStudy coverage;
  int named = 0;
};

// kOneSimulation: one simulation, a new draw of the noise per realisation.
// kSimulatedPerRealisation: each realisation also simulated anew, every
// step's settling cut kSettleShift_s later than the last's. A step whose
// response never settles to a periodic one (the friction's slipping steps
// still change by 1e-4–2e-3 between windows after 40 s) keeps a non-periodic
// part in its record, which the record's σ counts as noise; one simulation
// would hand the same draw of it to every realisation, a bias shared by all.
enum class CoverageRecords { kOneSimulation, kSimulatedPerRealisation };
inline constexpr double kSettleShift_s = 0.37;

// Simulated anew, a realisation differs from the first simulation only in
// the steps that did not settle there. Every level starts from rest
// (ScenarioTiming::restart_each_level), so a level's steps up to its first
// unsettled one are the first simulation's, sample for sample; a step that
// settled (to 1e-8, SettleTightly) after an unsettled one starts at another
// phase of the generator, its phasors (referred to the force) the same to
// 1e-8 of its amplitude, far below the noise. So a realisation simulates
// only the levels that hold an unsettled step, each up to its last one (the
// friction's 6 slipping steps of 27: 29 % less simulated time on average;
// the slipping steps come out sample for sample as in the whole campaign),
// and takes every step that settled from the first simulation.
inline hb::Scenario UpToTheUnsettledSteps(hb::Scenario scenario, const std::vector<hb::SimulatedStep>& first) {
  if (!scenario.timing.restart_each_level)
    throw std::invalid_argument("UpToTheUnsettledSteps: the levels must start from rest");
  std::vector<hb::ScenarioLevel> levels;
  for (const hb::ScenarioLevel& level : scenario.levels) {
    int last_unsettled = -1;
    for (const hb::SimulatedStep& step : first)
      if (step.level == level.label && !step.settled) last_unsettled = std::max(last_unsettled, step.index_in_level);
    if (last_unsettled < 0) continue;
    levels.push_back(level);
    levels.back().frequencies_hz.resize(static_cast<std::size_t>(last_unsettled) + 1);
  }
  scenario.levels = levels;
  return scenario;
}

// `first` with each step that did not settle there replaced by the step of
// `again` of the same level and place in it.
inline std::vector<hb::SimulatedStep> WithTheUnsettledStepsOf(std::vector<hb::SimulatedStep> first,
                                                              const std::vector<hb::SimulatedStep>& again) {
  for (hb::SimulatedStep& step : first) {
    if (step.settled) continue;
    const auto it = std::find_if(again.begin(), again.end(), [&](const hb::SimulatedStep& s) {
      return s.level == step.level && s.index_in_level == step.index_in_level;
    });
    if (it == again.end()) throw std::logic_error("WithTheUnsettledStepsOf: " + step.file + " was not simulated again");
    const int index = step.index;
    step = *it;
    step.index = index;
  }
  return first;
}

// kWholeLibrary: diagnosed as `beamid diagnose` does. kTheCauseAlone: the
// cause is the only candidate, without the recording's faults, pairs or the
// damping laws' refits; the named model's statistical intervals are the
// same, for a fraction of the time (the friction's diagnosis: 3.4 s, not 24).
enum class CoverageCandidates { kWholeLibrary, kTheCauseAlone };

struct DiagnosisCoverageOptions {
  solver::PhasorUncertainty weighting = solver::PhasorUncertainty::kPropagated;
  int realisations = 50;
  std::uint64_t first_seed = 7000;  // realisation r draws from first_seed + r
  CoverageRecords records = CoverageRecords::kOneSimulation;
  CoverageCandidates candidates = CoverageCandidates::kWholeLibrary;
};

inline DiagnosisCoverageStudy RunDiagnosisCoverageStudy(const ConcealedCause& cause,
                                                        const DiagnosisCoverageOptions& options) {
  const std::vector<hb::SimulatedStep> first = SimulateSteps(cause.scenario);
  const ExtractedCampaign written = WriteAndExtract(cause.scenario, first, 1, "beamid_coverage_" + cause.name);
  solver::DiagnosisOptions diagnosis{.modal_loss_factor = cause.exact};
  if (options.candidates == CoverageCandidates::kTheCauseAlone) {
    diagnosis.candidates = {cause.cause};
    diagnosis.measurement_artefacts = false;
    diagnosis.max_pair_partners = 0;
    diagnosis.damping_laws = false;
  }
  DiagnosisCoverageStudy study;
  for (const auto& [name, truth] : cause.truth) study.coverage.parameters.push_back({.name = name, .truth = truth});
  // A simulation anew takes four times a diagnosis here: two at a time, each
  // on its own thread (a simulation is single-threaded and shares nothing).
  constexpr int kBatch = 2;
  const bool anew = options.records == CoverageRecords::kSimulatedPerRealisation;
  for (int batch = 0; batch < options.realisations; batch += kBatch) {
    const int size = std::min(kBatch, options.realisations - batch);
    std::vector<std::vector<hb::SimulatedStep>> simulated(static_cast<std::size_t>(size));
    std::vector<std::exception_ptr> failures(static_cast<std::size_t>(size));
    if (anew) {
      std::vector<std::jthread> threads;
      for (int i = 0; i < size; ++i)
        if (batch + i > 0)
          threads.emplace_back([&, i] {
            try {
              hb::Scenario later = UpToTheUnsettledSteps(cause.scenario, first);
              later.timing.settle_max_s += kSettleShift_s * (batch + i);
              simulated[static_cast<std::size_t>(i)] =
                  later.levels.empty() ? first : WithTheUnsettledStepsOf(first, SimulateSteps(later));
            } catch (...) {
              failures[static_cast<std::size_t>(i)] = std::current_exception();
            }
          });
    }
    for (const std::exception_ptr& failure : failures)
      if (failure) std::rethrow_exception(failure);
    for (int i = 0; i < size; ++i) {
      const int r = batch + i;
      const std::vector<hb::SimulatedStep>& steps = anew && r > 0 ? simulated[static_cast<std::size_t>(i)] : first;
      const signal::PhasorSet phasors =
          MeasureAgain(cause.scenario, steps, written.campaign, options.first_seed + r);
      study.coverage.AddWindowStarts(phasors);
      const solver::DiagnosisResult result =
          DiagnoseProofData(MakeProofData(written.campaign, phasors, {.uncertainty = options.weighting}), diagnosis);
      const bool named = result.selected.front() == cause.cause;
      study.named += named;
      for (ParameterCoverage& c : study.coverage.parameters)
        for (const solver::ParameterEstimate& p : result.final_fit.parameters)
          if (named && p.name == c.name) c.Add(p);
      study.coverage.sum_reduced_chi_square += result.final_fit.reduced_chi_square;
      ++study.coverage.realisations;
    }
  }
  std::filesystem::remove_all(written.folder);
  return study;
}

}  // namespace beamid::testing
