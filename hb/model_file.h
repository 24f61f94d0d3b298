// The physical model of the beam and its support as read from a JSON model
// file (format in the README, "Model files"): the beam, the support law, the
// linear attachments, where the force acts and where the sensors sit.
// A simulation scenario (docs/simulator.md) is also a valid model file: its
// test-running fields (levels, timing, noise, …) are accepted and ignored.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hb/beam_properties.h"
#include "hb/linear_attachments.h"
#include "hb/support_law.h"

namespace beamid::hb {

struct ModelSensor {
  std::string channel;
  double position_m = 0.0;
};

struct ModelFile {
  std::string name;
  BeamProperties beam;
  PolynomialSupportLaw::Coefficients polynomial;
  std::optional<JenkinsSupportLaw::Parameters_> jenkins;
  double one_sided_stiffness_Nm_rad = 0.0;  // OneSidedStiffnessLaw in parallel when non-zero
  LinearAttachments attachments;
  double force_position_m = 0.570;
  std::vector<ModelSensor> sensors;

  // The polynomial law, with the Jenkins element in parallel if given.
  std::unique_ptr<SupportLaw> MakeSupportLaw() const;
};

// Throws std::invalid_argument naming the file, the field and what to fix.
ModelFile ParseModelFile(const std::string& json_text, const std::string& source);
ModelFile ReadModelFile(const std::filesystem::path& file);

}  // namespace beamid::hb
