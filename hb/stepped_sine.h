// A stepped-sine test run on the time-domain simulator, like the real one:
// for each force level a sweep of frequency steps; the beam's state carries
// over from step to step; each step settles (until the fundamental of every
// channel stops changing, hb/scenario.h ScenarioTiming), then records. The
// generator runs at the nominal frequency times (1 + clock_offset·1e-6) with a
// continuous phase φ, and the force is
//     F(t) = F₁·[cos φ + Σ_k r_k·cos(kφ + ψ_k)]        (prescribed force),
// or, with a voltage drive, the voltage V₀·[cos φ + Σ_k r_k·cos(kφ + ψ_k)]
// through the amplifier's gain g(f) (hb/scenario.h ScenarioAmplifier), or,
// with base excitation, the base's acceleration a_b(t) of the same form (the
// beam integrated relative to the base, hb/time_simulator.h). With
// timing.excitation_stop_fraction the drive is switched off inside each
// recording and the beam rings down. The phase reference of the truth is the
// fundamental of the excitation channel (force, voltage or a_b).
// Recordings are noise-free and in SI here (hb/noise.h adds noise); the truth
// of each step is the least-squares fit (hb/time_harmonic_fit.h) of harmonics
// 0..5 over its steady part, referenced to the force fundamental
// (docs/fourier-convention.md). A sensor's measurement artefacts (its gain
// error and delay, hb/scenario.h ScenarioSensor) are in its recorded
// channel only: the truth, and the settling test, see the beam's true motion
// at the sensor's true position. A step named by timing.early_records is
// recorded after its own settle time instead of the settling rule.
#pragma once

#include <array>
#include <functional>
#include <map>
#include <memory>
#include <optional>
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
  double force_amplitude_N = 0.0;    // fundamental of the true force (g(f)·V0 with a voltage drive)
  double voltage_amplitude_V = 0.0;  // voltage drive only: the level's V0
  double base_acceleration_amplitude_m_s2 = 0.0;  // base excitation only: the level's a_b

  double settle_s = 0.0;      // integrated before the steady record
  bool settled = false;       // false: settle_max_s reached first, or an early record
  // timing.early_records: the scenario's settle_s of this step (integrated
  // after the frequency change before the recording's first sample).
  std::optional<double> early_record_settle_s;
  double settle_change = 0.0; // last relative change between windows
  int transient_samples = 0;  // leading samples of the recording before the steady part
  // timing.excitation_stop_fraction: the time in the recording [s] after
  // which the force is zero (it falls to 0 over the next integration step).
  // The truth is fitted over the steady samples up to it.
  std::optional<double> excitation_stop_s;

  // Samples × channels (the excitation, then the sensors in scenario order),
  // SI (N, or V with a voltage drive, or the base's m/s²; m/s², m/s or m;
  // absolute acceleration with base excitation), noise-free, sampled at the
  // acquisition's true rate (ScenarioTiming::TrueSampleRate_hz) and labelled
  // at the stated one; each sensor's gain error and delay applied.
  Eigen::MatrixXd recording;

  // Truth, X_0..X_5 each, phase referenced to the force fundamental:
  // per channel, SI: the true motion at the sensor's true position, before
  // its gain error and delay (its recording's phasors are
  // (1 + g)·X_k·e^{−ikωτ}).
  std::vector<Eigen::VectorXcd> channel_phasors;
  Eigen::VectorXcd force_phasors;  // the true force [N] (channel 0 itself with a force drive; 0 with base excitation)
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
  // f1 of the amplifier's sag (hb/scenario.h ScenarioAmplifier): the first
  // natural frequency of the true FE model with the law's initial stiffness.
  double first_natural_frequency_hz() const { return first_natural_hz_; }

  // Runs every step in order and hands each to `sink` as soon as it is done
  // (the sink writes files and reports progress). Throws std::runtime_error
  // if the integrator fails. It is Step() on each level's frequencies in
  // the scenario's order.
  void Run(const std::function<void(const SimulatedStep&)>& sink);

  // One step on request, as a rig runs the next step a test asks for:
  // `level`'s drive at `nominal_frequency_hz`, settled by `timing`'s rule
  // and recorded for its record_s (its sample rate and clock must be the
  // scenario's). The beam's state and the generator's phase carry over from
  // the step before, so folds and jumps behave as in a real sweep; a step
  // whose level label differs from the last step's starts a level, from rest
  // when timing.restart_each_level. A level's steps are numbered on
  // (step_000.csv, step_001.csv, ...) also when the test comes back to it.
  SimulatedStep Step(const ScenarioLevel& level, double nominal_frequency_hz, const ScenarioTiming& timing);

 private:
  // The drive of one step: what the excitation channel records (force,
  // voltage or a_b) and the simulator's input (the force applied, or a_b),
  // both at the generator phase φ.
  struct Drive {
    double amplitude = 0.0;  // the level's force [N], voltage [V] or a_b [m/s²]
    // Force per unit of the recorded signal, per harmonic: 1 for a force
    // drive; g(f) for the fundamental and g(k·f) for each distortion term.
    double fundamental_gain = 1.0;
    std::vector<double> distortion_gain;
  };
  Drive DriveOf(const ScenarioLevel& level, double frequency_hz) const;
  double Signal(const Drive& drive, double phase_rad) const;
  double Force_N(const Drive& drive, double phase_rad) const;
  void ChannelValues(Eigen::Ref<Eigen::VectorXd> values) const;

  // A sensor's delay τ (ScenarioSensor::delay_s): its true signal at every
  // integration step of the last few, and the weights that interpolate it at
  // τ before the newest (see stepped_sine.cc).
  struct DelayLine {
    int channel = 0;                // column of the recording
    // The sensor's signal from the modal state: row · (modal displacement,
    // velocity or acceleration, by the sensor's quantity), plus a_b for an
    // accelerometer on a moving base.
    Eigen::RowVectorXd modal_row;
    int derivative = 0;             // 0 displacement, 1 velocity, 2 acceleration
    int newest_offset = 0;          // the stencil's first point, in steps back from the newest
    std::array<double, 4> weights{};  // Lagrange weights of the 4 points newest_offset..newest_offset + 3
    std::vector<double> history;    // ring of the last newest_offset + 4 values
    int next = 0;                   // where the next value goes
    void Fill(double value);
    void Push(double value);
    double Delayed() const;
  };
  // The delayed sensor's true signal now.
  double SignalOf(const DelayLine& line) const;
  // The channels' recorded values (gain errors and delays applied) from their
  // true values `channels`.
  void RecordedValues(const Eigen::VectorXd& channels, Eigen::Ref<Eigen::VectorXd> recorded) const;

  Scenario scenario_;
  std::unique_ptr<SupportLaw> law_;
  std::unique_ptr<TimeSimulator> simulator_;
  int substeps_ = 1;
  double first_natural_hz_ = 0.0;
  bool base_excitation_ = false;
  double excitation_signal_ = 0.0;  // the excitation channel's value now (force, voltage or a_b)
  std::vector<DelayLine> delay_lines_;  // one per delayed sensor
  Eigen::VectorXd recorded_gain_;       // per channel: 1 + its gain error
  // Where the test is (Step): steps run so far, the generator's phase, the
  // last step's level, each level's index (in order of first use) and its
  // next step's number.
  int steps_run_ = 0;
  double phase_ = 0.0;
  std::string last_level_;
  std::map<std::string, int> level_indices_;
  std::map<std::string, int> next_index_in_level_;
  // Scratch for the simulator's outputs (sensors, then hidden positions).
  mutable Eigen::VectorXd displacement_, velocity_, acceleration_;
};

}  // namespace beamid::hb
