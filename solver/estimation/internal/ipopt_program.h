// Internal: runs Ipopt on a FitProblem. The TNLP adapter lives in
// the .cc file, so no Ipopt type leaks out of solver/.
#pragma once

#include <string>

#include <Eigen/Core>

#include "solver/estimation/fit_problem.h"

namespace beamid::solver::internal {

struct IpoptOptions {
  int max_iterations = 200;  // a good start needs < 30; a start on another branch of the response stalls
  double tolerance = 1e-8;          // Ipopt's scaled NLP error
  double constraint_tolerance = 1e-10;  // on the residual of the balance [N·m]
  // CPU time limit of one run [s] (0: none): a refit whose start lies on
  // another branch of the response can crawl for minutes.
  double max_cpu_seconds = 0.0;
  int print_level = 0;              // 0 silent … 5 Ipopt's default output
  bool derivative_test = false;     // Ipopt's second-order derivative checker (development)

  // Throws InputError naming the field, its value and the allowed range.
  void Validate() const;
};

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
