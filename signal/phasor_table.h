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
// unit. Anything wrong throws InputError
// naming the file and the column (and row) to fix.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "signal/first_harmonic_level.h"

namespace beamid::signal {

// `source` names the text in messages; the level's label is `label`.
FirstHarmonicLevel ParsePhasorTable(std::string_view text, const std::string& source, const std::string& label);

// The level's label is the file name without its extension.
FirstHarmonicLevel ReadPhasorTable(const std::filesystem::path& file);

}  // namespace beamid::signal
