#include "solver/estimation/model_options.h"

#include "hb/option_checks.h"

namespace beamid::solver {

void ModelOptions::Validate() const {
  using namespace option_checks;
  RequireInRange("ModelOptions.num_harmonics", num_harmonics, 1, kMaxHarmonics);
  // Fewer than 2H + 2 samples cannot carry H harmonics (Nyquist).
  if (num_time_samples != 0)
    RequireAtLeast("ModelOptions.num_time_samples (0: automatic)", num_time_samples, 2 * num_harmonics + 2);
  // The readers' range of η (docs/architecture.md).
  if (!(beam_loss_factor >= 0.0 && beam_loss_factor < 1.0))
    Refuse("ModelOptions.beam_loss_factor", FormatValue(beam_loss_factor), "in [0, 1)");
}

}  // namespace beamid::solver
