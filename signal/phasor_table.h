// Reads one level of a stepped-sine test from a first-harmonic table, the CSV
// that acquisition systems export (docs/phasor-table.md): one row per step,
// columns frequency, excitation amplitude, response amplitude and the
// response's phase relative to the excitation, optionally their standard
// uncertainties. The excitation is a force unless its column says otherwise,
// by name ("voltage [V]", "base_acceleration [g]") or, for a column named
// "excitation" or "input", by unit (V, mV: a drive voltage; m/s^2, g: the
// base's acceleration); a base-excited level's response is an accelerometer's,
// taken relative to the base as signal/first_harmonic_level.h says.
//
// The response phasor is X = |X|·e^{iφ} with the force as the phase
// reference (F real, positive), as everywhere in beamid
// (signal/phasor_set.h). Uncertainties given in polar form (σ_|X|, σ_φ) become
// the Re/Im covariance R·diag(σ_|X|², |X|²σ_φ²)·Rᵀ, R the rotation by φ.
//
// The text goes through signal/table_reader.h, like a recording: ',' ';' or
// tab separators, a decimal comma with ';' or tab (detected: the whole file
// then uses it), a BOM, CRLF, quoted headers, comment lines ('#', '%', '//')
// and blank lines. Units in brackets "force [N]", parentheses
// "phase (deg)" or as a suffix "frequency_Hz", "acc_m_s2"; phase in rad or
// deg; the response an acceleration (m/s^2, g), velocity (m/s, mm/s) or
// displacement (m, mm), its quantity named by the column or implied by the
// unit. An export's metadata block and units row, and columns named by the
// user (an export's "X-Data [Hz]"), come as PhasorTableOptions.
// Anything wrong throws InputError
// naming the file and the column (and row) to fix.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "signal/first_harmonic_level.h"
#include "signal/table_reader.h"

namespace beamid::signal {

// Columns named by the user instead of recognised by name: each a header
// text as written (with or without its unit, case ignored) or a 1-based
// column number; empty: recognised by name. A mapped response or excitation
// takes its quantity from its name when that says one, else from its unit.
struct PhasorColumnMapping {
  std::string frequency, excitation, response, phase;
  bool Empty() const;
  // Takes "ROLE=COLUMN" (ROLE frequency, excitation, response or phase), as
  // the command line's --column gives it; throws InputError naming it.
  void Assign(std::string_view assignment);
};

// What the text alone cannot tell: an export's metadata block and units row
// (signal/table_reader.h), and columns whose names are an export's own.
struct PhasorTableOptions {
  TableLayout layout;
  PhasorColumnMapping columns;
};

// `source` names the text in messages; the level's label is `label`.
FirstHarmonicLevel ParsePhasorTable(std::string_view text, const std::string& source, const std::string& label,
                                    const PhasorTableOptions& options = {});

// The level's label is the file name without its extension.
FirstHarmonicLevel ReadPhasorTable(const std::filesystem::path& file, const PhasorTableOptions& options = {});

}  // namespace beamid::signal
