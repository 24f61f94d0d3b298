// How a fit problem shows its parameters to the optimiser: each scaled by
// its typical size, x_j = p_j / s_j with s_j = ParameterBounds::typical, so
// that every variable is ~1 whatever its unit (k3 ~ 1e5 N·m/rad³ beside
// η ~ 1e-4), and the physical bounds l_j ≤ p_j ≤ u_j become l_j/s_j ≤ x_j ≤
// u_j/s_j. The parameters come first in x; the states after them are
// unbounded here (each problem scales its own states).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "solver/estimation/model_structure.h"

namespace beamid::solver {

class ParameterScaling {
 public:
  ParameterScaling() = default;
  explicit ParameterScaling(std::vector<ParameterBounds> bounds) : bounds_(std::move(bounds)) {
    for (const auto& b : bounds_) scale_.push_back(b.typical);
  }

  int size() const { return static_cast<int>(scale_.size()); }
  double scale(int j) const { return scale_[j]; }
  const std::vector<double>& scales() const { return scale_; }
  const std::vector<ParameterBounds>& bounds() const { return bounds_; }

  // The physical parameters of x (its first size() entries).
  std::vector<double> Physical(const Eigen::VectorXd& x) const {
    std::vector<double> p(scale_.size());
    for (int j = 0; j < size(); ++j) p[j] = x[j] * scale_[j];
    return p;
  }
  // Sets x's first size() entries to these physical parameters.
  void SetScaled(const std::vector<double>& parameters, Eigen::VectorXd* x) const {
    for (int j = 0; j < size(); ++j) (*x)[j] = parameters[j] / scale_[j];
  }
  // Bounds of all num_variables variables: the parameters' scaled, the
  // states' none (±1e20, Ipopt's infinity).
  void Bounds(int num_variables, Eigen::VectorXd* lower, Eigen::VectorXd* upper) const {
    lower->setConstant(num_variables, -1e20);
    upper->setConstant(num_variables, 1e20);
    for (int j = 0; j < size(); ++j) {
      (*lower)[j] = bounds_[j].lower / scale_[j];
      (*upper)[j] = bounds_[j].upper / scale_[j];
    }
  }

 private:
  std::vector<ParameterBounds> bounds_;
  std::vector<double> scale_;
};

}  // namespace beamid::solver
