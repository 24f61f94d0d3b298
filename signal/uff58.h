// Universal File Format dataset 58 ("function at nodal DOF"), the export of
// common acquisition systems, in its ASCII form (58) and its binary form
// (58b: an ASCII header line giving byte order, float format and byte count,
// the 11 ASCII header records, then the raw values). Only what a stepped-sine
// recording needs is accepted (docs/uff58.md): real, evenly spaced ordinates
// (record 7: ordinate type 2 = single or 4 = double precision, abscissa
// spacing 1), of function type 0 (general) or 1 (time response); x_n =
// x_min + n·Δx with x_min and Δx from record 7. Other datasets of the file
// (151, 164, 2411, …) are skipped. Every problem is an InputError naming the
// file, the dataset (by its ID line 1) and what to fix.
// For first-harmonic results (signal/uff58_level.h) the reader also takes
// what a frequency-domain system exports: spectra and frequency response
// functions (any function type), complex ordinates (record 7 type 5 single,
// 6 double: real and imaginary part per point) and unevenly spaced abscissae
// (spacing 0: each point's abscissa before its ordinate).
#pragma once

#include <array>
#include <complex>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "signal/quantity.h"

namespace beamid::signal {

struct Uff58Axis {
  int data_type = 0;          // specific data type: 0 unknown, 1 general, 8 displacement, 11 velocity,
                              // 12 acceleration, 13 excitation force, 9 reaction force, 17 time, …
  std::string label;          // axis label (A20), trimmed
  std::string unit;           // axis units label (A20), trimmed; may be empty
};

// The numbers of the format that beamid's readers and writer use.
namespace uff58 {
// Record 6, function type.
inline constexpr int kTimeResponse = 1, kFrequencyResponse = 4, kSpectrum = 12;
// Record 7, ordinate data type and abscissa spacing.
inline constexpr int kRealSingle = 2, kRealDouble = 4, kComplexSingle = 5, kComplexDouble = 6;
inline constexpr int kUnevenSpacing = 0, kEvenSpacing = 1;
// Records 8-11, specific data type.
inline constexpr int kUnknownType = 0, kGeneralType = 1, kDisplacementType = 8, kReactionForceType = 9,
                     kVelocityType = 11, kAccelerationType = 12, kExcitationForceType = 13, kTimeType = 17,
                     kFrequencyType = 18;
}  // namespace uff58

// What a reading accepts: the time histories of a step's recording, or the
// spectra and frequency responses of a stepped-sine result.
enum class Uff58Functions { kTimeHistories, kFrequencyFunctions };

struct Uff58Dataset {
  int number = 0;                       // 1-based position among the file's datasets 58, for messages
  bool binary = false;                  // 58b
  std::array<std::string, 5> id_lines;  // ID lines 1..5, trailing blanks removed
  int function_type = 0;                // record 6 field 1: 0 general, 1 time response, 4 FRF, …
  std::string response_entity;          // record 6 field 5 (A10), trimmed
  int response_node = 0;                // record 6 field 6
  int response_direction = 0;           // record 6 field 7: 0 scalar, ±1..3 ±X/Y/Z, ±4..6 ±RX/RY/RZ
  std::string reference_entity;         // record 6 field 8 (A10), trimmed
  int reference_node = 0;               // record 6 field 9
  int reference_direction = 0;          // record 6 field 10
  int ordinate_type = 0;                // record 7 field 1: 2 real single, 4 real double, 5/6 complex
  int num_points = 0;                   // record 7 field 2
  bool uneven = false;                  // record 7 field 3 = 0
  double abscissa_start = 0.0;          // record 7 field 4, x_min
  double abscissa_step = 0.0;           // record 7 field 5, Δx
  Uff58Axis abscissa;                   // record 8
  Uff58Axis ordinate;                   // record 9 (numerator)
  Uff58Axis denominator;                // record 10 (a frequency response's reference)
  std::vector<double> values;           // record 12, as written (file units): for a time history the samples

  bool Complex() const;
  // Point i's abscissa (even: x_min + i·Δx) and ordinate (imaginary part 0 when real).
  double Abscissa(int i) const;
  std::complex<double> Ordinate(int i) const;

  // "dataset 3 ('acc1')": how messages name the dataset.
  std::string Describe() const;
  // "12:+Z": the response node and direction as a channel name.
  std::string NodeDirection() const;
};

// All datasets 58/58b of a universal file held in memory (source names it
// in messages). Throws InputError when the file is not a universal file,
// holds no dataset 58, or a dataset 58 is truncated, malformed or outside the
// accepted subset.
std::vector<Uff58Dataset> ParseUff58(std::string_view bytes, const std::string& source,
                                     Uff58Functions functions = Uff58Functions::kTimeHistories);

std::vector<Uff58Dataset> ReadUff58(const std::filesystem::path& file,
                                    Uff58Functions functions = Uff58Functions::kTimeHistories);

// The quantity a record 8..11 specific data type names (8 displacement, 11
// velocity, 12 acceleration, 9/13 force); nullopt for the others.
std::optional<Quantity> Uff58Quantity(int data_type);

// The spellings of acquisition systems for the units the campaign format
// accepts ("m/s2", "m/s**2", "m/s²" in UTF-8 or Latin-1, "G", "mm/sec", …)
// in the campaign's words (signal/quantity.h); blanks removed, any other
// label as it is.
std::string Uff58Unit(const std::string& unit);

// True for the extensions of universal files: .uff, .unv (any case).
bool IsUniversalFile(const std::filesystem::path& file);

}  // namespace beamid::signal
