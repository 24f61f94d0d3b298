// A stepped-sine test run on the time-domain simulator, like the real one:
// for each force level a sweep of frequency steps; the beam's state carries
// over from step to step; each step settles (until the fundamental of every
// channel stops changing, hb/scenario.h ScenarioTiming), then records. The
// generator runs at the nominal frequency times (1 + clock_offset·1e-6) with a
// continuous phase φ, and the force is
//     F(t) = F₁·[cos φ + Σ_k r_k·cos(kφ + ψ_k)]        (prescribed force).
// Recordings are noise-free and in SI here (hb/noise.h adds noise); the truth
// of each step is the least-squares fit (hb/time_harmonic_fit.h) of harmonics
// 0..5 over its steady part, referenced to the force fundamental
// (docs/fourier-convention.md).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "hb/scenario.h"
#include "hb/time_simulator.h"

namespace beamid::hb {

inline constexpr int kTruthHarmonics = 5;

struct SimulatedStep {
  int index = 0;          // position in the whole campaign (run order)
  int level_index = 0;
  int index_in_level = 0;
  std::string level;
  std::string file;       // relative path of its recording: <level>/step_NNN.csv
  double nominal_frequency_hz = 0.0;
  double frequency_hz = 0.0;  // true (generator clock offset applied)
  double force_amplitude_N = 0.0;

  double settle_s = 0.0;      // integrated before the steady record
  bool settled = false;       // false: settle_max_s reached first
  double settle_change = 0.0; // last relative change between windows
  int transient_samples = 0;  // leading samples of the recording before the steady part

  // Samples × channels (force, then the sensors in scenario order), SI
  // (N, m/s², m/s or m), noise-free, at the nominal sample rate.
  Eigen::MatrixXd recording;

  // Truth, X_0..X_5 each, phase referenced to the force fundamental:
  std::vector<Eigen::VectorXcd> channel_phasors;              // per channel, SI
  std::vector<Eigen::VectorXcd> hidden_displacement_phasors;  // per hidden position [m]
  Eigen::VectorXcd support_rotation_phasors;                  // θ = y'(L) [rad]
  Eigen::VectorXcd support_moment_phasors;                    // M_s [N·m]
};

class SteppedSineSimulation {
 public:
  // Throws std::invalid_argument if the scenario's physics is inconsistent.
  explicit SteppedSineSimulation(const Scenario& scenario);
  ~SteppedSineSimulation();

  const Scenario& scenario() const { return scenario_; }
  const TimeSimulator& simulator() const { return *simulator_; }
  int substeps_per_sample() const { return substeps_; }

  // Runs every step in order and hands each to `sink` as soon as it is done
  // (the sink writes files and reports progress). Throws std::runtime_error
  // if the integrator fails.
  void Run(const std::function<void(const SimulatedStep&)>& sink);

 private:
  double Force_N(double amplitude_N, double phase_rad) const;
  void ChannelValues(Eigen::Ref<Eigen::VectorXd> values) const;

  Scenario scenario_;
  std::unique_ptr<SupportLaw> law_;
  std::unique_ptr<TimeSimulator> simulator_;
  int substeps_ = 1;
  // Scratch for the simulator's outputs (sensors, then hidden positions).
  mutable Eigen::VectorXd displacement_, velocity_, acceleration_;
};

}  // namespace beamid::hb
