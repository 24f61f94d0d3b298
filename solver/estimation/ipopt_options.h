// The optimiser's settings for one run of a fit (Ipopt, the interior-point
// method that solves every fit problem): iteration and time limits and its
// tolerances. Public because identify and diagnose expose them; the Ipopt
// types themselves stay inside solver/estimation/internal/ipopt_program.cc.
#pragma once

namespace beamid::solver {

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

}  // namespace beamid::solver
