// Prediction from an identified model (result.json of `beamid identify`):
// for every step of the fit, the steady state of the model that was
// identified, driven by that step's measured force, evaluated at any
// position x, with its uncertainty propagated from the parameter covariance,
//     Cov(Y) = J·Cov(p)·Jᵀ,   J = ∂Y/∂p by central differences (each
//     perturbed model solved again),
// and the steady-state time history over one period with a 95 % band.
// The model is the one the parameters were fitted with (their values absorb
// that model's own error): its family (solver/estimation/model_family.h)
// solves it at every step on the branch of the step's fitted state.
#pragma once

#include <complex>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "hb/harmonic_balance.h"
#include "solver/estimation/model_family.h"
#include "solver/estimation/model_structure.h"
#include "solver/estimation/result_file.h"

namespace beamid::solver {

struct IdentifiedStep {
  std::string level;
  std::string file;
  double omega_rad_s = 0.0;
  Eigen::VectorXcd force_N;
  Eigen::VectorXcd state;  // the family's state at the fit (ModelFamily::StateName)
};

struct IdentifiedModel {
  const ModelFamily* family = &HarmonicBalanceFamily();
  hb::LinearBeamModel beam;  // nominal beam with sensor masses, before linear parameters
  double force_position_m = 0.0;
  int num_harmonics = 5;     // H of the family's model
  ModelStructure structure;  // values = identified
  Eigen::MatrixXd covariance;
  std::vector<IdentifiedStep> steps;
};

// Reads result.json (solver/estimation/result_io.h); throws InputError
// naming the file, the field and what to fix.
IdentifiedModel ReadIdentifiedModel(const std::filesystem::path& result_file);
// The model of a result; throws InputError naming the field of a model it
// cannot rebuild (another law, an unknown linear parameter).
IdentifiedModel ToIdentifiedModel(const ResultFile& result);

// The largest |state[entry]| over the identified steps (0 where no step's
// state has that entry): the range of amplitudes the test reached.
double LargestStateAmplitude(const IdentifiedModel& model, int entry);

// The harmonic balance of the identified model with parameters p (structure
// order; empty: the identified values), as PredictAt solves it.
hb::HarmonicBalance IdentifiedHarmonicBalance(const IdentifiedModel& model, const std::vector<double>& p = {});

struct PredictedStep {
  std::string level;
  std::string file;
  double frequency_hz = 0.0;
  Eigen::VectorXcd displacement_m;       // Y_0..Y_H at x
  Eigen::VectorXd std_real_m, std_imag_m;  // standard uncertainty of Re, Im
  Eigen::VectorXd time_s;                // one period
  Eigen::VectorXd acceleration_m_s2;     // steady-state history at x
  Eigen::VectorXd acceleration_std_m_s2; // its standard uncertainty
  bool converged = true;
};

std::vector<PredictedStep> PredictAt(const IdentifiedModel& model, double position_m, int samples_per_period = 64);

}  // namespace beamid::solver
