// One declaration per file format drives its writer, its reader and its
// documentation. A format declares the fields of each of its structs once,
// in a function found by argument-dependent lookup:
//
//   void Describe(auto& io, schema::Like<FrcCurve> auto& curve) {
//     io.Number("force_N", curve.force_N, "N", schema::Positive());
//     io.Integer("turning_points", curve.turning_points, 0, 1'000'000);
//     io.List("points", curve.points, 1'000'000);
//   }
//
// and the same lines then
//   - write the struct as JSON (schema::ToJson; the struct is const there),
//   - read it back (schema::FromJson): every field of the declaration is
//     required unless declared Optional, a key it does not declare is
//     refused, a number outside its range is refused, a list longer than
//     its bound is refused, and every complaint is an InputError naming the
//     file, the field's path ("curves[1].points[3].frequency_Hz") and the
//     fix;
//   - list the fields with their path, type, unit and range
//     (schema::Fields), the table of the format's documentation, so that
//     the documentation cannot drift from the reader.
// Parsing itself is hb/strict_json.h (duplicate keys, depth, sizes).
// A declaration only declares: it may compute from fields already read (a
// count from "harmonics") but keeps no other state, because the reader also
// runs it on a default struct to list an object's keys.
// JSON has no NaN: a number that is not finite is written as null; null
// reads back as NaN only where the declaration allows it (Limits::nullable).
#pragma once

#include <cmath>
#include <complex>
#include <algorithm>
#include <concepts>
#include <functional>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "hb/enum_names.h"
#include "hb/errors.h"
#include "hb/json_field.h"

namespace beamid::schema {

// `T` is U or const U: Describe functions take both (writing reads a const
// struct, reading fills a mutable one).
template <typename T, typename U>
concept Like = std::same_as<std::remove_const_t<T>, U>;

// The range of a number. A value outside it was not written by beamid and
// would reach a computation as if it were measured.
struct Limits {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_open = false;  // min itself excluded
  // null (JSON's only way to say "no number") reads as NaN.
  bool nullable = false;

  constexpr Limits OrNull() const {
    Limits l = *this;
    l.nullable = true;
    return l;
  }
  bool Holds(double v) const {
    if (std::isnan(v)) return nullable;
    return (min_open ? v > min : v >= min) && v <= max;
  }
  // "> 0", "0 .. 1", "any", with "or null".
  std::string Text() const {
    std::string text;
    const bool low = std::isfinite(min), high = std::isfinite(max);
    if (low && high)
      text = fmt::format("{}{} .. {}", min_open ? "> " : "", min, max);
    else if (low)
      text = fmt::format("{} {}", min_open ? ">" : "≥", min);
    else if (high)
      text = fmt::format("≤ {}", max);
    else
      text = "any";
    return nullable ? text + ", or null" : text;
  }
};
constexpr Limits Any() { return {}; }
constexpr Limits Positive() { return {.min = 0.0, .min_open = true}; }
constexpr Limits NonNegative() { return {.min = 0.0}; }
constexpr Limits Probability() { return {.min = 0.0, .max = 1.0}; }
constexpr Limits Between(double min, double max) { return {.min = min, .max = max}; }

// kOmittedWhenEmpty: optional, and the writer leaves it out when it is
// empty (an empty string or list, an optional without value), as files
// written before the field existed lack it.
enum class Presence { kRequired, kOptional, kOmittedWhenEmpty };
constexpr Presence kOptional = Presence::kOptional;
constexpr Presence kOmittedWhenEmpty = Presence::kOmittedWhenEmpty;

template <typename T>
bool IsEmpty(const T& v) {
  if constexpr (requires { v.has_value(); })
    return !v.has_value();
  else if constexpr (requires { v.empty(); })
    return v.empty();
  else
    return false;
}

// One number of a fixed-length array held in a member (Row, Rows): a
// parameter's ci95 [low, high], a position's [position_m, gain].
template <typename T>
struct Column {
  double T::*member;
  std::string_view name;  // in the documentation: "[low, high]"
  std::string_view unit;
  Limits limits = {};
};

// A string field's rule. Text from a file can reach a plot's labels and a
// terminal: a control character is refused everywhere.
enum class TextRule { kAny, kNotEmpty };

// How a format names itself in messages.
struct Format {
  std::string_view tag;   // "beamid-frc/1"
  std::string_view what;  // "frequency response file"
  std::string_view fix;   // what a complaint tells the user to do
};

// How many entries a list holds: at most `max` (a bound on the work a
// file can cause), or exactly a number that an earlier field sets (the
// harmonics + 1 phasors of a point), which `words` names in the documentation.
struct Count {
  Count(std::size_t max_entries) : max(max_entries) {}  // NOLINT: a bare number is "at most"
  static Count Exactly(std::size_t n, std::string_view words) {
    Count c(n);
    c.min = n;
    c.words = words;
    return c;
  }
  std::size_t min = 0;
  std::size_t max;
  std::string_view words;

  std::string Text() const {
    if (!words.empty()) return "exactly " + std::string(words);
    return fmt::format("at most {}", max);
  }
};

// The declaration of T's fields found by argument-dependent lookup; a
// List, Object or Keyed may pass its own (a lambda) when the element's
// fields depend on the enclosing one (a phasor count set by "harmonics").
struct DescribeByLookup {
  template <typename Io, typename T>
  void operator()(Io& io, T& value) const {
    Describe(io, value);
  }
};

// "low, high"; "m, 1"; "any; ≥ 0".
template <typename T, std::size_t N>
std::string ColumnNames(const Column<T> (&columns)[N]) {
  std::string text;
  for (const Column<T>& c : columns) text += (text.empty() ? "" : ", ") + std::string(c.name);
  return text;
}
template <typename T, std::size_t N>
std::string ColumnUnits(const Column<T> (&columns)[N]) {
  std::string text;
  for (const Column<T>& c : columns) text += (text.empty() ? "" : ", ") + std::string(c.unit.empty() ? "–" : c.unit);
  return text;
}
template <typename T, std::size_t N>
std::string ColumnRanges(const Column<T> (&columns)[N]) {
  std::string text;
  for (const Column<T>& c : columns) text += (text.empty() ? "" : "; ") + c.limits.Text();
  return text;
}

// ---- writing ------------------------------------------------------------

class Writer {
 public:
  static constexpr bool kReading = false;
  using Json = nlohmann::ordered_json;

  explicit Writer(Json& out) : out_(out) { out_ = Json::object(); }

  void Constant(std::string_view key, std::string_view value, Presence = Presence::kRequired) {
    Put(key, std::string(value));
  }
  void Number(std::string_view key, const double& v, std::string_view /*unit*/, Limits = {},
              Presence = Presence::kRequired) {
    Put(key, NumberJson(v));
  }
  // Optional: written when it holds a number.
  void Number(std::string_view key, const std::optional<double>& v, std::string_view /*unit*/, Limits = {}) {
    if (v) Put(key, NumberJson(*v));
  }
  // Written for a reader's convenience, computed from other fields, never
  // read back.
  void Derived(std::string_view key, double v, std::string_view /*unit*/) { Put(key, NumberJson(v)); }
  // A text for a reader (a description that is the same in every file).
  void Derived(std::string_view key, std::string_view text) { Put(key, std::string(text)); }
  template <std::integral I>
  void Integer(std::string_view key, const I& v, std::int64_t /*min*/, std::int64_t /*max*/,
               Presence = Presence::kRequired) {
    Put(key, v);
  }
  void Boolean(std::string_view key, const bool& v, Presence = Presence::kRequired) { Put(key, v); }
  void Text(std::string_view key, const std::string& v, TextRule = TextRule::kAny, Presence p = Presence::kRequired) {
    if (!Omitted(v, p)) Put(key, v);
  }
  template <typename E, std::size_t N>
  void Choice(std::string_view key, const E& v, const Name<E> (&names)[N], Presence = Presence::kRequired) {
    for (const Name<E>& n : names)
      if (n.value == v) return Put(key, std::string(n.name));
    throw std::logic_error("schema: a value of field \"" + std::string(key) + "\" has no name");
  }
  void Numbers(std::string_view key, const std::vector<double>& v, std::string_view /*unit*/, Limits, Count count,
               Presence p = Presence::kRequired) {
    if (Omitted(v, p)) return;
    CheckCount(key, v.size(), count);
    Json list = Json::array();
    for (double x : v) list.push_back(NumberJson(x));
    Put(key, std::move(list));
  }
  void Phasors(std::string_view key, const std::vector<std::complex<double>>& v, std::string_view /*unit*/,
               Count count, Presence presence = Presence::kRequired) {
    if (Omitted(v, presence)) return;
    CheckCount(key, v.size(), count);
    Json list = Json::array();
    for (const auto& p : v) list.push_back(Json::array({NumberJson(p.real()), NumberJson(p.imag())}));
    Put(key, std::move(list));
  }
  // One phasor [re, im]; `parts` is the range of re and im.
  void Phasor(std::string_view key, const std::complex<double>& v, std::string_view /*unit*/, Limits /*parts*/ = {},
              Presence = Presence::kRequired) {
    Put(key, Json::array({NumberJson(v.real()), NumberJson(v.imag())}));
  }
  void Phasors(std::string_view key, const Eigen::VectorXcd& v, std::string_view /*unit*/, Limits /*parts*/,
               Count count, Presence = Presence::kRequired) {
    CheckCount(key, static_cast<std::size_t>(v.size()), count);
    Json list = Json::array();
    for (const auto& p : v) list.push_back(Json::array({NumberJson(p.real()), NumberJson(p.imag())}));
    Put(key, std::move(list));
  }
  // A matrix as a list of rows.
  void Matrix(std::string_view key, const Eigen::MatrixXd& m, std::string_view /*unit*/, Limits, Count rows,
              Count columns, Presence = Presence::kRequired) {
    CheckCount(key, static_cast<std::size_t>(m.rows()), rows);
    if (m.rows() > 0) CheckCount(key, static_cast<std::size_t>(m.cols()), columns);
    Json out = Json::array();
    for (Eigen::Index r = 0; r < m.rows(); ++r) {
      Json row = Json::array();
      for (Eigen::Index c = 0; c < m.cols(); ++c) row.push_back(NumberJson(m(r, c)));
      out.push_back(std::move(row));
    }
    Put(key, std::move(out));
  }
  void Texts(std::string_view key, const std::vector<std::string>& v, Count count, TextRule = TextRule::kAny,
             Presence p = Presence::kRequired) {
    if (Omitted(v, p)) return;
    CheckCount(key, v.size(), count);
    Put(key, Json(v));
  }
  template <typename T, typename F = DescribeByLookup>
  void Object(std::string_view key, const T& v, Presence p = Presence::kRequired, F describe = {}) {
    if (!Omitted(v, p)) Put(key, Written(v, describe));
  }
  // An object, or null where the value's `present` member says there is
  // none (an estimate that could not be made).
  template <typename T, typename F = DescribeByLookup>
  void ObjectOrNull(std::string_view key, const T& v, bool T::*present, Presence = Presence::kRequired,
                    F describe = {}) {
    Put(key, v.*present ? Written(v, describe) : Json(nullptr));
  }
  template <typename T, typename F = DescribeByLookup>
  void List(std::string_view key, const std::vector<T>& v, Count count, Presence p = Presence::kRequired,
            F describe = {}) {
    if (Omitted(v, p)) return;
    CheckCount(key, v.size(), count);
    Json list = Json::array();
    for (const T& element : v) list.push_back(Written(element, describe));
    Put(key, std::move(list));
  }
  // An object keyed by a member of each element ({"acc1": {...}, ...}); the
  // element's own declaration leaves that member out.
  template <typename T, typename F = DescribeByLookup>
  void Keyed(std::string_view key, const std::vector<T>& v, std::string T::*name, Count /*count*/,
             Presence p = Presence::kRequired, F describe = {}) {
    if (Omitted(v, p)) return;
    Json object = Json::object();
    for (const T& element : v) object[element.*name] = Written(element, describe);
    Put(key, std::move(object));
  }
  // An object that a file may leave out (std::nullopt): written when it holds a value.
  template <typename T, typename F = DescribeByLookup>
  void Object(std::string_view key, const std::optional<T>& v, Presence = Presence::kOptional, F describe = {}) {
    if (v) Put(key, Written(*v, describe));
  }
  // An object keyed by name ({"acc1": {...}, ...}) held as a map.
  template <typename T, typename F = DescribeByLookup>
  void Keyed(std::string_view key, const std::map<std::string, T>& v, Count count, Presence = Presence::kRequired,
             F describe = {}) {
    CheckCount(key, v.size(), count);
    Json object = Json::object();
    for (const auto& [name, element] : v) object[name] = Written(element, describe);
    Put(key, std::move(object));
  }
  // A list of numbers that a file may also spell as an object (a range
  // {start, stop, step}) from which the declaration computes the list; the
  // writer writes the list.
  template <typename T, typename F = DescribeByLookup>
  void NumbersOr(std::string_view key, const std::vector<double>& v, std::string_view unit, Limits limits, Count count,
                 const T& /*alternative*/, Presence presence = Presence::kRequired, F /*describe*/ = {}) {
    Numbers(key, v, unit, limits, count, presence);
  }
  // A key of another format that this one reads past (a scenario's fields in
  // a model file): never written.
  void Ignored(std::string_view /*key*/) {}
  // A key this variant of the format does not take (a voltage drive's
  // amplifier with a force drive): never written.
  void Refused(std::string_view /*key*/, std::string_view /*problem*/, std::string_view /*fix*/) {}
  // An object written only when `present` (a flag of the struct); the
  // reader sets the flag to whether the file holds it.
  template <typename T, typename F = DescribeByLookup>
  void OptionalObject(std::string_view key, const bool& present, const T& v, F describe = {}) {
    if (present) Put(key, Written(v, describe));
  }
  void NamesChannel(const std::string&) const {}
  // A rule between fields: the writer's caller broke it (a bug, not input).
  void Check(bool ok, std::string_view rule, const std::string& = {}) const {
    if (!ok) throw std::logic_error("schema: a written value breaks the rule: " + std::string(rule));
  }
  // The fields of an optional struct in this object, all or none.
  template <typename T, typename F = DescribeByLookup>
  void Inline(const std::optional<T>& v, F describe = {}) {
    if (v) describe(*this, *v);
  }
  // A JSON value kept as its text (another format's object, which its own
  // reader reads).
  void Verbatim(std::string_view key, const std::string& json_text, Presence p = Presence::kRequired) {
    if (Omitted(json_text, p)) return;
    Put(key, ParseStrictJson<Json>(json_text, "schema: verbatim field \"" + std::string(key) + "\"", ""));
  }
  void Phasor(std::string_view key, const std::complex<double>& v, std::string_view unit, Presence p) {
    Phasor(key, v, unit, Limits{}, p);
  }
  // A fixed-length array of numbers held in members of this struct.
  template <typename T, std::size_t N>
  void Row(std::string_view key, const T& v, const Column<T> (&columns)[N], Presence = Presence::kRequired) {
    Put(key, RowJson(v, columns));
  }
  // A list of such arrays, one per element.
  template <typename T, std::size_t N>
  void Rows(std::string_view key, const std::vector<T>& v, const Column<T> (&columns)[N], Count count,
            Presence = Presence::kRequired) {
    CheckCount(key, v.size(), count);
    Json list = Json::array();
    for (const T& element : v) list.push_back(RowJson(element, columns));
    Put(key, std::move(list));
  }

 private:
  template <typename T, typename F>
  static Json Written(const T& v, F& describe) {
    Json child;
    Writer w(child);
    describe(w, v);
    return child;
  }
  // A list of the wrong length is the writer's caller's bug, not input.
  static void CheckCount(std::string_view key, std::size_t size, const Count& count) {
    if (size < count.min || size > count.max)
      throw std::logic_error("schema: field \"" + std::string(key) + "\" holds " + std::to_string(size) +
                             " entries, not " + count.Text());
  }
  static Json NumberJson(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }
  template <typename T, std::size_t N>
  static Json RowJson(const T& v, const Column<T> (&columns)[N]) {
    Json row = Json::array();
    for (const Column<T>& c : columns) row.push_back(NumberJson(v.*(c.member)));
    return row;
  }
  template <typename T>
  static bool Omitted(const T& v, Presence p) {
    return p == Presence::kOmittedWhenEmpty && IsEmpty(v);
  }
  void Put(std::string_view key, Json value) { out_[std::string(key)] = std::move(value); }
  Json& out_;
};

// ---- reading ------------------------------------------------------------

class Reader {
 public:
  static constexpr bool kReading = true;

  // declared_keys lists the keys of this object's declaration; it runs
  // only when a required key is missing, to tell a misspelling from an
  // absence.
  Reader(JsonField field, std::function<std::vector<std::string>()> declared_keys)
      : field_(std::move(field)), declared_keys_(std::move(declared_keys)), channel_(field_.channel()) {
    field_.Object();
  }

  // This object describes the channel `name` (read just before): every
  // later complaint about it, or below it, names the channel too.
  void NamesChannel(const std::string& name) { channel_ = name; }

  void Constant(std::string_view key, std::string_view value, Presence presence = Presence::kRequired) {
    if (!Present(key, presence)) return;
    const std::string text = Field(key).String();
    if (text != value) Field(key).Fail("is \"" + text + "\", not \"" + std::string(value) + "\"");
  }
  void Number(std::string_view key, double& v, std::string_view /*unit*/, Limits limits = {},
              Presence presence = Presence::kRequired) {
    if (Present(key, presence)) v = ReadNumber(Field(key), limits);
  }
  void Number(std::string_view key, std::optional<double>& v, std::string_view /*unit*/, Limits limits = {}) {
    if (Present(key, Presence::kOptional)) v = ReadNumber(Field(key), limits);
  }
  void Derived(std::string_view key, double /*v*/, std::string_view /*unit*/) {
    if (Present(key, Presence::kOptional)) Field(key).Number();
  }
  void Derived(std::string_view key, std::string_view /*text*/) {
    if (Present(key, Presence::kOptional)) ReadText(Field(key), TextRule::kAny);
  }
  template <std::integral I>
  void Integer(std::string_view key, I& v, std::int64_t min, std::int64_t max,
               Presence presence = Presence::kRequired) {
    if (!Present(key, presence)) return;
    const JsonField f = Field(key);
    const nlohmann::ordered_json& j = f.json();
    if (!j.is_number_integer()) f.Fail("must be an integer");
    bool in_range;
    if (j.is_number_unsigned()) {
      const std::uint64_t u = j.get<std::uint64_t>();
      in_range = max >= 0 && u <= static_cast<std::uint64_t>(max) && (min <= 0 || u >= static_cast<std::uint64_t>(min));
    } else {
      const std::int64_t i = j.get<std::int64_t>();
      in_range = i >= min && i <= max;
    }
    if (!in_range) f.Fail(fmt::format("= {} lies outside {} .. {}", j.dump(), min, max));
    v = j.get<I>();
  }
  void Boolean(std::string_view key, bool& v, Presence presence = Presence::kRequired) {
    if (Present(key, presence)) v = Field(key).Boolean();
  }
  void Text(std::string_view key, std::string& v, TextRule rule = TextRule::kAny,
            Presence presence = Presence::kRequired) {
    if (Present(key, presence)) v = ReadText(Field(key), rule);
  }
  template <typename E, std::size_t N>
  void Choice(std::string_view key, E& v, const Name<E> (&names)[N], Presence presence = Presence::kRequired) {
    if (!Present(key, presence)) return;
    const JsonField f = Field(key);
    const std::string text = f.String();
    std::string list;
    for (const Name<E>& n : names) {
      if (n.name == text) {
        v = n.value;
        return;
      }
      list += (list.empty() ? "\"" : ", \"") + std::string(n.name) + "\"";
    }
    f.Fail("is \"" + text + "\", not one of " + list);
  }
  void Numbers(std::string_view key, std::vector<double>& v, std::string_view /*unit*/, Limits limits, Count count,
               Presence presence = Presence::kRequired) {
    if (!Present(key, presence)) return;
    const JsonField f = Sized(Field(key), count);
    v.clear();
    for (std::size_t i = 0; i < f.Size(); ++i) v.push_back(ReadNumber(f.At(i), limits));
  }
  void Phasors(std::string_view key, std::vector<std::complex<double>>& v, std::string_view /*unit*/, Count count,
               Presence presence = Presence::kRequired) {
    if (!Present(key, presence)) return;
    const JsonField f = Sized(Field(key), count);
    v.clear();
    for (std::size_t i = 0; i < f.Size(); ++i) v.push_back(f.At(i).Phasor());
  }
  void Phasor(std::string_view key, std::complex<double>& v, std::string_view /*unit*/, Limits parts = {},
              Presence presence = Presence::kRequired) {
    if (Present(key, presence)) v = ReadPhasor(Field(key), parts);
  }
  void Phasors(std::string_view key, Eigen::VectorXcd& v, std::string_view /*unit*/, Limits parts, Count count,
               Presence presence = Presence::kRequired) {
    if (!Present(key, presence)) return;
    const JsonField f = Sized(Field(key), count);
    v.resize(static_cast<Eigen::Index>(f.Size()));
    for (std::size_t i = 0; i < f.Size(); ++i) v[static_cast<Eigen::Index>(i)] = ReadPhasor(f.At(i), parts);
  }
  void Matrix(std::string_view key, Eigen::MatrixXd& m, std::string_view /*unit*/, Limits limits, Count rows,
              Count columns, Presence presence = Presence::kRequired) {
    if (!Present(key, presence)) return;
    const JsonField f = Sized(Field(key), rows);
    // Every row as long as the first, allocated once the first is checked.
    for (std::size_t r = 0; r < f.Size(); ++r) {
      const JsonField row = Sized(f.At(r), columns);
      if (r == 0) m.resize(static_cast<Eigen::Index>(f.Size()), static_cast<Eigen::Index>(row.Size()));
      if (row.Size() != static_cast<std::size_t>(m.cols()))
        row.Fail(fmt::format("holds {} entries, not {} as the first row", row.Size(), m.cols()));
      for (std::size_t c = 0; c < row.Size(); ++c)
        m(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = ReadNumber(row.At(c), limits);
    }
    if (f.Size() == 0) m.resize(0, 0);
  }
  void Texts(std::string_view key, std::vector<std::string>& v, Count count, TextRule rule = TextRule::kAny,
             Presence presence = Presence::kRequired) {
    if (!Present(key, presence)) return;
    const JsonField f = Sized(Field(key), count);
    v.clear();
    for (std::size_t i = 0; i < f.Size(); ++i) v.push_back(ReadText(f.At(i), rule));
  }
  template <typename T, typename F = DescribeByLookup>
  void Object(std::string_view key, T& v, Presence presence = Presence::kRequired, F describe = {}) {
    if (Present(key, presence)) ReadInto(Field(key), v, describe);
  }
  template <typename T, typename F = DescribeByLookup>
  void ObjectOrNull(std::string_view key, T& v, bool T::*present, Presence presence = Presence::kRequired,
                    F describe = {}) {
    if (!Present(key, presence)) return;
    const JsonField f = Field(key);
    v = T{};
    if (f.json().is_null()) {
      v.*present = false;
      return;
    }
    ReadInto(f, v, describe);
    v.*present = true;
  }
  template <typename T, typename F = DescribeByLookup>
  void OptionalObject(std::string_view key, bool& present, T& v, F describe = {}) {
    present = Present(key, Presence::kOptional);
    if (present) ReadInto(Field(key), v, describe);
  }
  template <typename T, typename F = DescribeByLookup>
  void List(std::string_view key, std::vector<T>& v, Count count, Presence presence = Presence::kRequired,
            F describe = {}) {
    if (!Present(key, presence)) return;
    const JsonField f = Sized(Field(key), count);
    v.assign(f.Size(), T{});
    for (std::size_t i = 0; i < f.Size(); ++i) ReadInto(f.At(i), v[i], describe);
  }
  template <typename T, typename F = DescribeByLookup>
  void Keyed(std::string_view key, std::vector<T>& v, std::string T::*name, Count count,
             Presence presence = Presence::kRequired, F describe = {}) {
    if (!Present(key, presence)) return;
    const JsonField f = Field(key).Object();
    const std::size_t size = f.json().size();
    if (size < count.min || size > count.max)
      f.Fail(fmt::format("holds {} entries, not {}", size, count.Text()));
    v.clear();
    for (auto& [member, value] : f.Members()) {
      if (member.empty()) value.Fail("is an empty name", "name it");
      CheckText(value, member, TextRule::kNotEmpty);
      T element{};
      element.*name = member;
      ReadInto(value, element, describe);
      v.push_back(std::move(element));
    }
  }
  template <typename T, typename F = DescribeByLookup>
  void Object(std::string_view key, std::optional<T>& v, Presence presence = Presence::kOptional, F describe = {}) {
    if (!Present(key, presence)) return;
    v.emplace();
    ReadInto(Field(key), *v, describe);
  }
  template <typename T, typename F = DescribeByLookup>
  void Keyed(std::string_view key, std::map<std::string, T>& v, Count count, Presence presence = Presence::kRequired,
             F describe = {}) {
    if (!Present(key, presence)) return;
    const JsonField f = Field(key).Object();
    const std::size_t size = f.json().size();
    if (size < count.min || size > count.max) f.Fail(fmt::format("holds {} entries, not {}", size, count.Text()));
    v.clear();
    for (auto& [member, value] : f.Members()) {
      if (member.empty()) value.Fail("is an empty name", "name it");
      CheckText(value, member, TextRule::kNotEmpty);
      ReadInto(value, v[member], describe);
    }
  }
  // Reads the object spelling into `alternative` (and leaves `v` for the
  // declaration to compute), or the list into `v`.
  template <typename T, typename F = DescribeByLookup>
  void NumbersOr(std::string_view key, std::vector<double>& v, std::string_view unit, Limits limits, Count count,
                 T& alternative, Presence presence = Presence::kRequired, F describe = {}) {
    if (!Present(key, presence)) return;
    if (Field(key).json().is_object()) return ReadInto(Field(key), alternative, describe);
    keys_.pop_back();  // Numbers declares the key again
    Numbers(key, v, unit, limits, count, presence);
  }
  void Ignored(std::string_view key) { keys_.emplace_back(key); }
  void Refused(std::string_view key, std::string_view problem, std::string_view fix) const {
    if (field_.Has(std::string(key))) Field(key).Fail(std::string(problem), fix);
  }
  // A rule between fields, checked once they are read: `where` names the
  // part of this object that breaks it ("" for the object itself).
  void Check(bool ok, std::string_view rule, const std::string& where = {}) const {
    if (ok) return;
    // A misspelled key may be why the rule is broken: it is the news.
    RefuseKeysOtherThan(declared_keys_());
    const std::string problem = "breaks the rule: " + std::string(rule);
    if (where.empty()) Here().Fail(problem);
    Here().FailBelow(where, problem);
  }

  // Present when any of T's keys is: then all of them are required.
  template <typename T, typename F = DescribeByLookup>
  void Inline(std::optional<T>& v, F describe = {}) {
    const std::vector<std::string> keys = DeclaredKeys<T>(describe);
    bool present = false;
    for (const std::string& k : keys) present = present || field_.Has(k);
    if (!present) {
      keys_.insert(keys_.end(), keys.begin(), keys.end());
      return;
    }
    v.emplace();
    describe(*this, *v);
  }
  void Verbatim(std::string_view key, std::string& json_text, Presence presence = Presence::kRequired) {
    if (Present(key, presence)) json_text = Field(key).json().dump();
  }
  void Phasor(std::string_view key, std::complex<double>& v, std::string_view unit, Presence p) {
    Phasor(key, v, unit, Limits{}, p);
  }
  template <typename T, std::size_t N>
  void Row(std::string_view key, T& v, const Column<T> (&columns)[N], Presence presence = Presence::kRequired) {
    if (Present(key, presence)) ReadRow(Field(key), v, columns);
  }
  template <typename T, std::size_t N>
  void Rows(std::string_view key, std::vector<T>& v, const Column<T> (&columns)[N], Count count,
            Presence presence = Presence::kRequired) {
    if (!Present(key, presence)) return;
    const JsonField f = Sized(Field(key), count);
    v.assign(f.Size(), T{});
    for (std::size_t i = 0; i < f.Size(); ++i) ReadRow(f.At(i), v[i], columns);
  }

  // Refuses a key the declaration did not name (a misspelling, or another
  // file's field).
  void Finish() const { RefuseKeysOtherThan(keys_); }

  template <typename T, typename F = DescribeByLookup>
  static void ReadInto(const JsonField& field, T& v, F describe = {}) {
    Reader r(field, [&describe] { return DeclaredKeys<T>(describe); });
    describe(r, v);
    r.Finish();
  }

 private:
  bool Present(std::string_view key, Presence presence) {
    keys_.emplace_back(key);
    if (field_.Has(std::string(key))) return true;
    if (presence != Presence::kRequired) return false;
    // "completed" where "complete" is declared: the misspelling is the news.
    RefuseKeysOtherThan(declared_keys_());
    Field(key);  // "is missing"
    return false;
  }
  void RefuseKeysOtherThan(const std::vector<std::string>& known) const {
    for (const auto& [key, value] : Here().Members()) {
      if (std::find(known.begin(), known.end(), key) != known.end()) continue;
      std::string list;
      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
      value.Fail("is not a field here", "correct its name or remove it (the fields here: " + list + ")");
    }
  }
  template <typename T, typename F>
  static std::vector<std::string> DeclaredKeys(F& describe);
  JsonField Here() const { return field_.Named(channel_); }
  JsonField Field(std::string_view key) const { return Here().At(std::string(key)); }
  static double ReadNumber(const JsonField& f, const Limits& limits) {
    const double v = limits.nullable ? f.Number() : f.NumberNotNull();
    if (!limits.Holds(v)) f.Fail(fmt::format("= {} lies outside {}", v, limits.Text()));
    return v;
  }
  static std::complex<double> ReadPhasor(const JsonField& f, const Limits& parts) {
    if (f.Size() != 2) f.Fail("must be [re, im], not " + std::to_string(f.Size()) + " numbers");
    return {ReadNumber(f.At(0), parts), ReadNumber(f.At(1), parts)};
  }
  static std::string ReadText(const JsonField& f, TextRule rule) {
    std::string text = f.String();
    CheckText(f, text, rule);
    return text;
  }
  static void CheckText(const JsonField& f, const std::string& text, TextRule rule) {
    if (rule == TextRule::kNotEmpty && text.empty()) f.Fail("is empty", "give it a name");
    for (const char c : text)
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F)
        f.Fail(fmt::format("holds the control character 0x{:02X}", static_cast<unsigned char>(c)),
               "remove it: names and labels are one line of printable text");
  }
  template <typename T, std::size_t N>
  static void ReadRow(const JsonField& f, T& v, const Column<T> (&columns)[N]) {
    if (f.Size() != N) f.Fail(fmt::format("holds {} numbers, not {} ({})", f.Size(), N, ColumnNames(columns)));
    for (std::size_t c = 0; c < N; ++c) v.*(columns[c].member) = ReadNumber(f.At(c), columns[c].limits);
  }
  static const JsonField& Sized(const JsonField& f, const Count& count) {
    if (f.Size() < count.min || f.Size() > count.max)
      f.Fail(fmt::format("holds {} entries, not {}", f.Size(), count.Text()));
    return f;
  }

  JsonField field_;
  std::function<std::vector<std::string>()> declared_keys_;
  std::vector<std::string> keys_;
  std::string channel_;  // NamesChannel's, or the enclosing object's
};

// ---- documenting --------------------------------------------------------

struct FieldDoc {
  std::string path;  // "curves[].points[].frequency_Hz", "sensors.<name>.position_m"
  std::string type;  // "number", "integer", "string", "[number]", "[[re, im]]", "object", ...
  std::string unit;  // "Hz", "" where none
  std::string range;  // "> 0", "0 .. 50", "\"measured\" | \"feasible\"", ""
  bool optional = false;
  // What the reader holds the value to, for the generic checks of a format
  // (tests/support/schema_checks.h): a number's (or a number list's)
  // limits, an integer's range, a list's count, a string's choices.
  Limits limits{};
  std::int64_t integer_min = 0;
  std::int64_t integer_max = 0;
  std::size_t count_min = 0;
  std::vector<std::string> choices;
};

class Documenter {
 public:
  static constexpr bool kReading = false;

  Documenter(std::vector<FieldDoc>& out, std::string prefix) : out_(out), prefix_(std::move(prefix)) {}

  void Constant(std::string_view key, std::string_view value, Presence p = Presence::kRequired) {
    Add(key, "string", "", "\"" + std::string(value) + "\"", p).choices = {std::string(value)};
  }
  void Number(std::string_view key, const double&, std::string_view unit, Limits limits = {},
              Presence p = Presence::kRequired) {
    Add(key, "number", unit, limits.Text(), p).limits = limits;
  }
  void Number(std::string_view key, const std::optional<double>&, std::string_view unit, Limits limits = {}) {
    Add(key, "number", unit, limits.Text(), Presence::kOptional).limits = limits;
  }
  void Derived(std::string_view key, double, std::string_view unit) {
    Add(key, "number (derived)", unit, "written, not read", Presence::kOptional);
  }
  void Derived(std::string_view key, std::string_view) {
    Add(key, "string (derived)", "", "written, not read", Presence::kOptional);
  }
  template <std::integral I>
  void Integer(std::string_view key, const I&, std::int64_t min, std::int64_t max, Presence p = Presence::kRequired) {
    FieldDoc& f = Add(key, "integer", "", fmt::format("{} .. {}", min, max), p);
    f.integer_min = min;
    f.integer_max = max;
  }
  void Boolean(std::string_view key, const bool&, Presence p = Presence::kRequired) { Add(key, "boolean", "", "", p); }
  void Text(std::string_view key, const std::string&, TextRule rule = TextRule::kAny, Presence p = Presence::kRequired) {
    Add(key, "string", "", rule == TextRule::kNotEmpty ? "not empty" : "", p);
  }
  template <typename E, std::size_t N>
  void Choice(std::string_view key, const E&, const Name<E> (&names)[N], Presence p = Presence::kRequired) {
    std::string range;
    std::vector<std::string> choices;
    for (const Name<E>& n : names) {
      range += (range.empty() ? "\"" : " | \"") + std::string(n.name) + "\"";
      choices.emplace_back(n.name);
    }
    Add(key, "string", "", range, p).choices = std::move(choices);
  }
  void Numbers(std::string_view key, const std::vector<double>&, std::string_view unit, Limits limits, Count count,
               Presence p = Presence::kRequired) {
    FieldDoc& f = Add(key, "[number]", unit, fmt::format("{}; {} entries", limits.Text(), count.Text()), p);
    f.limits = limits;
    f.count_min = count.min;
  }
  void Phasors(std::string_view key, const std::vector<std::complex<double>>&, std::string_view unit, Count count,
               Presence p = Presence::kRequired) {
    Add(key, "[[re, im]]", unit, count.Text() + " entries", p).count_min = count.min;
  }
  void Phasor(std::string_view key, const std::complex<double>&, std::string_view unit, Limits parts = {},
              Presence p = Presence::kRequired) {
    Add(key, "[re, im]", unit, parts.Text(), p).limits = parts;
  }
  void Phasors(std::string_view key, const Eigen::VectorXcd&, std::string_view unit, Limits parts, Count count,
               Presence p = Presence::kRequired) {
    FieldDoc& f = Add(key, "[[re, im]]", unit, fmt::format("{}; {} entries", parts.Text(), count.Text()), p);
    f.limits = parts;
    f.count_min = count.min;
  }
  void Matrix(std::string_view key, const Eigen::MatrixXd&, std::string_view unit, Limits limits, Count rows,
              Count columns, Presence p = Presence::kRequired) {
    FieldDoc& f = Add(key, "[[number]]", unit,
                      fmt::format("{}; {} rows of {} entries", limits.Text(), rows.Text(), columns.Text()), p);
    f.limits = limits;
    f.count_min = rows.min;
  }
  void Texts(std::string_view key, const std::vector<std::string>&, Count count, TextRule = TextRule::kAny,
             Presence p = Presence::kRequired) {
    Add(key, "[string]", "", count.Text() + " entries", p).count_min = count.min;
  }
  template <typename T, typename F = DescribeByLookup>
  void Object(std::string_view key, const T&, Presence p = Presence::kRequired, F describe = {}) {
    Add(key, "object", "", "", p);
    Nested<T>(Path(key) + ".", describe);
  }
  template <typename T, typename F = DescribeByLookup>
  void ObjectOrNull(std::string_view key, const T&, bool T::*, Presence p = Presence::kRequired, F describe = {}) {
    Add(key, "object", "", "or null", p);
    Nested<T>(Path(key) + ".", describe);
  }
  template <typename T, typename F = DescribeByLookup>
  void List(std::string_view key, const std::vector<T>&, Count count, Presence p = Presence::kRequired,
            F describe = {}) {
    Add(key, "[object]", "", count.Text() + " entries", p).count_min = count.min;
    Nested<T>(Path(key) + "[].", describe);
  }
  template <typename T, typename F = DescribeByLookup>
  void Keyed(std::string_view key, const std::vector<T>&, std::string T::*, Count count,
             Presence p = Presence::kRequired, F describe = {}) {
    Add(key, "object", "", "keyed by name, " + count.Text() + " entries", p);
    Nested<T>(Path(key) + ".<name>.", describe);
  }
  template <typename T, typename F = DescribeByLookup>
  void Object(std::string_view key, const std::optional<T>&, Presence p = Presence::kOptional, F describe = {}) {
    Add(key, "object", "", "", p);
    Nested<T>(Path(key) + ".", describe);
  }
  template <typename T, typename F = DescribeByLookup>
  void Inline(const std::optional<T>&, F describe = {}) {
    const std::size_t first = out_.size();
    const T element{};
    describe(*this, element);
    for (std::size_t i = first; i < out_.size(); ++i)
      if (out_[i].type != "rule" && out_[i].path.find_first_of(".[", prefix_.size()) == std::string::npos)
        out_[i].optional = true;
  }
  void Verbatim(std::string_view key, const std::string&, Presence p = Presence::kRequired) {
    Add(key, "any", "", "kept as written", p);
  }
  void Phasor(std::string_view key, const std::complex<double>& v, std::string_view unit, Presence p) {
    Phasor(key, v, unit, Limits{}, p);
  }
  template <typename T, std::size_t N>
  void Row(std::string_view key, const T&, const Column<T> (&columns)[N], Presence p = Presence::kRequired) {
    Add(key, "[" + ColumnNames(columns) + "]", ColumnUnits(columns), ColumnRanges(columns), p).count_min = N;
  }
  template <typename T, std::size_t N>
  void Rows(std::string_view key, const std::vector<T>&, const Column<T> (&columns)[N], Count count,
            Presence p = Presence::kRequired) {
    Add(key, "[[" + ColumnNames(columns) + "]]", ColumnUnits(columns),
        ColumnRanges(columns) + "; " + count.Text() + " entries", p);
  }
  template <typename T, typename F = DescribeByLookup>
  void Keyed(std::string_view key, const std::map<std::string, T>&, Count count, Presence p = Presence::kRequired,
             F describe = {}) {
    Add(key, "object", "", "keyed by name, " + count.Text() + " entries", p).count_min = count.min;
    Nested<T>(Path(key) + ".<name>.", describe);
  }
  template <typename T, typename F = DescribeByLookup>
  void NumbersOr(std::string_view key, const std::vector<double>&, std::string_view unit, Limits limits, Count count,
                 const T&, Presence p = Presence::kRequired, F describe = {}) {
    FieldDoc& f = Add(key, "[number] or object", unit, fmt::format("{}; {} entries", limits.Text(), count.Text()), p);
    f.limits = limits;
    f.count_min = count.min;
    Nested<T>(Path(key) + ".", describe);
  }
  void Ignored(std::string_view key) { Add(key, "any", "", "read past, not used", Presence::kOptional); }
  void Refused(std::string_view, std::string_view, std::string_view) {}
  template <typename T, typename F = DescribeByLookup>
  void OptionalObject(std::string_view key, const bool&, const T&, F describe = {}) {
    Add(key, "object", "", "", Presence::kOptional);
    Nested<T>(Path(key) + ".", describe);
  }
  void NamesChannel(const std::string&) const {}
  void Check(bool, std::string_view rule, const std::string& = {}) {
    out_.push_back({.path = prefix_.empty() ? "(file)" : prefix_.substr(0, prefix_.size() - 1), .type = "rule",
                    .range = std::string(rule)});
  }

 private:
  std::string Path(std::string_view key) const { return prefix_ + std::string(key); }
  FieldDoc& Add(std::string_view key, std::string type, std::string_view unit, std::string range, Presence p) {
    out_.push_back({.path = Path(key),
                    .type = std::move(type),
                    .unit = std::string(unit),
                    .range = std::move(range),
                    .optional = p != Presence::kRequired});
    return out_.back();
  }
  template <typename T, typename F>
  void Nested(std::string prefix, F& describe) {
    const T element{};
    Documenter d(out_, std::move(prefix));
    describe(d, element);
  }
  std::vector<FieldDoc>& out_;
  std::string prefix_;
};

template <typename T, typename F>
std::vector<std::string> Reader::DeclaredKeys(F& describe) {
  std::vector<FieldDoc> fields;
  const T element{};
  Documenter d(fields, "");
  describe(d, element);
  std::vector<std::string> keys;
  for (const FieldDoc& f : fields)
    if (f.type != "rule" && f.path.find_first_of(".[") == std::string::npos) keys.push_back(f.path);
  return keys;
}

// ---- variants -----------------------------------------------------------

// A field the writer leaves out while it holds its default (`written`
// false: no Rayleigh damping, no artefact); the reader takes it when present
// and the documentation lists it.
template <typename Io>
constexpr bool Writes(const Io&, bool written) {
  if constexpr (std::is_same_v<Io, Writer>) return written;
  return true;
}

// True while the declaration is walked to document the format, so that a
// key or a value that depends on the data can be written as a placeholder.
template <typename Io>
constexpr bool kDocumenting = std::is_same_v<std::remove_const_t<Io>, Documenter>;

// A field of one variant of the format (a voltage drive's amplifier): the
// writer and the reader take it in that variant (`in_variant`), the
// documentation lists it always, so that the reader also knows it as one of
// the object's keys.
template <typename Io>
constexpr bool InVariant(const Io&, bool in_variant) {
  if constexpr (std::is_same_v<Io, Documenter>) return true;
  return in_variant;
}

// ---- the three uses -----------------------------------------------------

// The file's text: one field per line, the struct's order.
template <typename T>
std::string ToJson(const T& value) {
  nlohmann::ordered_json json;
  Writer w(json);
  Describe(w, value);
  return json.dump(1) + "\n";
}

// Reads a text that `source` names, throwing InputError "<source>: field
// "<path>" <problem>. Fix: <fix>".
template <typename T>
T FromJson(const std::string& text, const std::string& source, const Format& format) {
  const nlohmann::ordered_json json = ParseJsonObject(text, source, format.what, format.fix);
  T value{};
  Reader::ReadInto(JsonField(json, "", source, format.tag, format.fix), value);
  return value;
}

template <typename T>
std::vector<FieldDoc> Fields() {
  std::vector<FieldDoc> out;
  const T value{};
  Documenter d(out, "");
  Describe(d, value);
  return out;
}

// The fields as a Markdown table (the format's documentation holds it).
std::string FieldTable(const std::vector<FieldDoc>& fields);

}  // namespace beamid::schema
