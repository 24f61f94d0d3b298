#include "solver/estimation/ipopt_options.h"

#include "hb/option_checks.h"

namespace beamid::solver {

void IpoptOptions::Validate() const {
  using namespace option_checks;
  RequireAtLeast("IpoptOptions.max_iterations", max_iterations, 1);
  RequirePositive("IpoptOptions.tolerance", tolerance);
  RequirePositive("IpoptOptions.constraint_tolerance", constraint_tolerance);
  RequireNonNegative("IpoptOptions.max_cpu_seconds (0: no limit)", max_cpu_seconds);
  // Ipopt's own range of print_level.
  RequireInRange("IpoptOptions.print_level", print_level, 0, 12);
}


}  // namespace beamid::solver
