// The physical model of the beam and its support as read from a JSON model
// file (format "beamid-model/1", described in docs/model-file.md):
// the beam, the support law, the linear attachments, where the force acts
// and where the sensors sit. The format is declared once (hb/json_schema.h);
// that declaration is its reader, its writer and its field table. A
// simulation scenario (docs/simulator.md, "beamid-scenario/1") is also a
// valid model file: its test-running fields (levels, timing, noise, …) are
// accepted and ignored.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hb/beam_properties.h"
#include "hb/json_schema.h"
#include "hb/linear_attachments.h"
#include "hb/support_law.h"

namespace beamid::hb {

struct ModelSensor {
  std::string channel;
  double position_m = 0.0;
  // A scenario's sensor mass as the file gives it; the reader moves it to
  // ModelFile::attachments.point_masses (the beam carries it) and leaves 0.
  double mass_kg = 0.0;
};

struct ModelFile {
  std::string name = "beam model";
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

// The value of the optional "format" key. A file without it (every file
// written before the key) reads as this version; so does a scenario's
// "beamid-scenario/1"; another value is refused.
inline constexpr std::string_view kModelFileFormat = "beamid-model/1";

// Throws InputError (a std::invalid_argument) naming the file, the field and
// what to fix; "beamid_version" is accepted and ignored.
ModelFile ParseModelFile(const std::string& json_text, const std::string& source);
ModelFile ReadModelFile(const std::filesystem::path& file);

// The fields of the JSON file: path, type, unit, range (docs/formats.md).
std::vector<schema::FieldDoc> ModelFileFields();

// Every field the reader reads, with "format" and "beamid_version", so that
// reading the text gives the same ModelFile back. The sensors' masses are
// among the point masses (where the reader put them), so the sensors are
// written without "mass_kg"; a rigid attachment (infinite stiffness) is left
// out, as JSON has no infinity.
std::string ModelFileToJson(const ModelFile& model);
// Atomically (hb/text_file.h): the old file or the new one, never half.
void WriteModelFile(const std::filesystem::path& path, const ModelFile& model);

}  // namespace beamid::hb
