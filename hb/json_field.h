// Reading a JSON file that beamid wrote (result, diagnosis, prediction,
// measured backbone): every value carries the path of its field
// ("candidates[2].fit.chi_square"), so that every complaint is an InputError
// naming the file, the field and the fix; a key the format does not have is
// refused (a misspelling or another file, not something to skip); null reads
// as NaN, since JSON has none. The files are parsed as nlohmann::ordered_json.
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "hb/errors.h"
#include "hb/strict_json.h"

namespace beamid {

class JsonField {
 public:
  // format names the file's format in "is not a field of <format> here";
  // fix is what a complaint tells the user to do unless it says otherwise.
  // source, format and fix must outlive the fields (they are the reader's).
  JsonField(const nlohmann::ordered_json& value, std::string path, const std::string& source, std::string_view format,
            std::string_view fix)
      : value_(value), path_(std::move(path)), source_(source), format_(format), fix_(fix) {}
  // A nlohmann::json would be converted into a temporary that the field
  // would outlive: parse the files as ordered_json (beamid writes its keys
  // in the order of its structs).
  JsonField(const nlohmann::json&, std::string, const std::string&, std::string_view, std::string_view) = delete;

  const nlohmann::ordered_json& json() const { return value_; }

  // This field and those below it describe a channel of a test: every
  // complaint names it too (InputError::channel), since a list's index
  // ("sensors[2]") is not how the engineer knows the sensor.
  JsonField Named(std::string channel) const {
    JsonField named = *this;
    named.channel_ = std::move(channel);
    return named;
  }
  const std::string& channel() const { return channel_; }

  [[noreturn]] void Fail(const std::string& problem, std::string_view fix = {}) const {
    // The file travels apart too (InputError::file), for a caller that acts on it.
    throw InputError(source_, channel_, "field \"" + path_ + "\" " + problem, std::string(fix.empty() ? fix_ : fix));
  }

  // A complaint about a field below this one ("curves[0].points[1]"), which
  // a rule between fields found.
  [[noreturn]] void FailBelow(const std::string& sub_path, const std::string& problem) const {
    JsonField(value_, path_.empty() ? sub_path : path_ + (sub_path.starts_with('[') ? "" : ".") + sub_path, source_,
              format_, fix_)
        .Named(channel_)
        .Fail(problem);
  }

  // A key the format does not have is a misspelling or another file, not
  // something to skip.
  void OnlyKeys(std::initializer_list<std::string_view> known) const {
    for (const auto& item : Object().value_.items()) {
      if (std::find(known.begin(), known.end(), item.key()) != known.end()) continue;
      std::string list;
      for (std::string_view k : known) list += (list.empty() ? "" : ", ") + std::string(k);
      Child(item.value(), item.key())
          .Fail("is not a field of " + std::string(format_) + " here",
                "correct its name or remove it (the fields here: " + list + ")");
    }
  }

  bool Has(const std::string& key) const { return Object().value_.contains(key); }
  JsonField At(const std::string& key) const {
    const nlohmann::ordered_json& object = Object().value_;
    const std::string path = Child(key);
    const auto it = object.find(key);
    if (it == object.end()) JsonField(object, path, source_, format_, fix_).Named(channel_).Fail("is missing");
    return JsonField(*it, path, source_, format_, fix_).Named(channel_);
  }
  JsonField At(std::size_t i) const {
    return JsonField(value_[i], path_ + "[" + std::to_string(i) + "]", source_, format_, fix_).Named(channel_);
  }
  std::size_t Size() const { return Array().value_.size(); }
  // An array's elements, and an object's members in the file's order.
  std::vector<JsonField> Elements() const {
    std::vector<JsonField> out;
    for (std::size_t i = 0; i < Size(); ++i) out.push_back(At(i));
    return out;
  }
  std::vector<std::pair<std::string, JsonField>> Members() const {
    std::vector<std::pair<std::string, JsonField>> out;
    for (const auto& item : Object().value_.items()) out.emplace_back(item.key(), Child(item.value(), item.key()));
    return out;
  }

  const JsonField& Object() const {
    if (!value_.is_object()) Expected("an object");
    return *this;
  }
  const JsonField& Array() const {
    if (!value_.is_array()) Expected("an array");
    return *this;
  }
  // null is a NaN (JSON has none).
  double Number() const {
    if (value_.is_null()) return std::numeric_limits<double>::quiet_NaN();
    if (!value_.is_number()) Expected("a number (or null)");
    return value_.get<double>();
  }
  // A number that the format never leaves out: null is refused.
  double NumberNotNull() const {
    if (!value_.is_number()) Expected("a number");
    return value_.get<double>();
  }
  int Integer() const {
    if (value_.is_number_unsigned()) {
      if (value_.get<std::uint64_t>() <= static_cast<std::uint64_t>(std::numeric_limits<int>::max()))
        return value_.get<int>();
    } else if (value_.is_number_integer()) {
      const std::int64_t v = value_.get<std::int64_t>();
      if (v >= std::numeric_limits<int>::min() && v <= std::numeric_limits<int>::max()) return static_cast<int>(v);
    }
    Expected("an integer");
  }
  bool Boolean() const {
    if (!value_.is_boolean()) Expected("true or false");
    return value_.get<bool>();
  }
  std::string String() const {
    if (!value_.is_string()) Expected("a string");
    return value_.get<std::string>();
  }
  std::vector<double> Numbers() const {
    std::vector<double> out;
    for (std::size_t i = 0; i < Size(); ++i) out.push_back(At(i).Number());
    return out;
  }
  std::vector<std::string> Strings() const {
    std::vector<std::string> out;
    for (std::size_t i = 0; i < Size(); ++i) out.push_back(At(i).String());
    return out;
  }
  std::complex<double> Phasor() const {
    if (Size() != 2) Fail("must be [re, im], not " + std::to_string(Size()) + " numbers");
    return {At(0).Number(), At(1).Number()};
  }

  // The ranges of what beamid writes (null, NaN, passes: the writer's "no
  // number"): a value outside them was not written by beamid, and would
  // reach a computation as if it were measured.
  // An uncertainty, a χ², a duration: >= 0.
  double NonNegative() const {
    const double v = Number();
    if (v < 0.0) Fail("= " + Shown(v) + " is negative (it is never below 0)");
    return v;
  }
  // A frequency: > 0.
  double Positive() const {
    const double v = Number();
    if (v <= 0.0) Fail("= " + Shown(v) + " is not positive");
    return v;
  }
  // A probability: in [0, 1].
  double Probability() const {
    const double v = Number();
    if (v < 0.0 || v > 1.0) Fail("= " + Shown(v) + " lies outside [0, 1] (a probability)");
    return v;
  }
  // A count: an integer in [0, max].
  int Count(int max = 1'000'000) const {
    const int v = Integer();
    if (v < 0 || v > max) Fail("= " + std::to_string(v) + " lies outside 0.." + std::to_string(max));
    return v;
  }

  // Shorthands for a member of this object.
  double NonNegative(const std::string& key) const { return At(key).NonNegative(); }
  double Positive(const std::string& key) const { return At(key).Positive(); }
  double Probability(const std::string& key) const { return At(key).Probability(); }
  int Count(const std::string& key, int max = 1'000'000) const { return At(key).Count(max); }
  double Number(const std::string& key) const { return At(key).Number(); }
  int Integer(const std::string& key) const { return At(key).Integer(); }
  bool Boolean(const std::string& key) const { return At(key).Boolean(); }
  std::string String(const std::string& key) const { return At(key).String(); }

 private:
  static std::string Shown(double v) {
    std::ostringstream out;
    out << v;
    return out.str();
  }
  std::string Child(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  JsonField Child(const nlohmann::ordered_json& value, const std::string& key) const {
    return JsonField(value, Child(key), source_, format_, fix_).Named(channel_);
  }

  [[noreturn]] void Expected(const std::string& what) const {
    const std::string type = value_.type_name();
    const bool vowel = type.find_first_of("aeiou") == 0;
    Fail("must be " + what + ", not " + (value_.is_null() ? "null" : (vowel ? "an " : "a ") + type));
  }

  const nlohmann::ordered_json& value_;
  std::string path_;
  const std::string& source_;
  std::string_view format_;
  std::string_view fix_;
  std::string channel_;
};

// The text of a file as one JSON object, parsed strictly (hb/strict_json.h:
// a key written twice, a number beyond double range, too deep or too large a
// text are refused), or InputError "<source>: not valid JSON (…)" or "<source>:
// not a <what> (a JSON array, not an object)", each with "Fix: <fix>".
inline nlohmann::ordered_json ParseJsonObject(const std::string& text, const std::string& source,
                                              std::string_view what, std::string_view fix) {
  nlohmann::ordered_json json = ParseStrictJson(text, source, fix);
  if (!json.is_object())
    throw InputError(source + ": not a " + std::string(what) + " (a JSON " + json.type_name() +
                     ", not an object). Fix: " + std::string(fix));
  return json;
}

// Worker records (a fit run in another process, handed back as text): every
// double exact. Finite ones are JSON numbers (nlohmann writes the digits that
// read back to the same double); the others, which JSON lacks, by name.
inline nlohmann::json ExactJsonNumber(double v) {
  if (std::isfinite(v)) return v;
  return std::isnan(v) ? "nan" : v > 0 ? "inf" : "-inf";
}
// Throws std::runtime_error (or a nlohmann exception) on anything
// ExactJsonNumber did not write.
inline double ExactNumberFromJson(const nlohmann::json& v) {
  if (v.is_number()) return v.get<double>();
  const std::string& name = v.get_ref<const std::string&>();
  if (name == "nan") return std::numeric_limits<double>::quiet_NaN();
  if (name == "inf") return std::numeric_limits<double>::infinity();
  if (name == "-inf") return -std::numeric_limits<double>::infinity();
  throw std::runtime_error("not a number: " + name);
}
inline nlohmann::json ExactJsonNumbers(const std::vector<double>& values) {
  nlohmann::json out = nlohmann::json::array();
  for (double v : values) out.push_back(ExactJsonNumber(v));
  return out;
}
inline std::vector<double> ExactNumbersFromJson(const nlohmann::json& array) {
  std::vector<double> out;
  for (const auto& v : array.get_ref<const nlohmann::json::array_t&>()) out.push_back(ExactNumberFromJson(v));
  return out;
}

}  // namespace beamid
