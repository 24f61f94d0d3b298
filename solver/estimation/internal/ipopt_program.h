// Internal: runs Ipopt on a FitProblem. The TNLP adapter lives in
// the .cc file, so no Ipopt type leaks out of solver/.
#pragma once

#include <string>

#include <Eigen/Core>

#include "solver/estimation/fit_problem.h"
#include "solver/estimation/ipopt_options.h"

namespace beamid::solver::internal {

using solver::IpoptOptions;

struct IpoptOutcome {
  Eigen::VectorXd x;
  bool success = false;      // solved to tolerance (or acceptable level)
  int status = 0;            // Ipopt's ApplicationReturnStatus
  std::string status_text;
  int iterations = 0;
  double objective = 0.0;
};

// Ipopt's ApplicationReturnStatus in words.
std::string IpoptStatusText(int status);

IpoptOutcome RunIpopt(FitProblem& problem, const Eigen::VectorXd& start, const IpoptOptions& options);

}  // namespace beamid::solver::internal
