#include "hb/matched_modal_loss.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <numbers>

namespace beamid::hb {
namespace {

// Half-width of the central difference in Ω²/ω_j²: the residue's error is
// O(ε²) from the other modes and (δω_j/(εω_j))² from ω_j's error (1e-13).
constexpr double kResidueStep = 1e-6;
// |d_j| below this share of ω_j² (a harmonic on a θ-free natural frequency
// of an undamped beam to 13 digits) is held there, so that 1/d_j stays finite.
constexpr double kSmallestModalStiffness = 1e-13;
// Undamped beams whose modes are kept; a fit meets one or a few (a modulus
// or clamp candidate moves it at every iteration), so the cache is emptied
// when full rather than ordered by use.
constexpr std::size_t kCachedBeams = 32;

// Everything the undamped beam's modes depend on. A field added to these
// structs must be added here: the sizes stop the build until it is.
static_assert(sizeof(BeamProperties) == 9 * sizeof(double), "extend UndampedKey with the new beam field");
static_assert(sizeof(PointMass) == 2 * sizeof(double), "extend UndampedKey with the new point-mass field");
static_assert(sizeof(LinearAttachments) == 2 * sizeof(double) + sizeof(std::vector<PointMass>),
              "extend UndampedKey with the new attachment field");
std::vector<double> UndampedKey(const LinearBeamModel& model, double force_position_m, double max_frequency_hz) {
  const BeamProperties& b = model.beam;
  const LinearAttachments& a = model.attachments;
  std::vector<double> key{b.length_m, b.width_m, b.thickness_m, b.youngs_modulus_Pa, b.density_kg_m3,
                          a.clamp_rotational_stiffness_Nm_rad, a.support_translational_stiffness_N_m,
                          force_position_m, max_frequency_hz};
  for (const PointMass& m : a.point_masses) {
    key.push_back(m.position_m);
    key.push_back(m.mass_kg);
  }
  return key;
}

MatchedModalLoss::Modes ComputeModes(const LinearBeamModel& model, double force_position_m,
                                     const LinearBeamOptions& band) {
  LinearBeamModel undamped = model;
  undamped.beam.loss_factor = undamped.beam.modal_loss_factor = 0.0;
  undamped.beam.rayleigh_mass_1_s = undamped.beam.rayleigh_stiffness_s = 0.0;
  undamped.support_stiffness_Nm_rad = undamped.support_damping_Nms_rad = 0.0;
  const LinearBeam beam(undamped, force_position_m, band);
  const double omega_max = 2.0 * std::numbers::pi * band.max_frequency_hz;
  int count = 8;
  std::vector<double> omega = beam.NaturalFrequencies_rad_s(count);
  while (omega.back() < omega_max) omega = beam.NaturalFrequencies_rad_s(count *= 2);
  MatchedModalLoss::Modes modes;
  for (double w : omega) {
    if (w > omega_max) break;
    BeamDeflection below = beam.RespondToSupportMoment(w * std::sqrt(1.0 - kResidueStep));
    BeamDeflection above = beam.RespondToSupportMoment(w * std::sqrt(1.0 + kResidueStep));
    const double half_step = 0.5 * kResidueStep * w * w;
    // φ_j'(L)² = (ε·ω_j²/2)·(θ₋ − θ₊).
    const double rotation_squared =
        half_step * (below.SupportRotation_rad() - above.SupportRotation_rad()).real();
    // A mode that leaves θ at rest is not driven by the support and is not
    // seen there; none of a beam pinned at x = L.
    if (!(rotation_squared > 0.0)) continue;
    modes.omega_rad_s.push_back(w);
    modes.below.push_back(std::move(below));
    modes.above.push_back(std::move(above));
    modes.rotation.push_back(std::sqrt(rotation_squared));
    modes.scale.push_back(half_step / modes.rotation.back());
  }
  return modes;
}

}  // namespace

MatchedModalLoss::MatchedModalLoss(const LinearBeamModel& model, double force_position_m,
                                   const LinearBeamOptions& options)
    : modal_loss_factor_(model.beam.modal_loss_factor),
      loss_factor_(model.beam.loss_factor),
      rayleigh_mass_1_s_(model.beam.rayleigh_mass_1_s),
      rayleigh_stiffness_s_(model.beam.rayleigh_stiffness_s),
      force_position_m_(force_position_m) {
  // The band of the modes is the default one at least, whatever band the
  // caller needs exact: a mode far above the harmonics still takes its share
  // η_m·kω/ω_j of their quasi-static response (the modes below 470 Hz alone
  // put the 4th harmonic's receptances of the paper's beam 6 % off).
  const LinearBeamOptions band{.max_frequency_hz = std::max(options.max_frequency_hz, LinearBeamOptions{}.max_frequency_hz)};
  static std::mutex mutex;
  static std::map<std::vector<double>, std::shared_ptr<const Modes>> cache;
  std::vector<double> key = UndampedKey(model, force_position_m, band.max_frequency_hz);
  {
    const std::lock_guard<std::mutex> lock(mutex);
    const auto found = cache.find(key);
    if (found != cache.end()) {
      modes_ = found->second;
      return;
    }
  }
  modes_ = std::make_shared<const Modes>(ComputeModes(model, force_position_m, band));
  const std::lock_guard<std::mutex> lock(mutex);
  if (cache.size() >= kCachedBeams) cache.clear();
  cache.emplace(std::move(key), modes_);
}

MatchedModalLoss::ModeValues MatchedModalLoss::At(const std::vector<double>& positions_m) const {
  const int n = num_modes();
  const auto count = static_cast<Eigen::Index>(positions_m.size());
  ModeValues v{.rotation = Eigen::VectorXd(n), .at_force = Eigen::VectorXd(n), .at_positions = Eigen::MatrixXd(n, count)};
  for (int j = 0; j < n; ++j) {
    auto mode = [&](double x) {
      return modes_->scale[j] * (modes_->below[j].Displacement_m(x) - modes_->above[j].Displacement_m(x)).real();
    };
    v.rotation[j] = modes_->rotation[j];
    v.at_force[j] = mode(force_position_m_);
    for (Eigen::Index i = 0; i < count; ++i) v.at_positions(j, i) = mode(positions_m[static_cast<std::size_t>(i)]);
  }
  return v;
}

void MatchedModalLoss::Correct(const ModeValues& modes, double omega_rad_s, int harmonic,
                               LinearBeam::Condensed* condensed) const {
  const double frequency = harmonic * omega_rad_s;
  const Complex i(0.0, 1.0);
  Complex s_tt = 0.0, s_tf = 0.0;
  const auto count = modes.at_positions.cols();
  Eigen::VectorXcd s_xt = Eigen::VectorXcd::Zero(count), s_xf = Eigen::VectorXcd::Zero(count);
  for (int j = 0; j < num_modes(); ++j) {
    const double w = modes_->omega_rad_s[j], w2 = w * w;
    const double driving_harmonic = std::max(1.0, std::round(w / omega_rad_s));
    Complex d = w2 * (1.0 + i * (loss_factor_ + rayleigh_stiffness_s_ * frequency)) - frequency * frequency +
                i * rayleigh_mass_1_s_ * frequency;
    if (std::abs(d) < kSmallestModalStiffness * w2) d = kSmallestModalStiffness * w2;
    const Complex delta = 1.0 / (d + i * modal_loss_factor_ * w2 * static_cast<double>(harmonic) / driving_harmonic) - 1.0 / d;
    const double rotation = modes.rotation[j], force = modes.at_force[j];
    s_tt += rotation * rotation * delta;
    s_tf += rotation * force * delta;
    for (Eigen::Index x = 0; x < count; ++x) {
      s_xt[x] += modes.at_positions(j, x) * rotation * delta;
      s_xf[x] += modes.at_positions(j, x) * force * delta;
    }
  }
  LinearBeam::Condensed& c = *condensed;
  const Complex dd = c.rotational_stiffness_Nm_rad, bb = c.blocked_moment_per_force_m;
  const Complex denominator = 1.0 + dd * s_tt;
  for (Eigen::Index x = 0; x < count; ++x) {
    const Complex a = c.displacement_per_force_m_N[x], b = c.displacement_per_rotation_m[x];
    c.displacement_per_force_m_N[x] =
        a + s_xf[x] + (b * bb * s_tt - b * s_tf - bb * s_xt[x] - dd * s_xt[x] * s_tf) / denominator;
    c.displacement_per_rotation_m[x] = (b + dd * s_xt[x]) / denominator;
  }
  c.rotational_stiffness_Nm_rad = dd / denominator;
  c.blocked_moment_per_force_m = (bb + dd * s_tf) / denominator;
}

}  // namespace beamid::hb
