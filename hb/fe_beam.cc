#include "hb/fe_beam.h"

#include "hb/errors.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Eigenvalues>

#include "hb/option_checks.h"

namespace beamid::hb {
namespace {

constexpr double kNodeMatch_m = 1e-9;

std::vector<double> MeshNodes(double length_m, std::span<const double> required_m, int min_elements) {
  std::vector<double> anchors{0.0, length_m};
  for (double x : required_m) {
    if (!(x >= -kNodeMatch_m && x <= length_m + kNodeMatch_m))
      throw std::invalid_argument("finite-element beam: position " + std::to_string(x) +
                                  " m lies outside the beam [0, " + std::to_string(length_m) + "] m");
    anchors.push_back(std::clamp(x, 0.0, length_m));
  }
  std::sort(anchors.begin(), anchors.end());
  anchors.erase(std::unique(anchors.begin(), anchors.end(),
                            [](double a, double b) { return b - a < kNodeMatch_m; }),
                anchors.end());
  anchors.back() = length_m;  // a requested position within kNodeMatch_m of L is L
  const double max_element_m = length_m / std::max(min_elements, 1);
  std::vector<double> nodes{0.0};
  for (size_t i = 1; i < anchors.size(); ++i) {
    const double span_m = anchors[i] - anchors[i - 1];
    const int pieces = std::max(1, static_cast<int>(std::ceil(span_m / max_element_m - 1e-9)));
    for (int p = 1; p < pieces; ++p) nodes.push_back(anchors[i - 1] + span_m * p / pieces);
    nodes.push_back(anchors[i]);
  }
  return nodes;
}

}  // namespace

// The scenario reader's limit (mesh.min_elements): beyond it a step of the
// simulator costs seconds without changing the first modes.
void FeBeamOptions::Validate() const {
  option_checks::RequireInRange("FeBeamOptions.min_elements", min_elements, 1, 2000);
}

FeBeam::FeBeam(const BeamProperties& beam, const LinearAttachments& attachments,
               std::span<const double> required_nodes_m, const FeBeamOptions& options) {
  options.Validate();
  beam.Validate();
  const bool clamp_spring = std::isfinite(attachments.clamp_rotational_stiffness_Nm_rad);
  const bool support_spring = std::isfinite(attachments.support_translational_stiffness_N_m);
  if (clamp_spring && !(attachments.clamp_rotational_stiffness_Nm_rad > 0.0))
    throw std::invalid_argument("attachments: clamp_rotational_stiffness_Nm_rad must be positive");
  if (support_spring && !(attachments.support_translational_stiffness_N_m > 0.0))
    throw std::invalid_argument("attachments: support_translational_stiffness_N_m must be positive");

  std::vector<double> required(required_nodes_m.begin(), required_nodes_m.end());
  for (const PointMass& m : attachments.point_masses) {
    if (!(m.mass_kg >= 0.0)) throw std::invalid_argument("attachments: a point mass must be >= 0 kg");
    required.push_back(m.position_m);
  }
  node_positions_m_ = MeshNodes(beam.length_m, required, options.min_elements);
  const int num_nodes = static_cast<int>(node_positions_m_.size());

  // Free-DOF numbering: full DOF 2i is y_i, 2i+1 is y'_i.
  std::vector<int> free_index(2 * num_nodes, kConstrained);
  int next = 0;
  for (int dof = 0; dof < 2 * num_nodes; ++dof) {
    const bool constrained = dof == 0 || (dof == 1 && !clamp_spring) ||
                             (dof == 2 * (num_nodes - 1) && !support_spring);
    if (!constrained) free_index[dof] = next++;
  }
  deflection_dof_.resize(num_nodes);
  for (int i = 0; i < num_nodes; ++i) deflection_dof_[i] = free_index[2 * i];
  support_rotation_dof_ = free_index[2 * num_nodes - 1];

  stiffness_ = Eigen::MatrixXd::Zero(next, next);
  mass_ = Eigen::MatrixXd::Zero(next, next);
  const double ei = beam.BendingStiffness_Nm2();
  const double rho_a = beam.MassPerLength_kg_m();
  for (int e = 0; e + 1 < num_nodes; ++e) {
    const double l = node_positions_m_[e + 1] - node_positions_m_[e];
    Eigen::Matrix4d ke;
    ke << 12, 6 * l, -12, 6 * l, 6 * l, 4 * l * l, -6 * l, 2 * l * l, -12, -6 * l, 12, -6 * l, 6 * l,
        2 * l * l, -6 * l, 4 * l * l;
    ke *= ei / (l * l * l);
    Eigen::Matrix4d me;
    me << 156, 22 * l, 54, -13 * l, 22 * l, 4 * l * l, 13 * l, -3 * l * l, 54, 13 * l, 156, -22 * l,
        -13 * l, -3 * l * l, -22 * l, 4 * l * l;
    me *= rho_a * l / 420.0;
    for (int a = 0; a < 4; ++a) {
      const int ia = free_index[2 * e + a];
      if (ia == kConstrained) continue;
      for (int b = 0; b < 4; ++b) {
        const int ib = free_index[2 * e + b];
        if (ib == kConstrained) continue;
        stiffness_(ia, ib) += ke(a, b);
        mass_(ia, ib) += me(a, b);
      }
    }
  }
  if (clamp_spring) stiffness_(free_index[1], free_index[1]) += attachments.clamp_rotational_stiffness_Nm_rad;
  if (support_spring) {
    const int dof = free_index[2 * (num_nodes - 1)];
    stiffness_(dof, dof) += attachments.support_translational_stiffness_N_m;
  }
  for (const PointMass& m : attachments.point_masses) {
    const int dof = deflection_dof_[NodeIndex(m.position_m)];
    if (dof != kConstrained) mass_(dof, dof) += m.mass_kg;
  }
}

int FeBeam::NodeIndex(double position_m) const {
  const auto it = std::lower_bound(node_positions_m_.begin(), node_positions_m_.end(), position_m - kNodeMatch_m);
  if (it == node_positions_m_.end() || std::abs(*it - position_m) > kNodeMatch_m)
    throw std::invalid_argument("finite-element beam: position " + std::to_string(position_m) +
                                " m is not a node of the mesh");
  return static_cast<int>(it - node_positions_m_.begin());
}

int FeBeam::DeflectionDof(double position_m) const { return deflection_dof_[NodeIndex(position_m)]; }

std::vector<double> FeBeam::NaturalFrequencies_rad_s(int count, double support_stiffness_Nm_rad) const {
  Eigen::MatrixXd k = stiffness_;
  k(support_rotation_dof_, support_rotation_dof_) += support_stiffness_Nm_rad;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(k, mass_, Eigen::EigenvaluesOnly);
  if (solver.info() != Eigen::Success) throw NumericalError("finite-element beam: eigen-solution failed");
  std::vector<double> omegas;
  for (int i = 0; i < std::min<int>(count, NumDofs()); ++i) omegas.push_back(std::sqrt(std::max(0.0, solver.eigenvalues()(i))));
  return omegas;
}

}  // namespace beamid::hb
