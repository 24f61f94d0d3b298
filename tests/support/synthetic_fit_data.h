// A small FitData for tests that need a model's shape, not a fit: the paper
// beam, acc1 and acc2, three steps around the first resonance at a level
// where the response is single-valued (so re-solving follows one branch),
// made-up measurements with unit-free whitening.
#pragma once

#include <cmath>
#include <numbers>
#include <string>

#include "solver/estimation/fit_data.h"
#include "tests/support/paper_setup.h"

namespace beamid::testing {

inline solver::FitData SyntheticFitData() {
  using Complex = std::complex<double>;
  solver::FitData data;
  data.beam = PaperBeam();
  data.force_position_m = kForcePosition_m;
  data.channels = {{.channel = "acc1", .position_m = 0.1}, {.channel = "acc2", .position_m = 0.3}};
  data.num_fit_harmonics = 3;
  data.levels = {"low"};
  int index = 0;
  for (double frequency_hz : {53.4, 54.1, 54.9}) {
    solver::FitStep step{.level = "low", .file = "step" + std::to_string(index++) + ".csv",
                         .omega_rad_s = 2 * std::numbers::pi * frequency_hz};
    step.force_N = Eigen::VectorXcd::Zero(6);
    step.force_N[1] = std::polar(0.5, 0.3);
    step.force_N[3] = Complex(0.004, -0.002);
    step.measured.resize(2, 3);
    for (int c = 0; c < 2; ++c)
      for (int k = 0; k < 3; ++k) step.measured(c, k) = Complex(1.0 + c, -2.0 + k) * std::pow(0.02, k);
    step.whitening.assign(2, std::vector<Eigen::Matrix2d>(3, Eigen::Matrix2d::Identity() / 0.01));
    step.std_amplitude = Eigen::MatrixXd::Constant(2, 3, 0.01);
    data.steps.push_back(step);
  }
  return data;
}

}  // namespace beamid::testing
