// Files of a PhasorSet (signal/phasor_set.h), written by `beamid extract` and
// read by solver/:
//  - JSON, format "beamid-phasors/1": campaign, campaign_sha256 (the
//    campaign's content hash, signal/campaign_hash.h; absent in files of an
//    older beamid, read as ""), num_harmonics, and per step its file, level,
//    nominal_frequency_Hz, frequency_Hz, frequency_std_Hz, quality, and per
//    channel (force first) quantity, SI unit, position_m, mean, thd, snr_dB,
//    noise_rms and harmonics [{k, re, im, amplitude, phase_rad, std_re,
//    std_im, correlation, std_amplitude, std_phase_rad}] — amplitude, phase
//    and their stds are redundant conveniences; reading uses re, im, std_re,
//    std_im and correlation. Numbers are written with round-trip precision,
//    keys in the declaration's order; notes, unsettled and skipped_steps only when
//    there are some.
//  - CSV view: one row per step, channel and harmonic with the same fields.
// One declaration of the fields (hb/json_schema.h) is the writer and the
// reader: reading refuses a missing or unknown key, a number outside its
// range (PhasorSetFields lists them), and throws InputError naming the
// file and the field's path.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "hb/json_schema.h"
#include "signal/phasor_set.h"

namespace beamid::signal {

inline constexpr std::string_view kPhasorFormat = "beamid-phasors/1";

// The fields of the JSON file: path, type, unit, range (docs/formats.md).
std::vector<schema::FieldDoc> PhasorSetFields();

std::string PhasorSetToJson(const PhasorSet& set);
PhasorSet PhasorSetFromJson(std::string_view json_text, const std::string& source);
std::string PhasorSetToCsv(const PhasorSet& set);

// File versions; throw InputError when the file cannot be written or read.
void WritePhasorSetJson(const PhasorSet& set, const std::filesystem::path& file);
PhasorSet ReadPhasorSetJson(const std::filesystem::path& file);
void WritePhasorSetCsv(const PhasorSet& set, const std::filesystem::path& file);

}  // namespace beamid::signal
