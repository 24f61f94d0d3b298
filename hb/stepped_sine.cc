#include "hb/stepped_sine.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "hb/time_harmonic_fit.h"

namespace beamid::hb {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
// Settling windows span whole periods and at least this long.
constexpr double kMinSettleWindow_s = 0.04;

// The last `capacity` rows pushed, oldest first on read-out.
class SampleRing {
 public:
  SampleRing(int capacity, int columns) : rows_(Eigen::MatrixXd::Zero(std::max(capacity, 1), columns)), capacity_(capacity) {}
  void Push(const Eigen::VectorXd& row) {
    if (capacity_ == 0) return;
    rows_.row(next_) = row.transpose();
    next_ = (next_ + 1) % capacity_;
    size_ = std::min(size_ + 1, capacity_);
  }
  int size() const { return size_; }
  void CopyTo(Eigen::MatrixXd& out) const {
    const int start = size_ < capacity_ ? 0 : next_;
    for (int i = 0; i < size_; ++i) out.row(i) = rows_.row((start + i) % std::max(capacity_, 1));
  }
  void Clear() { size_ = next_ = 0; }

 private:
  Eigen::MatrixXd rows_;
  int capacity_;
  int next_ = 0;
  int size_ = 0;
};

}  // namespace

// A sensor's delay τ is honest in time: the channel records the true signal
// at t − τ. The integrator gives the signal only at its steps t_k = k·Δt
// (Δt = 1/(f_s·n), n integration steps per sample), so the value at t − τ,
// d = τ/Δt steps back from the newest, is interpolated by the cubic through
// the four steps around it (two on each side when the history reaches that
// far: d = 10.24 at τ = 0.2 ms and Δt = 1/51200 s uses steps 9..12 back; a
// delay below one step uses steps 0..3). The cubic's error on a harmonic at ω
// is at most 0.023·(ωΔt)⁴ relative between the middle two steps (0.042·(ωΔt)⁴
// between the first two): 7·10⁻¹¹ at 60 Hz and 4·10⁻⁸ at 300 Hz (the 5th
// harmonic) at that Δt, far below what any analysis resolves. A delay of
// whole steps takes the stored value itself. The delay line is a ring of the
// sensor's true signal at every step; a level's start fills it with the
// signal of the beam at rest there (what came before was never recorded).
void SteppedSineSimulation::DelayLine::Fill(double value) { std::fill(history.begin(), history.end(), value); }

void SteppedSineSimulation::DelayLine::Push(double value) {
  history[static_cast<size_t>(next)] = value;
  next = (next + 1) % static_cast<int>(history.size());
}

double SteppedSineSimulation::DelayLine::Delayed() const {
  const int size = static_cast<int>(history.size());
  double value = 0.0;
  for (int j = 0; j < 4; ++j) {
    // `next − 1` is the newest value; go back newest_offset + j from it.
    const int at = ((next - 1 - newest_offset - j) % size + size) % size;
    value += weights[static_cast<size_t>(j)] * history[static_cast<size_t>(at)];
  }
  return value;
}

namespace {

// Output `output`'s row of the simulator's (linear) map from the modal state
// to the outputs, read off by Outputs at unit modal displacements: a delayed
// sensor needs its signal at every integration step, and this row gives it
// for one dot product instead of every output's (which made a campaign with
// a delay 60 % slower).
Eigen::RowVectorXd OutputModalRow(TimeSimulator& simulator, int output) {
  const TimeSimulator::State rest = simulator.state();
  TimeSimulator::State probe = rest;
  const Eigen::Index modes = probe.modal_displacement.size();
  Eigen::VectorXd displacement(simulator.NumOutputs()), velocity(simulator.NumOutputs()),
      acceleration(simulator.NumOutputs());
  Eigen::RowVectorXd row(modes);
  for (Eigen::Index j = 0; j < modes; ++j) {
    probe.modal_displacement.setZero();
    probe.modal_displacement(j) = 1.0;
    simulator.set_state(probe);
    simulator.Outputs(displacement, velocity, acceleration);
    row(j) = displacement(output);
  }
  simulator.set_state(rest);
  return row;
}

}  // namespace

SteppedSineSimulation::SteppedSineSimulation(const Scenario& scenario)
    : scenario_(scenario), law_(scenario.MakeSupportLaw()), base_excitation_(scenario.BaseExcitation()) {
  const ScenarioTiming& timing = scenario_.timing;
  // The integrator lands on the samples the acquisition truly takes (its
  // clock's error, ScenarioTiming::daq_clock_error_relative, included): the
  // files label them at the stated rate, so nothing is interpolated.
  const double sample_period_s = 1.0 / timing.TrueSampleRate_hz();
  substeps_ = std::max(1, static_cast<int>(std::ceil(sample_period_s / timing.max_time_step_s - 1e-9)));
  TimeSimulatorModel model;
  model.beam = scenario_.beam;
  model.attachments = scenario_.TrueAttachments();
  model.force_position_m = scenario_.force_position_m;
  model.base_excitation = scenario_.BaseExcitation();
  model.modal_damping_ratios = scenario_.modal_damping_ratios;
  for (const ScenarioSensor& s : scenario_.sensors) model.output_positions_m.push_back(s.position_m);
  for (double x : scenario_.hidden_positions_m) model.output_positions_m.push_back(x);
  TimeSimulatorOptions options;
  options.time_step_s = sample_period_s / substeps_;
  options.damping_reference_rad_s = kTwoPi * scenario_.damping_reference_frequency_hz;
  options.mesh.min_elements = scenario_.mesh_min_elements;
  simulator_ = std::make_unique<TimeSimulator>(model, *law_, options);
  // Only the amplifier's sag needs it; computed only then, so that a force
  // drive costs nothing.
  if (scenario_.VoltageDrive())
    first_natural_hz_ =
        simulator_->fe_beam().NaturalFrequencies_rad_s(1, law_->InitialStiffness_Nm_rad()).at(0) / kTwoPi;
  const int outputs = simulator_->NumOutputs();
  displacement_.resize(outputs);
  velocity_.resize(outputs);
  acceleration_.resize(outputs);

  // The measurement artefacts of each sensor's channel (column i + 1).
  recorded_gain_ = Eigen::VectorXd::Ones(static_cast<Eigen::Index>(scenario_.sensors.size()) + 1);
  for (size_t i = 0; i < scenario_.sensors.size(); ++i) {
    const ScenarioSensor& sensor = scenario_.sensors[i];
    recorded_gain_(static_cast<Eigen::Index>(i) + 1) = 1.0 + sensor.gain_error_relative;
    if (!(sensor.delay_s > 0.0)) continue;
    DelayLine line;
    line.channel = static_cast<int>(i) + 1;
    line.derivative = sensor.quantity == "displacement" ? 0 : sensor.quantity == "velocity" ? 1 : 2;
    line.modal_row = OutputModalRow(*simulator_, static_cast<int>(i));
    const double steps_back = sensor.delay_s / options.time_step_s;
    line.newest_offset = std::max(0, static_cast<int>(std::floor(steps_back)) - 1);
    for (int j = 0; j < 4; ++j) {  // Lagrange's basis polynomials at steps_back, nodes newest_offset + 0..3
      double weight = 1.0;
      for (int l = 0; l < 4; ++l)
        if (l != j) weight *= (steps_back - (line.newest_offset + l)) / static_cast<double>(j - l);
      line.weights[static_cast<size_t>(j)] = weight;
    }
    line.history.assign(static_cast<size_t>(line.newest_offset) + 4, 0.0);
    delay_lines_.push_back(std::move(line));
  }
}

SteppedSineSimulation::~SteppedSineSimulation() = default;

SteppedSineSimulation::Drive SteppedSineSimulation::DriveOf(const ScenarioLevel& level, double frequency_hz) const {
  Drive drive;
  const ScenarioAmplifier& amplifier = scenario_.amplifier;
  if (scenario_.BaseExcitation()) {
    drive.amplitude = level.base_acceleration_amplitude_m_s2;
    return drive;
  }
  if (!scenario_.VoltageDrive()) {
    drive.amplitude = level.force_amplitude_N;
    return drive;
  }
  drive.amplitude = level.voltage_amplitude_V;
  drive.fundamental_gain = amplifier.Gain_N_per_V(frequency_hz, first_natural_hz_);
  for (const ForceHarmonic& h : scenario_.force_distortion)
    drive.distortion_gain.push_back(amplifier.Gain_N_per_V(h.harmonic * frequency_hz, first_natural_hz_));
  return drive;
}

double SteppedSineSimulation::Signal(const Drive& drive, double phase_rad) const {
  double f = std::cos(phase_rad);
  for (const ForceHarmonic& h : scenario_.force_distortion)
    f += h.amplitude_ratio * std::cos(h.harmonic * phase_rad + h.phase_rad);
  return drive.amplitude * f;
}

double SteppedSineSimulation::Force_N(const Drive& drive, double phase_rad) const {
  // A force drive is its own signal (and stays bit-identical to before the
  // voltage drive existed); with base excitation the simulator's input is
  // the base's acceleration itself (hb/time_simulator.h).
  if (!scenario_.VoltageDrive()) return Signal(drive, phase_rad);
  double f = drive.fundamental_gain * std::cos(phase_rad);
  for (size_t k = 0; k < scenario_.force_distortion.size(); ++k) {
    const ForceHarmonic& h = scenario_.force_distortion[k];
    f += drive.distortion_gain[k] * h.amplitude_ratio * std::cos(h.harmonic * phase_rad + h.phase_rad);
  }
  return drive.amplitude * f;
}

void SteppedSineSimulation::ChannelValues(Eigen::Ref<Eigen::VectorXd> values) const {
  simulator_->Outputs(displacement_, velocity_, acceleration_);
  values(0) = excitation_signal_;
  for (size_t i = 0; i < scenario_.sensors.size(); ++i) {
    const std::string& q = scenario_.sensors[i].quantity;
    const Eigen::Index k = static_cast<Eigen::Index>(i);
    values(k + 1) = q == "acceleration" ? acceleration_(k) : q == "velocity" ? velocity_(k) : displacement_(k);
    // The simulator's motion is relative to the moving base; an
    // accelerometer feels the absolute one (the reader allows only those).
    if (base_excitation_) values(k + 1) += excitation_signal_;
  }
}

double SteppedSineSimulation::SignalOf(const DelayLine& line) const {
  const TimeSimulator::State& state = simulator_->state();
  const Eigen::ArrayXd& motion = line.derivative == 0   ? state.modal_displacement
                                 : line.derivative == 1 ? state.modal_velocity
                                                        : state.modal_acceleration;
  double value = line.modal_row.dot(motion.matrix());
  // The simulator's motion is relative to the moving base (see ChannelValues).
  if (base_excitation_ && line.derivative == 2) value += excitation_signal_;
  return value;
}

void SteppedSineSimulation::RecordedValues(const Eigen::VectorXd& channels, Eigen::Ref<Eigen::VectorXd> recorded) const {
  // Multiplying by exactly 1 keeps a channel without a gain error bit-identical.
  recorded = channels.cwiseProduct(recorded_gain_);
  for (const DelayLine& line : delay_lines_) recorded(line.channel) = recorded_gain_(line.channel) * line.Delayed();
}

void SteppedSineSimulation::Run(const std::function<void(const SimulatedStep&)>& sink) {
  for (const ScenarioLevel& level : scenario_.levels)
    for (const double frequency_hz : level.frequencies_hz) sink(Step(level, frequency_hz, scenario_.timing));
}

SimulatedStep SteppedSineSimulation::Step(const ScenarioLevel& level, double nominal_frequency_hz,
                                         const ScenarioTiming& timing) {
  if (timing.sample_rate_hz != scenario_.timing.sample_rate_hz ||
      timing.daq_clock_error_relative != scenario_.timing.daq_clock_error_relative)
    throw std::invalid_argument("a step's timing keeps the scenario's sample rate and sample clock");
  // The acquisition counts samples of its own clock: the files' lengths and
  // the transient kept are set in samples at the stated rate, while the
  // settling, physical, is timed at the true one.
  const double fs = timing.sample_rate_hz;
  const double true_fs = timing.TrueSampleRate_hz();
  const double dt = simulator_->time_step_s();
  const int num_sensors = static_cast<int>(scenario_.sensors.size());
  const int num_channels = num_sensors + 1;
  const int num_hidden = static_cast<int>(scenario_.hidden_positions_m.size());
  const int transient_capacity = static_cast<int>(std::lround(timing.transient_s * fs));
  const int record_samples = static_cast<int>(std::lround(timing.record_s * fs));
  const double clock = 1.0 + 1e-6 * scenario_.clock_offset_ppm;

  // The channels' true values (what the truth and the settling test see),
  // and what they record (the sensors' gain errors and delays applied).
  Eigen::VectorXd channels(num_channels), recorded(num_channels);
  // Monitored while settling: the sensors and θ (the force is prescribed).
  std::vector<double> monitored(num_sensors + 1);
  // Fitted for the truth: channels, hidden deflections, θ, M_s.
  std::vector<double> truth_values(num_channels + num_hidden + 2);
  SampleRing ring(transient_capacity, num_channels);

  // A level begins when the label changes: the shaker stopped in between
  // (restart_each_level). A level run again later goes on numbering its
  // steps, so that no file of it is written twice.
  const bool new_level = steps_run_ == 0 || level.label != last_level_;
  last_level_ = level.label;
  const int level_index =
      level_indices_.try_emplace(level.label, static_cast<int>(level_indices_.size())).first->second;
  int& index_in_level = next_index_in_level_[level.label];
  if (steps_run_ == 0 || (new_level && timing.restart_each_level)) {
    phase_ = 0.0;
    const Drive first = DriveOf(level, nominal_frequency_hz * clock);
    excitation_signal_ = Signal(first, phase_);
    simulator_->Reset(Force_N(first, phase_));
    for (DelayLine& line : delay_lines_) line.Fill(SignalOf(line));
  }
  double& phase = phase_;
  SimulatedStep step;
  step.index = steps_run_++;
  step.level_index = level_index;
  step.index_in_level = index_in_level++;
  step.level = level.label;
  char name[32];
  std::snprintf(name, sizeof name, "step_%03d.csv", step.index_in_level);
  step.file = level.label + "/" + name;
  step.nominal_frequency_hz = nominal_frequency_hz;
  step.frequency_hz = step.nominal_frequency_hz * clock;
  const Drive drive = DriveOf(level, step.frequency_hz);
  step.force_amplitude_N = scenario_.BaseExcitation() ? 0.0 : drive.fundamental_gain * drive.amplitude;
  step.voltage_amplitude_V = level.voltage_amplitude_V;
  step.base_acceleration_amplitude_m_s2 = level.base_acceleration_amplitude_m_s2;
  const double omega = kTwoPi * step.frequency_hz;
  // The beam's loss factor as the real, frequency-independent one at this
  // step (hb/time_simulator.h), unless the scenario asks for C = (η/ω_ref)·K.
  if (scenario_.damping_reference_frequency_hz == 0.0) simulator_->MatchLossFactorAt(omega);

  // The generator's phase is continuous across the frequency change.
  const double phase_start = std::fmod(phase, kTwoPi);
  long substep = 0;
  // Switched off (timing.excitation_stop_fraction): the generator's phase
  // runs on, but the shaker applies nothing and its channel reads 0.
  bool switched_off = false;
  auto next_sample = [&] {
    for (int i = 0; i < substeps_; ++i) {
      ++substep;
      phase = phase_start + omega * dt * static_cast<double>(substep);
      excitation_signal_ = switched_off ? 0.0 : Signal(drive, phase);
      simulator_->Advance(switched_off ? 0.0 : Force_N(drive, phase));
      // A delayed channel needs its signal at every integration step.
      for (DelayLine& line : delay_lines_) line.Push(SignalOf(line));
    }
    ChannelValues(channels);
    RecordedValues(channels, recorded);
  };

  // Settle.
  const int window_periods = std::max(2, static_cast<int>(std::ceil(kMinSettleWindow_s * step.frequency_hz)));
  const int window_samples = std::max(16, static_cast<int>(std::lround(window_periods * true_fs / step.frequency_hz)));
  long min_samples = std::lround(timing.settle_min_s * true_fs);
  long max_samples = std::max(min_samples, std::lround(timing.settle_max_s * true_fs));
  // An early record ignores the settling rule: its file starts after
  // exactly its settle_s, so it holds the transient (the ring keeps the
  // last transient_capacity samples of the settling).
  const EarlyRecord* early = scenario_.EarlyRecordOf(level.label, step.nominal_frequency_hz);
  if (early) {
    step.early_record_settle_s = early->settle_s;
    min_samples = max_samples = std::lround(early->settle_s * true_fs) + transient_capacity;
  }
  TimeHarmonicFit window(kTruthHarmonics, num_sensors + 1);
  Eigen::VectorXcd previous_fundamentals;
  ring.Clear();
  long samples = 0;
  step.settle_change = 1.0;
  while (samples < max_samples) {
    next_sample();
    ++samples;
    ring.Push(recorded);
    for (int s = 0; s < num_sensors; ++s) monitored[s] = channels(s + 1);
    monitored[num_sensors] = simulator_->SupportRotation_rad();
    window.Add(phase, monitored);
    if (window.NumSamples() < window_samples) continue;
    const std::vector<Eigen::VectorXcd> phasors = window.Solve();
    window.Clear();
    Eigen::VectorXcd fundamentals(num_sensors + 1);
    for (int s = 0; s <= num_sensors; ++s) fundamentals(s) = phasors[s](1);
    if (previous_fundamentals.size() > 0) {
      double change = 0.0;
      for (int s = 0; s <= num_sensors; ++s) {
        const double scale = std::abs(fundamentals(s));
        if (scale > 0.0) change = std::max(change, std::abs(fundamentals(s) - previous_fundamentals(s)) / scale);
      }
      step.settle_change = change;
      if (!early && samples >= min_samples && change < timing.settle_tolerance) {
        step.settled = true;
        break;
      }
    }
    previous_fundamentals = fundamentals;
  }
  step.settle_s = static_cast<double>(samples) / true_fs;

  // Record: the tail of the settling, then the steady part, fitted for the truth.
  step.transient_samples = ring.size();
  step.recording.resize(step.transient_samples + record_samples, num_channels);
  ring.CopyTo(step.recording);
  TimeHarmonicFit truth(kTruthHarmonics, static_cast<int>(truth_values.size()));
  // The last sample of the file with the force on (the whole file when it never stops).
  int last_forced_sample = step.transient_samples + record_samples;
  if (timing.excitation_stop_fraction > 0.0) {
    // Inside the steady part by the reader's check (a shorter transient only moves it later in the record).
    const int file_samples = step.transient_samples + record_samples;
    last_forced_sample = std::min(
        file_samples - 1, static_cast<int>(std::lround(timing.excitation_stop_fraction * file_samples)));
    step.excitation_stop_s = last_forced_sample / fs;
  }
  for (int i = 0; i < record_samples; ++i) {
    // File sample n is reached from n − 1; past the stop the force is 0.
    switched_off = step.transient_samples + i > last_forced_sample;
    next_sample();
    step.recording.row(step.transient_samples + i) = recorded.transpose();
    for (int c = 0; c < num_channels; ++c) truth_values[c] = channels(c);
    for (int h = 0; h < num_hidden; ++h) truth_values[num_channels + h] = displacement_(num_sensors + h);
    truth_values[num_channels + num_hidden] = simulator_->SupportRotation_rad();
    truth_values[num_channels + num_hidden + 1] = simulator_->SupportMoment_Nm();
    if (step.transient_samples + i <= last_forced_sample) truth.Add(phase, truth_values);
  }
  std::vector<Eigen::VectorXcd> phasors = truth.Solve();
  const std::complex<double> force_fundamental = phasors[0](1);
  for (Eigen::VectorXcd& p : phasors) ReferenceToFundamental(force_fundamental, p);
  step.channel_phasors.assign(phasors.begin(), phasors.begin() + num_channels);
  // The applied force, harmonic by harmonic: the recorded signal times
  // the amplifier's gain at that harmonic's frequency (g is real, so the
  // phase reference is the same).
  step.force_phasors = phasors[0];
  if (scenario_.BaseExcitation()) step.force_phasors.setZero();
  if (scenario_.VoltageDrive())
    for (Eigen::Index k = 0; k < step.force_phasors.size(); ++k)
      step.force_phasors(k) *= scenario_.amplifier.Gain_N_per_V(k * step.frequency_hz, first_natural_hz_);
  step.hidden_displacement_phasors.assign(phasors.begin() + num_channels, phasors.begin() + num_channels + num_hidden);
  step.support_rotation_phasors = phasors[num_channels + num_hidden];
  step.support_moment_phasors = phasors[num_channels + num_hidden + 1];
  return step;
}

}  // namespace beamid::hb
