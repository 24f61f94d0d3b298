#include "signal/uff58_export.h"

#include <algorithm>
#include <complex>
#include <optional>

#include <fmt/core.h>

#include "hb/version.h"
#include "signal/input_error.h"
#include "signal/uff58.h"

namespace beamid::signal {
namespace {

using namespace uff58;

// Record 9/10's specific data type of a quantity (unknown: none fits).
int DataType(Quantity q) {
  switch (q) {
    case Quantity::kDisplacement: return kDisplacementType;
    case Quantity::kVelocity: return kVelocityType;
    case Quantity::kAcceleration: return kAccelerationType;
    case Quantity::kForce: return kExcitationForceType;
    default: return kUnknownType;
  }
}

// An A80 ID line or A10/A20 label: printable ASCII (a fixed-width field
// counts bytes), no longer than its field.
std::string Field(const std::string& text, std::size_t width) {
  std::string field = text.substr(0, std::min(text.size(), width));
  for (char& c : field)
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) > 0x7e) c = '_';
  return field;
}

struct Function {
  std::string name;
  int function_type = kSpectrum;
  int node = 1;
  Quantity ordinate = Quantity::kForce;
  std::optional<Quantity> denominator;
};

std::string Axis(int data_type, const std::string& label, std::string_view unit) {
  return fmt::format("{:10d}{:5d}{:5d}{:5d} {:<20} {:<20}\n", data_type, 0, 0, 0, Field(label, 20),
                     Field(std::string(unit), 20));
}

std::string Dataset(const FirstHarmonicLevel& level, const Function& f) {
  std::string text = "    -1\n    58\n";
  text += fmt::format("{:<80}\n{:<80}\n{:<80}\n{:<80}\n{:<80}\n", Field(f.name, 80),
                      Field("level " + level.label, 80), "NONE", Field("beamid " + std::string(kVersion), 80), "NONE");
  // Record 6: Format(2(I5,I10),2(1X,A10,I10,I4)); the reference is the excitation's node 1, +Z.
  text += fmt::format("{:5d}{:10d}{:5d}{:10d} {:<10}{:10d}{:4d} {:<10}{:10d}{:4d}\n", f.function_type, 0, 0, 0,
                      Field(f.name, 10), f.node, 3, "excitation", 1, 3);
  // Record 7: Format(3I10,3E13.5).
  text += fmt::format("{:10d}{:10d}{:10d}{:13.5E}{:13.5E}{:13.5E}\n", kComplexDouble, level.points.size(),
                      kUnevenSpacing, 0.0, 0.0, 0.0);
  text += Axis(kFrequencyType, "Frequency", "Hz");
  text += Axis(DataType(f.ordinate), std::string(QuantityName(f.ordinate)), SiUnit(f.ordinate));
  text += f.denominator ? Axis(DataType(*f.denominator), std::string(QuantityName(*f.denominator)),
                               SiUnit(*f.denominator))
                        : Axis(0, "NONE", "NONE");
  text += Axis(0, "NONE", "NONE");
  for (const FirstHarmonicPoint& p : level.points) {
    const std::complex<double> value =
        f.function_type == kFrequencyResponse ? p.response.value / p.force.value : p.force.value;
    text += fmt::format("{:20.12E}{:20.12E}{:20.12E}\n", p.frequency_hz, value.real(), value.imag());
  }
  return text + "    -1\n";
}

}  // namespace

std::string Uff58LevelText(const FirstHarmonicLevel& level) {
  // A base-excited level holds −A_b and the motion relative to the base
  // (signal/first_harmonic_level.h), which no other tool would read as its spectra.
  if (level.excitation_quantity == Quantity::kBaseAcceleration)
    throw InputError(level.source, "", "level '" + level.label + "' is base-excited: its phasors are relative to "
                                       "the base, not the spectra a universal file holds",
                     "export the recordings' own spectra from the acquisition system");
  std::string text = "    -1\n   151\n";
  // Dataset 151: model name, description, the writing program; no dates (the text does not depend on the clock).
  text += fmt::format("{:<80}\n{:<80}\n{:<80}\n{:<80}\n{:<80}\n{:<80}\n{:<80}\n", Field("beamid level " + level.label, 80),
                      Field(level.source, 80), Field("beamid " + std::string(kVersion), 80), "", "beamid", "", "beamid");
  text += "    -1\n";
  const std::string excitation_name = std::string(QuantityName(level.excitation_quantity));
  text += Dataset(level, {.name = excitation_name, .function_type = kSpectrum, .node = 1,
                          .ordinate = level.excitation_quantity});
  text += Dataset(level, {.name = level.channel.empty() ? "response" : level.channel,
                          .function_type = kFrequencyResponse, .node = 2, .ordinate = level.response_quantity,
                          .denominator = level.excitation_quantity});
  return text;
}

}  // namespace beamid::signal
