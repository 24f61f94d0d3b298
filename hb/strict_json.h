// The one way beamid parses JSON text, for every file format it reads
// (model, scenario, campaign, phasors, result, diagnosis, prediction, frc,
// backbone, measured backbone) and the records its worker processes hand
// back. Stricter than JSON itself, because a lenient parse hides mistakes
// that the readers after it cannot see:
//   - a key written twice in one object, at any depth, is refused (nlohmann,
//     like most parsers, keeps the last: a model with "length_m" 0.6 then
//     6.0 would silently be a 6 m beam);
//   - a number beyond double's range (1e400) is refused as out of range;
//   - nesting, the members of one object and the values of the whole text
//     are bounded (StrictJsonLimits), so that a hostile or broken file is
//     refused before it exhausts memory or time.
// Every refusal is an InputError "<source>: <problem> (at <path>). Fix:
// <fix>, see <format_doc>", and a syntax error names its line and column.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace beamid {

struct StrictJsonLimits {
  // Deeper than any beamid format (a diagnosis nests about 8 levels).
  int max_depth = 64;
  // One object: beamid's objects hold fields and channel names, never
  // thousands of keys (and an ordered object finds a key by a linear
  // search, so that a huge one costs quadratic time).
  std::size_t max_object_members = 10'000;
  // All values of the text (numbers, strings, arrays, objects, ...): a
  // large phasors or frc file holds a few hundred thousand; 5 million cost
  // a few hundred MB.
  std::size_t max_values = 5'000'000;
};

// Parses `text`, read from `source` (a path, named in every error), whose
// format `format_doc` describes (named in every fix). Json is
// nlohmann::ordered_json (the readers of the files beamid writes, which keep
// the file's order) or nlohmann::json.
template <typename Json = nlohmann::ordered_json>
Json ParseStrictJson(std::string_view text, const std::string& source, std::string_view format_doc,
                     const StrictJsonLimits& limits = {});

extern template nlohmann::ordered_json ParseStrictJson<nlohmann::ordered_json>(std::string_view, const std::string&,
                                                                               std::string_view,
                                                                               const StrictJsonLimits&);
extern template nlohmann::json ParseStrictJson<nlohmann::json>(std::string_view, const std::string&, std::string_view,
                                                               const StrictJsonLimits&);

}  // namespace beamid
