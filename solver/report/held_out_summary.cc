#include "solver/report/held_out_summary.h"

#include <fmt/core.h>

namespace beamid::solver {
namespace {

// Keyed on the count, not the value: files written before the worst error
// of an unresolved harmonic was NaN hold 0 there.
std::string Harmonic(int measurable_steps, int steps, double worst, const char* harmonic) {
  if (measurable_steps == 0)
    return fmt::format("nothing measurable on the {} harmonic (none of the {} steps resolves its error: all lie below "
                       "the noise floor)",
                       harmonic, steps);
  return fmt::format("worst error {:.2f} % on the {} harmonic (over the {} of {} steps that resolve it)", 100.0 * worst,
                     harmonic, measurable_steps, steps);
}

}  // namespace

std::string HeldOutSummary(const HeldOutChannel& channel) {
  return HeldOutSummary(static_cast<int>(channel.steps.size()), channel.worst_h1_relative_error,
                        channel.measurable_steps_h1, channel.worst_h3_relative_error, channel.measurable_steps_h3);
}

std::string HeldOutSummary(int steps, double worst_h1_relative_error, int measurable_steps_h1,
                           double worst_h3_relative_error, int measurable_steps_h3) {
  return Harmonic(measurable_steps_h1, steps, worst_h1_relative_error, "1st") + "; " +
         Harmonic(measurable_steps_h3, steps, worst_h3_relative_error, "3rd");
}

}  // namespace beamid::solver
