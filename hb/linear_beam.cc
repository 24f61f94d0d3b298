#include "hb/linear_beam.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "hb/internal/beam_mesh.h"
#include "hb/matched_modal_loss.h"
#include "hb/option_checks.h"

namespace beamid::hb {
namespace {

constexpr double kNodeMergeTolerance_m = 1e-9;

std::shared_ptr<const BeamMesh> MakeMesh(const LinearBeamModel& model, double force_position_m,
                                         const LinearBeamOptions& options) {
  const double length = model.beam.length_m;
  auto inside = [&](double x, const std::string& what) {
    if (!(x >= 0.0 && x <= length))
      throw std::invalid_argument(what + " at " + std::to_string(x) + " m lies outside the beam [0, " +
                                  std::to_string(length) + "] m");
  };
  inside(force_position_m, "the force position");
  std::vector<double> nodes = {0.0, force_position_m, length};
  for (const auto& mass : model.attachments.point_masses) {
    inside(mass.position_m, "a point mass");
    if (!(mass.mass_kg >= 0.0)) throw std::invalid_argument("a point mass must be >= 0 kg");
    nodes.push_back(mass.position_m);
  }
  std::sort(nodes.begin(), nodes.end());
  std::vector<double> unique;
  for (double x : nodes)
    if (unique.empty() || x - unique.back() > kNodeMergeTolerance_m) unique.push_back(x);
  unique.back() = length;  // a node merged into L must sit at L exactly
  const double omega_max = 2.0 * std::numbers::pi * options.max_frequency_hz;
  const double lambda_max =
      std::pow(model.beam.MassPerLength_kg_m() * omega_max * omega_max / model.beam.BendingStiffness_Nm2(), 0.25);
  constexpr double kMaxLambdaTimesLength = 12.0;
  std::vector<double> refined = {0.0};
  for (std::size_t i = 1; i < unique.size(); ++i) {
    const double gap = unique[i] - unique[i - 1];
    const int pieces = std::max(1, static_cast<int>(std::ceil(gap * lambda_max / kMaxLambdaTimesLength)));
    for (int p = 1; p <= pieces; ++p) refined.push_back(p == pieces ? unique[i] : unique[i - 1] + gap * p / pieces);
  }
  auto mesh = std::make_shared<BeamMesh>();
  mesh->node_positions_m = std::move(refined);
  mesh->bending_stiffness_Nm2 = model.beam.BendingStiffness_Nm2();
  mesh->loss_factor = model.beam.loss_factor;
  mesh->rayleigh_mass_1_s = model.beam.rayleigh_mass_1_s;
  mesh->rayleigh_stiffness_s = model.beam.rayleigh_stiffness_s;
  mesh->mass_per_length_kg_m = model.beam.MassPerLength_kg_m();
  return mesh;
}

int NodeAt(const BeamMesh& mesh, double position_m) {
  for (int i = 0; i < mesh.num_nodes(); ++i)
    if (std::abs(mesh.node_positions_m[i] - position_m) <= kNodeMergeTolerance_m) return i;
  throw std::logic_error("no mesh node at " + std::to_string(position_m) + " m");
}

struct SupportTerms {
  bool support_spring = true;  // add k1 + iωc at θ(L)
  bool undamped = false;       // drop c and the beam's damping (natural frequencies)
};

// Global dynamic stiffness [y_0, θ_0, y_1, θ_1, …] with the attachments, before constraints.
Eigen::MatrixXcd Assemble(const BeamMesh& mesh, const LinearBeamModel& model, double omega, SupportTerms terms) {
  const int n = mesh.num_nodes();
  Eigen::MatrixXcd k = Eigen::MatrixXcd::Zero(2 * n, 2 * n);
  BeamMesh undamped_mesh;
  if (terms.undamped) {
    undamped_mesh.bending_stiffness_Nm2 = mesh.bending_stiffness_Nm2;
    undamped_mesh.mass_per_length_kg_m = mesh.mass_per_length_kg_m;
  }
  const BeamMesh& material = terms.undamped ? undamped_mesh : mesh;
  const Complex ei = material.ComplexBendingStiffness(omega);
  const Complex mu = material.Lambda4(omega);
  for (int e = 0; e + 1 < n; ++e) {
    const double length = mesh.node_positions_m[e + 1] - mesh.node_positions_m[e];
    k.block<4, 4>(2 * e, 2 * e) += SegmentDynamicStiffness(mu, ei, length);
  }
  const auto& a = model.attachments;
  if (std::isfinite(a.clamp_rotational_stiffness_Nm_rad)) k(1, 1) += a.clamp_rotational_stiffness_Nm_rad;
  if (std::isfinite(a.support_translational_stiffness_N_m))
    k(2 * (n - 1), 2 * (n - 1)) += a.support_translational_stiffness_N_m;
  for (const auto& mass : a.point_masses) {
    const int node = NodeAt(mesh, mass.position_m);
    k(2 * node, 2 * node) -= material.Inertia(mass.mass_kg, omega);
  }
  if (terms.support_spring) {
    const double damping = terms.undamped ? 0.0 : model.support_damping_Nms_rad;
    k(2 * n - 1, 2 * n - 1) += Complex(model.support_stiffness_Nm_rad, omega * damping);
  }
  return k;
}

// Global indices of the unconstrained DOFs: y(0) = 0 always; θ(0) = 0 for a
// rigid clamp; y(L) = 0 for a rigid support.
std::vector<int> FreeDofs(const BeamMesh& mesh, const LinearBeamModel& model, bool include_support_rotation) {
  const int n = mesh.num_nodes();
  std::vector<int> free;
  for (int dof = 0; dof < 2 * n; ++dof) {
    if (dof == 0) continue;
    if (dof == 1 && !std::isfinite(model.attachments.clamp_rotational_stiffness_Nm_rad)) continue;
    if (dof == 2 * (n - 1) && !std::isfinite(model.attachments.support_translational_stiffness_N_m)) continue;
    if (dof == 2 * n - 1 && !include_support_rotation) continue;
    free.push_back(dof);
  }
  return free;
}

Eigen::MatrixXcd Select(const Eigen::MatrixXcd& k, const std::vector<int>& rows, const std::vector<int>& cols) {
  Eigen::MatrixXcd out(rows.size(), cols.size());
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t j = 0; j < cols.size(); ++j) out(i, j) = k(rows[i], cols[j]);
  return out;
}

// Clamped–clamped natural frequencies of one segment below ω (Wittrick–Williams J0).
int SegmentModesBelow(double z) {
  const int j = static_cast<int>(std::floor(z / std::numbers::pi));
  const double sign = (1.0 - std::cos(z) * std::cosh(z)) >= 0.0 ? 1.0 : -1.0;
  const double parity = (j % 2 == 0) ? 1.0 : -1.0;
  return j - static_cast<int>(std::lround((1.0 - parity * sign) / 2.0));
}

}  // namespace

Complex BeamDeflection::Evaluate(double position_m, int derivative) const {
  const int e = mesh_->SegmentOf(position_m);
  const double x0 = mesh_->node_positions_m[e];
  const double length = mesh_->node_positions_m[e + 1] - x0;
  return SegmentInterior(mesh_->Lambda4(omega_rad_s_), length, nodal_.segment<4>(2 * e), position_m - x0,
                         derivative);
}

Complex BeamDeflection::Displacement_m(double position_m) const { return Evaluate(position_m, 0); }
Complex BeamDeflection::Slope_rad(double position_m) const { return Evaluate(position_m, 1); }
Complex BeamDeflection::SupportRotation_rad() const { return nodal_[nodal_.size() - 1]; }

void LinearBeamOptions::Validate() const {
  option_checks::RequirePositive("LinearBeamOptions.max_frequency_hz", max_frequency_hz);
}

LinearBeam::LinearBeam(const LinearBeamModel& model, double force_position_m, const LinearBeamOptions& options)
    : model_(model), force_position_m_(force_position_m) {
  options.Validate();
  model_.beam.Validate();
  if (!(model.support_stiffness_Nm_rad >= 0.0) || !(model.support_damping_Nms_rad >= 0.0))
    throw std::invalid_argument("the support stiffness k1 and damping c must be >= 0");
  if (!(model.attachments.clamp_rotational_stiffness_Nm_rad > 0.0) ||
      !(model.attachments.support_translational_stiffness_N_m > 0.0))
    throw std::invalid_argument("clamp and support spring stiffnesses must be > 0 (infinite = rigid)");
  mesh_ = MakeMesh(model_, force_position_m, options);
  if (model_.beam.modal_loss_factor > 0.0)
    matched_modal_loss_ = std::make_shared<const MatchedModalLoss>(model_, force_position_m, options);
}

std::vector<double> LinearBeam::NaturalFrequencies_rad_s(int count) const {
  const std::vector<int> free = FreeDofs(*mesh_, model_, true);
  // J(ω): the number of natural frequencies below ω.
  auto modes_below = [&](double omega) {
    const Eigen::MatrixXd k = Select(Assemble(*mesh_, model_, omega, {.undamped = true}), free, free).real();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(k, Eigen::EigenvaluesOnly);
    int count_below = static_cast<int>((solver.eigenvalues().array() < 0.0).count());
    const double lambda = std::pow(mesh_->mass_per_length_kg_m * omega * omega / mesh_->bending_stiffness_Nm2, 0.25);
    for (int e = 0; e + 1 < mesh_->num_nodes(); ++e)
      count_below += SegmentModesBelow(lambda * (mesh_->node_positions_m[e + 1] - mesh_->node_positions_m[e]));
    return count_below;
  };
  double high = 1.0;
  while (modes_below(high) < count) high *= 2.0;
  std::vector<double> frequencies;
  for (int mode = 1; mode <= count; ++mode) {
    double low = frequencies.empty() ? 0.0 : frequencies.back();
    double up = high;
    while (up - low > 1e-13 * up) {
      const double mid = 0.5 * (low + up);
      (modes_below(mid) >= mode ? up : low) = mid;
    }
    frequencies.push_back(0.5 * (low + up));
  }
  return frequencies;
}

BeamDeflection LinearBeam::ModeShape(int index) const {
  const double omega = NaturalFrequencies_rad_s(index + 1).back();
  const std::vector<int> free = FreeDofs(*mesh_, model_, true);
  const Eigen::MatrixXd k = Select(Assemble(*mesh_, model_, omega, {.undamped = true}), free, free).real();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(k);
  Eigen::Index smallest = 0;
  solver.eigenvalues().cwiseAbs().minCoeff(&smallest);
  BeamDeflection shape;
  shape.mesh_ = mesh_;
  shape.omega_rad_s_ = omega;
  shape.nodal_ = Eigen::VectorXcd::Zero(2 * mesh_->num_nodes());
  for (std::size_t i = 0; i < free.size(); ++i) shape.nodal_[free[i]] = solver.eigenvectors()(i, smallest);
  // Scale to max |w| = 1, positive there.
  Complex peak = 0.0;
  constexpr int kSamples = 600;
  for (int i = 0; i <= kSamples; ++i) {
    const Complex w = shape.Displacement_m(model_.beam.length_m * i / kSamples);
    if (std::abs(w) > std::abs(peak)) peak = w;
  }
  shape.nodal_ /= peak;
  shape.nodal_ = shape.nodal_.real().cast<Complex>();
  return shape;
}

BeamDeflection LinearBeam::RespondToForce(double omega_rad_s) const {
  const std::vector<int> free = FreeDofs(*mesh_, model_, true);
  Eigen::VectorXcd load = Eigen::VectorXcd::Zero(free.size());
  const int force_dof = 2 * NodeAt(*mesh_, force_position_m_);
  for (std::size_t i = 0; i < free.size(); ++i)
    if (free[i] == force_dof) load[i] = 1.0;
  BeamDeflection out;
  out.mesh_ = mesh_;
  out.omega_rad_s_ = omega_rad_s;
  out.nodal_ = Eigen::VectorXcd::Zero(2 * mesh_->num_nodes());
  if (load.isZero()) return out;  // a force on a rigid constraint moves nothing
  const Eigen::VectorXcd u = Select(Assemble(*mesh_, model_, omega_rad_s, {}), free, free).partialPivLu().solve(load);
  for (std::size_t i = 0; i < free.size(); ++i) out.nodal_[free[i]] = u[i];
  return out;
}

BeamDeflection LinearBeam::RespondToSupportMoment(double omega_rad_s) const {
  const std::vector<int> free = FreeDofs(*mesh_, model_, true);
  Eigen::VectorXcd load = Eigen::VectorXcd::Zero(free.size());
  load[free.size() - 1] = 1.0;  // θ(L) is the last free DOF
  const Eigen::VectorXcd u = Select(Assemble(*mesh_, model_, omega_rad_s, {}), free, free).partialPivLu().solve(load);
  BeamDeflection out;
  out.mesh_ = mesh_;
  out.omega_rad_s_ = omega_rad_s;
  out.nodal_ = Eigen::VectorXcd::Zero(2 * mesh_->num_nodes());
  for (std::size_t i = 0; i < free.size(); ++i) out.nodal_[free[i]] = u[i];
  return out;
}

LinearBeam::Condensed LinearBeam::CondenseOnSupportRotation(double omega_rad_s,
                                                            const std::vector<double>& output_positions_m) const {
  const std::vector<int> retained = FreeDofs(*mesh_, model_, false);
  const int theta_dof = 2 * mesh_->num_nodes() - 1;
  const Eigen::MatrixXcd k = Assemble(*mesh_, model_, omega_rad_s, {.support_spring = false});
  const Eigen::MatrixXcd k_rr = Select(k, retained, retained);
  const Eigen::VectorXcd k_r_theta = Select(k, retained, {theta_dof});
  Eigen::MatrixXcd rhs = Eigen::MatrixXcd::Zero(retained.size(), 2);
  const int force_dof = 2 * NodeAt(*mesh_, force_position_m_);
  for (std::size_t i = 0; i < retained.size(); ++i)
    if (retained[i] == force_dof) rhs(i, 0) = 1.0;
  rhs.col(1) = -k_r_theta;
  const Eigen::MatrixXcd u = k_rr.partialPivLu().solve(rhs);  // col 0: unit force; col 1: unit θ(L)

  Condensed out;
  out.rotational_stiffness_Nm_rad = k(theta_dof, theta_dof) + (k_r_theta.transpose() * u.col(1)).value();
  out.blocked_moment_per_force_m = -(k_r_theta.transpose() * u.col(0)).value();
  BeamDeflection per_force, per_rotation;
  per_force.mesh_ = per_rotation.mesh_ = mesh_;
  per_force.omega_rad_s_ = per_rotation.omega_rad_s_ = omega_rad_s;
  per_force.nodal_ = per_rotation.nodal_ = Eigen::VectorXcd::Zero(2 * mesh_->num_nodes());
  for (std::size_t i = 0; i < retained.size(); ++i) {
    per_force.nodal_[retained[i]] = u(i, 0);
    per_rotation.nodal_[retained[i]] = u(i, 1);
  }
  per_rotation.nodal_[theta_dof] = 1.0;
  const auto count = static_cast<Eigen::Index>(output_positions_m.size());
  out.displacement_per_force_m_N.resize(count);
  out.displacement_per_rotation_m.resize(count);
  for (Eigen::Index i = 0; i < count; ++i) {
    out.displacement_per_force_m_N[i] = per_force.Displacement_m(output_positions_m[i]);
    out.displacement_per_rotation_m[i] = per_rotation.Displacement_m(output_positions_m[i]);
  }
  return out;
}

}  // namespace beamid::hb
